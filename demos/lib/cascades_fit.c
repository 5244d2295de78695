/* cascades_fit: the geometry of demos/cascades.c's fit (see
 * cascades_fit.h): the split schemes, the seen depth range, and each
 * cascade's box in the light's view with its stabilisation. No GL. */
#include <math.h>

#include "cascades_fit.h"
#include "frustum.h"
#include "technique.h"

/* The sine between the view and the light below which the view, seen from
 * the light, has no direction to align a box with. */
#define CASCADES_MIN_VIEW_ACROSS_LIGHT 1e-3f
/* Stabilised by steps (--stabilize steps, the default): the boxes of
 * cascades_slice_box in a light space fixed in the world but for its
 * heading, their corners snapped to whole texels, and what may change
 * only in steps: a box's side is a power of 2^(1 / SIDE_STEPS) (at most
 * that factor more than it needs), its heading (the view direction as the light
 * sees it, which the boxes are aligned with) a multiple of 1 /
 * HEADING_STEPS of a turn (at most 11.25 degrees off the view's). Walking,
 * nothing changes but where a side crosses a step; turning, the grid turns
 * once a sixteenth of a turn. Between steps a still receiver's shadow
 * stays put, and a box is at most a step larger than the free one, so
 * tighter than the sphere's. Finer steps fit tighter and step more often. */
#define CASCADES_SIDE_STEPS 8.0f
#define CASCADES_HEADING_STEPS 16.0f

/* ---- the splits ---- */

void cascades_splits(int count, float lambda, float near_plane, float far_plane, float *splits) {
    for (int i = 0; i <= count; i++) {
        float t = (float)i / (float)count;
        float log_split = near_plane * powf(far_plane / near_plane, t);
        float uniform_split = near_plane + (far_plane - near_plane) * t;
        splits[i] = lambda * log_split + (1 - lambda) * uniform_split;
    }
    /* The ends exactly, whatever the rounding of powf. */
    splits[0] = near_plane;
    splits[count] = far_plane;
}

bool cascades_seen_depths(const camera_view *view, const float (*points)[3], int n, float near_plane, float far_plane,
                          float *lo, float *hi) {
    *lo = INFINITY;
    *hi = -INFINITY;
    for (int i = 0; i < n; i++) {
        vec4 p = {points[i][0], points[i][1], points[i][2], 1}, v;
        glm_mat4_mulv((vec4 *)view->view, p, v);
        *lo = fminf(*lo, -v[2]);
        *hi = fmaxf(*hi, -v[2]);
    }
    *lo = fmaxf(*lo, near_plane);
    *hi = fminf(*hi, far_plane);
    return *lo < *hi;
}

float cascades_power_step(float x, float steps, float (*round)(float)) {
    return exp2f(round(log2f(x) * steps) / steps);
}

/* How far from the eye any receiver of s can be: the farthest corner of
 * their boxes, rounded up to a power of two. The splits end there when the
 * camera's far plane lies beyond (else a far plane far past the scene puts
 * the first practical split beyond it and every shadow in one texel: the
 * stress suite's near_far_1e6_far_directional). The same
 * whichever way the camera looks, and, rounded, the same while it moves a
 * little: the stabilised boxes keep their size. */
float cascades_receivers_reach(const scene *s, const float eye[3]) {
    float reach = 0;
    for (int i = 0; i < s->object_count; i++) {
        vec3 lo, hi, corners[8];
        if (!s->objects[i].receives)
            continue;
        scene_object_world_bounds(&s->objects[i], lo, hi);
        frustum_box_corners(lo, hi, corners);
        for (int c = 0; c < 8; c++)
            reach = fmaxf(reach, glm_vec3_distance(corners[c], (float *)eye));
    }
    return cascades_power_step(reach, 1, ceilf);
}

/* ---- a cascade's box ---- */

/* The camera's axes (right, up, forward) from its view matrix's rows, and
 * the tangents of its half-angles from its projection. */
static void cascades_camera_axes(const camera_view *view, vec3 right, vec3 up, vec3 forward, float *tan_x,
                                 float *tan_y) {
    for (int k = 0; k < 3; k++) {
        right[k] = view->view[k][0];
        up[k] = view->view[k][1];
        forward[k] = -view->view[k][2];
    }
    *tan_x = 1 / view->projection[0][0];
    *tan_y = 1 / view->projection[1][1];
}

