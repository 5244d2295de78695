/* build/stress: its quick subset (the cases marked quick, near 1e-6 of far
 * among them) passes, with each class's MAE in its table (a reference
 * copied as the technique's dump gives 0 in each class it has, "none" in
 * the penumbra of a hard light), and its verdicts say what happened: a GL
 * error is a gl-error, and fake programs that crash, hang, write a NaN,
 * exit badly or write nothing are each classified as such. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "path.h"
#include "render.h"
#include "shadowdiff.h"
#include "support.h"

#define EXIT_FAILED 1
#define EXIT_USAGE 2
#define MAX_ROWS 256
/* The CSV's columns: scene, technique, config, bound, misclassified, MAE,
 * each class's MAE, compared, verdict, seconds, stderr (the last, which
 * may hold commas). */
#define CSV_CLASS_FIELD 6
#define CSV_VERDICT_FIELD (CSV_CLASS_FIELD + SHADOWDIFF_CLASS_COUNT + 1)
#define CSV_FIELDS (CSV_VERDICT_FIELD + 3)
#define FAKE_DIR "out/test/stress-fake"
#define FAKE_BIN FAKE_DIR "/bin"
/* The fakes' hang is killed after this; its row must not take much longer.
 * The real reference runs under the same limit: long enough for it under
 * the sanitizers on a loaded machine, well short of the hang's sleep. */
#define FAKE_TIMEOUT_S 5
#define FAKE_TIMEOUT_SLACK_S 15

static char err[65536];

typedef struct row {
    char scene[64], technique[32], config[32], verdict[32], seconds[32], line[256];
    char class_mae[SHADOWDIFF_CLASS_COUNT][32];
} row;

static row rows[MAX_ROWS];

/* DIR/table.csv into rows; returns how many. */
static int read_table(const char *dir) {
    char path[1024];
    snprintf(path, sizeof path, "%s/table.csv", dir);
    char *text = path_read_text(path, 1 << 20, NULL);
    assert_non_null(text);
    int count = 0;
    char header[256] = "";
    for (int k = 0; k < SHADOWDIFF_CLASS_COUNT; k++)
        snprintf(header + strlen(header), sizeof header - strlen(header), ",%s_mae", shadowdiff_class_names[k]);
    if (!strstr(text, header))
        fail_msg("%s: no columns %s", path, header + 1);
    char *line = strchr(text, '\n'); /* past the header */
    while (line && line[1] && count < MAX_ROWS) {
        char *start = line + 1, *field[CSV_FIELDS];
        line = strchr(start, '\n');
        if (line)
            *line = '\0';
        for (int f = 0; f < CSV_FIELDS; f++) {
            field[f] = start;
            char *comma = f + 1 < CSV_FIELDS ? strchr(start, ',') : NULL;
            if (comma)
                *comma = '\0';
            start = comma ? comma + 1 : start + strlen(start);
        }
        row *r = &rows[count++];
        snprintf(r->scene, sizeof r->scene, "%s", field[0]);
        snprintf(r->technique, sizeof r->technique, "%s", field[1]);
        snprintf(r->config, sizeof r->config, "%s", field[2]);
        for (int k = 0; k < SHADOWDIFF_CLASS_COUNT; k++)
            snprintf(r->class_mae[k], sizeof r->class_mae[k], "%s", field[CSV_CLASS_FIELD + k]);
        snprintf(r->verdict, sizeof r->verdict, "%s", field[CSV_VERDICT_FIELD]);
        snprintf(r->seconds, sizeof r->seconds, "%s", field[CSV_VERDICT_FIELD + 1]);
        snprintf(r->line, sizeof r->line, "%s", field[CSV_VERDICT_FIELD + 2]);
    }
    free(text);
    return count;
}

static const row *find_row(int count, const char *scene, const char *technique, const char *config) {
    for (int i = 0; i < count; i++)
        if (!strcmp(rows[i].scene, scene) && !strcmp(rows[i].technique, technique) && !strcmp(rows[i].config, config))
            return &rows[i];
    fail_msg("no row %s %s %s", scene, technique, config);
    return NULL;
}

/* Every quick case passes; near 1e-6 of far among them, which the 24-bit
 * depth cannot resolve and reversed depth does (depth.h; refused at load
 * before it). Under the sanitizers (a sweep stride, support.h) the base
 * cases alone, every technique configuration under each kind of light
 * (BASE_MIN_ROWS rows or more): the plain pass runs the others. */
