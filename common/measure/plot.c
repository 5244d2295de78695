#include "plot.h"

#include <math.h>
#include <stdlib.h>

/* Room beyond the values: a linear axis' top is the largest value times
 * 1 + PLOT_LINEAR_ROOM; a log axis reaches this factor past its extreme
 * values before rounding to a decade (below a zero floor, this factor). */
#define PLOT_LINEAR_ROOM 0.08
#define PLOT_LOG_ROOM 1.2
/* The points' markers: gnuplot's pointsize, and half a marker's width in
 * pixels per unit of it (pngcairo). */
#define PLOT_POINT_SIZE 1.5
#define PLOT_MARKER_HALF_PIXELS 4.5
/* A character's box at a font of P points, in pixels: P times these. */
#define PLOT_CHAR_WIDTH 0.7
#define PLOT_CHAR_HEIGHT 1.4
/* Pixels between a marker and its number, the rings a number may try,
 * and the list's lines, in character heights. */
#define PLOT_LABEL_GAP 2.0
#define PLOT_LABEL_RINGS 8
#define PLOT_LIST_SPACING 1.2
/* The key and the front's list start this far right of the plot area. */
#define PLOT_COLUMN_GAP 0.02
/* The first symbol of gnuplot's filled ones, and their step. */
#define PLOT_FIRST_POINT_TYPE 5
#define PLOT_POINT_TYPE_STEP 2

plot_axis plot_axis_fit(const double *values, int count) {
    double low = INFINITY, high = 0;
    bool zero = false;
    for (int i = 0; i < count; i++) {
        if (values[i] > 0) {
            low = fmin(low, values[i]);
            high = fmax(high, values[i]);
        } else {
            zero = true;
        }
    }
    plot_axis a = {.min = 0, .max = high > 0 ? high * (1 + PLOT_LINEAR_ROOM) : 1};
    if (high > 0 && high / low > PLOT_LOG_SPAN) {
        a.log = true;
        a.max = pow(10, ceil(log10(high * PLOT_LOG_ROOM)));
        if (zero) {
            a.zero_floor = pow(10, floor(log10(low)) - 1);
            a.min = a.zero_floor / PLOT_LOG_ROOM;
        } else {
            a.min = pow(10, floor(log10(low / PLOT_LOG_ROOM)));
        }
    }
    return a;
}

double plot_axis_place(const plot_axis *a, double value) { return a->log && value <= 0 ? a->zero_floor : value; }

/* Where a placed value lies along the axis, from 0 at its start to 1 at
 * its end. */
static double plot_axis_fraction(const plot_axis *a, double placed) {
    if (a->log)
        return (log10(placed) - log10(a->min)) / (log10(a->max) - log10(a->min));
    return (placed - a->min) / (a->max - a->min);
}

void plot_write_quoted(FILE *g, const char *text) {
    fputc('\'', g);
    for (const char *c = text; *c; c++) {
        if (*c == '\'')
            fputc('\'', g); /* gnuplot's single quote within single quotes */
        fputc(*c, g);
    }
    fputc('\'', g);
}

void plot_axis_write(FILE *g, const plot_axis *a, char name, const char *label) {
    fprintf(g, "set %crange [%.17g:%.17g]\n", name, a->min, a->max);
    char text[512];
    if (a->log) {
        /* Each decade a tic, the zero floor's reading "0", and minor tics
         * at 2 to 9 times each decade, from the first above the floor. */
        fprintf(g, "set logscale %c\nset %ctics (", name, name);
        int first = (int)ceil(log10(a->min)), last = (int)floor(log10(a->max));
        if (a->zero_floor > 0) {
            fprintf(g, "'0' %g, ", a->zero_floor);
            first = (int)lround(log10(a->zero_floor)) + 1;
        }
        for (int e = first; e <= last; e++)
            fprintf(g, "%s'%g' %g", e > first ? ", " : "", pow(10, e), pow(10, e));
        for (int e = a->zero_floor > 0 ? first : first - 1; e <= last; e++)
            for (int times = 2; times < 10; times++)
                if (times * pow(10, e) > a->min && times * pow(10, e) < a->max)
                    fprintf(g, ", '' %g 1", times * pow(10, e));
        fprintf(g, ")\n");
        if (a->zero_floor > 0)
            snprintf(text, sizeof text, "%s (log scale; 0 drawn at %g)", label, a->zero_floor);
        else
            snprintf(text, sizeof text, "%s (log scale)", label);
    } else {
        snprintf(text, sizeof text, "%s", label);
    }
    fprintf(g, "set %clabel ", name);
    plot_write_quoted(g, text);
    fputc('\n', g);
}

