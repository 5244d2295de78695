/* Tests of demos/lib/warp.c (and the uniform fit of map_fit.c): the
 * math of warped shadow maps on hand-made views, points and lights. No GL
 * context is created: this is pure math. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "camera.h"
#include "frustum.h"
#include "map.h"
#include "warp.h"

#define PI 3.14159265358979323846
/* Float math on values of order 100: relative agreement to this. */
#define RELATIVE 1e-4
/* A point fitted to the map's edge may land just outside by rounding. */
#define CLIP_TOLERANCE 1e-4f

/* A street scene: the camera 2 units up looking down the -z axis, slightly
 * down; the ground in front of it (x -10..10, z -2..-100) as the receivers'
 * points, then the box corners of a post 20 units ahead as a caster's. */
#define RECEIVERS 4
#define POINTS (RECEIVERS + 8)
static camera_view street_view;
static float street_points[POINTS][3];

static int street_setup(void **state) {
    (void)state;
    scene_camera camera = {.position = {0, 2, 0},
                           .target = {0, 1.5f, -10},
                           .up = {0, 1, 0},
                           .fov_deg = 60,
                           .near_plane = 0.1f,
                           .far_plane = 200};
    camera_view_compute(&camera, 16.0f / 9.0f, &street_view);
    static const float ground[RECEIVERS][3] = {{-10, 0, -2}, {10, 0, -2}, {-10, 0, -100}, {10, 0, -100}};
    memcpy(street_points, ground, sizeof ground);
    for (int c = 0; c < 8; c++) {
        float *p = street_points[RECEIVERS + c];
        p[0] = c & 1 ? 1.0f : 0.0f;
        p[1] = c & 2 ? 3.0f : 0.0f;
        p[2] = c & 4 ? -21.0f : -20.0f;
    }
    return 0;
}

static scene_light directional(float x, float y, float z) {
    scene_light l = {.type = SCENE_LIGHT_DIRECTIONAL, .color = {1, 1, 1}, .intensity = 1};
    float norm = sqrtf(x * x + y * y + z * z);
    l.direction[0] = x / norm, l.direction[1] = y / norm, l.direction[2] = z / norm;
    return l;
}

static bool finite_matrix(const mat4 m) {
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            if (!isfinite(m[c][r]))
                return false;
    return true;
}

/* Every point inside the clip cube of `m` (in front of its eye). */
static void assert_inside_clip_cube(const mat4 m, const float (*points)[3], int n) {
    for (int i = 0; i < n; i++) {
        vec4 clip, h = {points[i][0], points[i][1], points[i][2], 1};
        glm_mat4_mulv((vec4 *)m, h, clip);
        float w = clip[3] * (1 + CLIP_TOLERANCE);
        assert_true(clip[3] > 0);
        for (int k = 0; k < 3; k++)
            assert_true(fabsf(clip[k]) <= w);
    }
}

static void assert_close(double actual, double expected) {
    if (!(fabs(actual - expected) <= RELATIVE * fabs(expected))) {
        fprintf(stderr, "    %.9g, expected %.9g\n", actual, expected);
        fail();
    }
}

/* ---- LiSPSM ---- */

static void test_n_opt_formula(void **state) {
    (void)state;
    /* (z_n + sqrt(z_n z_f)) / sin(gamma): (1 + 10) / 0.5 and (4 + 20) / 1. */
    assert_close(warp_lispsm_n_opt(1, 100, 0.5f), 22.0);
    assert_close(warp_lispsm_n_opt(4, 100, 1), 24.0);
}

/* A light straight down, a camera at 10 looking at angle gamma to it
 * along the x axis, receivers at depths 1 and 100 along the view (z_n 1,
 * z_f 100) spread across it and along the light. The warp's w (its
 * perspective) at the far receivers over the near ones is 1 + depth /
 * n_opt with depth 99 sin(gamma) and n_opt 11 / sin(gamma): 1 + 9
 * sin^2(gamma), which falls to 1, a uniform map, as the view turns
 * parallel to the light. */