#define QUICK_MIN_ROWS 50
#define BASE_MIN_ROWS 30
static void test_quick_cases_pass(void **state) {
    (void)state;
    char command[2048];
    bool base_only = support_sweep_stride() > 1;
    snprintf(command, sizeof command, "%s --quick --out out/test/stress%s", support_program("stress"),
             base_only ? " --only 'base_*'" : "");
    int status = support_run(command, err, sizeof err);
    int count = read_table("out/test/stress");
    for (int i = 0; i < count; i++) {
        const row *r = &rows[i];
        if (strcmp(r->verdict, "pass") != 0)
            print_message("    %s %s %s: %s %s\n", r->scene, r->technique, r->config, r->verdict, r->line);
        assert_string_equal(r->verdict, "pass");
        /* Every case's light is hard: no penumbra, and the other classes
         * measured (the reference's own row has no figures). */
        bool reference = strcmp(r->technique, "raytrace") == 0;
        assert_string_equal(r->class_mae[SHADOWDIFF_CLASS_PENUMBRA], reference ? "" : SHADOWDIFF_NO_FIGURE);
        assert_true(reference || r->class_mae[SHADOWDIFF_CLASS_LIT][0] != '\0');
    }
    assert_int_equal(status, 0);
    assert_true(count >= (base_only ? BASE_MIN_ROWS : QUICK_MIN_ROWS));
    if (!base_only)
        assert_non_null(find_row(count, "near_far_1e6_near_spot", "volumes", "default"));
}

/* A real technique's GL error (the test hook of render.h) is a gl-error,
 * not a crash or a refusal; the reference, which has no GL, passes. */
static void test_gl_error_is_classified(void **state) {
    (void)state;
    char command[2048];
    snprintf(command, sizeof command, RENDER_INJECT_GL_ERROR_ENV "=1 %s --only base_point --size 64x36 --out %s",
             support_program("stress"), "out/test/stress-gl-error");
    assert_int_equal(support_run(command, err, sizeof err), EXIT_FAILED);
    int count = read_table("out/test/stress-gl-error");
    assert_int_equal(count, 11);
    for (int i = 0; i < count; i++)
        assert_string_equal(rows[i].verdict, strcmp(rows[i].technique, "raytrace") ? "gl-error" : "pass");
}

static void write_script(const char *name, const char *body) {
    char path[1024];
    snprintf(path, sizeof path, FAKE_BIN "/%s", name);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fprintf(f, "#!/bin/sh\n%s", body);
    assert_int_equal(fclose(f), 0);
    assert_int_equal(chmod(path, 0755), 0);
}

static void link_program(const char *name) {
    char real[PATH_MAX], path[1024], build[1024];
    const char *dir = getenv("BUILD");
    snprintf(build, sizeof build, "%s/%s", dir && *dir ? dir : "build", name);
    snprintf(path, sizeof path, FAKE_BIN "/%s", name);
    assert_non_null(realpath(build, real));
    unlink(path);
    assert_int_equal(symlink(real, path), 0);
}

/* Fake techniques beside the real reference and shadowdiff, one verdict
 * per configuration (each fake reads its flags):
 *   planar     kills itself with SIGSEGV                     crash
 *   shadowmap  default: hangs                                timeout
 *              --filter: the reference's dump, copied        pass
 *              --depth: the same with a NaN id               nan
 *   psm        default: one line naming the scene, exit 1    refused
 *              --warp: two lines, exit 1                     error
 *   cascades   exits 0 having dumped nothing                 error
 *   volumes    --mode: exit status 200                       crash
 *              otherwise: exits 0 having dumped nothing      error
 * The run itself (stress, not the preloaded sanitizer runtime: the fakes
 * are shell scripts) must survive them all and reap every child. */
