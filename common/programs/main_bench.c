/* bench: run time against error for every technique over its parameter
 * sweep, on each scene, in one process on one GL context.
 *
 * For each scene: the ray-traced reference (computed once and cached under
 * OUT/reference/, recomputed when the scene file is newer), then for every
 * selected technique (--technique; the cost floor always, since every
 * ratio is to it) and each of its bench_configs (--configs defaults: only
 * its first, ""): warm-up frames, then timed frames (GPU time from
 * GL_TIME_ELAPSED queries, CPU time from the clock around the frame and
 * glFinish), then the technique's own dumps of --error-frames of the timed
 * frames compared with their references (shadowdiff rules), pooled: of
 * light 0, or of --light K's (the scene must have it). Each
 * frame's time is also a cost-floor frame's, timed in the same moments
 * (bench_time_frames); a row whose ratio to the floor lies below 1 beyond
 * its interval fails the run, after everything is written (the floor
 * check, bench_write_floor_check). A configuration that fails (a GL
 * error, a program that does not compile, a scene it refuses) is said on
 * stderr as it fails and the sweep goes on with the next; report.md lists
 * the failed ones and the run exits 1 after writing everything. Writes
 *   OUT/results.csv         one row per scene, configuration and skips setting
 *                           (floor_ms_median: the row's floor; ratio_low and
 *                           ratio_high: its ratio's interval; the last,
 *                           frame_size: WxH)
 *   OUT/report.md           a table per scene, its Pareto fronts (one per
 *                           error figure), and each technique's defaults
 *                           against its named (textbook) configurations
 *   OUT/pareto_SCENE.png    ms per frame against misclassified %, by gnuplot
 *   OUT/pareto_mae_SCENE.png  ms per frame against the mean absolute error
 *   OUT/scaling.png         (--scaling) each technique's defaults, ms per
 *                           frame against the scene's object count
 * Timings are medians and 90th percentiles of the timed frames: single
 * frames on a shared machine are noise.
 *
 * Motion (--motion) is described at bench_error_time, shimmer at
 * bench_shimmers.
 *
 * Skips (render.h) are on, as in the app; --no-skip turns them off, and
 * --skips-compare runs every configuration twice, skips on then off, each
 * row's floor frames under its own skips setting; results.csv's `skips`
 * column says which a row ran under.
 */
#include <glad/gl.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "capture.h"
#include "context.h"
#include "depth.h"
#include "flags.h"
#include "hud.h"
#include "median_interval.h"
#include "motion.h"
#include "path.h"
#include "plot.h"
#include "raytrace.h"
#include "registry.h"
#include "results_csv.h"
#include "shader.h"
#include "shadowdiff.h"
#include "technique_host.h"

#define BENCH_MAX_ROWS 512
#define BENCH_MAX_CONFIGS_WITH 8
#define BENCH_MAX_FRAMES 1000
#define BENCH_MAX_SCENES 16
#define BENCH_MAX_TECHNIQUES 16
/* --error-frames: its default under a motion, and its most. */
#define BENCH_DEFAULT_ERROR_FRAMES 6
#define BENCH_MAX_ERROR_FRAMES 16
/* Frame k is at k / BENCH_FRAME_RATE seconds, as the app's headless frames
 * are (app.c), so a bench frame is the frame `--frames` renders there. */
#define BENCH_FRAME_RATE MOTION_FRAME_RATE
/* The MAE's decimals: results.csv's, the report's. */
#define BENCH_MAE_DECIMALS 6
#define BENCH_REPORT_MAE_DECIMALS 5

/* --configs: the default first (a FLAGS_CHOICE list). */
typedef enum bench_configs { BENCH_CONFIGS_ALL, BENCH_CONFIGS_DEFAULTS } bench_configs;
static const char *const bench_config_choices[] = {"all", "defaults", NULL};

/* The error figures, each a cost as time is, with a front and a plot of
 * its own: misclassified % counts the pixels on the wrong side of the
 * visibility threshold; the mean absolute error also counts how far off
 * each is, so that a blurred shadow pays for its blur; the penumbra's and
 * the lit class's MAE (shadowdiff's classes, by the truth's visibility)
 * are how well a soft shadow is drawn and what a filter darkens that is
 * fully lit (acne, light bleeding). A class figure exists where the truth
 * has pixels of the class: a row without one is on no front of it, and a
 * scene without any has no plot of it. */
typedef enum bench_error {
    BENCH_ERROR_MISCLASSIFIED,
    BENCH_ERROR_MAE,
    BENCH_ERROR_PENUMBRA,
    BENCH_ERROR_LIT,
    BENCH_ERROR_COUNT
} bench_error;
/* A figure's class, or this for a figure of the whole picture. */
#define BENCH_WHOLE_PICTURE SHADOWDIFF_CLASS_COUNT
static const struct {
    const char *name;  /* the report's columns, "front (NAME)" */
    const char *plot;  /* OUT/PLOT_SCENE.png */
    const char *label; /* the plot's y axis */
    int class_index;   /* shadowdiff_class, or BENCH_WHOLE_PICTURE */
} bench_errors[BENCH_ERROR_COUNT] = {
    [BENCH_ERROR_MISCLASSIFIED] = {"misclassified", "pareto", "misclassified % of compared pixels",
                                   BENCH_WHOLE_PICTURE},
    [BENCH_ERROR_MAE] = {"MAE", "pareto_mae", "mean absolute visibility error", BENCH_WHOLE_PICTURE},
    [BENCH_ERROR_PENUMBRA] = {"penumbra MAE", "pareto_penumbra", "mean absolute error where the truth is in penumbra",
                              SHADOWDIFF_CLASS_PENUMBRA},
    [BENCH_ERROR_LIT] = {"lit MAE", "pareto_lit", "mean absolute error where the truth is fully lit",
                         SHADOWDIFF_CLASS_LIT},
};

typedef struct bench_row {
    const char *scene, *technique, *config;
    bool no_skip; /* ran under --no-skip */
    double gpu_median, gpu_p90, cpu_median, cpu_p90;
    double frame_ms; /* what the ratio, the front and the plot use */
    double floor_ms; /* the median of the floor frames interleaved with the row's */
    /* The median of the frames' ratios to the floor frames paired with
     * them, and the interval that holds it with RESULTS_CSV_RATIO_CONFIDENCE
     * (none with too few frames). */
    median_interval ratio;
    shadowdiff_result error;  /* pooled over the error frames (shadowdiff_result_add) */
    bool shimmer_measured;    /* under a motion that moves the camera */
    long followed, shimmered; /* summed over the error frames: shimmer % is their ratio */
    technique_rays rays;      /* summed over the error frames that counted them */
    int rays_frames;          /* those frames */
} bench_row;

static void bench_row_add_rays(bench_row *row, const technique_rays *rays) {
    row->rays.pixels += rays->pixels;
    row->rays.traced += rays->traced;
    row->rays.rays += rays->rays;
    row->rays_frames++;
}

/* A configuration that failed. */
typedef struct bench_failure {
    const char *scene, *technique, *config;
    bool no_skip;
} bench_failure;

