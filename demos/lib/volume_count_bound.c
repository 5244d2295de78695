#include "volume_count_bound.h"

#include <cglm/cglm.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "volume_mesh.h"

/* A face's differences and sums: one more row and column than bins. */
#define VOLUME_COUNT_BOUND_SIDE(g) ((g)->bins + 1)
#define VOLUME_COUNT_BOUND_FACE_CELLS(g) ((size_t)VOLUME_COUNT_BOUND_SIDE(g) * (size_t)VOLUME_COUNT_BOUND_SIDE(g))
/* A triangle clipped by a face's four planes: at most one corner more
 * each. */
#define VOLUME_COUNT_BOUND_CLIP_MAX (3 + 4)
/* A point light's face holds directions whose image lies in [-1, 1]. */
#define VOLUME_COUNT_BOUND_FACE_HALF 1.0f

bool volume_count_grid_init(volume_count_grid *g, int bins) {
    *g = (volume_count_grid){.bins = bins};
    g->cells = malloc(sizeof *g->cells * VOLUME_COUNT_BOUND_FACES * VOLUME_COUNT_BOUND_FACE_CELLS(g));
    if (!g->cells)
        fprintf(stderr, "volumes: out of memory for the count bound's grid\n");
    return g->cells != NULL;
}

void volume_count_grid_free(volume_count_grid *g) {
    free(g->cells);
    *g = (volume_count_grid){0};
}

void volume_count_grid_begin(volume_count_grid *g, const float light[4]) {
    memcpy(g->light, light, sizeof g->light);
    g->directional = light[3] == 0;
    g->lo[0] = g->lo[1] = INFINITY;
    g->hi[0] = g->hi[1] = -INFINITY;
    if (!g->directional)
        return;
    vec3 d = {light[0], light[1], light[2]}, other = {1, 0, 0};
    glm_vec3_normalize(d);
    if (fabsf(d[0]) > fabsf(d[1]) && fabsf(d[0]) > fabsf(d[2]))
        glm_vec3_copy((vec3){0, 1, 0}, other);
    glm_vec3_crossn(d, other, g->axis_u);
    glm_vec3_crossn(d, g->axis_u, g->axis_v);
}

/* Point p on a directional light's plane. */
static void volume_count_grid_plane(const volume_count_grid *g, const float p[3], float out[2]) {
    out[0] = glm_vec3_dot((float *)p, (float *)g->axis_u);
    out[1] = glm_vec3_dot((float *)p, (float *)g->axis_v);
}

void volume_count_grid_extent(volume_count_grid *g, const float (*triangles)[3][3], int count) {
    if (!g->directional)
        return;
    for (int k = 0; k < 3 * count; k++) {
        float uv[2];
        volume_count_grid_plane(g, triangles[k / 3][k % 3], uv);
        for (int a = 0; a < 2; a++) {
            g->lo[a] = fminf(g->lo[a], uv[a]);
            g->hi[a] = fmaxf(g->hi[a], uv[a]);
        }
    }
}

void volume_count_grid_start(volume_count_grid *g) {
    memset(g->cells, 0, sizeof *g->cells * VOLUME_COUNT_BOUND_FACES * VOLUME_COUNT_BOUND_FACE_CELLS(g));
    if (!g->directional) {
        g->lo[0] = g->lo[1] = -VOLUME_COUNT_BOUND_FACE_HALF;
        g->hi[0] = g->hi[1] = VOLUME_COUNT_BOUND_FACE_HALF;
    } else if (!(g->lo[0] <= g->hi[0])) {
        g->lo[0] = g->lo[1] = 0; /* nothing added: one empty bin */
        g->hi[0] = g->hi[1] = 0;
    }
}

/* The bin of coordinate x along axis a, clamped to the grid. */
static int volume_count_grid_bin(const volume_count_grid *g, int a, float x) {
    float span = g->hi[a] - g->lo[a];
    float t = span > 0 ? (x - g->lo[a]) / span * (float)g->bins : 0;
    if (!(t > 0))
        return 0;
    return t >= (float)(g->bins - 1) ? g->bins - 1 : (int)t;
}

/* Adds `weight` to face f's bins over the rectangle [lo, hi], grown by the
 * margin. */
