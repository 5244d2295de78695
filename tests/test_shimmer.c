/* End-to-end test of the shimmer figure (common/programs/main_bench.c):
 * the teapot under its directional light, 640x360, frame 30 of the
 * camera's yaw and of dolly's walk, dumped twice by each program: as it
 * is, and with --hold-fit (the maps fitted to frame 29's camera, drawn
 * from frame 30's), against the one reference build/raytrace traces of
 * that frame. Both dumps see the same pixels and the truth is the same,
 * so shadowdiff's shimmer of the pair is the share of compared pixels
 * whose decision the fit's motion alone changes: how far shadow edges
 * crawl between two frames, free of the resampling two views add.
 *
 * Bounds (the test prints each figure, yaw and dolly):
 *   a shadow map of a fixed 256 refits to the view every frame, its texels
 *   slide over the receivers: above CRAWLING_MIN_PERCENT;
 *   cascades, stabilised by steps (the default) and by the sphere: at
 *   most the goal STABLE_MAX_PERCENT (by steps none shimmers), and with
 *   --stabilize off above it: the test sees the difference;
 *   shadow volumes fit nothing: exactly 0. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "support.h"

#define DIR "out/test/shimmer"
#define SCENE "assets/scenes/teapot.json"
/* --frames: the frame dumped is the last, 30 (at 30/60 s). */
#define FRAMES 31
/* A quarter of the least of the 256 map's figures (yaw, dolly). */
#define CRAWLING_MIN_PERCENT 0.03
/* The goal set for stabilised cascades. */
#define STABLE_MAX_PERCENT 0.01
/* Valient's sphere holds its size on the practical splits, which depend on
 * near and far alone; sdsm's (the default) follow what is seen. */
#define SPHERE "--splits practical --stabilize sphere"
/* Without stabilisation, above the goal that stabilised cascades meet:
 * the test sees the difference. */
#define UNSTABLE_MIN_PERCENT STABLE_MAX_PERCENT

static const char *const motions[] = {"camera", "dolly"};

/* Dumps into DIR/NAME the frame of `program` with `flags` under
 * `motion`; returns its exit status. */
static int dump_of(const char *program, const char *flags, const char *motion, const char *name, char *dir,
                   size_t size) {
    snprintf(dir, size, DIR "/%s_%s", name, motion);
    char all_flags[1024];
    snprintf(all_flags, sizeof all_flags, "%s --motion %s --frames %d", flags, motion, FRAMES);
    return support_dump(program, SCENE, all_flags, dir);
}

/* The reference of each motion's frame, traced once for every test. */
static int trace_references(void **state) {
    (void)state;
    for (size_t m = 0; m < sizeof motions / sizeof *motions; m++) {
        char dir[256];
        if (dump_of("raytrace", "", motions[m], "raytrace", dir, sizeof dir) != 0) {
            fprintf(stderr, "build/raytrace failed to dump %s\n", dir);
            return -1;
        }
    }
    return 0;
}

/* The shimmer of `program` with `flags` under `motion`, printed. */
static double measure_shimmer(const char *program, const char *flags, const char *motion) {
    char reference_dir[256], test_dir[256], held_dir[256], held_flags[512], name[128];
    snprintf(reference_dir, sizeof reference_dir, DIR "/raytrace_%s", motion);
    snprintf(held_flags, sizeof held_flags, "%s --hold-fit", flags);
    snprintf(name, sizeof name - sizeof "_held", "%s%s", program, flags);
    for (char *c = name; *c; c++)
        *c = *c == ' ' ? '_' : *c;
    assert_int_equal(dump_of(program, flags, motion, name, test_dir, sizeof test_dir), 0);
    strcat(name, "_held");
    assert_int_equal(dump_of(program, held_flags, motion, name, held_dir, sizeof held_dir), 0);
    dump_frame reference, test, held;
    assert_true(dump_read(&reference, reference_dir));
    assert_true(dump_read(&test, test_dir));
    assert_true(dump_read(&held, held_dir));
    shadowdiff_shimmer_result r;
    assert_true(shadowdiff_shimmer(&reference, &held, &reference, &test, NULL, &r));
    fprintf(stderr, "    %s %s, motion %s: shimmer %.4f %% (%ld of %ld)\n", program, flags, motion, r.shimmer_percent,
            r.shimmered, r.followed);
    /* One view: every compared pixel follows itself, the truth the same. */
    assert_int_equal(r.followed, r.current.compared);
    assert_true(r.truth_changed_percent == 0);
    dump_frame_free(&reference);
    dump_frame_free(&test);
    dump_frame_free(&held);
    return r.shimmer_percent;
}

static void test_fixed_small_map_crawls(void **state) {
    (void)state;
    for (size_t m = 0; m < sizeof motions / sizeof *motions; m++)
        assert_true(measure_shimmer("shadowmap", "--map-size 256", motions[m]) > CRAWLING_MIN_PERCENT);
}

static void test_stabilised_cascades_stand_still(void **state) {
    (void)state;
    for (size_t m = 0; m < sizeof motions / sizeof *motions; m++) {
        assert_true(measure_shimmer("cascades", "", motions[m]) <= STABLE_MAX_PERCENT);
        assert_true(measure_shimmer("cascades", SPHERE, motions[m]) <= STABLE_MAX_PERCENT);
        assert_true(measure_shimmer("cascades", "--stabilize off", motions[m]) > UNSTABLE_MIN_PERCENT);
    }
}

static void test_volumes_stand_still(void **state) {
    (void)state;
    for (size_t m = 0; m < sizeof motions / sizeof *motions; m++)
        assert_true(measure_shimmer("volumes", "", motions[m]) == 0);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fixed_small_map_crawls),
        cmocka_unit_test(test_stabilised_cascades_stand_still),
        cmocka_unit_test(test_volumes_stand_still),
    };
    return cmocka_run_group_tests(tests, trace_references, NULL);
}
