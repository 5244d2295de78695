#include "wedge_area.h"

#include <cglm/cglm.h>
#include <math.h>
#include <stdbool.h>

float wedge_area_beyond(const float a[2], const float b[2]) {
    float d[2] = {b[0] - a[0], b[1] - a[1]};
    float length = sqrtf(d[0] * d[0] + d[1] * d[1]);
    if (length <= 0)
        return 0;
    d[0] /= length, d[1] /= length;
    /* On the line: u along it, v (constant) across it, from the centre. */
    float v = d[0] * a[1] - d[1] * a[0];
    if (v * v >= 1)
        return 0;
    float half = sqrtf(1 - v * v);
    float u1 = fmaxf(a[0] * d[0] + a[1] * d[1], -half), u2 = fminf(b[0] * d[0] + b[1] * d[1], half);
    if (u1 >= u2)
        return 0;
    float cross = v * (u1 - u2);
    return (atan2f(cross, u1 * u2 + v * v) - cross) / (2 * GLM_PIf);
}

/* The light's unit axis from p and its distance (1 for a directional
 * light). */
static float wedge_area_axis(const float p[3], const float light[4], vec3 axis) {
    float distance = 1;
    if (light[3] != 0) {
        glm_vec3_sub((float *)light, (float *)p, axis);
        distance = glm_vec3_norm(axis);
    } else {
        glm_vec3_copy((float *)light, axis);
    }
    glm_vec3_normalize(axis);
    return distance;
}

float wedge_area_edge(const float p[3], const float light[4], float size, const float a[3], const float b[3]) {
    vec3 axis, t, bt, ra, rb;
    float distance = wedge_area_axis(p, light, axis);
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
