/* report: `make report`'s pages, every results table regenerated from
 * the runs' own files, so that no copied figure drifts from them.
 *
 * Reads BENCH/RUN/results.csv for each run `make bench` makes (report_runs;
 * the cities' run is BENCH itself), STRESS/table.md and RULER/ (`make
 * ruler`: the rays file and each scene's shadowdiff JSON), and writes
 *   OUT/index.md    the stamp (commit, "dirty" when tracked files changed,
 *                   date in UTC, machine and CPU, renderer, frame size),
 *                   the compact table of current figures, one section per
 *                   table of report_tables, the stress suite's summary,
 *                   the reference's own noise, and each run's report.md
 *                   and plots, copied under OUT/RUN/
 *   OUT/index.html  the same page in plain HTML, nothing loaded from elsewhere
 *   OUT/compact.md  the stamp's line and the compact table alone
 * --readme FILE puts OUT/compact.md between FILE's lines
 * <!-- report:begin --> and <!-- report:end -->, a blank line either side.
 *
 * The static run is required (the compact table's); another run, the
 * stress table or the ruler that is missing is named where it would
 * stand. Malformed input stops the run with one line naming the file. The
 * date is SOURCE_DATE_EPOCH's when that is set.
 */
#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/utsname.h>
#include <time.h>
#include <unistd.h>

#include "context.h"
#include "csv.h"
#include "flags.h"
#include "gallery_page.h"
#include "json.h"
#include "path.h"
#include "raytrace.h"
#include "registry.h"
#include "results_csv.h"

#define REPORT_MAX_SCENES 16
#define REPORT_MAX_TECHNIQUES 16
#define REPORT_MAX_TABLE_COLUMNS 12
#define REPORT_MAX_VALUES 8 /* distinct renderers, frame sizes */
#define REPORT_MAX_MARKDOWN (4 << 20)
#define REPORT_CELL 512
#define REPORT_BEGIN "<!-- report:begin -->"
#define REPORT_END "<!-- report:end -->"

/* results.csv's columns the report reads, each checked in every row. */
typedef enum report_csv {
    REPORT_CSV_SCENE,
    REPORT_CSV_TECHNIQUE,
    REPORT_CSV_PARAMETERS,
    REPORT_CSV_GPU_MS,
    REPORT_CSV_CPU_MS,
    REPORT_CSV_RATIO,
    REPORT_CSV_FLOOR_MS,
    REPORT_CSV_RATIO_LOW,
    REPORT_CSV_RATIO_HIGH,
    REPORT_CSV_MISCLASSIFIED,
    REPORT_CSV_MAE,
    REPORT_CSV_UMBRA_MAE,
    REPORT_CSV_PENUMBRA_MAE,
    REPORT_CSV_LIT_MAE,
    REPORT_CSV_SHIMMER,
    REPORT_CSV_RENDERER,
    REPORT_CSV_MOTION,
    REPORT_CSV_SKIPS,
    REPORT_CSV_FRAME_SIZE,
    REPORT_CSV_TRACED,
    REPORT_CSV_RAYS,
    REPORT_CSV_COUNT
} report_csv;
static const struct {
    results_csv_column column;
    bool number;      /* a finite number, or `word` */
    const char *word; /* what stands for no figure ("none", "-"), or NULL */
} report_csv_columns[REPORT_CSV_COUNT] = {
    [REPORT_CSV_SCENE] = {RESULTS_CSV_SCENE, false, NULL},
    [REPORT_CSV_TECHNIQUE] = {RESULTS_CSV_TECHNIQUE, false, NULL},
    [REPORT_CSV_PARAMETERS] = {RESULTS_CSV_PARAMETERS, false, NULL},
    [REPORT_CSV_GPU_MS] = {RESULTS_CSV_GPU_MS, true, NULL},
    [REPORT_CSV_CPU_MS] = {RESULTS_CSV_CPU_MS, true, NULL},
    [REPORT_CSV_RATIO] = {RESULTS_CSV_RATIO, true, NULL},
    [REPORT_CSV_FLOOR_MS] = {RESULTS_CSV_FLOOR_MS, true, NULL},
    [REPORT_CSV_RATIO_LOW] = {RESULTS_CSV_RATIO_LOW, true, "-"},
    [REPORT_CSV_RATIO_HIGH] = {RESULTS_CSV_RATIO_HIGH, true, "-"},
    [REPORT_CSV_MISCLASSIFIED] = {RESULTS_CSV_MISCLASSIFIED, true, NULL},
    [REPORT_CSV_MAE] = {RESULTS_CSV_MAE, true, NULL},
    [REPORT_CSV_UMBRA_MAE] = {RESULTS_CSV_CLASS_MAE(SHADOWDIFF_CLASS_UMBRA), true, "none"},
    [REPORT_CSV_PENUMBRA_MAE] = {RESULTS_CSV_CLASS_MAE(SHADOWDIFF_CLASS_PENUMBRA), true, "none"},
    [REPORT_CSV_LIT_MAE] = {RESULTS_CSV_CLASS_MAE(SHADOWDIFF_CLASS_LIT), true, "none"},
    [REPORT_CSV_SHIMMER] = {RESULTS_CSV_SHIMMER, true, "-"},
    [REPORT_CSV_RENDERER] = {RESULTS_CSV_RENDERER, false, NULL},
    [REPORT_CSV_MOTION] = {RESULTS_CSV_MOTION, false, NULL},
    [REPORT_CSV_SKIPS] = {RESULTS_CSV_SKIPS, false, NULL},
    [REPORT_CSV_FRAME_SIZE] = {RESULTS_CSV_FRAME_SIZE, false, NULL},
    [REPORT_CSV_TRACED] = {RESULTS_CSV_TRACED_PERCENT, true, "-"},
    [REPORT_CSV_RAYS] = {RESULTS_CSV_RAYS, true, "-"},
};

/* One run of `make bench`: OUT/NAME/ holds its copied report and plots. */
typedef struct report_run {
    const char *name, *dir; /* dir: under --bench, "" for --bench itself */
    bool present;
    char path[PATH_MAX]; /* its results.csv */
    csv_table table;
    int columns[REPORT_CSV_COUNT];
} report_run;
static report_run report_runs[] = {
    {.name = "static", .dir = "static"},
    {.name = "light", .dir = "light"},
    {.name = "camera", .dir = "camera"},
    {.name = "dolly", .dir = "dolly"},
    {.name = "cities", .dir = ""},
    {.name = "cities-light", .dir = "cities-light"},
    {.name = "dense", .dir = "dense"},
    {.name = "dense-light", .dir = "dense-light"},
    {.name = "soft", .dir = "soft"},
    {.name = "soft-light", .dir = "soft-light"},
    {.name = "hidden", .dir = "hidden"},
    {.name = "hidden-light", .dir = "hidden-light"},
    {.name = "psm-cases", .dir = "psm-cases"},
    {.name = "eye-in-shadow", .dir = "eye-in-shadow"},
    {.name = "lamps", .dir = "lamps"},
    {.name = "lamps-lamp", .dir = "lamps-lamp"},
    {.name = "lamps-moving", .dir = "lamps-moving"},
};
#define REPORT_RUN_COUNT ((int)(sizeof report_runs / sizeof *report_runs))

