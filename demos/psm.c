/* psm: perspective shadow maps, with light space perspective shadow maps
 * and the uniform map for comparison.
 *
 * A uniform map spends its texels evenly over what the light sees, so near
 * the viewer one texel covers many pixels (perspective aliasing). Warping
 * the map puts texels where the viewer looks:
 *
 *   psm     Stamminger & Drettakis, "Perspective shadow maps", SIGGRAPH
 *           2002: the map is rendered in the camera's post-perspective
 *           space (PPS), where the near part of the view is large. A
 *           directional light becomes a point there, a point light on the
 *           camera's plane a direction. The hard cases follow Kozlov,
 *           "Perspective shadow maps: care and feeding" (GPU Gems, ch. 14):
 *           casters behind the camera are brought in by sliding a virtual
 *           camera back; a light behind the viewer lands beyond infinity,
 *           its rays reach the scene from the far side of its PPS image,
 *           so the map looks from there with its depth order reversed (the
 *           depth row negated: the test flipped without a special state).
 *   lispsm  Wimmer, Scherzer & Purgathofer, "Light space perspective shadow
 *           maps", EGSR 2004: a perspective warp along the view direction
 *           as seen from the light, its strength set by n_opt = (z_n +
 *           sqrt(z_n z_f)) / sin(gamma); as the view turns parallel to the
 *           light, n_opt grows without bound and the map turns uniform.
 *           Spot and point lights get the same warp in the light's own
 *           post-perspective space, where they are directional.
 *   uniform shadowmap.c's fitted map (a cube map for point lights).
 *
 * The same virtual near plane sets both warps' strength: z_n + sqrt(z_n
 * z_f), the optimum both papers derive for a light overhead. A warp can
 * lose to the uniform map (light nearly along the view, a point light
 * among the receivers), so each frame both are measured where the camera
 * looks: rays through a grid of pixels hit the receivers' boxes, and at
 * each hit the map texel's size in pixels on that plane (the dp/ds of the
 * papers) is found from both matrices. The warp is kept only where its
 * mean is at least a fifth smaller; the HUD says which won and why.
 *
 * Bias and filtering are shadowmap.c's: the constant and normal-offset
 * biases move the point in world units, one texel of the warped map there
 * (found from the matrix's derivatives), since the warp distorts depth.
 *
 * For lectures (--overlay): shadowmap.c's overlays, among them
 * "texel-size" (the dp/ds heat map: compare the warps on long_view), and
 * "post-perspective": a second viewport with light 0's warp space (PPS for
 * psm: its clip cube is the view frustum), the scene warped into it and the
 * map's frustum there.
 */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shadowmap.h"

#define PSM_MAX_POINTS (SHADOWMAP_MAX_RECEIVER_POINTS + 8 * 256) /* receivers' corners, then casters' */
#define PSM_MAX_HALF_ANGLE_DEG 80.0f      /* wider, and a perspective map starves its edges */
#define PSM_SAMPLES_X 32                  /* the pixel grid the warps are measured on */
#define PSM_SAMPLES_Y 18
#define PSM_GRAZING_SINE 0.0523f /* sin 3 degrees */
/* A warp is kept where it shrinks the mean texel by at least a fifth: the
 * measure is taken on the receivers' boxes, not their surfaces, so near
 * ties go to the map whose texels do not depend on the warp's aim. */
#define PSM_WARP_GAIN 0.8f

static const char *const psm_warps[] = {"psm", "uniform", "lispsm", NULL};
enum { PSM_WARP_PSM, PSM_WARP_UNIFORM, PSM_WARP_LISPSM };
static const char *const psm_overlays[] = {SHADOWMAP_OVERLAY_NAMES, "post-perspective", NULL};
enum { PSM_OVERLAY_POST_PERSPECTIVE = SHADOWMAP_OVERLAY_COUNT };

/* What a frame chose for one light, for the HUD, the tests and the
 * post-perspective view. */
