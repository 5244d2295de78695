/* volume_rule: the part of demos/lib/volume_mesh.h that says which rule
 * weighs a mesh's triangles for a light (see "Which meshes" and "The
 * closed rule" there): the edge table and when it counts as closed, the
 * facing test with its edge-on band, and whether a light is inside a
 * closed mesh. No GL. */
#include "volume_mesh.h"

#include <math.h>
#include <string.h>

/* ---- the edge table ---- */

/* The corner after `corner` in its triangle: where its edge ends. */
static uint32_t volume_mesh_next_corner(uint32_t corner) { return corner / 3 * 3 + (corner + 1) % 3; }

static bool volume_mesh_same_position(const mesh *m, uint32_t corner_a, uint32_t corner_b) {
    return memcmp(m->vertices[m->indices[corner_a]].position, m->vertices[m->indices[corner_b]].position,
                  sizeof m->vertices[0].position) == 0;
}

bool volume_mesh_uses_meet(const mesh *m, const mesh_edge_use *u, const mesh_edge_use *v) {
    uint32_t u_end = volume_mesh_next_corner(u->corner), v_end = volume_mesh_next_corner(v->corner);
    if (u->direction == v->direction)
        return volume_mesh_same_position(m, u->corner, v->corner) && volume_mesh_same_position(m, u_end, v_end);
    return volume_mesh_same_position(m, u->corner, v_end) && volume_mesh_same_position(m, u_end, v->corner);
}

bool volume_mesh_edges_build(const mesh *m, mesh_edges *e) {
    mesh_topology t;
    if (!mesh_weld(m, &t))
        return false;
    bool ok = mesh_edges_build(m, &t, e);
    mesh_topology_free(&t);
    /* Closed only where every edge's two triangles meet at one position
     * (see the header). */
    for (uint32_t i = 0; ok && e->closed && i < e->edge_count; i++) {
        const mesh_edge_use *u = &e->uses[e->edges[i].first_use];
        e->closed = volume_mesh_uses_meet(m, &u[0], &u[1]);
    }
    return ok;
}

/* ---- facing, and a light inside ---- */

/* The way towards the light from p (a point light's w is 1). */
static void volume_mesh_to_light(const float *p, const float light[4], float out[3]) {
    for (int k = 0; k < 3; k++)
        out[k] = light[k] - light[3] * p[k];
}

int volume_mesh_facing(const float *a, const float *b, const float *c, const float light[4]) {
    vec3 e1, e2, n, to_light[3];
    glm_vec3_sub((float *)b, (float *)a, e1);
    glm_vec3_sub((float *)c, (float *)a, e2);
    glm_vec3_cross(e1, e2, n);
    const float *corners[3] = {a, b, c};
    float reach = 0;
    for (int i = 0; i < 3; i++) {
        volume_mesh_to_light(corners[i], light, to_light[i]);
        reach += glm_vec3_norm(to_light[i]);
    }
    float along = glm_vec3_dot(n, to_light[0]);
    if (fabsf(along) <= glm_vec3_norm(n) * reach / VOLUME_MESH_EDGE_ON_RECIPROCAL)
        return 0;
    return along > 0 ? 1 : -1;
}

/* The solid angle of triangle (a, b, c) seen from the point light,
 * signed by its winding (Van Oosterom & Strackee 1983), in double; 0 for
 * a triangle edge-on to it (volume_mesh_facing): exact, unless the light
 * lies in the triangle, which is then on the surface (see the header). */
static double volume_mesh_solid_angle(const float *a, const float *b, const float *c, const float light[4]) {
    if (volume_mesh_facing(a, b, c, light) == 0)
        return 0;
    double u[3][3], length[3];
    const float *p[3] = {a, b, c};
    for (int i = 0; i < 3; i++) {
        for (int k = 0; k < 3; k++)
            u[i][k] = (double)p[i][k] - light[k];
        length[i] = sqrt(u[i][0] * u[i][0] + u[i][1] * u[i][1] + u[i][2] * u[i][2]);
    }
    double det = u[0][0] * (u[1][1] * u[2][2] - u[1][2] * u[2][1]) -
                 u[0][1] * (u[1][0] * u[2][2] - u[1][2] * u[2][0]) +
                 u[0][2] * (u[1][0] * u[2][1] - u[1][1] * u[2][0]);
    double dot01 = u[0][0] * u[1][0] + u[0][1] * u[1][1] + u[0][2] * u[1][2];
    double dot02 = u[0][0] * u[2][0] + u[0][1] * u[2][1] + u[0][2] * u[2][2];
    double dot12 = u[1][0] * u[2][0] + u[1][1] * u[2][1] + u[1][2] * u[2][2];
    double denominator =
        length[0] * length[1] * length[2] + dot01 * length[2] + dot02 * length[1] + dot12 * length[0];
    return 2 * atan2(det, denominator);
}

