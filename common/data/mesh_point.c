#include "mesh_point.h"

#include <math.h>

void mesh_point_from(const float *p, const float point[4], float out[3]) {
    for (int k = 0; k < 3; k++)
        out[k] = point[k] - point[3] * p[k];
}

int mesh_point_facing(const float *a, const float *b, const float *c, const float point[4]) {
    vec3 e1, e2, n, to_point[3];
    glm_vec3_sub((float *)b, (float *)a, e1);
    glm_vec3_sub((float *)c, (float *)a, e2);
    glm_vec3_cross(e1, e2, n);
    const float *corners[3] = {a, b, c};
    float reach = 0;
    for (int i = 0; i < 3; i++) {
        mesh_point_from(corners[i], point, to_point[i]);
        reach += glm_vec3_norm(to_point[i]);
    }
    float along = glm_vec3_dot(n, to_point[0]);
    if (fabsf(along) <= glm_vec3_norm(n) * reach / MESH_POINT_EDGE_ON_RECIPROCAL)
        return 0;
    return along > 0 ? 1 : -1;
}

/* The solid angle of triangle (a, b, c) seen from the position, signed by
 * its winding (Van Oosterom & Strackee 1983), in double; 0 for a triangle
 * edge-on to it (mesh_point_facing): exact, unless the point lies in the
 * triangle, which is then on the surface. */
static double mesh_point_solid_angle(const float *a, const float *b, const float *c, const float point[4]) {
    if (mesh_point_facing(a, b, c, point) == 0)
        return 0;
    double u[3][3], length[3];
    const float *p[3] = {a, b, c};
    for (int i = 0; i < 3; i++) {
        for (int k = 0; k < 3; k++)
            u[i][k] = (double)p[i][k] - point[k];
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

double mesh_point_winding(const mesh *m, const float point[4]) {
    if (point[3] == 0)
        return 0; /* a direction: at infinity, outside every mesh */
    /* A point on a triangle edge-on to it lies within this of the
     * triangle: its distances to the corners sum to at most 3 diagonals
     * (and a little: 4). */
    float margin =
        4 * glm_vec3_distance((float *)m->bounds_min, (float *)m->bounds_max) / MESH_POINT_EDGE_ON_RECIPROCAL;
    for (int k = 0; k < 3; k++)
        if (!(point[k] >= m->bounds_min[k] - margin && point[k] <= m->bounds_max[k] + margin))
            return 0;
    double total = 0;
    for (uint32_t t = 0; t < m->index_count / 3; t++) {
        const uint32_t *corner = &m->indices[t * 3];
        total += mesh_point_solid_angle(m->vertices[corner[0]].position, m->vertices[corner[1]].position,
                                        m->vertices[corner[2]].position, point);
    }
    return total / (4 * GLM_PI);
}

bool mesh_point_inside(const mesh *m, const float point[4]) {
    return mesh_point_winding(m, point) > MESH_POINT_INSIDE_WINDING;
}

void mesh_point_to_object(const mat4 model, const float point[4], float out[4]) {
    mat4 inverse;
    glm_mat4_inv((vec4 *)model, inverse);
    glm_mat4_mulv(inverse, (float *)point, out);
}
