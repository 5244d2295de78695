/* The benchmark's plots' scripts (plot.h), without gnuplot: an axis whose
 * figures span decades is logarithmic and one that does not is linear; a 0
 * on a log axis is drawn at the stated floor, its tic reading "0"; the
 * front's numbers overlap neither each other nor the plot area's edge,
 * however crowded the points, and the list names every front point. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plot.h"

/* The misclassified % of a standard scene's defaults: the floor's few
 * percent down to volumes' thousandths. */
static const double decades[] = {4.1264, 0.6023, 0.0268, 0.0018};
/* Figures within a decade of each other. */
static const double close[] = {4.1264, 0.6102, 0.6023};

/* The script of the axis `a` as plot_axis_write writes it, into `out`. */
static void axis_script(const plot_axis *a, char *out, size_t size) {
    FILE *g = fmemopen(out, size, "w");
    assert_non_null(g);
    plot_axis_write(g, a, 'y', "misclassified %");
    fclose(g);
}

static void test_axis_spanning_decades_is_logarithmic(void **state) {
    (void)state;
    char script[4096];
    plot_axis a = plot_axis_fit(decades, sizeof decades / sizeof *decades);
    assert_true(a.log);
    assert_true(a.min <= decades[3] && a.max >= decades[0]);
    assert_true(a.zero_floor == 0);
    axis_script(&a, script, sizeof script);
    assert_non_null(strstr(script, "set logscale y\n"));
    assert_non_null(strstr(script, "'0.01' "));
    assert_non_null(strstr(script, "set ylabel 'misclassified % (log scale)'"));
    /* Within a decade: linear from 0, as before. */
    a = plot_axis_fit(close, sizeof close / sizeof *close);
    assert_false(a.log);
    assert_true(a.min == 0 && a.max >= close[0]);
    axis_script(&a, script, sizeof script);
    assert_null(strstr(script, "logscale"));
}

/* A 0 among figures that span decades: drawn a decade below the smallest
 * figure's decade, where the tic reads "0", and the label says where. On
 * a linear axis a 0 is where it is. */
static void test_zero_on_a_log_axis_is_drawn_at_a_stated_floor(void **state) {
    (void)state;
    const double with_zero[] = {4.1264, 0.0268, 0.0018, 0};
    plot_axis a = plot_axis_fit(with_zero, sizeof with_zero / sizeof *with_zero);
    assert_true(a.log);
    assert_true(fabs(a.zero_floor - 1e-4) < 1e-12);
    assert_true(a.min < a.zero_floor);
    assert_true(plot_axis_place(&a, 0) == a.zero_floor);
    assert_true(plot_axis_place(&a, 0.0018) == 0.0018);
    char script[4096];
    axis_script(&a, script, sizeof script);
    assert_non_null(strstr(script, "set ytics ('0' 0.0001, '0.001' 0.001, "));
    assert_non_null(strstr(script, "(log scale; 0 drawn at 0.0001)"));
    const double linear_zero[] = {0.6, 0.5, 0};
    a = plot_axis_fit(linear_zero, sizeof linear_zero / sizeof *linear_zero);
    assert_false(a.log);
    assert_true(plot_axis_place(&a, 0) == 0);
}

/* A crowded sweep: many configurations about one time and figure, and a
 * front of every other one of them, fastest first. */
#define CROWD 60
#define CROWD_FRONT 30

/* Two numbers' boxes overlap. */
static bool numbers_overlap(int i, const plot_spot *a, int k, const plot_spot *b) {
    double aw, ah, bw, bh;
    plot_label_half_size(i + 1 >= 10 ? 2 : 1, &aw, &ah);
    plot_label_half_size(k + 1 >= 10 ? 2 : 1, &bw, &bh);
    return fabs(a->x - b->x) * PLOT_WIDTH < aw + bw && fabs(a->y - b->y) * PLOT_HEIGHT < ah + bh;
}

static void test_front_numbers_do_not_overlap(void **state) {
    (void)state;
    static plot_point points[CROWD];
    static int front[CROWD_FRONT];
    static char names[CROWD_FRONT][32];
    static const char *front_names[CROWD_FRONT];
    static const char *const series[] = {"shadowmap", "volumes"};
    for (int i = 0; i < CROWD; i++)
        points[i] = (plot_point){5 + 0.01 * i, 0.02 + 0.0001 * i, i % 2};
    for (int k = 0; k < CROWD_FRONT; k++) {
        front[k] = 2 * k;
        snprintf(names[k], sizeof names[k], "shadowmap: config %d", k);
        front_names[k] = names[k];
    }
    const plot_pareto p = {.xlabel = "ms",
                           .ylabel = "misclassified %",
                           .series = series,
                           .series_count = 2,
                           .points = points,
                           .point_count = CROWD,
                           .front = front,
                           .front_names = front_names,
                           .front_count = CROWD_FRONT};
    double xs[CROWD], ys[CROWD];
    for (int i = 0; i < CROWD; i++)
        xs[i] = points[i].x, ys[i] = points[i].y;
    plot_axis x = plot_axis_fit(xs, CROWD), y = plot_axis_fit(ys, CROWD);
    plot_spot spots[CROWD_FRONT];
    plot_pareto_spots(&p, &x, &y, spots);
    for (int k = 0; k < CROWD_FRONT; k++) {
        double w, h;
        plot_label_half_size(k + 1 >= 10 ? 2 : 1, &w, &h);
        assert_true(spots[k].x * PLOT_WIDTH - w >= PLOT_AREA_LEFT * PLOT_WIDTH);
        assert_true(spots[k].x * PLOT_WIDTH + w <= PLOT_AREA_RIGHT * PLOT_WIDTH);
        assert_true(spots[k].y * PLOT_HEIGHT - h >= PLOT_AREA_BOTTOM * PLOT_HEIGHT);
        assert_true(spots[k].y * PLOT_HEIGHT + h <= PLOT_AREA_TOP * PLOT_HEIGHT);
        for (int i = 0; i < k; i++)
            if (numbers_overlap(i, &spots[i], k, &spots[k]))
                fail_msg("numbers %d and %d overlap", i + 1, k + 1);
    }
    /* The script: every front point numbered and listed. */
    static char script[1 << 16];
    FILE *g = fmemopen(script, sizeof script, "w");
    assert_non_null(g);
    assert_true(plot_pareto_write(g, &p));
    fclose(g);
    for (int k = 0; k < CROWD_FRONT; k++) {
        char number[64], listed[96];
        snprintf(number, sizeof number, "set label '%d' at screen ", k + 1);
        snprintf(listed, sizeof listed, "set label '%d  %.31s' at screen ", k + 1, names[k]);
        assert_non_null(strstr(script, number));
        assert_non_null(strstr(script, listed));
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_axis_spanning_decades_is_logarithmic),
        cmocka_unit_test(test_zero_on_a_log_axis_is_drawn_at_a_stated_floor),
        cmocka_unit_test(test_front_numbers_do_not_overlap),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
