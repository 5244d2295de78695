/* warp: the warps and what they are fitted to (see warp.h). */
#include "warp.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "frustum.h"

/* Box extents and depth ranges below this are taken as this, so that a
 * flat box (a plane's) still maps to the clip cube without dividing by 0. */
#define WARP_MIN_EXTENT 1e-12f
/* The fitted depth range is widened by this fraction at each end, so the
 * points it was fitted to are not clipped by rounding. */
#define WARP_DEPTH_MARGIN 1e-3f
/* A light whose PPS image has |xyz| over this many times |w| is taken as a
 * direction there: a point so far out would give a map of no width. */
#define WARP_INFINITY_RATIO 1e3f

bool warp_project(const mat4 m, const float p[3], float out[3]) {
    vec4 h = {p[0], p[1], p[2], 1}, r;
    glm_mat4_mulv((vec4 *)m, h, r);
    if (!(r[3] > 0))
        return false;
    glm_vec3_scale(r, 1.0f / r[3], out);
    return true;
}

/* A matrix taking the box lo..hi to the clip cube. */
static void warp_fit_box(const vec3 lo, const vec3 hi, mat4 out) {
    glm_mat4_identity(out);
    for (int k = 0; k < 3; k++) {
        float extent = fmaxf(hi[k] - lo[k], WARP_MIN_EXTENT);
        out[k][k] = 2 / extent;
        out[3][k] = -(hi[k] + lo[k]) / extent;
    }
}

bool warp_finite(const mat4 m) {
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            if (!isfinite(m[c][r]))
                return false;
    return true;
}

bool warp_frustum_around(const float eye[3], const float (*points)[3], int n, mat4 out, float *near_plane,
                         float *far_plane) {
    vec3 center = GLM_VEC3_ZERO_INIT, axis;
    for (int i = 0; i < n; i++)
        glm_vec3_add(center, (float *)points[i], center);
    glm_vec3_scale(center, 1.0f / (float)n, center);
    glm_vec3_sub(center, (float *)eye, axis);
    if (!(glm_vec3_norm(axis) > 0))
        return false;
    glm_vec3_normalize(axis);
    mat4 view, projection;
    frustum_look_along(eye, axis, view);
    float lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY}, t_min = INFINITY, t_max = 0;
    for (int i = 0; i < n; i++) {
        vec3 q;
        glm_mat4_mulv3(view, (float *)points[i], 1, q);
        float t = -q[2];
        if (!(t > 0))
            return false;
        for (int k = 0; k < 2; k++) {
            lo[k] = fminf(lo[k], q[k] / t);
            hi[k] = fmaxf(hi[k], q[k] / t);
        }
        t_min = fminf(t_min, t);
        t_max = fmaxf(t_max, t);
    }
    float widest = tanf(glm_rad(WARP_MAX_HALF_ANGLE_DEG));
    if (fmaxf(fmaxf(-lo[0], hi[0]), fmaxf(-lo[1], hi[1])) > widest)
        return false;
    *near_plane = t_min * (1 - WARP_DEPTH_MARGIN);
    *far_plane = t_max * (1 + WARP_DEPTH_MARGIN);
    glm_frustum(lo[0] * *near_plane, hi[0] * *near_plane, lo[1] * *near_plane, hi[1] * *near_plane, *near_plane,
                *far_plane, projection);
    glm_mat4_mul(projection, view, out);
    return *far_plane > *near_plane;
}

/* ---- what the warps are fitted to ---- */

/* How far ahead of the camera p lies. */
static float warp_depth(const warp_view *v, const float p[3]) {
    vec3 d;
    glm_vec3_sub((float *)p, (float *)v->eye, d);
    return glm_vec3_dot(d, (float *)v->forward);
}

