#include "volume_draw.h"

#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "context.h"
#include "shading.h"

/* ---- set-up ---- */

/* Object i's edge table and adjacency on the GPU. */
static bool volume_draw_init_caster(volume_draw *d, const render_scene *gpu, int i) {
    const mesh *m = &gpu->scene->objects[i].mesh;
    return mesh_edges_build_welded(m, &d->edges[i]) &&
           volume_silhouette_mesh_init(&d->adjacency[i], m, &d->edges[i], gpu->meshes[i].vertex_buffer);
}

bool volume_draw_init(volume_draw *d, const render_scene *gpu) {
    static const char *const cpu_files[] = {"volume.vert", "volume.frag"};
    static const shader_define wide[] = {{VOLUME_SILHOUETTE_WIDE_DEFINE, 1}, {NULL, 0}};
    int cpu_file_count = (int)(sizeof cpu_files / sizeof *cpu_files);
    /* The GPU's silhouettes are a geometry shader's: none without one. */
    bool geometry = context_current_features()->geometry_shaders;
    if (!render_program_load(&d->cpu, cpu_files, cpu_file_count, NULL) ||
        !render_program_load(&d->cpu_wide, cpu_files, cpu_file_count, wide) ||
        (geometry && (!volume_silhouette_load(&d->gpu, false) || !volume_silhouette_load(&d->gpu_wide, true))))
        return false;
    d->cpu_color = shader_uniform(d->cpu.id, "u_color");
    d->cpu_wide_color = shader_uniform(d->cpu_wide.id, "u_color");
    const scene *s = gpu->scene;
    size_t objects = (size_t)s->object_count;
    d->edges = calloc(objects, sizeof *d->edges);
    d->adjacency = calloc(objects, sizeof *d->adjacency);
    if (!d->edges || !d->adjacency) {
        fprintf(stderr, "volumes: out of memory\n");
        return false;
    }
    d->object_count = s->object_count;
    d->caches = calloc((size_t)SCENE_MAX_LIGHTS * VOLUME_DRAW_CACHES, sizeof *d->caches);
    if (!d->caches) {
        fprintf(stderr, "volumes: out of memory\n");
        return false;
    }
    scene_receivers_bounds(s, d->receivers_lo, d->receivers_hi);
    for (int i = 0; i < s->object_count; i++)
        if (s->objects[i].casts && !volume_draw_init_caster(d, gpu, i))
            return false;
    glGenVertexArrays(1, &d->stream_vao);
    glGenBuffers(1, &d->stream_buffer);
    volume_cache_vertex_array(d->stream_vao, d->stream_buffer);
    return true;
}

void volume_draw_destroy(volume_draw *d) {
    render_program_destroy(&d->cpu);
    volume_silhouette_destroy(&d->gpu);
    render_program_destroy(&d->cpu_wide);
    volume_silhouette_destroy(&d->gpu_wide);
    for (int i = 0; i < d->object_count; i++) {
        mesh_edges_free(&d->edges[i]);
        volume_silhouette_mesh_free(&d->adjacency[i]);
    }
    for (int c = 0; d->caches && c < SCENE_MAX_LIGHTS * VOLUME_DRAW_CACHES; c++)
        volume_cache_free(&d->caches[c]);
    free(d->caches);
    free(d->edges);
    free(d->adjacency);
    volume_mesh_free(&d->geometry);
    glDeleteVertexArrays(1, &d->stream_vao);
    glDeleteBuffers(1, &d->stream_buffer);
    *d = (volume_draw){0};
}

int volume_draw_cache(int l, int k) { return l * VOLUME_DRAW_CACHES + 1 + k; }

void volume_draw_forget(volume_draw *d, int l) {
    for (int k = SHADING_LIGHT_CENTRE; k < SOFT_VISIBILITY_MAX_SAMPLES; k++)
        if (d->caches[volume_draw_cache(l, k)].ranges)
            volume_cache_forget(&d->caches[volume_draw_cache(l, k)]);
}

void volume_draw_free_points(volume_draw *d, int l) {
    for (int k = 0; k < SOFT_VISIBILITY_MAX_SAMPLES; k++) {
        volume_cache *c = &d->caches[volume_draw_cache(l, k)];
        d->cache_bytes -= c->capacity * VOLUME_CACHE_VERTEX_BYTES;
        volume_cache_free(c);
    }
}

