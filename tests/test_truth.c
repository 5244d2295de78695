/* Tests of common/measure/truth.c, the background reference of compare
 * mode: its row order, that a finished frame is raytrace_render's byte for
 * byte, that a newer request replaces an older one mid-trace, that an
 * equal request does not restart, that forgetting and stopping never hang
 * (and leak nothing under ASan), and that a failing trace says so. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdlib.h>
#include <string.h>

#include "support.h"
#include "truth.h"

#define SCENE "assets/scenes/simple.json"
#define WIDTH 96
#define HEIGHT 54
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
    return scene_load(&fixture.scene, SCENE) && truth_start(&fixture.truth, WIDTH, HEIGHT, &settings) ? 0 : -1;
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
    assert_true(truth_start(&fixture.truth, WIDTH * 8, HEIGHT * 8, &settings));
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

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_row_order_is_every_row_once_coarse_first),
        cmocka_unit_test_setup_teardown(test_finished_truth_is_the_reference, start_truth, stop_truth),
        cmocka_unit_test_setup_teardown(test_newer_request_replaces_older, start_truth, stop_truth),
        cmocka_unit_test_setup_teardown(test_stop_while_tracing, start_truth, stop_truth),
        cmocka_unit_test_setup_teardown(test_failed_trace_is_reported, start_truth, stop_truth),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