bool warp_view_of(const camera_view *c, const float (*receivers)[3], int n, warp_view *v) {
    glm_vec3_copy((float *)c->eye, v->eye);
    glm_vec3_copy((vec3){-c->view[0][2], -c->view[1][2], -c->view[2][2]}, v->forward);
    float camera_near = c->projection[3][2] / (c->projection[2][2] - 1);
    v->z_near = INFINITY;
    v->z_far = 0;
    for (int i = 0; i < n; i++) {
        float depth = warp_depth(v, receivers[i]);
        v->z_near = fminf(v->z_near, depth);
        v->z_far = fmaxf(v->z_far, depth);
    }
    v->z_near = fmaxf(v->z_near, camera_near);
    return v->z_far > v->z_near;
}

int warp_relevant_casters(const scene *s, const scene_light *l, float (*points)[3], int receiver_count, int capacity,
                          bool *mask) {
    vec3 lo, hi, axis_u, axis_v, up = {0, 1, 0};
    float ulo = INFINITY, uhi = -INFINITY, vlo = INFINITY, vhi = -INFINITY;
    bool directional = l->type == SCENE_LIGHT_DIRECTIONAL;
    glm_vec3_fill(lo, INFINITY);
    glm_vec3_fill(hi, -INFINITY);
    if (fabsf(l->direction[1]) > FRUSTUM_NEARLY_VERTICAL)
        glm_vec3_copy((vec3){1, 0, 0}, up);
    glm_vec3_crossn((float *)l->direction, up, axis_u);
    glm_vec3_crossn((float *)l->direction, axis_u, axis_v);
    for (int i = 0; i < receiver_count; i++) {
        glm_vec3_minv(lo, points[i], lo);
        glm_vec3_maxv(hi, points[i], hi);
        ulo = fminf(ulo, glm_vec3_dot(points[i], axis_u));
        uhi = fmaxf(uhi, glm_vec3_dot(points[i], axis_u));
        vlo = fminf(vlo, glm_vec3_dot(points[i], axis_v));
        vhi = fmaxf(vhi, glm_vec3_dot(points[i], axis_v));
    }
    if (!directional) {
        glm_vec3_minv(lo, (float *)l->position, lo);
        glm_vec3_maxv(hi, (float *)l->position, hi);
    }
    int n = receiver_count;
    for (int i = 0; i < s->object_count; i++) {
        vec3 blo, bhi, corners[8];
        mask[i] = false;
        if (!s->objects[i].casts)
            continue;
        scene_object_world_bounds(&s->objects[i], blo, bhi);
        frustum_box_corners(blo, bhi, corners);
        if (directional) {
            float clo[2] = {INFINITY, INFINITY}, chi[2] = {-INFINITY, -INFINITY};
            for (int c = 0; c < 8; c++) {
                float u = glm_vec3_dot(corners[c], axis_u), v = glm_vec3_dot(corners[c], axis_v);
                clo[0] = fminf(clo[0], u), chi[0] = fmaxf(chi[0], u);
                clo[1] = fminf(clo[1], v), chi[1] = fmaxf(chi[1], v);
            }
            mask[i] = clo[0] <= uhi && chi[0] >= ulo && clo[1] <= vhi && chi[1] >= vlo;
        } else {
            mask[i] = blo[0] <= hi[0] && bhi[0] >= lo[0] && blo[1] <= hi[1] && bhi[1] >= lo[1] && blo[2] <= hi[2] &&
                      bhi[2] >= lo[2];
        }
        if (mask[i] && n + 8 > capacity)
            return -1;
        if (mask[i]) {
            memcpy(points + n, corners, sizeof corners);
            n += 8;
        }
    }
    return n;
}

/* ---- the warps ---- */

/* Stamminger & Drettakis, with Kozlov's virtual camera: the camera slid
 * back until every point lies well in front of it and the near plane is
 * at the optimum distance; the light mapped into its post-perspective
 * space; the map's frustum fitted there. */
