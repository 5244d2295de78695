/* Tests that the GL techniques hold at extreme camera near/far ranges
 * (as the stress suite's near/far cases push them), or refuse them at
 * load with one line; each measuring test prints what it measured.
 *
 *   corners     the camera's frustum corners (camera.h), computed in
 *               double from the camera beyond CAMERA_INVERSE_MAX_RATIO,
 *               match the inverted view-projection there, and stay finite
 *               for any finite positive near < far, where the inverse is
 *               NaN.
 *   projection  beyond CAMERA_INFINITE_FAR_RATIO the projection is the
 *               infinite one; below it, glm_perspective's bit for bit.
 *   scenes      every scene file that loads passes the depth check with
 *               the standard 24-bit depth alone.
 *   mode        the depth a range takes: standard, reversed, or refused
 *               in one line where the context has no clip control.
 *   range       one table of cases: simple.json with the camera's near
 *               and far replaced (written under OUT_DIR), or the scene
 *               scaled by 1e30, through every shadow technique against
 *               the reference: within its bound, or refused with exit 1
 *               and one line naming the scene file. near/far 1e9 (and
 *               near 1e-30) take reversed depth in float (depth.h) and
 *               measure as near 0.1 does.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <cglm/cglm.h>
#include <cjson/cJSON.h>
#include <dirent.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "frustum.h"
#include "support.h"

#define SCENE "assets/scenes/simple.json"
#define SCALED_SCENE "tests/data/range_scaled_1e30.json"
#define OUT_DIR "out/test/range"
#define SIZE "--size 320x180"
#define ASPECT (16.0f / 9.0f)
#define EXIT_RUNTIME 1
/* Corners from the inverse and from the camera agree within this share
 * of their distance from the eye: the inverse's rounding, up to
 * CAMERA_INVERSE_MAX_RATIO float ulps (6e-4). */
#define CORNER_TOLERANCE 1e-3f
#define EYE_ROUNDING_ULPS 4

/* ---- corners and projection, in process ---- */

static scene_camera simple_camera(float near_plane, float far_plane) {
    return (scene_camera){.position = {7.5f, 6, 9.5f},
                          .target = {0, 0.6f, 0},
                          .up = {0, 1, 0},
                          .fov_deg = 45,
                          .near_plane = near_plane,
                          .far_plane = far_plane};
}

/* Just beyond CAMERA_INVERSE_MAX_RATIO, where the corners switch to the
 * camera's, they agree with the inverse's: no jump. */
static void test_corners_match_the_inverse(void **state) {
    (void)state;
    camera_view v;
    scene_camera c = simple_camera(0.1f, 0.1f * (float)CAMERA_INVERSE_MAX_RATIO * (1 + 1e-3f));
    camera_view_compute(&c, ASPECT, &v);
    float inverse[8][3];
    frustum_corners(v.view_projection, inverse);
    for (int k = 0; k < 8; k++) {
        float distance = glm_vec3_distance(inverse[k], v.eye);
        assert_true(glm_vec3_distance(inverse[k], v.corners[k]) <= CORNER_TOLERANCE * distance);
    }
}

static bool finite_corners(const camera_view *v) {
    for (int k = 0; k < 8; k++)
        for (int axis = 0; axis < 3; axis++)
            if (!isfinite(v->corners[k][axis]))
                return false;
    return true;
}

/* Near 1e-30 to 10, far up to FLT_MAX: no corner NaN or infinite, the
 * near corners at near along the view, the far ones beyond the scene. */
static void test_corners_finite_at_any_range(void **state) {
    (void)state;
    static const float nears[] = {1e-30f, 1e-6f, 1e-4f, 0.1f, 10};
    static const float fars[] = {20, 100, 1e5f, 1e7f, 1e30f, FLT_MAX};
    int inverse_nan = 0;
    for (size_t i = 0; i < sizeof nears / sizeof *nears; i++) {
        for (size_t j = 0; j < sizeof fars / sizeof *fars; j++) {
            camera_view v;
            scene_camera c = simple_camera(nears[i], fars[j]);
            camera_view_compute(&c, ASPECT, &v);
            assert_true(finite_corners(&v));
            vec3 forward, to_near, to_far;
            glm_vec3_sub(c.target, c.position, forward);
            glm_vec3_normalize(forward);
            glm_vec3_sub(v.corners[0], v.eye, to_near);
            glm_vec3_sub(v.corners[4], v.eye, to_far);
            /* Within rounding at the eye's coordinates: a 1e-30 step from
             * the eye is the eye itself in float. */
            float rounding = EYE_ROUNDING_ULPS * FLT_EPSILON * glm_vec3_norm(v.eye);
            assert_true(fabsf(glm_vec3_dot(to_near, forward) - nears[i]) <= nears[i] * CORNER_TOLERANCE + rounding);
            assert_true(glm_vec3_dot(to_far, forward) >= fminf(fars[j], 1e20f) * (1 - CORNER_TOLERANCE));
            float inverse[8][3];
            frustum_corners(v.view_projection, inverse);
            inverse_nan += !isfinite(inverse[7][0]);
        }
    }
    printf("    inverted view-projection: far corners not finite in %d of %zu ranges, the camera's in none\n",
           inverse_nan, sizeof nears / sizeof *nears * (sizeof fars / sizeof *fars));
}

