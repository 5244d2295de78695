/* Tests of common/data/motion.c: the camera orbit's frames as they were
 * (yaw about the target), and dolly's walk: eye and target translate
 * together along the view at MOTION_DOLLY_SPEED of their distance a
 * second, turn after MOTION_DOLLY_LEG_S and come back; lamp's one light
 * on its circle, the others where they are, and lamps' every light on
 * its own. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "camera.h"
#include "motion.h"

/* Float rounding of a few operations on coordinates of about 10. */
#define TOLERANCE 1e-4

static const scene_camera base = {.position = {2, 3, 10},
                                  .target = {1, 1, 0},
                                  .up = {0, 1, 0},
                                  .fov_deg = 60,
                                  .near_plane = 0.1f,
                                  .far_plane = 100};

static void assert_vec3(const float *actual, float x, float y, float z) {
    assert_float_equal(actual[0], x, TOLERANCE);
    assert_float_equal(actual[1], y, TOLERANCE);
    assert_float_equal(actual[2], z, TOLERANCE);
}

/* --motion camera is camera_orbit's yaw, bit for bit. */
static void test_camera_is_the_orbit(void **state) {
    (void)state;
    for (int frame = 0; frame < 120; frame += 7) {
        double time = frame / 60.0;
        scene_camera moved, orbit = base;
        motion_camera(MOTION_CAMERA, time, &base, &moved);
        camera_orbit(&orbit, (float)time * MOTION_CAMERA_RAD_PER_S, 0, 1, CAMERA_ORBIT_ANY);
        assert_memory_equal(&moved, &orbit, sizeof moved);
    }
    assert_true(motion_moves_camera(MOTION_CAMERA));
    assert_false(motion_moves_camera(MOTION_LIGHT));
    assert_false(motion_moves_camera(MOTION_STATIC));
}

/* The offset eye and target share at `time`, as a fraction of target -
 * position. */
static void assert_dolly(double time, float along) {
    scene_camera moved;
    motion_camera(MOTION_DOLLY, time, &base, &moved);
    float d[3];
    for (int k = 0; k < 3; k++)
        d[k] = along * (base.target[k] - base.position[k]);
    assert_vec3(moved.position, base.position[0] + d[0], base.position[1] + d[1], base.position[2] + d[2]);
    assert_vec3(moved.target, base.target[0] + d[0], base.target[1] + d[1], base.target[2] + d[2]);
    assert_memory_equal(moved.up, base.up, sizeof moved.up);
    assert_true(moved.fov_deg == base.fov_deg && moved.near_plane == base.near_plane);
}

static void test_dolly_walks_forward_and_back(void **state) {
    (void)state;
    assert_true(motion_moves_camera(MOTION_DOLLY));
    const float leg = (float)MOTION_DOLLY_LEG_S * MOTION_DOLLY_SPEED;
    assert_dolly(0, 0);
    assert_dolly(0.25 * MOTION_DOLLY_LEG_S, 0.25f * leg);
    assert_dolly(MOTION_DOLLY_LEG_S, leg);
    assert_dolly(1.5 * MOTION_DOLLY_LEG_S, 0.5f * leg);
    assert_dolly(2 * MOTION_DOLLY_LEG_S, 0);
    assert_dolly(2.25 * MOTION_DOLLY_LEG_S, 0.25f * leg);
    /* One speed: consecutive frames a constant step apart on each leg. */
    scene_camera a, b, c;
    motion_camera(MOTION_DOLLY, 10 / 60.0, &base, &a);
    motion_camera(MOTION_DOLLY, 11 / 60.0, &base, &b);
    motion_camera(MOTION_DOLLY, 12 / 60.0, &base, &c);
    for (int k = 0; k < 3; k++)
        assert_float_equal(b.position[k] - a.position[k], c.position[k] - b.position[k], TOLERANCE);
}

/* --motion lamp moves light `lamp` alone, on a horizontal circle through
 * its place of MOTION_LAMP_RADIUS_SHARE of its range. */
static void test_lamp_circles_one_light(void **state) {
    (void)state;
    assert_false(motion_moves_camera(MOTION_LAMP));
    const scene_light base_lights[3] = {
        {.type = SCENE_LIGHT_POINT, .position = {0, 5, 0}, .range = 10},
        {.type = SCENE_LIGHT_POINT, .position = {4, 6, -2}, .range = 20},
        {.type = SCENE_LIGHT_POINT, .position = {-3, 5, 1}, .range = 10},
    };
    const float radius = MOTION_LAMP_RADIUS_SHARE * base_lights[1].range;
    scene_light moved[3];
    motion_lights(MOTION_LAMP, 0, base.target, base_lights, 3, 1, moved);
    assert_vec3(moved[1].position, 4, 6, -2);
    bool moves = false;
    for (int frame = 1; frame <= 30; frame++) {
        motion_lights(MOTION_LAMP, frame / 60.0, base.target, base_lights, 3, 1, moved);
        for (int i = 0; i < 3; i += 2)
            assert_memory_equal(moved[i].position, base_lights[i].position, sizeof moved[i].position);
        const float middle[3] = {4 - radius, 6, -2};
        assert_float_equal(moved[1].position[1], 6, TOLERANCE);
        assert_float_equal(glm_vec3_distance(moved[1].position, (float *)middle), radius, TOLERANCE);
        moves |= glm_vec3_distance(moved[1].position, (float *)base_lights[1].position) > radius / 2;
    }
    assert_true(moves);
    /* --motion lamps: every light on its own circle. */
    motion_lights(MOTION_LAMPS, 10 / 60.0, base.target, base_lights, 3, 1, moved);
    for (int i = 0; i < 3; i++) {
        const float middle[3] = {base_lights[i].position[0] - MOTION_LAMP_RADIUS_SHARE * base_lights[i].range,
                                 base_lights[i].position[1], base_lights[i].position[2]};
        assert_float_equal(glm_vec3_distance(moved[i].position, (float *)middle),
                           MOTION_LAMP_RADIUS_SHARE * base_lights[i].range, TOLERANCE);
        assert_true(memcmp(moved[i].position, base_lights[i].position, sizeof moved[i].position) != 0);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_camera_is_the_orbit),
        cmocka_unit_test(test_dolly_walks_forward_and_back),
        cmocka_unit_test(test_lamp_circles_one_light),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