static void test_lispsm_turns_uniform_as_view_meets_light(void **state) {
    (void)state;
    static const float gammas_deg[] = {90, 60, 30, 10, 2};
    scene_light light = directional(0, -1, 0);
    float last_n_opt = 0, last_ratio = INFINITY;
    for (size_t g = 0; g < sizeof gammas_deg / sizeof *gammas_deg; g++) {
        float gamma = (float)(gammas_deg[g] * PI / 180);
        warp_view v = {.eye = {0, 10, 0}, .forward = {sinf(gamma), -cosf(gamma), 0}, .z_near = 1, .z_far = 100};
        float points[8][3], scratch[8][3];
        for (int c = 0; c < 8; c++) {
            float t = c & 1 ? 100.0f : 1.0f;
            for (int k = 0; k < 3; k++)
                points[c][k] = v.eye[k] + v.forward[k] * t;
            points[c][1] += c & 2 ? 5.0f : -5.0f; /* along the light */
            points[c][2] += c & 4 ? 5.0f : -5.0f; /* across the view */
        }
        warp_result r = {0};
        assert_true(warp_lispsm(&light, &v, (const float(*)[3])points, 8, 8, scratch, &r));
        assert_close(r.sin_gamma, sin(gamma));
        assert_close(r.n_opt, 11 / sin(gamma));
        assert_true(r.n_opt > last_n_opt);
        assert_true(finite_matrix(r.view_projection));
        assert_inside_clip_cube(r.view_projection, (const float(*)[3])points, 8);
        vec4 near_clip, far_clip;
        glm_mat4_mulv(r.view_projection, (vec4){points[0][0], points[0][1], points[0][2], 1}, near_clip);
        glm_mat4_mulv(r.view_projection, (vec4){points[1][0], points[1][1], points[1][2], 1}, far_clip);
        double ratio = far_clip[3] / near_clip[3];
        assert_close(ratio, 1 + 9 * sin(gamma) * sin(gamma));
        assert_true(ratio < last_ratio);
        last_n_opt = r.n_opt, last_ratio = ratio;
    }
    assert_true(last_ratio < 1.02);
    /* Parallel: no warp at all. */
    warp_view v = {.eye = {0, 10, 0}, .forward = {0, -1, 0}, .z_near = 1, .z_far = 100};
    float points[2][3] = {{0, 9, 0}, {1, -90, 1}}, scratch[2][3];
    warp_result r = {0};
    assert_false(warp_lispsm(&light, &v, (const float(*)[3])points, 2, 2, scratch, &r));
    assert_non_null(strstr(r.why, "parallel"));
}

/* ---- PSM ---- */

static warp_result street_psm(const scene_light *l, bool *placed) {
    warp_view v;
    float scratch[POINTS][3];
    warp_result r = {0};
    assert_true(warp_view_of(&street_view, (const float(*)[3])street_points, RECEIVERS, &v));
    *placed = warp_psm(&street_view, l, &v, (const float(*)[3])street_points, POINTS, scratch, &r);
    return r;
}

static void test_psm_light_in_front_is_a_point(void **state) {
    (void)state;
    scene_light light = directional(0, -0.7f, 0.7f); /* from ahead, towards the camera */
    bool placed;
    warp_result r = street_psm(&light, &placed);
    assert_true(placed);
    assert_int_equal(r.psm_case, WARP_PSM_IN_FRONT);
    assert_true(r.light_in_space[3] > 0);
    for (int k = 0; k < 3; k++)
        assert_true(isfinite(r.light_in_space[k] / r.light_in_space[3]));
    assert_false(r.orthographic);
    assert_true(r.slide > 0); /* the optimum near plane z_n + sqrt(z_n z_f) lies behind the camera's */
    assert_true(finite_matrix(r.view_projection));
    assert_inside_clip_cube(r.view_projection, (const float(*)[3])street_points, POINTS);
}

/* Behind the viewer the light's PPS image lies beyond infinity (w < 0):
 * the map is the frustum around the points from that image with its depth
 * row negated. */
static void test_psm_light_behind_is_inverted(void **state) {
    (void)state;
    scene_light light = directional(0, -0.7f, -0.7f); /* from behind, along the view */
    bool placed;
    warp_result r = street_psm(&light, &placed);
    assert_true(placed);
    assert_int_equal(r.psm_case, WARP_PSM_BEHIND);
    assert_true(r.light_in_space[3] < 0);
    assert_non_null(strstr(r.why, "inverted"));
    float warped[POINTS][3], eye[3], near_plane, far_plane;
    for (int i = 0; i < POINTS; i++)
        assert_true(warp_project(r.space, street_points[i], warped[i]));
    glm_vec3_scale(r.light_in_space, 1.0f / r.light_in_space[3], eye);
    mat4 frustum, expected;
    assert_true(warp_frustum_around(eye, (const float(*)[3])warped, POINTS, frustum, &near_plane, &far_plane));
    for (int col = 0; col < 4; col++)
        frustum[col][2] = -frustum[col][2];
    glm_mat4_mul(frustum, r.space, expected);
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++)
            assert_true(fabsf(r.view_projection[col][row] - expected[col][row]) <=
                        (float)RELATIVE * fmaxf(fabsf(expected[col][row]), 1));
    assert_true(finite_matrix(r.view_projection));
    assert_inside_clip_cube(r.view_projection, (const float(*)[3])street_points, POINTS);
}

/* A light across the view: its direction has no depth in view space, so
 * its PPS image is at infinity and the map orthographic there. */
