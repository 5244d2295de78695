/* Moment shadow maps (--filter vsm, evsm2, evsm4, msm; map.h,
 * "Moment shadow maps") against the ray-traced reference, by shadowdiff's
 * classes: on an area point light (a cube map), an area sun (a 2D map and
 * cascades' array map) and a hard spot light, each filter draws the umbra
 * dark, the lit surfaces lit and, under an area light, a penumbra nearer
 * the reference than a hard filter's edge. Then the skips: the same dumps
 * with every skip on and with --no-skip. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "map.h"
#include "shadowdiff.h"
#include "support.h"

#define OUT "out/test/moments"
/* The soft tests' size (tests/test_soft.c): --map-size auto sizes a texel
 * about a pixel there. */
#define MOMENTS_SIZE "--size 1280x720"

static const char *const filters[] = {"vsm", "evsm2", "evsm4", "msm"};
enum { FILTER_VSM, FILTER_EVSM2, FILTER_EVSM4, FILTER_MSM, FILTER_COUNT };
_Static_assert(sizeof filters / sizeof *filters == FILTER_COUNT, "a name per filter");

/* Per case and filter the most umbra MAE (light bleeding, and an area
 * light's umbra lit by a blur wider than its penumbra at contact), lit
 * MAE (over-darkening) and penumbra MAE (how the soft shadow is drawn):
 * the figures measured, with a quarter of margin. A hard light's umbra is
 * within MOMENTS_GOAL_UMBRA_MAE for every filter; an area light's is not
 * (a uniform blur has no contact hardening: the umbra's rim is lit by
 * half a penumbra where the reference's narrows to nothing), nor is VSM's
 * and EVSM2's penumbra nearer the sun's than a hard edge (bleeding across
 * the bunny's own curves). On the point
 * light every filter's bound lies below the penumbra MAE of a hard edge
 * (--filter pcf3 --soft off): a moment map drawn without its blur fails
 * there. */
#define MOMENTS_GOAL_UMBRA_MAE 0.03
static const struct {
    const char *program, *scene, *size;
    double max_umbra_mae[FILTER_COUNT], max_lit_mae[FILTER_COUNT], max_penumbra_mae[FILTER_COUNT];
} cases[] = {
    /* an area point light: a cube map */
    {"shadowmap",
     "assets/scenes/soft_table.json",
     MOMENTS_SIZE,
     {0.039, 0.049, 0.045, 0.044},
     {0.002, 0.001, 0.002, 0.002},
     {0.2, 0.18, 0.15, 0.14}},
    /* an area sun: a 2D map, then cascades' array map */
    {"shadowmap",
     "assets/scenes/soft_sun.json",
     MOMENTS_SIZE,
     {0.16, 0.33, 0.21, 0.19},
     {0.002, 0.001, 0.004, 0.003},
     {0.26, 0.31, 0.2, 0.18}},
    {"cascades",
     "assets/scenes/soft_sun.json",
     MOMENTS_SIZE,
     {0.13, 0.26, 0.15, 0.13},
     {0.001, 0.001, 0.002, 0.002},
     {0.26, 0.37, 0.24, 0.2}},
    /* a hard spot light, a 2D map; and psm's warped one */
    {"shadowmap",
     "assets/scenes/simple.json",
     MOMENTS_SIZE,
     {0.002, 0.003, 0.003, 0.003},
     {0.001, 0.001, 0.001, 0.001},
     {1, 1, 1, 1}},
    {"psm",
     "assets/scenes/simple.json",
     MOMENTS_SIZE,
     {0.002, 0.003, 0.003, 0.003},
     {0.001, 0.001, 0.001, 0.001},
     {1, 1, 1, 1}},
};

/* Every case with every filter (in make test's quick tier each case with
 * one filter in turn: support_sweep_takes). */
