/* Cascaded shadow maps (demos/cascades.c): the split schemes and a
 * cascade's box as pure math on hand-made views (no GL), then the
 * technique against the ray-traced reference with shadowdiff's fixed
 * rules at 640x360 (each test prints the figures it measured). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "cascades.h"
#include "frustum.h"
#include "path.h"
#include "support.h"

#define LONG_VIEW "assets/scenes/long_view.json"
/* long_view's camera range, and a count of every size the flag allows. */
#define NEAR_PLANE 0.1f
#define FAR_PLANE 600.0f
#define MAX_CASCADES 8
/* Float math on split distances up to 600: relative agreement to this. */
#define RELATIVE 1e-5f
/* A box corner on the texel grid: within this fraction of a texel of it
 * (its light-space coordinates are of order 100, its texels of 0.1). */
#define GRID_TOLERANCE_TEXELS 1e-2
#define SIZE 1024
#define MARGIN_TEXELS 4.0f

/* The shadow maps' bound on the standard scenes (tests/test_shadowmap.c). */
#define STANDARD_MAX_MISCLASSIFIED_PERCENT 0.5
/* long_view at 640x360 and 4 x 1024, measured: practical 0.166 %, log
 * 0.167 %, sdsm 0.071 % (unstabilised 0.019 %), uniform 1.23 %; one
 * shadowmap of 1024 1.96 %, lispsm at 2048 0.031 %. The bounds leave a
 * third for drivers. */
#define LONG_VIEW_MAX_PERCENT 0.25
#define LONG_VIEW_SDSM_MAX_PERCENT 0.1
#define LONG_VIEW_SDSM_FREE_MAX_PERCENT 0.03
#define LONG_VIEW_UNIFORM_MAX_PERCENT 1.6

static void assert_relative(float expected, float actual) {
    assert_true(fabsf(actual - expected) <= RELATIVE * fmaxf(fabsf(expected), 1));
}

/* lambda 0 is the uniform split, 1 the logarithmic, both as their
 * formulas give them; the practical one lies between; the ends are near
 * and far exactly, and the splits rise. */
static void test_split_schemes(void **state) {
    (void)state;
    for (int count = 1; count <= MAX_CASCADES; count++) {
        float uniform[MAX_CASCADES + 1], log_splits[MAX_CASCADES + 1], practical[MAX_CASCADES + 1];
        cascades_splits(count, 0, NEAR_PLANE, FAR_PLANE, uniform);
        cascades_splits(count, 1, NEAR_PLANE, FAR_PLANE, log_splits);
        cascades_splits(count, 0.75f, NEAR_PLANE, FAR_PLANE, practical);
        for (int i = 0; i <= count; i++) {
            double t = (double)i / count;
            assert_relative((float)(NEAR_PLANE + (FAR_PLANE - NEAR_PLANE) * t), uniform[i]);
            assert_relative((float)(NEAR_PLANE * pow(FAR_PLANE / NEAR_PLANE, t)), log_splits[i]);
            assert_true(practical[i] >= log_splits[i] - RELATIVE * log_splits[i]);
            assert_true(practical[i] <= uniform[i] + RELATIVE * uniform[i]);
            if (i > 0)
                assert_true(practical[i] > practical[i - 1] && log_splits[i] > log_splits[i - 1]);
        }
        assert_true(uniform[0] == NEAR_PLANE && log_splits[count] == FAR_PLANE && practical[count] == FAR_PLANE);
    }
}

/* A street: the camera 2 units up looking down -z, slightly down, turned
 * by `yaw` degrees about the vertical; the ground's corners from 3 to 100
 * units ahead are the receiver points. */
static void street_view(float yaw, camera_view *view) {
    float angle = glm_rad(yaw);
    scene_camera camera = {.position = {0, 2, 0},
                           .target = {-10 * sinf(angle), 1.5f, -10 * cosf(angle)},
                           .up = {0, 1, 0},
                           .fov_deg = 60,
                           .near_plane = NEAR_PLANE,
                           .far_plane = FAR_PLANE};
    camera_view_compute(&camera, 16.0f / 9.0f, view);
}

/* sdsm splits the seen range: its ends are the nearest and farthest view
 * depths of the receiver points (within near..far), and every split lies
 * between them. */