/* A table's columns: a CSV figure of the row, or one derived from it.
 * Zero ends a table's list. */
typedef enum report_figure {
    REPORT_END_OF_COLUMNS,
    REPORT_SCENE,
    REPORT_TECHNIQUE,
    REPORT_PARAMETERS,
    REPORT_MS, /* in the time the ratio uses: CPU on a software rasterizer */
    REPORT_RATIO,
    REPORT_FLOOR_MS,
    REPORT_MISCLASSIFIED,
    REPORT_MAE,
    REPORT_UMBRA_MAE,
    REPORT_PENUMBRA_MAE,
    REPORT_LIT_MAE,
    REPORT_SHIMMER,
    REPORT_TRACED,
    REPORT_RAYS,
    REPORT_MS_SKIPS_OFF,   /* the same row's with every skip off */
    REPORT_SKIPS_SPEED_UP, /* ms skips off over ms skips on */
    REPORT_FIGURE_COUNT
} report_figure;
static const struct {
    const char *header;
    int csv; /* report_csv, or -1 for a derived figure */
} report_figures[REPORT_FIGURE_COUNT] = {
    [REPORT_SCENE] = {"scene", REPORT_CSV_SCENE},
    [REPORT_TECHNIQUE] = {"technique", REPORT_CSV_TECHNIQUE},
    [REPORT_PARAMETERS] = {"parameters", REPORT_CSV_PARAMETERS},
    [REPORT_MS] = {"ms", -1},
    [REPORT_RATIO] = {"x unshadowed", REPORT_CSV_RATIO},
    [REPORT_FLOOR_MS] = {"floor ms", REPORT_CSV_FLOOR_MS},
    [REPORT_MISCLASSIFIED] = {"misclassified %", REPORT_CSV_MISCLASSIFIED},
    [REPORT_MAE] = {"MAE", REPORT_CSV_MAE},
    [REPORT_UMBRA_MAE] = {"umbra MAE", REPORT_CSV_UMBRA_MAE},
    [REPORT_PENUMBRA_MAE] = {"penumbra MAE", REPORT_CSV_PENUMBRA_MAE},
    [REPORT_LIT_MAE] = {"lit MAE", REPORT_CSV_LIT_MAE},
    [REPORT_SHIMMER] = {"shimmer %", REPORT_CSV_SHIMMER},
    [REPORT_TRACED] = {"traced %", REPORT_CSV_TRACED},
    [REPORT_RAYS] = {"rays/frame", REPORT_CSV_RAYS},
    [REPORT_MS_SKIPS_OFF] = {"ms skips off", -1},
    [REPORT_SKIPS_SPEED_UP] = {"skips speed-up", -1},
};

/* A table's column: a report_figure, with this bit for the figure of the
 * table's other run's row of the same configuration. */
#define REPORT_OTHER 0x100

/* A section of the report: the rows with skips on of one run (of some
 * techniques, one scene, some configurations, where it says), each with its
 * figures and those of the same configuration in another run. */
typedef struct report_table {
    const char *title;
    const char *run, *other;               /* run names; other may be NULL */
    const char *techniques[4];             /* none: every technique */
    const char *scene;                     /* NULL: every scene */
    const char *parameters[4];             /* none: every configuration; "": the defaults */
    int columns[REPORT_MAX_TABLE_COLUMNS]; /* report_figure | REPORT_OTHER */
} report_table;

#define REPORT_ERRORS REPORT_MISCLASSIFIED, REPORT_MAE
#define REPORT_SKIPS_COLUMNS                                                                                         \
    {                                                                                                                \
        REPORT_SCENE, REPORT_TECHNIQUE, REPORT_MS, REPORT_RATIO, REPORT_MS_SKIPS_OFF, REPORT_SKIPS_SPEED_UP,         \
            REPORT_MS | REPORT_OTHER, REPORT_RATIO | REPORT_OTHER, REPORT_SKIPS_SPEED_UP | REPORT_OTHER              \
    }
static const report_table report_tables[] = {
    {"Shadow maps",
     "static",
     NULL,
     {"shadowmap"},
     NULL,
     {NULL},
     {REPORT_SCENE, REPORT_PARAMETERS, REPORT_MS, REPORT_RATIO, REPORT_ERRORS, REPORT_LIT_MAE}},
    {"Perspective shadow maps",
     "static",
     NULL,
     {"psm"},
     NULL,
     {NULL},
     {REPORT_SCENE, REPORT_PARAMETERS, REPORT_MS, REPORT_RATIO, REPORT_ERRORS}},
    {"Perspective shadow maps: the hard cases",
     "psm-cases",
     NULL,
     {"psm"},
     NULL,
     {"--warp uniform", "", "--warp lispsm"},
     {REPORT_SCENE, REPORT_PARAMETERS, REPORT_ERRORS, REPORT_RATIO}},
    {"Volumes with the eye in a shadow: z-fail's caps against ZP+'s near-plane count",
     "eye-in-shadow",
     NULL,
     {"volumes"},
     NULL,
     {"", "--mode zfail", "--mode zp-plus", "--mode eye-count"},
     {REPORT_SCENE, REPORT_PARAMETERS, REPORT_MS, REPORT_RATIO, REPORT_ERRORS}},
    {"Shadow maps with rays where they are unsure (hybrid): the pixels traced and the rays, against the map alone "
     "(--rays off) and every pixel traced (--rays all)",
     "static",
     NULL,
     {"hybrid"},
     NULL,
     {NULL},
     {REPORT_SCENE, REPORT_PARAMETERS, REPORT_MS, REPORT_RATIO, REPORT_ERRORS, REPORT_TRACED, REPORT_RAYS}},
    {"Cascaded shadow maps",
     "static",
     NULL,
     {"cascades"},
     NULL,
     {NULL},
     {REPORT_SCENE, REPORT_PARAMETERS, REPORT_MS, REPORT_RATIO, REPORT_ERRORS}},
    {"Cascades against one map and the warps, on one ruler",
     "camera",
     "dolly",
     {"shadowmap", "psm", "cascades"},
     "long_view",
     {NULL},
     {REPORT_TECHNIQUE, REPORT_PARAMETERS, REPORT_ERRORS, REPORT_SHIMMER, REPORT_RATIO,
      REPORT_MISCLASSIFIED | REPORT_OTHER, REPORT_MAE | REPORT_OTHER, REPORT_SHIMMER | REPORT_OTHER,
      REPORT_RATIO | REPORT_OTHER}},
    {"Soft shadows from area lights",
     "soft",
     "soft-light",
     {NULL},
     NULL,
     {NULL},
     {REPORT_SCENE, REPORT_TECHNIQUE, REPORT_PARAMETERS, REPORT_PENUMBRA_MAE, REPORT_UMBRA_MAE, REPORT_LIT_MAE,
      REPORT_MAE, REPORT_MISCLASSIFIED, REPORT_RATIO, REPORT_RATIO | REPORT_OTHER}},
    {"Many lights: 64 shadowed lamps (lamps_64), still and one lamp moving (--motion lamp)",
     "lamps",
     "lamps-lamp",
     {NULL},
     NULL,
     {NULL},
     {REPORT_TECHNIQUE, REPORT_PARAMETERS, REPORT_MS, REPORT_RATIO, REPORT_ERRORS, REPORT_RATIO | REPORT_OTHER,
      REPORT_MISCLASSIFIED | REPORT_OTHER}},
    {"Many lights: every lamp moving (--motion lamps), and the shadow maps' budget",
     "lamps-moving",
     NULL,
     {NULL},
     NULL,
     {NULL},
     {REPORT_TECHNIQUE, REPORT_PARAMETERS, REPORT_MS, REPORT_RATIO, REPORT_ERRORS}},
    {"Skips: the cities", "cities", "cities-light", {NULL}, NULL, {""}, REPORT_SKIPS_COLUMNS},
    {"Skips: the dense scene", "dense", "dense-light", {NULL}, NULL, {""}, REPORT_SKIPS_COLUMNS},
    {"Hidden casters and objects", "hidden", "hidden-light", {NULL}, NULL, {""}, REPORT_SKIPS_COLUMNS},
    {"Frame cost",
     "static",
     "light",
     {NULL},
     NULL,
     {""},
     {REPORT_SCENE, REPORT_TECHNIQUE, REPORT_MS, REPORT_RATIO, REPORT_FLOOR_MS, REPORT_MS | REPORT_OTHER,
      REPORT_RATIO | REPORT_OTHER, REPORT_FLOOR_MS | REPORT_OTHER}},
    {"Measuring accuracy and speed",
     "static",
     NULL,
     {NULL},
     NULL,
     {NULL},
     {REPORT_SCENE, REPORT_TECHNIQUE, REPORT_PARAMETERS, REPORT_MS, REPORT_RATIO, REPORT_ERRORS, REPORT_PENUMBRA_MAE,
      REPORT_LIT_MAE}},
    {"Temporal stability: shimmer",
     "camera",
     "dolly",
     {NULL},
     NULL,
     {NULL},
     {REPORT_SCENE, REPORT_TECHNIQUE, REPORT_PARAMETERS, REPORT_SHIMMER, REPORT_MISCLASSIFIED,
      REPORT_SHIMMER | REPORT_OTHER, REPORT_MISCLASSIFIED | REPORT_OTHER}},
};
#define REPORT_TABLE_COUNT ((int)(sizeof report_tables / sizeof *report_tables))

