/* Tests of common/measure/truth.c, the background reference of compare
 * mode: its row order, that a finished frame is raytrace_render's byte for
 * byte, that a newer request replaces an older one mid-trace, that an
 * equal request does not restart, that forgetting and stopping never hang
 * (and leak nothing under ASan), and that a failing trace says so; and of
 * baked truths (truth_bake.c, what the web page shows): read back, they
 * decide every pixel as the traced truth, they are found for their own
 * view only, a truth started on them answers at once, and a damaged one
 * is said. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "shadowdiff.h"
#include "support.h"
#include "truth.h"
#include "truth_bake.h"

#define SCENE "assets/scenes/simple.json"
#define WIDTH 96
#define HEIGHT 54
/* Baked truths' folders. */
#define BAKED "out/test/truth/baked"
#define DAMAGED "out/test/truth/damaged"
/* An area light's scene: visibilities between 0 and 1. */
#define SOFT_SCENE "assets/scenes/soft_table.json"
/* How far a baked truth's position may be from the traced one's, as a
 * share of its depth: the depth's rounding (2^-16) and the pixel's ray
 * through float corners. */
#define BAKED_POSITION_TOLERANCE (0x1p-16 + 1e-6)
/* Tall enough for several bands and every pass. */
#define ORDER_HEIGHT 77

static const raytrace_settings settings = {.scene_name = SCENE};

static bool same_frame(const dump_frame *a, const dump_frame *b) {
    size_t n = (size_t)a->width * (size_t)a->height;
    return a->width == b->width && a->height == b->height && a->light_index == b->light_index &&
           memcmp(a->light, b->light, sizeof a->light) == 0 &&
           memcmp(a->visibility, b->visibility, n * sizeof *a->visibility) == 0 &&
           memcmp(a->depth, b->depth, n * sizeof *a->depth) == 0 && memcmp(a->ids, b->ids, n * sizeof *a->ids) == 0 &&
           memcmp(a->normal, b->normal, 3 * n * sizeof *a->normal) == 0 &&
           memcmp(a->position, b->position, 3 * n * sizeof *a->position) == 0 &&
           memcmp(a->color, b->color, 4 * n) == 0;
}

/* The truth of `s` once finished equals the reference's frame. */
static void expect_reference(truth *t, truth_frame *shown, const scene *s, int light) {
    truth_wait(t);
    truth_take(t, shown);
    assert_true(shown->complete);
    assert_false(shown->failed);
    assert_int_equal(shown->rows, HEIGHT);
    dump_frame reference;
    assert_true(raytrace_render(s, WIDTH, HEIGHT, light, &settings, &reference));
    assert_true(same_frame(&reference, &shown->dump));
    dump_frame_free(&reference);
}

static void test_row_order_is_every_row_once_coarse_first(void **state) {
    (void)state;
    int order[ORDER_HEIGHT], seen[ORDER_HEIGHT] = {0};
    truth_row_order(ORDER_HEIGHT, order);
    for (int k = 0; k < ORDER_HEIGHT; k++) {
        assert_in_range(order[k], 0, ORDER_HEIGHT - 1);
        seen[order[k]]++;
    }
    for (int y = 0; y < ORDER_HEIGHT; y++)
        assert_int_equal(seen[y], 1);
    /* The first pass spans the picture every 16th row, then the rows
     * halfway between. */
    int stride = 1 << (TRUTH_PASSES - 1), first_pass = (ORDER_HEIGHT + stride - 1) / stride;
    for (int k = 0; k < first_pass; k++)
        assert_int_equal(order[k], k * stride);
    assert_int_equal(order[first_pass], stride / 2);
}

/* Each test's truth, started on the scene. */
static struct {
    scene scene;
    truth truth;
    truth_frame shown;
} fixture;

static int start_truth(void **state) {
    (void)state;
    fixture.shown = (truth_frame){0};
    return scene_load(&fixture.scene, SCENE) && truth_start(&fixture.truth, WIDTH, HEIGHT, &settings, NULL) ? 0 : -1;
}

static int stop_truth(void **state) {
    (void)state;
    truth_frame_free(&fixture.shown);
    truth_stop(&fixture.truth);
    scene_free(&fixture.scene);
    return 0;
}

static void test_finished_truth_is_the_reference(void **state) {
    (void)state;
    truth *t = &fixture.truth;
    truth_request(t, &fixture.scene, 0);
    expect_reference(t, &fixture.shown, &fixture.scene, 0);
    long request = fixture.shown.request;
    /* The same view again: nothing restarts. */
    truth_request(t, &fixture.scene, 0);
    truth_wait(t);
    assert_false(truth_take(t, &fixture.shown));
    assert_int_equal(fixture.shown.request, request);
}

