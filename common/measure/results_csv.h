/* results_csv: the columns of the bench's results.csv, named once for
 * build/bench, which writes it, and build/report, which reads it.
 *
 * A row holds the columns in this enum's order: the fixed ones, then each
 * shadowdiff class's pixel count and MAE ("umbra_pixels", "umbra_mae", ...,
 * in shadowdiff_class order), then frame_size, traced_percent and
 * rays_per_frame.
 */
#ifndef RESULTS_CSV_H
#define RESULTS_CSV_H

#include <stdio.h>

#include "shadowdiff.h"

/* The confidence of ratio_low and ratio_high, the interval of a row's
 * ratio (median_interval.h), two-sided. A run has hundreds of rows, and a
 * technique with nothing to draw costs the floor's frame by design, so
 * bench's floor check (a row fails when its whole interval is under 1)
 * may fire on noise in at most one such row in 1 / (1 - confidence). */
#define RESULTS_CSV_RATIO_CONFIDENCE 0.999

typedef enum results_csv_column {
    RESULTS_CSV_SCENE,
    RESULTS_CSV_TECHNIQUE,
    RESULTS_CSV_PARAMETERS,
    RESULTS_CSV_GPU_MS,
    RESULTS_CSV_GPU_MS_P90,
    RESULTS_CSV_CPU_MS,
    RESULTS_CSV_CPU_MS_P90,
    RESULTS_CSV_RATIO,
    RESULTS_CSV_FALSE_SHADOW,
    RESULTS_CSV_FALSE_LIT,
    RESULTS_CSV_MISCLASSIFIED,
    RESULTS_CSV_MAE,
    RESULTS_CSV_COMPARED,
    RESULTS_CSV_RENDERER,
    RESULTS_CSV_MOTION,
    RESULTS_CSV_SKIPS,
    RESULTS_CSV_FLOOR_MS,
    RESULTS_CSV_RATIO_LOW,  /* the ratio's interval (RESULTS_CSV_RATIO_CONFIDENCE): */
    RESULTS_CSV_RATIO_HIGH, /* "-" where the row has too few frames for one */
    RESULTS_CSV_SHIMMER,
    RESULTS_CSV_CLASSES, /* class c's pixels: + 2c; its MAE: + 2c + 1 */
    RESULTS_CSV_FRAME_SIZE = RESULTS_CSV_CLASSES + 2 * SHADOWDIFF_CLASS_COUNT,
    /* A technique that casts shadow rays (technique.rays), over the error
     * frames: the lights traced per pixel (percent), the rays per frame;
     * "-" for the others. */
    RESULTS_CSV_TRACED_PERCENT,
    RESULTS_CSV_RAYS,
    RESULTS_CSV_COUNT
} results_csv_column;
/* Class c's (shadowdiff_class) MAE column. */
#define RESULTS_CSV_CLASS_MAE(c) ((results_csv_column)(RESULTS_CSV_CLASSES + 2 * (c) + 1))

/* The column's name in the header row. */
const char *results_csv_name(results_csv_column column);
/* The header row, with its newline. */
void results_csv_write_header(FILE *f);

#endif
