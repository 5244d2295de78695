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

bool volume_mesh_edges_build(const mesh *m, mesh_edges *e) {
    mesh_topology t;
    if (!mesh_weld(m, &t))
        return false;
    bool ok = mesh_edges_build(m, &t, e);
    mesh_topology_free(&t);
    return ok;
}

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

/* p swept away from the light to infinity: a direction. */
static void volume_mesh_extrude(const float p[3], const float light[4], float out[3]) {
    for (int k = 0; k < 3; k++)
        out[k] = p[k] * light[3] - light[k];
}

/* The side of edge a -> b swept to infinity, facing out of the prism of a
 * light-facing triangle that runs a -> b (reversed when sign < 0). A
 * directional light sends a and b to one point: one triangle. */
static void volume_mesh_emit_side(volume_mesh *v, const float *a, const float *b, const float light[4], int sign) {
    float a_far[3], b_far[3];
    volume_mesh_extrude(a, light, a_far);
    volume_mesh_extrude(b, light, b_far);
    if (sign < 0) {
        const float *t = a;
        a = b, b = t;
        float swap[3] = {a_far[0], a_far[1], a_far[2]};
        memcpy(a_far, b_far, sizeof a_far);
        memcpy(b_far, swap, sizeof b_far);
    }
    volume_mesh_emit_triangle(v, b, 1, a, 1, a_far, 0);
    if (light[3] != 0)
        volume_mesh_emit_triangle(v, b, 1, a_far, 0, b_far, 0);
}

/* +1: faces the light; otherwise -1, or 0 for a closed mesh (see the
 * header). */
static int volume_mesh_weight(const mesh *m, uint32_t triangle, const float light[4], bool closed) {
    const float *p0 = m->vertices[m->indices[triangle * 3]].position;
    const float *p1 = m->vertices[m->indices[triangle * 3 + 1]].position;
    const float *p2 = m->vertices[m->indices[triangle * 3 + 2]].position;
    vec3 e1, e2, n, to_light;
    glm_vec3_sub((float *)p1, (float *)p0, e1);
    glm_vec3_sub((float *)p2, (float *)p0, e2);
    glm_vec3_cross(e1, e2, n);
    for (int k = 0; k < 3; k++)
        to_light[k] = light[k] - light[3] * p0[k];
    return glm_vec3_dot(n, to_light) > 0 ? 1 : closed ? 0 : -1;
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

/* Every triangle of non-zero weight and its image at infinity. */
static void volume_mesh_emit_caps(volume_mesh *v, const mesh *m, const float light[4]) {
    for (uint32_t t = 0; t < m->index_count / 3; t++) {
        if (v->weights[t] == 0)
            continue;
        const float *p[3];
        float far[3][3];
        for (int k = 0; k < 3; k++) {
            /* Prisms of back-facing triangles run the other way round. */
            int corner = v->weights[t] > 0 ? k : 2 - k;
            p[k] = m->vertices[m->indices[t * 3 + corner]].position;
            volume_mesh_extrude(p[k], light, far[k]);
        }
        volume_mesh_emit_triangle(v, p[0], 1, p[1], 1, p[2], 1);
        if (light[3] != 0) /* a directional light's far cap is a point */
            volume_mesh_emit_triangle(v, far[0], 0, far[2], 0, far[1], 0);
    }
}

bool volume_mesh_build(volume_mesh *v, const mesh *m, const mesh_edges *e, const float light[4],
                       volume_mesh_parts parts) {
    v->count = 0;
    v->out_of_memory = false;
    if (!volume_mesh_weigh(v, m, light, e->closed))
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
        for (int k = 0; k < abs(multiplicity); k++)
            volume_mesh_emit_side(v, a, b, light, multiplicity);
    }
    if (parts == VOLUME_MESH_CAPS)
        volume_mesh_emit_caps(v, m, light);
    return !v->out_of_memory;
}

void volume_mesh_free(volume_mesh *v) {
    free(v->vertices);
    free(v->weights);
    *v = (volume_mesh){0};
}

void volume_mesh_object_light(const mat4 model, const float light[4], float out[4]) {
    mat4 inverse;
    glm_mat4_inv((vec4 *)model, inverse);
    glm_mat4_mulv(inverse, (float *)light, out);
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

bool volume_mesh_misses_view(const float lo[3], const float hi[3], const float light[4],
                             const mat4 view_projection) {
    enum { CORNERS = 8, POINTS = 2 * CORNERS };
    float corners[CORNERS][3], clip[POINTS][4], magnitude[POINTS][4];
    frustum_box_corners(lo, hi, corners);
    for (int i = 0; i < POINTS; i++) {
        float p[4] = {0, 0, 0, i < CORNERS};
        if (i < CORNERS)
            memcpy(p, corners[i], sizeof corners[i]);
        else
            volume_mesh_extrude(corners[i - CORNERS], light, p);
        for (int row = 0; row < 4; row++) {
            clip[i][row] = magnitude[i][row] = 0;
            for (int k = 0; k < 4; k++) {
                clip[i][row] += view_projection[k][row] * p[k];
                magnitude[i][row] += fabsf(view_projection[k][row] * p[k]);
            }
        }
    }
    for (int p = 0; p < VOLUME_MESH_CLIP_PLANES; p++)
        if (volume_mesh_all_beyond(volume_mesh_clip_planes[p], (const float(*)[4])clip,
                                   (const float(*)[4])magnitude, POINTS))
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
