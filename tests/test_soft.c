/* Soft shadows from area lights (scene "radius" > 0) against the
 * ray-traced penumbra, by shadowdiff's classes: each map technique's
 * default (pcss) against itself drawn hard (--soft off), on the soft
 * scenes; a hard light's pictures untouched by the soft filter; and the
 * penumbra overlay colouring the truth's penumbra, not the sky, and
 * nothing under a hard light. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shadowdiff.h"
#include "support.h"

/* At the benchmark's 1280x720 (where --map-size auto sizes a texel about
 * a pixel: at 640x360 the maps are half as fine and a penumbra's contact
 * end blurs over more of it). The goals: a penumbra drawn within 0.05 and
 * a quarter of the hard picture's error, light leaking into the umbra
 * within 0.01, the lit class no worse than hard, the whole picture's
 * error at most half. A case that misses one has its own bound, with
 * its reason beside it. */
#define SOFT_SIZE "--size 1280x720"
#define SOFT_GOAL_PENUMBRA_MAE 0.05
#define SOFT_GOAL_SHARE_OF_HARD 0.25
#define SOFT_GOAL_UMBRA_MAE 0.01
#define SOFT_GOAL_LIT_SHARE_OF_HARD 1.0
#define SOFT_GOAL_WHOLE_SHARE_OF_HARD 0.5
/* The least penumbra a soft scene shows, in pixels: so that its MAE is a
 * figure, not the noise of a few pixels. */
#define SOFT_MIN_PENUMBRA_PIXELS 2000

static const struct {
    const char *program, *scene;
    double max_penumbra_mae, max_share_of_hard, max_umbra_mae, max_lit_share_of_hard, max_whole_share_of_hard;
} soft_cases[] = {
    /* a point light: a cube map. A hard shadow's edge lies inside the
     * truth's penumbra and darkens nothing fully lit, where a penumbra
     * drawn a little wide does; the thin poles' far shadows are nearly
     * all penumbra, and 16 search taps over their wide cone miss them at
     * some pixels, which leak */
    {"shadowmap", "assets/scenes/soft_table.json", SOFT_GOAL_PENUMBRA_MAE, SOFT_GOAL_SHARE_OF_HARD, 0.016, 2.0,
     SOFT_GOAL_WHOLE_SHARE_OF_HARD},
    /* a 3-degree sun over the bunny, a 2D map: misses the goal on the
     * bunny's own curved self-shadowing, which one blocker distance and
     * one receiver plane cannot follow (the ground meets it) */
    {"shadowmap", "assets/scenes/soft_sun.json", 0.06, 0.35, 0.026, SOFT_GOAL_LIT_SHARE_OF_HARD,
     SOFT_GOAL_WHOLE_SHARE_OF_HARD},
    /* the same sun, an array map: its cascades' penumbrae are wider */
    {"cascades", "assets/scenes/soft_sun.json", 0.1, 0.6, 0.02, SOFT_GOAL_LIT_SHARE_OF_HARD, 0.55},
};

static void test_pcss_draws_the_penumbra(void **state) {
    (void)state;
    for (size_t i = 0; i < sizeof soft_cases / sizeof *soft_cases; i++) {
        char name[64];
        snprintf(name, sizeof name, "soft_%zu", i);
        shadowdiff_result soft = support_measure(soft_cases[i].program, soft_cases[i].scene, SOFT_SIZE, "", name);
        snprintf(name, sizeof name, "hard_%zu", i);
        shadowdiff_result hard =
            support_measure(soft_cases[i].program, soft_cases[i].scene, SOFT_SIZE, "--soft off", name);
        const double *s = soft.class_mae, *h = hard.class_mae;
        printf("    %s %s: penumbra MAE %.4f (hard %.4f) of %ld pixels, lit %.5f (hard %.5f), umbra %.4f (hard "
               "%.4f), whole %.4f (hard %.4f)\n",
               soft_cases[i].program, soft_cases[i].scene, s[SHADOWDIFF_CLASS_PENUMBRA], h[SHADOWDIFF_CLASS_PENUMBRA],
               soft.class_pixels[SHADOWDIFF_CLASS_PENUMBRA], s[SHADOWDIFF_CLASS_LIT], h[SHADOWDIFF_CLASS_LIT],
               s[SHADOWDIFF_CLASS_UMBRA], h[SHADOWDIFF_CLASS_UMBRA], soft.mean_abs_error, hard.mean_abs_error);
        assert_true(soft.class_pixels[SHADOWDIFF_CLASS_PENUMBRA] >= SOFT_MIN_PENUMBRA_PIXELS);
        assert_true(s[SHADOWDIFF_CLASS_PENUMBRA] <= soft_cases[i].max_penumbra_mae);
        assert_true(s[SHADOWDIFF_CLASS_PENUMBRA] <= soft_cases[i].max_share_of_hard * h[SHADOWDIFF_CLASS_PENUMBRA]);
        assert_true(s[SHADOWDIFF_CLASS_UMBRA] <= soft_cases[i].max_umbra_mae);
        assert_true(s[SHADOWDIFF_CLASS_LIT] <= soft_cases[i].max_lit_share_of_hard * h[SHADOWDIFF_CLASS_LIT]);
        assert_true(soft.mean_abs_error <= soft_cases[i].max_whole_share_of_hard * hard.mean_abs_error);
    }
}