/* The compact table: each technique's defaults on the static run's
 * scenes, and the skips' speed-up on these runs' scenes. */
static const char *const report_compact_skips[] = {"hidden", "cities"};
#define REPORT_COMPACT_SKIPS ((int)(sizeof report_compact_skips / sizeof *report_compact_skips))
#define REPORT_COMPACT_RUN "static"

typedef struct report_stamp {
    char commit[64], date[32], day[16], machine[256], cpu[256];
    char renderers[REPORT_CELL], sizes[REPORT_CELL];
} report_stamp;

static struct { const char *bench_dir, *stress_dir, *ruler_dir, *out_dir, *readme; } report;

static const flags_param report_flags[] = {
    {"bench", "where `make bench` wrote its runs (out/bench)", 0, FLAGS_STRING, .text = &report.bench_dir,
     .value_name = "DIR"},
    {"stress", "where `make stress` wrote table.md (out/stress)", 0, FLAGS_STRING, .text = &report.stress_dir,
     .value_name = "DIR"},
    {"ruler", "where `make ruler` wrote its comparisons (out/ruler)", 0, FLAGS_STRING, .text = &report.ruler_dir,
     .value_name = "DIR"},
    {"out", "where the report goes (out/report)", 0, FLAGS_STRING, .text = &report.out_dir, .value_name = "DIR"},
    {"readme", "also put the compact table between FILE's report markers", 0, FLAGS_STRING, .text = &report.readme,
     .value_name = "FILE"},
    {.name = "help", .help = "this text", .kind = FLAGS_HELP},
};

static report_run *report_find_run(const char *name) {
    for (int r = 0; r < REPORT_RUN_COUNT; r++)
        if (strcmp(report_runs[r].name, name) == 0)
            return &report_runs[r];
    return NULL;
}

static const char *report_cell(const report_run *run, int row, report_csv column) {
    return csv_cell(&run->table, row, run->columns[column]);
}

/* Whether `text` is one finite number and nothing else. */
static bool report_is_number(const char *text) {
    char *end;
    double v = strtod(text, &end);
    return end != text && *end == '\0' && isfinite(v);
}

/* The run's results.csv, if there is one: every column report_csv names,
 * every figure a number (or its word for none). */
static bool report_load_run(report_run *run) {
    snprintf(run->path, sizeof run->path, "%s%s%s/results.csv", report.bench_dir, *run->dir ? "/" : "", run->dir);
    if (access(run->path, F_OK) != 0)
        return true;
    if (!csv_read(run->path, &run->table))
        return false;
    run->present = true;
    for (int c = 0; c < REPORT_CSV_COUNT; c++) {
        run->columns[c] = csv_column(&run->table, results_csv_name(report_csv_columns[c].column));
        if (run->columns[c] < 0) {
            fprintf(stderr, "%s: no column %s (a results.csv from an older build/bench? run make bench again)\n",
                    run->path, results_csv_name(report_csv_columns[c].column));
            return false;
        }
    }
    for (int row = 0; row < run->table.rows; row++)
        for (int c = 0; c < REPORT_CSV_COUNT; c++) {
            const char *text = report_cell(run, row, (report_csv)c), *word = report_csv_columns[c].word;
            bool ok = !report_csv_columns[c].number || report_is_number(text) || (word && strcmp(text, word) == 0);
            if (c == REPORT_CSV_SKIPS)
                ok = strcmp(text, "on") == 0 || strcmp(text, "off") == 0;
            if (!ok) {
                /* the header is line 1 */
                fprintf(stderr, "%s:%d: column %s: expected %s, got '%s'\n", run->path, row + 2,
                        results_csv_name(report_csv_columns[c].column),
                        c == REPORT_CSV_SKIPS ? "on or off" : "a number", text);
                return false;
            }
        }
    return true;
}

/* The row's time in the basis its ratio uses. */
static double report_ms(const report_run *run, int row) {
    bool software = context_software_renderer(report_cell(run, row, REPORT_CSV_RENDERER));
    return atof(report_cell(run, row, software ? REPORT_CSV_CPU_MS : REPORT_CSV_GPU_MS));
}

/* The row of `run` with the configuration of row `row` of `of`, under the
 * skips setting `skips`; -1 if it has none. */
