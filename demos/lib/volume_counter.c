#include "volume_counter.h"

#include <glad/gl.h>
#include <stdio.h>

#include "depth.h"
#include "volume_bounds.h"
#include "volume_mesh.h"

bool volume_counter_init(volume_counter *c, volume_draw *draw, int object_count) {
    *c = (volume_counter){.draw = draw};
    return volume_wide_init(&c->wide, object_count) && volume_near_init(&c->near);
}

void volume_counter_destroy(volume_counter *c) {
    volume_wide_destroy(&c->wide);
    volume_near_destroy(&c->near);
}

void volume_counter_clear(volume_counter *c, const technique_frame *f, const volume_plan *plan) {
    const int *rect = plan->bounds.rect;
    glEnable(GL_SCISSOR_TEST);
    glScissor(rect[0], rect[1], rect[2], rect[3]);
    int eye = c->settings.mode == VOLUME_PLAN_EYE_COUNT ? volume_plan_eye_count(f, plan, c->draw->edges) : 0;
    if (plan->reported)
        c->eye = eye;
    c->start = eye;
    glClearStencil(eye & VOLUME_COUNTER_STENCIL_MASK);
    glClear(GL_STENCIL_BUFFER_BIT);
    glClearStencil(0);
    glEnable(GL_STENCIL_TEST);
}

/* Whether the plan's volumes count wide: their bound passes what the
 * stencil holds (--counter auto), or always (float). */
void volume_counter_begin(volume_counter *c, const technique_frame *f, const volume_plan *plan) {
    int bound = volume_wide_bound(&c->wide, f, plan, c->draw->edges, volume_plan_forced_zpass(c->settings.mode));
    bool wide = c->settings.kind == VOLUME_COUNTER_FLOAT ||
                (c->settings.kind == VOLUME_COUNTER_AUTO && bound > VOLUME_COUNT_BOUND_STENCIL_MAX);
    c->counting_wide = wide && volume_wide_begin(&c->wide, c->draw, c->start);
    if (plan->reported) {
        c->bound = bound;
        c->bound_wide = c->counting_wide;
    }
}

/* Counting ops for both faces in one pass, wrapping so that more than 255
 * overlapping volumes still sum right modulo 256; or the float count's
 * depth test and sign. */
static void volume_counter_caster_ops(volume_counter *c, const technique_frame *f, bool zfail) {
    if (zfail) {
        glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_DECR_WRAP, GL_KEEP);
        glStencilOpSeparate(GL_BACK, GL_KEEP, GL_INCR_WRAP, GL_KEEP);
    } else {
        glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_KEEP, GL_INCR_WRAP);
        glStencilOpSeparate(GL_BACK, GL_KEEP, GL_KEEP, GL_DECR_WRAP);
    }
    if (c->counting_wide)
        volume_wide_caster(&c->wide, c->draw, f->view, zfail);
}

/* Caster k's own bounds on, where narrowed: whether they are not empty
 * (the caller sets the plan's back after). */
static bool volume_counter_narrow(const volume_plan_caster *k) {
    if (!k->narrowed)
        return true;
    volume_bounds_use(&k->bounds);
    return k->bounds.rect[2] > 0 && k->bounds.rect[3] > 0;
}

/* ZP+: the count on the near plane of the casters that take it
 * (volume_near.h), each within its bounds. */
static int volume_counter_near(volume_counter *c, const technique_frame *f, const volume_plan *plan) {
    const scene *s = f->gpu->scene;
    int near = 0;
    for (int i = 0; i < s->object_count; i++) {
        const volume_plan_caster *k = &plan->casters[i];
        if (!k->needed || !k->near)
            continue;
        near++;
        if (volume_counter_narrow(k)) {
            const scene_object *o = &s->objects[i];
            float light[4];
            mesh_point_to_object(o->model, plan->position, light);
            bool closed = volume_mesh_closed_rule(&o->mesh, &c->draw->edges[i], light);
            volume_near_caster(&c->near, f, i, plan->position, plan->near_plane, closed, c->counting_wide);
        }
        if (k->narrowed)
            volume_bounds_use(&plan->bounds);
    }
    return near;
}

void volume_counter_draw(volume_counter *c, const technique_frame *f, const volume_plan *plan) {
    const scene *s = f->gpu->scene;
    int zpass = 0, zfail = 0;
    if (plan->bounds.bounded) {
        glEnable(GL_DEPTH_BOUNDS_TEST_EXT);
        glDepthBoundsEXT(plan->bounds.depth[0], plan->bounds.depth[1]);
    }
    glColorMask(c->counting_wide, GL_FALSE, GL_FALSE, GL_FALSE); /* the float count's red */
    glDepthMask(GL_FALSE);
    glStencilFunc(GL_ALWAYS, 0, VOLUME_COUNTER_STENCIL_MASK);
    int near = volume_counter_near(c, f, plan);
    /* Counted from the near plane (ZP+), the faces before it are clipped;
     * a plan without such a caster (ZP+'s light in the near plane's plane
     * counts as auto) keeps z-fail's caps at infinity. */
    depth_clamp(!c->settings.no_depth_clamp && near == 0);
    glDisable(GL_CULL_FACE);
    glDepthFunc(depth_func(f->view, GL_LESS)); /* a surface's own cap, at its depth, counts as behind it */
    /* Not only casters in view: one outside may cast a volume across it. */
    for (int i = 0; i < s->object_count; i++) {
        const volume_plan_caster *k = &plan->casters[i];
        if (!k->needed)
            continue;
        zfail += k->zfail;
        zpass += !k->zfail;
        volume_counter_caster_ops(c, f, k->zfail);
        if (volume_counter_narrow(k))
            volume_draw_caster(c->draw, f, plan->cache, i, plan->position, c->settings.gpu_silhouettes, k->zfail);
        if (k->narrowed)
            volume_bounds_use(&plan->bounds);
    }
    depth_clamp(false);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (plan->bounds.bounded)
        glDisable(GL_DEPTH_BOUNDS_TEST_EXT);
    if (plan->reported) {
        c->zpass = zpass;
        c->zfail = zfail;
        c->near_counted = near;
    }
}

void volume_counter_end(volume_counter *c, const technique_frame *f) {
    if (c->counting_wide)
        volume_wide_end(&c->wide, c->draw, f->view);
    c->counting_wide = false;
}

int volume_counter_describe(const volume_counter *c, char *out, size_t size) {
    bool deep = c->bound > VOLUME_COUNT_BOUND_STENCIL_MAX;
    if (c->bound_wide)
        return snprintf(out, size, "; count: float (bound %d%s)", c->bound,
                        deep ? " past the stencil's" : ", --counter float");
    if (!deep)
        return snprintf(out, size, "; stencil: 8-bit exact (bound %d)", c->bound);
    return snprintf(out, size, "; stencil: 8-bit, may WRAP (bound %d > %d%s)", c->bound,
                    VOLUME_COUNT_BOUND_STENCIL_MAX,
                    c->settings.kind == VOLUME_COUNTER_STENCIL ? ", --counter stencil" : "");
}