static void volume_count_grid_rect(volume_count_grid *g, int f, const float lo[2], const float hi[2], int weight) {
    int b0[2], b1[2];
    for (int a = 0; a < 2; a++) {
        float grow = VOLUME_COUNT_BOUND_MARGIN * (1 + fmaxf(fabsf(lo[a]), fabsf(hi[a])) + (g->hi[a] - g->lo[a]));
        if (hi[a] + grow < g->lo[a] || lo[a] - grow > g->hi[a])
            return;
        b0[a] = volume_count_grid_bin(g, a, lo[a] - grow);
        b1[a] = volume_count_grid_bin(g, a, hi[a] + grow) + 1;
    }
    int *c = g->cells + (size_t)f * VOLUME_COUNT_BOUND_FACE_CELLS(g), side = VOLUME_COUNT_BOUND_SIDE(g);
    c[b0[1] * side + b0[0]] += weight;
    c[b0[1] * side + b1[0]] -= weight;
    c[b1[1] * side + b0[0]] -= weight;
    c[b1[1] * side + b1[0]] += weight;
}

/* The polygon's part (in the light's space: q, n corners) inside face f's
 * pyramid, w >= |u| and w >= |v|, clipped plane by plane
 * (Sutherland-Hodgman) into `out`; its corners. */
static int volume_count_grid_clip(int f, const float (*q)[3], int n, float (*out)[3]) {
    int axis = f / 2;
    float sign = f % 2 ? -1.0f : 1.0f;
    float a[VOLUME_COUNT_BOUND_CLIP_MAX][3], *from = &a[0][0], *to = &out[0][0];
    memcpy(a, q, (size_t)n * sizeof *q);
    for (int plane = 0; plane < 4; plane++) {
        int across = (axis + 1 + plane / 2) % 3;
        float side = plane % 2 ? -1.0f : 1.0f;
        int m = 0;
        for (int k = 0; k < n; k++) {
            const float *p = from + 3 * k, *r = from + 3 * ((k + 1) % n);
            float dp = sign * p[axis] - side * p[across], dr = sign * r[axis] - side * r[across];
            if (dp >= 0)
                memcpy(to + 3 * m++, p, 3 * sizeof *p);
            if ((dp >= 0) != (dr >= 0)) {
                float t = dp / (dp - dr);
                for (int c = 0; c < 3; c++)
                    to[3 * m + c] = p[c] + t * (r[c] - p[c]);
                m++;
            }
        }
        n = m;
        float *swap = from;
        from = to;
        to = swap;
    }
    if (from != &out[0][0])
        memcpy(out, from, (size_t)n * sizeof *out);
    return n;
}

void volume_count_grid_add(volume_count_grid *g, const float (*triangles)[3][3], int count, int weight) {
    float lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    if (g->directional) {
        for (int t = 0; t < count; t++)
            for (int k = 0; k < 3; k++) {
                float uv[2];
                volume_count_grid_plane(g, triangles[t][k], uv);
                for (int a = 0; a < 2; a++) {
                    lo[a] = fminf(lo[a], uv[a]);
                    hi[a] = fmaxf(hi[a], uv[a]);
                }
            }
        volume_count_grid_rect(g, 0, lo, hi, weight);
        return;
    }
    for (int f = 0; f < VOLUME_COUNT_BOUND_FACES; f++) {
        int axis = f / 2;
        float sign = f % 2 ? -1.0f : 1.0f;
        bool any = false, everywhere = false;
        lo[0] = lo[1] = INFINITY;
        hi[0] = hi[1] = -INFINITY;
        for (int t = 0; t < count && !everywhere; t++) {
            float q[3][3], part[VOLUME_COUNT_BOUND_CLIP_MAX][3];
            float size = 0;
            for (int k = 0; k < 3; k++) {
                for (int a = 0; a < 3; a++)
                    q[k][a] = triangles[t][k][a] * g->light[3] - g->light[a];
                size = fmaxf(size, glm_vec3_norm(q[k]));
            }
            int n = volume_count_grid_clip(f, (const float(*)[3])q, 3, part);
            for (int k = 0; k < n; k++) {
                float w = sign * part[k][axis];
                /* Only the light itself lies this near in the pyramid: it
                 * sees the triangle's plane at every angle. */
                if (w <= VOLUME_COUNT_BOUND_MARGIN * size) {
                    everywhere = true;
                    break;
                }
                float uv[2] = {part[k][(axis + 1) % 3] / w, part[k][(axis + 2) % 3] / w};
                for (int a = 0; a < 2; a++) {
                    lo[a] = fminf(lo[a], uv[a]);
                    hi[a] = fmaxf(hi[a], uv[a]);
                }
                any = true;
            }
        }
        if (everywhere) {
            lo[0] = lo[1] = -VOLUME_COUNT_BOUND_FACE_HALF;
            hi[0] = hi[1] = VOLUME_COUNT_BOUND_FACE_HALF;
        } else if (!any) {
            continue;
        }
        volume_count_grid_rect(g, f, lo, hi, weight);
    }
}