static void test_sdsm_within_seen_range(void **state) {
    (void)state;
    static const float ground[4][3] = {{-10, 0, -3}, {10, 0, -3}, {-10, 0, -100}, {10, 0, -100}};
    camera_view view;
    street_view(0, &view);
    float lo, hi, splits[MAX_CASCADES + 1];
    assert_true(cascades_seen_depths(&view, ground, 4, NEAR_PLANE, FAR_PLANE, &lo, &hi));
    fprintf(stderr, "    seen view depths %.4g .. %.4g\n", lo, hi);
    assert_true(lo > 2.9f && lo < 3.1f && hi > 99 && hi < 101);
    cascades_splits(4, 1, lo, hi, splits);
    for (int i = 0; i <= 4; i++)
        assert_true(splits[i] >= lo && splits[i] <= hi);
    /* Points beyond far are seen no farther than far. */
    static const float beyond[2][3] = {{0, 0, -3}, {0, 0, -1000}};
    assert_true(cascades_seen_depths(&view, beyond, 2, NEAR_PLANE, FAR_PLANE, &lo, &hi));
    assert_true(hi == FAR_PLANE);
}

/* Stabilised, a cascade's box has the same size whatever way the camera
 * looks, its corner on whole texels of a light space fixed in the world
 * (so two views' boxes share one texel grid), and it holds its slice;
 * unstabilised, its size follows the view (the test bites). */
static void test_stabilized_box(void **state) {
    (void)state;
    const float direction[3] = {0.5657f, -0.7071f, 0.4243f}, origin[3] = {0, 0, 0};
    const float receivers_lo[3] = {-1e3f, -1e3f, -1e3f}, receivers_hi[3] = {1e3f, 1e3f, 1e3f};
    mat4 light_view;
    frustum_look_along(origin, direction, light_view);
    static const float yaws[] = {0, 7.3f, 45, 130};
    float first_lo[3], first_size = 0, first_free_size = 0;
    bool free_changed = false;
    for (size_t y = 0; y < sizeof yaws / sizeof *yaws; y++) {
        camera_view view;
        street_view(yaws[y], &view);
        float lo[3], hi[3], free_lo[3], free_hi[3];
        cascades_slice_box(&view, light_view, 5, 20, SIZE, MARGIN_TEXELS, true, receivers_lo, receivers_hi, lo, hi);
        cascades_slice_box(&view, light_view, 5, 20, SIZE, MARGIN_TEXELS, false, receivers_lo, receivers_hi, free_lo,
                           free_hi);
        float size = hi[0] - lo[0], texel = size / SIZE;
        fprintf(stderr, "    yaw %5.1f: stabilised box %.6g x %.6g at (%.6g, %.6g) texels; free %.6g x %.6g\n",
                yaws[y], size, hi[1] - lo[1], lo[0] / texel, lo[1] / texel, free_hi[0] - free_lo[0],
                free_hi[1] - free_lo[1]);
        assert_relative(size, hi[1] - lo[1]);
        for (int k = 0; k < 2; k++)
            assert_true(fabs(lo[k] / texel - round(lo[k] / texel)) < GRID_TOLERANCE_TEXELS);
        if (y == 0) {
            glm_vec3_copy(lo, first_lo);
            first_size = size;
            first_free_size = free_hi[0] - free_lo[0];
        }
        assert_relative(first_size, size);
        for (int k = 0; k < 2; k++) {
            double shift = (lo[k] - first_lo[k]) / texel;
            assert_true(fabs(shift - round(shift)) < GRID_TOLERANCE_TEXELS);
        }
        free_changed = free_changed || fabsf(free_hi[0] - free_lo[0] - first_free_size) > 0.01f * first_free_size;
        /* The slice's corners, from the frustum's, lie inside. */
        for (int c = 0; c < 8; c++) {
            float depth = c & 4 ? 20.0f : 5.0f, t = (depth - NEAR_PLANE) / (FAR_PLANE - NEAR_PLANE), p[3], q[3];
            for (int k = 0; k < 3; k++)
                p[k] = view.corners[c & 3][k] + t * (view.corners[(c & 3) | 4][k] - view.corners[c & 3][k]);
            glm_mat4_mulv3(light_view, p, 1, q);
            for (int k = 0; k < 3; k++)
                assert_true(q[k] >= lo[k] - RELATIVE * size && q[k] <= hi[k] + RELATIVE * size);
        }
    }
    assert_true(free_changed);
}

/* Spot (simple) and point light (bunny): shadowmap's fit; directional
 * (teapot): cascades. Within the shadow maps' bound. */
static void test_standard_scenes_within_bound(void **state) {
    (void)state;
    support_standard_scenes_within("cascades", STANDARD_MAX_MISCLASSIFIED_PERCENT);
}

/* long_view, where one map's perspective aliasing is worst: every scheme
 * within its bound, each but uniform misclassifying less than half of
 * uniform's, and every one less than one map of a cascade's size, with at
 * most half its mean error (but uniform's); unstabilised sdsm within the
 * issue's goal, no more than lispsm at one 2048 map. */
