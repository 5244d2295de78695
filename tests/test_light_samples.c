/* Area lights sampled by the stencil techniques (--light-samples N;
 * common/gl/soft_visibility.h): the average of N hard shadows from the
 * light's points (area_light.h, as the reference takes them) converges to
 * the ray-traced truth, by shadowdiff's classes. One table of cases: each
 * program on each soft scene, its penumbra MAE hard (1 point), then at
 * CONVERGE_SAMPLES and SAMPLES, over the receiver the technique can
 * shadow (planar: the ground; volumes: every object), falling, and within
 * the case's bound at SAMPLES with no light leaking into the umbra. Volumes'
 * penumbra wedges (--soft wedges) on the same scenes: within their own
 * bound, far below the hard shadow's error, leaking little into the umbra.
 * A hard light is drawn byte for byte as without the flags, and an area
 * light drawn hard says so once. In the window the points are added over
 * frames (progressive): once they are all in, the same picture as
 * headless; before, a partial one whose HUD says how far it is; while the
 * camera moves, the hard one; and the order they are added in spreads
 * every partial sum over the disk. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "area_light.h"
#include "shadowdiff.h"
#include "support.h"

#define CONVERGE_SAMPLES 16
#define SAMPLES 64
/* Each step from 1 to CONVERGE_SAMPLES points cuts the penumbra's error
 * at least this much: a sampled light converges, it does not merely
 * blur. */
#define CONVERGE_FACTOR 3.0
/* Light leaking into the truth's umbra at SAMPLES points. */
#define MAX_UMBRA_MAE 0.005

static const struct {
    const char *program, *scene, *receiver; /* receiver NULL: every object */
    double max_penumbra_mae;                /* at SAMPLES */
} cases[] = {
    /* a point light of radius 0.8: every pixel sees the disk turned to
     * it, the points one ball for all (area_light_sample_ball), so the
     * error left at SAMPLES is the ball's sampling noise */
    {"planar", "assets/scenes/soft_table.json", "ground", 0.03},
    {"volumes", "assets/scenes/soft_table.json", NULL, 0.03},
    /* a 3-degree sun: the same disk of directions from every pixel */
    {"planar", "assets/scenes/soft_sun.json", "ground", 0.02},
    {"volumes", "assets/scenes/soft_sun.json", NULL, 0.025},
};

/* Penumbra wedges: the error left is the silhouette taken from the light's
 * centre (on a caster's own terminator, where the surface itself hides
 * part of the disk, most) and overlapping casters' wedges, which darken
 * twice. Each step's bound is the scene's. */
static const struct {
    const char *scene;
    double max_penumbra_mae, max_umbra_mae;
    double factor; /* the hard shadow's penumbra error over the wedges', at least */
} wedge_cases[] = {
    {"assets/scenes/soft_table.json", 0.03, 0.005, 3},
    /* the bunny's terminator under a small sun: its own surface hides the
     * disk's lower part, which no edge from the centre knows */
    {"assets/scenes/soft_sun.json", 0.075, 0.02, 3},
    /* an open mesh (the open rule, every layer counted) under the sun: the
     * spout's layers before the body leak into the umbra */
    {"tests/data/soft_teapot.json", 0.1, 0.06, 2},
};

static char err[16384];

/* Program's penumbra (and umbra) MAE on scene with flags, over the
 * receiver (NULL: every object). */
static shadowdiff_result measure_flags(const char *program, const char *scene, const char *receiver,
                                       const char *flags, const char *name) {
    dump_frame reference, test;
    unsigned char *heatmap;
    shadowdiff_result all = support_measure_dumps(program, scene, "", flags, name, &reference, &test, &heatmap);
    shadowdiff_result r = all;
    if (receiver) {
        const shadowdiff_settings on = {.receiver = receiver};
        assert_true(shadowdiff_compare(&reference, &test, &on, &r, NULL));
    }
    printf("    %s on %s, %s: penumbra MAE %.4f, umbra MAE %.4f, lit MAE %.4f%s%s\n", program, scene, flags,
           r.class_mae[SHADOWDIFF_CLASS_PENUMBRA], r.class_mae[SHADOWDIFF_CLASS_UMBRA],
           r.class_mae[SHADOWDIFF_CLASS_LIT], receiver ? " on the " : "", receiver ? receiver : "");
    free(heatmap);
    dump_frame_free(&reference);
    dump_frame_free(&test);
    assert_true(r.class_pixels[SHADOWDIFF_CLASS_PENUMBRA] > 0);
    return r;
}

