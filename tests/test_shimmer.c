/* End-to-end test of shadowdiff's shimmer (shadowdiff.h) on real frames:
 * the teapot under its directional light, 640x360, frames 29 and 30 of
 * the camera's yaw and of dolly's walk, each traced by build/raytrace
 * (--motion, --frames: the frames the raster programs dump last) and
 * dumped by the programs. A shadow map of a fixed 256 texels refits to
 * the view every frame, so its texels slide over the receivers and its
 * shadow edges crawl: shimmer well above 0 (measured 0.116 % under the
 * yaw, 0.135 % walking). Shadow volumes are exact in every frame: 0
 * (measured 0 and 0). Also: the reference's frame is the programs' (the
 * cameras in the dumps agree, or shimmer would refuse them). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "support.h"

#define DIR "out/test/shimmer"
#define SCENE "assets/scenes/teapot.json"
/* --frames of the previous frame; the current one is the next. */
#define PREVIOUS_FRAMES 30
/* A still picture has shimmer exactly 0; an exact technique may still
 * flip a pixel or two where a rasterized edge and a traced one round
 * apart: at most this share (about 7 of 150000 pixels). */
#define EXACT_MAX_PERCENT 0.005
/* A quarter of the least measured for the 256 map (0.116 %). */
#define CRAWLING_MIN_PERCENT 0.03

static const char *const motions[] = {"camera", "dolly"};

/* Dumps into DIR/PROGRAM_MOTION_F the program's frame F - 1; returns its
 * exit status. */
static int dump_frame_of(const char *program, const char *flags, const char *motion, int frames, char *dir,
                         size_t size) {
    snprintf(dir, size, DIR "/%s_%s_%d", program, motion, frames);
    char all_flags[512];
    snprintf(all_flags, sizeof all_flags, "%s --motion %s --frames %d", flags, motion, frames);
    return support_dump(program, SCENE, all_flags, dir);
}

/* The references of both frames of each motion, traced once for every
 * test. */
static int trace_references(void **state) {
    (void)state;
    for (size_t m = 0; m < sizeof motions / sizeof *motions; m++)
        for (int f = 0; f < 2; f++) {
            char dir[256];
            if (dump_frame_of("raytrace", "", motions[m], PREVIOUS_FRAMES + f, dir, sizeof dir) != 0) {
                fprintf(stderr, "build/raytrace failed to dump %s\n", dir);
                return -1;
            }
        }
    return 0;
}

/* The shimmer of `program` with `flags` under `motion`, printed. */
static double measure_shimmer(const char *program, const char *flags, const char *motion) {
    dump_frame frames[2][2]; /* [previous, current][reference, test] */
    for (int f = 0; f < 2; f++) {
        char reference_dir[256], test_dir[256];
        snprintf(reference_dir, sizeof reference_dir, DIR "/raytrace_%s_%d", motion, PREVIOUS_FRAMES + f);
        assert_int_equal(dump_frame_of(program, flags, motion, PREVIOUS_FRAMES + f, test_dir, sizeof test_dir), 0);
        assert_true(dump_read(&frames[f][0], reference_dir));
        assert_true(dump_read(&frames[f][1], test_dir));
    }
    shadowdiff_shimmer_result r;
    assert_true(shadowdiff_shimmer(&frames[0][0], &frames[0][1], &frames[1][0], &frames[1][1], NULL, &r));
    fprintf(stderr, "    %s %s, motion %s: shimmer %.4f %% (%ld of %ld followed), truth changed %.4f %%\n", program,
            flags, motion, r.shimmer_percent, r.shimmered, r.followed, r.truth_changed_percent);
    /* Most of what is compared is followed: a frame's motion is small. */
    assert_true(r.followed > r.current.compared / 2);
    for (int f = 0; f < 2; f++) {
        dump_frame_free(&frames[f][0]);
        dump_frame_free(&frames[f][1]);
    }
    return r.shimmer_percent;
}

static void test_fixed_small_map_crawls(void **state) {
    (void)state;
    for (size_t m = 0; m < sizeof motions / sizeof *motions; m++)
        assert_true(measure_shimmer("shadowmap", "--map-size 256", motions[m]) > CRAWLING_MIN_PERCENT);
}

static void test_volumes_stand_still(void **state) {
    (void)state;
    for (size_t m = 0; m < sizeof motions / sizeof *motions; m++)
        assert_true(measure_shimmer("volumes", "", motions[m]) <= EXACT_MAX_PERCENT);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fixed_small_map_crawls),
        cmocka_unit_test(test_volumes_stand_still),
    };
    return cmocka_run_group_tests(tests, trace_references, NULL);
}
