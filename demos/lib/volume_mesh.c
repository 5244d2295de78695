#include "volume_mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "frustum.h"

/* Vertices the first growth makes room for: a small caster's volume (a
 * few hundred silhouette edges) fits without growing again; growth then
 * doubles, so a large one costs few reallocations. */
#define VOLUME_MESH_FIRST_CAPACITY 4096

/* frustum_corners numbers the near corners by bits (x bit 0, y bit 1):
 * these go round the rectangle instead, as the hull's faces need. */
static const int volume_mesh_rectangle_corners[4] = {0, 1, 3, 2};

/* ---- building a volume ---- */

static void volume_mesh_emit(volume_mesh *v, const float p[3], float w) {
    if (v->count == v->capacity) {
        size_t capacity = v->capacity ? v->capacity * 2 : VOLUME_MESH_FIRST_CAPACITY;
        float(*grown)[4] = realloc(v->vertices, capacity * sizeof *grown);
        if (!grown) {
            v->out_of_memory = true;
            return;
        }
        v->vertices = grown;
        v->capacity = capacity;
    }
    float *out = v->vertices[v->count++];
    out[0] = p[0], out[1] = p[1], out[2] = p[2], out[3] = w;
}

static void volume_mesh_emit_triangle(volume_mesh *v, const float *a, float wa, const float *b, float wb,
                                      const float *c, float wc) {
    volume_mesh_emit(v, a, wa);
    volume_mesh_emit(v, b, wb);
    volume_mesh_emit(v, c, wc);
}

/* p swept away from the light: to infinity (a direction, w = 0), or with
 * a trim to where it stops (see the header). */
static void volume_mesh_extrude(const float p[3], const float light[4], const volume_mesh_trim *trim, float out[4]) {
    for (int k = 0; k < 3; k++)
        out[k] = p[k] * light[3] - light[k];
    out[3] = 0;
    if (!trim || !trim->on)
        return;
    /* out is the way p travels: p + out * s, s from the distance. */
    float along = glm_vec3_dot(out, out), s;
    if (light[3] != 0)
        s = trim->distance / sqrtf(along) - 1; /* a point light's w is 1: out = p - light */
    else
        s = (trim->distance - glm_vec3_dot((float *)p, out)) / along;
    for (int k = 0; k < 3; k++)
        out[k] = p[k] + out[k] * s;
    out[3] = 1;
}

/* Whether an edge's two swept ends are one point: a directional light's,
 * at infinity. */
static bool volume_mesh_ends_meet(const float light[4], const volume_mesh_trim *trim) {
    return light[3] == 0 && !(trim && trim->on);
}

/* The side of edge a -> b swept away, facing out of the prism of a
 * light-facing triangle that runs a -> b (reversed when sign < 0). Ends
 * that meet (volume_mesh_ends_meet) make it one triangle. */
static void volume_mesh_emit_side(volume_mesh *v, const float *a, const float *b, const float light[4],
                                  const volume_mesh_trim *trim, int sign) {
    if (sign < 0) {
        const float *t = a;
        a = b, b = t;
    }
    float a_far[4], b_far[4];
    volume_mesh_extrude(a, light, trim, a_far);
    volume_mesh_extrude(b, light, trim, b_far);
    volume_mesh_emit_triangle(v, b, 1, a, 1, a_far, a_far[3]);
    if (!volume_mesh_ends_meet(light, trim))
        volume_mesh_emit_triangle(v, b, 1, a_far, a_far[3], b_far, b_far[3]);
}

/* +1: faces the light; -1 faces away, or 0 for a closed mesh; 0 edge-on
 * (see the header). */
static int volume_mesh_weight(const mesh *m, uint32_t triangle, const float light[4], bool closed) {
    const uint32_t *corner = &m->indices[triangle * 3];
    int facing = mesh_point_facing(m->vertices[corner[0]].position, m->vertices[corner[1]].position,
                                   m->vertices[corner[2]].position, light);
    return facing < 0 && closed ? 0 : facing;
}

static bool volume_mesh_weigh(volume_mesh *v, const mesh *m, const float light[4], bool closed) {
    uint32_t triangles = m->index_count / 3;
    if (triangles > v->weight_capacity) {
        signed char *grown = realloc(v->weights, triangles);
        if (!grown)
            return false;
        v->weights = grown;
        v->weight_capacity = triangles;
    }
    for (uint32_t t = 0; t < triangles; t++)
        v->weights[t] = (signed char)volume_mesh_weight(m, t, light, closed);
    return true;
}

/* Every triangle of non-zero weight, near (its own place), far (its image
 * swept away: none where the ends meet, a point) or both. */