static void test_newer_request_replaces_older(void **state) {
    (void)state;
    truth *t = &fixture.truth;
    truth_request(t, &fixture.scene, 0);
    truth_take(t, &fixture.shown);
    scene moved = fixture.scene;
    moved.camera.position[0] += 1.5f;
    moved.lights[0].direction[2] += 0.25f;
    truth_request(t, &moved, 0);
    expect_reference(t, &fixture.shown, &moved, 0);
    /* Forgotten, the same view starts afresh. */
    long request = fixture.shown.request;
    truth_forget(t);
    truth_request(t, &moved, 0);
    expect_reference(t, &fixture.shown, &moved, 0);
    assert_true(fixture.shown.request > request);
}

static void test_stop_while_tracing(void **state) {
    (void)state;
    truth_stop(&fixture.truth);
    assert_true(truth_start(&fixture.truth, WIDTH * 8, HEIGHT * 8, &settings, NULL));
    truth_request(&fixture.truth, &fixture.scene, 0);
    truth_stop(&fixture.truth);
    truth_stop(&fixture.truth); /* twice is harmless */
}

static void test_failed_trace_is_reported(void **state) {
    (void)state;
    truth *t = &fixture.truth;
    scene broken = fixture.scene;
    memcpy(broken.camera.target, broken.camera.position, sizeof broken.camera.target); /* no view direction */
    support_capture_stderr();
    truth_request(t, &broken, 0);
    truth_wait(t);
    const char *said = support_release_stderr();
    truth_take(t, &fixture.shown);
    assert_true(fixture.shown.failed);
    assert_false(fixture.shown.complete);
    assert_non_null(strstr(said, "raytrace:"));
    /* A good view after it works again. */
    truth_request(t, &fixture.scene, 0);
    expect_reference(t, &fixture.shown, &fixture.scene, 0);
}

/* ---- baked truths ---- */

/* The truth of light 0 of `path` traced and baked into `dir`; the scene
 * and the traced frame stay the caller's. */
static void bake(const char *path, const char *dir, scene *s, dump_frame *traced) {
    const raytrace_settings traced_settings = {.scene_name = path};
    assert_true(scene_load(s, path));
    assert_true(raytrace_render(s, WIDTH, HEIGHT, 0, &traced_settings, traced));
    assert_true(truth_bake_write(dir, traced, s, &traced_settings));
}

/* Read back, a baked truth is the traced one but for its stated
 * rounding, and shadowdiff compares the same pixels against either. */
static void expect_baked_as_traced(const char *path) {
    scene s;
    dump_frame traced, baked;
    bake(path, BAKED, &s, &traced);
    const raytrace_settings baked_settings = {.scene_name = path};
    assert_int_equal(truth_bake_find(BAKED, &s, WIDTH, HEIGHT, 0, &baked_settings, &baked), TRUTH_BAKE_FOUND);
    size_t n = (size_t)WIDTH * HEIGHT;
    assert_memory_equal(traced.color, baked.color, 4 * n);
    for (size_t i = 0; i < n; i++) {
        assert_true(traced.ids[i] == baked.ids[i]);
        if (traced.ids[i] < 0)
            continue;
        assert_true(traced.visibility[i] == baked.visibility[i]);
        assert_true(fabsf(traced.depth[i] - baked.depth[i]) <= ldexpf(traced.depth[i], -16));
        float cosine = 0, moved = 0;
        for (int k = 0; k < 3; k++) {
            cosine += traced.normal[3 * i + k] * baked.normal[3 * i + k];
            moved = fmaxf(moved, fabsf(traced.position[3 * i + k] - baked.position[3 * i + k]));
        }
        assert_true(cosine >= 1 - 1e-6f);
        assert_true(moved <= BAKED_POSITION_TOLERANCE * traced.depth[i]);
    }
    shadowdiff_result against_traced, against_baked;
    assert_true(shadowdiff_compare(&traced, &traced, NULL, &against_traced, NULL));
    assert_true(shadowdiff_compare(&baked, &traced, NULL, &against_baked, NULL));
    assert_int_equal(against_baked.compared, against_traced.compared);
    assert_int_equal(against_baked.false_shadow + against_baked.false_lit, 0);
    assert_true(against_baked.mean_abs_error == 0);
    dump_frame_free(&traced);
    dump_frame_free(&baked);
    scene_free(&s);
}

static void test_baked_truth_reads_back_as_traced(void **state) {
    (void)state;
    expect_baked_as_traced(SCENE);
    expect_baked_as_traced(SOFT_SCENE);
}