typedef struct psm_choice {
    const char *warp;    /* the map in use: "psm", "lispsm" or "uniform" */
    char why[160];       /* the case the warp took, or why it fell back */
    float texel_pixels[2]; /* mean texel size on screen: the warp's, uniform's */
    mat4 warp_space;     /* world -> the space the warp fits in (PPS for psm) */
    bool has_warp_space;
} psm_choice;

static struct {
    shadowmap_settings settings;
    int warp;
    shadowmap_maps maps;
    bool *casters[SCENE_MAX_LIGHTS]; /* per light: the casters that can shadow what is seen */
    psm_choice choice[SCENE_MAX_LIGHTS];
    render_program warped;           /* the scene in the post-perspective view */
    int warped_space;
} psm;

static const technique_param psm_params[] = {
    {"warp", "how the map is placed: post-perspective, light-space perspective, or uniform", GLFW_KEY_W,
     TECHNIQUE_CHOICE, .index = &psm.warp, .choices = psm_warps},
    SHADOWMAP_PARAMS(psm.settings),
    {"overlay", "for lectures: shadowmap's overlays, texel size on screen, the post-perspective view", GLFW_KEY_V,
     TECHNIQUE_CHOICE, .index = &psm.settings.overlay, .choices = psm_overlays},
};

/* ---- small geometry ---- */

/* p transformed by the projective m and divided by w; false if w <= 0
 * (behind the eye of m), where the division would fold the point over. */
static bool psm_project(const mat4 m, const float p[3], float out[3]) {
    vec4 h = {p[0], p[1], p[2], 1}, r;
    glm_mat4_mulv((vec4 *)m, h, r);
    if (!(r[3] > 0))
        return false;
    glm_vec3_scale(r, 1.0f / r[3], out);
    return true;
}

/* A matrix taking the box lo..hi to the clip cube. */
static void psm_fit_box(const vec3 lo, const vec3 hi, mat4 out) {
    glm_mat4_identity(out);
    for (int k = 0; k < 3; k++) {
        float extent = fmaxf(hi[k] - lo[k], 1e-12f);
        out[k][k] = 2 / extent;
        out[3][k] = -(hi[k] + lo[k]) / extent;
    }
}

static bool psm_finite(const mat4 m) {
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            if (!isfinite(m[c][r]))
                return false;
    return true;
}

/* A perspective frustum from `eye` just around `points`: its axis through
 * their centroid, its sides and depth range fitted. False when a point
 * lies behind the eye or the frustum would be wider than
 * PSM_MAX_HALF_ANGLE_DEG each side. */
static bool psm_frustum_around(const float eye[3], const float (*points)[3], int n, mat4 out, float *near_plane,
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
    float widest = tanf(glm_rad(PSM_MAX_HALF_ANGLE_DEG));
    if (fmaxf(fmaxf(-lo[0], hi[0]), fmaxf(-lo[1], hi[1])) > widest)
        return false;
    *near_plane = t_min * 0.999f;
    *far_plane = t_max * 1.001f;
    glm_frustum(lo[0] * *near_plane, hi[0] * *near_plane, lo[1] * *near_plane, hi[1] * *near_plane, *near_plane,
                *far_plane, projection);
    glm_mat4_mul(projection, view, out);
    return *far_plane > *near_plane;
}

/* ---- what the warps are fitted to ---- */

/* The camera's forward axis and the depth range of the visible receivers
 * along it (at least the camera's near plane). */
typedef struct psm_view {
    vec3 eye, forward;
    float z_near, z_far;
} psm_view;

/* How far ahead of the camera p lies. */
static float psm_depth(const psm_view *v, const float p[3]) {
    vec3 d;
    glm_vec3_sub((float *)p, (float *)v->eye, d);
    return glm_vec3_dot(d, (float *)v->forward);
}