bool warp_psm(const camera_view *c, const scene_light *l, const warp_view *v, const float (*points)[3], int n,
              float (*scratch)[3], warp_result *out) {
    float nearest = INFINITY;
    for (int i = 0; i < n; i++)
        nearest = fminf(nearest, warp_depth(v, points[i]));
    float optimum = v->z_near + sqrtf(v->z_near * v->z_far);
    /* Far enough back for the optimum near plane, and for every point to
     * lie at least half the near distance in front (so none is near w = 0). */
    float slide = fmaxf(fmaxf(optimum - v->z_near, v->z_near - 2 * nearest), 0);
    float near_plane = v->z_near + slide, far_plane = v->z_far + slide;
    mat4 projection, view, translate = GLM_MAT4_IDENTITY_INIT;
    glm_mat4_copy((vec4 *)c->projection, projection);
    projection[2][2] = -(far_plane + near_plane) / (far_plane - near_plane);
    projection[3][2] = -2 * far_plane * near_plane / (far_plane - near_plane);
    translate[3][2] = -slide;
    glm_mat4_mul(translate, (vec4 *)c->view, view);
    glm_mat4_mul(projection, view, out->space);
    out->has_space = true;
    out->slide = slide;

    float(*warped)[3] = scratch;
    for (int i = 0; i < n; i++)
        if (!warp_project(out->space, points[i], warped[i]))
            return false;
    vec4 light;
    scene_light_homogeneous(l, light);
    glm_mat4_mulv(out->space, light, out->light_in_space);
    const float *light_pps = out->light_in_space;
    mat4 fit;
    float length = glm_vec3_norm((float *)light_pps);
    if (fabsf(light_pps[3]) * WARP_INFINITY_RATIO < length) {
        /* Far enough to be a direction in PPS; on either side of infinity
         * the light comes from +xyz. */
        vec3 travel, lo, hi;
        glm_vec3_scale((float *)light_pps, -1.0f / length, travel);
        mat4 light_view, box;
        frustum_look_along(GLM_VEC3_ZERO, travel, light_view); /* any eye: depths are relative */
        frustum_view_bounds(light_view, (const float(*)[3])warped, n, lo, hi);
        out->near_plane = -hi[2];
        out->far_plane = -lo[2];
        glm_ortho(lo[0], hi[0], lo[1], hi[1], out->near_plane, out->far_plane, box);
        glm_mat4_mul(box, light_view, fit);
        out->orthographic = true;
        out->psm_case = WARP_PSM_AT_INFINITY;
        snprintf(out->why, sizeof out->why, "light at infinity in post-perspective space");
    } else {
        vec3 eye;
        glm_vec3_scale((float *)light_pps, 1.0f / light_pps[3], eye);
        if (!warp_frustum_around(eye, (const float(*)[3])warped, n, fit, &out->near_plane, &out->far_plane)) {
            snprintf(out->why, sizeof out->why, "the seen scene surrounds the light in post-perspective space");
            return false;
        }
        bool behind = light_pps[3] < 0;
        if (behind) /* nearer the light is farther from its PPS image */
            for (int col = 0; col < 4; col++)
                fit[col][2] = -fit[col][2];
        out->orthographic = false;
        out->psm_case = behind ? WARP_PSM_BEHIND : WARP_PSM_IN_FRONT;
        snprintf(out->why, sizeof out->why, "%s, virtual camera slid back %.3g",
                 behind ? "light behind the viewer: inverted, depth order flipped" : "light in front of the viewer",
                 slide);
    }
    glm_mat4_mul(fit, out->space, out->view_projection);
    return true;
}

float warp_lispsm_n_opt(float z_near, float z_far, float sin_gamma) {
    return (z_near + sqrtf(z_near * z_far)) / sin_gamma;
}

/* Wimmer et al.: in a space where the light travels along -z (its view
 * for a directional light, its post-perspective space for the others), a
 * perspective along the view direction projected onto the map's plane,
 * its centre n_opt behind the near side of the points. */
