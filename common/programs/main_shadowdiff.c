/* main of build/shadowdiff: a technique's dump against the reference's;
 * the rules are in shadowdiff.h. */
#include <cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dump.h"
#include "flags.h"
#include "image.h"
#include "shadowdiff.h"

/* Exit statuses, besides 0 and FLAGS_EXIT_USAGE (2), for scripts: each
 * says what went wrong without parsing stderr (main_usage lists them). */
#define MAIN_EXIT_RUNTIME 1
#define MAIN_EXIT_OVER_MAX 3
#define MAIN_EXIT_NOTHING_COMPARED 4
#define MAIN_EXIT_NOT_FINITE 5

#define MAIN_MAX_GRAZING_DEGREES 45
/* The text report's MAEs: mean abs error's and each class's. */
#define MAIN_MAE_DECIMALS 4
/* --max-misclassified's value until it is given: 0 is a real limit (no
 * misclassified pixel at all), so "not given" needs a value of its own. */
#define MAIN_NO_MAX_MISCLASSIFIED (-1.0f)

typedef struct main_options {
    const char *program;
    const char *dirs[2]; /* REF_DIR TEST_DIR */
    int dir_count;
    const char *previous[2]; /* --previous PREV_REF_DIR PREV_TEST_DIR */
    int previous_count;
    const char *heatmap_path, *receiver;
    int grazing_degrees;
    float max_misclassified; /* percent; MAIN_NO_MAX_MISCLASSIFIED: no limit */
    bool json;
} main_options;

static void main_usage(const char *program, const flags_param *params, int count) {
    printf("usage: %s REF_DIR TEST_DIR [flags] [--previous PREV_REF_DIR PREV_TEST_DIR]\n"
           "Compares the shadows of the dump TEST_DIR with the reference dump REF_DIR (both\n"
           "written by --dump: same scene, camera, size and light).\n",
           program);
    flags_print_help(stdout, params, count, 2, 0);
    printf("A pixel is compared where both see a surface at the same depth (0.1 %%) and the\n"
           "reference surface faces the light; lit means visibility >= 0.5. Percentages\n"
           "are of the compared pixels; MAE is the mean |visibility difference| over them.\n"
           "The compared pixels are also split by the reference's visibility v: umbra\n"
           "(v <= 1/32), lit (v >= 31/32) and penumbra (between, only under an area light);\n"
           "each class's MAE is over its pixels (umbra: leaks; lit: acne, darkening;\n"
           "penumbra: the soft shadow's drawing), \"none\" (JSON null) where it has none.\n"
           "JSON keys: umbra_mae, penumbra_mae, lit_mae, umbra_pixels, penumbra_pixels,\n"
           "lit_pixels, beside the others.\n"
           "Shimmer (--previous): each compared pixel is followed, by the reference's world\n"
           "position and the previous frame's camera, to a compared pixel of the previous\n"
           "frame on the same object within 1 %% of its distance (else it is not followed:\n"
           "disoccluded); shimmer %% is the share of followed pixels whose test decision\n"
           "changed where the reference's did not.\n"
           "Exit status: 0 compared; 1 a dump unreadable or the two inconsistent (size,\n"
           "light, objects; with --previous also camera, and the frames' size and objects),\n"
           "an unknown receiver, the heat map unwritable; 2 a bad\n"
           "command line; 3 misclassified over --max-misclassified (the figures are\n"
           "printed); 4 nothing compared (no figure: 0 %% would look perfect; with\n"
           "--previous also nothing followed); 5 a dump\n"
           "holds NaN or infinity where it is read (no figure).\n");
}