/* A light of radius 0 never reaches the soft filter: --soft pcss and
 * --soft off dump the same bytes, for each kind of map. */
static void test_hard_lights_unchanged(void **state) {
    (void)state;
    static const struct {
        const char *program, *scene;
    } cases[] = {
        {"shadowmap", "assets/scenes/simple.json"}, /* spot */
        {"shadowmap", "assets/scenes/bunny.json"},  /* point: cube */
        {"cascades", "assets/scenes/teapot.json"},  /* directional: array */
    };
    static const char *const files[] = {"color.png", "visibility.pfm"};
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char on[256], off[256];
        snprintf(on, sizeof on, "out/test/soft/hard_on_%zu", i);
        snprintf(off, sizeof off, "out/test/soft/hard_off_%zu", i);
        assert_int_equal(support_dump(cases[i].program, cases[i].scene, "", on), 0);
        assert_int_equal(support_dump(cases[i].program, cases[i].scene, "--soft off", off), 0);
        const char *differs = support_first_difference(on, off, files, sizeof files / sizeof *files);
        printf("    %s %s: %s\n", cases[i].program, cases[i].scene, differs ? differs : "identical");
        assert_null(differs);
    }
}

/* The penumbra overlay's legend lies in the picture's bottom-right
 * corner, within these shares of its width and height (from its top
 * left); the pixels counted below lie outside it. */
#define OVERLAY_LEGEND_LEFT 0.7
#define OVERLAY_LEGEND_TOP 0.85
static bool in_legend_corner(size_t i, int width, int height) {
    return (double)(i % (size_t)width) >= OVERLAY_LEGEND_LEFT * width &&
           (double)(i / (size_t)width) >= OVERLAY_LEGEND_TOP * height;
}

/* The colour picture of a dump (a screenshot of its frame). */
static unsigned char *dump_color(const char *dir, int width, int height) {
    char path[256];
    snprintf(path, sizeof path, "%s/color.png", dir);
    return support_read_png(path, width, height);
}

/* --overlay penumbra against the same frame without it, pixel by pixel
 * outside its legend, by the reference's class there: nearly every
 * penumbra pixel of the truth is coloured (the blocker search found a
 * blocker there), no pixel without a surface is, and most of the lit ones
 * keep their colour (the search reaches a little beyond the penumbra);
 * and the colour follows the estimate, small at a contact, large far
 * from it. */
#define OVERLAY_SCENE "assets/scenes/soft_table.json"
#define OVERLAY_MIN_PENUMBRA_SHARE 0.85
/* Ground points in the tall pole's shadow (its foot at x 0.6, z 2.4; the
 * light above x -1.5, z 1; the shadow's far end near x 2.44, z 3.63): a
 * little past the foot, and near the far end. There the overlay's colour
 * must be the ramp's low end's (more green than red), here its high end's
 * (more red than green): the estimate grows with the blocker's distance
 * from the receiver. Read over the coloured pixels of a small window. */
static const float overlay_near_foot[3] = {0.77f, 0, 2.51f}, overlay_far_end[3] = {2.19f, 0, 3.46f};
#define OVERLAY_WINDOW 3 /* pixels either side */
#define OVERLAY_RECEIVER "ground"
#define OVERLAY_MAX_LIT_SHARE 0.25
enum { OVERLAY_NO_SURFACE = SHADOWDIFF_CLASS_COUNT, OVERLAY_KINDS };
/* The mean red less green (in 0..255) of the coloured pixels about the
 * receiver's pixel nearest p. */
static double overlay_redness(const dump_frame *reference, const unsigned char *before, const unsigned char *after,
                              const float p[3]) {
    int receiver = -1;
    for (int k = 0; k < reference->object_count; k++)
        receiver = strcmp(reference->object_names[k], OVERLAY_RECEIVER) == 0 ? k : receiver;
    assert_true(receiver >= 0);
    int width = reference->width, height = reference->height, nearest = -1;
    float best = INFINITY;
    for (int i = 0; i < width * height; i++) {
        const float *q = reference->position + 3 * (size_t)i;
        float d = (q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) + (q[2] - p[2]) * (q[2] - p[2]);
        if (reference->ids[i] == receiver && d < best) {
            best = d;
            nearest = i;
        }
    }
    assert_true(nearest >= 0);
    double sum = 0;
    int count = 0;
    for (int y = nearest / width - OVERLAY_WINDOW; y <= nearest / width + OVERLAY_WINDOW; y++)
        for (int x = nearest % width - OVERLAY_WINDOW; x <= nearest % width + OVERLAY_WINDOW; x++) {
            size_t i = (size_t)y * (size_t)width + (size_t)x;
            if (x < 0 || y < 0 || x >= width || y >= height || memcmp(before + 4 * i, after + 4 * i, 3) == 0)
                continue;
            sum += (double)after[4 * i] - (double)after[4 * i + 1];
            count++;
        }
    assert_true(count > 0);
    return sum / count;
}