/* The case's penumbra (and umbra) MAE with `samples` points. */
static shadowdiff_result measure(size_t c, int samples) {
    char flags[64], name[128];
    snprintf(flags, sizeof flags, "--light-samples %d", samples);
    snprintf(name, sizeof name, "samples_%zu_%d", c, samples);
    return measure_flags(cases[c].program, cases[c].scene, cases[c].receiver, flags, name);
}

static void test_sampled_area_lights_converge(void **state) {
    (void)state;
    for (size_t c = 0; c < sizeof cases / sizeof *cases; c += support_sweep_stride()) {
        double hard = measure(c, 1).class_mae[SHADOWDIFF_CLASS_PENUMBRA];
        double some = measure(c, CONVERGE_SAMPLES).class_mae[SHADOWDIFF_CLASS_PENUMBRA];
        shadowdiff_result many = measure(c, SAMPLES);
        assert_true(some * CONVERGE_FACTOR <= hard);
        assert_true(many.class_mae[SHADOWDIFF_CLASS_PENUMBRA] < some);
        assert_true(many.class_mae[SHADOWDIFF_CLASS_PENUMBRA] <= cases[c].max_penumbra_mae);
        assert_true(many.class_mae[SHADOWDIFF_CLASS_UMBRA] <= MAX_UMBRA_MAE);
    }
}

static void test_wedges_near_truth(void **state) {
    (void)state;
    for (size_t c = 0; c < sizeof wedge_cases / sizeof *wedge_cases; c++) {
        const char *scene = wedge_cases[c].scene;
        double hard = measure_flags("volumes", scene, NULL, "", "wedges_hard").class_mae[SHADOWDIFF_CLASS_PENUMBRA];
        shadowdiff_result r = measure_flags("volumes", scene, NULL, "--soft wedges", "wedges");
        assert_true(r.class_mae[SHADOWDIFF_CLASS_PENUMBRA] * wedge_cases[c].factor <= hard);
        assert_true(r.class_mae[SHADOWDIFF_CLASS_PENUMBRA] <= wedge_cases[c].max_penumbra_mae);
        assert_true(r.class_mae[SHADOWDIFF_CLASS_UMBRA] <= wedge_cases[c].max_umbra_mae);
    }
}

/* A hard light (simple's spot; the bunny's point light, its volumes
 * closed) with --light-samples, or --soft wedges: the same dump, byte for
 * byte, as without. */
static void test_hard_light_untouched(void **state) {
    (void)state;
    static const struct {
        const char *program, *scene, *flags;
    } runs[] = {
        {"planar", "assets/scenes/simple.json", "--light-samples 64"},
        {"volumes", "assets/scenes/simple.json", "--light-samples 64"},
        {"volumes", "assets/scenes/simple.json", "--soft wedges"},
        {"volumes", "assets/scenes/bunny.json", "--soft wedges"},
    };
    static const char *const files[] = {"visibility.pfm", "color.png"};
    for (size_t p = 0; p < sizeof runs / sizeof *runs; p++) {
        char plain[128], soft[128];
        snprintf(plain, sizeof plain, "out/test/light_samples/%zu_plain", p);
        snprintf(soft, sizeof soft, "out/test/light_samples/%zu_soft", p);
        assert_int_equal(support_dump(runs[p].program, runs[p].scene, "", plain), 0);
        assert_int_equal(support_dump(runs[p].program, runs[p].scene, runs[p].flags, soft), 0);
        assert_null(support_first_difference(plain, soft, files, 2));
    }
}

/* An area light drawn hard (one point) is said once on stderr, however
 * many frames. */
static void test_drawn_hard_said_once(void **state) {
    (void)state;
    static const char *const programs[] = {"planar", "volumes"};
    for (size_t p = 0; p < 2; p++) {
        char command[512];
        snprintf(command, sizeof command,
                 "%s --backend egl --scene assets/scenes/soft_table.json --size 320x180 --frames 3 "
                 "--light-samples 1",
                 support_program(programs[p]));
        assert_int_equal(support_run(command, err, sizeof err), 0);
        const char *said = strstr(err, "drawn hard from its centre: --light-samples");
        assert_non_null(said);
        assert_null(strstr(said + 1, "drawn hard from its centre"));
    }
}

/* area_light_progressive_index: a permutation of every count's points,
 * each first 4^i of them one per cell of the 2^i x 2^i grid (the points'
 * rows and columns of the square, sample k's k / m and k % m). */