bool volume_mesh_light_inside(const mesh *m, const float light[4]) {
    if (light[3] == 0)
        return false; /* a direction: at infinity, outside every mesh */
    /* A light on a triangle edge-on to it lies within this of the
     * triangle: its distances to the corners sum to at most 3 diagonals
     * (and a little: 4). */
    float margin =
        4 * glm_vec3_distance((float *)m->bounds_min, (float *)m->bounds_max) / VOLUME_MESH_EDGE_ON_RECIPROCAL;
    for (int k = 0; k < 3; k++)
        if (!(light[k] >= m->bounds_min[k] - margin && light[k] <= m->bounds_max[k] + margin))
            return false;
    double total = 0;
    for (uint32_t t = 0; t < m->index_count / 3; t++) {
        const uint32_t *corner = &m->indices[t * 3];
        total += volume_mesh_solid_angle(m->vertices[corner[0]].position, m->vertices[corner[1]].position,
                                         m->vertices[corner[2]].position, light);
    }
    /* The winding number: 1 inside, 0 outside, 1/2 on the surface (-1
     * inside a mesh wound inwards, where the closed rule holds). */
    return total / (4 * GLM_PI) > VOLUME_MESH_INSIDE_WINDING;
}

bool volume_mesh_closed_rule(const mesh *m, const mesh_edges *e, const float light[4]) {
    return e->closed && !volume_mesh_light_inside(m, light);
}

/* ---- the count at a point ---- */

/* Whether the segment from p along d (t in (0, t_max)) crosses triangle
 * (a, b, c) (Moller & Trumbore, "Fast, minimum storage ray/triangle
 * intersection", JGT 2(1), 1997). */
static bool volume_mesh_crosses(const float *p, const vec3 d, float t_max, const float *a, const float *b,
                                const float *c) {
    vec3 e1, e2, h, s, q;
    glm_vec3_sub((float *)b, (float *)a, e1);
    glm_vec3_sub((float *)c, (float *)a, e2);
    glm_vec3_cross((float *)d, e2, h);
    float det = glm_vec3_dot(e1, h);
    if (det == 0)
        return false;
    glm_vec3_sub((float *)p, (float *)a, s);
    float u = glm_vec3_dot(s, h) / det;
    if (u < 0 || u > 1)
        return false;
    glm_vec3_cross(s, e1, q);
    float v = glm_vec3_dot((float *)d, q) / det;
    if (v < 0 || u + v > 1)
        return false;
    float t = glm_vec3_dot(e2, q) / det;
    return t > 0 && t < t_max;
}

int volume_mesh_count_at(const mesh *m, bool closed, const float light[4], const float p[3]) {
    /* A skew direction no axis-aligned edge or face diagonal lies in. */
    static const float skew[3] = {0.5773f, 0.2113f, 0.7887f};
    float size = 0;
    for (int k = 0; k < 3; k++)
        size = fmaxf(size, m->bounds_max[k] - m->bounds_min[k]);
    vec3 nudged, d;
    glm_vec3_copy((float *)p, nudged);
    glm_vec3_muladds((float *)skew, size * VOLUME_MESH_COUNT_NUDGE, nudged);
    volume_mesh_to_light(nudged, light, d);
    float t_max = light[3] != 0 ? 1.0f : INFINITY;
    int count = 0;
    for (uint32_t i = 0; i + 2 < m->index_count; i += 3) {
        const float *a = m->vertices[m->indices[i]].position, *b = m->vertices[m->indices[i + 1]].position,
                    *c = m->vertices[m->indices[i + 2]].position;
        int facing = volume_mesh_facing(a, b, c, light);
        if ((closed ? facing > 0 : facing != 0) && volume_mesh_crosses(nudged, d, t_max, a, b, c))
            count++;
    }
    return count;
}
