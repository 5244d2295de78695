#include "volume_plan.h"

#include <cglm/cglm.h>
#include <math.h>

#include "frustum.h"
#include "volume_mesh.h"

bool volume_plan_forced_zpass(volume_plan_mode mode) {
    return mode == VOLUME_PLAN_ZPASS || mode == VOLUME_PLAN_EYE_COUNT;
}

bool volume_plan_zfail(volume_plan_mode mode, bool zpass_safe, bool seen_through) {
    if (seen_through && !volume_plan_forced_zpass(mode))
        return true;
    if (mode != VOLUME_PLAN_AUTO)
        return mode == VOLUME_PLAN_ZFAIL;
    return !zpass_safe;
}

/* The mode the plan's casters take: ZP+ only where the light lies off the
 * near plane's plane (see volume_plan_mode), which it then holds,
 * oriented towards the light. */
static volume_plan_mode volume_plan_casters_mode(const technique_frame *f, volume_plan_mode mode, volume_plan *plan) {
    if (mode != VOLUME_PLAN_ZP_PLUS)
        return mode;
    float *n = plan->near_plane, *l = plan->position;
    frustum_near_plane(f->view->view_projection, n);
    float d = glm_vec4_dot(n, l);
    float size = fabsf(n[0] * l[0]) + fabsf(n[1] * l[1]) + fabsf(n[2] * l[2]) + fabsf(n[3] * l[3]);
    if (fabsf(d) <= VOLUME_PLAN_NEAR_TOLERANCE * size)
        return VOLUME_PLAN_AUTO;
    if (d < 0)
        glm_vec4_negate(n);
    return mode;
}

/* Caster i's part of the plan (see top). */
static void volume_plan_caster_for(const technique_frame *f, volume_plan_mode mode, volume_plan *plan, int i,
                                   const vec3 near_rectangle[4]) {
    const scene_object *o = &f->gpu->scene->objects[i];
    volume_plan_caster *c = &plan->casters[i];
    *c = (volume_plan_caster){0};
    if (!o->casts)
        return;
    float lo[3], hi[3];
    scene_object_world_bounds(o, lo, hi);
    if (f->skips->cull_casters && volume_mesh_misses_view(lo, hi, plan->position, f->view->view_projection)) {
        f->skips->counts->casters_culled[plan->light]++;
        return;
    }
    bool zpass_safe = volume_mesh_zpass_safe(lo, hi, plan->position, near_rectangle);
    c->zfail = volume_plan_zfail(mode, zpass_safe, o->single_sided);
    if (volume_plan_forced_zpass(mode) && !zpass_safe) {
        f->skips->counts->casters_drawn[plan->light]++;
        c->needed = true;
        return;
    }
    c->needed = skips_caster_needed(f->skips, &plan->hull, i);
    c->narrowed = c->needed && volume_bounds_caster(f, &plan->hull, i, &plan->bounds, &c->bounds);
    c->near = c->needed && mode == VOLUME_PLAN_ZP_PLUS && !zpass_safe && !c->zfail;
}

void volume_plan_light(const technique_frame *f, int l, const float point[4], volume_plan_mode mode,
                       const int receivers_rect[4], bool depth_bounds, volume_plan_caster *casters,
                       volume_plan *plan) {
    const scene *s = f->gpu->scene;
    *plan = (volume_plan){.light = l, .casters = casters};
    if (point) {
        glm_vec4_copy((float *)point, plan->position);
        skips_point_hull(f->skips, l, point, &plan->hull);
    } else {
        scene_light_homogeneous(&s->lights[l], plan->position);
        skips_light_hull(f->skips, l, &plan->hull);
    }
    volume_bounds_light(f, &plan->hull, receivers_rect, depth_bounds, &plan->bounds);
    mode = volume_plan_casters_mode(f, mode, plan);
    vec3 near_rectangle[4];
    volume_mesh_near_rectangle(f->view->view_projection, near_rectangle);
    for (int i = 0; i < s->object_count; i++)
        volume_plan_caster_for(f, mode, plan, i, (const vec3 *)near_rectangle);
}

void volume_plan_every_caster(const technique_frame *f, int l, const float position[4], volume_plan_mode mode,
                              volume_plan_caster *casters, volume_plan *plan) {
    const scene *s = f->gpu->scene;
    *plan = (volume_plan){.light = l, .casters = casters};
    glm_vec4_copy((float *)position, plan->position);
    mode = volume_plan_casters_mode(f, mode, plan);
    vec3 near_rectangle[4];
    volume_mesh_near_rectangle(f->view->view_projection, near_rectangle);
    for (int i = 0; i < s->object_count; i++) {
        volume_plan_caster *c = &plan->casters[i];
        *c = (volume_plan_caster){.needed = s->objects[i].casts};
        if (!c->needed)
            continue;
        float lo[3], hi[3];
        scene_object_world_bounds(&s->objects[i], lo, hi);
        bool zpass_safe = volume_mesh_zpass_safe(lo, hi, plan->position, (const vec3 *)near_rectangle);
        c->zfail = volume_plan_zfail(mode, zpass_safe, s->objects[i].single_sided);
        c->near = mode == VOLUME_PLAN_ZP_PLUS && !zpass_safe && !c->zfail;
    }
}

int volume_plan_eye_count(const technique_frame *f, const volume_plan *plan, const mesh_edges *edges) {
    const scene *s = f->gpu->scene;
    int count = 0;
    for (int i = 0; i < s->object_count; i++) {
        if (!plan->casters[i].needed)
            continue;
        const scene_object *o = &s->objects[i];
        float light[4];
        vec3 eye;
        mat4 world_to_object;
        mesh_point_to_object(o->model, plan->position, light);
        glm_mat4_inv((vec4 *)o->model, world_to_object);
        glm_mat4_mulv3(world_to_object, (float *)f->view->eye, 1, eye);
        count += volume_mesh_count_at(&o->mesh, volume_mesh_closed_rule(&o->mesh, &edges[i], light), light, eye);
    }
    return count;
}