static void test_long_view_splits(void **state) {
    (void)state;
    shadowdiff_result one_map = support_measure("shadowmap", LONG_VIEW, "", "--map-size 1024", "long_view_1024");
    shadowdiff_result uniform = support_measure("cascades", LONG_VIEW, "", "--splits uniform", "long_view_uniform");
    assert_true(uniform.misclassified_percent <= LONG_VIEW_UNIFORM_MAX_PERCENT);
    assert_true(uniform.misclassified_percent < one_map.misclassified_percent);
    shadowdiff_result lispsm =
        support_measure("psm", LONG_VIEW, "", "--warp lispsm --map-size 2048", "long_view_lispsm_2048");
    static const struct {
        const char *flags, *name;
        double bound;
    } schemes[] = {{"", "long_view_practical", LONG_VIEW_MAX_PERCENT},
                   {"--splits log", "long_view_log", LONG_VIEW_MAX_PERCENT},
                   {"--splits sdsm", "long_view_sdsm", LONG_VIEW_SDSM_MAX_PERCENT},
                   {"--splits sdsm --no-stabilize", "long_view_sdsm_free", LONG_VIEW_SDSM_FREE_MAX_PERCENT}};
    for (size_t i = 0; i < sizeof schemes / sizeof *schemes; i++) {
        shadowdiff_result r = support_measure("cascades", LONG_VIEW, "", schemes[i].flags, schemes[i].name);
        assert_true(r.misclassified_percent <= schemes[i].bound);
        assert_true(r.misclassified_percent < 0.5 * uniform.misclassified_percent);
        assert_true(r.mean_abs_error <= 0.5 * one_map.mean_abs_error);
        if (strstr(schemes[i].flags, "--no-stabilize"))
            assert_true(r.misclassified_percent <= lispsm.misclassified_percent);
    }
}

/* A camera turn, for the stabilisation test: long_view's camera turned
 * by TURN_DEG about the vertical through its eye, dumped at the accuracy
 * tests' 640x360 (DUMP_ASPECT) with one nearest test a pixel (no Poisson
 * rotation, no dithered band: per pixel, only the map decides), at 256 a
 * cascade, so that a texel spans several pixels. A ground point of the
 * turned view compares with the unturned view's pixel whose point lies
 * within MATCH_PIXELS of a pixel's footprint of it. Measured at 2, 4 and 7
 * degrees (MATCH_PIXELS 0.75): 35, 25, 18 points decided apart
 * stabilised, 136, 164, 143 unstabilised; at 4 degrees and 0.3, 7 against
 * 52 of 8297. */
#define TURN_DEG 4.0
#define DUMP_ASPECT (640.0f / 360.0f)
#define DUMP_FLAGS "--backend egl --filter none --no-blend --map-size 256"
#define MAX_SCENE_BYTES (1 << 20)
#define MATCH_PIXELS 0.3f
#define OUT_DIR "out/test/cascades"
#define STABILIZED_GAIN 3
#define MIN_MATCHED 5000

/* OUT_DIR/NAME.json: long_view with its camera turned by `degrees`; the
 * camera as camera_view_compute sees it in *camera. */
static void write_turned_scene(double degrees, const char *name, char *path, size_t size, scene_camera *camera) {
    char *text = path_read_text(LONG_VIEW, MAX_SCENE_BYTES, NULL);
    assert_non_null(text);
    cJSON *root = cJSON_Parse(text);
    free(text);
    assert_non_null(root);
    cJSON *json_camera = cJSON_GetObjectItemCaseSensitive(root, "camera");
    cJSON *position = cJSON_GetObjectItemCaseSensitive(json_camera, "position");
    cJSON *target = cJSON_GetObjectItemCaseSensitive(json_camera, "target");
    double p[3], t[3], a = degrees * GLM_PI / 180;
    for (int k = 0; k < 3; k++) {
        p[k] = cJSON_GetArrayItem(position, k)->valuedouble;
        t[k] = cJSON_GetArrayItem(target, k)->valuedouble;
    }
    double dx = t[0] - p[0], dz = t[2] - p[2];
    t[0] = p[0] + dx * cos(a) + dz * sin(a);
    t[2] = p[2] - dx * sin(a) + dz * cos(a);
    for (int k = 0; k < 3; k++) {
        cJSON_SetNumberValue(cJSON_GetArrayItem(target, k), t[k]);
        camera->position[k] = (float)p[k];
        camera->target[k] = (float)t[k];
    }
    camera->up[0] = camera->up[2] = 0;
    camera->up[1] = 1;
    camera->fov_deg = (float)cJSON_GetObjectItemCaseSensitive(json_camera, "fov")->valuedouble;
    camera->near_plane = (float)cJSON_GetObjectItemCaseSensitive(json_camera, "near")->valuedouble;
    camera->far_plane = (float)cJSON_GetObjectItemCaseSensitive(json_camera, "far")->valuedouble;
    support_write_json(root, OUT_DIR, name, path, size);
    cJSON_Delete(root);
}