static struct {
    /* flags (zero: the default, which --quick makes small) */
    const char *out_dir;
    int width, height, frames, warmup, light_samples, error_frames;
    int motion;                                       /* motion_kind */
    int configs;                                      /* bench_configs */
    const char *configs_with[BENCH_MAX_CONFIGS_WITH]; /* --configs-with: the sweep's configurations holding one */
    int configs_with_count;
    int light; /* --light: the light measured */
    bool quick, verbose, no_skip, skips_compare, scaling;
    const char *scenes[BENCH_MAX_SCENES];
    char scene_names[BENCH_MAX_SCENES][128];
    int scene_objects[BENCH_MAX_SCENES]; /* the scaling plot's x */
    int scene_count;
    const char *techniques[BENCH_MAX_TECHNIQUES]; /* --technique: none means all */
    int technique_count;
    char default_scenes[4][PATH_MAX]; /* the standard scenes */
    const char *shader_dir;
    char default_shader_dir[PATH_MAX];
    /* the skips settings each configuration runs under: no_skip false
     * (skips on) then true with --skips-compare, else --no-skip's */
    bool no_skip_settings[2];
    int setting_count;
    /* run */
    context ctx;
    target target;
    scene scene;
    scene_light base_lights[SCENE_MAX_LIGHTS]; /* the scene's own, before motion */
    scene_camera base_camera;
    render_scene gpu;
    camera_view view;
    bool hold_fit;        /* the maps fitted to fit_view (shimmer's held dump) */
    camera_view fit_view; /* the camera of the frame before the one rendered */
    double time;          /* of the frame being rendered, seconds */
    const technique *current;
    technique_host host;
    const technique *floor;    /* the registry's cost floor */
    technique_host floor_host; /* its frames between the current technique's */
    render_skips skips;
    unsigned query;
    bool software; /* a CPU rasterizer: timer queries miss its work */
    bench_row rows[BENCH_MAX_ROWS];
    int row_count;
    bench_failure failed[BENCH_MAX_ROWS]; /* in the order they ran */
    int failed_count;
} bench;

static const flags_param bench_flags[] = {
    {NULL, NULL, 0, FLAGS_LIST, .items = bench.scenes, .count = &bench.scene_count, .max = BENCH_MAX_SCENES,
     .what = "at most " FLAGS_TEXT(BENCH_MAX_SCENES) " scene files"},
    {"out", "where results go (out/bench)", 0, FLAGS_STRING, .text = &bench.out_dir, .value_name = "DIR"},
    {"size", "frame size (1280x720; --quick: 320x180)", 0, FLAGS_SIZE, .width = &bench.width,
     .height = &bench.height},
    {"frames", "timed frames per configuration, after warm-up (30; --quick: 5)", 0, FLAGS_INT,
     .integer = &bench.frames, .min = 1, .max = BENCH_MAX_FRAMES, .what = "a count"},
    {"warmup", "untimed frames first (5; --quick: 2)", 0, FLAGS_INT, .integer = &bench.warmup, .min = 0,
     .max = BENCH_MAX_FRAMES, .what = "a count"},
    {"error-frames",
     "frames whose error the figures pool, spread evenly over the\ntimed ones, the last among them (static: 1; "
     "else " FLAGS_TEXT(BENCH_DEFAULT_ERROR_FRAMES) ",\nat most --frames)",
     0, FLAGS_INT, .integer = &bench.error_frames, .min = 1, .max = BENCH_MAX_ERROR_FRAMES, .what = "a count"},
    {"light-samples", "reference shadow rays per area light (256; --quick: 16)", 0, FLAGS_INT,
     .integer = &bench.light_samples, .min = 1, .max = RAYTRACE_MAX_LIGHT_SAMPLES, .what = "a count"},
    {"motion",
     "what moves: nothing, the lights (as --animate turns them),\nthe camera about its target, along its view (dolly), or\nthe measured light alone (lamp, --light K) or every light\n(lamps) on a small circle; frame k is at k/60 s",
     0, FLAGS_CHOICE, .index = &bench.motion, .choices = motion_names},
    {"configs-with",
     "of each sweep, only the defaults and the configurations\nwhose text holds TEXT (--configs-with budget); repeat "
     "it\nfor more",
     0, FLAGS_LIST, .repeat = true, .items = bench.configs_with, .count = &bench.configs_with_count, .min = 1,
     .max = BENCH_MAX_CONFIGS_WITH, .what = "texts", .value_name = "TEXT"},
    {"configs", "each technique's whole sweep, or its defaults only", 0, FLAGS_CHOICE, .index = &bench.configs,
     .choices = bench_config_choices},
    {"quick", "small and short: a smoke test of the whole pipeline", 0, FLAGS_SWITCH, .on = &bench.quick},
    {"skip",
     "no skips at all (view culling...): every pass draws the\nwhole scene; results.csv's skips column says off", 0,
     FLAGS_TOGGLE, .disabled = &bench.no_skip},
    {"skips-compare", "every configuration twice, skips on then --no-skip;\nthe report compares them", 0,
     FLAGS_SWITCH, .on = &bench.skips_compare},
    {"scaling", "also OUT/scaling.png: ms per frame against the scenes'\nobject counts", 0, FLAGS_SWITCH,
     .on = &bench.scaling},
    {"shader-dir", "where the GLSL files are", 0, FLAGS_STRING, .text = &bench.shader_dir, .value_name = "DIR"},
    {"light",
     "the light measured, from 0 (0): the reference's visibility of it\nand each technique's (its --dump --light "
     "K)",
     0, FLAGS_INT, .integer = &bench.light, .min = 0, .max = SCENE_MAX_LIGHTS - 1, .what = "a light index",
     .value_name = "K"},
    {"verbose", "print the backend and GL renderer, and each model's\ntriangles and bounds", 0, FLAGS_SWITCH,
     .on = &bench.verbose},
    {"technique", "only this one (and the cost floor); repeat it for more", 0, FLAGS_LIST, .repeat = true,
     .items = bench.techniques, .count = &bench.technique_count, .min = 1, .max = BENCH_MAX_TECHNIQUES,
     .what = "technique names", .value_name = "NAME"},
    {.name = "help", .help = "this text", .kind = FLAGS_HELP},
};

static const technique *bench_find_technique(const char *name) {
    for (int t = 0; t < registry_technique_count; t++)
        if (strcmp(registry_techniques[t]->name, name) == 0)
            return registry_techniques[t];
    return NULL;
}

/* Whether the run times t: every technique without --technique; the cost
 * floor always. */
static bool bench_selected(const technique *t) {
    bool named = bench.technique_count == 0 || t->cost_floor;
    for (int i = 0; i < bench.technique_count && !named; i++)
        named = strcmp(bench.techniques[i], t->name) == 0;
    return named;
}

static int bench_config_count(const technique *t) {
    return bench.configs == BENCH_CONFIGS_DEFAULTS ? 1 : t->bench_config_count;
}

/* Technique t's configuration c is timed: the defaults (the first)
 * always, the others unless --configs-with leaves them out (none of its
 * texts in theirs). */
static bool bench_config_taken(const technique *t, int c) {
    bool taken = c == 0 || bench.configs_with_count == 0;
    for (int i = 0; i < bench.configs_with_count && !taken; i++)
        taken = strstr(t->bench_configs[c], bench.configs_with[i]) != NULL;
    return taken;
}

/* The configurations of t timed on each scene and setting. */
static int bench_configs_taken(const technique *t) {
    int n = 0;
    for (int c = 0; c < bench_config_count(t); c++)
        n += bench_config_taken(t, c);
    return n;
}