static void test_filters_against_reference(void **state) {
    (void)state;
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        for (int k = 0; k < FILTER_COUNT; k++) {
            if (!support_sweep_takes((int)i, k, FILTER_COUNT))
                continue;
            char name[64], flags[64];
            snprintf(name, sizeof name, "moments_%s_%zu", filters[k], i);
            snprintf(flags, sizeof flags, "--filter %s", filters[k]);
            shadowdiff_result r = support_measure(cases[i].program, cases[i].scene, cases[i].size, flags, name);
            const double *c = r.class_mae;
            printf("    %s %s %s: penumbra MAE %.4f of %ld px, umbra %.4f of %ld px, lit %.4f, whole %.4f, "
                   "misclassified %.3f %%\n",
                   cases[i].program, cases[i].scene, filters[k], c[SHADOWDIFF_CLASS_PENUMBRA],
                   r.class_pixels[SHADOWDIFF_CLASS_PENUMBRA], c[SHADOWDIFF_CLASS_UMBRA],
                   r.class_pixels[SHADOWDIFF_CLASS_UMBRA], c[SHADOWDIFF_CLASS_LIT], r.mean_abs_error,
                   r.misclassified_percent);
            assert_true(r.class_pixels[SHADOWDIFF_CLASS_UMBRA] > 0);
            assert_true(c[SHADOWDIFF_CLASS_UMBRA] <= cases[i].max_umbra_mae[k]);
            assert_true(c[SHADOWDIFF_CLASS_LIT] <= cases[i].max_lit_mae[k]);
            assert_true(c[SHADOWDIFF_CLASS_PENUMBRA] <= cases[i].max_penumbra_mae[k]);
            if (r.class_pixels[SHADOWDIFF_CLASS_PENUMBRA] == 0)
                assert_true(c[SHADOWDIFF_CLASS_UMBRA] <= MOMENTS_GOAL_UMBRA_MAE);
        }
    }
}

/* Caster culling and the cache hold for moment maps (their reads reach
 * the blur's width, and every depth of it, a caster's behind the
 * receivers too): with every skip on the dumps are those of --no-skip, a
 * cube map and an array map, over frames with the light or the camera
 * moving (layers reused, then rendered again). At tests/test_skip.c's
 * size for its runs with and without the skips: what a skip leaves out
 * does not depend on the pixels. */
#define SKIPS_SIZE "--size 320x180"
static void test_skips_change_nothing(void **state) {
    (void)state;
    static const struct {
        const char *program, *scene, *flags;
    } runs[] = {
        {"shadowmap", "assets/scenes/soft_table.json", "--filter msm --frames 3 --motion light"},
        {"shadowmap", "assets/scenes/soft_table.json", "--filter vsm --frames 3 --motion camera"},
        {"cascades", "assets/scenes/soft_sun.json", "--filter evsm4 --frames 3 --motion camera"},
        {"shadowmap", "assets/scenes/simple.json", "--filter evsm2 --frames 2 --motion light"},
    };
    static const char *const files[] = {"visibility.pfm", "depth.pfm", "color.png"};
    for (size_t i = 0; i < sizeof runs / sizeof *runs; i++) {
        char on[256], off[256], flags[256];
        snprintf(on, sizeof on, OUT "/skips_on_%zu", i);
        snprintf(off, sizeof off, OUT "/skips_off_%zu", i);
        snprintf(flags, sizeof flags, SKIPS_SIZE " %s", runs[i].flags);
        assert_int_equal(support_dump(runs[i].program, runs[i].scene, flags, on), 0);
        snprintf(flags, sizeof flags, SKIPS_SIZE " %s --no-skip", runs[i].flags);
        assert_int_equal(support_dump(runs[i].program, runs[i].scene, flags, off), 0);
        const char *differs = support_first_difference(on, off, files, sizeof files / sizeof *files);
        printf("    %s %s %s: %s\n", runs[i].program, runs[i].scene, runs[i].flags,
               differs ? differs : "identical with and without skips");
        assert_null(differs);
    }
}

/* Precedence: a moment filter draws an area light by its blur whatever
 * --soft says, so nothing says it is drawn hard (stderr stays empty), and
 * the HUD's words say how it is drawn; a hard light has no such words. */
static void test_area_lights_take_the_blur(void **state) {
    (void)state;
    for (int k = 0; k < FILTER_COUNT; k++) {
        char command[512], text[4096];
        snprintf(command, sizeof command,
                 "%s --size 160x90 --scene assets/scenes/soft_table.json --filter %s --soft off --frames 2",
                 support_program("shadowmap"), filters[k]);
        assert_int_equal(support_run(command, text, sizeof text), 0);
        printf("    --filter %s --soft off: %d lines on stderr\n", filters[k], support_count_lines(text));
        assert_int_equal(support_count_lines(text), 0);
    }
    const scene_light area = {.type = SCENE_LIGHT_POINT, .radius = 1};
    const map_settings moments = {.filter = MAP_FILTER_MSM, .soft = MAP_SOFT_OFF};
    const map_settings kernel = {.filter = MAP_FILTER_PCF3, .soft = MAP_SOFT_OFF};
    assert_non_null(strstr(map_area_light_text(&moments, &area), "moment map"));
    assert_null(strstr(map_area_light_text(&kernel, &area), "moment map"));
    assert_false(map_light_soft(&moments, &area));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_filters_against_reference),
        cmocka_unit_test(test_skips_change_nothing),
        cmocka_unit_test(test_area_lights_take_the_blur),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
