/* build/report on fixture runs (tests/data/report/): the stamp says the
 * commit, the date (SOURCE_DATE_EPOCH's), the renderer and the frame size
 * of the CSVs; a fixture's figure lands in its technique's row, a run's
 * skips-off twin gives the speed-up; the page is plain HTML; refilling the
 * README's markers keeps what is outside them and twice is once; the
 * ruler's JSON fills its table; a malformed CSV or JSON, a missing run or
 * missing markers stop it with one line naming the file. No GPU: the generator only reads files. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "path.h"
#include "support.h"

#define EXIT_FAILED 1
#define DATA "tests/data/report"
#define OUT "out/test/report"
/* 1970-01-02 00:00 UTC */
#define EPOCH "86400"
/* Every input but the ruler's, and with it. */
#define INPUTS "--bench " DATA "/bench --stress " DATA "/stress --out " OUT
#define RUN_FLAGS INPUTS " --ruler " DATA "/ruler"
#define MAX_TEXT (1 << 20)

static char err[8192];

/* Runs build/report with `flags` at the fixed date; its exit status. */
static int run_report(const char *flags) {
    char command[2048];
    snprintf(command, sizeof command, "SOURCE_DATE_EPOCH=" EPOCH " %s %s >/dev/null", support_program("report"),
             flags);
    return support_run(command, err, sizeof err);
}

static char *read_text(const char *path) {
    char *text = path_read_text(path, MAX_TEXT, NULL);
    assert_non_null(text);
    return text;
}

/* The line of `text` that starts with `start`, into line. */
static void find_line(const char *text, const char *start, char *line, size_t size) {
    const char *at = strstr(text, start);
    assert_non_null(at);
    snprintf(line, size, "%.*s", (int)strcspn(at, "\n"), at);
}

static void test_stamp(void **state) {
    (void)state;
    assert_int_equal(run_report(RUN_FLAGS), 0);
    char *index = read_text(OUT "/index.md");
    char line[1024];
    find_line(index, "Commit ", line, sizeof line);
    assert_non_null(strstr(line, "1970-01-02 00:00 UTC"));
    assert_non_null(strstr(line, "renderer llvmpipe (fixture, 2 cores)"));
    assert_non_null(strstr(line, "frame size 320x180"));
    assert_non_null(strstr(line, "machine "));
    free(index);
}

/* The compact table's shadowmap row: its defaults' CPU ms (the renderer is
 * a software one), ratio, misclassified % and MAE on each scene, and the
 * hidden run's speed-up, its skips-off ms over its skips-on ms; under the
 * table, the noise: the floor's row on each scene, with its interval where
 * the run had one. */
static void test_figures_land_in_their_rows(void **state) {
    (void)state;
    assert_int_equal(run_report(RUN_FLAGS), 0);
    char *compact = read_text(OUT "/compact.md"), line[1024];
    find_line(compact, "| shadowmap |", line, sizeof line);
    assert_string_equal(line,
                        "| shadowmap | 12.35 / 10.00 | 2.47 / 2.50 | 0.0123 / 0.0166 | 0.00123 / 0.00200 | 2.13x |");
    find_line(compact, "| technique |", line, sizeof line);
    assert_non_null(strstr(line, "ms (simple / teapot)"));
    assert_non_null(strstr(line, "skips speed-up, hidden (street)"));
    find_line(compact, "The noise: the unshadowed frame timed against a second copy of itself", line, sizeof line);
    assert_non_null(strstr(line, "confidence where the run had the frames for one): simple 1.000 [0.970, 1.030]; "
                                 "teapot 1.000. A technique is below the floor"));
    char *index = read_text(OUT "/index.md");
    find_line(index, "| simple | --filter pcf5 |", line, sizeof line);
    assert_string_equal(line, "| simple | --filter pcf5 | 20.0000 | 4.000 | 0.0080 | 0.000900 | 0.000300 |");
    /* a run that is not there is named, not guessed */
    assert_non_null(strstr(index, "camera (not run: no " DATA "/bench/camera/results.csv)"));
    assert_non_null(strstr(index, "| shadowmap | 1 | 0 |")); /* the stress summary */
    char *html = read_text(OUT "/index.html");
    assert_non_null(strstr(html, "<td>shadowmap</td>"));
    assert_non_null(strstr(html, "<a href=\"stress/table.md\">"));
    assert_null(strstr(html, "<script"));
    free(html);
    free(index);
    free(compact);
}

/* The psm hard cases' table shows the three warps' defaults, not the
 * map sizes; the ruler's table each scene's JSON, null as "none". */
