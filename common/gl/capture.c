#include "capture.h"

#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "context.h"
#include "depth.h"

/* The float buffers of the geometry pass: normal + distance, position + id. */
typedef struct capture_buffers {
    unsigned framebuffer, color[2], depth;
} capture_buffers;

/* reversed_depth: the float depth, as the target's (target.h). */
static bool capture_buffers_create(capture_buffers *b, int width, int height, bool reversed_depth) {
    glGenFramebuffers(1, &b->framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, b->framebuffer);
    glGenRenderbuffers(2, b->color);
    for (int i = 0; i < 2; i++) {
        glBindRenderbuffer(GL_RENDERBUFFER, b->color[i]);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA32F, width, height);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_RENDERBUFFER, b->color[i]);
    }
    glGenRenderbuffers(1, &b->depth);
    glBindRenderbuffer(GL_RENDERBUFFER, b->depth);
    glRenderbufferStorage(GL_RENDERBUFFER, reversed_depth ? GL_DEPTH_COMPONENT32F : GL_DEPTH_COMPONENT24, width,
                          height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, b->depth);
    static const GLenum draw[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(2, draw);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        fprintf(stderr, "capture: %dx%d float framebuffer incomplete\n", width, height);
        return false;
    }
    return context_gl_ok("capture_buffers_create");
}

static void capture_buffers_destroy(capture_buffers *b) {
    glDeleteFramebuffers(1, &b->framebuffer);
    glDeleteRenderbuffers(2, b->color);
    glDeleteRenderbuffers(1, &b->depth);
}

/* Reads one RGBA float attachment, bottom row first as GL has it. */
static void capture_read_floats(GLenum attachment, int width, int height, float *rgba) {
    glReadBuffer(attachment);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, rgba);
}

/* Object i's triangles unshared, each vertex with its own position, the
 * triangle's three corners and its texture coordinates
 * (shaders/geometry_faces.vert), drawn with p as render_draw_object
 * would draw them: the geometry pass where there are no geometry
 * shaders. */
enum { capture_corner_floats = 3, capture_uv_floats = 2, capture_face_floats = 4 * 3 + 2 };
static bool capture_draw_faces(const render_scene *gpu, const render_program *p, int i) {
    const scene_object *o = &gpu->scene->objects[i];
    const mesh *m = &o->mesh;
    float *vertices = malloc((size_t)m->index_count * capture_face_floats * sizeof(float));
    if (!vertices) {
        fprintf(stderr, "capture: out of memory for %u corners of \"%s\"\n", m->index_count, o->name);
        return false;
    }
    for (uint32_t c = 0; c < m->index_count; c++) {
        float *v = vertices + (size_t)c * capture_face_floats;
        uint32_t first = c - c % 3;
        const mesh_vertex *own = &m->vertices[m->indices[c]];
        memcpy(v, own->position, sizeof own->position);
        for (int k = 0; k < 3; k++)
            memcpy(v + capture_corner_floats * (k + 1), m->vertices[m->indices[first + k]].position,
                   sizeof own->position);
        memcpy(v + 4 * capture_corner_floats, own->uv, sizeof own->uv);
    }
    unsigned vao, buffer;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &buffer);
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)((size_t)m->index_count * capture_face_floats * sizeof(float)),
                 vertices, GL_STREAM_DRAW);
    free(vertices);
    /* Attributes 0 to 3 the position and the corners, 4 the coordinates. */
    for (unsigned a = 0; a <= 4; a++) {
        glEnableVertexAttribArray(a);
        glVertexAttribPointer(a, a < 4 ? capture_corner_floats : capture_uv_floats, GL_FLOAT, GL_FALSE,
                              capture_face_floats * sizeof(float),
                              (const void *)(a * capture_corner_floats * sizeof(float)));
    }
    bool culled = render_object_begin(gpu, p, i);
    glDrawArrays(GL_TRIANGLES, 0, (GLsizei)m->index_count);
    render_object_end(gpu, culled);
    glBindVertexArray(0);
    glDeleteBuffers(1, &buffer);
    glDeleteVertexArrays(1, &vao);
    return true;
}

