/* Smoke test of the benchmark (make bench QUICK=1): it runs end to end and
 * its outputs exist and are well formed; the selections (--technique,
 * --configs), --motion, --skips-compare and --scaling give the rows and
 * files they say; each row's ratio is to its own interleaved floor frames,
 * with an interval about it where it has the frames for one, the floor's
 * own row against a twin of itself, and the report's floor check says
 * so; the report's fronts, one per
 * error figure, agree with its own table; the error of several frames
 * pools theirs (--error-frames). Nothing about speed is asserted:
 * speed is for `make bench` to show, not for a test to guess. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "plot.h"
#include "support.h"

#define OUT "out/test/bench"
/* The selection runs: small and short, on one scene. */
#define SELECT_OUT OUT "-select"
#define LIGHT_OUT OUT "-light"
#define DOLLY_OUT OUT "-dolly"
/* The dolly run's two error frames (its default under a motion, at most
 * its two timed frames), each the last timed frame of a run of its own. */
#define DOLLY_FIRST_OUT OUT "-dolly-first"
#define DOLLY_LAST_OUT OUT "-dolly-last"
#define DOLLY_FLAGS SMALL_SCENE " --motion dolly --technique shadowmap"
#define DOLLY_RUN "--frames 2 " DOLLY_FLAGS
#define SMALL_SCENE "--quick --configs defaults assets/scenes/simple.json"
#define SMALL_RUN "--frames 2 " SMALL_SCENE
/* An area light's scene, every shadowmap configuration: the penumbra's
 * figures, its plot and its front. */
#define SOFT_OUT OUT "-soft"
#define SOFT_SCENE "soft_table"
#define SOFT_RUN "--quick --frames 2 --technique shadowmap assets/scenes/" SOFT_SCENE ".json"
/* --light: light 0 and light 2 of a scene of three, planar and the floor;
 * planar's decisions for a light agree with that light's truth within
 * this many percent misclassified. */
#define LAMP_OUT OUT "-lamp"
#define LAMP2_OUT OUT "-lamp2"
#define LAMP_RUN "--quick --frames 1 --configs defaults --technique planar tests/data/planar_three_lights.json"
#define LAMP_MAX_MISCLASSIFIED 1.0
/* A run with the fewest timed frames whose ratios have an interval
 * (median_interval_min_samples at RESULTS_CSV_RATIO_CONFIDENCE). */
#define INTERVAL_OUT OUT "-interval"
/* --configs-with twice: shadowmap's defaults and the rows holding either
 * text, one each. */
#define WITH_OUT OUT "-with"
#define WITH_RUN                                                                                                     \
    "--quick --frames 1 --technique shadowmap --configs-with budget --configs-with 'filter hw' "                     \
    "assets/scenes/simple.json"
/* A run whose shadowmap configuration fails: its shaders, a broken copy. */
#define BROKEN_OUT OUT "-broken"
#define BROKEN_SHADERS OUT "-broken-shaders"
#define INTERVAL_FRAMES 11
#define TEXT(x) #x
#define TEXT_OF(x) TEXT(x)
#define INTERVAL_FRAMES_TEXT TEXT_OF(INTERVAL_FRAMES)
#define CSV_COLUMNS 29
#define CSV_MAX_ROWS 512
/* results.csv's columns the tests read by position. */
#define CSV_GPU_MEDIAN 3
#define CSV_CPU_MEDIAN 5
#define CSV_RATIO 7
#define CSV_MISCLASSIFIED 10
#define CSV_MAE 11
#define CSV_COMPARED 12
#define CSV_RENDERER 13
#define CSV_MOTION 14
#define CSV_SKIPS 15
#define CSV_FLOOR_MS 16
#define CSV_RATIO_LOW 17
#define CSV_RATIO_HIGH 18
#define CSV_SHIMMER 19
/* Then per shadowdiff class (umbra, penumbra, lit) its pixels and MAE,
 * then the frame size, then the rays (technique.rays: "-" for a technique
 * without them). */
#define CSV_CLASS_PIXELS(c) (20 + 2 * (c))
#define CSV_CLASS_MAE(c) (21 + 2 * (c))
#define CSV_FRAME_SIZE 26
#define CSV_TRACED 27
#define CSV_RAYS 28
/* --quick's frame size. */
#define QUICK_SIZE "320x180"
/* The CSV's rounding: the times and percentages are printed to 4
 * decimals, the MAE to 6. */
#define CSV_MS_ROUNDING 0.00005
#define CSV_PERCENT_ROUNDING 0.00005
#define CSV_MAE_ROUNDING 0.0000005
/* A scene's table in report.md: technique, parameters, skips, GPU ms, CPU
 * ms, ratio, floor ms, false shadow, false lit, misclassified, MAE,
 * penumbra MAE, lit MAE, shimmer, then a front column per own-technique
 * setting and error figure. */
