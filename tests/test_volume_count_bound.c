/* volume_count_bound (demos/lib/volume_count_bound.h), without a GL
 * context: a convex closed mesh bounds at 1, a non-convex one is binned;
 * every bound is at least the number of weighing triangles that rays from
 * the light cross (sampled, for point and directional lights, closed and
 * open meshes); and a stack of N layers straight under a sun bounds at N. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "support.h"
#include "volume_count_bound.h"
#include "volume_mesh.h"

#define RAYS 4000
#define STACK_LAYERS 300
#define STACK_PITCH 0.01f

/* Whether the ray from `origin` along `d` (t > 0) crosses triangle abc
 * (Moller & Trumbore 1997). */
static bool crosses(const float origin[3], const float d[3], const float *a, const float *b, const float *c) {
    float e1[3], e2[3], p[3], s[3], q[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = b[k] - a[k];
        e2[k] = c[k] - a[k];
        s[k] = origin[k] - a[k];
    }
    glm_vec3_cross((float *)d, e2, p);
    float det = glm_vec3_dot(e1, p);
    if (fabsf(det) < 1e-12f)
        return false;
    float u = glm_vec3_dot(s, p) / det;
    glm_vec3_cross(s, e1, q);
    float v = glm_vec3_dot((float *)d, q) / det, t = glm_vec3_dot(e2, q) / det;
    return u >= 0 && v >= 0 && u + v <= 1 && t > 0;
}

static uint64_t rng = 12345;
static float uniform(void) {
    rng = rng * 6364136223846793005ULL + 1442695040888963407ULL;
    return (float)(rng >> 40) / (float)(1u << 24);
}

/* The most weighing triangles of m one sampled ray from the light crosses
 * (towards random points of the mesh's box, or along a directional light
 * from random points beyond the box). */
static int deepest_sampled(const mesh *m, bool closed_rule, const float light[4]) {
    int deepest = 0;
    for (int r = 0; r < RAYS; r++) {
        float target[3], origin[3], d[3];
        for (int k = 0; k < 3; k++)
            target[k] = m->bounds_min[k] + uniform() * (m->bounds_max[k] - m->bounds_min[k]);
        for (int k = 0; k < 3; k++) {
            d[k] = light[3] == 0 ? -light[k] : target[k] - light[k];
            origin[k] = light[3] == 0 ? target[k] + light[k] * 100 : light[k];
        }
        int count = 0;
        for (uint32_t t = 0; t < m->index_count / 3; t++) {
            const float *a = m->vertices[m->indices[3 * t]].position,
                        *b = m->vertices[m->indices[3 * t + 1]].position,
                        *c = m->vertices[m->indices[3 * t + 2]].position;
            int facing = mesh_point_facing(a, b, c, light);
            if ((closed_rule ? facing > 0 : facing != 0) && crosses(origin, d, a, b, c))
                count++;
        }
        deepest = count > deepest ? count : deepest;
    }
    return deepest;
}

static void assert_safe(const mesh *m, bool closed_rule, const float light[4], const char *name) {
    volume_count_grid g;
    assert_true(volume_count_grid_init(&g, VOLUME_COUNT_BOUND_MESH_BINS));
    bool convex = closed_rule && volume_count_bound_convex(m);
    int bound = volume_count_bound_mesh(&g, m, closed_rule, convex, light);
    int sampled = deepest_sampled(m, closed_rule, light);
    printf("    %-28s bound %4d, deepest sampled ray %4d\n", name, bound, sampled);
    assert_true(bound >= sampled);
    volume_count_grid_free(&g);
}

static void test_convex(void **state) {
    (void)state;
    mesh box = {0}, torus = {0}, sphere = {0};
    assert_true(mesh_make_box(&box, 1, 2, 3));
    assert_true(mesh_make_torus(&torus, 1, 0.3f, 24));
    assert_true(mesh_make_sphere(&sphere, 1, 16));
    assert_true(volume_count_bound_convex(&box));
    assert_true(volume_count_bound_convex(&sphere));
    assert_false(volume_count_bound_convex(&torus));
    volume_count_grid g;
    assert_true(volume_count_grid_init(&g, VOLUME_COUNT_BOUND_MESH_BINS));
    const float light[4] = {3, 4, 5, 1};
    assert_int_equal(volume_count_bound_mesh(&g, &box, true, true, light), 1);
    volume_count_grid_free(&g);
    mesh_free(&box);
    mesh_free(&torus);
    mesh_free(&sphere);
}