/* Of the turned view's ground pixels facing the light, those whose point
 * the unturned view also sees (a pixel within MATCH_PIXELS of its
 * footprint away), and of those, how many the two dumps decide apart. */
static void turned_decisions(const dump_frame *before, const dump_frame *after, const camera_view *before_view,
                             long *matched, long *differ) {
    *matched = *differ = 0;
    for (int y = 0; y < after->height; y++) {
        for (int x = 0; x < after->width; x++) {
            long i = (long)y * after->width + x;
            if (after->ids[i] != 0 || after->visibility[i] < 0)
                continue;
            vec4 p = {after->position[3 * i], after->position[3 * i + 1], after->position[3 * i + 2], 1}, clip;
            glm_mat4_mulv((vec4 *)before_view->view_projection, p, clip);
            int bx = (int)floorf((clip[0] / clip[3] * 0.5f + 0.5f) * (float)before->width);
            int by = (int)floorf((0.5f - clip[1] / clip[3] * 0.5f) * (float)before->height); /* top row first */
            if (clip[3] <= 0 || bx < 0 || by < 0 || bx >= before->width || by >= before->height)
                continue;
            long j = (long)by * before->width + bx;
            /* A pixel's footprint there: the distance to the next pixel's point. */
            long k = x + 1 < after->width ? i + 1 : i - 1;
            float footprint = glm_vec3_distance(&after->position[3 * i], &after->position[3 * k]);
            if (before->ids[j] != 0 || before->visibility[j] < 0 ||
                glm_vec3_distance(&after->position[3 * i], &before->position[3 * j]) > MATCH_PIXELS * footprint)
                continue;
            (*matched)++;
            *differ += (after->visibility[i] >= 0.5f) != (before->visibility[j] >= 0.5f);
        }
    }
}

/* Stabilisation: a still receiver's shadow edges stay where they were
 * while the camera turns, so the turned view decides the ground points
 * both views see as the unturned one did, but where the two views'
 * points straddle an edge (the points are not the same, only within a
 * third of a pixel: a turn moves every pixel's ray, so no test can ask
 * for identical decisions at identical points); unstabilised, every
 * cascade's box moves with the view and its edges crawl across the
 * ground by up to half a texel: more than STABILIZED_GAIN times as many
 * decisions differ. */
static void test_stabilization_holds_edges_under_a_turn(void **state) {
    (void)state;
    char before_scene[512], after_scene[512];
    scene_camera before_camera, after_camera;
    write_turned_scene(0, "turn_before", before_scene, sizeof before_scene, &before_camera);
    write_turned_scene(TURN_DEG, "turn_after", after_scene, sizeof after_scene, &after_camera);
    camera_view before_view;
    camera_view_compute(&before_camera, DUMP_ASPECT, &before_view);
    static const char *const modes[] = {"", "--no-stabilize"};
    long differ[2], matched[2];
    for (int m = 0; m < 2; m++) {
        char flags[256], before_dir[256], after_dir[256];
        snprintf(flags, sizeof flags, DUMP_FLAGS " %s", modes[m]);
        snprintf(before_dir, sizeof before_dir, OUT_DIR "/turn_before_%d", m);
        snprintf(after_dir, sizeof after_dir, OUT_DIR "/turn_after_%d", m);
        assert_int_equal(support_dump("cascades", before_scene, flags, before_dir), 0);
        assert_int_equal(support_dump("cascades", after_scene, flags, after_dir), 0);
        dump_frame before, after;
        assert_true(dump_read(&before, before_dir));
        assert_true(dump_read(&after, after_dir));
        turned_decisions(&before, &after, &before_view, &matched[m], &differ[m]);
        fprintf(stderr, "    %s: %ld of %ld ground points seen by both views decided apart\n",
                m == 0 ? "stabilised" : "unstabilised", differ[m], matched[m]);
        dump_frame_free(&before);
        dump_frame_free(&after);
    }
    assert_true(matched[0] > MIN_MATCHED && matched[1] > MIN_MATCHED);
    assert_true(differ[0] * STABILIZED_GAIN < differ[1]);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_split_schemes),
        cmocka_unit_test(test_sdsm_within_seen_range),
        cmocka_unit_test(test_stabilized_box),
        cmocka_unit_test(test_standard_scenes_within_bound),
        cmocka_unit_test(test_long_view_splits),
        cmocka_unit_test(test_stabilization_holds_edges_under_a_turn),
    };
    return cmocka_run_group_tests_name("cascaded shadow maps", tests, NULL, NULL);
}