static void volume_mesh_emit_caps(volume_mesh *v, const mesh *m, const float light[4], const volume_mesh_trim *trim,
                                  bool near, bool far) {
    far = far && !volume_mesh_ends_meet(light, trim);
    for (uint32_t t = 0; t < m->index_count / 3; t++) {
        if (v->weights[t] == 0)
            continue;
        const float *p[3];
        float swept[3][4];
        for (int k = 0; k < 3; k++) {
            /* Prisms of back-facing triangles run the other way round. */
            int corner = v->weights[t] > 0 ? k : 2 - k;
            p[k] = m->vertices[m->indices[t * 3 + corner]].position;
            volume_mesh_extrude(p[k], light, trim, swept[k]);
        }
        if (near)
            volume_mesh_emit_triangle(v, p[0], 1, p[1], 1, p[2], 1);
        if (far)
            volume_mesh_emit_triangle(v, swept[0], swept[0][3], swept[2], swept[2][3], swept[1], swept[1][3]);
    }
}

bool volume_mesh_build(volume_mesh *v, const mesh *m, const mesh_edges *e, const float light[4],
                       const volume_mesh_trim *trim, volume_mesh_parts parts) {
    v->count = 0;
    v->out_of_memory = false;
    if (!volume_mesh_weigh(v, m, light, volume_mesh_closed_rule(m, e, light)))
        return false;
    for (uint32_t i = 0; parts != VOLUME_MESH_CAPS && i < e->edge_count; i++) {
        int multiplicity = 0;
        for (uint32_t k = 0; k < e->edges[i].use_count; k++) {
            const mesh_edge_use *u = &e->uses[e->edges[i].first_use + k];
            multiplicity += u->direction * v->weights[u->corner / 3];
        }
        const float *a = m->vertices[e->edges[i].a].position, *b = m->vertices[e->edges[i].b].position;
        if (parts == VOLUME_MESH_SILHOUETTE_LINES && multiplicity != 0) {
            volume_mesh_emit(v, a, 1);
            volume_mesh_emit(v, b, 1);
            continue;
        }
        if (parts == VOLUME_MESH_SILHOUETTE_EDGES) {
            if (multiplicity != 0) {
                volume_mesh_emit(v, a, (float)multiplicity);
                volume_mesh_emit(v, b, (float)multiplicity);
            }
            continue;
        }
        for (int k = 0; k < abs(multiplicity); k++)
            volume_mesh_emit_side(v, a, b, light, trim, multiplicity);
    }
    /* A trimmed volume's far caps close its sides, for z-pass too. */
    bool trimmed = trim && trim->on;
    if (parts == VOLUME_MESH_CAPS)
        volume_mesh_emit_caps(v, m, light, trim, true, !trimmed);
    else if (parts == VOLUME_MESH_SIDES && trimmed)
        volume_mesh_emit_caps(v, m, light, trim, false, true);
    return !v->out_of_memory;
}

void volume_mesh_free(volume_mesh *v) {
    free(v->vertices);
    free(v->weights);
    *v = (volume_mesh){0};
}

/* ---- trimmed to the light's reach ---- */

void volume_mesh_trim_for(const mat4 model, const float light[4], const mesh *m, const float reach_lo[3],
                          const float reach_hi[3], volume_mesh_trim *out) {
    *out = (volume_mesh_trim){0};
    float world[8][3], reach[8][3], caster[8][3];
    mat4 inverse;
    glm_mat4_inv((vec4 *)model, inverse);
    frustum_box_corners(reach_lo, reach_hi, world);
    frustum_box_corners(m->bounds_min, m->bounds_max, caster);
    for (int c = 0; c < 8; c++)
        glm_mat4_mulv3(inverse, world[c], 1, reach[c]);
    if (light[3] != 0) {
        /* A sphere round the light holding the reach and the caster, grown
         * for the chords of a caster that spans at most 2 asin(spread). */
        vec3 centre;
        glm_vec3_center((float *)m->bounds_min, (float *)m->bounds_max, centre);
        float spread = glm_vec3_distance((float *)m->bounds_min, centre);
        float distance = glm_vec3_distance(centre, (float *)light), reach_distance = 0;
        if (!(spread < VOLUME_MESH_TRIM_MAX_SPREAD * distance))
            return;
        for (int c = 0; c < 8; c++)
            reach_distance = fmaxf(reach_distance, glm_vec3_distance(reach[c], (float *)light));
        float ratio = spread / distance, cos_span = 1 - 2 * ratio * ratio;
        out->distance = fmaxf(reach_distance / sqrtf(cos_span), distance + spread) * (1 + VOLUME_MESH_TRIM_MARGIN);
    } else {
        /* A plane across the travel beyond the reach and the caster. */
        vec3 travel = {-light[0], -light[1], -light[2]};
        float lo = INFINITY, hi = -INFINITY;
        for (int c = 0; c < 16; c++) {
            float along = glm_vec3_dot(travel, c < 8 ? reach[c] : caster[c - 8]);
            lo = fminf(lo, along);
            hi = fmaxf(hi, along);
        }
        if (!(hi > lo))
            return;
        out->distance = hi + (hi - lo) * VOLUME_MESH_TRIM_MARGIN;
    }
    out->on = isfinite(out->distance);
}