static void test_projection_infinite_beyond_the_ratio(void **state) {
    (void)state;
    camera_view v;
    mat4 expected;
    scene_camera c = simple_camera(0.1f, 100);
    camera_view_compute(&c, ASPECT, &v);
    glm_perspective(glm_rad(45), ASPECT, 0.1f, 100, expected);
    assert_memory_equal(v.projection, expected, sizeof expected);
    c = simple_camera(10, FLT_MAX);
    camera_view_compute(&c, ASPECT, &v);
    assert_float_equal(v.projection[2][2], -1, 0);
    assert_float_equal(v.projection[3][2], -20, 0);
    for (int k = 0; k < 16; k++)
        assert_true(isfinite(v.view_projection[k / 4][k % 4]));
}

/* Every scene file the programs or tests load passes the check (the
 * standard scenes included: long_view needs 1.08e-4 of its size). */
static void test_scenes_pass_the_depth_check(void **state) {
    (void)state;
    static const char *const dirs[] = {"assets/scenes", "tests/data"};
    int checked = 0;
    for (size_t d = 0; d < sizeof dirs / sizeof *dirs; d++) {
        DIR *dir = opendir(dirs[d]);
        assert_non_null(dir);
        for (struct dirent *e; (e = readdir(dir));) {
            size_t length = strlen(e->d_name);
            char path[512];
            if (length < 5 || strcmp(e->d_name + length - 5, ".json") != 0)
                continue;
            snprintf(path, sizeof path, "%s/%s", dirs[d], e->d_name);
            if (strcmp(path, SCALED_SCENE) == 0)
                continue; /* refused on purpose (test_ranges) */
            scene s;
            support_capture_stderr();
            bool loaded = scene_load(&s, path);
            support_release_stderr();
            if (!loaded)
                continue;                             /* the files that test refusals */
            if (!camera_check_depth(&s, path, false)) /* the standard depth: every file keeps it */
                fail_msg("%s: refused", path);
            scene_free(&s);
            checked++;
        }
        closedir(dir);
    }
    printf("    %d scene files pass\n", checked);
}

/* The depth each range takes: the standard one where its 24 bits do,
 * reversed depth beyond, and without ARB_clip_control the same range
 * refused in one line that names the file and the missing extension. */
static void test_depth_mode_by_range(void **state) {
    (void)state;
    scene s;
    assert_true(scene_load(&s, SCENE));
    s.camera.near_plane = 0.1f;
    assert_true(camera_check_depth(&s, SCENE, true));
    assert_false(s.camera.reversed_depth);
    s.camera.near_plane = 1e-4f;
    s.camera.far_plane = 1e5f;
    assert_true(camera_check_depth(&s, SCENE, true));
    assert_true(s.camera.reversed_depth);
    support_capture_stderr();
    bool accepted = camera_check_depth(&s, SCENE, false);
    const char *err = support_release_stderr();
    printf("    without clip control: %s", err);
    assert_false(accepted);
    assert_int_equal(support_count_lines(err), 1);
    assert_non_null(strstr(err, SCENE ": camera: "));
    assert_non_null(strstr(err, "ARB_clip_control"));
    scene_free(&s);
}

/* ---- the techniques at each range ---- */

typedef struct range_technique {
    const char *program;
    const char *receiver; /* compared on that object alone; NULL: every object */
    double max_misclassified_percent;
} range_technique;

static const range_technique range_techniques[] = {
    {"planar", "ground", 0.05},
    {"shadowmap", NULL, 0.5},
    {"psm", NULL, 0.5},
    {"volumes", NULL, 0.01},
};

typedef struct range_case {
    const char *name;
    float near_plane, far_plane; /* 0: the scene file's own (SCALED_SCENE) */
    bool refused;                /* every technique exits 1 with one line */
} range_case;

static const range_case range_cases[] = {
    {"near 0.1 far 100", 0.1f, 100, false},
    {"near 0.015 far 1e5", 0.015f, 1e5f, false}, /* depth step 0.97 of the bound */
    {"near 0.1 far 1e7", 0.1f, 1e7f, false},
    {"near 0.1 far 1e30", 0.1f, 1e30f, false},
    {"near 1 far 3e38", 1, 3e38f, false},
    {"near 1e-4 far 1e5", 1e-4f, 1e5f, false},
    {"near 1e-6 far 1e3", 1e-6f, 1e3f, false},
    {"near 1e-30 far 100", 1e-30f, 100, false},
    {"scaled 1e30", 0, 0, true},
};

/* OUT_DIR/range_N.json: `source` with the case's near and far. */
static void write_case_scene(const char *source, const range_case *c, int index, char *path, size_t size) {
    cJSON *root = support_read_json(source);
    cJSON *camera = cJSON_GetObjectItemCaseSensitive(root, "camera");
    cJSON_SetNumberValue(cJSON_GetObjectItemCaseSensitive(camera, "near"), c->near_plane);
    cJSON_SetNumberValue(cJSON_GetObjectItemCaseSensitive(camera, "far"), c->far_plane);
    char name[64];
    snprintf(name, sizeof name, "range_%d", index);
    support_write_json(root, OUT_DIR, name, path, size);
    cJSON_Delete(root);
}