static bool psm_view_of(const technique_frame *f, const float (*receivers)[3], int n, psm_view *v) {
    const camera_view *c = f->view;
    glm_vec3_copy((float *)c->eye, v->eye);
    glm_vec3_copy((vec3){-c->view[0][2], -c->view[1][2], -c->view[2][2]}, v->forward);
    float camera_near = c->projection[3][2] / (c->projection[2][2] - 1);
    v->z_near = INFINITY;
    v->z_far = 0;
    for (int i = 0; i < n; i++) {
        float depth = psm_depth(v, receivers[i]);
        v->z_near = fminf(v->z_near, depth);
        v->z_far = fmaxf(v->z_far, depth);
    }
    v->z_near = fmaxf(v->z_near, camera_near);
    return v->z_far > v->z_near;
}

/* The casters that can shadow the visible receivers, marked in `mask`,
 * their box corners appended after the receivers in `points`. Directional
 * light: boxes that overlap the receivers seen along the light. Spot and
 * point: boxes that meet the box around the light and the receivers (which
 * holds every segment between them). Returns the new point count, or -1
 * when they do not fit in PSM_MAX_POINTS. */
static int psm_relevant_casters(const technique_frame *f, const scene_light *l, float (*points)[3],
                                int receiver_count, bool *mask) {
    const scene *s = f->gpu->scene;
    vec3 lo, hi, axis_u, axis_v, up = {0, 1, 0};
    float ulo = INFINITY, uhi = -INFINITY, vlo = INFINITY, vhi = -INFINITY;
    bool directional = l->type == SCENE_LIGHT_DIRECTIONAL;
    glm_vec3_fill(lo, INFINITY);
    glm_vec3_fill(hi, -INFINITY);
    if (fabsf(l->direction[1]) > 0.99f)
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
            mask[i] = blo[0] <= hi[0] && bhi[0] >= lo[0] && blo[1] <= hi[1] && bhi[1] >= lo[1] &&
                      blo[2] <= hi[2] && bhi[2] >= lo[2];
        }
        if (mask[i] && n + 8 > PSM_MAX_POINTS)
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
static bool psm_warp_psm(const technique_frame *f, const scene_light *l, const psm_view *v, const float (*points)[3],
                         int n, shadowmap_light *m, psm_choice *choice) {
    const camera_view *c = f->view;
    float nearest = INFINITY;
    for (int i = 0; i < n; i++)
        nearest = fminf(nearest, psm_depth(v, points[i]));
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
    glm_mat4_mul(projection, view, choice->warp_space);
    choice->has_warp_space = true;

    static float warped[PSM_MAX_POINTS][3];
    for (int i = 0; i < n; i++)
        if (!psm_project(choice->warp_space, points[i], warped[i]))
            return false;
    vec4 light, light_pps;
    scene_light_homogeneous(l, light);
    glm_mat4_mulv(choice->warp_space, light, light_pps);
    mat4 fit;
    float length = glm_vec3_norm(light_pps);
    if (fabsf(light_pps[3]) * 1e3f < length) {
        /* Far enough to be a direction in PPS; on either side of infinity
         * the light comes from +xyz. */
        vec3 travel, lo, hi;
        glm_vec3_scale(light_pps, -1.0f / length, travel);
        mat4 light_view, box;
        frustum_look_along(GLM_VEC3_ZERO, travel, light_view); /* any eye: depths are relative */
        frustum_view_bounds(light_view, (const float(*)[3])warped, n, lo, hi);
        m->near_plane = -hi[2];
        m->far_plane = -lo[2];
        glm_ortho(lo[0], hi[0], lo[1], hi[1], m->near_plane, m->far_plane, box);
        glm_mat4_mul(box, light_view, fit);
        m->orthographic = true;
        snprintf(choice->why, sizeof choice->why, "light at infinity in post-perspective space");
    } else {
        vec3 eye;
        glm_vec3_scale(light_pps, 1.0f / light_pps[3], eye);
        if (!psm_frustum_around(eye, (const float(*)[3])warped, n, fit, &m->near_plane, &m->far_plane)) {
            snprintf(choice->why, sizeof choice->why, "the seen scene surrounds the light in post-perspective space");
            return false;
        }
        bool behind = light_pps[3] < 0;
        if (behind) /* nearer the light is farther from its PPS image */
            for (int col = 0; col < 4; col++)
                fit[col][2] = -fit[col][2];
        m->orthographic = false;
        snprintf(choice->why, sizeof choice->why, "%s, virtual camera slid back %.3g",
                 behind ? "light behind the viewer: inverted, depth order flipped" : "light in front of the viewer",
                 slide);
    }
    glm_mat4_mul(fit, choice->warp_space, m->view_projection[0]);
    return true;
}

