/* Accuracy against the ray-traced reference, with shadowdiff's fixed
 * rules. Each test prints the figures it measured. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "dump.h"
#include "image.h"
#include "shadowdiff.h"
#include "support.h"

/* Planar shadows are exact on their plane: only pixels whose centre lies
 * within float rounding of a shadow edge may disagree. */
#define PLANAR_MAX_MISCLASSIFIED_PERCENT 0.05

static void dump_scene(const char *program, const char *scene, const char *flags, const char *dir) {
    assert_int_equal(support_dump(program, scene, flags, dir), 0);
}

static void dump_program(const char *program, const char *flags, const char *dir) {
    dump_scene(program, "assets/scenes/simple.json", flags, dir);
}

static shadowdiff_result compare_on_ground(const char *reference_dir, const char *test_dir) {
    dump_frame reference, test;
    assert_true(dump_read(&reference, reference_dir));
    assert_true(dump_read(&test, test_dir));
    const shadowdiff_settings settings = {.receiver = "ground"};
    shadowdiff_result r;
    assert_true(shadowdiff_compare(&reference, &test, &settings, &r, NULL));
    /* The geometry pass sees the ground where the ray tracer does: nearly
     * every ground pixel facing the light is compared. */
    long ground_pixels = 0;
    for (long i = 0; i < (long)reference.width * reference.height; i++)
        ground_pixels += reference.ids[i] == 0 && reference.visibility[i] >= 0;
    fprintf(stderr,
            "    %s vs %s, ground: %ld compared of %ld ground pixels; false-shadow %.4f %%, "
            "false-lit %.4f %%, misclassified %.4f %%, MAE %.5f\n",
            test_dir, reference_dir, r.compared, ground_pixels, r.false_shadow_percent, r.false_lit_percent,
            r.misclassified_percent, r.mean_abs_error);
    assert_true(r.compared > ground_pixels / 2);
    dump_frame_free(&reference);
    dump_frame_free(&test);
    return r;
}

static int make_reference(void **state) {
    (void)state;
    dump_program("raytrace", "", "out/test/accuracy/reference");
    return 0;
}

static void test_planar_matches_reference_on_ground(void **state) {
    (void)state;
    dump_program("planar", "--backend egl", "out/test/accuracy/planar");
    shadowdiff_result r = compare_on_ground("out/test/accuracy/reference", "out/test/accuracy/planar");
    assert_true(r.misclassified_percent <= PLANAR_MAX_MISCLASSIFIED_PERCENT);
}

/* The bound bites: z-fighting without polygon offset leaves lit speckles
 * inside the shadows. */
static void test_planar_without_offset_exceeds_bound(void **state) {
    (void)state;
    dump_program("planar", "--backend egl --no-offset", "out/test/accuracy/planar_no_offset");
    shadowdiff_result r = compare_on_ground("out/test/accuracy/reference", "out/test/accuracy/planar_no_offset");
    assert_true(r.misclassified_percent > PLANAR_MAX_MISCLASSIFIED_PERCENT);
    assert_true(r.false_lit > 0);
}

/* The ground's colour in `scene`, planar against the reference: all but
 * PLANAR_MAX_MISCLASSIFIED_PERCENT of its pixels within the screenshot
 * tolerance. The two dumps are handed back for more checks. */
static void check_ground_colour(const char *scene, const char *name, dump_frame *reference, dump_frame *test) {
    char reference_dir[256], test_dir[256], path[300];
    snprintf(reference_dir, sizeof reference_dir, "out/test/accuracy/%s_reference", name);
    snprintf(test_dir, sizeof test_dir, "out/test/accuracy/%s_planar", name);
    dump_scene("raytrace", scene, "", reference_dir);
    dump_scene("planar", scene, "--backend egl", test_dir);
    int w, h, tw, th;
    assert_true(dump_read(reference, reference_dir));
    assert_true(dump_read(test, test_dir));
    snprintf(path, sizeof path, "%s/color.png", reference_dir);
    unsigned char *ref_rgb = image_read_png(path, &w, &h);
    snprintf(path, sizeof path, "%s/color.png", test_dir);
    unsigned char *test_rgb = image_read_png(path, &tw, &th);
    assert_non_null(ref_rgb);
    assert_non_null(test_rgb);
    assert_true(w == tw && h == th && w == reference->width);
    long ground = 0, differ = 0;
    for (long i = 0; i < (long)w * h; i++) {
        if (reference->ids[i] != 0 || test->ids[i] != 0)
            continue;
        ground++;
        int worst = 0;
        for (int c = 0; c < 3; c++)
            worst = abs(ref_rgb[i * 4 + c] - test_rgb[i * 4 + c]) > worst
                        ? abs(ref_rgb[i * 4 + c] - test_rgb[i * 4 + c])
                        : worst;
        differ += worst > SUPPORT_TOLERANCE;
    }
    fprintf(stderr, "    %s, ground colour: %ld of %ld pixels differ by more than %d/255 (%.4f %%)\n", name, differ,
            ground, SUPPORT_TOLERANCE, 100.0 * differ / ground);
    assert_true(ground > w * h / 4);
    assert_true(differ <= ground * PLANAR_MAX_MISCLASSIFIED_PERCENT / 100);
    free(ref_rgb);
    free(test_rgb);
}

/* Several lights, one bright enough to saturate 8 bits: the ground's
 * colour, not only its visibility, must be the reference's. A shadowed
 * pixel is the picture without that light, whatever the others add. */
static void test_planar_colour_with_three_lights(void **state) {
    (void)state;
    dump_frame reference, test;
    check_ground_colour("tests/data/planar_three_lights.json", "three", &reference, &test);
    dump_frame_free(&reference);
    dump_frame_free(&test);
}

/* Lights with a range (the point light's reaches the ground out to 4.5
 * units from below it, the spot's cuts its cone at 2.5): the colour
 * follows the same window in the shaders and the reference, and light 0's
 * visibility is 0 beyond its range in both dumps, lit inside it. */
static void test_light_range_matches_reference(void **state) {
    (void)state;
    dump_frame reference, test;
    check_ground_colour("tests/data/range_lights.json", "range", &reference, &test);
    const float light[3] = {3, 6, 1}, range = 7.5f;
    long beyond = 0, beyond_lit = 0, inside_lit = 0;
    for (long i = 0; i < (long)reference.width * reference.height; i++) {
        if (reference.ids[i] != 0 || test.ids[i] != 0)
            continue;
        float d = 0;
        for (int k = 0; k < 3; k++)
            d += (reference.position[i * 3 + k] - light[k]) * (reference.position[i * 3 + k] - light[k]);
        if (sqrtf(d) > range * (1 + 1e-3f)) {
            beyond++;
            beyond_lit += reference.visibility[i] > 0 || test.visibility[i] > 0;
        } else {
            inside_lit += reference.visibility[i] > 0 && test.visibility[i] > 0;
        }
    }
    fprintf(stderr, "    range: %ld ground pixels beyond light 0's range, %ld of them lit; %ld lit inside\n", beyond,
            beyond_lit, inside_lit);
    assert_true(beyond > 0);
    assert_int_equal(beyond_lit, 0);
    assert_true(inside_lit > 0);
    dump_frame_free(&reference);
    dump_frame_free(&test);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_planar_matches_reference_on_ground),
        cmocka_unit_test(test_planar_without_offset_exceeds_bound),
        cmocka_unit_test(test_planar_colour_with_three_lights),
        cmocka_unit_test(test_light_range_matches_reference),
    };
    return cmocka_run_group_tests_name("accuracy against the reference", tests, make_reference, NULL);
}
