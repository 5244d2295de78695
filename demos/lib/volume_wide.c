#include "volume_wide.h"

#include <glad/gl.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "context.h"
#include "depth.h"
#include "shader.h"

/* The texture unit the write-back and the overlay read the count from. */
#define VOLUME_WIDE_UNIT 14
/* The stencil's bits, all written back. */
#define VOLUME_WIDE_STENCIL_BITS 0xffu
/* The slots of kept bounds: volume_draw_cache's, for every light. */
#define VOLUME_WIDE_SLOTS (SCENE_MAX_LIGHTS * VOLUME_DRAW_CACHES)
/* The counter is soft_visibility's first light's sum. */
#define VOLUME_WIDE_TARGET_LIGHT 0

/* A program of volume_wide.frag over viewport_triangle.vert's triangle;
 * `overlay`: the overlay's. */
static unsigned volume_wide_program(bool overlay) {
    static const char *const files[] = {"viewport_triangle.vert", "volume_wide.frag"};
    const shader_define defines[] = {SHADER_DEFINE(VOLUME_COUNT_BOUND_STENCIL_MAX),
                                     SHADER_DEFINE(VOLUME_WIDE_OTHER),
                                     SHADER_DEFINE(VOLUME_WIDE_OVERLAY_STEPS),
                                     {overlay ? "VOLUME_WIDE_OVERLAY" : NULL, 1},
                                     {NULL, 0}};
    return shader_load_program(files, (int)(sizeof files / sizeof *files), defines);
}

bool volume_wide_init(volume_wide *w, int object_count) {
    *w = (volume_wide){.object_count = object_count};
    w->resolve = volume_wide_program(false);
    w->overlay = volume_wide_program(true);
    w->convex = malloc((size_t)(object_count > 0 ? object_count : 1));
    w->kept = calloc(VOLUME_WIDE_SLOTS, sizeof *w->kept);
    if (!w->resolve || !w->overlay || !soft_visibility_init(&w->target))
        return false;
    if (!w->convex || !w->kept || !volume_count_grid_init(&w->caster_grid, VOLUME_COUNT_BOUND_MESH_BINS) ||
        !volume_count_grid_init(&w->light_grid, VOLUME_COUNT_BOUND_LIGHT_BINS)) {
        fprintf(stderr, "volumes: out of memory for the wide count\n");
        return false;
    }
    memset(w->convex, -1, (size_t)object_count);
    w->resolve_select = shader_uniform(w->resolve, "u_select");
    w->resolve_count = shader_uniform(w->resolve, "u_count");
    w->overlay_count = shader_uniform(w->overlay, "u_count");
    w->overlay_ramp = shader_uniform(w->overlay, "u_ramp");
    w->overlay_alpha = shader_uniform(w->overlay, "u_alpha");
    glGenVertexArrays(1, &w->vao);
    return context_gl_ok("volume_wide_init");
}

void volume_wide_destroy(volume_wide *w) {
    shader_delete_program(w->resolve);
    shader_delete_program(w->overlay);
    glDeleteVertexArrays(1, &w->vao);
    soft_visibility_destroy(&w->target);
    volume_count_grid_free(&w->caster_grid);
    volume_count_grid_free(&w->light_grid);
    for (int s = 0; w->kept && s < VOLUME_WIDE_SLOTS; s++)
        free(w->kept[s]);
    free(w->kept);
    free(w->convex);
    *w = (volume_wide){0};
}

/* ---- the bound ---- */

/* Caster i's bound for the light (homogeneous, world), kept in `slot`;
 * -1 where it cannot be kept (out of memory: then counted wide). */
static int volume_wide_caster_bound(volume_wide *w, const scene_object *o, const mesh_edges *e, int i, int slot,
                                    const float light[4]) {
    if (!w->kept[slot]) {
        w->kept[slot] = malloc((size_t)w->object_count * sizeof *w->kept[slot]);
        if (!w->kept[slot]) {
            fprintf(stderr, "volumes: out of memory for the count bounds\n");
            return -1;
        }
        for (int k = 0; k < w->object_count; k++)
            w->kept[slot][k].bound = -1;
    }
    volume_wide_kept *kept = &w->kept[slot][i];
    if (kept->bound >= 0 && memcmp(kept->light, light, sizeof kept->light) == 0)
        return kept->bound;
    float object_light[4];
    mesh_point_to_object(o->model, light, object_light);
    bool closed_rule = volume_mesh_closed_rule(&o->mesh, e, object_light);
    if (closed_rule && w->convex[i] < 0)
        w->convex[i] = (signed char)volume_count_bound_convex(&o->mesh);
    memcpy(kept->light, light, sizeof kept->light);
    kept->bound = volume_count_bound_mesh(&w->caster_grid, &o->mesh, closed_rule, w->convex[i] > 0, object_light);
    return kept->bound;
}

/* A box's faces as triangles: corners by bits x, y, z of their index. */
#define VOLUME_WIDE_BOX_TRIANGLES 12
static const int volume_wide_box_corners[VOLUME_WIDE_BOX_TRIANGLES][3] = {{0, 1, 3}, {0, 3, 2}, {4, 5, 7}, {4, 7, 6},
                                                                          {0, 1, 5}, {0, 5, 4}, {2, 3, 7}, {2, 7, 6},
                                                                          {0, 2, 6}, {0, 6, 4}, {1, 3, 7}, {1, 7, 5}};

