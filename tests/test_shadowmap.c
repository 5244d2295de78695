/* Shadow maps against the ray-traced reference, with shadowdiff's fixed
 * rules; each test prints the figures it measured. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dump.h"
#include "flags.h"
#include "map.h"
#include "shadowdiff.h"
#include "support.h"

#define STANDARD_MAX_MISCLASSIFIED_PERCENT 0.5
#define BENCH_SIZE "--size 1280x720" /* make bench's frame size */
/* A spot with a range far down a street seen from eye height: its pool
 * is a band a few pixels high on the ground, a wall's shadow in it. */
#define FAR_LAMP_SCENE "tests/data/map_far_lamp.json"
/* Of the wall's shadow's pixels there, at most this share misclassified. */
#define FAR_LAMP_MAX_WRONG_SHARE 0.25
#define STRESS_SIZE "--size 320x180" /* make stress's */
#define STRESS_MIN_COMPARED 30000    /* of its 57600 pixels: the receivers seen */

static shadowdiff_result measure_dumps(const char *scene, const char *size, const char *flags, const char *name,
                                       dump_frame *reference, dump_frame *test, unsigned char **heatmap) {
    return support_measure_dumps("shadowmap", scene, size, flags, name, reference, test, heatmap);
}

static shadowdiff_result measure_sized(const char *scene, const char *size, const char *flags, const char *name) {
    return support_measure("shadowmap", scene, size, flags, name);
}

static shadowdiff_result measure(const char *scene, const char *flags, const char *name) {
    return support_measure("shadowmap", scene, "", flags, name);
}

/* shadowdiff paints false-lit pixels pure blue in its heat map. */
static bool false_lit(const unsigned char *heatmap, long i) {
    return heatmap[i * 4] == 0 && heatmap[i * 4 + 1] == 0 && heatmap[i * 4 + 2] == 255;
}

/* Spot (simple), point with a cube map (bunny), directional (teapot). */
static void test_standard_scenes_within_bound(void **state) {
    (void)state;
    support_standard_scenes_within("shadowmap", STANDARD_MAX_MISCLASSIFIED_PERCENT);
}

/* Lights a single map of their own kind cannot serve (the stress suite's
 * extremes): a spot wider than a 2D map can hold (89.5 degrees: a 2D
 * map's frustum must stop short of 90, and what lay outside it would read
 * lit) gets a cube map; a point light a million units away, whose
 * receivers lie in a cone a few microradians wide (a cube face's texel
 * would span hundreds of units there and lose every ground shadow), gets
 * one perspective map around them. Within the shadow maps' bound. */
static void test_extreme_lights_within_bound(void **state) {
    (void)state;
    static const char *const scenes[] = {"shadowmap_wide_spot", "shadowmap_far_point"};
    for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++) {
        char path[256];
        snprintf(path, sizeof path, "tests/data/%s.json", scenes[i]);
        shadowdiff_result r = measure(path, "", scenes[i]);
        fprintf(stderr, "    %s: %.3f %% misclassified of %ld pixels (bound %.1f %%)\n", scenes[i],
                r.misclassified_percent, r.compared, STANDARD_MAX_MISCLASSIFIED_PERCENT);
        assert_true(r.compared > 50000);
        assert_true(r.misclassified_percent <= STANDARD_MAX_MISCLASSIFIED_PERCENT);
    }
}

/* The stress suite's shadow-map extremes, at its picture size (320x180),
 * through both techniques on the shared fit and camera pass: a spot 1e4
 * away, whose map around its whole 38-degree cone would have texels of 2
 * units and lose the sphere's shadow, gets a map around the receivers; a
 * sun 0.1 degrees above the ground, whose map sized on the casters' sides
 * alone would be small, gets the most texels; with the camera inside a
 * box, a face turned from the light gets the closed mesh's own shadow,
 * not false light along its corner (map.frag,
 * map_through_closed). */