bool warp_lispsm(const scene_light *l, const warp_view *v, const float (*points)[3], int receiver_count, int n,
                 float (*scratch)[3], warp_result *out) {
    mat4 space;
    float unused_near, unused_far;
    if (l->type == SCENE_LIGHT_DIRECTIONAL) {
        frustum_look_along(v->eye, l->direction, space);
    } else {
        if (!warp_frustum_around(l->position, points, n, space, &unused_near, &unused_far)) {
            snprintf(out->why, sizeof out->why, "the seen scene surrounds the light");
            return false;
        }
        for (int col = 0; col < 4; col++) /* the light travels along -z */
            space[col][2] = -space[col][2];
    }
    /* A point half the near distance ahead: where the view points. */
    vec3 eye, ahead, view_dir, point;
    glm_vec3_scale((float *)v->forward, 0.5f * v->z_near, point);
    glm_vec3_add(point, (float *)v->eye, point);
    if (!warp_project(space, v->eye, eye) || !warp_project(space, point, ahead)) {
        snprintf(out->why, sizeof out->why, "the camera is behind the light");
        return false;
    }
    glm_vec3_sub(ahead, eye, view_dir);
    glm_vec3_normalize(view_dir);
    float sin_gamma = sqrtf(view_dir[0] * view_dir[0] + view_dir[1] * view_dir[1]);
    out->sin_gamma = sin_gamma;
    if (sin_gamma < WARP_MIN_SIN_GAMMA) {
        snprintf(out->why, sizeof out->why, "view parallel to the light: n_opt is infinite");
        return false;
    }
    /* Turn about z so the view runs along +y. */
    mat4 turn = GLM_MAT4_IDENTITY_INIT;
    float ux = view_dir[0] / sin_gamma, uy = view_dir[1] / sin_gamma;
    turn[0][0] = uy, turn[1][0] = -ux;
    turn[0][1] = ux, turn[1][1] = uy;
    glm_mat4_mul(turn, space, space);
    float(*turned)[3] = scratch;
    vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i < n; i++) {
        if (!warp_project(space, points[i], turned[i]))
            return false;
        if (i < receiver_count) {
            glm_vec3_minv(lo, turned[i], lo);
            glm_vec3_maxv(hi, turned[i], hi);
        }
    }
    glm_mat4_mulv3(turn, eye, 1, eye);
    /* n_opt in world units; in a light's post-perspective space scaled by
     * how the points' depth range along the view shrank there. */
    float depth = hi[1] - lo[1], world_depth = (v->z_far - v->z_near) * sin_gamma;
    float scale = l->type == SCENE_LIGHT_DIRECTIONAL ? 1.0f : depth / fmaxf(world_depth, WARP_MIN_EXTENT);
    float n_opt = warp_lispsm_n_opt(v->z_near, v->z_far, sin_gamma) * scale;
    out->n_opt = n_opt;
    float near_plane = n_opt, far_plane = n_opt + depth;
    vec3 center = {eye[0], lo[1] - n_opt, 0};
    mat4 warp = GLM_MAT4_ZERO_INIT;
    warp[0][0] = 1, warp[3][0] = -center[0];
    warp[1][1] = (far_plane + near_plane) / (far_plane - near_plane);
    warp[3][1] = -warp[1][1] * center[1] - 2 * far_plane * near_plane / (far_plane - near_plane);
    warp[2][2] = -1; /* depth grows away from the light */
    warp[1][3] = 1, warp[3][3] = -center[1];
    glm_mat4_mul(warp, space, out->space);
    out->has_space = true;
    vec3 wlo = {INFINITY, INFINITY, INFINITY}, whi = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i < n; i++) {
        vec3 p, q;
        glm_vec3_copy(turned[i], p);
        /* A caster matters only over the receivers: its depth range there. */
        p[0] = glm_clamp(p[0], lo[0], hi[0]);
        p[1] = glm_clamp(p[1], lo[1], hi[1]);
        if (!warp_project(warp, p, q))
            return false;
        glm_vec3_minv(wlo, q, wlo);
        glm_vec3_maxv(whi, q, whi);
    }
    mat4 box;
    warp_fit_box(wlo, whi, box);
    glm_mat4_mul(box, out->space, out->view_projection);
    out->near_plane = wlo[2];
    out->far_plane = whi[2];
    out->orthographic = true;
    snprintf(out->why, sizeof out->why, "n_opt %.3g, sin(gamma) %.2f", n_opt, sin_gamma);
    return true;
}