/* The slice's bounding sphere in light space: its centre on the view
 * axis where the near and far corners are equally far (clamped to the
 * far face's centre), from the depths and the half-angles alone.
 * --stabilize sphere (Valient 2008) fits a box to it, snapped in a light
 * space fixed in the world: its size depends only on the slice's depths
 * and the projection, so no step at all, for texels larger by the air the
 * sphere holds, unaligned with the view. sdsm's slices follow what is
 * seen, so their spheres change size where the seen range steps (use it
 * with practical splits). A grazing light gets the steps' boxes instead
 * (cascades_grazing). */
static float cascades_slice_sphere(const camera_view *view, const mat4 light_view, float a, float b, vec3 center) {
    vec3 right, up, forward, world;
    float tan_x, tan_y;
    cascades_camera_axes(view, right, up, forward, &tan_x, &tan_y);
    float spread = tan_x * tan_x + tan_y * tan_y; /* corner distance from the axis, squared, per unit depth */
    float c = fminf(0.5f * (a + b) * (1 + spread), b);
    glm_vec3_copy((float *)view->eye, world);
    glm_vec3_muladds(forward, c, world);
    glm_mat4_mulv3((vec4 *)light_view, world, 1, center);
    return sqrtf((b - c) * (b - c) + b * b * spread);
}

/* The slice's frustum: its eight corners, numbered as frustum_corners
 * numbers them, and its view-projection (near a, far b). */
static void cascades_slice_frustum(const camera_view *view, float a, float b, vec3 corners[8], mat4 view_projection) {
    vec3 right, up, forward;
    float tan_x, tan_y;
    cascades_camera_axes(view, right, up, forward, &tan_x, &tan_y);
    for (int c = 0; c < 8; c++) {
        float depth = c & 4 ? b : a;
        glm_vec3_copy((float *)view->eye, corners[c]);
        glm_vec3_muladds(forward, depth, corners[c]);
        glm_vec3_muladds(right, (c & 1 ? 1 : -1) * tan_x * depth, corners[c]);
        glm_vec3_muladds(up, (c & 2 ? 1 : -1) * tan_y * depth, corners[c]);
    }
    mat4 projection;
    glm_perspective(2 * atanf(tan_y), tan_x / tan_y, a, b, projection);
    glm_mat4_mul(projection, (vec4 *)view->view, view_projection);
}

/* The light-space bounds of the slice's eight corners. */
static void cascades_slice_bounds(const camera_view *view, const mat4 light_view, float a, float b, vec3 lo,
                                  vec3 hi) {
    vec3 corners[8];
    mat4 view_projection;
    cascades_slice_frustum(view, a, b, corners, view_projection);
    frustum_view_bounds(light_view, (const float(*)[3])corners, 8, lo, hi);
}

/* lo..hi (empty, lo > hi, when called) grown to the light-space bounds of
 * the parts of s's receivers' boxes inside the slice (frustum_box_part):
 * where the slice's receivers are, tighter than the slice (a slice is
 * mostly air above the ground); still empty where none is in it. */
void cascades_slice_receivers(const scene *s, const camera_view *view, const mat4 light_view, float a, float b,
                              vec3 lo, vec3 hi) {
    vec3 corners[8];
    mat4 view_projection;
    float part[SKIPS_MAX_PART_POINTS][3];
    cascades_slice_frustum(view, a, b, corners, view_projection);
    for (int i = 0; i < s->object_count; i++) {
        vec3 box_lo, box_hi, part_lo, part_hi;
        if (!s->objects[i].receives)
            continue;
        scene_object_world_bounds(&s->objects[i], box_lo, box_hi);
        int n = frustum_box_part(view_projection, (const vec3 *)corners, box_lo, box_hi, part, SKIPS_MAX_PART_POINTS);
        if (n == 0)
            continue;
        frustum_view_bounds(light_view, (const float(*)[3])part, n, part_lo, part_hi);
        glm_vec3_minv(lo, part_lo, lo);
        glm_vec3_maxv(hi, part_hi, hi);
    }
}