static void test_stress_extremes_within_bound(void **state) {
    (void)state;
    static const char *const scenes[] = {"shadowmap_far_spot", "shadowmap_grazing_sun", "shadowmap_camera_inside"};
    static const char *const programs[] = {"shadowmap", "psm"};
    for (size_t p = 0; p < sizeof programs / sizeof *programs; p++) {
        for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++) {
            char path[256], name[64];
            snprintf(path, sizeof path, "tests/data/%s.json", scenes[i]);
            snprintf(name, sizeof name, "%s_%s", programs[p], scenes[i] + strlen("shadowmap_"));
            shadowdiff_result r = support_measure(programs[p], path, STRESS_SIZE, "", name);
            assert_true(r.compared > STRESS_MIN_COMPARED);
            assert_true(r.misclassified_percent <= STANDARD_MAX_MISCLASSIFIED_PERCENT);
        }
    }
}

/* A ground that casts onto itself and nothing else, lit from `elevation`
 * degrees above the horizon: every shadow on it is acne. */
static void write_acne_scene(const char *path, const char *light_type, float elevation) {
    float e = elevation * 3.14159265f / 180, c = cosf(e), s = sinf(e);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    if (light_type[0] == 'd')
        fprintf(f,
                "{\"camera\": {\"position\": [0, 7, 12], \"target\": [0, 0, 0]},\n"
                " \"lights\": [{\"type\": \"directional\", \"direction\": [%g, %g, %g]}],\n",
                -c * 0.8f, -s, -c * 0.6f);
    else
        fprintf(f,
                "{\"camera\": {\"position\": [0, 7, 12], \"target\": [0, 0, 0]},\n"
                " \"lights\": [{\"type\": \"point\", \"position\": [%g, %g, %g]}],\n",
                c * 8, s * 8 + 0.01f, c * 6);
    fprintf(f, " \"objects\": [{\"name\": \"ground\", \"mesh\": {\"kind\": \"plane\", \"size\": [20, 20]}}]}\n");
    fclose(f);
}

static void test_no_acne_at_any_elevation(void **state) {
    (void)state;
    static const float elevations[] = {5, 10, 20, 30, 45, 60, 75, 90};
    static const char *const types[] = {"directional", "point"};
    assert_int_equal(system("mkdir -p out/test/shadowmap"), 0);
    for (size_t t = 0; t < 2; t++) {
        /* Under the sanitizers every support_sweep_stride()th elevation. */
        for (size_t i = 0; i < sizeof elevations / sizeof *elevations; i += (size_t)support_sweep_stride()) {
            char path[256], name[64];
            snprintf(name, sizeof name, "acne_%s_%g", types[t], elevations[i]);
            snprintf(path, sizeof path, "out/test/shadowmap/%s.json", name);
            write_acne_scene(path, types[t], elevations[i]);
            shadowdiff_result r = measure(path, "", name);
            assert_true(r.compared > 10000);
            assert_int_equal(r.false_shadow, 0);
        }
    }
}

/* The sweep can see acne: with every bias off it is there. */
static void test_acne_without_bias(void **state) {
    (void)state;
    write_acne_scene("out/test/shadowmap/acne_unbiased.json", "directional", 30);
    shadowdiff_result r =
        measure("out/test/shadowmap/acne_unbiased.json", "--no-constant-bias --no-slope-bias", "acne_unbiased");
    assert_true(r.false_shadow_percent > 1);
}

/* A bias turned off reads the map with one nearest test while the filter
 * is auto (the default), so that acne shows unblurred: by the window's
 * keys (C, L: the flag table's toggles), back to the disc when the bias
 * is back, and by the flags; a filter chosen (F, --filter) holds, and an
 * area light is hard meanwhile. Each shadow-map technique's state line
 * says so. */
