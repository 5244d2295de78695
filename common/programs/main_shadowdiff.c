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

typedef struct main_options {
    const char *program;
    const char *reference_dir, *test_dir;
    const char *heatmap_path, *receiver;
    int grazing_degrees;
    bool json;
} main_options;

static void main_usage(const char *program) {
    printf("usage: %s REF_DIR TEST_DIR [flags]\n"
           "Compares the shadows of the dump TEST_DIR with the reference dump REF_DIR (both\n"
           "written by --dump: same scene, camera, size and light).\n"
           "  --heatmap PATH.png  picture of the verdicts: red false shadow (lit in the\n"
           "                      reference, shadowed in the test), blue false lit (the\n"
           "                      other way round), grey by the reference visibility where\n"
           "                      they agree, dark grey not compared, black no surface\n"
           "  --json              one JSON object on stdout instead of text\n"
           "  --receiver NAME     only pixels of that object\n"
           "  --grazing DEG       also leave out surfaces within DEG degrees (0..45) of\n"
           "                      edge-on to the light (0): for sweeps of light directions\n"
           "  --help              this text\n"
           "A pixel is compared where both see a surface at the same depth (0.1 %%) and the\n"
           "reference surface faces the light; lit means visibility >= 0.5. Percentages\n"
           "are of the compared pixels; MAE is the mean |visibility difference| over them.\n",
           program);
}

/* Returns 0 to run, -1 after --help, or an exit status. */
static int main_parse_flags(int argc, char **argv, main_options *o) {
    static const char *const with_value[] = {"--heatmap", "--receiver", "--grazing", NULL};
    flags_cursor c = {.program = o->program, .argc = argc, .argv = argv, .next = 1, .with_value = with_value};
    const char *name, *value;
    int status, positional = 0;
    while ((status = flags_next(&c, &name, &value)) == 1) {
        if (name[0] != '-') {
            if (positional == 2)
                return flags_usage_error(o->program, "expected two dump directories, got also", name);
            *(positional++ == 0 ? &o->reference_dir : &o->test_dir) = name;
            continue;
        }
        if (strcmp(name, "--help") == 0 || strcmp(name, "-h") == 0) {
            main_usage(o->program);
            return -1;
        } else if (strcmp(name, "--heatmap") == 0) {
            o->heatmap_path = value;
        } else if (strcmp(name, "--receiver") == 0) {
            o->receiver = value;
        } else if (strcmp(name, "--grazing") == 0) {
            if (!flags_parse_int(value, 0, 45, &o->grazing_degrees))
                return flags_usage_error(o->program, "--grazing takes whole degrees 0..45, got", value);
        } else if (strcmp(name, "--json") == 0) {
            o->json = true;
        } else {
            return flags_usage_error(o->program, "unknown flag", name);
        }
    }
    if (status)
        return status;
    if (positional < 2)
        return flags_usage_error(o->program, "expected two dump directories: REF_DIR TEST_DIR", NULL);
    return 0;
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
    if (!dump_read(&reference, o->reference_dir))
        return false;
    if (!dump_read(&test, o->test_dir)) {
        dump_frame_free(&reference);
        return false;
    }
    size_t heatmap_bytes = (size_t)reference.width * (size_t)reference.height * 4;
    unsigned char *heatmap = o->heatmap_path ? malloc(heatmap_bytes) : NULL;
    const shadowdiff_settings settings = {
        .receiver = o->receiver,
        .reference_name = o->reference_dir,
        .test_name = o->test_dir,
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
    const char *slash = strrchr(argv[0], '/');
    main_options options = {.program = slash ? slash + 1 : argv[0]};
    int status = main_parse_flags(argc, argv, &options);
    if (status)
        return status < 0 ? 0 : status;
    return main_run(&options) ? 0 : MAIN_EXIT_RUNTIME;
}