/* Wimmer et al.: in a space where the light travels along -z (its view
 * for a directional light, its post-perspective space for the others), a
 * perspective along the view direction projected onto the map's plane,
 * its centre n_opt behind the near side of the points. */
static bool psm_warp_lispsm(const scene_light *l, const psm_view *v, const float (*points)[3], int receiver_count,
                            int n, shadowmap_light *m, psm_choice *choice) {
    mat4 space;
    float unused_near, unused_far;
    if (l->type == SCENE_LIGHT_DIRECTIONAL) {
        frustum_look_along(v->eye, l->direction, space);
    } else {
        if (!psm_frustum_around(l->position, points, n, space, &unused_near, &unused_far)) {
            snprintf(choice->why, sizeof choice->why, "the seen scene surrounds the light");
            return false;
        }
        for (int col = 0; col < 4; col++) /* the light travels along -z */
            space[col][2] = -space[col][2];
    }
    vec3 eye, ahead, view_dir, point;
    glm_vec3_scale((float *)v->forward, 0.5f * v->z_near, point);
    glm_vec3_add(point, (float *)v->eye, point);
    if (!psm_project(space, v->eye, eye) || !psm_project(space, point, ahead)) {
        snprintf(choice->why, sizeof choice->why, "the camera is behind the light");
        return false;
    }
    glm_vec3_sub(ahead, eye, view_dir);
    glm_vec3_normalize(view_dir);
    float sin_gamma = sqrtf(view_dir[0] * view_dir[0] + view_dir[1] * view_dir[1]);
    if (sin_gamma < 1e-3f) {
        snprintf(choice->why, sizeof choice->why, "view parallel to the light: n_opt is infinite");
        return false;
    }
    /* Turn about z so the view runs along +y. */
    mat4 turn = GLM_MAT4_IDENTITY_INIT;
    float ux = view_dir[0] / sin_gamma, uy = view_dir[1] / sin_gamma;
    turn[0][0] = uy, turn[1][0] = -ux;
    turn[0][1] = ux, turn[1][1] = uy;
    glm_mat4_mul(turn, space, space);
    static float turned[PSM_MAX_POINTS][3];
    vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i < n; i++) {
        if (!psm_project(space, points[i], turned[i]))
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
    float scale = l->type == SCENE_LIGHT_DIRECTIONAL ? 1.0f : depth / fmaxf(world_depth, 1e-12f);
    float n_opt = (v->z_near + sqrtf(v->z_near * v->z_far)) / sin_gamma * scale;
    float near_plane = n_opt, far_plane = n_opt + depth;
    vec3 center = {eye[0], lo[1] - n_opt, 0};
    mat4 warp = GLM_MAT4_ZERO_INIT;
    warp[0][0] = 1, warp[3][0] = -center[0];
    warp[1][1] = (far_plane + near_plane) / (far_plane - near_plane);
    warp[3][1] = -warp[1][1] * center[1] - 2 * far_plane * near_plane / (far_plane - near_plane);
    warp[2][2] = -1; /* depth grows away from the light */
    warp[1][3] = 1, warp[3][3] = -center[1];
    glm_mat4_mul(warp, space, choice->warp_space);
    choice->has_warp_space = true;
    vec3 wlo = {INFINITY, INFINITY, INFINITY}, whi = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i < n; i++) {
        vec3 p, q;
        glm_vec3_copy(turned[i], p);
        /* A caster matters only over the receivers: its depth range there. */
        p[0] = glm_clamp(p[0], lo[0], hi[0]);
        p[1] = glm_clamp(p[1], lo[1], hi[1]);
        if (!psm_project(warp, p, q))
            return false;
        glm_vec3_minv(wlo, q, wlo);
        glm_vec3_maxv(whi, q, whi);
    }
    mat4 box;
    psm_fit_box(wlo, whi, box);
    glm_mat4_mul(box, choice->warp_space, m->view_projection[0]);
    m->near_plane = wlo[2];
    m->far_plane = whi[2];
    m->orthographic = true;
    snprintf(choice->why, sizeof choice->why, "n_opt %.3g, sin(gamma) %.2f", n_opt, sin_gamma);
    return true;
}