static void test_bias_off_reads_unfiltered(void **state) {
    (void)state;
    map_settings st = {0};
    const flags_param params[] = {MAP_PARAMS(st)};
    const int count = (int)(sizeof params / sizeof *params);
    const scene_light area = {.radius = 0.5f};
    assert_int_equal(map_filter_in_use(&st), MAP_FILTER_POISSON);
    assert_true(map_light_soft(&st, &area));
    assert_true(flags_press_key(params, count, GLFW_KEY_C));
    assert_int_equal(map_filter_in_use(&st), MAP_FILTER_NONE);
    assert_false(map_light_soft(&st, &area));
    assert_true(flags_press_key(params, count, GLFW_KEY_C));
    assert_int_equal(map_filter_in_use(&st), MAP_FILTER_POISSON);
    assert_true(flags_press_key(params, count, GLFW_KEY_L));
    assert_int_equal(map_filter_in_use(&st), MAP_FILTER_NONE);
    assert_true(flags_press_key(params, count, GLFW_KEY_F)); /* auto -> poisson, chosen */
    assert_int_equal(map_filter_in_use(&st), MAP_FILTER_POISSON);
    assert_true(map_light_soft(&st, &area));
    static const struct {
        const char *flags;
        map_filter filter;
    } cases[] = {
        {"--no-slope-bias", MAP_FILTER_NONE},
        {"--no-constant-bias --filter pcf3", MAP_FILTER_PCF3},
        {"--no-constant-bias --filter auto", MAP_FILTER_NONE},
        {"--filter auto", MAP_FILTER_POISSON},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char text[128], *argv[8];
        snprintf(text, sizeof text, "%s", cases[i].flags);
        int argc = 0;
        for (char *word = strtok(text, " "); word && argc < 8; word = strtok(NULL, " "))
            argv[argc++] = word;
        flags_reset(params, count);
        assert_int_equal(flags_parse("test", params, count, argc, argv), 0);
        if (map_filter_in_use(&st) != cases[i].filter)
            fail_msg("%s: filter %d in use, expected %d", cases[i].flags, map_filter_in_use(&st), cases[i].filter);
    }
    static const char *const programs[] = {"shadowmap", "psm", "cascades"};
    for (size_t i = 0; i < sizeof programs / sizeof *programs; i++) {
        char marker[32];
        snprintf(marker, sizeof marker, "%s: light 0:", programs[i]);
        const char *line = support_verbose_line(programs[i], "assets/scenes/teapot.json", "--no-slope-bias", marker);
        if (!line || !strstr(line, ", filter: none (shows acne)\n"))
            fail_msg("%s --no-slope-bias: state line \"%s\"", programs[i], line ? line : "(none)");
        line = support_verbose_line(programs[i], "assets/scenes/teapot.json", "", marker);
        if (!line || strstr(line, "shows acne"))
            fail_msg("%s: state line \"%s\"", programs[i], line ? line : "(none)");
    }
}

/* The state line says "shows acne" only where acne shows: with each bias
 * off, and both, on each standard scene (the quick tier each setting on
 * one scene in turn: support_sweep_takes), its claim against the false
 * shadow measured (lit in the reference, shadowed here), at least
 * ACNE_SHOWN_PERCENT of the compared pixels where it claims acne, less
 * where it does not. */
#define ACNE_SHOWN_PERCENT 0.2
static void test_state_line_claims_acne_where_it_shows(void **state) {
    (void)state;
    static const char *const scenes[] = {"simple", "bunny", "teapot"};
    static const char *const bias_off[] = {"--no-constant-bias", "--no-slope-bias",
                                           "--no-constant-bias --no-slope-bias"};
    int scene_count = (int)(sizeof scenes / sizeof *scenes);
    for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++)
        for (size_t k = 0; k < sizeof bias_off / sizeof *bias_off; k++) {
            if (!support_sweep_takes((int)k, (int)i, scene_count))
                continue;
            char scene[256], name[64], state_line[512];
            snprintf(scene, sizeof scene, "assets/scenes/%s.json", scenes[i]);
            snprintf(name, sizeof name, "acne_claim_%s_%zu", scenes[i], k);
            const char *line = support_verbose_line("shadowmap", scene, bias_off[k], "shadowmap: light 0:");
            assert_non_null(line);
            snprintf(state_line, sizeof state_line, "%.*s", (int)strcspn(line, "\n"), line);
            bool claimed = strstr(state_line, "shows acne") != NULL;
            shadowdiff_result r = measure(scene, bias_off[k], name);
            printf("    %s %s: false shadow %.3f %%, \"%s\"\n", scenes[i], bias_off[k], r.false_shadow_percent,
                   state_line);
            if (claimed != (r.false_shadow_percent >= ACNE_SHOWN_PERCENT))
                fail_msg("%s %s: the state line %s acne, and %.3f %% of the pixels are false shadow", scenes[i],
                         bias_off[k], claimed ? "claims" : "does not claim", r.false_shadow_percent);
        }
}