void plot_write_head(FILE *g, const char *output, const char *title) {
    fprintf(g, "set terminal pngcairo size %d,%d font ',%d' noenhanced\nset output ", PLOT_WIDTH, PLOT_HEIGHT,
            PLOT_FONT_POINTS);
    plot_write_quoted(g, output);
    fprintf(g, "\nset title ");
    plot_write_quoted(g, title);
    fprintf(g,
            "\nset lmargin at screen %g\nset rmargin at screen %g\nset bmargin at screen %g\n"
            "set tmargin at screen %g\nset grid\nset key at screen %g, %g left top Left reverse\n",
            PLOT_AREA_LEFT, PLOT_AREA_RIGHT, PLOT_AREA_BOTTOM, PLOT_AREA_TOP, PLOT_AREA_RIGHT + PLOT_COLUMN_GAP,
            PLOT_AREA_TOP);
}

void plot_label_half_size(int chars, double *half_width, double *half_height) {
    *half_width = chars * PLOT_CHAR_WIDTH * PLOT_LABEL_POINTS / 2;
    *half_height = PLOT_CHAR_HEIGHT * PLOT_LABEL_POINTS / 2;
}

/* An axis-aligned box: centre and half sizes, pixels. */
typedef struct plot_box {
    double x, y, half_width, half_height;
} plot_box;

static bool plot_boxes_overlap(const plot_box *a, const plot_box *b) {
    return fabs(a->x - b->x) < a->half_width + b->half_width && fabs(a->y - b->y) < a->half_height + b->half_height;
}

static bool plot_box_inside_area(const plot_box *b) {
    return b->x - b->half_width >= PLOT_AREA_LEFT * PLOT_WIDTH &&
           b->x + b->half_width <= PLOT_AREA_RIGHT * PLOT_WIDTH &&
           b->y - b->half_height >= PLOT_AREA_BOTTOM * PLOT_HEIGHT &&
           b->y + b->half_height <= PLOT_AREA_TOP * PLOT_HEIGHT;
}

/* A point's marker, pixels from the picture's bottom left. */
static plot_box plot_marker(const plot_point *point, const plot_axis *x, const plot_axis *y) {
    double fx = plot_axis_fraction(x, plot_axis_place(x, point->x));
    double fy = plot_axis_fraction(y, plot_axis_place(y, point->y));
    double half = PLOT_POINT_SIZE * PLOT_MARKER_HALF_PIXELS;
    return (plot_box){PLOT_WIDTH * (PLOT_AREA_LEFT + fx * (PLOT_AREA_RIGHT - PLOT_AREA_LEFT)),
                      PLOT_HEIGHT * (PLOT_AREA_BOTTOM + fy * (PLOT_AREA_TOP - PLOT_AREA_BOTTOM)), half, half};
}

/* The digits of n, from 1. */
static int plot_digits(int n) {
    int digits = 1;
    while (n >= 10)
        n /= 10, digits++;
    return digits;
}

/* Number k's box (from 0, reading k + 1) at its spot, pixels. */
static plot_box plot_number_box(int k, const plot_spot *spot) {
    plot_box box = {spot->x * PLOT_WIDTH, spot->y * PLOT_HEIGHT, 0, 0};
    plot_label_half_size(plot_digits(k + 1), &box.half_width, &box.half_height);
    return box;
}

void plot_pareto_spots(const plot_pareto *p, const plot_axis *x, const plot_axis *y, plot_spot *spots) {
    /* Right, up, left, down, then the diagonals. */
    static const int directions[][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}, {1, 1}, {-1, 1}, {1, -1}, {-1, -1}};
    enum { direction_count = sizeof directions / sizeof *directions };
    for (int k = 0; k < p->front_count; k++) {
        plot_box marker = plot_marker(&p->points[p->front[k]], x, y), box = marker;
        plot_label_half_size(plot_digits(k + 1), &box.half_width, &box.half_height);
        bool found = false;
        for (int ring = 0; ring < PLOT_LABEL_RINGS && !found; ring++) {
            double step = ring * 2 * box.half_height;
            for (int d = 0; d < direction_count && !found; d++) {
                box.x = marker.x + directions[d][0] * (marker.half_width + PLOT_LABEL_GAP + box.half_width + step);
                box.y = marker.y + directions[d][1] * (marker.half_height + PLOT_LABEL_GAP + box.half_height + step);
                found = plot_box_inside_area(&box);
                for (int i = 0; i < p->point_count && found; i++) {
                    plot_box other = plot_marker(&p->points[i], x, y);
                    found = !plot_boxes_overlap(&box, &other);
                }
                for (int i = 0; i < k && found; i++) {
                    plot_box other = plot_number_box(i, &spots[i]);
                    found = !plot_boxes_overlap(&box, &other);
                }
                spots[k].leader = ring > 0;
            }
        }
        if (!found) { /* nowhere free: right of the point */
            box.x = marker.x + marker.half_width + PLOT_LABEL_GAP + box.half_width;
            box.y = marker.y;
            spots[k].leader = false;
        }
        spots[k].x = box.x / PLOT_WIDTH;
        spots[k].y = box.y / PLOT_HEIGHT;
    }
}