/* Returns 0 to run, FLAGS_HELP_ASKED after --help, or an exit status. */
static int main_parse_flags(int argc, char **argv, main_options *o) {
    const flags_param params[] = {
        {NULL, NULL, 0, FLAGS_LIST, .items = o->dirs, .count = &o->dir_count, .min = 2, .max = 2,
         .what = "two dump directories: REF_DIR TEST_DIR"},
        {"heatmap",
         "picture of the verdicts: red false shadow (lit in\nthe reference, shadowed in the test), blue false lit\n"
         "(the other way round), grey by the reference\nvisibility where they agree, dark grey not compared,\n"
         "black no surface",
         0, FLAGS_STRING, .text = &o->heatmap_path, .extension = ".png", .value_name = "PATH.png"},
        {"json", "one JSON object on stdout instead of text", 0, FLAGS_SWITCH, .on = &o->json},
        {"receiver", "only pixels of that object", 0, FLAGS_STRING, .text = &o->receiver, .value_name = "NAME"},
        {"grazing",
         "also leave out surfaces within DEG degrees\n(0.." FLAGS_TEXT(
             MAIN_MAX_GRAZING_DEGREES) ") of "
                                       "edge-on to the light (0): for\nsweeps of light directions",
         0, FLAGS_INT, .integer = &o->grazing_degrees, .min = 0, .max = MAIN_MAX_GRAZING_DEGREES,
         .what = "whole degrees", .value_name = "DEG"},
        {"max-misclassified", "exit with status 3 when misclassified is over P\npercent (0..100), after the report",
         0, FLAGS_NUMBER, .number = &o->max_misclassified, .min = 0, .max = 100, .value_name = "P"},
        {"previous",
         "also the shimmer: the dumps of the frame before\n(reference, then test), whose shadow decisions\n"
         "REF_DIR and TEST_DIR's are followed from",
         0, FLAGS_LIST, .items = o->previous, .count = &o->previous_count, .min = 2, .max = 2,
         .what = "two dump directories: PREV_REF_DIR PREV_TEST_DIR", .value_name = "PREV_REF_DIR PREV_TEST_DIR"},
        {.name = "help", .help = "this text", .kind = FLAGS_HELP},
    };
    int count = (int)(sizeof params / sizeof *params);
    int status = flags_parse(o->program, params, count, argc - 1, argv + 1);
    if (status == FLAGS_HELP_ASKED)
        main_usage(o->program, params, count);
    return status;
}

static void main_print_text(const shadowdiff_result *r, const dump_frame *reference, const char *receiver) {
    printf("compared pixels  %ld of %ld%s%s\n", r->compared, (long)reference->width * reference->height,
           receiver ? " on " : "", receiver ? receiver : "");
    printf("false shadow     %.3f %% (%ld: lit in the reference, shadowed in the test)\n", r->false_shadow_percent,
           r->false_shadow);
    printf("false lit        %.3f %% (%ld: shadowed in the reference, lit in the test)\n", r->false_lit_percent,
           r->false_lit);
    printf("misclassified    %.3f %%\n", r->misclassified_percent);
    printf("mean abs error   %.*f\n", MAIN_MAE_DECIMALS, r->mean_abs_error);
    /* What each class's error is, in the order of shadowdiff_class. */
    static const char *const meaning[SHADOWDIFF_CLASS_COUNT] = {
        [SHADOWDIFF_CLASS_UMBRA] = "light leaking into the reference's full shadow",
        [SHADOWDIFF_CLASS_PENUMBRA] = "how the reference's soft shadow is drawn",
        [SHADOWDIFF_CLASS_LIT] = "acne and darkening where the reference is fully lit",
    };
    for (int c = 0; c < SHADOWDIFF_CLASS_COUNT; c++) {
        char label[32], mae[32];
        snprintf(label, sizeof label, "%s MAE", shadowdiff_class_names[c]);
        printf("%-16s %s (%ld pixels: %s)\n", label,
               shadowdiff_class_mae_text(r, (shadowdiff_class)c, MAIN_MAE_DECIMALS, mae, sizeof mae),
               r->class_pixels[c], meaning[c]);
    }
    if (r->coloured)
        printf("channel MAE      %.*f %.*f %.*f (red, green, blue: the light translucent casters colour)\n",
               MAIN_MAE_DECIMALS, r->channel_mae[0], MAIN_MAE_DECIMALS, r->channel_mae[1], MAIN_MAE_DECIMALS,
               r->channel_mae[2]);
}