#define REPORT_ERRORS 4
#define REPORT_PENUMBRA_ERROR 2
#define REPORT_FRONTS (2 * REPORT_ERRORS)
#define REPORT_COLUMNS (14 + REPORT_FRONTS)
#define REPORT_GPU_COLUMN 3
#define REPORT_CPU_COLUMN 4
#define REPORT_ERROR_COLUMN 9
#define REPORT_FRONT_COLUMN 14
#define REPORT_MAX_ROWS 128

/* The bench's default scenes. Under the sanitizers (a sweep stride, see
 * support.h) the quick run takes every Nth of them, named. */
static const char *const scenes[] = {"simple", "bunny", "teapot", "long_view"};
#define SCENE_COUNT (sizeof scenes / sizeof *scenes)
#define SCENE_STRIDE ((size_t)support_sweep_stride())
/* The plots, one per error figure the scene has: PREFIX_SCENE.png (a hard
 * light's truth has no penumbra). */
static const char *const plot_prefixes[] = {"pareto", "pareto_mae", "pareto_penumbra", "pareto_lit"};
#define HARD_PLOTS 3
static const char *const hard_plot_prefixes[HARD_PLOTS] = {"pareto", "pareto_mae", "pareto_lit"};
static char err[65536];

/* The whole --quick run; a static selection of one technique; the lights
 * moving with skips compared and the scaling plot; the camera walking
 * (dolly), where shimmer is measured. */
static int run_bench(void **state) {
    (void)state;
    static const char *const runs[][2] = {
        {OUT, "--quick"},
        {SELECT_OUT, SMALL_RUN " --technique planar"},
        {LIGHT_OUT, SMALL_RUN " --motion light --skips-compare --scaling --technique volumes"},
        {DOLLY_OUT, DOLLY_RUN},
        {DOLLY_FIRST_OUT, "--frames 1 " DOLLY_FLAGS},
        {DOLLY_LAST_OUT, DOLLY_RUN " --error-frames 1"},
        {SOFT_OUT, SOFT_RUN},
        {LAMP_OUT, LAMP_RUN},
        {LAMP2_OUT, LAMP_RUN " --light 2"},
        {INTERVAL_OUT, SMALL_SCENE " --technique planar --frames " INTERVAL_FRAMES_TEXT},
        {WITH_OUT, WITH_RUN},
    };
    char strided[512] = "";
    for (size_t i = 0; SCENE_STRIDE > 1 && i < SCENE_COUNT; i += SCENE_STRIDE) {
        size_t used = strlen(strided);
        snprintf(strided + used, sizeof strided - used, " assets/scenes/%s.json", scenes[i]);
    }
    for (size_t i = 0; i < sizeof runs / sizeof *runs; i++) {
        char command[1024];
        snprintf(command, sizeof command, "rm -rf %s && %s --out %s %s%s", runs[i][0], support_program("bench"),
                 runs[i][0], runs[i][1], i == 0 ? strided : "");
        if (support_run(command, err, sizeof err) != 0) {
            fprintf(stderr, "%s failed:\n%s", command, err);
            return -1;
        }
    }
    return 0;
}

static char *read_file(const char *path) {
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    static char text[1 << 20];
    size_t n = fread(text, 1, sizeof text - 1, f);
    text[n] = '\0';
    fclose(f);
    return text;
}

/* Splits one CSV line on commas outside quotes; returns the field count. */
static int csv_fields(char *line, char **fields, int max) {
    int n = 0;
    bool quoted = false;
    fields[n++] = line;
    for (char *p = line; *p; p++) {
        if (*p == '"')
            quoted = !quoted;
        else if (*p == ',' && !quoted && n < max)
            *p = '\0', fields[n++] = p + 1;
    }
    return n;
}

/* What the tests look at in a row of results.csv. */
typedef struct csv_row {
    char scene[64], technique[32], parameters[256], motion[16], skips[8], shimmer[16];
    double misclassified, mae;
    long compared;
    long class_pixels[3];
    double class_mae[3]; /* -1: "none" */
    bool interval;       /* the ratio has one */
} csv_row;

/* A row's ratio is the median of its frames' ratios to the floor frames
 * paired with them (the floor's own row too: against a twin), so it lies
 * between the ratios of the medians' extremes: at least the fastest own
 * frame's over the slowest floor frame's, which the medians bound (a
 * positive number, with the floor's median timed). Its interval: "-" for
 * both ends (too few frames, test_interval_needs_the_frames), or two
 * numbers about the ratio. Returns whether it has one. */
static bool check_ratio(char **fields) {
    double ratio = atof(fields[CSV_RATIO]), floor_ms = atof(fields[CSV_FLOOR_MS]);
    assert_true(floor_ms > CSV_MS_ROUNDING);
    assert_true(ratio > 0);
    bool none = strcmp(fields[CSV_RATIO_LOW], "-") == 0;
    assert_int_equal(none, strcmp(fields[CSV_RATIO_HIGH], "-") == 0);
    double low = atof(fields[CSV_RATIO_LOW]), high = atof(fields[CSV_RATIO_HIGH]);
    assert_true(none || (0 < low && low <= ratio && ratio <= high));
    return !none;
}