static void test_penumbra_overlay_colours_the_penumbra(void **state) {
    (void)state;
    dump_frame reference, plain;
    unsigned char *heatmap;
    support_measure_dumps("shadowmap", OVERLAY_SCENE, "", "", "overlay_none", &reference, &plain, &heatmap);
    free(heatmap);
    assert_int_equal(support_dump("shadowmap", OVERLAY_SCENE, "--overlay penumbra", "out/test/soft/overlay"), 0);
    int width = reference.width, height = reference.height;
    unsigned char *before = dump_color("out/test/shadowmap/overlay_none", width, height);
    unsigned char *after = dump_color("out/test/soft/overlay", width, height);
    long pixels[OVERLAY_KINDS] = {0}, coloured[OVERLAY_KINDS] = {0};
    for (size_t i = 0; i < (size_t)width * (size_t)height; i++) {
        if (in_legend_corner(i, width, height))
            continue;
        int kind = reference.ids[i] < 0 ? OVERLAY_NO_SURFACE : (int)shadowdiff_class_of(reference.visibility[i]);
        pixels[kind]++;
        coloured[kind] += memcmp(before + 4 * i, after + 4 * i, 3) != 0;
    }
    for (int k = 0; k < OVERLAY_KINDS; k++)
        printf("    %s: %ld of %ld pixels coloured\n",
               k < SHADOWDIFF_CLASS_COUNT ? shadowdiff_class_names[k] : "no surface", coloured[k], pixels[k]);
    assert_true(pixels[SHADOWDIFF_CLASS_PENUMBRA] >= SOFT_MIN_PENUMBRA_PIXELS && pixels[OVERLAY_NO_SURFACE] > 0);
    assert_true(coloured[SHADOWDIFF_CLASS_PENUMBRA] >=
                OVERLAY_MIN_PENUMBRA_SHARE * pixels[SHADOWDIFF_CLASS_PENUMBRA]);
    assert_true(coloured[SHADOWDIFF_CLASS_LIT] <= OVERLAY_MAX_LIT_SHARE * pixels[SHADOWDIFF_CLASS_LIT]);
    assert_int_equal(coloured[OVERLAY_NO_SURFACE], 0);
    double near_foot = overlay_redness(&reference, before, after, overlay_near_foot),
           far_end = overlay_redness(&reference, before, after, overlay_far_end);
    printf("    red less green: %.1f near the tall pole's foot, %.1f near its shadow's far end\n", near_foot,
           far_end);
    assert_true(near_foot < 0 && far_end > 0);
    free(before);
    free(after);
    dump_frame_free(&reference);
    dump_frame_free(&plain);
}

/* Under a hard light the penumbra overlay colours nothing: its picture is
 * the default's but for the legend, which it draws in its corner. */
static void test_penumbra_overlay_leaves_hard_lights(void **state) {
    (void)state;
    assert_int_equal(support_dump("shadowmap", "assets/scenes/bunny.json", "", "out/test/soft/hard_plain"), 0);
    assert_int_equal(
        support_dump("shadowmap", "assets/scenes/bunny.json", "--overlay penumbra", "out/test/soft/hard_overlay"), 0);
    dump_frame plain;
    assert_true(dump_read(&plain, "out/test/soft/hard_plain"));
    int width = plain.width, height = plain.height;
    dump_frame_free(&plain);
    unsigned char *before = dump_color("out/test/soft/hard_plain", width, height);
    unsigned char *after = dump_color("out/test/soft/hard_overlay", width, height);
    long legend = 0, elsewhere = 0;
    for (size_t i = 0; i < (size_t)width * (size_t)height; i++) {
        bool differs = memcmp(before + 4 * i, after + 4 * i, 3) != 0;
        legend += differs && in_legend_corner(i, width, height);
        elsewhere += differs && !in_legend_corner(i, width, height);
    }
    printf("    bunny: %ld pixels differ in the legend's corner, %ld elsewhere\n", legend, elsewhere);
    assert_true(legend > 0);
    assert_int_equal(elsewhere, 0);
    free(before);
    free(after);
}

/* A technique that cannot draw soft shadows says so once on stderr. */
static void test_hard_techniques_say_so(void **state) {
    (void)state;
    static const char *const programs[] = {"volumes", "planar"};
    for (size_t i = 0; i < sizeof programs / sizeof *programs; i++) {
        char command[512], text[4096];
        snprintf(command, sizeof command, "%s --size 160x90 --scene assets/scenes/soft_table.json --frames 2",
                 support_program(programs[i]));
        assert_int_equal(support_run(command, text, sizeof text), 0);
        printf("    %s: %s", programs[i], text);
        assert_int_equal(support_count_lines(text), 1);
        assert_non_null(strstr(text, "area light"));
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pcss_draws_the_penumbra),
        cmocka_unit_test(test_hard_lights_unchanged),
        cmocka_unit_test(test_hard_techniques_say_so),
        cmocka_unit_test(test_penumbra_overlay_colours_the_penumbra),
        cmocka_unit_test(test_penumbra_overlay_leaves_hard_lights),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