/* Each class's "CLASS_mae" (null where it has no pixel) and
 * "CLASS_pixels"; false when out of memory. */
static bool main_add_class_json(cJSON *root, const shadowdiff_result *r) {
    for (int c = 0; c < SHADOWDIFF_CLASS_COUNT; c++) {
        char mae[32], pixels[32];
        snprintf(mae, sizeof mae, "%s_mae", shadowdiff_class_names[c]);
        snprintf(pixels, sizeof pixels, "%s_pixels", shadowdiff_class_names[c]);
        bool added = r->class_pixels[c] > 0 ? cJSON_AddNumberToObject(root, mae, r->class_mae[c]) != NULL
                                            : cJSON_AddNullToObject(root, mae) != NULL;
        if (!added || !cJSON_AddNumberToObject(root, pixels, (double)r->class_pixels[c]))
            return false;
    }
    return true;
}

static void main_print_shimmer_text(const shadowdiff_shimmer_result *r) {
    printf("shimmer          %.3f %% (%ld of %ld followed pixels: the test's decision changed, the "
           "reference's did not)\n",
           r->shimmer_percent, r->shimmered, r->followed);
    printf("truth changed    %.3f %% (%ld: the reference's decision changed)\n", r->truth_changed_percent,
           r->truth_changed);
}

/* shimmer may be NULL (no --previous). */
static bool main_print_json(const shadowdiff_result *r, const shadowdiff_shimmer_result *shimmer) {
    cJSON *root = cJSON_CreateObject();
    bool ok = root &&
              (!shimmer || (cJSON_AddNumberToObject(root, "followed", (double)shimmer->followed) &&
                            cJSON_AddNumberToObject(root, "shimmered", (double)shimmer->shimmered) &&
                            cJSON_AddNumberToObject(root, "truth_changed", (double)shimmer->truth_changed) &&
                            cJSON_AddNumberToObject(root, "shimmer_percent", shimmer->shimmer_percent) &&
                            cJSON_AddNumberToObject(root, "truth_changed_percent", shimmer->truth_changed_percent)));
    ok = ok && cJSON_AddNumberToObject(root, "compared", (double)r->compared) &&
         cJSON_AddNumberToObject(root, "false_shadow", (double)r->false_shadow) &&
         cJSON_AddNumberToObject(root, "false_lit", (double)r->false_lit) &&
         cJSON_AddNumberToObject(root, "false_shadow_percent", r->false_shadow_percent) &&
         cJSON_AddNumberToObject(root, "false_lit_percent", r->false_lit_percent) &&
         cJSON_AddNumberToObject(root, "misclassified_percent", r->misclassified_percent) &&
         cJSON_AddNumberToObject(root, "mean_abs_error", r->mean_abs_error) && main_add_class_json(root, r);
    /* "channel_mae": [red, green, blue] where both dumps are coloured. */
    if (ok && r->coloured) {
        cJSON *channels = cJSON_CreateDoubleArray(r->channel_mae, 3);
        ok = channels && cJSON_AddItemToObject(root, "channel_mae", channels);
    }
    char *text = ok ? cJSON_PrintUnformatted(root) : NULL;
    cJSON_Delete(root);
    if (!text) {
        fprintf(stderr, "shadowdiff: out of memory for the JSON output\n");
        return false;
    }
    printf("%s\n", text);
    free(text);
    return true;
}

/* The exit status of a comparison that gave no figure. */
static int main_problem_status(shadowdiff_problem problem) {
    switch (problem) {
    case SHADOWDIFF_PROBLEM_NOTHING_COMPARED: return MAIN_EXIT_NOTHING_COMPARED;
    case SHADOWDIFF_PROBLEM_NOT_FINITE: return MAIN_EXIT_NOT_FINITE;
    case SHADOWDIFF_PROBLEM_NONE:
    case SHADOWDIFF_PROBLEM_MISMATCH: break;
    }
    return MAIN_EXIT_RUNTIME;
}

