#include "wedge_area.h"

#include <cglm/cglm.h>
#include <math.h>
#include <stdbool.h>

float wedge_area_beyond(const float a[2], const float b[2]) {
    float d[2] = {b[0] - a[0], b[1] - a[1]};
    float qa = d[0] * d[0] + d[1] * d[1], qb = a[0] * d[0] + a[1] * d[1], qc = a[0] * a[0] + a[1] * a[1] - 1;
    float disc = qb * qb - qa * qc;
    if (qa <= 0 || disc <= 0)
        return 0;
    float root = sqrtf(disc);
    float t1 = fmaxf((-qb - root) / qa, 0), t2 = fminf((-qb + root) / qa, 1);
    if (t1 >= t2)
        return 0;
    float p1[2] = {a[0] + t1 * d[0], a[1] + t1 * d[1]}, p2[2] = {a[0] + t2 * d[0], a[1] + t2 * d[1]};
    float cross = p1[0] * p2[1] - p1[1] * p2[0];
    float angle = atan2f(cross, p1[0] * p2[0] + p1[1] * p2[1]);
    return (angle - cross) / (2 * GLM_PIf);
}

float wedge_area_edge(const float p[3], const float light[4], float size, const float a[3], const float b[3]) {
    vec3 axis, t, bt, ra, rb;
    float distance = 1;
    if (light[3] != 0) {
        glm_vec3_sub((float *)light, (float *)p, axis);
        distance = glm_vec3_norm(axis);
    } else {
        glm_vec3_copy((float *)light, axis);
    }
    glm_vec3_normalize(axis);
    /* Any axis across: t, then bt = axis x t, so that t x bt = axis. */
    glm_vec3_cross(axis, fabsf(axis[0]) < 0.5f ? (vec3){1, 0, 0} : (vec3){0, 1, 0}, t);
    glm_vec3_normalize(t);
    glm_vec3_cross(axis, t, bt);
    glm_vec3_sub((float *)a, (float *)p, ra);
    glm_vec3_sub((float *)b, (float *)p, rb);
    float da = glm_vec3_dot(ra, axis), db = glm_vec3_dot(rb, axis);
    float near = distance / WEDGE_AREA_NEAR_RECIPROCAL;
    bool bounded = light[3] != 0;
    if ((da < near && db < near) || (bounded && da > distance && db > distance))
        return 0;
    if (da < near) {
        glm_vec3_lerp(ra, rb, (near - da) / (db - da), ra);
        da = near;
    } else if (db < near) {
        glm_vec3_lerp(ra, rb, (near - da) / (db - da), rb);
        db = near;
    }
    if (bounded && da > distance) {
        glm_vec3_lerp(ra, rb, (distance - da) / (db - da), ra);
        da = distance;
    } else if (bounded && db > distance) {
        glm_vec3_lerp(ra, rb, (distance - da) / (db - da), rb);
        db = distance;
    }
    float scale_a = distance / (da * size), scale_b = distance / (db * size);
    float pa[2] = {glm_vec3_dot(ra, t) * scale_a, glm_vec3_dot(ra, bt) * scale_a};
    float pb[2] = {glm_vec3_dot(rb, t) * scale_b, glm_vec3_dot(rb, bt) * scale_b};
    return wedge_area_beyond(pa, pb);
}