bool plot_pareto_write(FILE *g, const plot_pareto *p) {
    double *xs = malloc((size_t)(p->point_count ? p->point_count : 1) * sizeof *xs);
    double *ys = malloc((size_t)(p->point_count ? p->point_count : 1) * sizeof *ys);
    plot_spot *spots = malloc((size_t)(p->front_count ? p->front_count : 1) * sizeof *spots);
    if (!xs || !ys || !spots) {
        fprintf(stderr, "%s: out of memory for a plot of %d points\n", p->ylabel, p->point_count);
        free(xs), free(ys), free(spots);
        return false;
    }
    for (int i = 0; i < p->point_count; i++)
        xs[i] = p->points[i].x, ys[i] = p->points[i].y;
    plot_axis x = plot_axis_fit(xs, p->point_count), y = plot_axis_fit(ys, p->point_count);
    plot_axis_write(g, &x, 'x', p->xlabel);
    plot_axis_write(g, &y, 'y', p->ylabel);
    /* Each series' points, where they are drawn, then the front's. */
    for (int s = 0; s < p->series_count; s++) {
        fprintf(g, "$series%d << EOD\n", s);
        for (int i = 0; i < p->point_count; i++)
            if (p->points[i].series == s)
                fprintf(g, "%.9g %.9g\n", plot_axis_place(&x, xs[i]), plot_axis_place(&y, ys[i]));
        fprintf(g, "EOD\n");
    }
    fprintf(g, "$front << EOD\n");
    for (int k = 0; k < p->front_count; k++)
        fprintf(g, "%.9g %.9g\n", plot_axis_place(&x, xs[p->front[k]]), plot_axis_place(&y, ys[p->front[k]]));
    fprintf(g, "EOD\n");
    /* The front's numbers, on an opaque box over any line they join. */
    plot_pareto_spots(p, &x, &y, spots);
    fprintf(g, "set style textbox opaque noborder\n");
    for (int k = 0; k < p->front_count; k++) {
        const plot_point *point = &p->points[p->front[k]];
        if (spots[k].leader)
            fprintf(g, "set arrow from first %.9g, first %.9g to screen %.6f, %.6f nohead linecolor 'grey50' back\n",
                    plot_axis_place(&x, point->x), plot_axis_place(&y, point->y), spots[k].x, spots[k].y);
        fprintf(g, "set label '%d' at screen %.6f, %.6f center font ',%d' boxed front\n", k + 1, spots[k].x,
                spots[k].y, PLOT_LABEL_POINTS);
    }
    /* What each number is, at the bottom of the column right of the area. */
    double line = PLOT_LIST_SPACING * PLOT_CHAR_HEIGHT * PLOT_LABEL_POINTS / PLOT_HEIGHT;
    double list_x = PLOT_AREA_RIGHT + PLOT_COLUMN_GAP;
    if (p->front_count)
        fprintf(g, "set label 'Pareto front, fastest first:' at screen %.6f, %.6f left font ',%d'\n", list_x,
                PLOT_AREA_BOTTOM + p->front_count * line, PLOT_LABEL_POINTS);
    for (int k = 0; k < p->front_count; k++) {
        char text[256];
        snprintf(text, sizeof text, "%d  %s", k + 1, p->front_names[k]);
        fprintf(g, "set label ");
        plot_write_quoted(g, text);
        fprintf(g, " at screen %.6f, %.6f left font ',%d'\n", list_x,
                PLOT_AREA_BOTTOM + (p->front_count - 1 - k) * line, PLOT_LABEL_POINTS);
    }
    fprintf(g, "plot ");
    for (int s = 0; s < p->series_count; s++) {
        bool any = false;
        for (int i = 0; i < p->point_count && !any; i++)
            any = p->points[i].series == s;
        if (!any)
            continue;
        fprintf(g, "$series%d using 1:2 with points pointsize %g pointtype %d title ", s, PLOT_POINT_SIZE,
                PLOT_FIRST_POINT_TYPE + PLOT_POINT_TYPE_STEP * s);
        plot_write_quoted(g, p->series[s]);
        fprintf(g, ", ");
    }
    fprintf(g, "$front using 1:2 with lines dashtype 2 linecolor 'grey40' title 'Pareto front'\n");
    free(xs), free(ys), free(spots);
    return true;
}