void volume_draw_reach(volume_draw *d, const scene_light *light, bool trim) {
    glm_vec3_copy(d->receivers_lo, d->reach_lo);
    glm_vec3_copy(d->receivers_hi, d->reach_hi);
    d->reach_on = trim && scene_light_clip_to_range(light, d->reach_lo, d->reach_hi);
}

/* ---- drawing ---- */

/* The program the CPU volumes count with. */
static const render_program *volume_draw_cpu(const volume_draw *d) { return d->wide ? &d->cpu_wide : &d->cpu; }

void volume_draw_wide_sign(volume_draw *d, float sign) {
    if (sign == d->wide_sign)
        return;
    d->wide_sign = sign;
    glUseProgram(d->cpu_wide.id);
    glUniform4f(d->cpu_wide_color, sign, 0, 0, 0);
    if (d->gpu_wide.program.id) {
        glUseProgram(d->gpu_wide.program.id);
        glUniform4f(d->gpu_wide.color, sign, 0, 0, 0);
    }
}

void volume_draw_stream(volume_draw *d, const float (*vertices)[4], size_t count, unsigned primitive) {
    glBindVertexArray(d->stream_vao);
    glBindBuffer(GL_ARRAY_BUFFER, d->stream_buffer);
    size_t bytes = count * sizeof *vertices;
    if (bytes > d->stream_capacity) {
        d->stream_capacity = bytes * 2;
        glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)d->stream_capacity, NULL, GL_STREAM_DRAW);
    }
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)bytes, vertices);
    glDrawArrays(primitive, 0, (GLsizei)count);
}

bool volume_draw_build(volume_draw *d, const technique_frame *f, int i, const float light[4],
                       volume_mesh_parts part) {
    const scene_object *o = &f->gpu->scene->objects[i];
    float object_light[4];
    mesh_point_to_object(o->model, light, object_light);
    volume_mesh_trim trim = {0};
    if (d->reach_on)
        volume_mesh_trim_for(o->model, object_light, &o->mesh, d->reach_lo, d->reach_hi, &trim);
    const render_program *p = volume_draw_cpu(d);
    render_program_use(p, f->view);
    glUniformMatrix4fv(p->model, 1, GL_FALSE, (const float *)o->model);
    if (volume_mesh_build(&d->geometry, &o->mesh, &d->edges[i], object_light, &trim, part))
        return true;
    fprintf(stderr, "volumes: %s: out of memory building its volume\n", o->name);
    return false;
}

/* Caster i's CPU part, from `cache`, kept there first if it is not yet
 * (streamed when it does not fit, or the cache cannot be made). */
static void volume_draw_kept(volume_draw *d, const technique_frame *f, int cache, int i, const float light[4],
                             volume_mesh_parts part) {
    volume_cache *c = &d->caches[cache];
    if (!c->ranges && !volume_cache_init(c, d->object_count)) {
        d->built++;
        if (volume_draw_build(d, f, i, light, part))
            volume_draw_stream(d, d->geometry.vertices, d->geometry.count, GL_TRIANGLES);
        return;
    }
    if (volume_cache_has(c, i, part)) {
        d->reused++;
        const render_program *p = volume_draw_cpu(d);
        render_program_use(p, f->view);
        glUniformMatrix4fv(p->model, 1, GL_FALSE, (const float *)f->gpu->scene->objects[i].model);
    } else {
        d->built++;
        if (!volume_draw_build(d, f, i, light, part))
            return;
        const volume_mesh *v = &d->geometry;
        if (!volume_cache_keep(c, i, part, v, &d->cache_bytes, VOLUME_DRAW_CACHE_MAX_BYTES)) {
            volume_draw_stream(d, v->vertices, v->count, GL_TRIANGLES);
            return;
        }
    }
    volume_cache_draw(c, i, part);
}

void volume_draw_caster(volume_draw *d, const technique_frame *f, int cache, int i, const float light[4], bool gpu,
                        bool zfail) {
    if (gpu) {
        const scene_object *o = &f->gpu->scene->objects[i];
        float object_light[4];
        mesh_point_to_object(o->model, light, object_light);
        volume_silhouette_draw(d->wide ? &d->gpu_wide : &d->gpu, &d->adjacency[i], f->view, (const float *)o->model,
                               object_light, volume_mesh_closed_rule(&o->mesh, &d->edges[i], object_light));
    } else {
        volume_draw_kept(d, f, cache, i, light, VOLUME_MESH_SIDES);
    }
    if (zfail)
        volume_draw_kept(d, f, cache, i, light, VOLUME_MESH_CAPS);
}
