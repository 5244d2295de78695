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

#define MAIN_EXIT_RUNTIME 1

#define MAIN_MAX_GRAZING_DEGREES 45

typedef struct main_options {
    const char *program;
    const char *dirs[2]; /* REF_DIR TEST_DIR */
    int dir_count;
    const char *heatmap_path, *receiver;
    int grazing_degrees;
    bool json;
} main_options;

static void main_usage(const char *program, const flags_param *params, int count) {
    printf("usage: %s REF_DIR TEST_DIR [flags]\n"
           "Compares the shadows of the dump TEST_DIR with the reference dump REF_DIR (both\n"
           "written by --dump: same scene, camera, size and light).\n",
           program);
    flags_print_help(stdout, params, count, 2, 0);
    printf("A pixel is compared where both see a surface at the same depth (0.1 %%) and the\n"
           "reference surface faces the light; lit means visibility >= 0.5. Percentages\n"
           "are of the compared pixels; MAE is the mean |visibility difference| over them.\n");
}

/* Returns 0 to run, FLAGS_HELP_ASKED after --help, or an exit status. */
static int main_parse_flags(int argc, char **argv, main_options *o) {
    const flags_param params[] = {
        {NULL, NULL, 0, FLAGS_LIST, .items = o->dirs, .count = &o->dir_count, .min = 2, .max = 2,
         .what = "two dump directories: REF_DIR TEST_DIR"},
        {"heatmap",
         "picture of the verdicts: red false shadow (lit in the\nreference, shadowed in the test), blue false lit (the\n"
         "other way round), grey by the reference visibility where\nthey agree, dark grey not compared, black no surface",
         0, FLAGS_STRING, .text = &o->heatmap_path, .value_name = "PATH.png"},
        {"json", "one JSON object on stdout instead of text", 0, FLAGS_SWITCH, .on = &o->json},
        {"receiver", "only pixels of that object", 0, FLAGS_STRING, .text = &o->receiver, .value_name = "NAME"},
        {"grazing",
         "also leave out surfaces within DEG degrees (0.." FLAGS_TEXT(MAIN_MAX_GRAZING_DEGREES) ") of\n"
         "edge-on to the light (0): for sweeps of light directions",
         0, FLAGS_INT, .integer = &o->grazing_degrees, .min = 0, .max = MAIN_MAX_GRAZING_DEGREES,
         .what = "whole degrees", .value_name = "DEG"},
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
    printf("mean abs error   %.4f\n", r->mean_abs_error);
}

static bool main_print_json(const shadowdiff_result *r) {
    cJSON *root = cJSON_CreateObject();
    bool ok = root && cJSON_AddNumberToObject(root, "compared", (double)r->compared) &&
              cJSON_AddNumberToObject(root, "false_shadow", (double)r->false_shadow) &&
              cJSON_AddNumberToObject(root, "false_lit", (double)r->false_lit) &&
              cJSON_AddNumberToObject(root, "false_shadow_percent", r->false_shadow_percent) &&
              cJSON_AddNumberToObject(root, "false_lit_percent", r->false_lit_percent) &&
              cJSON_AddNumberToObject(root, "misclassified_percent", r->misclassified_percent) &&
              cJSON_AddNumberToObject(root, "mean_abs_error", r->mean_abs_error);
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

/* Everything after the flags: both dumps are read, compared, reported. */
static bool main_run(const main_options *o) {
    dump_frame reference, test;
    if (!dump_read(&reference, o->dirs[0]))
        return false;
    if (!dump_read(&test, o->dirs[1])) {
        dump_frame_free(&reference);
        return false;
    }
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
        fprintf(stderr, "%s: out of memory for a %dx%d heat map\n", o->heatmap_path, reference.width, reference.height);
    ok = ok && shadowdiff_compare(&reference, &test, &settings, &result, heatmap);
    ok = ok && (!heatmap || image_write_png(o->heatmap_path, reference.width, reference.height, heatmap));
    if (ok && o->json)
        ok = main_print_json(&result);
    else if (ok)
        main_print_text(&result, &reference, o->receiver);
    free(heatmap);
    dump_frame_free(&reference);
    dump_frame_free(&test);
    return ok;
}

int main(int argc, char **argv) {
    main_options options = {.program = flags_program_name(argv[0])};
    int status = main_parse_flags(argc, argv, &options);
    if (status)
        return status == FLAGS_HELP_ASKED ? 0 : status;
    return main_run(&options) ? 0 : MAIN_EXIT_RUNTIME;
}