/* ---- measuring a map where the camera looks ---- */

/* The derivative of m's (x, y) / w at p along t, in units of `half`
 * (half the map's or the viewport's size: clip units to texels or pixels). */
static void psm_derivative(const mat4 m, const vec4 clip, const float t[3], const float half[2], float out[2]) {
    for (int k = 0; k < 2; k++) {
        float row = m[0][k] * t[0] + m[1][k] * t[1] + m[2][k] * t[2];
        float w_row = m[0][3] * t[0] + m[1][3] * t[1] + m[2][3] * t[2];
        out[k] = (row - clip[k] / clip[3] * w_row) / clip[3] * half[k];
    }
}

/* The map's matrix for point p: a cube face by p's major axis from the
 * light (GL's face order), or the 2D map's. */
static const vec4 *psm_map_matrix(const shadowmap_light *m, const float light[3], const float p[3]) {
    if (!m->cube)
        return m->view_projection[0];
    vec3 d;
    glm_vec3_sub((float *)p, (float *)light, d);
    int axis = fabsf(d[0]) >= fabsf(d[1]) && fabsf(d[0]) >= fabsf(d[2]) ? 0 : fabsf(d[1]) >= fabsf(d[2]) ? 1 : 2;
    return m->view_projection[2 * axis + (d[axis] < 0)];
}

/* A point on a receiver where the camera looks, to measure maps at. */
typedef struct psm_sample {
    vec3 position, tangent[2]; /* on a face of a receiver's box */
    float pixels;              /* pixels per unit area of that face there */
} psm_sample;

/* Rays through a grid of pixels to the receivers' boxes; each hit is a
 * sample, with the pixel area on the face it hit. Faces within 3 degrees
 * of edge-on to the light are left out: every map's texels on them are of
 * unbounded length (and they take almost no light). Faces turned away
 * count: boxes stand for surfaces that may well face the light. Outside a
 * spot's cone the cone decides, not the map. Returns how many. */