/* Reads results.csv under `dir` into rows (room for CSV_MAX_ROWS), checking
 * the header and that every row is well formed; returns the row count. */
static int read_csv(const char *dir, csv_row *rows) {
    char path[256];
    snprintf(path, sizeof path, "%s/results.csv", dir);
    char *text = read_file(path);
    char *rest = text, *line = strtok_r(rest, "\n", &rest);
    assert_string_equal(line, "scene,technique,parameters,gpu_ms_median,gpu_ms_p90,cpu_ms_median,cpu_ms_p90,"
                              "ratio_to_unshadowed,false_shadow_percent,false_lit_percent,misclassified_percent,"
                              "mae,compared_pixels,renderer,motion,skips,floor_ms_median,ratio_low,ratio_high,"
                              "shimmer_percent,"
                              "umbra_pixels,umbra_mae,penumbra_pixels,penumbra_mae,lit_pixels,lit_mae,frame_size,"
                              "traced_percent,rays_per_frame");
    int n = 0;
    while ((line = strtok_r(rest, "\n", &rest))) {
        char *fields[CSV_COLUMNS + 1];
        assert_int_equal(csv_fields(line, fields, CSV_COLUMNS + 1), CSV_COLUMNS);
        bool moving = strcmp(fields[CSV_MOTION], "camera") == 0 || strcmp(fields[CSV_MOTION], "dolly") == 0;
        if (!moving)
            assert_string_equal(fields[CSV_SHIMMER], "-");
        for (int c = CSV_GPU_MEDIAN; c < CSV_COLUMNS; c++) {
            /* shimmer: "-" where the camera stands still (checked below);
             * a class's MAE "none" where it has no pixel (checked below);
             * the ratio's interval "-" without one (check_ratio) */
            bool interval_none = (c == CSV_RATIO_LOW || c == CSV_RATIO_HIGH) && strcmp(fields[c], "-") == 0;
            bool no_rays = (c == CSV_TRACED || c == CSV_RAYS) && strcmp(fields[c], "-") == 0;
            if (c == CSV_RENDERER || c == CSV_MOTION || c == CSV_SKIPS || (c == CSV_SHIMMER && !moving) ||
                c == CSV_FRAME_SIZE || strcmp(fields[c], "none") == 0 || interval_none || no_rays)
                continue;
            char *end;
            double v = strtod(fields[c], &end);
            assert_true(end != fields[c] && *end == '\0' && isfinite(v) && v >= 0);
        }
        assert_string_equal(fields[CSV_FRAME_SIZE], QUICK_SIZE); /* every run here is --quick */
        /* The rays: the hybrid's counted where it casts them, none for the
         * others. */
        bool casts = strcmp(fields[1], "hybrid") == 0 && !strstr(fields[2], "--rays off");
        assert_int_equal(strcmp(fields[CSV_TRACED], "-") != 0, casts);
        assert_int_equal(strcmp(fields[CSV_RAYS], "-") != 0, casts);
        assert_true(atof(fields[CSV_GPU_MEDIAN]) > 0);  /* a frame takes time */
        assert_true(atol(fields[CSV_COMPARED]) > 1000); /* pixels were compared */
        bool interval = check_ratio(fields);
        assert_true(n < CSV_MAX_ROWS);
        csv_row *r = &rows[n++];
        r->interval = interval;
        snprintf(r->scene, sizeof r->scene, "%s", fields[0]);
        snprintf(r->technique, sizeof r->technique, "%s", fields[1]);
        snprintf(r->parameters, sizeof r->parameters, "%s", fields[2]);
        snprintf(r->motion, sizeof r->motion, "%s", fields[CSV_MOTION]);
        snprintf(r->skips, sizeof r->skips, "%s", fields[CSV_SKIPS]);
        snprintf(r->shimmer, sizeof r->shimmer, "%s", fields[CSV_SHIMMER]);
        r->misclassified = atof(fields[CSV_MISCLASSIFIED]);
        r->mae = atof(fields[CSV_MAE]);
        r->compared = atol(fields[CSV_COMPARED]);
        long classified = 0;
        for (int k = 0; k < 3; k++) {
            r->class_pixels[k] = atol(fields[CSV_CLASS_PIXELS(k)]);
            bool none = strcmp(fields[CSV_CLASS_MAE(k)], "none") == 0;
            assert_true(none == (r->class_pixels[k] == 0));
            r->class_mae[k] = none ? -1 : atof(fields[CSV_CLASS_MAE(k)]);
            assert_true(r->class_mae[k] <= 1);
            classified += r->class_pixels[k];
        }
        assert_int_equal(classified, r->compared); /* the classes split the compared pixels */
    }
    return n;
}

static int count_rows(const csv_row *rows, int n, const char *technique, const char *skips) {
    int count = 0;
    for (int i = 0; i < n; i++)
        count += strcmp(rows[i].technique, technique) == 0 && (!skips || strcmp(rows[i].skips, skips) == 0);
    return count;
}