/* ---- depth bounds ---- */

/* The window depths of the points into [lo, hi]; false when one is not in
 * front of the eye (its depth bounds nothing). */
static bool volume_mesh_depth_range(const mat4 view_projection, const float (*points)[3], int count, float *lo,
                                    float *hi) {
    *lo = INFINITY, *hi = -INFINITY;
    for (int i = 0; i < count; i++) {
        vec4 p = {points[i][0], points[i][1], points[i][2], 1};
        glm_mat4_mulv((vec4 *)view_projection, p, p);
        if (!(p[3] > 0))
            return false;
        float depth = p[2] / p[3] * 0.5f + 0.5f;
        *lo = fminf(*lo, depth);
        *hi = fmaxf(*hi, depth);
    }
    return true;
}

bool volume_mesh_depth_bounds(const mat4 view_projection, const float (*points)[3], int count,
                              const float reach_lo[3], const float reach_hi[3], float out[2]) {
    if (count <= 0 || !volume_mesh_depth_range(view_projection, points, count, &out[0], &out[1]))
        return false;
    float corners[8][3], lo, hi;
    if (reach_lo) {
        frustum_box_corners(reach_lo, reach_hi, corners);
        if (volume_mesh_depth_range(view_projection, (const float(*)[3])corners, 8, &lo, &hi)) {
            out[0] = fmaxf(out[0], lo);
            out[1] = fminf(out[1], hi);
        }
    }
    out[0] = glm_clamp(out[0] - VOLUME_MESH_DEPTH_BOUNDS_MARGIN, 0, 1);
    out[1] = glm_clamp(out[1] + VOLUME_MESH_DEPTH_BOUNDS_MARGIN, 0, 1);
    return out[0] <= out[1];
}

/* ---- when z-pass is safe ---- */

void volume_mesh_near_rectangle(const mat4 view_projection, vec3 out[4]) {
    vec3 corners[8];
    frustum_corners(view_projection, corners);
    for (int k = 0; k < 4; k++)
        glm_vec3_copy(corners[volume_mesh_rectangle_corners[k]], out[k]);
}

/* Whether the box [lo, hi] lies wholly on the negative side of the plane
 * n.x + d = 0. */
static bool volume_mesh_box_outside(const float n[3], float d, const float lo[3], const float hi[3]) {
    float best = d;
    for (int k = 0; k < 3; k++)
        best += n[k] * (n[k] > 0 ? hi[k] : lo[k]);
    return best < 0;
}

/* The plane through a and b containing the direction `along`, facing the
 * point `inside`; false when it is degenerate. */
static bool volume_mesh_plane(const float a[3], const float b[3], const float along[3], const float inside[3],
                              float n[3], float *d) {
    vec3 ab;
    glm_vec3_sub((float *)b, (float *)a, ab);
    glm_vec3_cross(ab, (float *)along, n);
    if (glm_vec3_norm2(n) == 0)
        return false;
    *d = -glm_vec3_dot(n, (float *)a);
    if (glm_vec3_dot(n, (float *)inside) + *d < 0) {
        glm_vec3_negate(n);
        *d = -*d;
    }
    return true;
}

bool volume_mesh_zpass_safe(const float lo[3], const float hi[3], const float light[4], const vec3 rectangle[4]) {
    float n[3], d;
    vec3 centre = {0, 0, 0}, inside;
    for (int k = 0; k < 4; k++)
        glm_vec3_muladds((float *)rectangle[k], 0.25f, centre);
    /* The faces through the light and an edge of the rectangle. */
    for (int k = 0; k < 4; k++) {
        const float *a = rectangle[k], *b = rectangle[(k + 1) % 4];
        vec3 along;
        if (light[3] != 0)
            glm_vec3_sub((float *)light, (float *)a, along);
        else
            glm_vec3_copy((float *)light, along);
        if (volume_mesh_plane(a, b, along, centre, n, &d) && volume_mesh_box_outside(n, d, lo, hi))
            return true;
    }
    /* The rectangle's own plane: the hull lies on the light's side. */
    vec3 side;
    glm_vec3_sub((float *)rectangle[3], (float *)rectangle[0], side);
    if (light[3] != 0)
        glm_vec3_copy((float *)light, inside);
    else
        glm_vec3_add(centre, (float *)light, inside);
    return volume_mesh_plane(rectangle[0], rectangle[1], side, inside, n, &d) && glm_vec3_dot(n, inside) + d > 0 &&
           volume_mesh_box_outside(n, d, lo, hi);
}