int volume_count_grid_max(const volume_count_grid *g) {
    int faces = g->directional ? 1 : VOLUME_COUNT_BOUND_FACES, best = 0;
    int side = VOLUME_COUNT_BOUND_SIDE(g);
    for (int f = 0; f < faces; f++) {
        int *c = g->cells + (size_t)f * VOLUME_COUNT_BOUND_FACE_CELLS(g);
        for (int y = 0; y < g->bins; y++)
            for (int x = 0; x < g->bins; x++) {
                int *cell = &c[y * side + x];
                if (x > 0)
                    *cell += cell[-1];
                if (y > 0)
                    *cell += cell[-side];
                if (x > 0 && y > 0)
                    *cell -= cell[-side - 1];
                best = *cell > best ? *cell : best;
            }
    }
    return best;
}

bool volume_count_bound_convex(const mesh *m) {
    size_t triangles = m->index_count / 3;
    if ((double)triangles * m->vertex_count > VOLUME_COUNT_BOUND_CONVEX_MAX_WORK || triangles == 0)
        return false;
    float tolerance =
        VOLUME_COUNT_BOUND_CONVEX_TOLERANCE * glm_vec3_distance((float *)m->bounds_min, (float *)m->bounds_max);
    for (size_t t = 0; t < triangles; t++) {
        float *a = m->vertices[m->indices[3 * t]].position, *b = m->vertices[m->indices[3 * t + 1]].position,
              *c = m->vertices[m->indices[3 * t + 2]].position;
        vec3 ab, ac, n;
        glm_vec3_sub(b, a, ab);
        glm_vec3_sub(c, a, ac);
        glm_vec3_cross(ab, ac, n);
        float length = glm_vec3_norm(n);
        if (length == 0)
            continue;
        glm_vec3_scale(n, 1 / length, n);
        for (uint32_t v = 0; v < m->vertex_count; v++) {
            vec3 d;
            glm_vec3_sub(m->vertices[v].position, a, d);
            if (glm_vec3_dot(d, n) > tolerance)
                return false;
        }
    }
    return true;
}

/* Triangle t of m as three points, and whether it weighs non-zero for the
 * light under the rule (volume_mesh.h). */
static bool volume_count_bound_weighs(const mesh *m, size_t t, bool closed_rule, const float light[4],
                                      float out[3][3]) {
    for (int k = 0; k < 3; k++)
        memcpy(out[k], m->vertices[m->indices[3 * t + (size_t)k]].position, sizeof out[k]);
    int facing = mesh_point_facing(out[0], out[1], out[2], light);
    return closed_rule ? facing > 0 : facing != 0;
}

int volume_count_bound_mesh(volume_count_grid *g, const mesh *m, bool closed_rule, bool convex,
                            const float light[4]) {
    if (closed_rule && convex)
        return 1;
    size_t triangles = m->index_count / 3;
    float corners[1][3][3];
    volume_count_grid_begin(g, light);
    for (size_t t = 0; g->directional && t < triangles; t++)
        if (volume_count_bound_weighs(m, t, closed_rule, light, corners[0]))
            volume_count_grid_extent(g, (const float(*)[3][3])corners, 1);
    volume_count_grid_start(g);
    for (size_t t = 0; t < triangles; t++)
        if (volume_count_bound_weighs(m, t, closed_rule, light, corners[0]))
            volume_count_grid_add(g, (const float(*)[3][3])corners, 1, 1);
    return volume_count_grid_max(g);
}
