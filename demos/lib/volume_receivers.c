#include "volume_receivers.h"

#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "context.h"

/* Floats per triangle, a texel of the planes' texture (GL_RGBA32F): the
 * unit normal, then the eye's distance along it. Triangle t is texel
 * (t % width, t / width), rows as wide as the GL allows. */
#define VOLUME_RECEIVERS_PLANE_FLOATS 4
/* The texture unit the planes are read from, during this pass only. */
#define VOLUME_RECEIVERS_UNIT 0

/* The planes' texture of `triangles` in rows of at most `row` texels:
 * its width and height. */
static void volume_receivers_size(uint32_t triangles, int row, int *width, int *height) {
    *height = (int)((triangles + (uint32_t)row - 1) / (uint32_t)row);
    *width = *height > 1 ? row : (int)triangles;
}

/* The active unit and the planes' unit's 2D texture, as a pass found
 * them: it leaves them so. */
typedef struct volume_receivers_binding {
    GLint active, texture;
} volume_receivers_binding;

/* Binds `texture` on the planes' unit, made the active one. */
static volume_receivers_binding volume_receivers_bind(unsigned texture) {
    volume_receivers_binding was = {0};
    glGetIntegerv(GL_ACTIVE_TEXTURE, &was.active);
    glActiveTexture(GL_TEXTURE0 + VOLUME_RECEIVERS_UNIT);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &was.texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    return was;
}

static void volume_receivers_unbind(volume_receivers_binding was) {
    glBindTexture(GL_TEXTURE_2D, (GLuint)was.texture);
    glActiveTexture((GLenum)was.active);
}

bool volume_receivers_init(volume_receivers *r, const render_scene *gpu) {
    const scene *s = gpu->scene;
    size_t objects = (size_t)s->object_count;
    r->object_count = s->object_count;
    r->textures = calloc(objects, sizeof *r->textures);
    r->huge = calloc(objects, sizeof *r->huge);
    if (!r->textures || !r->huge) {
        fprintf(stderr, "volumes: out of memory\n");
        return false;
    }
    /* Without the fragment's triangle (gl_PrimitiveID) no object is ever
     * huge: all keep the rasterized depth. */
    if (!context_current_features()->primitive_id)
        return true;
    static const char *const files[] = {"lit.vert", "volume_receiver_depth.frag"};
    if (!render_program_load(&r->program, files, (int)(sizeof files / sizeof *files), NULL))
        return false;
    r->projection = shader_uniform(r->program.id, "u_projection");
    r->zero_to_one = shader_uniform(r->program.id, "u_zero_to_one");
    r->planes = shader_uniform(r->program.id, "u_planes");
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    r->width = max_size;
    size_t most = 0; /* texels */
    for (int i = 0; i < s->object_count; i++) {
        const scene_object *o = &s->objects[i];
        uint32_t triangles = o->mesh.index_count / 3;
        /* Never huge: even at the near plane no edge is long enough. */
        int width, rows;
        volume_receivers_size(triangles, r->width, &width, &rows);
        if (gpu->meshes[i].longest_edge <= RENDER_HUGE_RATIO * s->camera.near_plane || rows > max_size)
            continue;
        glGenTextures(1, &r->textures[i]);
        volume_receivers_binding was = volume_receivers_bind(r->textures[i]);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, rows, 0, GL_RGBA, GL_FLOAT, NULL);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        volume_receivers_unbind(was);
        size_t texels = (size_t)width * (size_t)rows;
        most = texels > most ? texels : most;
    }
    r->scratch = most ? calloc(most * VOLUME_RECEIVERS_PLANE_FLOATS, sizeof *r->scratch) : NULL;
    if (most && !r->scratch) {
        fprintf(stderr, "volumes: out of memory\n");
        return false;
    }
    return context_gl_ok("volume_receivers_init");
}

void volume_receivers_destroy(volume_receivers *r) {
    for (int i = 0; r->textures && i < r->object_count; i++)
        glDeleteTextures(1, &r->textures[i]);
    render_program_destroy(&r->program);
    free(r->textures);
    free(r->huge);
    free(r->scratch);
    *r = (volume_receivers){0};
}