/* The entries of DIR/reference/ (one scene, one run: one reference,
 * also where shimmer is measured: its held dump is of the same view),
 * the last read into name; returns how many. */
static int reference_names(const char *dir, char *name, size_t size) {
    char path[256];
    snprintf(path, sizeof path, "%s/reference", dir);
    DIR *d = opendir(path);
    assert_non_null(d);
    int entries = 0;
    for (struct dirent *e; (e = readdir(d));)
        if (e->d_name[0] != '.')
            snprintf(name, size, "%s", e->d_name), entries++;
    closedir(d);
    return entries;
}

static void reference_name(const char *dir, char *name, size_t size) {
    assert_int_equal(reference_names(dir, name, size), 1);
}

static void test_csv_has_every_configuration(void **state) {
    (void)state;
    static csv_row rows[CSV_MAX_ROWS];
    int n = read_csv(OUT, rows);
    for (int i = 0; i < n; i++) {
        assert_string_equal(rows[i].skips, "on"); /* skips are on by default */
        assert_string_equal(rows[i].motion, "static");
    }
    int scene_count = (int)((SCENE_COUNT + SCENE_STRIDE - 1) / SCENE_STRIDE);
    int planar_rows = count_rows(rows, n, "planar", NULL), floor_rows = count_rows(rows, n, "unshadowed", NULL);
    assert_int_equal(floor_rows, scene_count);
    assert_true(planar_rows >= scene_count * 2);
    assert_true(n >= floor_rows + planar_rows);
}

/* --technique planar --configs defaults: planar's defaults and the cost
 * floor's, nothing else. */
static void test_selection_keeps_the_floor(void **state) {
    (void)state;
    static csv_row rows[CSV_MAX_ROWS];
    int n = read_csv(SELECT_OUT, rows);
    assert_int_equal(n, 2);
    assert_int_equal(count_rows(rows, n, "planar", "on"), 1);
    assert_int_equal(count_rows(rows, n, "unshadowed", "on"), 1);
    for (int i = 0; i < n; i++) {
        assert_string_equal(rows[i].parameters, "\"\"");
        assert_string_equal(rows[i].motion, "static");
    }
}

/* --configs-with budget --configs-with 'filter hw': shadowmap's defaults,
 * its one budget row and its one hw row, and the floor. */
static void test_configs_with_takes_each_text(void **state) {
    (void)state;
    static csv_row rows[CSV_MAX_ROWS];
    int n = read_csv(WITH_OUT, rows);
    assert_int_equal(n, 4);
    static const char *const parameters[] = {"\"\"", "\"--filter hw\"", "\"--shadow-budget 8\""};
    for (size_t i = 0; i < sizeof parameters / sizeof *parameters; i++) {
        int found = 0;
        for (int r = 0; r < n; r++)
            found += strcmp(rows[r].technique, "shadowmap") == 0 && strcmp(rows[r].parameters, parameters[i]) == 0;
        assert_int_equal(found, 1);
    }
    assert_int_equal(count_rows(rows, n, "unshadowed", "on"), 1);
}

/* A ratio's interval needs the frames for one: the --quick run's rows
 * (its five timed frames) have none, and its report says the floor check
 * was not made; a run of INTERVAL_FRAMES has one in every row, the
 * floor's own row included, and its report's floor check names that row
 * as the noise. */
static void test_interval_needs_the_frames(void **state) {
    (void)state;
    static csv_row rows[CSV_MAX_ROWS];
    int n = read_csv(OUT, rows);
    for (int i = 0; i < n; i++)
        assert_false(rows[i].interval);
    char *report = read_file(OUT "/report.md");
    assert_non_null(strstr(
        report, "\n## The floor check\n\nNot made: 5 timed frames give no interval (at least " INTERVAL_FRAMES_TEXT
                " do).\n"));
    n = read_csv(INTERVAL_OUT, rows);
    assert_int_equal(n, 2);
    for (int i = 0; i < n; i++)
        assert_true(rows[i].interval);
    report = read_file(INTERVAL_OUT "/report.md");
    char *check = strstr(report, "\n## The floor check\n\n");
    assert_non_null(check);
    assert_non_null(strstr(check, "The noise: the unshadowed frame against itself: simple (skips on) "));
}

/* --motion light --skips-compare: each configuration skips on then off,
 * the rows say light, and the references (one per error frame: two) are
 * of the moved scene: cached apart from the static one. */
static void test_light_motion_and_skips_compare(void **state) {
    (void)state;
    static csv_row rows[CSV_MAX_ROWS];
    int n = read_csv(LIGHT_OUT, rows);
    assert_int_equal(n, 4);
    static const char *const techniques[] = {"volumes", "unshadowed"};
    for (int t = 0; t < 2; t++) {
        assert_int_equal(count_rows(rows, n, techniques[t], "on"), 1);
        assert_int_equal(count_rows(rows, n, techniques[t], "off"), 1);
    }
    for (int i = 0; i < n; i++)
        assert_string_equal(rows[i].motion, "light");
    char moving[256], still[256];
    assert_int_equal(reference_names(LIGHT_OUT, moving, sizeof moving), 2);
    reference_name(SELECT_OUT, still, sizeof still);
    assert_string_not_equal(moving, still);
    assert_non_null(strstr(moving, "light"));
    char *report = read_file(LIGHT_OUT "/report.md");
    assert_non_null(strstr(report, "| technique | ms skips on | ms skips off | speed-up |"));
    assert_non_null(strstr(report, "\n| volumes | "));
}

