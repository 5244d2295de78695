/* warp: measuring a map where the camera looks, the dp/ds of the papers
 * (see warp.h). */
#include <math.h>
#include <string.h>

#include "frustum.h"
#include "warp.h"

/* A sample counts as inside a map within this fraction of w beyond its
 * edge (rounding at a receiver fitted to the edge exactly). */
#define WARP_MAP_EDGE_TOLERANCE 1e-3f

/* The derivative of m's (x, y) / w at p along t, in units of `half`
 * (half the map's or the viewport's size: clip units to texels or pixels). */
static void warp_derivative(const mat4 m, const vec4 clip, const float t[3], const float half[2], float out[2]) {
    for (int k = 0; k < 2; k++) {
        float row = m[0][k] * t[0] + m[1][k] * t[1] + m[2][k] * t[2];
        float w_row = m[0][3] * t[0] + m[1][3] * t[1] + m[2][3] * t[2];
        out[k] = (row - clip[k] / clip[3] * w_row) / clip[3] * half[k];
    }
}

int warp_cube_face(const float light[3], const float p[3]) {
    vec3 d;
    glm_vec3_sub((float *)p, (float *)light, d);
    int axis = fabsf(d[0]) >= fabsf(d[1]) && fabsf(d[0]) >= fabsf(d[2]) ? 0 : fabsf(d[1]) >= fabsf(d[2]) ? 1 : 2;
    return 2 * axis + (d[axis] < 0);
}

/* The map's matrix for point p: its cube face's, or the 2D map's. */
static const vec4 *warp_map_matrix(const mat4 *layer_view_projection, int layer_count, const float light[3],
                                   const float p[3]) {
    return layer_view_projection[layer_count == 1 ? 0 : warp_cube_face(light, p)];
}

/* Screen bounds this far (NDC) apart still count as meeting: rounding. */
#define WARP_NDC_MARGIN 1e-3f

int warp_receiver_boxes(const scene *s, float (*out)[2][3]) {
    int n = 0;
    for (int i = 0; i < s->object_count; i++) {
        if (!s->objects[i].receives)
            continue;
        scene_object_world_bounds(&s->objects[i], out[n][0], out[n][1]);
        n++;
    }
    return n;
}

int warp_boxes_seen_in(const float (*boxes)[2][3], int n, const camera_view *view, const float ndc[4],
                       float (*out)[2][3]) {
    int kept = 0;
    for (int i = 0; i < n; i++) {
        vec2 lo, hi;
        if (frustum_box_ndc_bounds(view->view_projection, boxes[i][0], boxes[i][1], lo, hi) &&
            (lo[0] > ndc[2] + WARP_NDC_MARGIN || hi[0] < ndc[0] - WARP_NDC_MARGIN ||
             lo[1] > ndc[3] + WARP_NDC_MARGIN || hi[1] < ndc[1] - WARP_NDC_MARGIN))
            continue;
        memcpy(out[kept++], boxes[i], sizeof *out);
    }
    return kept;
}

/* Where the ray eye + t direction (t in 0..1) first enters one of the
 * boxes: t (INFINITY if none) and the axis of the face it enters by. */
static float warp_hit_boxes(const float (*boxes)[2][3], int n, const float eye[3], const vec3 direction,
                            int *hit_axis) {
    float best = INFINITY;
    *hit_axis = 0;
    for (int i = 0; i < n; i++) {
        const float *lo = boxes[i][0], *hi = boxes[i][1];
        float t0 = 0, t1 = best;
        int axis = -1;
        for (int k = 0; k < 3; k++) {
            float a = (lo[k] - eye[k]) / direction[k], b = (hi[k] - eye[k]) / direction[k];
            if (a > b) {
                float swap = a;
                a = b, b = swap;
            }
            if (a > t0)
                t0 = a, axis = k;
            t1 = fminf(t1, b);
        }
        if (axis >= 0 && t0 <= t1 && t0 < best)
            best = t0, *hit_axis = axis;
    }
    return best;
}

/* The point of the far plane at NDC (x, y): the far corners mixed (the far
 * plane is flat, so the mix is exact), not the inverse view-projection's,
 * which loses the far plane past far / near 1e7 (camera.h). */
static void warp_far_point(const camera_view *view, float x, float y, vec3 out) {
    vec3 bottom, top;
    float u = 0.5f * (x + 1), v = 0.5f * (y + 1);
    glm_vec3_lerp((float *)view->corners[4], (float *)view->corners[5], u, bottom);
    glm_vec3_lerp((float *)view->corners[6], (float *)view->corners[7], u, top);
    glm_vec3_lerp(bottom, top, v, out);
}