/* Object i's triangles' planes relative to `eye`, into its buffer; a
 * triangle too thin for a normal gets none (0: the shader keeps the
 * rasterized depth there). */
static void volume_receivers_planes(const volume_receivers *r, const scene_object *o, int i, const double eye[3]) {
    uint32_t triangles = o->mesh.index_count / 3;
    for (uint32_t t = 0; t < triangles; t++) {
        double v[3][3], e1[3], e2[3], n[3];
        for (int k = 0; k < 3; k++)
            scene_object_world_corner(o, t, k, v[k]);
        for (int c = 0; c < 3; c++) {
            e1[c] = v[1][c] - v[0][c];
            e2[c] = v[2][c] - v[0][c];
        }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        double length = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        float *plane = r->scratch + (size_t)t * VOLUME_RECEIVERS_PLANE_FLOATS;
        double offset = 0;
        for (int c = 0; c < 3; c++) {
            n[c] = length > 0 ? n[c] / length : 0;
            offset += n[c] * (v[0][c] - eye[c]);
            plane[c] = (float)n[c];
        }
        plane[3] = (float)offset;
    }
    int width, rows;
    volume_receivers_size(triangles, r->width, &width, &rows);
    volume_receivers_binding was = volume_receivers_bind(r->textures[i]);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, rows, GL_RGBA, GL_FLOAT, r->scratch);
    volume_receivers_unbind(was);
}

int volume_receivers_update(volume_receivers *r, const technique_frame *f) {
    const scene *s = f->gpu->scene;
    const double eye[3] = {f->view->eye[0], f->view->eye[1], f->view->eye[2]};
    bool moved = !r->planes_made || memcmp(r->planes_eye, f->view->eye, sizeof r->planes_eye) != 0;
    int count = 0;
    for (int i = 0; i < s->object_count; i++) {
        const scene_object *o = &s->objects[i];
        r->huge[i] =
            r->textures[i] && render_in_mask(f->skips->in_view, i) && render_object_huge(f->gpu, i, f->view->eye);
        count += r->huge[i];
        /* Every candidate's, so that one huge only later has its planes. */
        if (r->textures[i] && moved)
            volume_receivers_planes(r, o, i, eye);
    }
    memcpy(r->planes_eye, f->view->eye, sizeof r->planes_eye);
    r->planes_made = true;
    return count;
}

/* The exact program's uniforms for f's view: the eye ray of a pixel from
 * the projection's x and y rows, the view's rotation alone (the planes
 * are relative to the eye). */
static void volume_receivers_use(const volume_receivers *r, const technique_frame *f) {
    const camera_view *v = f->view;
    render_program_use(&r->program, v);
    render_eye_ray_uniforms(r->program.id, v, f->width, f->height);
    glUniformMatrix4fv(r->projection, 1, GL_FALSE, (const float *)v->raster_projection);
    glUniform1i(r->zero_to_one, v->reversed_depth);
    glUniform1i(r->planes, VOLUME_RECEIVERS_UNIT);
}

void volume_receivers_depth(const volume_receivers *r, const technique_frame *f, bool exact) {
    glDisable(GL_SCISSOR_TEST);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glClear(GL_DEPTH_BUFFER_BIT);
    if (!exact) {
        render_depth_prepass(f->gpu, f->view, f->skips->in_view);
        return;
    }
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    const render_programs *depth = &f->gpu->depth;
    for (int pass = 0; pass < render_programs_passes(depth); pass++) {
        render_program_use(render_programs_pass(depth, pass), f->view);
        for (int i = 0; i < r->object_count; i++)
            if (render_in_mask(f->skips->in_view, i) && !r->huge[i] &&
                render_programs_draws(depth, pass, &f->gpu->scene->objects[i]))
                render_draw_object(f->gpu, render_programs_pass(depth, pass), i);
    }
    volume_receivers_use(r, f);
    volume_receivers_binding was = volume_receivers_bind(0);
    for (int i = 0; i < r->object_count; i++) {
        if (!r->huge[i])
            continue;
        glBindTexture(GL_TEXTURE_2D, r->textures[i]);
        render_draw_object(f->gpu, &r->program, i);
    }
    volume_receivers_unbind(was);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
}
