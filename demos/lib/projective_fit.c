#include "projective_fit.h"

#include <math.h>

#include "frustum.h"
#include "map.h"

/* The frustum is this fraction wider than the casters' sphere or box, so
 * that their silhouette's edge texels and the lookup's bilinear taps stay
 * inside the texture. */
#define PROJECTIVE_FIT_MARGIN 0.02f
/* The near plane at least this fraction of the far one (a caster touching
 * the light would put it at 0). */
#define PROJECTIVE_FIT_NEAR_RATIO 1e-3f

bool projective_fit_casts(const scene_object *o, bool receivers_cast) {
    return o->casts && (!o->receives || receivers_cast);
}

/* The casters' corners and bounds that the light can reach, into corners
 * (8 per caster); returns how many corners. */
static int projective_fit_corners(const scene *s, const scene_light *light, bool receivers_cast, float (*corners)[3],
                                  vec3 lo, vec3 hi) {
    int n = 0;
    glm_vec3_fill(lo, INFINITY);
    glm_vec3_fill(hi, -INFINITY);
    for (int i = 0; i < s->object_count; i++) {
        vec3 blo, bhi;
        if (!projective_fit_casts(&s->objects[i], receivers_cast))
            continue;
        scene_object_world_bounds(&s->objects[i], blo, bhi);
        if (!scene_light_reaches_box(light, blo, bhi))
            continue;
        frustum_box_corners(blo, bhi, &corners[n]);
        n += 8;
        glm_vec3_minv(lo, blo, lo);
        glm_vec3_maxv(hi, bhi, hi);
    }
    return n;
}

void projective_fit(const scene *s, const scene_light *light, bool receivers_cast, float (*corners)[3],
                    projective_frustum *t) {
    vec3 lo, hi, centre, axis, eye;
    int n = projective_fit_corners(s, light, receivers_cast, corners, lo, hi);
    t->fitted = n > 0;
    t->clamped = false;
    if (!t->fitted)
        return;
    glm_vec3_center(lo, hi, centre);
    float radius = glm_vec3_distance(lo, hi) / 2;
    mat4 view, projection;
    t->orthographic = light->type == SCENE_LIGHT_DIRECTIONAL;
    if (t->orthographic) {
        glm_vec3_normalize_to((float *)light->direction, axis);
        glm_vec3_copy(centre, eye);
        frustum_look_along(eye, axis, view);
        vec3 vlo, vhi;
        frustum_view_bounds(view, (const float(*)[3])corners, n, vlo, vhi);
        float grow = PROJECTIVE_FIT_MARGIN * fmaxf(vhi[0] - vlo[0], vhi[1] - vlo[1]);
        float near_plane, far_plane;
        map_depth_range(-vhi[2], -vlo[2], &near_plane, &far_plane);
        glm_ortho(vlo[0] - grow, vhi[0] + grow, vlo[1] - grow, vhi[1] + grow, near_plane, far_plane, projection);
    } else {
        glm_vec3_copy((float *)light->position, eye);
        glm_vec3_sub(centre, eye, axis);
        float distance = glm_vec3_norm(axis);
        if (distance > 0)
            glm_vec3_scale(axis, 1 / distance, axis);
        else
            glm_vec3_copy(light->type == SCENE_LIGHT_SPOT ? (float *)light->direction : (vec3){0, -1, 0}, axis);
        float max_half = glm_rad(PROJECTIVE_FIT_MAX_HALF_ANGLE_DEG);
        float half = max_half;
        if (distance > radius * (1 + PROJECTIVE_FIT_MARGIN))
            half = fminf(asinf(radius / distance) * (1 + PROJECTIVE_FIT_MARGIN), max_half);
        t->clamped = half >= max_half;
        t->half_angle_deg = glm_deg(half);
        float far_plane = distance + radius;
        float near_plane = fmaxf(distance - radius, far_plane * PROJECTIVE_FIT_NEAR_RATIO);
        map_depth_range(near_plane, far_plane, &near_plane, &far_plane);
        near_plane = fmaxf(near_plane, far_plane * PROJECTIVE_FIT_NEAR_RATIO);
        frustum_look_along(eye, axis, view);
        glm_perspective(2 * half, 1, near_plane, far_plane, projection);
    }
    glm_mat4_mul(projection, view, t->view_projection);
    /* Depth from the light along its axis: for a point light, a blocker
     * on the segment from it to a receiver point is nearer along any axis
     * the point lies ahead on; for a directional light, along its rays. */
    glm_vec4((float *)axis, -glm_vec3_dot(axis, eye), t->depth_plane);
    t->nearest = INFINITY;
    for (int c = 0; c < n; c++)
        t->nearest = fminf(t->nearest, glm_vec3_dot(axis, corners[c]) + t->depth_plane[3]);
}