int warp_samples(const float (*boxes)[2][3], int box_count, const camera_view *view, int width, int height,
                 const float ndc[4], warp_sample *out) {
    float screen_half[2] = {0.5f * (float)width, 0.5f * (float)height};
    int n = 0;
    int columns = ndc ? WARP_RECT_SAMPLES_X : WARP_SAMPLES_X, rows = ndc ? WARP_RECT_SAMPLES_Y : WARP_SAMPLES_Y;
    for (int sy = 0; sy < rows; sy++) {
        for (int sx = 0; sx < columns; sx++) {
            vec3 direction, far_point;
            /* The cell's centre in -1..1, then in ndc. */
            float x = (2.0f * (float)sx + 1) / (float)columns - 1, y = (2.0f * (float)sy + 1) / (float)rows - 1;
            if (ndc) {
                x = 0.5f * (ndc[0] + ndc[2]) + 0.5f * (ndc[2] - ndc[0]) * x;
                y = 0.5f * (ndc[1] + ndc[3]) + 0.5f * (ndc[3] - ndc[1]) * y;
            }
            warp_far_point(view, x, y, far_point);
            glm_vec3_sub(far_point, (float *)view->eye, direction);
            int best_axis;
            float best = warp_hit_boxes(boxes, box_count, view->eye, direction, &best_axis);
            if (!isfinite(best) || best > 1)
                continue;
            warp_sample *sample = &out[n];
            glm_vec3_scale(direction, best, sample->position);
            glm_vec3_add(sample->position, (float *)view->eye, sample->position);
            glm_vec3_zero(sample->tangent[0]);
            glm_vec3_zero(sample->tangent[1]);
            glm_vec3_zero(sample->normal);
            sample->tangent[0][(best_axis + 1) % 3] = 1;
            sample->tangent[1][(best_axis + 2) % 3] = 1;
            sample->normal[best_axis] = direction[best_axis] > 0 ? -1.0f : 1.0f;
            vec4 screen_clip, h = {sample->position[0], sample->position[1], sample->position[2], 1};
            glm_mat4_mulv((vec4 *)view->view_projection, h, screen_clip);
            float b[2][2];
            for (int k = 0; k < 2; k++)
                warp_derivative(view->view_projection, screen_clip, sample->tangent[k], screen_half, b[k]);
            sample->pixels = fabsf(b[0][0] * b[1][1] - b[0][1] * b[1][0]);
            n++;
        }
    }
    return n;
}

int warp_samples_lit(const warp_sample *samples, int n, const scene_light *l, warp_sample *out, int *grazing) {
    int kept = 0, edge_on = 0;
    for (int i = 0; i < n; i++) {
        const warp_sample *sample = &samples[i];
        vec3 to_light;
        if (l->type == SCENE_LIGHT_DIRECTIONAL)
            glm_vec3_negate_to((float *)l->direction, to_light);
        else
            glm_vec3_sub((float *)l->position, (float *)sample->position, to_light);
        if (l->type == SCENE_LIGHT_SPOT && -glm_vec3_dot(to_light, (float *)l->direction) <
                                               cosf(glm_rad(l->outer_angle_deg)) * glm_vec3_norm(to_light))
            continue;
        if (l->type != SCENE_LIGHT_DIRECTIONAL && l->range > 0 && glm_vec3_norm(to_light) >= l->range)
            continue;
        if (!(fabsf(glm_vec3_dot((float *)sample->normal, to_light)) > WARP_GRAZING_SINE * glm_vec3_norm(to_light)))
            edge_on++;
        else
            out[kept++] = *sample;
    }
    if (grazing)
        *grazing = edge_on;
    return kept;
}

float warp_sample_texel_pixels(const mat4 *layer_view_projection, int layer_count, int size,
                               const float light_position[3], const warp_sample *sample) {
    float map_half[2] = {0.5f * (float)size, 0.5f * (float)size};
    const vec4 *map = warp_map_matrix(layer_view_projection, layer_count, light_position, sample->position);
    vec4 map_clip, h = {sample->position[0], sample->position[1], sample->position[2], 1};
    glm_mat4_mulv((vec4 *)map, h, map_clip);
    float edge = map_clip[3] * (1 + WARP_MAP_EDGE_TOLERANCE);
    if (!(map_clip[3] > 0) || fabsf(map_clip[0]) > edge || fabsf(map_clip[1]) > edge)
        return INFINITY;
    float a[2][2];
    for (int k = 0; k < 2; k++)
        warp_derivative(map, map_clip, sample->tangent[k], map_half, a[k]);
    float texels = fabsf(a[0][0] * a[1][1] - a[0][1] * a[1][0]);
    float ratio = sample->pixels / texels;
    return texels > 0 && isfinite(ratio) ? sqrtf(ratio) : NAN;
}

float warp_texel_pixels(const mat4 *layer_view_projection, int layer_count, int size, const float light_position[3],
                        const warp_sample *samples, int n) {
    double sum = 0;
    int measured = 0;
    for (int i = 0; i < n; i++) {
        float texel = warp_sample_texel_pixels(layer_view_projection, layer_count, size, light_position, &samples[i]);
        if (isinf(texel))
            return INFINITY;
        if (!isnan(texel)) {
            sum += texel;
            measured++;
        }
    }
    return measured > 0 ? (float)(sum / measured) : INFINITY;
}