static int psm_samples(const technique_frame *f, const scene_light *l, psm_sample *out) {
    const scene *s = f->gpu->scene;
    mat4 inverse;
    glm_mat4_inv((vec4 *)f->view->view_projection, inverse);
    float screen_half[2] = {0.5f * (float)f->width, 0.5f * (float)f->height};
    int n = 0;
    for (int sy = 0; sy < PSM_SAMPLES_Y; sy++) {
        for (int sx = 0; sx < PSM_SAMPLES_X; sx++) {
            vec4 ndc = {(2.0f * (float)sx + 1) / PSM_SAMPLES_X - 1, (2.0f * (float)sy + 1) / PSM_SAMPLES_Y - 1, 1, 1};
            vec3 direction, far_point;
            glm_mat4_mulv(inverse, ndc, ndc);
            glm_vec3_scale(ndc, 1.0f / ndc[3], far_point);
            glm_vec3_sub(far_point, (float *)f->view->eye, direction);
            float best = INFINITY;
            int best_axis = 0;
            for (int i = 0; i < s->object_count; i++) {
                vec3 lo, hi;
                if (!s->objects[i].receives)
                    continue;
                scene_object_world_bounds(&s->objects[i], lo, hi);
                float t0 = 0, t1 = best;
                int axis = -1;
                for (int k = 0; k < 3; k++) {
                    float a = (lo[k] - f->view->eye[k]) / direction[k], b = (hi[k] - f->view->eye[k]) / direction[k];
                    if (a > b) {
                        float swap = a;
                        a = b, b = swap;
                    }
                    if (a > t0)
                        t0 = a, axis = k;
                    t1 = fminf(t1, b);
                }
                if (axis >= 0 && t0 <= t1 && t0 < best)
                    best = t0, best_axis = axis;
            }
            if (!isfinite(best) || best > 1)
                continue;
            psm_sample *sample = &out[n];
            vec3 normal = {0, 0, 0}, to_light;
            glm_vec3_scale(direction, best, sample->position);
            glm_vec3_add(sample->position, (float *)f->view->eye, sample->position);
            glm_vec3_zero(sample->tangent[0]);
            glm_vec3_zero(sample->tangent[1]);
            sample->tangent[0][(best_axis + 1) % 3] = 1;
            sample->tangent[1][(best_axis + 2) % 3] = 1;
            normal[best_axis] = direction[best_axis] > 0 ? -1.0f : 1.0f;
            if (l->type == SCENE_LIGHT_DIRECTIONAL)
                glm_vec3_negate_to((float *)l->direction, to_light);
            else
                glm_vec3_sub((float *)l->position, sample->position, to_light);
            if (!(fabsf(glm_vec3_dot(normal, to_light)) > PSM_GRAZING_SINE * glm_vec3_norm(to_light)))
                continue;
            if (l->type == SCENE_LIGHT_SPOT && -glm_vec3_dot(to_light, (float *)l->direction) <
                                                   cosf(glm_rad(l->outer_angle_deg)) * glm_vec3_norm(to_light))
                continue;
            vec4 screen_clip, h = {sample->position[0], sample->position[1], sample->position[2], 1};
            glm_mat4_mulv((vec4 *)f->view->view_projection, h, screen_clip);
            float b[2][2];
            for (int k = 0; k < 2; k++)
                psm_derivative(f->view->view_projection, screen_clip, sample->tangent[k], screen_half, b[k]);
            sample->pixels = fabsf(b[0][0] * b[1][1] - b[0][1] * b[1][0]);
            n++;
        }
    }
    return n;
}

/* Mean size in pixels of a map texel at the samples; INFINITY if one lies
 * outside the map (or none can be measured). On each sample's face, a
 * texel's footprint is the ratio of two areas: a pixel's over a texel's. */
static float psm_texel_pixels(const shadowmap_light *m, const scene_light *l, const psm_sample *samples, int n) {
    float map_half[2] = {0.5f * (float)m->size, 0.5f * (float)m->size};
    double sum = 0;
    int measured = 0;
    for (int i = 0; i < n; i++) {
        const psm_sample *sample = &samples[i];
        const vec4 *map = psm_map_matrix(m, l->position, sample->position);
        vec4 map_clip, h = {sample->position[0], sample->position[1], sample->position[2], 1};
        glm_mat4_mulv((vec4 *)map, h, map_clip);
        if (!(map_clip[3] > 0) || fabsf(map_clip[0]) > map_clip[3] * 1.001f ||
            fabsf(map_clip[1]) > map_clip[3] * 1.001f)
            return INFINITY;
        float a[2][2];
        for (int k = 0; k < 2; k++)
            psm_derivative(map, map_clip, sample->tangent[k], map_half, a[k]);
        float texels = fabsf(a[0][0] * a[1][1] - a[0][1] * a[1][0]);
        if (texels > 0 && isfinite(sample->pixels / texels)) {
            sum += sqrt((double)sample->pixels / texels);
            measured++;
        }
    }
    return measured > 0 ? (float)(sum / measured) : INFINITY;
}