static int bench_parse_flags(int argc, char **argv) {
    int count = (int)(sizeof bench_flags / sizeof *bench_flags);
    int status = flags_parse("bench", bench_flags, count, argc - 1, argv + 1);
    if (status == FLAGS_HELP_ASKED) {
        printf("usage: bench [flags] [SCENE.json...]\n"
               "Times every technique over its parameter sweep and measures its error against the\n"
               "ray-traced reference, on each scene (default: the standard scenes and long_view).\n"
               "Exits 1, after writing everything, where a configuration costs less than the\n"
               "unshadowed floor beyond the noise (its ratio's whole interval under 1).\n"
               "Techniques:");
        for (int t = 0; t < registry_technique_count; t++)
            printf(" %s%s", registry_techniques[t]->name, registry_techniques[t]->cost_floor ? " (cost floor)" : "");
        printf(".\n");
        flags_print_help(stdout, bench_flags, count, 2, 0);
    }
    if (status)
        return status;
    for (int i = 0; i < bench.technique_count; i++)
        if (!bench_find_technique(bench.techniques[i]))
            return flags_usage_error("bench", "--technique: unknown technique", bench.techniques[i]);
    if (bench.skips_compare && bench.no_skip)
        return flags_usage_error("bench", "--skips-compare runs with and without skips: drop", "--no-skip");
    if (!bench.out_dir)
        bench.out_dir = "out/bench";
    /* Zero means the default, which --quick makes small. */
    if (!bench.width) {
        bench.width = bench.quick ? 320 : 1280;
        bench.height = bench.quick ? 180 : 720;
    }
    if (!bench.frames)
        bench.frames = bench.quick ? 5 : 30;
    if (!bench.warmup)
        bench.warmup = bench.quick ? 2 : 5;
    if (!bench.light_samples)
        bench.light_samples = bench.quick ? 16 : 256;
    if (bench.error_frames > bench.frames)
        return flags_usage_error("bench", "--error-frames: more than the timed frames (--frames)", NULL);
    if (!bench.error_frames) {
        int moving = bench.motion == MOTION_STATIC ? 1 : BENCH_DEFAULT_ERROR_FRAMES;
        bench.error_frames = moving < bench.frames ? moving : bench.frames;
    }
    bench.no_skip_settings[bench.setting_count++] = bench.no_skip;
    if (bench.skips_compare)
        bench.no_skip_settings[bench.setting_count++] = true;
    return 0;
}

static double bench_now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

/* The scene's lights and camera as the motion has them at `time`, from
 * the scene's own, and the view; the frames that follow are at `time`. */
static void bench_move(double time) {
    scene *s = &bench.scene;
    bench.time = time;
    motion_lights((motion_kind)bench.motion, time, bench.base_camera.target, bench.base_lights, s->light_count,
                  bench.light, s->lights);
    motion_camera((motion_kind)bench.motion, time, &bench.base_camera, &s->camera);
    camera_view_compute(&s->camera, (float)bench.width / (float)bench.height, &bench.view);
}

/* The time of error frame k (0..error_frames - 1, in order of time; the
 * last is the last timed frame): timed frames spread evenly.
 *
 * Motion (--motion, motion.h, the app's paths): frame k of a configuration,
 * warm-up frames first, is rendered at time k / BENCH_FRAME_RATE with the
 * lights or the camera moved from the scene's own, so that caches are
 * measured as the app exercises them; every configuration starts again at
 * frame 0. One frame's error is noise under a motion (shadow edges cross
 * texels from frame to frame: test_cascades' walked long_view), so the
 * error figures pool the compared pixels of --error-frames frames spread
 * evenly over the timed ones, the last timed frame the last of them (under
 * a motion BENCH_DEFAULT_ERROR_FRAMES by default, static 1: its frames are
 * one picture); each is dumped after the timing, in order of time (frames
 * are deterministic in their time, and a skip or cache never changes a
 * decision), and each has its reference, ray traced for its time and
 * cached under a name that says the motion and that time. */
static double bench_error_time(int k) {
    int timed = bench.frames - 1 - (bench.error_frames - 1 - k) * bench.frames / bench.error_frames;
    return (bench.warmup + timed) / BENCH_FRAME_RATE;
}

static bool bench_host_frame(technique_host *h, int visibility_of) {
    return technique_host_frame(h, &bench.view, bench.hold_fit ? &bench.fit_view : NULL, &bench.target, bench.time,
                                visibility_of);
}

/* The current technique's frame (capture_dump's callback). */
static bool bench_render_frame(int visibility_of) { return bench_host_frame(&bench.host, visibility_of); }

