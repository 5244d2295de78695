/* Unit tests: the planar shadow matrix and the camera helpers. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <cglm/cglm.h>
#include "camera.h"
#include "planar.h"

#define EPS 1e-4f

/* Applies S and divides by w: where v's shadow falls. */
static void shadow_point(const float plane[4], const float light[4], const float v[3], float out[3]) {
    mat4 s;
    vec4 p = {v[0], v[1], v[2], 1}, q;
    planar_shadow_matrix(plane, light, s);
    glm_mat4_mulv(s, p, q);
    assert_true(fabsf(q[3]) > 1e-6f);
    glm_vec3_scale(q, 1.0f / q[3], out);
}

static void assert_on_plane(const float plane[4], const float x[3]) {
    assert_true(fabsf(glm_vec3_dot((float *)plane, (float *)x) + plane[3]) < EPS);
}

static const float test_points[][3] = {{0.5f, 1, 0.25f}, {-2, 3, 1}, {1.5f, 0.1f, -3}, {0, 4.5f, 0}};

static void test_point_light_projects_along_rays(void **state) {
    (void)state;
    /* A tilted plane through (0,-1,0), so the test is not axis-aligned. */
    vec3 n = {0.2f, 1, -0.1f};
    glm_vec3_normalize(n);
    const float plane[4] = {n[0], n[1], n[2], n[1] * 1.0f};
    const float light[4] = {1, 6, 2, 1};
    for (size_t i = 0; i < sizeof test_points / sizeof *test_points; i++) {
        float x[3], to_v[3], to_x[3], cross[3];
        shadow_point(plane, light, test_points[i], x);
        assert_on_plane(plane, x);
        /* x lies on the line from the light through v, beyond v. */
        glm_vec3_sub((float *)test_points[i], (float *)light, to_v);
        glm_vec3_sub(x, (float *)light, to_x);
        glm_vec3_cross(to_v, to_x, cross);
        assert_true(glm_vec3_norm(cross) < EPS * glm_vec3_norm(to_x));
        assert_true(glm_vec3_dot(to_v, to_x) > 0);
        assert_true(glm_vec3_norm(to_x) >= glm_vec3_norm(to_v) - EPS);
    }
}

static void test_directional_light_projects_along_direction(void **state) {
    (void)state;
    const float plane[4] = {0, 1, 0, 0};
    vec3 towards = {-0.45f, 1, 0.35f};
    glm_vec3_normalize(towards);
    const float light[4] = {towards[0], towards[1], towards[2], 0};
    for (size_t i = 0; i < sizeof test_points / sizeof *test_points; i++) {
        float x[3], moved[3], cross[3];
        shadow_point(plane, light, test_points[i], x);
        assert_on_plane(plane, x);
        glm_vec3_sub((float *)test_points[i], x, moved);
        glm_vec3_cross(moved, towards, cross);
        assert_true(glm_vec3_norm(cross) < EPS);
        /* The shadow lies away from the light: v - x points towards it. */
        assert_true(glm_vec3_dot(moved, towards) >= 0);
    }
}

static void test_point_on_plane_is_its_own_shadow(void **state) {
    (void)state;
    const float plane[4] = {0, 1, 0, 0}, light[4] = {3, 5, -1, 1}, v[3] = {2, 0, 7};
    float x[3];
    shadow_point(plane, light, v, x);
    assert_true(glm_vec3_distance((float *)v, x) < EPS);
}

static void test_receiver_plane_follows_model_matrix(void **state) {
    (void)state;
    scene_object o = {0};
    mat4 m;
    glm_translate_make(m, (vec3){1, 2, 3});
    glm_rotate_x(m, glm_rad(90), m); /* local +Y becomes world +Z */
    glm_scale(m, (vec3){4, 4, 4});
    glm_mat4_copy(m, o.model);
    float plane[4];
    planar_receiver_plane(&o, plane);
    assert_true(fabsf(plane[0]) < EPS && fabsf(plane[1]) < EPS && fabsf(plane[2] - 1) < EPS);
    assert_true(fabsf(plane[3] + 3) < EPS); /* z = 3 */
}

static void test_camera_view_centres_target(void **state) {
    (void)state;
    const scene_camera c = {.position = {4, 3, 5}, .target = {0, 1, 0}, .up = {0, 1, 0},
                            .fov_deg = 45, .near_plane = 0.1f, .far_plane = 50};
    camera_view v;
    camera_view_compute(&c, 16.0f / 9.0f, &v);
    vec4 target = {0, 1, 0, 1}, clip;
    glm_mat4_mulv(v.view_projection, target, clip);
    assert_true(fabsf(clip[0] / clip[3]) < EPS && fabsf(clip[1] / clip[3]) < EPS);
    /* A point on the near plane along the view axis has depth -1. */
    vec3 dir, near_point;
    glm_vec3_sub((float *)c.target, (float *)c.position, dir);
    glm_vec3_normalize(dir);
    glm_vec3_scale(dir, c.near_plane, dir);
    glm_vec3_add((float *)c.position, dir, near_point);
    glm_mat4_mulv(v.view_projection, (vec4){near_point[0], near_point[1], near_point[2], 1}, clip);
    assert_true(fabsf(clip[2] / clip[3] + 1) < 1e-3f);
}

static void test_camera_orbit_keeps_distance_and_stops_at_pole(void **state) {
    (void)state;
    scene_camera c = {.position = {0, 0, 10}, .target = {0, 0, 0}, .up = {0, 1, 0}};
    camera_orbit(&c, glm_rad(90), 0, 1);
    assert_true(fabsf(glm_vec3_norm(c.position) - 10) < EPS);
    assert_true(fabsf(c.position[0] - 10) < 1e-3f); /* turned about +Y */
    camera_orbit(&c, 0, glm_rad(200), 0.5f);    /* far past the pole */
    assert_true(fabsf(glm_vec3_norm(c.position) - 5) < EPS);
    float elevation = glm_deg(asinf(c.position[1] / 5));
    assert_true(elevation > 88.9f && elevation < 89.1f);
}

static void test_light_orbit_turns_direction_with_position(void **state) {
    (void)state;
    scene_light l = {.type = SCENE_LIGHT_SPOT, .position = {5, 5, 0}, .direction = {-1, -1, 0}};
    glm_vec3_normalize(l.direction);
    const float centre[3] = {0, 0, 0};
    camera_orbit_light(&l, centre, glm_rad(90), 0);
    /* Still aimed at the centre. */
    vec3 to_centre;
    glm_vec3_negate_to(l.position, to_centre);
    glm_vec3_normalize(to_centre);
    assert_true(glm_vec3_distance(to_centre, l.direction) < EPS);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_point_light_projects_along_rays),
        cmocka_unit_test(test_directional_light_projects_along_direction),
        cmocka_unit_test(test_point_on_plane_is_its_own_shadow),
        cmocka_unit_test(test_receiver_plane_follows_model_matrix),
        cmocka_unit_test(test_camera_view_centres_target),
        cmocka_unit_test(test_camera_orbit_keeps_distance_and_stops_at_pole),
        cmocka_unit_test(test_light_orbit_turns_direction_with_position),
    };
    return cmocka_run_group_tests_name("planar and camera", tests, NULL, NULL);
}