/* The two configurations tutorials teach, as in the benchmark's sweep and
 * at its frame size (where the criterion is stated; at 640x360 the whole
 * margin is a handful of pixels), their taps at the centre's depth as the
 * tutorials'. The defaults were chosen by misclassified % and lit MAE
 * together: on every standard scene neither textbook configuration is
 * more accurate than the defaults by both (that they also take no more
 * time is for `make bench` to show: its report says so per scene). And
 * our biases
 * against theirs at the same map size and filter, so at the same cost
 * (same passes, same taps, the centre's depth): ours must misclassify no
 * more on any standard scene and less over all of them. */
static void test_defaults_and_our_bias_beat_textbook(void **state) {
    (void)state;
    static const char *const pairs[][2] = {
        {"--map-size 1024 --filter pcf3 --kernel-depth centre",
         "--map-size 1024 --filter pcf3 --kernel-depth centre --no-constant-bias --no-slope-bias --depth-bias-slope "
         "0.05 --depth-bias-min 0.005"},
        {"--filter pcf3 --kernel-depth centre",
         "--filter pcf3 --kernel-depth centre --no-constant-bias --slope-factor 1.25 --slope-units 1.75"},
    };
    static const char *const scenes[] = {"simple", "bunny", "teapot"};
    double ours_total[2] = {0}, textbook_total[2] = {0};
    for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++) {
        char path[256], name[64];
        snprintf(path, sizeof path, "assets/scenes/%s.json", scenes[i]);
        snprintf(name, sizeof name, "%s_defaults", scenes[i]);
        shadowdiff_result defaults = measure_sized(path, BENCH_SIZE, "", name);
        for (size_t k = 0; k < sizeof pairs / sizeof *pairs; k++) {
            snprintf(name, sizeof name, "%s_ours_%zu", scenes[i], k + 1);
            shadowdiff_result ours = measure_sized(path, BENCH_SIZE, pairs[k][0], name);
            snprintf(name, sizeof name, "%s_textbook_%zu", scenes[i], k + 1);
            shadowdiff_result textbook = measure_sized(path, BENCH_SIZE, pairs[k][1], name);
            const double lit = defaults.class_mae[SHADOWDIFF_CLASS_LIT];
            const double textbook_lit = textbook.class_mae[SHADOWDIFF_CLASS_LIT];
            fprintf(stderr,
                    "    %s, textbook %zu: misclassified %.4f %% (defaults %.4f %%), lit MAE %.5f (defaults %.5f)\n",
                    scenes[i], k + 1, textbook.misclassified_percent, defaults.misclassified_percent, textbook_lit,
                    lit);
            assert_false(textbook.misclassified_percent < defaults.misclassified_percent && textbook_lit < lit);
            assert_true(ours.misclassified_percent <= textbook.misclassified_percent);
            ours_total[k] += ours.misclassified_percent;
            textbook_total[k] += textbook.misclassified_percent;
        }
    }
    for (size_t k = 0; k < sizeof pairs / sizeof *pairs; k++) {
        fprintf(stderr, "    textbook %zu: summed misclassified %% ours %.4f, textbook %.4f\n", k + 1, ours_total[k],
                textbook_total[k]);
        assert_true(ours_total[k] < textbook_total[k]);
    }
}

/* Receiver-plane taps (the default; Isidoro, GDC 2006) against taps at
 * the centre's depth, which reach texels of a flat or slanted receiver
 * itself and speckle it with partial acne. By the lit class (the truth
 * fully lit): at most half the centre depth's error, with a wide kernel
 * on a spot and a point light, and with the default's on flat box tops
 * under a spot and a point light, where it must also misclassify no more
 * than a tenth above the centre depth's: the defaults were chosen by both
 * figures. The flat boxes at the bench's size, where the automatic map
 * size is the one the bench measures. */