/* ---- the fit ---- */

static bool psm_fit(const technique_frame *f, int light, shadowmap_light *m, const float (*receivers)[3],
                    int receiver_count) {
    const scene_light *l = &f->gpu->scene->lights[light];
    psm_choice *choice = &psm.choice[light];
    choice->warp = psm_warps[PSM_WARP_UNIFORM];
    choice->has_warp_space = false;
    choice->texel_pixels[0] = choice->texel_pixels[1] = INFINITY;
    snprintf(choice->why, sizeof choice->why, "as asked");
    if (!shadowmap_fit_uniform(f, light, m, receivers, receiver_count))
        return false;
    if (psm.warp == PSM_WARP_UNIFORM)
        return true;
    static float points[PSM_MAX_POINTS][3];
    memcpy(points, receivers, sizeof *points * (size_t)receiver_count);
    int n = psm_relevant_casters(f, l, points, receiver_count, psm.casters[light]);
    if (n < 0) {
        snprintf(choice->why, sizeof choice->why, "more casters than the warp's fit holds");
        return true;
    }
    psm_view v;
    shadowmap_light warped = *m;
    warped.cube = false;
    warped.casters = psm.casters[light];
    warped.texel_kind = SHADOWMAP_TEXEL_PROJECTIVE;
    bool ok = psm_view_of(f, receivers, receiver_count, &v) &&
              (psm.warp == PSM_WARP_PSM
                   ? psm_warp_psm(f, l, &v, (const float(*)[3])points, n, &warped, choice)
                   : psm_warp_lispsm(l, &v, (const float(*)[3])points, receiver_count, n, &warped, choice));
    if (ok && !psm_finite(warped.view_projection[0])) {
        snprintf(choice->why, sizeof choice->why, "the warp is not finite here");
        ok = false;
    }
    if (!ok)
        return true;
    static psm_sample samples[PSM_SAMPLES_X * PSM_SAMPLES_Y];
    int sample_count = psm_samples(f, l, samples);
    choice->texel_pixels[0] = psm_texel_pixels(&warped, l, samples, sample_count);
    choice->texel_pixels[1] = psm_texel_pixels(m, l, samples, sample_count);
    if (!(choice->texel_pixels[0] < PSM_WARP_GAIN * choice->texel_pixels[1])) {
        snprintf(choice->why + strlen(choice->why), sizeof choice->why - strlen(choice->why),
                 "; the warp does not pay here");
        return true;
    }
    choice->warp = psm_warps[psm.warp];
    *m = warped;
    return true;
}

/* ---- the post-perspective view ---- */

/* Light 0's warp space in the bottom-left half: the scene through the
 * warp (clipped to the clip cube of the warp space, where it is defined),
 * the cube's edges and the map's frustum, seen from above one side. */