static int report_twin(const report_run *run, const report_run *of, int row, const char *skips) {
    if (!run || !run->present)
        return -1;
    for (int r = 0; r < run->table.rows; r++) {
        bool same = strcmp(report_cell(run, r, REPORT_CSV_SKIPS), skips) == 0;
        for (int c = REPORT_CSV_SCENE; same && c <= REPORT_CSV_PARAMETERS; c++)
            same = strcmp(report_cell(run, r, (report_csv)c), report_cell(of, row, (report_csv)c)) == 0;
        if (same)
            return r;
    }
    return -1;
}

/* Figure `figure` of row `row` of `run` as text into out ("-" where the
 * row or its skips-off twin is missing). */
static void report_figure_text(report_figure figure, const report_run *run, int row, char *out, size_t size) {
    if (row < 0) {
        snprintf(out, size, "-");
        return;
    }
    int off =
        figure == REPORT_MS_SKIPS_OFF || figure == REPORT_SKIPS_SPEED_UP ? report_twin(run, run, row, "off") : -1;
    double on_ms = report_ms(run, row);
    switch (figure) {
    case REPORT_MS: snprintf(out, size, "%.4f", on_ms); break;
    case REPORT_MS_SKIPS_OFF:
        if (off < 0)
            snprintf(out, size, "-");
        else
            snprintf(out, size, "%.4f", report_ms(run, off));
        break;
    case REPORT_SKIPS_SPEED_UP:
        if (off < 0 || on_ms <= 0)
            snprintf(out, size, "-");
        else
            snprintf(out, size, "%.2fx", report_ms(run, off) / on_ms);
        break;
    case REPORT_PARAMETERS: {
        const char *parameters = report_cell(run, row, REPORT_CSV_PARAMETERS);
        snprintf(out, size, "%s", *parameters ? parameters : "defaults");
        break;
    }
    default: snprintf(out, size, "%s", report_cell(run, row, (report_csv)report_figures[figure].csv));
    }
}

/* A markdown table cell: `|` escaped. */
static void report_markdown_cell(FILE *f, const char *text) {
    fputs(" ", f);
    for (const char *c = text; *c; c++)
        fputs(*c == '|' ? "\\|" : (char[]){*c, '\0'}, f);
    fputs(" |", f);
}

/* Whether `value` is one of the (up to 4) names; true when none is given. */
static bool report_named(const char *const names[4], const char *value) {
    bool named = !names[0];
    for (int i = 0; i < 4 && names[i] && !named; i++)
        named = strcmp(names[i], value) == 0;
    return named;
}

static bool report_row_selected(const report_table *t, const report_run *run, int row) {
    return report_named(t->techniques, report_cell(run, row, REPORT_CSV_TECHNIQUE)) &&
           report_named(t->parameters, report_cell(run, row, REPORT_CSV_PARAMETERS)) &&
           strcmp(report_cell(run, row, REPORT_CSV_SKIPS), "on") == 0 &&
           (!t->scene || strcmp(t->scene, report_cell(run, row, REPORT_CSV_SCENE)) == 0);
}

/* A link to the run's section of the page, or that it did not run. */
static void report_run_reference(FILE *f, const report_run *run) {
    if (run->present)
        fprintf(f, "[%s](#run-%s)", run->name, run->name);
    else
        fprintf(f, "%s (not run: no %s)", run->name, run->path);
}

static void report_write_table(FILE *f, const report_table *t) {
    report_run *run = report_find_run(t->run), *other = t->other ? report_find_run(t->other) : NULL;
    fprintf(f, "\n## %s\n\nRun: ", t->title);
    report_run_reference(f, run);
    if (other) {
        fputs("; in brackets: ", f);
        report_run_reference(f, other);
    }
    fputs(".\n", f);
    int rows = 0;
    for (int row = 0; run->present && row < run->table.rows; row++)
        rows += report_row_selected(t, run, row);
    if (run->present && !rows)
        fprintf(f, "\nNo rows: %s has no configuration this table shows.\n", run->name);
    if (!rows)
        return;
    fputs("\n|", f);
    for (const int *c = t->columns; *c; c++) {
        char header[REPORT_CELL];
        bool from_other = *c & REPORT_OTHER;
        snprintf(header, sizeof header, "%s%s%s%s", report_figures[*c & ~REPORT_OTHER].header, from_other ? " (" : "",
                 from_other ? other->name : "", from_other ? ")" : "");
        report_markdown_cell(f, header);
    }
    fputs("\n|", f);
    for (const int *c = t->columns; *c; c++)
        fputs("---|", f);
    for (int row = 0; row < run->table.rows; row++) {
        if (!report_row_selected(t, run, row))
            continue;
        fputs("\n|", f);
        int twin = report_twin(other, run, row, "on");
        for (const int *c = t->columns; *c; c++) {
            char text[REPORT_CELL];
            bool from_other = *c & REPORT_OTHER;
            report_figure_text((report_figure)(*c & ~REPORT_OTHER), from_other ? other : run, from_other ? twin : row,
                               text, sizeof text);
            report_markdown_cell(f, text);
        }
    }
    fputs("\n", f);
}

/* The distinct values of `column` over every present run, joined. */
static void report_distinct(report_csv column, char *out, size_t size) {
    const char *seen[REPORT_MAX_VALUES];
    int count = 0;
    out[0] = '\0';
    for (int r = 0; r < REPORT_RUN_COUNT; r++)
        for (int row = 0; report_runs[r].present && row < report_runs[r].table.rows; row++) {
            const char *value = report_cell(&report_runs[r], row, column);
            bool known = false;
            for (int i = 0; i < count && !known; i++)
                known = strcmp(seen[i], value) == 0;
            if (known || count == REPORT_MAX_VALUES)
                continue;
            seen[count] = value;
            size_t used = strlen(out);
            snprintf(out + used, size - used, "%s%s", count++ ? "; " : "", value);
        }
}

/* The first line of a command's output, or "" when it fails. */
static void report_command_line(const char *command, char *out, size_t size) {
    out[0] = '\0';
    FILE *p = popen(command, "r");
    if (!p)
        return;
    if (!fgets(out, (int)size, p))
        out[0] = '\0';
    /* the rest read too: a command cut off by a closed pipe fails */
    for (char rest[256]; fgets(rest, sizeof rest, p);)
        continue;
    if (pclose(p) != 0)
        out[0] = '\0';
    out[strcspn(out, "\n")] = '\0';
}