#define PLANE_LIT_SHARE_OF_CENTRE 0.5
#define PLANE_MISCLASSIFIED_SHARE_OF_CENTRE 1.1
static void test_receiver_plane_removes_partial_acne(void **state) {
    (void)state;
    static const struct {
        const char *scene, *size, *filter;
        bool default_filter; /* also the misclassified bound */
    } cases[] = {
        {"simple", "", "--filter pcf7", false},
        {"bunny", "", "--filter pcf7", false},
        {"flat_boxes", BENCH_SIZE, "", true},
        {"flat_boxes_point", BENCH_SIZE, "", true},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char path[256], name[64], flags[64];
        snprintf(path, sizeof path, "assets/scenes/%s.json", cases[i].scene);
        snprintf(name, sizeof name, "%s_plane_%zu", cases[i].scene, i);
        shadowdiff_result plane = measure_sized(path, cases[i].size, cases[i].filter, name);
        snprintf(name, sizeof name, "%s_centre_%zu", cases[i].scene, i);
        snprintf(flags, sizeof flags, "%s --kernel-depth centre", cases[i].filter);
        shadowdiff_result centre = measure_sized(path, cases[i].size, flags, name);
        const double p = plane.class_mae[SHADOWDIFF_CLASS_LIT], c = centre.class_mae[SHADOWDIFF_CLASS_LIT];
        fprintf(stderr, "    %s %s: lit MAE %.5f (centre %.5f), misclassified %.4f %% (centre %.4f %%)\n",
                cases[i].scene, cases[i].filter, p, c, plane.misclassified_percent, centre.misclassified_percent);
        assert_true(p <= PLANE_LIT_SHARE_OF_CENTRE * c);
        if (cases[i].default_filter)
            assert_true(plane.misclassified_percent <=
                        PLANE_MISCLASSIFIED_SHARE_OF_CENTRE * centre.misclassified_percent);
    }
}

/* The tents (tent3, tent5: 4 and 9 bilinear taps, map.glsl) on the
 * standard scenes (the quick tier each size on one scene in turn, a spot
 * light's 2D map and a point light's cube map: support_sweep_takes):
 * within the same bound as the defaults, and blurring less than the N x N
 * grid of as many texels (pcfN, N^2 taps: its weights reach a texel
 * farther): a lower mean error (the test prints both). */
static void test_tents_within_bound_and_sharper_than_grids(void **state) {
    (void)state;
    static const char *const scenes[] = {"simple", "bunny", "teapot"};
    static const int sizes[] = {3, 5};
    int scene_count = (int)(sizeof scenes / sizeof *scenes);
    for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++)
        for (size_t k = 0; k < sizeof sizes / sizeof *sizes; k++) {
            if (!support_sweep_takes((int)k, (int)i, scene_count))
                continue;
            char path[256], name[64], flags[64];
            snprintf(path, sizeof path, "assets/scenes/%s.json", scenes[i]);
            snprintf(name, sizeof name, "%s_tent%d", scenes[i], sizes[k]);
            snprintf(flags, sizeof flags, "--filter tent%d", sizes[k]);
            shadowdiff_result tent = measure(path, flags, name);
            snprintf(name, sizeof name, "%s_pcf%d", scenes[i], sizes[k]);
            snprintf(flags, sizeof flags, "--filter pcf%d", sizes[k]);
            shadowdiff_result grid = measure(path, flags, name);
            fprintf(stderr, "    %s, N = %d: mean error tent %.5f, pcf %.5f\n", scenes[i], sizes[k],
                    tent.mean_abs_error, grid.mean_abs_error);
            assert_true(tent.compared > 50000);
            assert_true(tent.misclassified_percent <= STANDARD_MAX_MISCLASSIFIED_PERCENT);
            assert_true(tent.mean_abs_error < grid.mean_abs_error);
        }
}

/* Pixels of a surface whose lit / shadowed decision differs between two
 * dumps of the same frame; *changed: those whose visibility differs at all. */
static long decisions_differing(const dump_frame *a, const dump_frame *b, long *changed) {
    long differing = 0;
    *changed = 0;
    for (long i = 0; i < (long)a->width * a->height; i++) {
        if (a->ids[i] < 0)
            continue;
        *changed += a->visibility[i] != b->visibility[i];
        differing += (a->visibility[i] >= SHADOWDIFF_LIT_THRESHOLD) != (b->visibility[i] >= SHADOWDIFF_LIT_THRESHOLD);
    }
    return differing;
}

/* The early-out (four rim taps first, map.glsl) answers alone only
 * where those agree wholly; a feature thinner than the kernel between them
 * would change that answer. On the standard scenes and long_view it
 * changes no decision with any kernel it applies to (it only snaps
 * near-0 and near-1 values in penumbrae, which lowers the mean error). */
