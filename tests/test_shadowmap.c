/* Shadow maps against the ray-traced reference, with shadowdiff's fixed
 * rules; each test prints the figures it measured. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "dump.h"
#include "shadowdiff.h"
#include "support.h"

#define SIZE "640x360"
#define STANDARD_MAX_MISCLASSIFIED_PERCENT 0.5

static char err[16384];

static void dump_scene(const char *program, const char *scene, const char *flags, const char *dir) {
    char command[2048];
    snprintf(command, sizeof command, "%s --size " SIZE " --scene %s %s --dump %s", support_program(program), scene,
             flags, dir);
    assert_int_equal(support_run(command, err, sizeof err), 0);
}

/* Reference and shadow map of `scene`, compared over every object. */
static shadowdiff_result measure(const char *scene, const char *flags, const char *name) {
    char reference_dir[256], test_dir[256];
    snprintf(reference_dir, sizeof reference_dir, "out/test/shadowmap/%s_reference", name);
    snprintf(test_dir, sizeof test_dir, "out/test/shadowmap/%s", name);
    dump_scene("raytrace", scene, "", reference_dir);
    dump_scene("shadowmap", scene, flags, test_dir);
    dump_frame reference, test;
    assert_true(dump_read(&reference, reference_dir));
    assert_true(dump_read(&test, test_dir));
    shadowdiff_result r;
    assert_true(shadowdiff_compare(&reference, &test, NULL, &r, NULL));
    fprintf(stderr, "    %-26s %s: %ld compared, false-shadow %.4f %% (%ld), false-lit %.4f %% (%ld), "
                    "misclassified %.4f %%\n",
            name, flags, r.compared, r.false_shadow_percent, r.false_shadow, r.false_lit_percent, r.false_lit,
            r.misclassified_percent);
    dump_frame_free(&reference);
    dump_frame_free(&test);
    return r;
}

/* Spot (simple), point with a cube map (bunny), directional (teapot). */
static void test_standard_scenes_within_bound(void **state) {
    (void)state;
    static const char *const scenes[] = {"simple", "bunny", "teapot"};
    for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++) {
        char path[256];
        snprintf(path, sizeof path, "assets/scenes/%s.json", scenes[i]);
        shadowdiff_result r = measure(path, "", scenes[i]);
        assert_true(r.compared > 50000);
        assert_true(r.misclassified_percent <= STANDARD_MAX_MISCLASSIFIED_PERCENT);
    }
}

/* A ground that casts onto itself and nothing else, lit from `elevation`
 * degrees above the horizon: every shadow on it is acne. */
static void write_acne_scene(const char *path, const char *light_type, float elevation) {
    float e = elevation * 3.14159265f / 180, c = cosf(e), s = sinf(e);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    if (light_type[0] == 'd')
        fprintf(f, "{\"camera\": {\"position\": [0, 7, 12], \"target\": [0, 0, 0]},\n"
                   " \"lights\": [{\"type\": \"directional\", \"direction\": [%g, %g, %g]}],\n",
                -c * 0.8f, -s, -c * 0.6f);
    else
        fprintf(f, "{\"camera\": {\"position\": [0, 7, 12], \"target\": [0, 0, 0]},\n"
                   " \"lights\": [{\"type\": \"point\", \"position\": [%g, %g, %g]}],\n",
                c * 8, s * 8 + 0.01f, c * 6);
    fprintf(f, " \"objects\": [{\"name\": \"ground\", \"mesh\": {\"kind\": \"plane\", \"size\": [20, 20]}}]}\n");
    fclose(f);
}

static void test_no_acne_at_any_elevation(void **state) {
    (void)state;
    static const float elevations[] = {5, 10, 20, 30, 45, 60, 75, 90};
    static const char *const types[] = {"directional", "point"};
    assert_int_equal(system("mkdir -p out/test/shadowmap"), 0);
    for (size_t t = 0; t < 2; t++) {
        for (size_t i = 0; i < sizeof elevations / sizeof *elevations; i++) {
            char path[256], name[64];
            snprintf(name, sizeof name, "acne_%s_%g", types[t], elevations[i]);
            snprintf(path, sizeof path, "out/test/shadowmap/%s.json", name);
            write_acne_scene(path, types[t], elevations[i]);
            shadowdiff_result r = measure(path, "", name);
            assert_true(r.compared > 10000);
            assert_int_equal(r.false_shadow, 0);
        }
    }
}

/* The sweep can see acne: with every bias off it is there. */
static void test_acne_without_bias(void **state) {
    (void)state;
    write_acne_scene("out/test/shadowmap/acne_unbiased.json", "directional", 30);
    shadowdiff_result r = measure("out/test/shadowmap/acne_unbiased.json",
                                  "--no-constant-bias --no-slope-bias", "acne_unbiased");
    assert_true(r.false_shadow_percent > 1);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_standard_scenes_within_bound),
        cmocka_unit_test(test_no_acne_at_any_elevation),
        cmocka_unit_test(test_acne_without_bias),
    };
    return cmocka_run_group_tests_name("shadow maps against the reference", tests, NULL, NULL);
}
