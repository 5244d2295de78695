/* Smoke test of the benchmark (make bench QUICK=1): it runs end to end and
 * its outputs exist and are well formed. Nothing about speed is asserted:
 * speed is for `make bench` to show, not for a test to guess. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "support.h"

#define OUT "out/test/bench"
#define CSV_COLUMNS 15

static const char *const scenes[] = {"simple", "bunny", "teapot", "long_view"};
static char err[65536];

static int run_bench(void **state) {
    (void)state;
    char command[1024];
    snprintf(command, sizeof command, "rm -rf " OUT " && %s --quick --out " OUT, support_program("bench"));
    return support_run(command, err, sizeof err);
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

static void test_csv_has_every_configuration(void **state) {
    (void)state;
    char *text = read_file(OUT "/results.csv");
    char *rest = text, *line = strtok_r(rest, "\n", &rest);
    assert_string_equal(line, "scene,technique,parameters,gpu_ms_median,gpu_ms_p90,cpu_ms_median,cpu_ms_p90,"
                              "ratio_to_unshadowed,false_shadow_percent,false_lit_percent,misclassified_percent,"
                              "mae,compared_pixels,renderer,skips");
    int rows = 0, planar_rows = 0, floor_rows = 0;
    while ((line = strtok_r(rest, "\n", &rest))) {
        char *fields[CSV_COLUMNS + 1];
        assert_int_equal(csv_fields(line, fields, CSV_COLUMNS + 1), CSV_COLUMNS);
        for (int c = 3; c < 13; c++) {
            char *end;
            double v = strtod(fields[c], &end);
            assert_true(end != fields[c] && *end == '\0' && isfinite(v) && v >= 0);
        }
        assert_true(atof(fields[3]) > 0);    /* a frame takes time */
        assert_true(atol(fields[12]) > 1000); /* pixels were compared */
        assert_string_equal(fields[14], "on"); /* skips are on by default */
        planar_rows += strcmp(fields[1], "planar") == 0;
        floor_rows += strcmp(fields[1], "unshadowed") == 0;
        rows++;
    }
    int scene_count = (int)(sizeof scenes / sizeof *scenes);
    assert_int_equal(floor_rows, scene_count);
    assert_true(planar_rows >= scene_count * 2);
    assert_true(rows >= floor_rows + planar_rows);
}

static void test_report_has_a_table_front_and_comparison_per_scene(void **state) {
    (void)state;
    char *text = read_file(OUT "/report.md");
    for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++) {
        char heading[64];
        snprintf(heading, sizeof heading, "\n## %s\n", scenes[i]);
        char *section = strstr(text, heading);
        assert_non_null(section);
        char *next = strstr(section + 1, "\n## "), saved = next ? *next : 0;
        if (next) /* look at this scene's section only */
            *next = '\0';
        assert_non_null(strstr(section, "| technique | parameters |"));
        assert_non_null(strstr(section, "| yes |"));
        assert_non_null(strstr(section, "\nshadowmap defaults against textbook depth bias: misclassified "));
        assert_non_null(strstr(section, "\nshadowmap defaults against textbook polygon offset: misclassified "));
        if (next)
            *next = saved;
    }
}

static void test_plots_are_images(void **state) {
    (void)state;
    for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++) {
        char path[256];
        int w, h;
        snprintf(path, sizeof path, OUT "/pareto_%s.png", scenes[i]);
        unsigned char *pixels = image_read_png(path, &w, &h);
        assert_non_null(pixels);
        assert_true(w >= 640 && h >= 400);
        free(pixels);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_csv_has_every_configuration),
        cmocka_unit_test(test_report_has_a_table_front_and_comparison_per_scene),
        cmocka_unit_test(test_plots_are_images),
    };
    return cmocka_run_group_tests_name("benchmark smoke test", tests, run_bench, NULL);
}