static void test_early_out_changes_no_decision(void **state) {
    (void)state;
    static const char *const scenes[] = {"simple", "bunny", "teapot", "long_view"};
    static const char *const filters[] = {"poisson", "pcf3", "pcf5", "pcf7", "tent5"};
    enum { SCENE_COUNT = sizeof scenes / sizeof *scenes, FILTER_COUNT = sizeof filters / sizeof *filters };
    /* Under the sanitizers every support_sweep_stride()th pair, spread
     * over every scene and filter. */
    SUPPORT_SWEEPABLE(FILTER_COUNT);
    assert_int_equal(system("mkdir -p out/test/shadowmap"), 0);
    for (size_t pair = 0; pair < SCENE_COUNT * FILTER_COUNT; pair += (size_t)support_sweep_stride()) {
        size_t i = pair / FILTER_COUNT, k = pair % FILTER_COUNT;
        char path[256], dirs[2][256], flags[64];
        snprintf(path, sizeof path, "assets/scenes/%s.json", scenes[i]);
        dump_frame frames[2];
        for (int off = 0; off < 2; off++) {
            snprintf(dirs[off], sizeof dirs[off], "out/test/shadowmap/early_out_%s_%s_%s", scenes[i], filters[k],
                     off ? "off" : "on");
            snprintf(flags, sizeof flags, "--filter %s%s", filters[k], off ? " --no-early-out" : "");
            assert_int_equal(support_dump("shadowmap", path, flags, dirs[off]), 0);
            assert_true(dump_read(&frames[off], dirs[off]));
        }
        long changed, differing = decisions_differing(&frames[0], &frames[1], &changed);
        fprintf(stderr, "    %s, %s: early-out changes %ld pixels' visibility, %ld decisions\n", scenes[i],
                filters[k], changed, differing);
        assert_int_equal(differing, 0);
        dump_frame_free(&frames[0]);
        dump_frame_free(&frames[1]);
    }
}

/* A gap pixel lies inside the reference's shadow: each of its four
 * neighbours is shadowed ground or the box. A false-lit pixel with a lit
 * neighbour is on the shadow's outline: edge aliasing, not a gap. */
static bool inside_reference_shadow(const dump_frame *r, long i) {
    long x = i % r->width, y = i / r->width;
    if (x == 0 || y == 0 || x == r->width - 1 || y == r->height - 1)
        return false;
    const long neighbours[4] = {i - 1, i + 1, i - r->width, i + r->width};
    for (int k = 0; k < 4; k++) {
        long n = neighbours[k];
        if (r->ids[n] != 1 && (r->ids[n] != 0 || r->visibility[n] >= SHADOWDIFF_LIT_THRESHOLD))
            return false;
    }
    return true;
}

/* The widest false-lit gap between the box of tests/data/
 * shadowmap_contact.json (a unit cube on the ground at the origin) and
 * its shadow: the largest distance from the box's footprint of a false-lit
 * ground pixel inside the reference's shadow within half a unit of it. */
static double contact_gap(const char *flags, const char *name) {
    dump_frame reference, test;
    unsigned char *heatmap;
    measure_dumps("tests/data/shadowmap_contact.json", "", flags, name, &reference, &test, &heatmap);
    double widest = 0;
    for (long i = 0; i < (long)reference.width * reference.height; i++) {
        if (reference.ids[i] != 0 || !false_lit(heatmap, i) || !inside_reference_shadow(&reference, i))
            continue;
        const float *p = &reference.position[i * 3];
        double dx = fmax(fabs(p[0]) - 0.5, 0), dz = fmax(fabs(p[2]) - 0.5, 0), d = sqrt(dx * dx + dz * dz);
        if (d < 0.5)
            widest = fmax(widest, d);
    }
    free(heatmap);
    dump_frame_free(&reference);
    dump_frame_free(&test);
    return widest;
}

/* Peter-panning: no lit band between a resting box and its shadow wider
 * than one map texel. The map covers at most the 20 x 20 ground's
 * diagonal, so a texel is at most that over the map size. */
