/* bench: run time against error for every technique over its parameter
 * sweep, on each scene, in one process on one GL context.
 *
 * For each scene: the ray-traced reference (computed once and cached under
 * OUT/reference/, recomputed when the scene file is newer), then for every
 * registered technique and each of its bench_configs: warm-up frames, then
 * timed frames (GPU time from GL_TIME_ELAPSED queries, CPU time from the
 * clock around the frame and glFinish), then the technique's own dump
 * compared with the reference (shadowdiff rules). Writes
 *   OUT/results.csv         one row per scene and configuration
 *   OUT/report.md           a table per scene, its Pareto front, and each
 *                           technique's defaults against its named
 *                           (textbook) configurations
 *   OUT/pareto_SCENE.png    ms per frame against misclassified %, by gnuplot
 * Timings are medians and 90th percentiles of the timed frames: single
 * frames on a shared machine are noise.
 *
 * Skips (render.h: view culling) are on, as in the app; --no-skip turns
 * them off, and results.csv's `skips` column says which it was.
 */
#include <glad/gl.h>
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "capture.h"
#include "context.h"
#include "flags.h"
#include "path.h"
#include "raytrace.h"
#include "registry.h"
#include "shader.h"
#include "shadowdiff.h"

#define BENCH_MAX_ROWS 256
#define BENCH_MAX_FRAMES 1000
#define BENCH_MAX_SCENES 16

typedef struct bench_row {
    const char *scene, *technique, *config;
    bool cost_floor; /* the technique is the registry's cost floor */
    double gpu_median, gpu_p90, cpu_median, cpu_p90;
    double frame_ms; /* what the ratio, the front and the plot use */
    double ratio;
    shadowdiff_result error;
} bench_row;

static struct {
    /* flags (zero: the default, which --quick makes small) */
    const char *out_dir;
    int width, height, frames, warmup, light_samples;
    bool quick, verbose;
    render_skips skips;
    const char *scenes[BENCH_MAX_SCENES];
    char scene_names[BENCH_MAX_SCENES][128];
    int scene_count;
    char default_scenes[4][PATH_MAX]; /* the standard scenes */
    const char *shader_dir;
    char default_shader_dir[PATH_MAX];
    /* run */
    context ctx;
    target target;
    scene scene;
    render_scene gpu;
    camera_view view;
    const technique *current;
    technique_host host;
    unsigned query;
    bool software; /* a CPU rasterizer: timer queries miss its work */
    bench_row rows[BENCH_MAX_ROWS];
    int row_count;
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
    {"light-samples", "reference shadow rays per area light (256; --quick: 16)", 0, FLAGS_INT,
     .integer = &bench.light_samples, .min = 1, .max = RAYTRACE_MAX_LIGHT_SAMPLES, .what = "a count"},
    {"quick", "small and short: a smoke test of the whole pipeline", 0, FLAGS_SWITCH, .on = &bench.quick},
    {"skip", "no skips at all (view culling...): every pass draws the\nwhole scene; results.csv's skips column says off", 0, FLAGS_TOGGLE,
     .disabled = &bench.skips.no_skip},
    {"shader-dir", "where the GLSL files are", 0, FLAGS_STRING, .text = &bench.shader_dir, .value_name = "DIR"},
    {"verbose", "print the backend and GL renderer", 0, FLAGS_SWITCH, .on = &bench.verbose},
    {.name = "help", .help = "this text", .kind = FLAGS_HELP},
};

static int bench_parse_flags(int argc, char **argv) {
    int count = (int)(sizeof bench_flags / sizeof *bench_flags);
    int status = flags_parse("bench", bench_flags, count, argc - 1, argv + 1);
    if (status == FLAGS_HELP_ASKED) {
        printf("usage: bench [flags] [SCENE.json...]\n"
               "Times every technique over its parameter sweep and measures its error against the\n"
               "ray-traced reference, on each scene (default: the standard scenes and long_view).\n");
        flags_print_help(stdout, bench_flags, count, 2, 0);
    }
    if (status)
        return status;
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
    return 0;
}

static double bench_now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