/* --motion dolly: every row has a shimmer figure, a percentage; a
 * reference is traced for each of the two error frames (the held dump is
 * of the same view); the report says what the column is. */
static void test_dolly_measures_shimmer(void **state) {
    (void)state;
    static csv_row rows[CSV_MAX_ROWS];
    int n = read_csv(DOLLY_OUT, rows);
    assert_int_equal(n, 2);
    for (int i = 0; i < n; i++) {
        assert_string_equal(rows[i].motion, "dolly");
        double shimmer = atof(rows[i].shimmer);
        assert_true(shimmer >= 0 && shimmer <= 100);
    }
    char name[256];
    assert_int_equal(reference_names(DOLLY_OUT, name, sizeof name), 2);
    assert_non_null(strstr(name, "dolly"));
    char *report = read_file(DOLLY_OUT "/report.md");
    assert_non_null(strstr(report, "| MAE | penumbra MAE | lit MAE | shimmer % |"));
    assert_non_null(strstr(report, "Shimmer %: of the compared pixels of those frames, those whose decision "
                                   "changes when the maps are held"));
    report = read_file(SELECT_OUT "/report.md");
    assert_non_null(strstr(report, "Shimmer %: \"-\": the camera does not move"));
}

/* The dolly run's figures pool its two error frames': the compared pixels
 * add up, and misclassified %, MAE and shimmer are the pooled ones (each
 * frame's weighed by its compared pixels; shimmer by its followed ones,
 * which the CSV does not give: between the two frames'). */
static void test_error_frames_pool(void **state) {
    (void)state;
    static csv_row both[CSV_MAX_ROWS], first[CSV_MAX_ROWS], last[CSV_MAX_ROWS];
    int n = read_csv(DOLLY_OUT, both);
    assert_int_equal(read_csv(DOLLY_FIRST_OUT, first), n);
    assert_int_equal(read_csv(DOLLY_LAST_OUT, last), n);
    for (int i = 0; i < n; i++) {
        const csv_row *a = &first[i], *b = &last[i], *pooled = &both[i];
        assert_string_equal(a->technique, pooled->technique);
        assert_string_equal(b->technique, pooled->technique);
        assert_int_equal(pooled->compared, a->compared + b->compared);
        double weight_a = (double)a->compared / (double)pooled->compared, weight_b = 1 - weight_a;
        assert_true(fabs(pooled->misclassified - (weight_a * a->misclassified + weight_b * b->misclassified)) <=
                    2 * CSV_PERCENT_ROUNDING);
        assert_true(fabs(pooled->mae - (weight_a * a->mae + weight_b * b->mae)) <= 2 * CSV_MAE_ROUNDING);
        double shimmer = atof(pooled->shimmer), shimmer_a = atof(a->shimmer), shimmer_b = atof(b->shimmer);
        assert_true(shimmer >= fmin(shimmer_a, shimmer_b) - CSV_PERCENT_ROUNDING &&
                    shimmer <= fmax(shimmer_a, shimmer_b) + CSV_PERCENT_ROUNDING);
    }
    /* The unshadowed row is wrong wherever the truth is shadowed: the
     * check above compared something. */
    assert_true(both[n - 1].misclassified > 0);
}

/* A plot gnuplot drew: a PNG of at least PLOT_MIN_WIDTH x PLOT_MIN_HEIGHT. */
#define PLOT_MIN_WIDTH 640
#define PLOT_MIN_HEIGHT 400
static void check_plot(const char *path) {
    int w, h;
    unsigned char *pixels = image_read_png(path, &w, &h);
    assert_non_null(pixels);
    assert_true(w >= PLOT_MIN_WIDTH && h >= PLOT_MIN_HEIGHT);
    free(pixels);
}

static void test_scaling_plot_is_an_image(void **state) {
    (void)state;
    check_plot(LIGHT_OUT "/scaling.png");
}

/* Usage errors: exit 2, one line naming what is wrong. */
static void test_usage_errors(void **state) {
    (void)state;
    static const struct {
        const char *flags, *named;
    } cases[] = {
        {"--technique planar --technique nosuch", "'nosuch'"}, /* an unknown technique */
        {"--frames 2 --error-frames 3", "--error-frames"},     /* more error frames than timed ones */
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char command[512];
        snprintf(command, sizeof command, "%s %s", support_program("bench"), cases[i].flags);
        assert_int_equal(support_run(command, err, sizeof err), 2);
        assert_int_equal(support_count_lines(err), 1);
        assert_non_null(strstr(err, cases[i].named));
    }
}