static void test_no_peter_panning_at_contact(void **state) {
    (void)state;
    const double texel = 20 * sqrt(2.0) / 2048;
    double gap = contact_gap("", "contact");
    fprintf(stderr, "    contact gap %.5f world units, one texel at most %.5f\n", gap, texel);
    assert_true(gap <= texel);
    /* The measure bites: a bias of 40 texels detaches the shadow. */
    double detached = contact_gap("--constant-texels 40", "contact_detached");
    fprintf(stderr, "    with a 40-texel bias: gap %.5f\n", detached);
    assert_true(detached > 4 * texel);
}

/* A point light's cube map has no seams: false-lit pixels whose direction
 * from the light lies near a face edge (its two largest components within
 * a hundredth of the largest) are at most 5e-4 of the compared pixels. */
static void test_no_cube_seams(void **state) {
    (void)state;
    dump_frame reference, test;
    unsigned char *heatmap;
    shadowdiff_result r =
        measure_dumps("tests/data/shadowmap_cube_edges.json", "", "", "cube_edges", &reference, &test, &heatmap);
    long on_edges = 0, false_lit_on_edges = 0;
    for (long i = 0; i < (long)reference.width * reference.height; i++) {
        if (reference.ids[i] < 0)
            continue;
        double a[3];
        for (int k = 0; k < 3; k++)
            a[k] = fabs(reference.position[i * 3 + k] - reference.light[k]);
        double largest = fmax(a[0], fmax(a[1], a[2])),
               second = a[0] + a[1] + a[2] - largest - fmin(a[0], fmin(a[1], a[2]));
        if (largest - second > 0.01 * largest)
            continue;
        on_edges++;
        false_lit_on_edges += false_lit(heatmap, i);
    }
    double percent = 100.0 * false_lit_on_edges / r.compared;
    fprintf(stderr, "    %ld pixels near cube-face edges, %ld false lit: %.4f %% of %ld compared\n", on_edges,
            false_lit_on_edges, percent, r.compared);
    assert_true(on_edges > 1000);
    assert_true(percent <= 0.05);
    free(heatmap);
    dump_frame_free(&reference);
    dump_frame_free(&test);
}

/* --map-size auto, the default, sizes each map so that a texel covers
 * about a pixel where the camera sees its receivers (at most 1 on average,
 * rounded up to a power of two; a quarter of one for a hard light over
 * cut-outs): the same scene needs half the map in a picture half as wide,
 * a long view the most (capped at 4096), and a size given stays as given;
 * the HUD's line says which ("auto: 2048" or "2048"). */
