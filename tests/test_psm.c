/* Perspective shadow maps against the ray-traced reference: the warps
 * must pay where perspective aliasing is (long_view), never cost much
 * where it is not (a sweep of light directions over the whole sphere),
 * and take their path in each hard case. Each test prints its figures.
 *
 * Every run uses a 1024 map, where a uniform map over long_view's 600
 * units is coarse enough for the difference to show. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"

#define LONG_VIEW "assets/scenes/long_view.json"
#define LONG_VIEW_BEHIND "assets/scenes/long_view_behind.json"
#define MAP "--map-size 1024"
/* The sweep's bound: a warp may exceed uniform's misclassified pixels by
 * a tenth, plus a few pixels of one edge that the rasterizer and the
 * reference's rays round differently (with uniform at 0, a ratio alone
 * would fail on a single pixel). */
#define SWEEP_RATIO 1.1
#define SWEEP_SLACK_PIXELS 8
/* The sweep leaves out surfaces within 3 degrees of edge-on to the light:
 * they take about a twentieth of it at most, and there every map's
 * decision is ill-conditioned (see shadowdiff.h). */
#define SWEEP_GRAZING_DEGREES 3
#define SWEEP_SIZE "--size 480x270"
#define SWEEP_DIRECTIONS 64 /* sweep_direction's */

static const char *const warps[] = {"uniform", "psm", "lispsm"};

/* How many misclassified pixels a warp has over the sweep's bound (<= 0:
 * within it). */
static double over_bound(long warp_pixels, long uniform_pixels) {
    return (double)warp_pixels - (SWEEP_RATIO * (double)uniform_pixels + SWEEP_SLACK_PIXELS);
}

static shadowdiff_result measure(const char *scene, const char *flags, const char *name) {
    char all[512];
    snprintf(all, sizeof all, MAP " %s", flags);
    return support_measure("psm", scene, "", all, name);
}

/* The HUD's line for light 0 after one frame (printed by --verbose). */
static const char *describe(const char *scene, const char *flags) {
    char all[512];
    snprintf(all, sizeof all, MAP " %s", flags);
    const char *line = support_verbose_line("psm", scene, all, "psm: light 0:");
    assert_non_null(line);
    return line;
}

/* `scene` with each warp, as NAME_WARP. */
static void measure_warps(const char *scene, const char *name, shadowdiff_result r[3]) {
    for (int w = 0; w < 3; w++) {
        char flags[64], full_name[64];
        snprintf(flags, sizeof flags, "--warp %s", warps[w]);
        snprintf(full_name, sizeof full_name, "%s_%s", name, warps[w]);
        r[w] = measure(scene, flags, full_name);
    }
}

/* long_view: many casters receding to a horizon 500 units away, light at
 * 45 degrees. Both warps at least halve uniform's misclassified pixels. */
static void test_long_view_warps_halve_uniform(void **state) {
    (void)state;
    static const char *const scenes[] = {LONG_VIEW, LONG_VIEW_BEHIND};
    for (size_t s = 0; s < sizeof scenes / sizeof *scenes; s++) {
        shadowdiff_result r[3];
        measure_warps(scenes[s], s == 0 ? "long_view" : "long_view_behind", r);
        assert_true(r[0].misclassified_percent > 0.2); /* aliasing the warps must fix */
        assert_true(r[1].misclassified_percent <= 0.5 * r[0].misclassified_percent);
        assert_true(r[2].misclassified_percent <= 0.5 * r[0].misclassified_percent);
    }
}

/* 60 directions spread evenly over the sphere (a Fibonacci lattice), then
 * straight overhead, along the view (from behind the viewer), against it
 * (into the viewer's eyes) and 30 degrees above the view from behind. */
static void sweep_direction(int k, float out[3]) {
    static const float named[4][3] = {
        {0, -1, 0}, {0, -0.02222f, -0.99975f}, {0, 0.02222f, 0.99975f}, {0, -0.5f, -0.86603f}};
    if (k >= 60) {
        memcpy(out, named[k - 60], sizeof named[0]);
        return;
    }
    float y = 1 - 2 * ((float)k + 0.5f) / 60, r = sqrtf(1 - y * y), a = (float)k * 2.39996323f;
    out[0] = r * cosf(a), out[1] = y, out[2] = r * sinf(a);
}

/* long_view with light 0 travelling along `d`. */
static void write_sweep_scene(const char *path, const float d[3]) {
    FILE *in = fopen(LONG_VIEW, "r"), *out = fopen(path, "w");
    assert_non_null(in);
    assert_non_null(out);
    char line[4096];
    while (fgets(line, sizeof line, in)) {
        char *direction = strstr(line, "\"direction\": [");
        if (direction) {
            char *rest = strchr(direction, ']');
            assert_non_null(rest);
            *direction = '\0';
            fprintf(out, "%s\"direction\": [%.5f, %.5f, %.5f%s", line, d[0], d[1], d[2], rest);
        } else {
            fputs(line, out);
        }
    }
    fclose(in);
    assert_int_equal(fclose(out), 0);
}

static bool all_finite(const dump_frame *d) {
    for (long i = 0; i < (long)d->width * d->height; i++)
        if (!isfinite(d->visibility[i]))
            return false;
    return true;
}

/* SWEEP_DIRECTIONS light directions (every support_sweep_stride()th under
 * the sanitizers): no NaN or Inf in any picture, and at no direction
 * does a warp misclassify more than uniform by over SWEEP_RATIO (plus
 * SWEEP_SLACK_PIXELS); an inverted shadow would misclassify most of them.
 * Prints every direction's figures and the worst. */