static void test_safe(void **state) {
    (void)state;
    mesh torus = {0}, sphere = {0};
    assert_true(mesh_make_torus(&torus, 1, 0.3f, 24));
    assert_true(mesh_make_sphere(&sphere, 1, 16));
    const float point[4] = {0.5f, 3, 0.2f, 1}, near_point[4] = {1.2f, 0.1f, 0.3f, 1}, sun[4] = {0.3f, 1, 0.2f, 0};
    assert_safe(&torus, true, point, "torus, closed, point");
    assert_safe(&torus, false, point, "torus, open rule, point");
    assert_safe(&torus, false, near_point, "torus, open rule, light near");
    assert_safe(&torus, true, sun, "torus, closed, sun");
    assert_safe(&sphere, false, sun, "sphere, open rule, sun");
    mesh_free(&torus);
    mesh_free(&sphere);
}

/* STACK_LAYERS unit squares, each two triangles, one above the other. */
static void make_stack(mesh *m) {
    *m = (mesh){0};
    m->vertex_count = 4 * STACK_LAYERS;
    m->index_count = 6 * STACK_LAYERS;
    m->vertices = calloc(m->vertex_count, sizeof *m->vertices);
    m->indices = calloc(m->index_count, sizeof *m->indices);
    assert_non_null(m->vertices);
    assert_non_null(m->indices);
    static const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    static const uint32_t quad[6] = {0, 2, 1, 0, 3, 2};
    for (uint32_t l = 0; l < STACK_LAYERS; l++) {
        for (int k = 0; k < 4; k++) {
            float *p = m->vertices[4 * l + (uint32_t)k].position;
            p[0] = corners[k][0];
            p[1] = (float)l * STACK_PITCH;
            p[2] = corners[k][1];
        }
        for (int k = 0; k < 6; k++)
            m->indices[6 * l + (uint32_t)k] = 4 * l + quad[k];
    }
    glm_vec3_copy((vec3){-1, 0, -1}, m->bounds_min);
    glm_vec3_copy((vec3){1, (STACK_LAYERS - 1) * STACK_PITCH, 1}, m->bounds_max);
}

static void test_stack(void **state) {
    (void)state;
    mesh m;
    make_stack(&m);
    volume_count_grid g;
    assert_true(volume_count_grid_init(&g, VOLUME_COUNT_BOUND_MESH_BINS));
    const float overhead[4] = {0, 1, 0, 0}, slanted[4] = {0.3f, 1, 0.2f, 0}, point[4] = {0.2f, 10, 0.1f, 1};
    /* A quad's two triangles share a bin along their diagonal. */
    int bound = volume_count_bound_mesh(&g, &m, false, false, overhead);
    assert_true(bound >= STACK_LAYERS && bound <= 2 * STACK_LAYERS);
    volume_count_grid_free(&g);
    assert_safe(&m, false, slanted, "stack, open rule, sun");
    assert_safe(&m, false, point, "stack, open rule, point");
    mesh_free(&m);
}

/* A light's grid of casters' boxes: boxes apart in direction never add. */
static void test_light_grid(void **state) {
    (void)state;
    volume_count_grid g;
    assert_true(volume_count_grid_init(&g, VOLUME_COUNT_BOUND_LIGHT_BINS));
    const float light[4] = {0, 10, 0, 1};
    float a[1][3][3] = {{{-5, 0, -5}, {-4, 0, -5}, {-4, 0, -4}}}, b[1][3][3] = {{{4, 0, 4}, {5, 0, 4}, {5, 0, 5}}};
    volume_count_grid_begin(&g, light);
    volume_count_grid_start(&g);
    volume_count_grid_add(&g, (const float(*)[3][3])a, 1, 7);
    volume_count_grid_add(&g, (const float(*)[3][3])b, 1, 9);
    assert_int_equal(volume_count_grid_max(&g), 9);
    volume_count_grid_begin(&g, light);
    volume_count_grid_start(&g);
    volume_count_grid_add(&g, (const float(*)[3][3])a, 1, 7);
    volume_count_grid_add(&g, (const float(*)[3][3])a, 1, 9);
    assert_int_equal(volume_count_grid_max(&g), 16);
    volume_count_grid_free(&g);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_convex),
        cmocka_unit_test(test_safe),
        cmocka_unit_test(test_stack),
        cmocka_unit_test(test_light_grid),
    };
    return cmocka_run_group_tests_name("volumes' count bound", tests, NULL, NULL);
}