/* The box, in the light's view (cascades_fit.h): around its slice of the view
 * frustum (a: grown at its near end by the band where the slice before
 * blends into it), clipped to the parts of the receivers' boxes inside the
 * slice where they are tighter (a slice is mostly air above the ground),
 * aligned with the view direction as the light sees it
 * (cascades_light_view: a slice is long along it; the sphere's box is
 * not). The caller deepens it towards the light to every caster that
 * overlaps it (map_nearest_caster: casters outside the view still
 * cast); the library's caster culling then draws into each layer only the
 * casters a read of that layer can meet. Biases are the library's, in
 * texels of world size: each layer's texel is known to the shader (its
 * box's scale), and the layer read sizes them. */
void cascades_slice_box(const camera_view *view, const mat4 light_view, float a, float b, int size, float margin,
                        cascades_stabilize stabilize, const float receivers_lo[3], const float receivers_hi[3],
                        float lo[3], float hi[3]) {
    /* The inner size - 2 margin texels hold the slice. */
    float grow = (float)size / ((float)size - 2 * margin);
    if (stabilize == CASCADES_STABILIZE_SPHERE) {
        vec3 center;
        float radius = cascades_slice_sphere(view, light_view, a, b, center) * grow;
        float texel = 2 * radius / (float)size;
        for (int k = 0; k < 3; k++) {
            /* Across the light, the corner on the texel grid; along it the
             * sphere's depth (which no texel grid follows). */
            float corner = k < 2 ? floorf((center[k] - radius) / texel) * texel : center[k] - radius;
            lo[k] = corner;
            hi[k] = corner + 2 * radius;
        }
        return;
    }
    cascades_slice_bounds(view, light_view, a, b, lo, hi);
    for (int k = 0; k < 3; k++) {
        /* The receivers' bounds where they are tighter, unless the slice
         * holds none of them (then the slice's own). */
        float clipped_lo = fmaxf(lo[k], receivers_lo[k]), clipped_hi = fminf(hi[k], receivers_hi[k]);
        if (clipped_lo < clipped_hi) {
            lo[k] = clipped_lo;
            hi[k] = clipped_hi;
        }
        if (k == 2)
            continue;
        float middle = 0.5f * (lo[k] + hi[k]), side = (hi[k] - lo[k]) * grow;
        if (stabilize == CASCADES_STABILIZE_STEPS) {
            /* Up to the next step, then the corner down to whole texels:
             * it moves by less than one, which the margin holds. */
            side = cascades_power_step(side, CASCADES_SIDE_STEPS, ceilf);
            float texel = side / (float)size;
            lo[k] = floorf((middle - 0.5f * side) / texel) * texel;
        } else {
            lo[k] = middle - 0.5f * side;
        }
        hi[k] = lo[k] + side;
    }
}

void cascades_light_view(const float direction[3], const camera_view *view, cascades_stabilize stabilize,
                         mat4 light_view) {
    /* A light space fixed in the world (its origin at the world's), so
     * that snapped boxes keep one texel grid from frame to frame. */
    const vec3 origin = GLM_VEC3_ZERO_INIT;
    frustum_look_along(origin, direction, light_view);
    if (stabilize == CASCADES_STABILIZE_SPHERE)
        return;
    vec3 right, up, forward, seen;
    float tan_x, tan_y;
    cascades_camera_axes(view, right, up, forward, &tan_x, &tan_y);
    glm_mat4_mulv3(light_view, forward, 0, seen);
    if (hypotf(seen[0], seen[1]) <= CASCADES_MIN_VIEW_ACROSS_LIGHT)
        return;
    /* Turned about the light's axis so that the heading is +y. */
    float heading = atan2f(seen[1], seen[0]);
    if (stabilize == CASCADES_STABILIZE_STEPS) {
        float step = 2 * GLM_PIf / CASCADES_HEADING_STEPS;
        heading = roundf(heading / step) * step;
    }
    mat4 turn;
    glm_rotate_make(turn, GLM_PI_2f - heading, (vec3){0, 0, 1});
    glm_mat4_mul(turn, light_view, light_view);
}