static void test_fake_programs_are_classified(void **state) {
    (void)state;
    assert_true(path_make_directories(FAKE_BIN));
    link_program("raytrace");
    link_program("shadowdiff");
    write_script("planar", "kill -SEGV $$\n");
    write_script(
        "shadowmap",
        "mode=hang\n"
        "while [ $# -gt 0 ]; do case $1 in --dump) dump=$2;; --filter) mode=copy;; --depth) mode=nan;; esac;"
        " shift; done\n"
        "[ $mode = hang ] && sleep 30\n"
        "cp \"$dump\"/../reference/*.pfm \"$dump\"/../reference/meta.json \"$dump\"/../reference/color.png "
        "\"$dump\"/\n"
        "if [ $mode = nan ]; then\n"
        "  header=$(head -n 3 \"$dump/ids.pfm\" | wc -c)\n"
        "  printf '\\000\\000\\300\\177' | dd of=\"$dump/ids.pfm\" bs=1 seek=$header conv=notrunc 2>/dev/null\n"
        "fi\n");
    write_script("psm", "while [ $# -gt 0 ]; do case $1 in --scene) scene=$2;; --warp) two=1;; esac; shift; done\n"
                        "echo \"$scene: refused by a fake\" >&2\n"
                        "[ -n \"$two\" ] && echo \"and a second line\" >&2\n"
                        "exit 1\n");
    write_script("cascades", "exit 0\n");
    write_script("volumes", "case \"$*\" in *--mode*) exit 200;; esac\nexit 0\n");
    char command[2048], build[1024];
    const char *dir = getenv("BUILD");
    snprintf(build, sizeof build, "%s/stress", dir && *dir ? dir : "build");
    snprintf(command, sizeof command, "%s --bin " FAKE_BIN " --only base_spot --timeout %d --out " FAKE_DIR, build,
             FAKE_TIMEOUT_S);
    assert_int_equal(support_run(command, err, sizeof err), EXIT_FAILED);
    int count = read_table(FAKE_DIR);
    static const char *const expect[][3] = {
        {"raytrace", "reference", "pass"},
        {"planar", "default", "crash"},
        {"shadowmap", "default", "timeout"},
        {"shadowmap", "filter-none", "pass"},
        {"shadowmap", "depth-32f", "nan"},
        {"psm", "default", "refused"},
        {"psm", "lispsm", "error"},
        {"cascades", "default", "error"},
        {"volumes", "default", "error"},
        {"volumes", "zfail", "crash"},
        {"volumes", "gpu-silhouette", "error"},
    };
    assert_int_equal(count, sizeof expect / sizeof *expect);
    for (size_t i = 0; i < sizeof expect / sizeof *expect; i++) {
        const row *r = find_row(count, "base_spot", expect[i][0], expect[i][1]);
        if (strcmp(r->verdict, expect[i][2]) != 0)
            print_message("    %s %s: %s, expected %s (%s)\n", r->technique, r->config, r->verdict, expect[i][2],
                          r->line);
        assert_string_equal(r->verdict, expect[i][2]);
    }
    assert_true(atof(find_row(count, "base_spot", "shadowmap", "default")->seconds) < FAKE_TIMEOUT_SLACK_S);
    /* The copy of the reference: off by nothing in every class the spot's
     * hard truth has (outside its cone the umbra), none in the penumbra. */
    const row *copy = find_row(count, "base_spot", "shadowmap", "filter-none");
    static const char *const copied[SHADOWDIFF_CLASS_COUNT] = {[SHADOWDIFF_CLASS_UMBRA] = "0.00000",
                                                               [SHADOWDIFF_CLASS_PENUMBRA] = SHADOWDIFF_NO_FIGURE,
                                                               [SHADOWDIFF_CLASS_LIT] = "0.00000"};
    for (int k = 0; k < SHADOWDIFF_CLASS_COUNT; k++)
        assert_string_equal(copy->class_mae[k], copied[k]);
    assert_non_null(strstr(find_row(count, "base_spot", "planar", "default")->line, "signal"));
}

static void test_command_line(void **state) {
    (void)state;
    char command[2048];
    snprintf(command, sizeof command, "%s --only no_such_case", support_program("stress"));
    assert_int_equal(support_run(command, err, sizeof err), EXIT_USAGE);
    assert_int_equal(support_count_lines(err), 1);
    assert_non_null(strstr(err, "no_such_case"));
    snprintf(command, sizeof command, "%s -j 0", support_program("stress"));
    assert_int_equal(support_run(command, err, sizeof err), EXIT_USAGE);
    assert_int_equal(support_count_lines(err), 1);
    assert_non_null(strstr(err, "--jobs"));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_quick_cases_pass),
        cmocka_unit_test(test_gl_error_is_classified),
        cmocka_unit_test(test_fake_programs_are_classified),
        cmocka_unit_test(test_command_line),
    };
    return cmocka_run_group_tests_name("stress", tests, NULL, NULL);
}