static bool capture_geometry(const render_scene *gpu, const camera_view *view, dump_frame *out) {
    /* Each face's normal from a geometry shader: desktop GLSL on desktop
     * GL, whatever the dialect (shader.h). Where GL has none (WebGL 2),
     * every vertex of the unshared triangle makes it. */
    bool geometry_stage = context_current_features()->desktop_gl;
    static const char *const staged[] = {"geometry.vert", "geometry.geom", "geometry.frag"};
    static const char *const unshared[] = {"geometry_faces.vert", "geometry.frag"};
    render_programs programs = {0};
    capture_buffers b = {0};
    size_t n = (size_t)out->width * (size_t)out->height;
    float *normal_distance = malloc(n * 4 * sizeof(float)), *position_id = malloc(n * 4 * sizeof(float));
    /* Cut-out objects through their variant (render.h), with a geometry
     * stage or without. */
    bool ok = normal_distance && position_id &&
              (geometry_stage ? render_programs_load(&programs, gpu->scene, staged, 3, NULL)
                              : render_programs_load(&programs, gpu->scene, unshared, 2, NULL));
    if (ok && (ok = capture_buffers_create(&b, out->width, out->height, view->reversed_depth))) {
        static const float none[4] = {0, 0, 0, -1};
        glViewport(0, 0, out->width, out->height);
        glClearBufferfv(GL_COLOR, 0, none);
        glClearBufferfv(GL_COLOR, 1, none);
        glClearDepth(depth_far(view));
        glClear(GL_DEPTH_BUFFER_BIT);
        render_reset_state();
        depth_use_camera(view); /* the nearest surface, as the frame's depth test finds it */
        bool every_exact = !context_current_features()->close_interpolation;
        for (int pass = 0; pass < render_programs_passes(&programs); pass++) {
            const render_program *program = render_programs_pass(&programs, pass);
            render_program_use(program, view);
            glUniform3fv(shader_uniform(program->id, "u_eye"), 1, view->eye);
            render_eye_ray_uniforms(program->id, view, out->width, out->height);
            int object = shader_uniform(program->id, "u_object"), exact = shader_uniform(program->id, "u_exact");
            /* Every object, never the frame's culling: the dump's geometry
             * is the scene's, the ground truth that culling is checked
             * against. */
            for (int i = 0; ok && i < gpu->scene->object_count; i++) {
                if (!render_programs_draws(&programs, pass, &gpu->scene->objects[i]))
                    continue;
                glUniform1f(object, (float)i);
                glUniform1i(exact, every_exact || render_object_huge(gpu, i, view->eye));
                if (geometry_stage)
                    render_draw_object(gpu, program, i);
                else
                    ok = capture_draw_faces(gpu, program, i);
            }
        }
        capture_read_floats(GL_COLOR_ATTACHMENT0, out->width, out->height, normal_distance);
        capture_read_floats(GL_COLOR_ATTACHMENT1, out->width, out->height, position_id);
        for (int y = 0; y < out->height; y++) {
            for (int x = 0; x < out->width; x++) {
                size_t gl = ((size_t)(out->height - 1 - y) * out->width + x) * 4, i = (size_t)y * out->width + x;
                for (int c = 0; c < 3; c++) {
                    out->normal[i * 3 + c] = normal_distance[gl + c];
                    out->position[i * 3 + c] = position_id[gl + c];
                }
                out->depth[i] = normal_distance[gl + 3];
                out->ids[i] = position_id[gl + 3];
            }
        }
        depth_use_standard(view);
        ok = context_gl_ok("capture_geometry") && ok;
    }
    if (!normal_distance || !position_id)
        fprintf(stderr, "capture: out of memory for a %dx%d frame\n", out->width, out->height);
    capture_buffers_destroy(&b);
    render_programs_destroy(&programs);
    free(normal_distance);
    free(position_id);
    return ok;
}

bool capture_dump(const render_scene *gpu, const camera_view *view, const target *t, int light_index, bool coloured,
                  capture_render_frame render_frame, dump_frame *out) {
    if (!dump_frame_create(out, t->width, t->height, gpu->scene, light_index))
        return false;
    bool ok = target_read_rgba(t, out->color) && capture_geometry(gpu, view, out) && render_frame(light_index);
    unsigned char *rgba = ok ? malloc((size_t)t->width * t->height * 4) : NULL;
    ok = rgba && target_read_rgba(t, rgba);
    for (long i = 0; ok && i < (long)t->width * t->height; i++)
        out->visibility[i] = out->ids[i] < 0 ? -1.0f : rgba[i * 4] / 255.0f;
    dump_frame_grey_rgb(out);
    for (long i = 0; ok && coloured && out->visibility_rgb && i < (long)t->width * t->height; i++) {
        float *rgb = out->visibility_rgb + 3 * i;
        for (int k = 0; k < 3 && out->ids[i] >= 0; k++)
            rgb[k] = rgba[i * 4 + k] / 255.0f;
        if (rgb[0] != rgb[1] || rgb[1] != rgb[2])
            out->visibility[i] = (rgb[0] + rgb[1] + rgb[2]) / 3.0f;
    }
    free(rgba);
    /* Leave the target as it was: the picture, not the visibility. */
    ok = ok && render_frame(-1);
    if (!ok)
        dump_frame_free(out);
    return ok;
}