/* A configuration that fails (here shadowmap's camera program, whose
 * shader a copy of shaders/ breaks: a copy of its files, since a test's
 * shaders/ may be a link to the project's) is said on stderr and listed in the
 * report, and the sweep goes on: volumes after it and the floor are
 * measured; the run exits 1. */
static void test_failed_configuration_does_not_stop_the_sweep(void **state) {
    (void)state;
    char command[1024];
    snprintf(command, sizeof command,
             "rm -rf " BROKEN_SHADERS " " BROKEN_OUT " && cp -rL shaders " BROKEN_SHADERS
             " && echo 'not GLSL' >> " BROKEN_SHADERS "/map.frag && %s --out " BROKEN_OUT
             " --shader-dir " BROKEN_SHADERS " " SMALL_RUN " --technique shadowmap --technique volumes",
             support_program("bench"));
    assert_int_equal(support_run(command, err, sizeof err), 1);
    assert_non_null(strstr(err, "shadowmap defaults failed; the sweep goes on"));
    static csv_row rows[CSV_MAX_ROWS];
    int n = read_csv(BROKEN_OUT, rows);
    assert_int_equal(count_rows(rows, n, "shadowmap", NULL), 0);
    assert_int_equal(count_rows(rows, n, "volumes", "on"), 1);
    assert_int_equal(count_rows(rows, n, "unshadowed", "on"), 1);
    const char *report = read_file(BROKEN_OUT "/report.md");
    const char *failed = strstr(report, "## Failed configurations");
    assert_non_null(failed);
    assert_non_null(strstr(failed, "- simple, shadowmap defaults (skips on)"));
}

/* --light K: the reference is of light K (its cache says so) and so is
 * each technique's dump: planar agrees with it, and the floor's error,
 * the light's shadows, is that light's, not light 0's. A light the scene
 * does not have is one line naming the scene. */
static void test_light_picks_the_measured_light(void **state) {
    (void)state;
    static csv_row rows[2][CSV_MAX_ROWS];
    static const char *const outs[] = {LAMP_OUT, LAMP2_OUT};
    static const int lights[] = {0, 2};
    for (int i = 0; i < 2; i++) {
        char name[256], dir[512];
        assert_int_equal(read_csv(outs[i], rows[i]), 2);
        reference_name(outs[i], name, sizeof name);
        assert_true((strstr(name, "_light2") != NULL) == (lights[i] == 2));
        snprintf(dir, sizeof dir, "%s/reference/%s", outs[i], name);
        dump_frame reference;
        assert_true(dump_read(&reference, dir));
        assert_int_equal(reference.light_index, lights[i]);
        dump_frame_free(&reference);
        assert_string_equal(rows[i][0].technique, "planar");
        assert_true(rows[i][0].misclassified <= LAMP_MAX_MISCLASSIFIED);
    }
    assert_true(rows[0][1].misclassified != rows[1][1].misclassified); /* the floor's: two lights' shadows */
    char *report = read_file(LAMP2_OUT "/report.md");
    assert_non_null(strstr(report, "Error against the ray-traced reference of light 2 "));
    char command[512];
    snprintf(command, sizeof command, "%s --out %s-refused --light 1 %s", support_program("bench"), LAMP_OUT,
             "--quick --frames 1 --configs defaults --technique planar assets/scenes/simple.json");
    assert_int_equal(support_run(command, err, sizeof err), 1);
    assert_int_equal(support_count_lines(err), 1);
    assert_non_null(strstr(err, "assets/scenes/simple.json: --light 1: the scene has light 0 only"));
}

/* A row of a scene's table in report.md, as printed. */
typedef struct report_row {
    char technique[32];
    double ms, error[REPORT_ERRORS];
    bool has_error[REPORT_ERRORS]; /* a class figure: "none" where the truth has no pixel of it */
    bool front[REPORT_FRONTS];     /* misclassified, MAE, penumbra MAE, lit MAE; then the own fronts */
} report_row;

/* Splits a table line "| a | b |" into its trimmed cells; returns how many. */
static int report_cells(char *line, char **cells, int max) {
    int n = 0;
    for (char *p = strchr(line, '|'); p && p[1] && n < max; n++) {
        char *cell = p + 1, *end = strchr(cell, '|');
        if (!end)
            break;
        *end = '\0';
        while (*cell == ' ')
            cell++;
        for (char *t = end; t > cell && t[-1] == ' ';)
            *--t = '\0';
        cells[n] = cell;
        p = end;
    }
    return n;
}

/* The rows of the first table in a scene's section (a copy: it is changed
 * in place), times from ms_column; returns the row count. */