static void test_hard_cases_and_ruler(void **state) {
    (void)state;
    assert_int_equal(run_report(RUN_FLAGS), 0);
    char *index = read_text(OUT "/index.md"), line[1024];
    find_line(index, "| long_view_behind | --warp uniform |", line, sizeof line);
    assert_string_equal(line, "| long_view_behind | --warp uniform | 0.7700 | 0.020000 | 1.800 |");
    assert_non_null(strstr(index, "| long_view_behind | defaults | 0.0800 |"));
    assert_non_null(strstr(index, "| long_view_behind | --warp lispsm | 0.0910 |"));
    assert_null(strstr(index, "| long_view_behind | --map-size 1024 | 0.1100 |"));
    assert_non_null(strstr(index, "default 256 shadow rays per pixel, compared with the same traced with 4096"));
    find_line(index, "| soft_sun |", line, sizeof line);
    assert_string_equal(line, "| soft_sun | none | 0.00532 | 10423 | 0.000006 | 0.00010 | 0.011 |");
    find_line(index, "| soft_table |", line, sizeof line);
    assert_string_equal(line, "| soft_table | 0.00031 | 0.00542 | 46646 | 0.000050 | 0.00049 | 0.028 |");
    free(index);
}

static void test_readme_refill_is_idempotent(void **state) {
    (void)state;
    char *fixture = read_text(DATA "/readme.md");
    assert_true(path_make_directories(OUT));
    FILE *f = fopen(OUT "/README.md", "w");
    assert_non_null(f);
    fputs(fixture, f);
    assert_int_equal(fclose(f), 0);
    assert_int_equal(run_report(RUN_FLAGS " --readme " OUT "/README.md"), 0);
    char *once = read_text(OUT "/README.md");
    assert_int_equal(run_report(RUN_FLAGS " --readme " OUT "/README.md"), 0);
    char *twice = read_text(OUT "/README.md");
    assert_string_equal(once, twice);
    assert_null(strstr(once, "an old table"));
    char *compact = read_text(OUT "/compact.md");
    char expected[MAX_TEXT / 64];
    snprintf(expected, sizeof expected,
             "# A notebook\n\nText before the figures.\n\n<!-- report:begin -->\n\n%s\n<!-- report:end -->\n\n"
             "Text after the figures.\n",
             compact);
    assert_string_equal(once, expected);
    free(compact);
    free(twice);
    free(once);
    free(fixture);
}

static void test_malformed_csv_is_one_line(void **state) {
    (void)state;
    assert_int_equal(run_report("--bench " DATA "/malformed --out " OUT "-malformed"), EXIT_FAILED);
    assert_int_equal(support_count_lines(err), 1);
    assert_non_null(strstr(err, DATA "/malformed/static/results.csv:4: column mae: expected a number, got 'x'"));
    assert_int_equal(run_report(INPUTS " --ruler " DATA "/ruler-malformed"), EXIT_FAILED);
    assert_int_equal(support_count_lines(err), 1);
    assert_non_null(strstr(err, DATA "/ruler-malformed/soft_table.json: penumbra_mae: expected a number or null"));
}

static void test_missing_input_is_one_line(void **state) {
    (void)state;
    assert_int_equal(run_report("--bench " OUT "-nothing --out " OUT "-nothing"), EXIT_FAILED);
    assert_int_equal(support_count_lines(err), 1);
    assert_non_null(strstr(err, OUT "-nothing/static/results.csv: missing"));
    /* a README without its markers is left as it was */
    assert_true(path_make_directories(OUT));
    FILE *f = fopen(OUT "/unmarked.md", "w");
    assert_non_null(f);
    fputs("# No markers\n", f);
    assert_int_equal(fclose(f), 0);
    assert_int_equal(run_report(RUN_FLAGS " --readme " OUT "/unmarked.md"), EXIT_FAILED);
    assert_int_equal(support_count_lines(err), 1);
    assert_non_null(strstr(err, OUT "/unmarked.md: expected one line <!-- report:begin -->"));
    char *unmarked = read_text(OUT "/unmarked.md");
    assert_string_equal(unmarked, "# No markers\n");
    free(unmarked);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_stamp),
        cmocka_unit_test(test_figures_land_in_their_rows),
        cmocka_unit_test(test_hard_cases_and_ruler),
        cmocka_unit_test(test_readme_refill_is_idempotent),
        cmocka_unit_test(test_malformed_csv_is_one_line),
        cmocka_unit_test(test_missing_input_is_one_line),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