static void psm_draw_post_perspective(const technique_frame *f, const int viewport[4]) {
    const psm_choice *choice = &psm.choice[0];
    if (!choice->has_warp_space)
        return;
    int height = viewport[3] / 2, width = height;
    glViewport(viewport[0] + 8, viewport[1] + 8, width, height);
    glEnable(GL_SCISSOR_TEST);
    glScissor(viewport[0] + 8, viewport[1] + 8, width, height);
    glClearColor(0.08f, 0.08f, 0.1f, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    glDepthMask(GL_TRUE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_BLEND);
    mat4 observer, projection, view;
    glm_perspective(glm_rad(40), 1, 0.5f, 20, projection);
    glm_lookat((vec3){3.2f, 2.4f, -4.2f}, (vec3){0, 0, 0}, (vec3){0, 1, 0}, view);
    glm_mat4_mul(projection, view, observer);
    glUseProgram(psm.warped.id);
    glUniformMatrix4fv(psm.warped_space, 1, GL_FALSE, (const float *)choice->warp_space);
    glUniformMatrix4fv(psm.warped.view_projection, 1, GL_FALSE, (const float *)observer);
    for (int k = 0; k < 6; k++)
        glEnable(GL_CLIP_DISTANCE0 + (unsigned)k);
    for (int i = 0; i < f->gpu->scene->object_count; i++)
        render_draw_object(f->gpu, &psm.warped, i);
    for (int k = 0; k < 6; k++)
        glDisable(GL_CLIP_DISTANCE0 + (unsigned)k);
    mat4 identity = GLM_MAT4_IDENTITY_INIT, map_in_space, space_inverse;
    shadowmap_draw_frustum(&psm.maps, identity, observer); /* the clip cube of the warp space */
    glm_mat4_inv((vec4 *)choice->warp_space, space_inverse);
    glm_mat4_mul(psm.maps.lights[0].view_projection[0], space_inverse, map_in_space);
    shadowmap_draw_frustum(&psm.maps, map_in_space, observer);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
}

/* ---- the technique ---- */

static bool psm_init(const render_scene *gpu) {
    static const char *const warped_files[] = {"post_perspective.vert", "post_perspective.frag"};
    for (int l = 0; l < SCENE_MAX_LIGHTS; l++) {
        psm.casters[l] = calloc((size_t)gpu->scene->object_count + 1, sizeof(bool));
        if (!psm.casters[l]) {
            fprintf(stderr, "psm: out of memory\n");
            return false;
        }
    }
    if (!shadowmap_maps_init(&psm.maps) || !render_program_load(&psm.warped, warped_files, 2, NULL))
        return false;
    psm.warped_space = glGetUniformLocation(psm.warped.id, "u_warp_space");
    return true;
}

static void psm_destroy(void) {
    shadowmap_maps_destroy(&psm.maps);
    render_program_destroy(&psm.warped);
    for (int l = 0; l < SCENE_MAX_LIGHTS; l++) {
        free(psm.casters[l]);
        psm.casters[l] = NULL;
    }
}

static void psm_render(const technique_frame *f) {
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    shadowmap_maps_render(&psm.maps, &psm.settings, f, psm_fit);
    if (psm.settings.overlay == PSM_OVERLAY_POST_PERSPECTIVE)
        psm_draw_post_perspective(f, viewport);
}

static void psm_describe(char *out, size_t size) {
    const psm_choice *c = &psm.choice[0];
    const shadowmap_light *m = &psm.maps.lights[0];
    int n = snprintf(out, size, "light 0: %s %s map %dx%d (%s)", c->warp, m->cube ? "cube" : "2D", m->size, m->size,
                     c->why);
    if (n > 0 && (size_t)n < size && isfinite(c->texel_pixels[1]))
        snprintf(out + n, size - (size_t)n, "; texel on screen %.3g px, uniform's %.3g px", c->texel_pixels[0],
                 c->texel_pixels[1]);
}

/* The sweep: warp x map size. */
static const char *const psm_bench_configs[] = {
    "",
    "--map-size 1024",
    "--warp lispsm",
    "--warp lispsm --map-size 1024",
    "--warp uniform",
    "--warp uniform --map-size 1024",
};

const technique psm_technique = {
    .name = "psm",
    .title = "perspective shadow maps (Stamminger & Drettakis 2002), LiSPSM (Wimmer et al. 2004), uniform",
    .params = psm_params,
    .param_count = (int)(sizeof psm_params / sizeof *psm_params),
    .bench_configs = psm_bench_configs,
    .bench_config_count = (int)(sizeof psm_bench_configs / sizeof *psm_bench_configs),
    .init = psm_init,
    .render = psm_render,
    .destroy = psm_destroy,
    .describe = psm_describe,
    .gallery_config = "--overlay post-perspective",
};