static void test_psm_light_across_view_is_at_infinity(void **state) {
    (void)state;
    scene_light light = directional(1, 0, 0);
    bool placed;
    warp_result r = street_psm(&light, &placed);
    assert_true(placed);
    assert_int_equal(r.psm_case, WARP_PSM_AT_INFINITY);
    assert_true(r.orthographic);
    assert_true(finite_matrix(r.view_projection));
    assert_inside_clip_cube(r.view_projection, (const float(*)[3])street_points, POINTS);
}

/* ---- fitting ---- */

static void test_uniform_fit_contains_receivers(void **state) {
    (void)state;
    scene s = {.light_count = 2};
    s.lights[0] = directional(0.3f, -1, -0.5f);
    s.lights[1] = (scene_light){.type = SCENE_LIGHT_SPOT,
                                .position = {0, 40, -50},
                                .direction = {0, -1, 0},
                                .outer_angle_deg = 70,
                                .inner_angle_deg = 60};
    for (int l = 0; l < s.light_count; l++) {
        map_light m = {.size = 1024};
        assert_true(map_fit_uniform(&s, l, &m, (const float(*)[3])street_points, RECEIVERS));
        assert_int_equal(m.kind, MAP_2D);
        assert_int_equal(m.layer_count, 1);
        assert_true(finite_matrix(m.layer_view_projection[0]));
        assert_inside_clip_cube(m.layer_view_projection[0], (const float(*)[3])street_points, RECEIVERS);
    }
}

/* Seen along a light straight down, a box over the receivers can shadow
 * them and one beside them cannot. */
static void test_relevant_casters(void **state) {
    (void)state;
    scene_object objects[2] = {{.casts = true}, {.casts = true}};
    static const float boxes[2][2][3] = {{{0, 0, -30}, {1, 3, -29}}, {{40, 0, -30}, {41, 3, -29}}};
    for (int i = 0; i < 2; i++) {
        glm_mat4_identity(objects[i].model);
        memcpy(objects[i].mesh.bounds_min, boxes[i][0], sizeof boxes[i][0]);
        memcpy(objects[i].mesh.bounds_max, boxes[i][1], sizeof boxes[i][1]);
    }
    scene s = {.objects = objects, .object_count = 2};
    scene_light light = directional(0, -1, 0);
    float points[RECEIVERS + 16][3];
    bool mask[2];
    memcpy(points, street_points, sizeof(float[RECEIVERS][3]));
    assert_int_equal(warp_relevant_casters(&s, &light, points, RECEIVERS, RECEIVERS + 16, mask), RECEIVERS + 8);
    assert_true(mask[0]);
    assert_false(mask[1]);
    assert_true(points[RECEIVERS + 7][0] == 1 && points[RECEIVERS + 7][1] == 3 && points[RECEIVERS + 7][2] == -29);
    /* No room for the caster's corners: -1. */
    assert_int_equal(warp_relevant_casters(&s, &light, points, RECEIVERS, RECEIVERS + 7, mask), -1);
}

/* ---- measuring ---- */

/* A grid over a rectangle of the picture (a light's reach) casts
 * WARP_RECT_SAMPLES_X x WARP_RECT_SAMPLES_Y rays, each through the
 * rectangle, against the boxes warp_boxes_seen_in keeps for it: those
 * whose screen bounds meet it and those that reach behind the eye, never
 * one beside it. A camera 10 units above a plane looking straight down,
 * a box on the plane at each side of the picture and one above the eye. */
static void test_rectangle_grid_and_its_boxes(void **state) {
    (void)state;
    enum { WIDTH = 640, HEIGHT = 360, RIGHT = 2, ABOVE = 3 };
    scene_object objects[] = {
        {.receives = true, .mesh = {.bounds_min = {-100, 0, -100}, .bounds_max = {100, 0, 100}}},
        {.receives = true, .mesh = {.bounds_min = {-9, 0, -0.5f}, .bounds_max = {-8, 1, 0.5f}}},
        {.receives = true, .mesh = {.bounds_min = {8, 0, -0.5f}, .bounds_max = {9, 1, 0.5f}}},
        {.receives = true, .mesh = {.bounds_min = {-1, 20, -1}, .bounds_max = {1, 21, 1}}},
    };
    enum { OBJECTS = sizeof objects / sizeof *objects };
    for (int i = 0; i < OBJECTS; i++)
        glm_mat4_identity(objects[i].model);
    scene s = {.objects = objects, .object_count = OBJECTS};
    scene_camera camera = {.position = {0, 10, 0},
                           .target = {0, 0, 0},
                           .up = {0, 0, -1},
                           .fov_deg = 60,
                           .near_plane = 0.1f,
                           .far_plane = 100};
    camera_view view;
    camera_view_compute(&camera, (float)WIDTH / HEIGHT, &view);
    float boxes[OBJECTS][2][3], seen[OBJECTS][2][3];
    assert_int_equal(warp_receiver_boxes(&s, boxes), OBJECTS);
    const float right[4] = {0.5f, -0.5f, 1, 0.5f};
    int kept = warp_boxes_seen_in((const float(*)[2][3])boxes, OBJECTS, &view, right, seen);
    assert_int_equal(kept, 3); /* the ground, the right box, the one above the eye; in their order */
    assert_memory_equal(seen[0], boxes[0], sizeof seen[0]);
    assert_memory_equal(seen[1], boxes[RIGHT], sizeof seen[1]);
    assert_memory_equal(seen[2], boxes[ABOVE], sizeof seen[2]);
    warp_sample hits[WARP_SAMPLE_COUNT];
    int n = warp_samples((const float(*)[2][3])seen, kept, &view, WIDTH, HEIGHT, right, hits);
    assert_int_equal(n, WARP_RECT_SAMPLES_X * WARP_RECT_SAMPLES_Y);
    bool on_box = false;
    for (int i = 0; i < n; i++) {
        vec4 clip;
        glm_mat4_mulv(view.view_projection, (vec4){hits[i].position[0], hits[i].position[1], hits[i].position[2], 1},
                      clip);
        for (int k = 0; k < 2; k++) {
            float ndc = clip[k] / clip[3];
            assert_true(ndc > right[k] && ndc < right[k + 2]);
        }
        on_box = on_box || hits[i].position[1] > 0.5f; /* the right box's top, a unit up */
    }
    assert_true(on_box);
}

