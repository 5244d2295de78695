/* volume_rule: the part of demos/lib/volume_mesh.h that says which rule
 * weighs a mesh's triangles for a light (see "Which meshes" and "The
 * closed rule" there): from whether the mesh is closed
 * (mesh_edges_build_welded) and the light inside it (mesh_point.h), and
 * the count at a point. No GL. */
#include "volume_mesh.h"

#include <math.h>

/* ---- which rule ---- */

bool volume_mesh_closed_rule(const mesh *m, const mesh_edges *e, const float light[4]) {
    return e->closed && !mesh_point_inside(m, light);
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
    mesh_point_from(nudged, light, d);
    float t_max = light[3] != 0 ? 1.0f : INFINITY;
    int count = 0;
    for (uint32_t i = 0; i + 2 < m->index_count; i += 3) {
        const float *a = m->vertices[m->indices[i]].position, *b = m->vertices[m->indices[i + 1]].position,
                    *c = m->vertices[m->indices[i + 2]].position;
        int facing = mesh_point_facing(a, b, c, light);
        if ((closed ? facing > 0 : facing != 0) && volume_mesh_crosses(nudged, d, t_max, a, b, c))
            count++;
    }
    return count;
}