/* Found for its view, within another libm's rounding, and no other. */
static void test_baked_truth_is_found_for_its_view_only(void **state) {
    (void)state;
    scene s;
    dump_frame traced, found;
    bake(SCENE, BAKED, &s, &traced);
    scene nudged = s, moved = s, relit = s;
    nudged.camera.position[0] = nextafterf(s.camera.position[0], INFINITY);
    moved.camera.position[0] += 0.01f;
    relit.lights[0].intensity *= 2;
    const raytrace_settings fewer = {.light_samples = RAYTRACE_DEFAULT_LIGHT_SAMPLES / 4};
    assert_int_equal(truth_bake_find(BAKED, &nudged, WIDTH, HEIGHT, 0, &settings, &found), TRUTH_BAKE_FOUND);
    dump_frame_free(&found);
    assert_int_equal(truth_bake_find(BAKED, &moved, WIDTH, HEIGHT, 0, &settings, &found), TRUTH_BAKE_NONE);
    assert_int_equal(truth_bake_find(BAKED, &relit, WIDTH, HEIGHT, 0, &settings, &found), TRUTH_BAKE_NONE);
    assert_int_equal(truth_bake_find(BAKED, &s, WIDTH + 1, HEIGHT, 0, &settings, &found), TRUTH_BAKE_NONE);
    assert_int_equal(truth_bake_find(BAKED, &s, WIDTH, HEIGHT, 0, &fewer, &found), TRUTH_BAKE_NONE);
    assert_int_equal(truth_bake_find(BAKED "/none", &s, WIDTH, HEIGHT, 0, &settings, &found), TRUTH_BAKE_NONE);
    dump_frame_free(&traced);
    scene_free(&s);
}

/* Started on baked truths, a truth answers each request at once: the
 * baked frame, complete; a view with none fails, said once. */
static void test_truth_on_baked_truths_answers_at_once(void **state) {
    (void)state;
    scene s;
    dump_frame traced, baked;
    bake(SCENE, BAKED, &s, &traced);
    assert_int_equal(truth_bake_find(BAKED, &s, WIDTH, HEIGHT, 0, &settings, &baked), TRUTH_BAKE_FOUND);
    truth t;
    truth_frame shown = {0};
    assert_true(truth_start(&t, WIDTH, HEIGHT, &settings, BAKED));
    truth_request(&t, &s, 0);
    assert_true(truth_take(&t, &shown));
    assert_true(shown.complete);
    assert_int_equal(shown.rows, HEIGHT);
    assert_true(same_frame(&shown.dump, &baked));
    scene moved = s;
    support_capture_stderr();
    for (int k = 0; k < 2; k++) {
        moved.camera.position[0] += 0.5f;
        truth_request(&t, &moved, 0);
        truth_wait(&t);
        truth_take(&t, &shown);
        assert_true(shown.failed);
        assert_false(shown.complete);
    }
    const char *said = support_release_stderr();
    assert_int_equal(support_count_lines(said), 1);
    assert_non_null(strstr(said, "no truth is baked"));
    truth_forget(&t);
    truth_request(&t, &s, 0);
    truth_take(&t, &shown);
    assert_true(shown.complete);
    truth_frame_free(&shown);
    truth_stop(&t);
    dump_frame_free(&baked);
    dump_frame_free(&traced);
    scene_free(&s);
}

/* A baked truth whose image is damaged is an error naming the file. */
static void test_damaged_baked_truth_is_said(void **state) {
    (void)state;
    scene s;
    dump_frame traced, found;
    char errors[512];
    assert_int_equal(support_run("rm -rf " DAMAGED, errors, sizeof errors), 0);
    bake(SCENE, DAMAGED, &s, &traced);
    assert_int_equal(
        support_run("for d in " DAMAGED "/*/; do echo damaged > \"$d/depth.png\"; done", errors, sizeof errors), 0);
    support_capture_stderr();
    truth_bake_found result = truth_bake_find(DAMAGED, &s, WIDTH, HEIGHT, 0, &settings, &found);
    const char *said = support_release_stderr();
    assert_int_equal(result, TRUTH_BAKE_ERROR);
    assert_int_equal(support_count_lines(said), 1);
    assert_non_null(strstr(said, "depth.png"));
    dump_frame_free(&traced);
    scene_free(&s);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_row_order_is_every_row_once_coarse_first),
        cmocka_unit_test_setup_teardown(test_finished_truth_is_the_reference, start_truth, stop_truth),
        cmocka_unit_test_setup_teardown(test_newer_request_replaces_older, start_truth, stop_truth),
        cmocka_unit_test_setup_teardown(test_stop_while_tracing, start_truth, stop_truth),
        cmocka_unit_test_setup_teardown(test_failed_trace_is_reported, start_truth, stop_truth),
        cmocka_unit_test(test_baked_truth_reads_back_as_traced),
        cmocka_unit_test(test_baked_truth_is_found_for_its_view_only),
        cmocka_unit_test(test_truth_on_baked_truths_answers_at_once),
        cmocka_unit_test(test_damaged_baked_truth_is_said),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
