#include "results_csv.h"

#include <stdio.h>

#define RESULTS_CSV_NAME_MAX 64

static const char *const results_csv_fixed_names[RESULTS_CSV_CLASSES] = {
    [RESULTS_CSV_SCENE] = "scene",
    [RESULTS_CSV_TECHNIQUE] = "technique",
    [RESULTS_CSV_PARAMETERS] = "parameters",
    [RESULTS_CSV_GPU_MS] = "gpu_ms_median",
    [RESULTS_CSV_GPU_MS_P90] = "gpu_ms_p90",
    [RESULTS_CSV_CPU_MS] = "cpu_ms_median",
    [RESULTS_CSV_CPU_MS_P90] = "cpu_ms_p90",
    [RESULTS_CSV_RATIO] = "ratio_to_unshadowed",
    [RESULTS_CSV_FALSE_SHADOW] = "false_shadow_percent",
    [RESULTS_CSV_FALSE_LIT] = "false_lit_percent",
    [RESULTS_CSV_MISCLASSIFIED] = "misclassified_percent",
    [RESULTS_CSV_MAE] = "mae",
    [RESULTS_CSV_COMPARED] = "compared_pixels",
    [RESULTS_CSV_RENDERER] = "renderer",
    [RESULTS_CSV_MOTION] = "motion",
    [RESULTS_CSV_SKIPS] = "skips",
    [RESULTS_CSV_FLOOR_MS] = "floor_ms_median",
    [RESULTS_CSV_RATIO_LOW] = "ratio_low",
    [RESULTS_CSV_RATIO_HIGH] = "ratio_high",
    [RESULTS_CSV_SHIMMER] = "shimmer_percent",
};

const char *results_csv_name(results_csv_column column) {
    static char class_names[2 * SHADOWDIFF_CLASS_COUNT][RESULTS_CSV_NAME_MAX];
    if (column < RESULTS_CSV_CLASSES)
        return results_csv_fixed_names[column];
    if (column == RESULTS_CSV_FRAME_SIZE)
        return "frame_size";
    if (column == RESULTS_CSV_TRACED_PERCENT)
        return "traced_percent";
    if (column == RESULTS_CSV_RAYS)
        return "rays_per_frame";
    int i = column - RESULTS_CSV_CLASSES;
    snprintf(class_names[i], sizeof class_names[i], "%s_%s", shadowdiff_class_names[i / 2], i % 2 ? "mae" : "pixels");
    return class_names[i];
}

void results_csv_write_header(FILE *f) {
    for (int c = 0; c < RESULTS_CSV_COUNT; c++)
        fprintf(f, "%s%s", c ? "," : "", results_csv_name((results_csv_column)c));
    fputc('\n', f);
}