/* 0 or MAIN_EXIT_OVER_MAX after saying so: the report is out already. */
static int main_check_max(const main_options *o, const shadowdiff_result *r) {
    if (o->max_misclassified == MAIN_NO_MAX_MISCLASSIFIED || r->misclassified_percent <= o->max_misclassified)
        return 0;
    fprintf(stderr, "shadowdiff: %s: misclassified %.3f %% is over --max-misclassified %g %%\n", o->dirs[1],
            r->misclassified_percent, o->max_misclassified);
    return MAIN_EXIT_OVER_MAX;
}

/* Reads the count dumps of `dirs` into `frames`; false (none kept) if one
 * is unreadable. */
static bool main_read_dumps(const char *const *dirs, int count, dump_frame *frames) {
    for (int i = 0; i < count; i++) {
        if (!dump_read(&frames[i], dirs[i])) {
            while (i-- > 0)
                dump_frame_free(&frames[i]);
            return false;
        }
    }
    return true;
}

/* --previous: the shimmer from the previous dumps to the current ones;
 * 0 or the exit status of a shimmer that gave no figure. */
static int main_shimmer(const main_options *o, const dump_frame *reference, const dump_frame *test,
                        const shadowdiff_settings *settings, shadowdiff_shimmer_result *out) {
    dump_frame previous[2];
    if (!main_read_dumps(o->previous, 2, previous))
        return MAIN_EXIT_RUNTIME;
    shadowdiff_settings s = *settings;
    s.previous_reference_name = o->previous[0];
    s.previous_test_name = o->previous[1];
    int status = shadowdiff_shimmer(&previous[0], &previous[1], reference, test, &s, out)
                     ? 0
                     : main_problem_status(out->problem);
    dump_frame_free(&previous[0]);
    dump_frame_free(&previous[1]);
    return status;
}

/* Everything after the flags: the dumps are read, compared, reported.
 * Returns the exit status. */
static int main_run(const main_options *o) {
    dump_frame frames[2];
    if (!main_read_dumps(o->dirs, 2, frames))
        return MAIN_EXIT_RUNTIME;
    dump_frame reference = frames[0], test = frames[1];
    size_t heatmap_bytes = (size_t)reference.width * (size_t)reference.height * 4;
    unsigned char *heatmap = o->heatmap_path ? malloc(heatmap_bytes) : NULL;
    const shadowdiff_settings settings = {
        .receiver = o->receiver,
        .reference_name = o->dirs[0],
        .test_name = o->dirs[1],
        .grazing_degrees = o->grazing_degrees,
    };
    shadowdiff_result result;
    bool ok = !o->heatmap_path || heatmap;
    if (!ok)
        fprintf(stderr, "%s: out of memory for a %dx%d heat map\n", o->heatmap_path, reference.width,
                reference.height);
    int status = ok ? 0 : MAIN_EXIT_RUNTIME;
    if (ok && !shadowdiff_compare(&reference, &test, &settings, &result, heatmap))
        status = main_problem_status(result.problem);
    shadowdiff_shimmer_result shimmer;
    bool shimmering = o->previous_count > 0;
    if (!status && shimmering)
        status = main_shimmer(o, &reference, &test, &settings, &shimmer);
    if (!status && heatmap && !image_write_png(o->heatmap_path, reference.width, reference.height, heatmap))
        status = MAIN_EXIT_RUNTIME;
    if (!status && o->json && !main_print_json(&result, shimmering ? &shimmer : NULL))
        status = MAIN_EXIT_RUNTIME;
    else if (!status && !o->json)
        main_print_text(&result, &reference, o->receiver);
    if (!status && !o->json && shimmering)
        main_print_shimmer_text(&shimmer);
    if (!status)
        status = main_check_max(o, &result);
    free(heatmap);
    dump_frame_free(&reference);
    dump_frame_free(&test);
    return status;
}

int main(int argc, char **argv) {
    main_options options = {.program = flags_program_name(argv[0]), .max_misclassified = MAIN_NO_MAX_MISCLASSIFIED};
    int status = main_parse_flags(argc, argv, &options);
    if (status)
        return status == FLAGS_HELP_ASKED ? 0 : status;
    return main_run(&options);
}