static void check_refused(const range_technique *t, const char *scene) {
    char command[1024], err[4096];
    snprintf(command, sizeof command, "%s %s --scene %s --frames 1", support_program(t->program), SIZE, scene);
    int status = support_run(command, err, sizeof err);
    printf("      %-9s exit %d, %d line\n", t->program, status, support_count_lines(err));
    assert_int_equal(status, EXIT_RUNTIME);
    assert_int_equal(support_count_lines(err), 1);
    assert_non_null(strstr(err, scene));
    assert_non_null(strstr(err, ": camera: "));
}

static void check_within(const range_technique *t, const char *scene, const char *reference_dir, int index) {
    char dir[256];
    snprintf(dir, sizeof dir, "%s/%s_%d", OUT_DIR, t->program, index);
    assert_int_equal(support_dump(t->program, scene, SIZE, dir), 0);
    dump_frame reference, test;
    assert_true(dump_read(&reference, reference_dir));
    assert_true(dump_read(&test, dir));
    shadowdiff_result r;
    const shadowdiff_settings settings = {.receiver = t->receiver};
    bool compared = shadowdiff_compare(&reference, &test, &settings, &r, NULL);
    dump_frame_free(&reference);
    dump_frame_free(&test);
    printf("      %-9s %ld compared, misclassified %.4f %% (bound %.2f %%)\n", t->program, r.compared,
           r.misclassified_percent, t->max_misclassified_percent);
    assert_true(compared);
    assert_true(r.misclassified_percent <= t->max_misclassified_percent);
}

static void test_ranges(void **state) {
    (void)state;
    for (size_t i = 0; i < sizeof range_cases / sizeof *range_cases; i++) {
        const range_case *c = &range_cases[i];
        char scene[256], reference_dir[256];
        if (c->near_plane > 0)
            write_case_scene(SCENE, c, (int)i, scene, sizeof scene);
        else
            snprintf(scene, sizeof scene, "%s", SCALED_SCENE);
        printf("    %s (%s): %s\n", c->name, scene, c->refused ? "refused" : "within bounds");
        if (!c->refused) {
            snprintf(reference_dir, sizeof reference_dir, "%s/reference_%zu", OUT_DIR, i);
            assert_int_equal(support_dump("raytrace", scene, SIZE, reference_dir), 0);
        }
        for (size_t t = 0; t < sizeof range_techniques / sizeof *range_techniques; t++) {
            if (c->refused)
                check_refused(&range_techniques[t], scene);
            else
                check_within(&range_techniques[t], scene, reference_dir, (int)i);
        }
    }
}

/* A far plane far beyond the scene changes no map: long_view (whose
 * uniform map exceeds the bound at this size on its own, perspective
 * aliasing) misclassifies as much with far 1e7 as with its own 600. Past
 * far / near 1e7 the inverse view-projection loses the far plane, so the
 * map measure (warp_samples) must not take its rays from it: the automatic
 * size and psm's choice would fall back. */
#define RANGE_LONG_VIEW "assets/scenes/long_view.json"
#define RANGE_SAME_PERCENT 0.01
static void test_far_plane_changes_no_map(void **state) {
    (void)state;
    static const char *const programs[] = {"shadowmap", "psm"};
    const range_case far = {"long_view far 1e7", 0.1f, 1e7f, false};
    char scene[256];
    write_case_scene(RANGE_LONG_VIEW, &far, (int)(sizeof range_cases / sizeof *range_cases), scene, sizeof scene);
    for (size_t p = 0; p < sizeof programs / sizeof *programs; p++) {
        char name[64];
        snprintf(name, sizeof name, "range_long_view_%s", programs[p]);
        shadowdiff_result own = support_measure(programs[p], RANGE_LONG_VIEW, SIZE, "", name);
        snprintf(name, sizeof name, "range_long_view_far_%s", programs[p]);
        shadowdiff_result farther = support_measure(programs[p], scene, SIZE, "", name);
        printf("    %s: misclassified %.4f %% with far 600, %.4f %% with far 1e7\n", programs[p],
               own.misclassified_percent, farther.misclassified_percent);
        assert_true(fabs(own.misclassified_percent - farther.misclassified_percent) <= RANGE_SAME_PERCENT);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_corners_match_the_inverse),
        cmocka_unit_test(test_corners_finite_at_any_range),
        cmocka_unit_test(test_projection_infinite_beyond_the_ratio),
        cmocka_unit_test(test_scenes_pass_the_depth_check),
        cmocka_unit_test(test_depth_mode_by_range),
        cmocka_unit_test(test_ranges),
        cmocka_unit_test(test_far_plane_changes_no_map),
    };
    return cmocka_run_group_tests_name("camera ranges", tests, NULL, NULL);
}