static int bench_compare_doubles(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Nearest-rank percentile of sorted samples. */
static double bench_percentile(const double *sorted, int n, double p) {
    int rank = (int)(p * n + 0.999999);
    return sorted[rank < 1 ? 0 : rank > n ? n - 1 : rank - 1];
}

/* The timed frames of one host, in ms. */
typedef struct bench_series {
    double gpu[BENCH_MAX_FRAMES], cpu[BENCH_MAX_FRAMES];
} bench_series;

/* One frame of host h, timed into sample i of s: CPU time from the clock
 * around the frame and glFinish, GPU time from a timer query. */
static bool bench_timed_frame(technique_host *h, bench_series *s, int i) {
    double start = bench_now_ms();
    glBeginQuery(GL_TIME_ELAPSED, bench.query);
    bool ok = bench_host_frame(h, -1);
    glEndQuery(GL_TIME_ELAPSED);
    glFinish();
    s->cpu[i] = bench_now_ms() - start;
    GLuint64 ns = 0;
    glGetQueryObjectui64v(bench.query, GL_QUERY_RESULT, &ns);
    s->gpu[i] = ns / 1e6;
    return ok;
}

/* The series' samples in the time the ratio uses (bench_time_basis). */
static const double *bench_basis(const bench_series *s) { return bench.software ? s->cpu : s->gpu; }

/* Sorts the series' samples; returns its median in the time the ratio
 * uses. */
static double bench_sort_series(bench_series *s) {
    qsort(s->gpu, (size_t)bench.frames, sizeof *s->gpu, bench_compare_doubles);
    qsort(s->cpu, (size_t)bench.frames, sizeof *s->cpu, bench_compare_doubles);
    return bench_percentile(bench_basis(s), bench.frames, 0.5);
}

/* A row's ratio for the report: with its interval where it has one. */
static const char *bench_ratio_text(const bench_row *r) {
    static char text[64];
    if (r->ratio.bounded)
        snprintf(text, sizeof text, "%.2f [%.2f, %.2f]", r->ratio.median, r->ratio.low, r->ratio.high);
    else
        snprintf(text, sizeof text, "%.2f", r->ratio.median);
    return text;
}

/* A row below the floor: its whole interval under 1. */
static bool bench_below_floor(const bench_row *r) { return r->ratio.bounded && r->ratio.high < 1; }

/* One frame of the row and one of the floor, in an order that alternates
 * with i: whichever goes second meets what the first left (caches, the
 * rasterizer's threads), so each goes second half the time. */
static bool bench_frame_pair(int i, bench_series *own, bench_series *floor_series) {
    bool floor_first = i % 2 == 0;
    if (floor_first && !bench_timed_frame(&bench.floor_host, floor_series, i))
        return false;
    if (!bench_timed_frame(&bench.host, own, i))
        return false;
    return floor_first || bench_timed_frame(&bench.floor_host, floor_series, i);
}

/* Warms up and times the current technique (bench.host) against the
 * floor's frames (bench.floor_host).
 *
 * The ratio to the cost floor is measured in the same moments as the
 * configuration: the machine is shared, and a floor timed once per scene,
 * minutes away, would be timed under another load. So every frame k of a
 * configuration, warm-up included, is a pair of a floor frame and the
 * configuration's frame, both at time k and under the row's skips, each
 * timed on its own (two technique hosts at once: the floor's and the
 * configuration's), the one first in turn (bench_frame_pair). The row's
 * ratio is the median of its pairs' ratios, with its interval
 * (median_interval.h); results.csv's floor_ms_median is the floor
 * frames' own median. The floor's own row is timed against a second host
 * of the floor in the same way (it keeps no state of its own, so the two
 * share nothing): its ratio and interval are the noise of the rule. The
 * configuration's frames and its dump are those it renders alone: the
 * floor frames between them share no state with it that a frame does not
 * set afresh. */
static bool bench_time_frames(bench_row *row) {
    static bench_series own, floor_series;
    static double ratios[BENCH_MAX_FRAMES];
    int frame = 0;
    for (; frame < bench.warmup; frame++) {
        bench_move(frame / BENCH_FRAME_RATE);
        if (!bench_host_frame(&bench.floor_host, -1) || !bench_render_frame(-1))
            return false;
    }
    glFinish();
    for (int i = 0; i < bench.frames; i++, frame++) {
        bench_move(frame / BENCH_FRAME_RATE);
        if (!bench_frame_pair(i, &own, &floor_series))
            return false;
        double floor_ms = bench_basis(&floor_series)[i];
        ratios[i] = floor_ms > 0 ? bench_basis(&own)[i] / floor_ms : 0;
    }
    row->ratio = median_interval_of(ratios, bench.frames, RESULTS_CSV_RATIO_CONFIDENCE);
    row->frame_ms = bench_sort_series(&own);
    row->gpu_median = bench_percentile(own.gpu, bench.frames, 0.5);
    row->gpu_p90 = bench_percentile(own.gpu, bench.frames, 0.9);
    row->cpu_median = bench_percentile(own.cpu, bench.frames, 0.5);
    row->cpu_p90 = bench_percentile(own.cpu, bench.frames, 0.9);
    row->floor_ms = bench_sort_series(&floor_series);
    return true;
}

static bool bench_newer(const char *path, const char *than) {
    struct stat a, b;
    return stat(path, &a) == 0 && stat(than, &b) == 0 && a.st_mtime >= b.st_mtime;
}

/* Whether the run measures shimmer.
 *
 * Shimmer: under the motions that move the camera (camera, dolly), each
 * configuration also dumps each error frame with the maps held as the
 * frame before fitted them (technique_host_frame's fit_view: the app's
 * --hold-fit), and results.csv's shimmer_percent is the share of compared
 * pixels whose decision the fit's motion alone changed, pooled likewise
 * (shadowdiff's shimmer of the two dumps of one view against its one
 * reference: every pixel follows itself and the truth is the same, so the
 * figure is free of the sub-pixel resampling that two views' pixels add;
 * report.md's "shimmer %"). Under static and
 * light it is "-": with the camera still nothing is refitted for the
 * viewer, and a moving light moves the true shadows. */
static bool bench_shimmers(void) { return motion_moves_camera((motion_kind)bench.motion); }

/* The reference of the measured light (--light) for the frame at `time`,
 * from the cache when it is newer than the scene. A light other than 0
 * adds its number to the cache's name, and a moving run the motion and
 * the time: the reference is of that moved scene. */
static bool bench_reference(const char *scene_path, const char *name, double time, dump_frame *reference) {
    char dir[PATH_MAX], meta[PATH_MAX + 16];
    int n = snprintf(dir, sizeof dir, "%s/reference/%s_%dx%d_%d", bench.out_dir, name, bench.width, bench.height,
                     bench.light_samples);
    if (bench.light && n > 0 && (size_t)n < sizeof dir)
        n += snprintf(dir + n, sizeof dir - (size_t)n, "_light%d", bench.light);
    if (bench.motion != MOTION_STATIC && n > 0 && (size_t)n < sizeof dir)
        snprintf(dir + n, sizeof dir - (size_t)n, "_%s_%.3fs", motion_names[bench.motion], time);
    snprintf(meta, sizeof meta, "%s/meta.json", dir);
    bench_move(time);
    if (bench_newer(meta, scene_path) && dump_read(reference, dir)) {
        fprintf(stderr, "  reference: cached in %s\n", dir);
        return true;
    }
    fprintf(stderr, "  reference: ray tracing %dx%d ...\n", bench.width, bench.height);
    const raytrace_settings settings = {.light_samples = bench.light_samples};
    return raytrace_render(&bench.scene, bench.width, bench.height, bench.light, &settings, reference) &&
           dump_write(reference, dir);
}

/* The current technique's dumps of the frame at `time`, and, where
 * shimmer is measured, first of that frame with the maps held as the frame
 * before fitted them; held is otherwise left empty. */
static bool bench_dumps(double time, dump_frame *held, dump_frame *last) {
    *held = (dump_frame){0};
    bench_move(time);
    if (bench_shimmers()) {
        scene_camera camera;
        motion_camera((motion_kind)bench.motion, time - 1 / BENCH_FRAME_RATE, &bench.base_camera, &camera);
        camera_view_compute(&camera, (float)bench.width / (float)bench.height, &bench.fit_view);
        bench.hold_fit = true;
        bool held_ok = capture_dump(&bench.gpu, &bench.view, &bench.target, bench.light,
                                    bench.current->coloured_shadows, bench_render_frame, held);
        bench.hold_fit = false;
        if (!held_ok)
            return false;
    }
    if (capture_dump(&bench.gpu, &bench.view, &bench.target, bench.light, bench.current->coloured_shadows,
                     bench_render_frame, last))
        return true;
    dump_frame_free(held);
    return false;
}

/* Adds one error frame's figures to the row's: the dump against its
 * reference, and where shimmer is measured the held dump's against it. A
 * shimmer that gives no figure (its line says why) leaves the row's "-". */
static bool bench_measure(bench_row *row, const dump_frame *reference, const dump_frame *held, const dump_frame *dump,
                          bool first) {
    shadowdiff_result error;
    if (!shadowdiff_compare(reference, dump, NULL, &error, NULL))
        return false;
    shadowdiff_result_add(&row->error, &error);
    shadowdiff_shimmer_result shimmer;
    bool measured = bench_shimmers() && shadowdiff_shimmer(reference, held, reference, dump, NULL, &shimmer);
    row->shimmer_measured = measured && (first || row->shimmer_measured);
    row->followed += measured ? shimmer.followed : 0;
    row->shimmered += measured ? shimmer.shimmered : 0;
    return true;
}

/* The current technique's error frames: each one's dumps measured against
 * its reference (references[k]: error frame k's). */
static bool bench_error_frames(bench_row *row, const dump_frame *references) {
    bool ok = true;
    bench.host.counters = true; /* untimed: the rays counted (technique.rays) */
    for (int k = 0; ok && k < bench.error_frames; k++) {
        dump_frame held, dump;
        ok = bench_dumps(bench_error_time(k), &held, &dump);
        if (!ok)
            break;
        ok = bench_measure(row, &references[k], &held, &dump, k == 0);
        dump_frame_free(&held);
        dump_frame_free(&dump);
        technique_rays rays;
        if (ok && bench.current->rays && bench.current->rays(&rays))
            bench_row_add_rays(row, &rays);
    }
    bench.host.counters = false;
    return ok;
}

/* Times and measures one configuration of the current technique under the
 * skips setting no_skip, interleaved with the floor's frames. */

static bool bench_configuration(const char *scene_name, const char *config, bool no_skip,
                                const dump_frame *references) {
    if (bench.row_count == BENCH_MAX_ROWS) {
        fprintf(stderr, "bench: more than %d configurations\n", BENCH_MAX_ROWS);
        return false;
    }
    bench_row *row = &bench.rows[bench.row_count];
    *row = (bench_row){.scene = scene_name, .technique = bench.current->name, .config = config, .no_skip = no_skip};
    bench.skips = (render_skips){.no_skip = no_skip};
    /* A host whose start was tried is stopped: destroy follows even a
     * failed init. The floor runs at its defaults. */
    bool configured = technique_apply_config(bench.current, config) && technique_apply_config(bench.floor, "");
    bool ok = configured && technique_host_start(&bench.host, bench.current, &bench.gpu, &bench.skips);
    bool floor_tried = ok;
    ok = ok && technique_host_start(&bench.floor_host, bench.floor, &bench.gpu, &bench.skips) &&
         bench_time_frames(row) && bench_error_frames(row, references);
    if (floor_tried)
        technique_host_stop(&bench.floor_host);
    if (configured)
        technique_host_stop(&bench.host);
    bench.row_count += ok;
    return ok;
}

static const char *bench_config_label(const char *config) {
    static char labels[4][128];
    static int next;
    char *out = labels[next++ % 4];
    technique_config_label(config, out, sizeof labels[0]);
    return out;
}

/* Keeps the current technique's configuration as failed (its failure is
 * said above it on stderr), after reading and saying any GL error it left
 * behind, so that the next configuration starts clean. */
static void bench_failed(const char *scene_name, const char *config, bool no_skip) {
    context_gl_ok("bench: after the failed configuration");
    fprintf(stderr, "bench: %s, %s %s failed; the sweep goes on\n", scene_name, bench.current->name,
            bench_config_label(config));
    if (bench.failed_count < BENCH_MAX_ROWS)
        bench.failed[bench.failed_count++] = (bench_failure){scene_name, bench.current->name, config, no_skip};
}

/* results.csv's `skips` of a row: every skip on, or --no-skip. */
static const char *bench_skips_text(bool no_skip) { return no_skip ? "off" : "on"; }

static bool bench_scene(const char *scene_path, int scene_index, int *done, int total) {
    char *name = bench.scene_names[scene_index];
    path_stem(scene_path, name, sizeof bench.scene_names[scene_index]);
    if (!scene_load(&bench.scene, scene_path))
        return false;
    if (!camera_check_depth(&bench.scene, scene_path, depth_reversed_available()) ||
        !scene_check_light_flag(&bench.scene, scene_path, bench.light)) {
        scene_free(&bench.scene);
        return false;
    }
    /* After the checks: a scene refused says only why. */
    fprintf(stderr, "[scene %d/%d] %s\n", scene_index + 1, bench.scene_count, name);
    if (bench.verbose)
        scene_print_models(&bench.scene, scene_path);
    bench.scene_objects[scene_index] = bench.scene.object_count;
    memcpy(bench.base_lights, bench.scene.lights, sizeof bench.base_lights);
    bench.base_camera = bench.scene.camera;
    bool ok = render_scene_create(&bench.gpu, &bench.scene);
    dump_frame references[BENCH_MAX_ERROR_FRAMES] = {0};
    for (int k = 0; ok && k < bench.error_frames; k++)
        ok = bench_reference(scene_path, name, bench_error_time(k), &references[k]);
    for (int t = 0; ok && t < registry_technique_count; t++) {
        bench.current = registry_techniques[t];
        for (int c = 0; ok && bench_selected(bench.current) && c < bench_config_count(bench.current); c++) {
            if (!bench_config_taken(bench.current, c))
                continue;
            const char *config = bench.current->bench_configs[c];
            for (int s = 0; ok && s < bench.setting_count; s++) {
                bool no_skip = bench.no_skip_settings[s];
                fprintf(stderr, "  [%d/%d] %s %s%s\n", ++*done, total, bench.current->name, config,
                        bench.skips_compare ? (no_skip ? " (skips off)" : " (skips on)") : "");
                if (!bench_configuration(name, config, no_skip, references))
                    bench_failed(name, config, no_skip);
            }
        }
    }
    for (int k = 0; k < bench.error_frames; k++)
        dump_frame_free(&references[k]);
    render_scene_destroy(&bench.gpu);
    scene_free(&bench.scene);
    return ok;
}

/* The Pareto fronts and plots and the named comparisons are among the rows
 * of the run's first skips setting (skips on when comparing): a row
 * without skips is the same decision at more time. */
static bool bench_in_front_set(const bench_row *r) { return r->no_skip == bench.no_skip_settings[0]; }

/* The row has the figure: a class figure needs a pixel of its class. */
static bool bench_has_error(const bench_row *r, bench_error error) {
    int c = bench_errors[error].class_index;
    return c == BENCH_WHOLE_PICTURE || r->error.class_pixels[c] > 0;
}

static double bench_error_of(const bench_row *r, bench_error error) {
    int c = bench_errors[error].class_index;
    if (c != BENCH_WHOLE_PICTURE)
        return r->error.class_mae[c];
    return error == BENCH_ERROR_MAE ? r->error.mean_abs_error : r->error.misclassified_percent;
}

/* o is at least as fast and as accurate by `error` as row, and better in
 * one of the two. */
static bool bench_dominates(const bench_row *o, const bench_row *row, bench_error error) {
    double ot = o->frame_ms, rt = row->frame_ms;
    double oe = bench_error_of(o, error), re = bench_error_of(row, error);
    return ot <= rt && oe <= re && (ot < rt || oe < re);
}

/* Some row of the scene's front set has the figure: it has a plot. */
static bool bench_scene_has_error(const char *scene, bench_error error) {
    for (int i = 0; i < bench.row_count; i++)
        if (strcmp(bench.rows[i].scene, scene) == 0 && bench_in_front_set(&bench.rows[i]) &&
            bench_has_error(&bench.rows[i], error))
            return true;
    return false;
}

/* Whether row is in the scene's front set and no other configuration of
 * the scene (of the same technique when own_technique) in it dominates
 * row by `error`. */
static bool bench_on_front(const bench_row *row, bool own_technique, bench_error error) {
    if (!bench_in_front_set(row) || !bench_has_error(row, error))
        return false;
    for (int i = 0; i < bench.row_count; i++) {
        const bench_row *o = &bench.rows[i];
        if (o == row || strcmp(o->scene, row->scene) != 0 || !bench_in_front_set(o) || !bench_has_error(o, error) ||
            (own_technique && strcmp(o->technique, row->technique) != 0))
            continue;
        if (bench_dominates(o, row, error))
            return false;
    }
    return true;
}

/* The row of scene, technique and config under the skips setting no_skip,
 * or NULL. */
static const bench_row *bench_find_row(const char *scene, const char *technique, const char *config, bool no_skip) {
    for (int i = 0; i < bench.row_count; i++) {
        const bench_row *r = &bench.rows[i];
        if (strcmp(r->scene, scene) == 0 && strcmp(r->technique, technique) == 0 && strcmp(r->config, config) == 0 &&
            r->no_skip == no_skip)
            return r;
    }
    return NULL;
}

static FILE *bench_open(const char *name, char *path, size_t size) {
    snprintf(path, size, "%s/%s", bench.out_dir, name);
    FILE *f = fopen(path, "w");
    if (!f)
        fprintf(stderr, "%s: cannot create: %s\n", path, strerror(errno));
    return f;
}

static bool bench_close(FILE *f, const char *path) {
    if (fclose(f) != 0) {
        fprintf(stderr, "%s: cannot write: %s\n", path, strerror(errno));
        return false;
    }
    return true;
}

/* A row's shimmer_percent, "-" where the motion does not measure it. */
static const char *bench_shimmer_text(const bench_row *r) {
    static char text[32];
    if (!r->shimmer_measured)
        return "-";
    snprintf(text, sizeof text, "%.4f", 100.0 * (double)r->shimmered / (double)r->followed);
    return text;
}

static bool bench_write_csv(void) {
    char path[PATH_MAX];
    FILE *f = bench_open("results.csv", path, sizeof path);
    if (!f)
        return false;
    results_csv_write_header(f); /* the row below writes its columns in the same order */
    for (int i = 0; i < bench.row_count; i++) {
        const bench_row *r = &bench.rows[i];
        char low[32] = "-", high[32] = "-";
        if (r->ratio.bounded) {
            snprintf(low, sizeof low, "%.3f", r->ratio.low);
            snprintf(high, sizeof high, "%.3f", r->ratio.high);
        }
        fprintf(f, "%s,%s,\"%s\",%.4f,%.4f,%.4f,%.4f,%.3f,%.4f,%.4f,%.4f,%.6f,%ld,\"%s\",%s,%s,%.4f,%s,%s,%s",
                r->scene, r->technique, r->config, r->gpu_median, r->gpu_p90, r->cpu_median, r->cpu_p90,
                r->ratio.median, r->error.false_shadow_percent, r->error.false_lit_percent,
                r->error.misclassified_percent, r->error.mean_abs_error, r->error.compared, bench.ctx.renderer,
                motion_names[bench.motion], bench_skips_text(r->no_skip), r->floor_ms, low, high,
                bench_shimmer_text(r));
        for (int c = 0; c < SHADOWDIFF_CLASS_COUNT; c++) {
            char mae[32];
            fprintf(f, ",%ld,%s", r->error.class_pixels[c],
                    shadowdiff_class_mae_text(&r->error, (shadowdiff_class)c, BENCH_MAE_DECIMALS, mae, sizeof mae));
        }
        fprintf(f, ",%dx%d", bench.width, bench.height);
        if (r->rays_frames > 0 && r->rays.pixels > 0)
            fprintf(f, ",%.4f,%.0f\n", 100.0 * (double)r->rays.traced / (double)r->rays.pixels,
                    (double)r->rays.rays / r->rays_frames);
        else
            fprintf(f, ",-,-\n");
    }
    return bench_close(f, path);
}

static const char *bench_time_basis(void) { return bench.software ? "CPU" : "GPU"; }

/* a is more accurate than b: no worse by either error figure, better by
 * one. */
static bool bench_more_accurate(const bench_row *a, const bench_row *b) {
    bool better = false, worse = false;
    for (int e = 0; e < BENCH_ERROR_COUNT; e++) {
        if (!bench_has_error(a, (bench_error)e) || !bench_has_error(b, (bench_error)e))
            continue;
        double x = bench_error_of(a, (bench_error)e), y = bench_error_of(b, (bench_error)e);
        better = better || x < y;
        worse = worse || x > y;
    }
    return better && !worse;
}

/* Each technique's defaults against its named configurations (the
 * textbook settings a sweep labels "NAME: flags"): the defaults should be
 * more accurate (bench_more_accurate) at no more time. */
static void bench_write_named_comparisons(FILE *f, const char *scene) {
    const bench_row *defaults = NULL;
    for (int i = 0; i < bench.row_count; i++) {
        const bench_row *r = &bench.rows[i];
        if (strcmp(r->scene, scene) != 0 || !bench_in_front_set(r))
            continue;
        if (r->config[0] == 0)
            defaults = r;
        else if (defaults && strcmp(defaults->technique, r->technique) == 0 && strstr(r->config, ": "))
            fprintf(f,
                    "\n%s defaults against %s: misclassified %.4f %% against %.4f %%, MAE %.5f against %.5f, "
                    "%.3f ms against %.3f ms: %s.\n",
                    r->technique, bench_config_label(r->config), defaults->error.misclassified_percent,
                    r->error.misclassified_percent, defaults->error.mean_abs_error, r->error.mean_abs_error,
                    defaults->frame_ms, r->frame_ms,
                    bench_more_accurate(defaults, r) && defaults->frame_ms <= r->frame_ms
                        ? "more accurate at no more time"
                        : "**not** more accurate at no more time");
    }
}

/* --skips-compare: each technique's defaults with every skip on against
 * --no-skip, on the scene. */
static void bench_write_skips_comparison(FILE *f, const char *scene) {
    fprintf(f,
            "\nSkips on against off (defaults, %s ms per frame):\n\n"
            "| technique | ms skips on | ms skips off | speed-up |\n|---|---|---|---|\n",
            bench_time_basis());
    for (int t = 0; t < registry_technique_count; t++) {
        const char *name = registry_techniques[t]->name;
        const bench_row *on = bench_find_row(scene, name, "", false), *off = bench_find_row(scene, name, "", true);
        if (on && off)
            fprintf(f, "| %s | %.3f | %.3f | %.2fx |\n", name, on->frame_ms, off->frame_ms,
                    on->frame_ms > 0 ? off->frame_ms / on->frame_ms : 0);
    }
}

/* What the run's skips were, for the report and the plots' titles. */
static const char *bench_skips_summary(void) {
    return bench.skips_compare ? "on and off (every configuration twice)" : bench_skips_text(bench.no_skip);
}

/* The floor check: the rows whose whole interval lies under 1 (no
 * technique's frame costs less than the floor's beyond the noise), and
 * the noise itself: the floor's rows against their twin and the widest
 * interval of any row. */
static void bench_write_floor_check(FILE *f) {
    int below = 0;
    double widest = 0;
    for (int i = 0; i < bench.row_count; i++) {
        const bench_row *r = &bench.rows[i];
        below += bench_below_floor(r);
        const median_interval *m = &r->ratio;
        if (m->bounded && m->median > 0)
            widest = fmax(widest, fmax(m->high / m->median - 1, 1 - m->low / m->median));
    }
    fprintf(f, "\n## The floor check\n\n");
    if (median_interval_min_samples(RESULTS_CSV_RATIO_CONFIDENCE) > bench.frames) {
        fprintf(f, "Not made: %d timed frames give no interval (at least %d do).\n", bench.frames,
                median_interval_min_samples(RESULTS_CSV_RATIO_CONFIDENCE));
        return;
    }
    fprintf(f, "%s. The noise: the unshadowed frame against itself",
            below ? "**Rows below the floor**" : "No row is below the floor");
    for (int i = 0, n = 0; i < bench.row_count; i++)
        if (strcmp(bench.rows[i].technique, bench.floor->name) == 0)
            fprintf(f, "%s %s (skips %s) %s", n++ ? ";" : ":", bench.rows[i].scene,
                    bench_skips_text(bench.rows[i].no_skip), bench_ratio_text(&bench.rows[i]));
    fprintf(f, "; the widest interval of any row reaches %.1f %% from its median.\n", 100 * widest);
    for (int i = 0; i < bench.row_count; i++)
        if (bench_below_floor(&bench.rows[i]))
            fprintf(f, "\n- %s, %s %s (skips %s): %s", bench.rows[i].scene, bench.rows[i].technique,
                    bench_config_label(bench.rows[i].config), bench_skips_text(bench.rows[i].no_skip),
                    bench_ratio_text(&bench.rows[i]));
    if (below)
        fprintf(f, "\n");
}

/* report.md's list of the configurations that failed, if any. */
static void bench_write_failures(FILE *f) {
    if (bench.failed_count == 0)
        return;
    fprintf(f, "\n## Failed configurations\n\nThese ran no frame to the end (why: the run's stderr); the run "
               "exits 1.\n\n");
    for (int i = 0; i < bench.failed_count; i++) {
        const bench_failure *b = &bench.failed[i];
        fprintf(f, "- %s, %s %s (skips %s)\n", b->scene, b->technique, bench_config_label(b->config),
                bench_skips_text(b->no_skip));
    }
}

/* Says each row below the floor on stderr; returns how many. */
static int bench_floor_failures(void) {
    int below = 0;
    for (int i = 0; i < bench.row_count; i++) {
        const bench_row *r = &bench.rows[i];
        if (!bench_below_floor(r))
            continue;
        fprintf(
            stderr, "bench: %s, %s %s (skips %s): x%s of the unshadowed frame, below the floor beyond the noise\n",
            r->scene, r->technique, bench_config_label(r->config), bench_skips_text(r->no_skip), bench_ratio_text(r));
        below++;
    }
    return below;
}

static bool bench_write_report(void) {
    char path[PATH_MAX];
    FILE *f = bench_open("report.md", path, sizeof path);
    if (!f)
        return false;
    fprintf(f,
            "# Shadow techniques: run time against error\n\n"
            "Renderer: %s. Frames %dx%d; %d timed frames per configuration after %d warm-up "
            "frames; times are medians (p90 in brackets) of GPU time (timer queries) and of CPU "
            "time around each frame and glFinish. Error against the ray-traced reference of light %d "
            "(shadowdiff rules; misclassified at visibility threshold 0.5; MAE, the mean absolute "
            "visibility error, also counts how far off each pixel is, so that blur is a cost too; penumbra "
            "MAE and lit MAE are the MAE over the pixels the truth has in penumbra (visibility strictly "
            "between its umbra and lit bounds) and fully lit: how well a soft shadow is drawn, and what a "
            "filter darkens that should be lit; \"none\" where the truth has no such pixel). A Pareto "
            "front per error figure: a configuration is on the misclassified front when no other "
            "configuration of the scene is both faster and more accurate by misclassified %%, on the other "
            "fronts likewise by their figure (own fronts: no other configuration of the same technique). "
            "In the comparisons of the defaults with the named configurations, more accurate means no "
            "worse by any figure both have and better by one.\n\n"
            "The ratio, the fronts and the plots use **%s time**. %s A row's ratio (x unshadowed) is "
            "the median of its frames' ratios to the unshadowed frames paired with them (frame k of the "
            "floor and frame k of the row, at the same time and under the same skips, each first in turn; "
            "floor ms is the floor frames' median), so that both are timed under the same load of a shared "
            "machine; in brackets, the interval that holds that median with %g %% confidence, from the "
            "pairs alone (the binomial interval of a median; none with fewer than %d frames). The "
            "unshadowed row is the floor against a second copy of itself: its interval is the noise. "
            "Skips: %s. Motion: %s (frame k at k/%g s; the error figures pool the compared pixels of "
            "%d of the timed frames spread evenly over them, the last at %.3f s). Shimmer %%: %s\n",
            bench.ctx.renderer, bench.width, bench.height, bench.frames, bench.warmup, bench.light,
            bench_time_basis(),
            bench.software ? "This renderer rasterizes on the CPU after the commands are submitted, so its "
                             "timer queries measure little more than the submission; the time around the frame "
                             "and glFinish is its real cost."
                           : "GPU time is what the frame costs the GPU; CPU time adds submission and the wait "
                             "in glFinish.",
            100 * RESULTS_CSV_RATIO_CONFIDENCE, median_interval_min_samples(RESULTS_CSV_RATIO_CONFIDENCE),
            bench_skips_summary(), motion_names[bench.motion], BENCH_FRAME_RATE, bench.error_frames,
            bench_error_time(bench.error_frames - 1),
            bench_shimmers() ? "of the compared pixels of those frames, those whose decision changes when "
                               "the maps are held as the frame before fitted them (the same view drawn twice, "
                               "--hold-fit): how much the shadows crawl as the camera moves, free of the "
                               "resampling two views' pixels add."
                             : "\"-\": the camera does not move (it is measured under --motion camera and dolly).");
    if (bench.skips_compare)
        fprintf(f, "\nEach row's floor frames ran under the row's own skips setting; the fronts, the plots and "
                   "the named comparisons are of the rows with skips on.\n");
    for (int s = 0; s < bench.scene_count; s++) {
        const char *scene = bench.scene_names[s];
        fprintf(f, "\n## %s\n\n", scene);
        for (int e = 0; e < BENCH_ERROR_COUNT; e++)
            if (bench_scene_has_error(scene, (bench_error)e))
                fprintf(f, "![time against %s](%s_%s.png)\n", bench_errors[e].name, bench_errors[e].plot, scene);
        fprintf(f, "\n| technique | parameters | skips | GPU ms | CPU ms | x unshadowed | floor ms | "
                   "false-shadow %% | false-lit %% | misclassified %% | MAE | penumbra MAE | lit MAE | shimmer %% |");
        for (int own = 0; own < 2; own++)
            for (int e = 0; e < BENCH_ERROR_COUNT; e++)
                fprintf(f, " %sfront (%s) |", own ? "own " : "", bench_errors[e].name);
        fprintf(f, "\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
        for (int column = 0; column < 2 * BENCH_ERROR_COUNT; column++)
            fprintf(f, "---|");
        fprintf(f, "\n");
        for (int i = 0; i < bench.row_count; i++) {
            const bench_row *r = &bench.rows[i];
            if (strcmp(r->scene, scene) != 0)
                continue;
            char penumbra[32], lit[32];
            fprintf(
                f,
                "| %s | %s | %s | %.3f (%.3f) | %.3f (%.3f) | %s | %.3f | %.4f | %.4f | %.4f | %.5f | %s | %s | %s |",
                r->technique, bench_config_label(r->config), bench_skips_text(r->no_skip), r->gpu_median, r->gpu_p90,
                r->cpu_median, r->cpu_p90, bench_ratio_text(r), r->floor_ms, r->error.false_shadow_percent,
                r->error.false_lit_percent, r->error.misclassified_percent, r->error.mean_abs_error,
                shadowdiff_class_mae_text(&r->error, SHADOWDIFF_CLASS_PENUMBRA, BENCH_REPORT_MAE_DECIMALS, penumbra,
                                          sizeof penumbra),
                shadowdiff_class_mae_text(&r->error, SHADOWDIFF_CLASS_LIT, BENCH_REPORT_MAE_DECIMALS, lit,
                                          sizeof lit),
                bench_shimmer_text(r));
            for (int own = 0; own < 2; own++)
                for (int e = 0; e < BENCH_ERROR_COUNT; e++)
                    fprintf(f, " %s |", bench_on_front(r, own, (bench_error)e) ? "yes" : "");
            fprintf(f, "\n");
        }
        bench_write_named_comparisons(f, scene);
        if (bench.skips_compare)
            bench_write_skips_comparison(f, scene);
    }
    bench_write_floor_check(f);
    bench_write_failures(f);
    return bench_close(f, path);
}

static int bench_compare_rows_by_time(const void *a, const void *b) {
    const bench_row *x = *(const bench_row *const *)a, *y = *(const bench_row *const *)b;
    return bench_compare_doubles(&x->frame_ms, &y->frame_ms);
}

/* The techniques the run times, in registry order, into out (room for
 * BENCH_MAX_TECHNIQUES); returns how many. */
static int bench_selected_techniques(const technique **out) {
    int n = 0;
    for (int t = 0; t < registry_technique_count && n < BENCH_MAX_TECHNIQUES; t++)
        if (bench_selected(registry_techniques[t]))
            out[n++] = registry_techniques[t];
    return n;
}

/* Opens OUT/NAME.gp with its head (plot_write_head: OUT/NAME.png and the
 * title) for the axes and the plot command; NULL on failure. */
static FILE *bench_open_script(const char *name, char *path, size_t size, const char *title) {
    char file[160], picture[PATH_MAX];
    snprintf(file, sizeof file, "%s.gp", name);
    snprintf(picture, sizeof picture, "%s/%s.png", bench.out_dir, name);
    FILE *g = bench_open(file, path, size);
    if (g)
        plot_write_head(g, picture, title);
    return g;
}

/* Closes the script and runs gnuplot on it. */
static bool bench_run_script(FILE *g, const char *script) {
    bool ok = bench_close(g, script);
    char command[PATH_MAX + 64];
    snprintf(command, sizeof command, "gnuplot '%s'", script);
    if (ok && system(command) != 0) {
        fprintf(stderr, "%s: gnuplot failed (is gnuplot installed? make deps)\n", script);
        ok = false;
    }
    return ok;
}

/* Time against `error` on the scene (plot.h): each technique's
 * configurations, a symbol per technique, and that figure's front,
 * numbered from the fastest to the most accurate. */
static bool bench_plot(const char *scene, bench_error error) {
    const technique *techniques[BENCH_MAX_TECHNIQUES];
    const char *series[BENCH_MAX_TECHNIQUES];
    int series_count = bench_selected_techniques(techniques);
    for (int t = 0; t < series_count; t++)
        series[t] = techniques[t]->name;
    static plot_point points[BENCH_MAX_ROWS];
    static const bench_row *plotted[BENCH_MAX_ROWS];
    int point_count = 0;
    for (int t = 0; t < series_count; t++)
        for (int i = 0; i < bench.row_count; i++) {
            const bench_row *r = &bench.rows[i];
            if (strcmp(r->scene, scene) == 0 && strcmp(r->technique, techniques[t]->name) == 0 &&
                bench_in_front_set(r) && bench_has_error(r, error)) {
                plotted[point_count] = r;
                points[point_count++] = (plot_point){r->frame_ms, bench_error_of(r, error), t};
            }
        }
    static const bench_row *front_rows[BENCH_MAX_ROWS];
    static int front[BENCH_MAX_ROWS];
    static char names[BENCH_MAX_ROWS][160];
    static const char *front_names[BENCH_MAX_ROWS];
    int front_count = 0;
    for (int i = 0; i < bench.row_count; i++)
        if (strcmp(bench.rows[i].scene, scene) == 0 && bench_on_front(&bench.rows[i], false, error))
            front_rows[front_count++] = &bench.rows[i];
    qsort(front_rows, (size_t)front_count, sizeof *front_rows, bench_compare_rows_by_time);
    for (int k = 0; k < front_count; k++) {
        for (int i = 0; i < point_count; i++)
            if (plotted[i] == front_rows[k])
                front[k] = i;
        snprintf(names[k], sizeof names[k], "%s: %s", front_rows[k]->technique,
                 bench_config_label(front_rows[k]->config));
        front_names[k] = names[k];
    }
    char name[144], script[PATH_MAX], title[512], xlabel[64];
    snprintf(name, sizeof name, "%s_%s", bench_errors[error].plot, scene);
    snprintf(title, sizeof title, "%s: run time against %s (%s, motion %s, skips %s)", scene,
             bench_errors[error].name, bench.ctx.renderer, motion_names[bench.motion],
             bench_skips_text(bench.no_skip_settings[0]));
    snprintf(xlabel, sizeof xlabel, "%s ms per frame (median)", bench_time_basis());
    const plot_pareto plot = {
        .xlabel = xlabel,
        .ylabel = bench_errors[error].label,
        .series = series,
        .series_count = series_count,
        .points = points,
        .point_count = point_count,
        .front = front,
        .front_names = front_names,
        .front_count = front_count,
    };
    FILE *g = bench_open_script(name, script, sizeof script, title);
    if (!g)
        return false;
    if (!plot_pareto_write(g, &plot)) {
        bench_close(g, script);
        return false;
    }
    return bench_run_script(g, script);
}

static int bench_compare_scenes_by_objects(const void *a, const void *b) {
    int x = bench.scene_objects[*(const int *)a], y = bench.scene_objects[*(const int *)b];
    return (x > y) - (x < y);
}

/* --scaling: one data block per technique and skips setting, its
 * defaults' ms per frame on each scene in order of object count; a line
 * each, solid with skips on, dashed off; each axis as plot.h fits it. */
static bool bench_plot_scaling(void) {
    char data[PATH_MAX], script[PATH_MAX];
    FILE *d = bench_open("scaling.dat", data, sizeof data);
    if (!d)
        return false;
    int order[BENCH_MAX_SCENES];
    double objects[BENCH_MAX_SCENES], ms[BENCH_MAX_ROWS];
    int ms_count = 0;
    for (int s = 0; s < bench.scene_count; s++) {
        order[s] = s;
        objects[s] = bench.scene_objects[s];
    }
    qsort(order, (size_t)bench.scene_count, sizeof *order, bench_compare_scenes_by_objects);
    const technique *techniques[BENCH_MAX_TECHNIQUES];
    int technique_count = bench_selected_techniques(techniques);
    for (int t = 0; t < technique_count; t++)
        for (int k = 0; k < bench.setting_count; k++) {
            for (int s = 0; s < bench.scene_count; s++) {
                const bench_row *r =
                    bench_find_row(bench.scene_names[order[s]], techniques[t]->name, "", bench.no_skip_settings[k]);
                if (r) {
                    fprintf(d, "%d %g\n", bench.scene_objects[order[s]], r->frame_ms);
                    ms[ms_count++] = r->frame_ms;
                }
            }
            fprintf(d, "\n\n");
        }
    char title[512], ylabel[64];
    snprintf(title, sizeof title, "time per frame against object count (%s, motion %s, %s time)", bench.ctx.renderer,
             motion_names[bench.motion], bench_time_basis());
    snprintf(ylabel, sizeof ylabel, "%s ms per frame (median), defaults", bench_time_basis());
    FILE *g = bench_close(d, data) ? bench_open_script("scaling", script, sizeof script, title) : NULL;
    if (!g)
        return false;
    const plot_axis x = plot_axis_fit(objects, bench.scene_count), y = plot_axis_fit(ms, ms_count);
    plot_axis_write(g, &x, 'x', "objects in the scene");
    plot_axis_write(g, &y, 'y', ylabel);
    fprintf(g, "plot ");
    for (int t = 0, block = 0; t < technique_count; t++)
        for (int k = 0; k < bench.setting_count; k++, block++) {
            bool no_skip = bench.no_skip_settings[k];
            fprintf(g,
                    "%s'%s' index %d using 1:2 with linespoints linecolor %d dashtype %d pointtype %d "
                    "title '%s, skips %s'",
                    block ? ", " : "", data, block, t + 1, no_skip ? 2 : 1, 5 + 2 * t, techniques[t]->name,
                    bench_skips_text(no_skip));
        }
    fprintf(g, "\n");
    return bench_run_script(g, script);
}

int main(int argc, char **argv) {
    int status = bench_parse_flags(argc, argv);
    if (status)
        return status == FLAGS_HELP_ASKED ? 0 : status;
    path_in_project("shaders", bench.default_shader_dir, sizeof bench.default_shader_dir);
    shader_set_directory(bench.shader_dir ? bench.shader_dir : bench.default_shader_dir);
    /* The standard scenes, and long_view, where perspective aliasing is. */
    static const char *const standard[] = {"simple", "bunny", "teapot", "long_view"};
    enum { standard_count = sizeof standard / sizeof *standard };
    for (int i = 0; bench.scene_count == 0 && i < standard_count; i++) {
        char relative[64];
        snprintf(relative, sizeof relative, "assets/scenes/%s.json", standard[i]);
        path_in_project(relative, bench.default_scenes[i], sizeof bench.default_scenes[i]);
    }
    if (bench.scene_count == 0)
        for (int i = 0; i < standard_count; i++)
            bench.scenes[bench.scene_count++] = bench.default_scenes[i];
    const context_settings settings = {.backend = CONTEXT_AUTO, .verbose = bench.verbose};
    if (!context_create(&bench.ctx, &settings))
        return 1;
    bench.software = context_software_renderer(bench.ctx.renderer);
    bench.floor = registry_cost_floor();
    int total = 0, done = 0;
    for (int t = 0; t < registry_technique_count; t++)
        if (bench_selected(registry_techniques[t]))
            total += bench_configs_taken(registry_techniques[t]) * bench.setting_count * bench.scene_count;
    /* The HUD's text is the techniques' legends' (legend.h). */
    bool ok =
        path_make_directories(bench.out_dir) && target_create(&bench.target, bench.width, bench.height) && hud_init();
    glGenQueries(1, &bench.query);
    for (int s = 0; ok && s < bench.scene_count; s++)
        ok = bench_scene(bench.scenes[s], s, &done, total);
    ok = ok && bench_write_csv() && bench_write_report();
    for (int s = 0; ok && s < bench.scene_count; s++)
        for (int e = 0; ok && e < BENCH_ERROR_COUNT; e++)
            ok = !bench_scene_has_error(bench.scene_names[s], (bench_error)e) ||
                 bench_plot(bench.scene_names[s], (bench_error)e);
    ok = ok && (!bench.scaling || bench_plot_scaling());
    glDeleteQueries(1, &bench.query);
    hud_destroy();
    target_destroy(&bench.target);
    context_destroy(&bench.ctx);
    if (ok)
        printf("%s/results.csv\n%s/report.md\n", bench.out_dir, bench.out_dir);
    if (ok && bench.scaling)
        printf("%s/scaling.png\n", bench.out_dir);
    /* After every output is written: a run below the floor, or with a
     * failed configuration, fails. */
    return ok && bench_floor_failures() == 0 && bench.failed_count == 0 ? 0 : 1;
}