static void report_make_stamp(report_stamp *s) {
    char status[8];
    report_command_line("git rev-parse --short HEAD 2>/dev/null", s->commit, sizeof s->commit);
    /* README.md is left out: the compact table refilled there is this
     * report's own output. */
    report_command_line("git status --porcelain --untracked-files=no -- ':(top)' ':(top,exclude)README.md' "
                        "2>/dev/null",
                        status, sizeof status);
    if (!s->commit[0])
        snprintf(s->commit, sizeof s->commit, "unknown (not a git checkout)");
    else if (status[0])
        strncat(s->commit, " dirty", sizeof s->commit - strlen(s->commit) - 1);
    const char *epoch = getenv("SOURCE_DATE_EPOCH");
    time_t now = epoch && *epoch ? (time_t)strtoll(epoch, NULL, 10) : time(NULL);
    struct tm utc;
    if (!gmtime_r(&now, &utc))
        utc = (struct tm){0};
    strftime(s->date, sizeof s->date, "%Y-%m-%d %H:%M UTC", &utc);
    strftime(s->day, sizeof s->day, "%Y-%m-%d", &utc);
    struct utsname name;
    snprintf(s->machine, sizeof s->machine, "%s", uname(&name) == 0 ? name.nodename : "unknown");
    snprintf(s->cpu, sizeof s->cpu, "CPU unknown");
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[512];
    int processors = 0;
    while (f && fgets(line, sizeof line, f)) {
        char *colon = strchr(line, ':');
        processors += strncmp(line, "processor", strlen("processor")) == 0;
        if (colon && strncmp(line, "model name", strlen("model name")) == 0 && processors == 1) {
            colon[strcspn(colon, "\n")] = '\0';
            snprintf(s->cpu, sizeof s->cpu, "%s", colon + 1 + (colon[1] == ' '));
        }
    }
    if (f)
        fclose(f);
    size_t used = strlen(s->cpu);
    if (processors)
        snprintf(s->cpu + used, sizeof s->cpu - used, ", %d processors", processors);
    report_distinct(REPORT_CSV_RENDERER, s->renderers, sizeof s->renderers);
    report_distinct(REPORT_CSV_FRAME_SIZE, s->sizes, sizeof s->sizes);
}

/* The row of `technique`'s defaults on `scene` with skips on; -1: none. */
static int report_defaults_row(const report_run *run, const char *technique, const char *scene) {
    for (int row = 0; row < run->table.rows; row++)
        if (strcmp(report_cell(run, row, REPORT_CSV_SCENE), scene) == 0 &&
            strcmp(report_cell(run, row, REPORT_CSV_TECHNIQUE), technique) == 0 &&
            !*report_cell(run, row, REPORT_CSV_PARAMETERS) &&
            strcmp(report_cell(run, row, REPORT_CSV_SKIPS), "on") == 0)
            return row;
    return -1;
}

/* Each value of one defaults' figure on the run's scenes, " / " between,
 * "-" where a scene has no such row. */
static void report_compact_cell(const report_run *run, const char *technique, const char *const *scenes,
                                int scene_count, report_figure figure, char *out, size_t size) {
    out[0] = '\0';
    for (int s = 0; s < scene_count; s++) {
        int found = report_defaults_row(run, technique, scenes[s]);
        char text[64] = "-";
        if (found >= 0 && figure == REPORT_MS)
            snprintf(text, sizeof text, "%.2f", report_ms(run, found));
        else if (found >= 0 && figure == REPORT_SKIPS_SPEED_UP)
            report_figure_text(figure, run, found, text, sizeof text);
        else if (found >= 0) {
            static const char *const formats[REPORT_FIGURE_COUNT] = {
                [REPORT_RATIO] = "%.2f", [REPORT_MISCLASSIFIED] = "%.4f", [REPORT_MAE] = "%.5f"};
            snprintf(text, sizeof text, formats[figure],
                     atof(report_cell(run, found, (report_csv)report_figures[figure].csv)));
        }
        size_t used = strlen(out);
        snprintf(out + used, size - used, "%s%s", s ? " / " : "", text);
    }
}

/* The noise under the compact table: on each scene, the cost floor's row,
 * timed against a second copy of itself, with its ratio's interval. */
static void report_write_noise(FILE *f, const report_run *run, const char *const *scenes, int scene_count) {
    const char *floor = registry_cost_floor()->name;
    fprintf(f,
            "\nThe noise: the %s frame timed against a second copy of itself (x %s, with the interval that "
            "holds its median at %g %% confidence where the run had the frames for one):",
            floor, floor, 100 * RESULTS_CSV_RATIO_CONFIDENCE);
    for (int i = 0; i < scene_count; i++) {
        int row = report_defaults_row(run, floor, scenes[i]);
        const char *low = row >= 0 ? report_cell(run, row, REPORT_CSV_RATIO_LOW) : "-";
        fprintf(f, "%s %s %s", i ? ";" : "", scenes[i], row >= 0 ? report_cell(run, row, REPORT_CSV_RATIO) : "-");
        if (strcmp(low, "-") != 0)
            fprintf(f, " [%s, %s]", low, report_cell(run, row, REPORT_CSV_RATIO_HIGH));
    }
    fprintf(f, ". A technique is below the floor only where its ratio's whole interval is under 1, which fails "
               "`build/bench`.\n");
}

/* The distinct values of `column` of the run, in order of first row. */
static int report_run_values(const report_run *run, report_csv column, const char **out, int max) {
    int count = 0;
    for (int row = 0; row < run->table.rows; row++) {
        const char *value = report_cell(run, row, column);
        bool known = false;
        for (int i = 0; i < count && !known; i++)
            known = strcmp(out[i], value) == 0;
        if (!known && count < max)
            out[count++] = value;
    }
    return count;
}

/* The stamp's line and the compact table: each technique's defaults on
 * the static run's scenes, with skips on, and the skips' speed-up on the
 * scenes of report_compact_skips' runs. */
static void report_write_compact(FILE *f, const report_stamp *s) {
    const report_run *run = report_find_run(REPORT_COMPACT_RUN);
    const char *scenes[REPORT_MAX_SCENES], *techniques[REPORT_MAX_TECHNIQUES];
    int scene_count = report_run_values(run, REPORT_CSV_SCENE, scenes, REPORT_MAX_SCENES);
    int technique_count = report_run_values(run, REPORT_CSV_TECHNIQUE, techniques, REPORT_MAX_TECHNIQUES);
    fprintf(f,
            "Current figures, from `make report` (commit %s, %s; %s; %s): each technique's defaults, nothing "
            "moving, skips on; ms is the time the ratio uses. Every table: `out/report/index.md`.\n\n",
            s->commit, s->day, s->renderers, s->sizes);
    char scene_list[REPORT_CELL] = "";
    for (int i = 0; i < scene_count; i++) {
        size_t used = strlen(scene_list);
        snprintf(scene_list + used, sizeof scene_list - used, "%s%s", i ? " / " : "", scenes[i]);
    }
    static const report_figure figures[] = {REPORT_MS, REPORT_RATIO, REPORT_MISCLASSIFIED, REPORT_MAE};
    enum { figure_count = sizeof figures / sizeof *figures };
    fputs("| technique |", f);
    for (int i = 0; i < figure_count; i++)
        fprintf(f, " %s (%s) |", report_figures[figures[i]].header, scene_list);
    const char *skip_scenes[REPORT_COMPACT_SKIPS][REPORT_MAX_SCENES];
    int skip_counts[REPORT_COMPACT_SKIPS] = {0};
    for (int k = 0; k < REPORT_COMPACT_SKIPS; k++) {
        const report_run *skips = report_find_run(report_compact_skips[k]);
        if (!skips->present)
            continue;
        skip_counts[k] = report_run_values(skips, REPORT_CSV_SCENE, skip_scenes[k], REPORT_MAX_SCENES);
        fprintf(f, " skips speed-up, %s (", skips->name);
        for (int i = 0; i < skip_counts[k]; i++)
            fprintf(f, "%s%s", i ? " / " : "", skip_scenes[k][i]);
        fprintf(f, ") |");
    }
    fputs("\n|---|", f);
    for (int i = 0; i < figure_count; i++)
        fputs("---|", f);
    for (int k = 0; k < REPORT_COMPACT_SKIPS; k++)
        fputs(report_find_run(report_compact_skips[k])->present ? "---|" : "", f);
    for (int t = 0; t < technique_count; t++) {
        fprintf(f, "\n| %s |", techniques[t]);
        char cell[REPORT_CELL];
        for (int i = 0; i < figure_count; i++) {
            report_compact_cell(run, techniques[t], scenes, scene_count, figures[i], cell, sizeof cell);
            fprintf(f, " %s |", cell);
        }
        for (int k = 0; k < REPORT_COMPACT_SKIPS; k++) {
            const report_run *skips = report_find_run(report_compact_skips[k]);
            if (!skips->present)
                continue;
            report_compact_cell(skips, techniques[t], skip_scenes[k], skip_counts[k], REPORT_SKIPS_SPEED_UP, cell,
                                sizeof cell);
            fprintf(f, " %s |", cell);
        }
    }
    fputs("\n", f);
    report_write_noise(f, run, scenes, scene_count);
}

