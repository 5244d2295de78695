/* plot: the benchmark's gnuplot scripts (build/bench's pareto_*.png and
 * scaling.png), no GL.
 *
 * Axes: an axis is linear from 0, or logarithmic where its positive values
 * span more than a factor of PLOT_LOG_SPAN, over whole decades about them,
 * so that figures decades apart stay apart. A 0 has no place on a log axis:
 * it is drawn at the axis' zero floor, a decade below the smallest
 * positive value's decade, where the axis' tic reads "0" and its label
 * says so.
 *
 * Labels: a Pareto plot numbers the front's points (1 the fastest) and
 * lists beside the plot what each number is, instead of a label at every
 * point. Each number sits beside its point where its box, estimated from
 * the font's size, overlaps no point's marker, no other number and
 * nothing outside the plot area: the first free spot on rings of growing
 * distance about the point, joined to it by a thin line beyond the first
 * ring. The plot area is fixed in the picture (PLOT_AREA_*), so a value
 * lands where the script says it does.
 */
#ifndef PLOT_H
#define PLOT_H

#include <stdbool.h>
#include <stdio.h>

/* An axis whose positive values span more than this factor is
 * logarithmic. */
#define PLOT_LOG_SPAN 10.0
/* The picture, pixels, and its text, points. */
#define PLOT_WIDTH 1200
#define PLOT_HEIGHT 720
#define PLOT_FONT_POINTS 11
#define PLOT_LABEL_POINTS 9
/* The plot area in fractions of the picture; the key and the front's list
 * are to its right. */
#define PLOT_AREA_LEFT 0.08
#define PLOT_AREA_RIGHT 0.64
#define PLOT_AREA_BOTTOM 0.10
#define PLOT_AREA_TOP 0.90

typedef struct plot_axis {
    bool log;
    double min, max;   /* the range shown */
    double zero_floor; /* log with a 0 among the values: where a 0 is drawn; else 0 */
} plot_axis;

/* The axis for `count` values, none negative. */
plot_axis plot_axis_fit(const double *values, int count);
/* Where `value` is drawn on the axis: itself, or a 0 at the zero floor. */
double plot_axis_place(const plot_axis *a, double value);
/* The axis' scale, range, tics and label ('x' or 'y'); the label says
 * "log scale" and where a 0 is drawn. */
void plot_axis_write(FILE *g, const plot_axis *a, char name, const char *label);

/* The script's head: the picture (PLOT_WIDTH x PLOT_HEIGHT, written to
 * `output`), the title, the plot area, the grid and the key to the area's
 * right. */
void plot_write_head(FILE *g, const char *output, const char *title);
/* `text` as a gnuplot string in single quotes. */
void plot_write_quoted(FILE *g, const char *text);

typedef struct plot_point {
    double x, y;
    int series;
} plot_point;

/* Time against an error figure, a series (technique) per symbol. */
typedef struct plot_pareto {
    const char *xlabel, *ylabel;
    const char *const *series; /* the key's names, series_count of them */
    int series_count;
    const plot_point *points;
    int point_count;
    const int *front; /* the front's points (indices), fastest first */
    const char *const *front_names;
    int front_count;
} plot_pareto;

/* A label's place, in fractions of the picture (its centre). */
typedef struct plot_spot {
    double x, y;
    bool leader; /* away from its point: a line joins them */
} plot_spot;

/* The front's numbers' places (front_count of them, in `spots`). */
void plot_pareto_spots(const plot_pareto *p, const plot_axis *x, const plot_axis *y, plot_spot *spots);
/* The script after its head (plot_write_head), its points in it; false
 * after a line on stderr. */
bool plot_pareto_write(FILE *g, const plot_pareto *p);

/* A number's box about a spot, in pixels: half its width and height for
 * `chars` characters at PLOT_LABEL_POINTS. */
void plot_label_half_size(int chars, double *half_width, double *half_height);

#endif