static bool bench_render_frame(int visibility_of) {
    return technique_host_frame(&bench.host, &bench.view, &bench.target, 0, visibility_of);
}

static int bench_compare_doubles(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Nearest-rank percentile of sorted samples. */
static double bench_percentile(const double *sorted, int n, double p) {
    int rank = (int)(p * n + 0.999999);
    return sorted[rank < 1 ? 0 : rank > n ? n - 1 : rank - 1];
}

static bool bench_time_frames(bench_row *row) {
    static double gpu[BENCH_MAX_FRAMES], cpu[BENCH_MAX_FRAMES];
    for (int i = 0; i < bench.warmup; i++)
        if (!bench_render_frame(-1))
            return false;
    glFinish();
    for (int i = 0; i < bench.frames; i++) {
        double start = bench_now_ms();
        glBeginQuery(GL_TIME_ELAPSED, bench.query);
        bool ok = bench_render_frame(-1);
        glEndQuery(GL_TIME_ELAPSED);
        glFinish();
        cpu[i] = bench_now_ms() - start;
        GLuint64 ns = 0;
        glGetQueryObjectui64v(bench.query, GL_QUERY_RESULT, &ns);
        gpu[i] = ns / 1e6;
        if (!ok)
            return false;
    }
    qsort(gpu, (size_t)bench.frames, sizeof *gpu, bench_compare_doubles);
    qsort(cpu, (size_t)bench.frames, sizeof *cpu, bench_compare_doubles);
    row->gpu_median = bench_percentile(gpu, bench.frames, 0.5);
    row->gpu_p90 = bench_percentile(gpu, bench.frames, 0.9);
    row->cpu_median = bench_percentile(cpu, bench.frames, 0.5);
    row->cpu_p90 = bench_percentile(cpu, bench.frames, 0.9);
    row->frame_ms = bench.software ? row->cpu_median : row->gpu_median;
    return true;
}

static bool bench_newer(const char *path, const char *than) {
    struct stat a, b;
    return stat(path, &a) == 0 && stat(than, &b) == 0 && a.st_mtime >= b.st_mtime;
}

/* The reference of light 0, from the cache when it is newer than the scene. */
static bool bench_reference(const char *scene_path, const char *name, dump_frame *reference) {
    char dir[PATH_MAX], meta[PATH_MAX + 16];
    snprintf(dir, sizeof dir, "%s/reference/%s_%dx%d_%d", bench.out_dir, name, bench.width, bench.height,
             bench.light_samples);
    snprintf(meta, sizeof meta, "%s/meta.json", dir);
    if (bench_newer(meta, scene_path) && dump_read(reference, dir)) {
        fprintf(stderr, "  reference: cached in %s\n", dir);
        return true;
    }
    fprintf(stderr, "  reference: ray tracing %dx%d ...\n", bench.width, bench.height);
    const raytrace_settings settings = {.light_samples = bench.light_samples};
    return raytrace_render(&bench.scene, bench.width, bench.height, 0, &settings, reference) &&
           dump_write(reference, dir);
}

/* Times and measures one configuration of the current technique. */
static bool bench_configuration(const char *scene_name, const char *config, const dump_frame *reference) {
    if (bench.row_count == BENCH_MAX_ROWS) {
        fprintf(stderr, "bench: more than %d configurations\n", BENCH_MAX_ROWS);
        return false;
    }
    bench_row *row = &bench.rows[bench.row_count];
    *row = (bench_row){.scene = scene_name, .technique = bench.current->name, .config = config,
                      .cost_floor = bench.current->cost_floor};
    dump_frame dump;
    bool ok = technique_apply_config(bench.current, config) && technique_host_start(&bench.host, bench.current, &bench.gpu, &bench.skips) &&
              bench_time_frames(row) &&
              capture_dump(&bench.gpu, &bench.view, &bench.target, 0, bench_render_frame, &dump);
    technique_host_stop(&bench.host);
    if (!ok)
        return false;
    ok = shadowdiff_compare(reference, &dump, NULL, &row->error, NULL);
    dump_frame_free(&dump);
    bench.row_count += ok;
    return ok;
}

static bool bench_scene(const char *scene_path, int scene_index, int *done, int total) {
    char *name = bench.scene_names[scene_index];
    path_stem(scene_path, name, sizeof bench.scene_names[scene_index]);
    fprintf(stderr, "[scene %d/%d] %s\n", scene_index + 1, bench.scene_count, name);
    if (!scene_load(&bench.scene, scene_path))
        return false;
    bool ok = render_scene_create(&bench.gpu, &bench.scene);
    dump_frame reference = {0};
    camera_view_compute(&bench.scene.camera, (float)bench.width / (float)bench.height, &bench.view);
    ok = ok && bench_reference(scene_path, name, &reference);
    int first_row = bench.row_count;
    for (int t = 0; ok && t < registry_technique_count; t++) {
        bench.current = registry_techniques[t];
        for (int c = 0; ok && c < bench.current->bench_config_count; c++) {
            const char *config = bench.current->bench_configs[c];
            fprintf(stderr, "  [%d/%d] %s %s\n", ++*done, total, bench.current->name, config);
            ok = bench_configuration(name, config, &reference);
        }
    }
    /* The cost floor: how much each technique adds to a plain frame. */
    double floor_ms = 0;
    for (int r = first_row; r < bench.row_count; r++)
        if (bench.rows[r].cost_floor)
            floor_ms = bench.rows[r].frame_ms;
    for (int r = first_row; r < bench.row_count; r++)
        bench.rows[r].ratio = floor_ms > 0 ? bench.rows[r].frame_ms / floor_ms : 0;
    dump_frame_free(&reference);
    render_scene_destroy(&bench.gpu);
    scene_free(&bench.scene);
    return ok;
}

/* o is at least as fast and as accurate as row, and better in one of the two. */
static bool bench_dominates(const bench_row *o, const bench_row *row) {
    double ot = o->frame_ms, rt = row->frame_ms;
    double oe = o->error.misclassified_percent, re = row->error.misclassified_percent;
    return ot <= rt && oe <= re && (ot < rt || oe < re);
}

/* No other configuration of the scene (of the same technique when
 * own_technique) dominates row. */
static bool bench_on_front(const bench_row *row, bool own_technique) {
    for (int i = 0; i < bench.row_count; i++) {
        const bench_row *o = &bench.rows[i];
        if (o == row || strcmp(o->scene, row->scene) != 0 ||
            (own_technique && strcmp(o->technique, row->technique) != 0))
            continue;
        if (bench_dominates(o, row))
            return false;
    }
    return true;
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

/* results.csv's `skips`: every skip on, or --no-skip. */
static const char *bench_skips_text(void) { return bench.skips.no_skip ? "off" : "on"; }

static bool bench_write_csv(void) {
    char path[PATH_MAX];
    FILE *f = bench_open("results.csv", path, sizeof path);
    if (!f)
        return false;
    fprintf(f, "scene,technique,parameters,gpu_ms_median,gpu_ms_p90,cpu_ms_median,cpu_ms_p90,"
               "ratio_to_unshadowed,false_shadow_percent,false_lit_percent,misclassified_percent,mae,"
               "compared_pixels,renderer,skips\n");
    for (int i = 0; i < bench.row_count; i++) {
        const bench_row *r = &bench.rows[i];
        fprintf(f, "%s,%s,\"%s\",%.4f,%.4f,%.4f,%.4f,%.3f,%.4f,%.4f,%.4f,%.6f,%ld,\"%s\",%s\n", r->scene,
                r->technique, r->config, r->gpu_median, r->gpu_p90, r->cpu_median, r->cpu_p90, r->ratio,
                r->error.false_shadow_percent, r->error.false_lit_percent, r->error.misclassified_percent,
                r->error.mean_abs_error, r->error.compared, bench.ctx.renderer, bench_skips_text());
    }
    return bench_close(f, path);
}

static const char *bench_time_basis(void) { return bench.software ? "CPU" : "GPU"; }

static const char *bench_config_label(const char *config) {
    static char labels[4][128];
    static int next;
    char *out = labels[next++ % 4];
    technique_config_label(config, out, sizeof labels[0]);
    return out;
}

/* Each technique's defaults against its named configurations (the
 * textbook settings a sweep labels "NAME: flags"): the defaults should be
 * more accurate at no more time. */
static void bench_write_named_comparisons(FILE *f, const char *scene) {
    const bench_row *defaults = NULL;
    for (int i = 0; i < bench.row_count; i++) {
        const bench_row *r = &bench.rows[i];
        if (strcmp(r->scene, scene) != 0)
            continue;
        if (r->config[0] == 0)
            defaults = r;
        else if (defaults && strcmp(defaults->technique, r->technique) == 0 && strstr(r->config, ": "))
            fprintf(f, "\n%s defaults against %s: misclassified %.4f %% against %.4f %%, %.3f ms against %.3f "
                       "ms: %s.\n",
                    r->technique, bench_config_label(r->config), defaults->error.misclassified_percent,
                    r->error.misclassified_percent, defaults->frame_ms, r->frame_ms,
                    defaults->error.misclassified_percent < r->error.misclassified_percent &&
                            defaults->frame_ms <= r->frame_ms
                        ? "more accurate at no more time"
                        : "**not** more accurate at no more time");
    }
}

static bool bench_write_report(void) {
    char path[PATH_MAX];
    FILE *f = bench_open("report.md", path, sizeof path);
    if (!f)
        return false;
    fprintf(f, "# Shadow techniques: run time against error\n\n"
               "Renderer: %s. Frames %dx%d; %d timed frames per configuration after %d warm-up "
               "frames; times are medians (p90 in brackets) of GPU time (timer queries) and of CPU "
               "time around each frame and glFinish. Error against the ray-traced reference of light 0 "
               "(shadowdiff rules; misclassified at visibility threshold 0.5). Pareto front: no other "
               "configuration of the scene is both faster and more accurate (own front: no other "
               "configuration of the same technique).\n\n"
               "The ratio, the front and the plots use **%s time**. %s Skips (view culling): %s.\n",
            bench.ctx.renderer, bench.width, bench.height, bench.frames, bench.warmup, bench_time_basis(),
            bench.software ? "This renderer rasterizes on the CPU after the commands are submitted, so its "
                             "timer queries measure little more than the submission; the time around the frame "
                             "and glFinish is its real cost."
                           : "GPU time is what the frame costs the GPU; CPU time adds submission and the wait "
                             "in glFinish.",
            bench_skips_text());
    for (int s = 0; s < bench.scene_count; s++) {
        const char *scene = bench.scene_names[s];
        fprintf(f, "\n## %s\n\n![time against error](pareto_%s.png)\n\n"
                   "| technique | parameters | GPU ms | CPU ms | x unshadowed | false-shadow %% | "
                   "false-lit %% | misclassified %% | MAE | front | own front |\n"
                   "|---|---|---|---|---|---|---|---|---|---|---|\n",
                scene, scene);
        for (int i = 0; i < bench.row_count; i++) {
            const bench_row *r = &bench.rows[i];
            if (strcmp(r->scene, scene) == 0)
                fprintf(f, "| %s | %s | %.3f (%.3f) | %.3f (%.3f) | %.2f | %.4f | %.4f | %.4f | %.5f | %s | %s |\n",
                        r->technique, bench_config_label(r->config), r->gpu_median, r->gpu_p90, r->cpu_median,
                        r->cpu_p90, r->ratio, r->error.false_shadow_percent, r->error.false_lit_percent,
                        r->error.misclassified_percent, r->error.mean_abs_error, bench_on_front(r, false) ? "yes" : "",
                        bench_on_front(r, true) ? "yes" : "");
        }
        bench_write_named_comparisons(f, scene);
    }
    return bench_close(f, path);
}

static int bench_compare_rows_by_time(const void *a, const void *b) {
    const bench_row *x = *(const bench_row *const *)a, *y = *(const bench_row *const *)b;
    return bench_compare_doubles(&x->frame_ms, &y->frame_ms);
}

/* One gnuplot data block per technique (its configurations), then the
 * front, as a line from the fastest to the most accurate. */
static bool bench_plot(const char *scene) {
    char data_name[160], script_name[160], data[PATH_MAX], script[PATH_MAX];
    snprintf(data_name, sizeof data_name, "pareto_%s.dat", scene);
    snprintf(script_name, sizeof script_name, "pareto_%s.gp", scene);
    FILE *d = bench_open(data_name, data, sizeof data);
    if (!d)
        return false;
    int blocks = 0;
    for (int t = 0; t < registry_technique_count; t++, blocks++) {
        for (int i = 0; i < bench.row_count; i++) {
            const bench_row *r = &bench.rows[i];
            if (strcmp(r->scene, scene) == 0 && strcmp(r->technique, registry_techniques[t]->name) == 0)
                fprintf(d, "%g %g \"%s\"\n", r->frame_ms, r->error.misclassified_percent,
                        bench_config_label(r->config));
        }
        fprintf(d, "\n\n");
    }
    const bench_row *front[BENCH_MAX_ROWS];
    int front_count = 0;
    for (int i = 0; i < bench.row_count; i++)
        if (strcmp(bench.rows[i].scene, scene) == 0 && bench_on_front(&bench.rows[i], false))
            front[front_count++] = &bench.rows[i];
    qsort(front, (size_t)front_count, sizeof *front, bench_compare_rows_by_time);
    for (int i = 0; i < front_count; i++)
        fprintf(d, "%g %g\n", front[i]->frame_ms, front[i]->error.misclassified_percent);
    bool ok = bench_close(d, data);
    FILE *g = ok ? bench_open(script_name, script, sizeof script) : NULL;
    if (!g)
        return false;
    fprintf(g, "set terminal pngcairo size 960,640 font ',11'\nset output '%s/pareto_%s.png'\n"
               "set title '%s: run time against error (%s)'\nset xlabel '%s ms per frame (median)'\n"
               "set ylabel 'misclassified %% of compared pixels'\nset grid\nset key outside right\n"
               "set offsets graph 0.05, graph 0.25, graph 0.1, 0\nset yrange [0:*]\nplot ",
            bench.out_dir, scene, scene, bench.ctx.renderer, bench_time_basis());
    for (int t = 0; t < blocks; t++)
        fprintf(g, "'%s' index %d using 1:2 with points pointsize 2 pointtype %d title '%s', "
                   "'' index %d using 1:2:3 with labels offset 1,0.7 font ',8' left notitle, ",
                data, t, 5 + 2 * t, registry_techniques[t]->name, t);
    fprintf(g, "'%s' index %d using 1:2 with lines dashtype 2 linecolor 'grey40' title 'Pareto front'\n", data,
            blocks);
    ok = bench_close(g, script);
    char command[PATH_MAX + 64];
    snprintf(command, sizeof command, "gnuplot '%s'", script);
    if (ok && system(command) != 0) {
        fprintf(stderr, "%s: gnuplot failed (is gnuplot installed? make deps)\n", script);
        ok = false;
    }
    return ok;
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
    /* Mesa's software rasterizers name themselves in GL_RENDERER. */
    bench.software = strstr(bench.ctx.renderer, "llvmpipe") || strstr(bench.ctx.renderer, "softpipe");
    int total = 0, done = 0;
    for (int t = 0; t < registry_technique_count; t++)
        total += registry_techniques[t]->bench_config_count * bench.scene_count;
    bool ok = path_make_directories(bench.out_dir) && target_create(&bench.target, bench.width, bench.height);
    glGenQueries(1, &bench.query);
    for (int s = 0; ok && s < bench.scene_count; s++)
        ok = bench_scene(bench.scenes[s], s, &done, total);
    ok = ok && bench_write_csv() && bench_write_report();
    for (int s = 0; ok && s < bench.scene_count; s++)
        ok = bench_plot(bench.scene_names[s]);
    glDeleteQueries(1, &bench.query);
    target_destroy(&bench.target);
    context_destroy(&bench.ctx);
    if (ok)
        printf("%s/results.csv\n%s/report.md\n", bench.out_dir, bench.out_dir);
    return ok ? 0 : 1;
}