static int report_rows(char *section, int ms_column, report_row *rows) {
    char *table = strstr(section, "\n|---|");
    assert_non_null(table);
    int n = 0;
    for (char *line = strchr(table + 1, '\n') + 1; line[0] == '|';) {
        char *end = strchr(line, '\n');
        assert_non_null(end);
        *end = '\0';
        char *cells[REPORT_COLUMNS + 1];
        assert_int_equal(report_cells(line, cells, REPORT_COLUMNS + 1), REPORT_COLUMNS);
        assert_true(n < REPORT_MAX_ROWS);
        report_row *r = &rows[n++];
        snprintf(r->technique, sizeof r->technique, "%s", cells[0]);
        r->ms = atof(cells[ms_column]);
        for (int e = 0; e < REPORT_ERRORS; e++) {
            r->has_error[e] = strcmp(cells[REPORT_ERROR_COLUMN + e], "none") != 0;
            r->error[e] = atof(cells[REPORT_ERROR_COLUMN + e]);
        }
        for (int f = 0; f < REPORT_FRONTS; f++) {
            assert_true(cells[REPORT_FRONT_COLUMN + f][0] == 0 || strcmp(cells[REPORT_FRONT_COLUMN + f], "yes") == 0);
            r->front[f] = cells[REPORT_FRONT_COLUMN + f][0] != 0;
        }
        line = end + 1;
    }
    return n;
}

/* Each front column agrees with the table's figures, as far as their
 * rounding tells: rounding keeps order, so a row on the front has no row
 * both faster and more accurate even when rounded, and a row off it has
 * one no slower and no less accurate when rounded. A row without the
 * figure is on no front of it; every front of a figure some row has has a
 * row. */
static void check_fronts(const report_row *rows, int n) {
    for (int f = 0; f < REPORT_FRONTS; f++) {
        int e = f % REPORT_ERRORS, on_front = 0, with_figure = 0;
        bool own = f >= REPORT_ERRORS;
        for (int i = 0; i < n; i++) {
            bool beaten = false, matched = false;
            with_figure += rows[i].has_error[e];
            if (!rows[i].has_error[e]) {
                assert_false(rows[i].front[f]);
                continue;
            }
            for (int j = 0; j < n; j++) {
                if (j == i || !rows[j].has_error[e] || (own && strcmp(rows[j].technique, rows[i].technique) != 0))
                    continue;
                beaten = beaten || (rows[j].ms < rows[i].ms && rows[j].error[e] < rows[i].error[e]);
                matched = matched || (rows[j].ms <= rows[i].ms && rows[j].error[e] <= rows[i].error[e]);
            }
            if (rows[i].front[f])
                assert_false(beaten);
            else
                assert_true(matched);
            on_front += rows[i].front[f];
        }
        assert_true(on_front > 0 || with_figure == 0);
    }
}

/* Scene `scene`'s section of the report at `path`: its table's header,
 * a plot per figure of `prefixes` (n), the fronts agreeing with the table;
 * with `textbook`, the comparisons with shadowmap's textbook settings. */
static void check_report_section(const char *path, const char *scene, const char *const *prefixes, size_t n,
                                 bool textbook) {
    char *text = read_file(path);
    /* The time the report says the fronts use. */
    int ms_column = strstr(text, "use **CPU time**") ? REPORT_CPU_COLUMN : REPORT_GPU_COLUMN;
    char heading[64];
    snprintf(heading, sizeof heading, "\n## %s\n", scene);
    char *section = strstr(text, heading);
    assert_non_null(section);
    char *next = strstr(section + 1, "\n## ");
    if (next) /* look at this scene's section only */
        *next = '\0';
    assert_non_null(strstr(section, "| technique | parameters |"));
    assert_non_null(strstr(section, " | misclassified % | MAE | penumbra MAE | lit MAE | shimmer % | front "
                                    "(misclassified) | front (MAE) | front (penumbra MAE) | front (lit MAE) | own "
                                    "front (misclassified) | own front (MAE) | own front (penumbra MAE) | own front "
                                    "(lit MAE) |\n"));
    for (size_t p = 0; p < sizeof plot_prefixes / sizeof *plot_prefixes; p++) {
        bool expected = false;
        for (size_t k = 0; k < n; k++)
            expected = expected || strcmp(prefixes[k], plot_prefixes[p]) == 0;
        char image[128];
        snprintf(image, sizeof image, "(%s_%s.png)\n", plot_prefixes[p], scene);
        assert_int_equal(strstr(section, image) != NULL, expected);
    }
    if (textbook) {
        assert_non_null(strstr(section, "\nshadowmap defaults against textbook depth bias: misclassified "));
        assert_non_null(strstr(section, "\nshadowmap defaults against textbook polygon offset: misclassified "));
        assert_non_null(strstr(section, " %, MAE "));
    }
    static report_row rows[REPORT_MAX_ROWS];
    check_fronts(rows, report_rows(section, ms_column, rows));
}

static void test_report_has_a_table_front_and_comparison_per_scene(void **state) {
    (void)state;
    for (size_t i = 0; i < SCENE_COUNT; i += SCENE_STRIDE)
        check_report_section(OUT "/report.md", scenes[i], hard_plot_prefixes, HARD_PLOTS, true);
}

/* The plots of the figures PREFIXES (n) of `scene` under `dir`. */
static void check_plots(const char *dir, const char *scene, const char *const *prefixes, size_t n) {
    for (size_t p = 0; p < n; p++) {
        char path[256];
        snprintf(path, sizeof path, "%s/%s_%s.png", dir, prefixes[p], scene);
        check_plot(path);
    }
}