/* ---- when a volume misses the view ---- */

/* The planes that clip with depth clamp on (see the header): weights of
 * the clip coordinates x, y, z, w (rows of the view-projection matrix). */
#define VOLUME_MESH_CLIP_PLANES 5
static const float volume_mesh_clip_planes[VOLUME_MESH_CLIP_PLANES][4] = {
    {1, 0, 0, 1}, {-1, 0, 0, 1}, {0, 1, 0, 1}, {0, -1, 0, 1}, {0, 0, 0, 1}};

/* Whether every point is beyond the plane (a combination of clip
 * coordinates) by more than the float rounding of either side's
 * arithmetic could make up: FRUSTUM_CLIP_TOLERANCE of the magnitudes
 * summed into each clip coordinate. */
static bool volume_mesh_all_beyond(const float plane[4], const float (*clip)[4], const float (*magnitude)[4],
                                   int count) {
    for (int i = 0; i < count; i++) {
        float sum = 0, size = 0;
        for (int row = 0; row < 4; row++) {
            sum += plane[row] * clip[i][row];
            size += fabsf(plane[row]) * magnitude[i][row];
        }
        if (sum >= -FRUSTUM_CLIP_TOLERANCE * size)
            return false;
    }
    return true;
}

bool volume_mesh_misses_view(const float lo[3], const float hi[3], const float light[4], const mat4 view_projection) {
    enum { CORNERS = 8, POINTS = 2 * CORNERS };
    float corners[CORNERS][3], clip[POINTS][4], magnitude[POINTS][4];
    frustum_box_corners(lo, hi, corners);
    for (int i = 0; i < POINTS; i++) {
        float p[4] = {0, 0, 0, i < CORNERS};
        if (i < CORNERS)
            memcpy(p, corners[i], sizeof corners[i]);
        else
            volume_mesh_extrude(corners[i - CORNERS], light, NULL, p);
        for (int row = 0; row < 4; row++) {
            clip[i][row] = magnitude[i][row] = 0;
            for (int k = 0; k < 4; k++) {
                clip[i][row] += view_projection[k][row] * p[k];
                magnitude[i][row] += fabsf(view_projection[k][row] * p[k]);
            }
        }
    }
    for (int p = 0; p < VOLUME_MESH_CLIP_PLANES; p++)
        if (volume_mesh_all_beyond(volume_mesh_clip_planes[p], (const float(*)[4])clip, (const float(*)[4])magnitude,
                                   POINTS))
            return true;
    return false;
}

/* ---- where the light can reach ---- */

bool volume_mesh_receivers_ndc(const scene *s, const mat4 view_projection, float lo[2], float hi[2]) {
    lo[0] = lo[1] = 1;
    hi[0] = hi[1] = -1;
    for (int i = 0; i < s->object_count; i++) {
        float box_lo[3], box_hi[3], corners[8][3];
        if (!s->objects[i].receives)
            continue;
        scene_object_world_bounds(&s->objects[i], box_lo, box_hi);
        frustum_box_corners(box_lo, box_hi, corners);
        for (int c = 0; c < 8; c++) {
            vec4 p = {corners[c][0], corners[c][1], corners[c][2], 1};
            glm_mat4_mulv((vec4 *)view_projection, p, p);
            if (p[3] <= 0)
                return false;
            for (int k = 0; k < 2; k++) {
                lo[k] = fminf(lo[k], p[k] / p[3]);
                hi[k] = fmaxf(hi[k], p[k] / p[3]);
            }
        }
    }
    return true;
}

/* NDC coordinate -> pixels on an axis of `size`, within the viewport. */
static float volume_mesh_to_pixels(float ndc, int size) {
    return (glm_clamp(ndc, -1, 1) * 0.5f + 0.5f) * (float)size;
}

void volume_mesh_receivers_scissor(const scene *s, const mat4 view_projection, int width, int height, int out[4]) {
    float lo[2], hi[2];
    if (!volume_mesh_receivers_ndc(s, view_projection, lo, hi)) {
        out[0] = out[1] = 0, out[2] = width, out[3] = height;
        return;
    }
    int x0 = (int)floorf(volume_mesh_to_pixels(lo[0], width));
    int y0 = (int)floorf(volume_mesh_to_pixels(lo[1], height));
    int x1 = (int)ceilf(volume_mesh_to_pixels(hi[0], width));
    int y1 = (int)ceilf(volume_mesh_to_pixels(hi[1], height));
    out[0] = x0, out[1] = y0, out[2] = x1 > x0 ? x1 - x0 : 0, out[3] = y1 > y0 ? y1 - y0 : 0;
}