static void test_light_direction_sweep(void **state) {
    (void)state;
    double worst_excess = -INFINITY;
    char worst[320] = "";
    assert_int_equal(system("mkdir -p out/test/psm"), 0);
    for (int k = 0; k < SWEEP_DIRECTIONS; k += support_sweep_stride()) {
        char scene[256], reference_dir[256];
        float d[3];
        sweep_direction(k, d);
        snprintf(scene, sizeof scene, "out/test/psm/sweep_%d.json", k);
        snprintf(reference_dir, sizeof reference_dir, "out/test/psm/sweep_%d_reference", k);
        write_sweep_scene(scene, d);
        assert_int_equal(support_dump("raytrace", scene, SWEEP_SIZE, reference_dir), 0);
        dump_frame reference;
        assert_true(dump_read(&reference, reference_dir));
        long misclassified[3];
        double percent[3];
        for (int w = 0; w < 3; w++) {
            char flags[128], dir[256];
            snprintf(flags, sizeof flags, SWEEP_SIZE " " MAP " --warp %s", warps[w]);
            snprintf(dir, sizeof dir, "out/test/psm/sweep_%d_%s", k, warps[w]);
            assert_int_equal(support_dump("psm", scene, flags, dir), 0);
            dump_frame test;
            assert_true(dump_read(&test, dir));
            assert_true(all_finite(&test));
            shadowdiff_result r;
            const shadowdiff_settings rules = {.grazing_degrees = SWEEP_GRAZING_DEGREES};
            assert_true(shadowdiff_compare(&reference, &test, &rules, &r, NULL));
            misclassified[w] = r.false_shadow + r.false_lit;
            percent[w] = r.misclassified_percent;
            dump_frame_free(&test);
        }
        dump_frame_free(&reference);
        char line[256];
        snprintf(line, sizeof line, "direction %2d (%+.3f %+.3f %+.3f): uniform %.3f %%, psm %.3f %%, lispsm %.3f %%",
                 k, d[0], d[1], d[2], percent[0], percent[1], percent[2]);
        fprintf(stderr, "    %s\n", line);
        for (int w = 1; w < 3; w++) {
            double excess = over_bound(misclassified[w], misclassified[0]);
            if (excess > worst_excess) {
                worst_excess = excess;
                snprintf(worst, sizeof worst, "%s (%s)", line, warps[w]);
            }
        }
    }
    fprintf(stderr, "    worst: %s, %+.0f pixels from the bound\n", worst, worst_excess);
    assert_true(worst_excess <= 0);
}

/* Each hard case takes its path, and says so on the HUD. */
static void test_hard_cases_take_their_path(void **state) {
    (void)state;
    /* The light behind the viewer lands beyond infinity in PPS: inverted. */
    const char *line = describe(LONG_VIEW_BEHIND, "");
    fprintf(stderr, "    behind: %s", line);
    assert_non_null(strstr(line, "psm 2D map"));
    assert_non_null(strstr(line, "light behind the viewer: inverted"));
    line = describe(LONG_VIEW, "");
    fprintf(stderr, "    in front: %s", line);
    assert_non_null(strstr(line, "light in front of the viewer"));
    /* Along the view: LiSPSM's n_opt is infinite, the map uniform. */
    assert_int_equal(system("mkdir -p out/test/psm"), 0);
    const float along[3] = {0, -0.02222f, -0.99975f};
    write_sweep_scene("out/test/psm/along_view.json", along);
    line = describe("out/test/psm/along_view.json", "--warp lispsm");
    fprintf(stderr, "    along the view: %s", line);
    assert_non_null(strstr(line, "uniform 2D map"));
    assert_non_null(strstr(line, "view parallel to the light"));
    /* A wall 34 units behind the camera shadows the view: the virtual
     * camera slides back past it, further than the optimum alone (43.2 in
     * long_view), and the wall's shadow is right. */
    line = describe("assets/scenes/psm_caster_behind.json", "");
    fprintf(stderr, "    caster behind: %s", line);
    const char *slide = strstr(line, "slid back ");
    assert_non_null(slide);
    assert_true(atof(slide + strlen("slid back ")) > 60);
    shadowdiff_result uniform = measure("assets/scenes/psm_caster_behind.json", "--warp uniform", "behind_uniform");
    shadowdiff_result warped = measure("assets/scenes/psm_caster_behind.json", "", "behind_psm");
    assert_true(warped.misclassified_percent <= 0.5 * uniform.misclassified_percent);
    /* A point light far above: warped in both; one among the receivers:
     * no single frustum holds what it lights, so the cube map stays. */
    static const char *const point_scenes[] = {"assets/scenes/psm_point_high.json",
                                               "assets/scenes/psm_point_low.json"};
    for (int s = 0; s < 2; s++) {
        shadowdiff_result r[3];
        measure_warps(point_scenes[s], s == 0 ? "point_high" : "point_low", r);
        for (int w = 1; w < 3; w++)
            assert_true(over_bound(r[w].false_shadow + r[w].false_lit, r[0].false_shadow + r[0].false_lit) <= 0);
    }
    line = describe("assets/scenes/psm_point_high.json", "");
    fprintf(stderr, "    point light high: %s", line);
    assert_non_null(strstr(line, "psm 2D map"));
    line = describe("assets/scenes/psm_point_low.json", "");
    fprintf(stderr, "    point light low: %s", line);
    assert_non_null(strstr(line, "uniform cube map"));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_long_view_warps_halve_uniform),
        cmocka_unit_test(test_light_direction_sweep),
        cmocka_unit_test(test_hard_cases_take_their_path),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