static void test_plots_are_images(void **state) {
    (void)state;
    for (size_t i = 0; i < SCENE_COUNT; i += SCENE_STRIDE)
        check_plots(OUT, scenes[i], hard_plot_prefixes, HARD_PLOTS);
}

/* Each scene's misclassified plot has a log axis where its figures span
 * decades (the floor's percents against a few thousandths), and a linear
 * one where they lie within a decade; the CSV's rounding is kept away
 * from the boundary by a factor of PLOT_AXIS_MARGIN either way. Some
 * scene of the run spans decades, so the check is not empty. */
#define PLOT_AXIS_MARGIN 2.0
static void test_plots_log_axis_where_figures_span_decades(void **state) {
    (void)state;
    static csv_row rows[CSV_MAX_ROWS];
    int n = read_csv(OUT, rows), spanning = 0;
    for (size_t s = 0; s < SCENE_COUNT; s += SCENE_STRIDE) {
        double low = INFINITY, high = 0;
        bool zero = false;
        for (int i = 0; i < n; i++)
            if (strcmp(rows[i].scene, scenes[s]) == 0) {
                if (rows[i].misclassified > 0)
                    low = fmin(low, rows[i].misclassified), high = fmax(high, rows[i].misclassified);
                else
                    zero = true;
            }
        char path[256];
        snprintf(path, sizeof path, "%s/pareto_%s.gp", OUT, scenes[s]);
        bool log = strstr(read_file(path), "set logscale y\n") != NULL;
        if (high / low > PLOT_LOG_SPAN * PLOT_AXIS_MARGIN) {
            spanning++;
            if (!log)
                fail_msg("%s: misclassified from %g %% to %g %%, but a linear axis", path, low, high);
        } else if (!zero && high / low < PLOT_LOG_SPAN / PLOT_AXIS_MARGIN && log) {
            fail_msg("%s: misclassified from %g %% to %g %%, but a log axis", path, low, high);
        }
    }
    assert_true(spanning > 0);
}

/* An area light's scene: every row has penumbra pixels (the truth's) and
 * their MAE; the penumbra's plot and fronts are there; shadowmap's soft
 * default draws the penumbra closer to the truth than itself drawn hard
 * and than a wide PCF's blur of the same width everywhere. */
static void test_soft_scene_measures_the_penumbra(void **state) {
    (void)state;
    static csv_row rows[CSV_MAX_ROWS];
    int n = read_csv(SOFT_OUT, rows);
    const csv_row *defaults = NULL, *hard = NULL, *wide = NULL;
    for (int i = 0; i < n; i++) {
        assert_true(rows[i].class_pixels[1] > 0 && rows[i].class_mae[1] >= 0);
        if (strcmp(rows[i].technique, "shadowmap") != 0)
            continue;
        if (strcmp(rows[i].parameters, "\"\"") == 0)
            defaults = &rows[i];
        else if (strstr(rows[i].parameters, "--soft off --filter pcf7"))
            wide = &rows[i];
        else if (strstr(rows[i].parameters, "--soft off"))
            hard = &rows[i];
    }
    assert_non_null(defaults);
    assert_non_null(hard);
    assert_non_null(wide);
    printf("    penumbra MAE: defaults %.4f, hard %.4f, wide pcf %.4f\n", defaults->class_mae[1], hard->class_mae[1],
           wide->class_mae[1]);
    assert_true(defaults->class_mae[1] < hard->class_mae[1]);
    assert_true(defaults->class_mae[1] < wide->class_mae[1]);
    check_report_section(SOFT_OUT "/report.md", SOFT_SCENE, plot_prefixes,
                         sizeof plot_prefixes / sizeof *plot_prefixes, false);
    check_plots(SOFT_OUT, SOFT_SCENE, plot_prefixes, sizeof plot_prefixes / sizeof *plot_prefixes);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_csv_has_every_configuration),
        cmocka_unit_test(test_report_has_a_table_front_and_comparison_per_scene),
        cmocka_unit_test(test_plots_are_images),
        cmocka_unit_test(test_plots_log_axis_where_figures_span_decades),
        cmocka_unit_test(test_soft_scene_measures_the_penumbra),
        cmocka_unit_test(test_selection_keeps_the_floor),
        cmocka_unit_test(test_configs_with_takes_each_text),
        cmocka_unit_test(test_interval_needs_the_frames),
        cmocka_unit_test(test_light_motion_and_skips_compare),
        cmocka_unit_test(test_dolly_measures_shimmer),
        cmocka_unit_test(test_error_frames_pool),
        cmocka_unit_test(test_scaling_plot_is_an_image),
        cmocka_unit_test(test_usage_errors),
        cmocka_unit_test(test_light_picks_the_measured_light),
        cmocka_unit_test(test_failed_configuration_does_not_stop_the_sweep),
    };
    return cmocka_run_group_tests_name("benchmark smoke test", tests, run_bench, NULL);
}