static bool report_close(FILE *f, const char *path) {
    bool ok = !ferror(f);
    if (fclose(f) != 0 || !ok) {
        fprintf(stderr, "%s: cannot write: %s\n", path, strerror(errno));
        return false;
    }
    return true;
}

static FILE *report_create(const char *path) {
    FILE *f = fopen(path, "w");
    if (!f)
        fprintf(stderr, "%s: cannot create: %s\n", path, strerror(errno));
    return f;
}

static bool report_copy(const char *from, const char *to) {
    char *text;
    size_t length;
    if (!(text = path_read_text(from, REPORT_MAX_MARKDOWN * 4, &length)))
        return false;
    FILE *f = report_create(to);
    bool ok = f && fwrite(text, 1, length, f) == length;
    ok = f && report_close(f, to) && ok;
    free(text);
    return ok;
}

/* What a run's section copies: its report.md and its plots. */
static int report_select_copied(const struct dirent *entry) {
    const char *name = entry->d_name;
    size_t n = strlen(name);
    return strcmp(name, "report.md") == 0 || (n > 4 && strcmp(name + n - 4, ".png") == 0);
}

/* The run's section under "Runs": its report.md and plots, copied to
 * OUT/NAME/. */
static bool report_write_run(FILE *f, const report_run *run) {
    char from[PATH_MAX], dir[PATH_MAX];
    snprintf(dir, sizeof dir, "%s/%s", report.out_dir, run->name);
    snprintf(from, sizeof from, "%s%s%s", report.bench_dir, *run->dir ? "/" : "", run->dir);
    fprintf(f, "\n### Run: %s\n\n`%s`; motion %s.", run->name, run->path,
            run->table.rows ? report_cell(run, 0, REPORT_CSV_MOTION) : "-");
    struct dirent **entries;
    int count = scandir(from, &entries, report_select_copied, alphasort);
    if (count < 0) {
        fprintf(stderr, "%s: cannot list: %s\n", from, strerror(errno));
        return false;
    }
    bool ok = path_make_directories(dir);
    for (int i = 0; i < count; i++) {
        const char *name = entries[i]->d_name;
        char source[PATH_MAX + 256], target[PATH_MAX + 256];
        snprintf(source, sizeof source, "%s/%s", from, name);
        snprintf(target, sizeof target, "%s/%s", dir, name);
        ok = ok && report_copy(source, target);
        if (strcmp(name, "report.md") == 0)
            fprintf(f, " Its own report: [%s/report.md](%s/report.md).", run->name, run->name);
    }
    fputs("\n\n", f);
    for (int i = 0; i < count; i++) {
        if (strcmp(entries[i]->d_name, "report.md") != 0)
            fprintf(f, "![%s](%s/%s)\n", entries[i]->d_name, run->name, entries[i]->d_name);
        free(entries[i]);
    }
    free(entries);
    return ok;
}

/* The stress run's summary: table.md up to its "## Every row", its
 * headings a level down, and the whole file copied to OUT/stress/. */
static bool report_write_stress(FILE *f) {
    char path[PATH_MAX], dir[PATH_MAX], copy[PATH_MAX + 16];
    snprintf(path, sizeof path, "%s/table.md", report.stress_dir);
    fputs("\n## Stress suite\n\n", f);
    if (access(path, F_OK) != 0) {
        fprintf(f, "Not run: no %s (make stress).\n", path);
        return true;
    }
    char *text = path_read_text(path, REPORT_MAX_MARKDOWN, NULL);
    if (!text)
        return false;
    char *summary = strstr(text, "\n## Summary\n"), *rows = strstr(text, "\n## Every row\n");
    bool ok = summary && rows && rows > summary;
    if (!ok)
        fprintf(stderr, "%s: expected a \"## Summary\" section, then \"## Every row\"\n", path);
    snprintf(dir, sizeof dir, "%s/stress", report.out_dir);
    snprintf(copy, sizeof copy, "%s/table.md", dir);
    ok = ok && path_make_directories(dir) && report_copy(path, copy);
    if (ok) {
        *rows = '\0';
        char *body = strchr(text, '\n');
        fprintf(f, "Every row: [stress/table.md](stress/table.md).\n");
        for (char *line = body + 1, *next; *line; line = next) {
            next = line + strcspn(line, "\n");
            next += *next == '\n';
            fprintf(f, "%s%.*s", line[0] == '#' ? "#" : "", (int)(next - line), line);
        }
    }
    free(text);
    return ok;
}

/* The ruler's comparisons: shadowdiff's JSON files. */
static int report_select_json(const struct dirent *entry) {
    size_t n = strlen(entry->d_name);
    return n > 5 && strcmp(entry->d_name + n - 5, ".json") == 0;
}

/* shadowdiff's JSON figure `key` of `file` as text: a number, or "none"
 * for null (a class without pixels). */
static bool report_json_figure(const char *file, const cJSON *root, const char *key, const char *format, char *out,
                               size_t size) {
    const cJSON *item = cJSON_GetObjectItemCaseSensitive(root, key);
    if (cJSON_IsNull(item)) {
        snprintf(out, size, "none");
        return true;
    }
    if (!cJSON_IsNumber(item) || !isfinite(item->valuedouble))
        return json_fail(file, "", key, "expected a number or null, got %s", item ? json_kind(item) : "nothing");
    snprintf(out, size, format, item->valuedouble);
    return true;
}

/* The reference's own noise: RULER/SCENE.json, shadowdiff --json of the
 * scene traced with raytrace's default rays against RULER/rays rays. */