/* A camera 10 units above a plane looking straight down sees it at one
 * scale everywhere: height / (2 * 10 tan 30 deg) pixels per unit. An
 * orthographic map of 2L units over S texels has texels 2L / S units
 * wide: their size in pixels is the product. */
static void test_texel_size_of_orthographic_map_on_plane(void **state) {
    (void)state;
    enum { WIDTH = 640, HEIGHT = 360, SIZE = 1024 };
    const float half_extent = 20, height = 10, fov_deg = 60;
    scene_object ground = {.receives = true, .mesh = {.bounds_min = {-100, 0, -100}, .bounds_max = {100, 0, 100}}};
    glm_mat4_identity(ground.model);
    scene s = {.objects = &ground, .object_count = 1};
    scene_camera camera = {.position = {0, height, 0},
                           .target = {0, 0, 0},
                           .up = {0, 0, -1},
                           .fov_deg = fov_deg,
                           .near_plane = 0.1f,
                           .far_plane = 100};
    camera_view view;
    camera_view_compute(&camera, (float)WIDTH / HEIGHT, &view);
    scene_light light = directional(0, -1, 0);
    warp_sample hits[WARP_SAMPLE_COUNT], samples[WARP_SAMPLE_COUNT];
    float boxes[1][2][3];
    int box_count = warp_receiver_boxes(&s, boxes);
    int n =
        warp_samples_lit(hits, warp_samples((const float(*)[2][3])boxes, box_count, &view, WIDTH, HEIGHT, NULL, hits),
                         &light, samples, NULL);
    assert_int_equal(n, WARP_SAMPLE_COUNT);
    mat4 map_view, projection, map;
    frustum_look_along((vec3){0, 2 * height, 0}, light.direction, map_view);
    glm_ortho(-half_extent, half_extent, -half_extent, half_extent, 1, 4 * height, projection);
    glm_mat4_mul(projection, map_view, map);
    double pixels_per_unit = HEIGHT / (2 * height * tan(fov_deg / 2 * PI / 180));
    double expected = 2 * half_extent / SIZE * pixels_per_unit;
    assert_close(warp_texel_pixels((const mat4 *)&map, 1, SIZE, light.position, samples, n), expected);
    /* Twice the texels, half their size. */
    assert_close(warp_texel_pixels((const mat4 *)&map, 1, 2 * SIZE, light.position, samples, n), expected / 2);
    /* A map that leaves a sample out cannot be measured. */
    glm_ortho(-1, 1, -1, 1, 1, 4 * height, projection);
    glm_mat4_mul(projection, map_view, map);
    assert_true(isinf(warp_texel_pixels((const mat4 *)&map, 1, SIZE, light.position, samples, n)));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_n_opt_formula),
        cmocka_unit_test(test_lispsm_turns_uniform_as_view_meets_light),
        cmocka_unit_test(test_psm_light_in_front_is_a_point),
        cmocka_unit_test(test_psm_light_behind_is_inverted),
        cmocka_unit_test(test_psm_light_across_view_is_at_infinity),
        cmocka_unit_test(test_uniform_fit_contains_receivers),
        cmocka_unit_test(test_relevant_casters),
        cmocka_unit_test(test_texel_size_of_orthographic_map_on_plane),
        cmocka_unit_test(test_rectangle_grid_and_its_boxes),
    };
    return cmocka_run_group_tests(tests, street_setup, NULL);
}