static void test_progressive_order_spreads(void **state) {
    (void)state;
    static const int counts[] = {4, 16, 64, 256}; /* --light-samples' */
    for (size_t c = 0; c < sizeof counts / sizeof *counts; c++) {
        int n = counts[c], m = 1;
        while (m * m < n)
            m++;
        bool taken[256] = {0};
        for (int j = 0; j < n; j++) {
            int k = area_light_progressive_index(j, n);
            assert_in_range(k, 0, n - 1);
            assert_false(taken[k]);
            taken[k] = true;
        }
        for (int cells = 2; cells * cells <= n; cells *= 2) {
            bool cell_taken[256] = {0};
            for (int j = 0; j < cells * cells; j++) {
                int k = area_light_progressive_index(j, n);
                int cell = k / m * cells / m * cells + k % m * cells / m;
                assert_false(cell_taken[cell]);
                cell_taken[cell] = true;
            }
        }
    }
    assert_int_equal(area_light_progressive_index(5, 9), 5); /* not a power of 4: in order */
}

#define PROGRESSIVE_SAMPLES 64
#define PROGRESSIVE_PARTIAL 8
#define PROGRESSIVE_DIR "out/test/light_samples"

/* The window's picture (Xvfb) of volumes on soft_table after `frames`
 * frames at `samples` points with `flags`, its HUD's last text in err. */
static void window_picture(int frames, int samples, const char *flags, const char *path) {
    char command[1024];
    snprintf(command, sizeof command,
             "timeout 240 %s %s --backend glfw --scene assets/scenes/soft_table.json --size 320x180 --frames %d "
             "--light-samples %d %s --screenshot " PROGRESSIVE_DIR "/%s",
             support_xvfb_run(), support_program("volumes"), frames, samples, flags, path);
    assert_int_equal(support_run(command, err, sizeof err), 0);
}

static bool same_picture(const char *a, const char *b) {
    char command[512];
    snprintf(command, sizeof command, "cmp -s " PROGRESSIVE_DIR "/%s " PROGRESSIVE_DIR "/%s", a, b);
    return system(command) == 0;
}

static void assert_hud_says(const char *said) {
    if (!strstr(err, said))
        fail_msg("the HUD does not say \"%s\":\n%s", said, err);
}

/* The first frame (the technique's first: everything changed) is the
 * centre's; each one after adds a point. While the camera moves, every
 * frame is the hard technique's picture. */
static void test_progressive_in_the_window(void **state) {
    (void)state;
    assert_int_equal(system("mkdir -p " PROGRESSIVE_DIR), 0);
    char command[1024];
    snprintf(command, sizeof command,
             "%s --backend egl --scene assets/scenes/soft_table.json --size 320x180 --frames 1 --light-samples %d "
             "--no-hud --screenshot " PROGRESSIVE_DIR "/headless.png",
             support_program("volumes"), PROGRESSIVE_SAMPLES);
    assert_int_equal(support_run(command, err, sizeof err), 0);
    window_picture(1 + PROGRESSIVE_SAMPLES, PROGRESSIVE_SAMPLES, "--no-hud", "window_full.png");
    assert_true(same_picture("window_full.png", "headless.png"));
    window_picture(1 + PROGRESSIVE_PARTIAL, PROGRESSIVE_SAMPLES, "--no-hud", "window_partial.png");
    assert_false(same_picture("window_partial.png", "headless.png"));
    window_picture(1 + PROGRESSIVE_PARTIAL, PROGRESSIVE_SAMPLES, "--verbose", "window_partial_hud.png");
    char said[64];
    snprintf(said, sizeof said, "sampled at %d points, %d so far", PROGRESSIVE_SAMPLES, PROGRESSIVE_PARTIAL);
    assert_hud_says(said);
    window_picture(PROGRESSIVE_PARTIAL, PROGRESSIVE_SAMPLES, "--motion camera --no-hud", "window_moving.png");
    window_picture(PROGRESSIVE_PARTIAL, 1, "--motion camera --no-hud", "window_moving_hard.png");
    assert_true(same_picture("window_moving.png", "window_moving_hard.png"));
    window_picture(PROGRESSIVE_PARTIAL, PROGRESSIVE_SAMPLES, "--motion camera --verbose", "window_moving_hud.png");
    assert_hud_says("while nothing moves (now hard, from its centre)");
    printf("    window: the headless picture after %d frames, partial after %d (\"%s\"), the hard one while the "
           "camera moves\n",
           1 + PROGRESSIVE_SAMPLES, 1 + PROGRESSIVE_PARTIAL, said);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_progressive_order_spreads),    cmocka_unit_test(test_progressive_in_the_window),
        cmocka_unit_test(test_sampled_area_lights_converge), cmocka_unit_test(test_wedges_near_truth),
        cmocka_unit_test(test_hard_light_untouched),         cmocka_unit_test(test_drawn_hard_said_once),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