static bool report_write_ruler(FILE *f) {
    static const struct {
        const char *key, *header, *format;
    } figures[] = {
        {"umbra_mae", "umbra MAE", "%.5f"},
        {"penumbra_mae", "penumbra MAE", "%.5f"},
        {"penumbra_pixels", "penumbra pixels", "%.0f"},
        {"lit_mae", "lit MAE", "%.6f"},
        {"mean_abs_error", "MAE", "%.5f"},
        {"misclassified_percent", "misclassified %", "%.3f"},
    };
    enum { FIGURE_COUNT = sizeof figures / sizeof *figures };
    char path[PATH_MAX];
    snprintf(path, sizeof path, "%s/rays", report.ruler_dir);
    fputs("\n## The reference's own noise\n\n", f);
    if (access(path, F_OK) != 0) {
        fprintf(f, "Not run: no %s (make ruler).\n", path);
        return true;
    }
    char *text = path_read_text(path, REPORT_CELL, NULL), *end = NULL;
    long rays = text ? strtol(text, &end, 10) : 0;
    bool ok = text && end != text && (*end == '\n' || !*end) && rays > 0;
    if (text && !ok)
        fprintf(stderr, "%s: expected a count of rays, got '%s'\n", path, text);
    free(text);
    struct dirent **entries = NULL;
    int count = ok ? scandir(report.ruler_dir, &entries, report_select_json, alphasort) : 0;
    if (count < 0) {
        fprintf(stderr, "%s: cannot list: %s\n", report.ruler_dir, strerror(errno));
        return false;
    }
    if (ok) {
        fprintf(f,
                "Each area light's scene traced with raytrace's default %d shadow rays per pixel, compared with "
                "the same traced with %ld (`make ruler`), as shadowdiff compares a technique with the "
                "reference. A technique's class MAE within these is within the ruler's own noise.\n\n| scene |",
                RAYTRACE_DEFAULT_LIGHT_SAMPLES, rays);
        for (int i = 0; i < FIGURE_COUNT; i++)
            report_markdown_cell(f, figures[i].header);
        fputs("\n|---|", f);
        for (int i = 0; i < FIGURE_COUNT; i++)
            fputs("---|", f);
        fputs("\n", f);
    }
    for (int e = 0; e < count; e++) {
        snprintf(path, sizeof path, "%s/%s", report.ruler_dir, entries[e]->d_name);
        cJSON *root = ok ? json_load(path, REPORT_MAX_MARKDOWN) : NULL;
        ok = root != NULL;
        fprintf(f, "| %.*s |", (int)(strlen(entries[e]->d_name) - strlen(".json")), entries[e]->d_name);
        for (int i = 0; ok && i < FIGURE_COUNT; i++) {
            char cell[REPORT_CELL];
            ok = report_json_figure(path, root, figures[i].key, figures[i].format, cell, sizeof cell);
            if (ok)
                report_markdown_cell(f, cell);
        }
        fputs("\n", f);
        cJSON_Delete(root);
        free(entries[e]);
    }
    free(entries);
    return ok;
}

static bool report_write_markdown(const char *path, const report_stamp *s) {
    FILE *f = report_create(path);
    if (!f)
        return false;
    fprintf(
        f,
        "# Shadow techniques: the results\n\n"
        "Commit %s; %s; machine %s (%s); renderer %s; frame size %s.\n\n"
        "Written by `make report` from the runs below (`make bench`, `make stress`, `make ruler`): every figure here is "
        "a run's own, none copied by hand.\n\n## Current figures\n\n",
        s->commit, s->date, s->machine, s->cpu, s->renderers, s->sizes);
    report_write_compact(f, s);
    for (int t = 0; t < REPORT_TABLE_COUNT; t++)
        report_write_table(f, &report_tables[t]);
    bool ok = report_write_stress(f) && report_write_ruler(f);
    fputs("\n## Runs\n", f);
    for (int r = 0; ok && r < REPORT_RUN_COUNT; r++)
        ok = !report_runs[r].present || report_write_run(f, &report_runs[r]);
    return report_close(f, path) && ok;
}

/* ---- the page: index.md's markdown as HTML ---- */

/* The anchor of a heading: lower case letters, digits and dashes, a space
 * a dash (as the markdown renderers make them). */
static void report_anchor(FILE *f, const char *heading) {
    for (const char *c = heading; *c; c++)
        if (isalnum((unsigned char)*c) || *c == '-')
            fputc(tolower((unsigned char)*c), f);
        else if (*c == ' ')
            fputc('-', f);
}

/* Writes text[0..length) with `code`, **bold**, [text](link) and
 * ![text](picture) as HTML, `\|` as `|`, everything else escaped. */
static void report_html_inline(FILE *f, const char *text, size_t length) {
    char piece[REPORT_CELL * 4];
    const char *end = text + length;
    while (text < end) {
        const char *close;
        bool image = text[0] == '!' && text + 1 < end && text[1] == '[';
        const char *bracket = text + image;
        if (*text == '`' && (close = memchr(text + 1, '`', (size_t)(end - text - 1)))) {
            snprintf(piece, sizeof piece, "%.*s", (int)(close - text - 1), text + 1);
            fputs("<code>", f), gallery_page_text(f, piece), fputs("</code>", f);
            text = close + 1;
        } else if (text + 1 < end && text[0] == '*' && text[1] == '*' && (close = strstr(text + 2, "**")) &&
                   close < end) {
            snprintf(piece, sizeof piece, "%.*s", (int)(close - text - 2), text + 2);
            fputs("<strong>", f), gallery_page_text(f, piece), fputs("</strong>", f);
            text = close + 2;
        } else if (*bracket == '[' && (close = strstr(bracket, "](")) && close < end &&
                   memchr(close, ')', (size_t)(end - close))) {
            const char *target = close + 2, *target_end = memchr(target, ')', (size_t)(end - target));
            char label[REPORT_CELL * 2];
            snprintf(label, sizeof label, "%.*s", (int)(close - bracket - 1), bracket + 1);
            snprintf(piece, sizeof piece, "%.*s", (int)(target_end - target), target);
            fputs(image ? "<img src=\"" : "<a href=\"", f), gallery_page_text(f, piece);
            fputs(image ? "\" alt=\"" : "\">", f), gallery_page_text(f, label), fputs(image ? "\">" : "</a>", f);
            text = target_end + 1;
        } else {
            bool escaped = text[0] == '\\' && text + 1 < end && text[1] == '|';
            text += escaped;
            snprintf(piece, sizeof piece, "%c", *text++);
            gallery_page_text(f, piece);
        }
    }
}

/* One markdown table row's cells as <th> or <td>, split at unescaped `|`. */
static void report_html_row(FILE *f, const char *line, const char *cell_tag) {
    fputs("<tr>", f);
    const char *start = line + 1;
    for (const char *c = start; *c && *c != '\n'; c++) {
        if (*c == '\\' && c[1] == '|') {
            c++;
            continue;
        }
        if (*c != '|')
            continue;
        const char *first = start, *last = c;
        while (first < last && *first == ' ')
            first++;
        while (last > first && last[-1] == ' ')
            last--;
        fprintf(f, "<%s>", cell_tag);
        report_html_inline(f, first, (size_t)(last - first));
        fprintf(f, "</%s>", cell_tag);
        start = c + 1;
    }
    fputs("</tr>\n", f);
}