/* Object o's world box as triangles. */
static void volume_wide_box(const scene_object *o, float out[VOLUME_WIDE_BOX_TRIANGLES][3][3]) {
    float lo[3], hi[3];
    scene_object_world_bounds(o, lo, hi);
    for (int t = 0; t < VOLUME_WIDE_BOX_TRIANGLES; t++)
        for (int k = 0; k < 3; k++)
            for (int a = 0; a < 3; a++)
                out[t][k][a] = volume_wide_box_corners[t][k] >> a & 1 ? hi[a] : lo[a];
}

int volume_wide_bound(volume_wide *w, const technique_frame *f, const volume_plan *plan, const mesh_edges *edges,
                      bool forced_zpass) {
    const scene *s = f->gpu->scene;
    float box[VOLUME_WIDE_BOX_TRIANGLES][3][3];
    volume_count_grid *g = &w->light_grid;
    volume_count_grid_begin(g, plan->position);
    for (int i = 0; g->directional && i < s->object_count; i++)
        if (plan->casters[i].needed) {
            volume_wide_box(&s->objects[i], box);
            volume_count_grid_extent(g, (const float(*)[3][3])box, VOLUME_WIDE_BOX_TRIANGLES);
        }
    volume_count_grid_start(g);
    for (int i = 0; i < s->object_count; i++) {
        if (!plan->casters[i].needed)
            continue;
        int bound = volume_wide_caster_bound(w, &s->objects[i], &edges[i], i, plan->cache, plan->position);
        if (bound < 0)
            return INT_MAX;
        volume_wide_box(&s->objects[i], box);
        volume_count_grid_add(g, (const float(*)[3][3])box, VOLUME_WIDE_BOX_TRIANGLES, bound);
    }
    int bound = volume_count_grid_max(g);
    return forced_zpass ? 2 * bound : bound;
}

/* ---- counting ---- */

bool volume_wide_begin(volume_wide *w, volume_draw *d, int start) {
    if (!soft_visibility_begin(&w->target, VOLUME_WIDE_TARGET_LIGHT, 1, true))
        return false;
    glBindFramebuffer(GL_FRAMEBUFFER, w->target.lights[VOLUME_WIDE_TARGET_LIGHT].framebuffer);
    glColorMask(GL_TRUE, GL_FALSE, GL_FALSE, GL_FALSE);
    if (start != 0) {
        glClearColor((float)start, 0, 0, 0);
        glClear(GL_COLOR_BUFFER_BIT);
        glClearColor(0, 0, 0, 0);
    }
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glStencilMask(0);
    d->wide = true;
    return true;
}

void volume_wide_caster(volume_wide *w, volume_draw *d, const camera_view *view, bool zfail) {
    (void)w;
    glDepthFunc(depth_func(view, zfail ? GL_GEQUAL : GL_LESS));
    volume_draw_wide_sign(d, zfail ? -1.0f : 1.0f);
}

/* Draws viewport_triangle.vert's triangle over the viewport with `program`,
 * the counter bound to its sampler `count`. */
static void volume_wide_screen(volume_wide *w, unsigned program, int count) {
    glUseProgram(program);
    glUniform1i(count, VOLUME_WIDE_UNIT);
    glActiveTexture(GL_TEXTURE0 + VOLUME_WIDE_UNIT);
    glBindTexture(GL_TEXTURE_2D, w->target.lights[VOLUME_WIDE_TARGET_LIGHT].texture);
    glActiveTexture(GL_TEXTURE0);
    glBindVertexArray(w->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
}

void volume_wide_end(volume_wide *w, volume_draw *d, const camera_view *view) {
    d->wide = false;
    glBindFramebuffer(GL_FRAMEBUFFER, w->target.target_framebuffer);
    glDisable(GL_BLEND);
    glStencilMask(VOLUME_WIDE_STENCIL_BITS);
    glDepthFunc(depth_func(view, GL_LESS));
    GLboolean depth_test = glIsEnabled(GL_DEPTH_TEST);
    glDisable(GL_DEPTH_TEST);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glClear(GL_STENCIL_BUFFER_BIT); /* 0 where the count is, whatever the stencil started from */
    glEnable(GL_STENCIL_TEST);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    for (int value = 1; value <= VOLUME_WIDE_OTHER; value++) {
        glStencilFunc(GL_ALWAYS, value, VOLUME_WIDE_STENCIL_BITS);
        glUseProgram(w->resolve);
        glUniform1i(w->resolve_select, value);
        volume_wide_screen(w, w->resolve, w->resolve_count);
    }
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (depth_test)
        glEnable(GL_DEPTH_TEST);
}

/* ---- the overlay ---- */

void volume_wide_overlay(volume_wide *w, const float (*ramp)[3], float alpha, int *largest) {
    soft_visibility_light *counter = &w->target.lights[VOLUME_WIDE_TARGET_LIGHT];
    size_t pixels = (size_t)w->target.width * (size_t)w->target.height;
    /* Read as RGBA, the one format every GL reads a float colour buffer
     * in (ES: not GL_RED); the count is red. */
    float(*counts)[4] = malloc((pixels ? pixels : 1) * sizeof *counts);
    *largest = 0;
    if (counts) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, counter->framebuffer);
        glReadPixels(0, 0, w->target.width, w->target.height, GL_RGBA, GL_FLOAT, counts);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, w->target.target_framebuffer);
        for (size_t p = 0; p < pixels; p++)
            *largest = fabsf(counts[p][0]) > (float)*largest ? (int)fabsf(counts[p][0]) : *largest;
        free(counts);
    } else {
        fprintf(stderr, "volumes: out of memory reading the wide count back\n");
    }
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(w->overlay);
    glUniform3fv(w->overlay_ramp, VOLUME_WIDE_OVERLAY_STEPS, (const float *)ramp);
    glUniform1f(w->overlay_alpha, alpha);
    volume_wide_screen(w, w->overlay, w->overlay_count);
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
}