static void test_map_size_from_need(void **state) {
    (void)state;
    static const struct {
        const char *program, *scene, *flags, *expected;
    } cases[] = {
        {"shadowmap", "assets/scenes/simple.json", BENCH_SIZE, "2D map auto: 2048,"},
        {"shadowmap", "assets/scenes/simple.json", "", "2D map auto: 1024,"},
        {"shadowmap", "assets/scenes/bunny.json", BENCH_SIZE, "cube map auto: 2048,"},
        {"shadowmap", "assets/scenes/long_view.json", BENCH_SIZE, "2D map auto: 4096,"},
        {"shadowmap", "assets/scenes/simple.json", BENCH_SIZE " --map-size 512", "2D map 512,"},
        {"psm", "assets/scenes/teapot.json", BENCH_SIZE, "psm 2D map auto: 2048 "},
        {"psm", "assets/scenes/teapot.json", "", "psm 2D map auto: 1024 "},
        {"psm", "assets/scenes/teapot.json", "--map-size 2048", "psm 2D map 2048 "},
        /* A far lamp's pool, a band a few pixels high between the rows of
         * the picture's grid: measured on the grid over its reach, not
         * given the fallback (test_far_lamp_drawn_from_its_small_map). */
        {"shadowmap", FAR_LAMP_SCENE, BENCH_SIZE, "2D map auto: 256,"},
        /* The same pool behind a post whose face, all the picture's grid
         * sees in the lamp's reach, is edge-on to it: the pool's grid
         * decides, not the grazing rule. */
        {"shadowmap", "tests/data/map_far_lamp_edge_on.json", BENCH_SIZE, "2D map auto: 256,"},
        /* A hard sun over cut-out casters: texels four times finer
         * (test_gltf_fence_within_goal_by_auto_maps); a point light's
         * cube and a spot's map over them as fine, within
         * MAP_AUTO_MAX_SIZE; the same fence under a sun of 2 degrees keeps
         * its usual texels, which PCSS's blocker search needs. */
        {"shadowmap", "assets/scenes/fence.gltf", BENCH_SIZE, "2D map auto: 8192,"},
        {"shadowmap", "tests/data/fence_point_light.json", BENCH_SIZE, "cube map auto: 4096,"},
        {"shadowmap", "tests/data/fence_spot.json", "", "2D map auto: 4096,"},
        {"shadowmap", "tests/data/fence_soft_sun.json", BENCH_SIZE, "2D map auto: 2048,"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char marker[64];
        const char *scene = cases[i].scene;
        snprintf(marker, sizeof marker, "%s: light 0:", cases[i].program);
        const char *line = support_verbose_line(cases[i].program, scene, cases[i].flags, marker);
        assert_non_null(line);
        fprintf(stderr, "    %s %s %s: %.*s", cases[i].program, cases[i].scene, cases[i].flags,
                (int)strcspn(line, "\n") + 1, line);
        assert_non_null(strstr(line, cases[i].expected));
    }
}

/* The far lamp's map, sized by its pool (test_map_size_from_need), draws
 * the wall's shadow in it as the reference does. */
static void test_far_lamp_drawn_from_its_small_map(void **state) {
    (void)state;
    shadowdiff_result r = support_measure("shadowmap", FAR_LAMP_SCENE, BENCH_SIZE, "", "shadowmap_far_lamp");
    /* The shadow's pixels: those the unshadowed floor draws lit. */
    shadowdiff_result floor = support_measure("unshadowed", FAR_LAMP_SCENE, BENCH_SIZE, "", "unshadowed_far_lamp");
    long shadow = floor.false_lit, wrong = r.false_shadow + r.false_lit;
    printf("    far lamp: %ld pixels in the wall's shadow, %ld misclassified\n", shadow, wrong);
    assert_true(shadow > 0);
    assert_true((double)wrong <= FAR_LAMP_MAX_WRONG_SHARE * (double)shadow);
}

/* --overlay map's inset fitted to what the map holds
 * (support_expect_insets_fitted): long_view's sun (one orthographic map
 * over 400 units of road, whose posts are a texel or two wide: the inset
 * shows each block's nearest depth), simple's spot and bunny's point
 * light (a cube, its six faces one inset). */
static void test_inset_fitted_to_its_map(void **state) {
    (void)state;
    static const struct {
        const char *scene;
        map_kind kind;
        int layers;
    } cases[] = {{"long_view", MAP_2D, 1}, {"simple", MAP_2D, 1}, {"bunny", MAP_CUBE, 6}};
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char scene[256], name[64];
        snprintf(scene, sizeof scene, "assets/scenes/%s.json", cases[i].scene);
        snprintf(name, sizeof name, "shadowmap_inset_%s", cases[i].scene);
        free(support_expect_insets_fitted("shadowmap", scene, "--overlay map", name, cases[i].kind, cases[i].layers,
                                          0));
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_standard_scenes_within_bound),
        cmocka_unit_test(test_extreme_lights_within_bound),
        cmocka_unit_test(test_stress_extremes_within_bound),
        cmocka_unit_test(test_no_acne_at_any_elevation),
        cmocka_unit_test(test_acne_without_bias),
        cmocka_unit_test(test_bias_off_reads_unfiltered),
        cmocka_unit_test(test_state_line_claims_acne_where_it_shows),
        cmocka_unit_test(test_defaults_and_our_bias_beat_textbook),
        cmocka_unit_test(test_receiver_plane_removes_partial_acne),
        cmocka_unit_test(test_tents_within_bound_and_sharper_than_grids),
        cmocka_unit_test(test_early_out_changes_no_decision),
        cmocka_unit_test(test_no_peter_panning_at_contact),
        cmocka_unit_test(test_no_cube_seams),
        cmocka_unit_test(test_map_size_from_need),
        cmocka_unit_test(test_far_lamp_drawn_from_its_small_map),
        cmocka_unit_test(test_inset_fitted_to_its_map),
    };
    return cmocka_run_group_tests_name("shadow maps against the reference", tests, NULL, NULL);
}