typedef enum report_block { REPORT_NONE, REPORT_PARAGRAPH, REPORT_TABLE, REPORT_LIST } report_block;

static void report_html_close(FILE *f, report_block *block) {
    static const char *const closes[] = {"", "</p>\n", "</table>\n", "</ul>\n"};
    fputs(closes[*block], f);
    *block = REPORT_NONE;
}

/* The markdown index.md writes (headings, paragraphs, tables, lists,
 * pictures on lines of their own) as a page of its own. */
static bool report_write_html(const char *markdown_path, const char *path) {
    char *text = path_read_text(markdown_path, REPORT_MAX_MARKDOWN, NULL);
    FILE *f = text ? report_create(path) : NULL;
    if (!f) {
        free(text);
        return false;
    }
    fputs("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>Shadow techniques: the "
          "results</title>\n<style>body{font-family:sans-serif;max-width:90em;margin:auto;padding:1em}"
          "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:.2em .5em;"
          "text-align:left}th{background:#eee}img{max-width:100%}code{background:#f4f4f4}</style>"
          "</head><body>\n",
          f);
    report_block block = REPORT_NONE;
    int table_row = 0;
    for (char *line = text, *next; *line; line = next) {
        next = line + strcspn(line, "\n");
        size_t length = (size_t)(next - line);
        next += *next == '\n';
        int level = 0;
        while (line[level] == '#')
            level++;
        if (length == 0) {
            report_html_close(f, &block);
        } else if (level > 0 && line[level] == ' ') {
            report_html_close(f, &block);
            char heading[REPORT_CELL];
            snprintf(heading, sizeof heading, "%.*s", (int)(length - (size_t)level - 1), line + level + 1);
            fprintf(f, "<h%d id=\"", level), report_anchor(f, heading), fputs("\">", f);
            report_html_inline(f, heading, strlen(heading)), fprintf(f, "</h%d>\n", level);
        } else if (line[0] == '|') {
            if (block != REPORT_TABLE)
                report_html_close(f, &block), fputs("<table>\n", f), block = REPORT_TABLE, table_row = 0;
            if (strncmp(line, "|---", 4) != 0)
                report_html_row(f, line, table_row++ ? "td" : "th");
        } else if (line[0] == '-' && line[1] == ' ') {
            if (block != REPORT_LIST)
                report_html_close(f, &block), fputs("<ul>\n", f), block = REPORT_LIST;
            fputs("<li>", f), report_html_inline(f, line + 2, length - 2), fputs("</li>\n", f);
        } else {
            if (block != REPORT_PARAGRAPH)
                report_html_close(f, &block), fputs("<p>", f), block = REPORT_PARAGRAPH;
            else
                fputs("\n", f);
            report_html_inline(f, line, length);
        }
    }
    report_html_close(f, &block);
    fputs("</body></html>\n", f);
    free(text);
    return report_close(f, path);
}

/* FILE with the compact table between its markers, written beside it
 * and renamed over it. */
static bool report_refill(const char *readme, const char *compact_path) {
    char *text = path_read_text(readme, REPORT_MAX_MARKDOWN, NULL);
    char *compact = text ? path_read_text(compact_path, REPORT_MAX_MARKDOWN, NULL) : NULL;
    bool ok = compact != NULL;
    char *begin = ok ? strstr(text, "\n" REPORT_BEGIN "\n") : NULL;
    char *end = begin ? strstr(begin, "\n" REPORT_END "\n") : NULL;
    if (ok &&
        (!begin || !end || strstr(begin + 1, "\n" REPORT_BEGIN "\n") || strstr(end + 1, "\n" REPORT_END "\n"))) {
        fprintf(stderr, "%s: expected one line %s, then one line %s\n", readme, REPORT_BEGIN, REPORT_END);
        ok = false;
    }
    char fresh[PATH_MAX];
    snprintf(fresh, sizeof fresh, "%s.new", readme);
    FILE *f = ok ? report_create(fresh) : NULL;
    if (f) {
        size_t head = (size_t)(begin - text) + strlen("\n" REPORT_BEGIN "\n");
        fwrite(text, 1, head, f);
        fprintf(f, "\n%s\n%s", compact, end + 1);
        ok = report_close(f, fresh);
        if (ok && rename(fresh, readme) != 0) {
            fprintf(stderr, "%s: cannot replace with %s: %s\n", readme, fresh, strerror(errno));
            ok = false;
        }
    } else {
        ok = false;
    }
    free(compact);
    free(text);
    return ok;
}

int main(int argc, char **argv) {
    int count = (int)(sizeof report_flags / sizeof *report_flags);
    int status = flags_parse("report", report_flags, count, argc - 1, argv + 1);
    if (status == FLAGS_HELP_ASKED) {
        printf("usage: report [flags]\n"
               "Writes OUT/index.md and index.html: every results table, from the runs of make bench"
               "\nand make stress, stamped with the commit, date, machine, renderer and frame size.\n");
        flags_print_help(stdout, report_flags, count, 2, 0);
        return 0;
    }
    if (status)
        return status;
    report.bench_dir = report.bench_dir ? report.bench_dir : "out/bench";
    report.stress_dir = report.stress_dir ? report.stress_dir : "out/stress";
    report.ruler_dir = report.ruler_dir ? report.ruler_dir : "out/ruler";
    report.out_dir = report.out_dir ? report.out_dir : "out/report";
    bool ok = true;
    for (int r = 0; ok && r < REPORT_RUN_COUNT; r++)
        ok = report_load_run(&report_runs[r]);
    const report_run *required = report_find_run(REPORT_COMPACT_RUN);
    if (ok && !required->present) {
        fprintf(stderr, "%s: missing: the compact table's run (make bench)\n", required->path);
        ok = false;
    }
    char markdown[PATH_MAX], html[PATH_MAX], compact[PATH_MAX];
    snprintf(markdown, sizeof markdown, "%s/index.md", report.out_dir);
    snprintf(html, sizeof html, "%s/index.html", report.out_dir);
    snprintf(compact, sizeof compact, "%s/compact.md", report.out_dir);
    report_stamp stamp = {0};
    if (ok)
        report_make_stamp(&stamp);
    FILE *f = ok && path_make_directories(report.out_dir) ? report_create(compact) : NULL;
    if (f)
        report_write_compact(f, &stamp);
    ok = f && report_close(f, compact) && report_write_markdown(markdown, &stamp) &&
         report_write_html(markdown, html) && (!report.readme || report_refill(report.readme, compact));
    for (int r = 0; r < REPORT_RUN_COUNT; r++)
        csv_free(&report_runs[r].table);
    if (ok)
        printf("%s\n%s\n", markdown, html);
    return ok ? 0 : 1;
}
