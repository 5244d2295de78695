/* Tests of common/measure/shadowdiff.c and build/shadowdiff on synthetic dumps
 * whose answer is known: which pixels are compared, the counts, the heat
 * map, the classes (umbra, penumbra, lit) and their errors on wrong
 * pictures, the consistency checks, the comparisons that give no figure
 * (nothing compared, NaN or infinity), --max-misclassified, and the dump
 * files' round trip. Run from the repository root. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dump.h"
#include "image.h"
#include "shadowdiff.h"
#include "support.h"

#define EXIT_RUNTIME 1
#define EXIT_USAGE 2
#define EXIT_OVER_MAX 3
#define EXIT_NOTHING_COMPARED 4
#define EXIT_NOT_FINITE 5
#define SIZE 8
#define PIXELS (SIZE * SIZE)
#define GROUND 0
#define BOX 1
#define DEPTH 10.0f
#define DIR "out/test/shadowdiff"
/* build/shadowdiff's text report: compared, false shadow, false lit,
 * misclassified, MAE, then a line per class; --previous adds two. */
#define TEXT_LINES (5 + SHADOWDIFF_CLASS_COUNT)
#define SHIMMER_TEXT_LINES (TEXT_LINES + 2)

static const scene_light point_light = {.type = SCENE_LIGHT_POINT, .position = {0, 10, 0}};
/* Straight down: the dump's light is (0, 1, 0, 0). */
static const scene_light sun = {.type = SCENE_LIGHT_DIRECTIONAL, .direction = {0, -1, 0}};

static char err[16384];

static void set_vec3(float *array, size_t i, float x, float y, float z) {
    memcpy(array + 3 * i, (float[3]){x, y, z}, sizeof(float[3]));
}

/* Objects "ground" and "box" lit by `light`; every pixel sees the ground
 * (plane y = 0, pixel (x, y) at (x, 0, y)) at depth 10, facing the light
 * (above it), lit. */
static void make_frame(dump_frame *d, int width, int height, scene_light light) {
    scene_object objects[2] = {{.name = "ground"}, {.name = "box"}};
    scene s = {.lights = {light}, .light_count = 1, .objects = objects, .object_count = 2};
    assert_true(dump_frame_create(d, width, height, &s, 0));
    for (int y = 0; y < height; y++) {
        for (int x = 0; x < width; x++) {
            size_t i = (size_t)y * (size_t)width + (size_t)x;
            d->ids[i] = GROUND;
            d->depth[i] = DEPTH;
            d->visibility[i] = 1;
            set_vec3(d->normal, i, 0, 1, 0);
            set_vec3(d->position, i, (float)x, 0, (float)y);
        }
    }
}

static void make_pair(dump_frame *reference, dump_frame *test, scene_light light) {
    make_frame(reference, SIZE, SIZE, light);
    make_frame(test, SIZE, SIZE, light);
}

static void free_pair(dump_frame *reference, dump_frame *test) {
    dump_frame_free(reference);
    dump_frame_free(test);
}

static void set_visibility(dump_frame *reference, dump_frame *test, size_t i, float r, float t) {
    reference->visibility[i] = r;
    test->visibility[i] = t;
}

static void set_no_surface(dump_frame *d, size_t i) { d->ids[i] = d->depth[i] = d->visibility[i] = -1; }

/* 5 false shadows and 3 false lit among 64 compared pixels; the others
 * agree, lit or shadowed, some at the threshold. */
static void set_known_verdicts(dump_frame *reference, dump_frame *test) {
    for (size_t i = 0; i < 4; i++)
        set_visibility(reference, test, i, 1, 0);
    set_visibility(reference, test, 4, 0.5f, 0.49f);
    for (size_t i = 10; i < 12; i++)
        set_visibility(reference, test, i, 0, 1);
    set_visibility(reference, test, 12, 0.49f, 0.5f);
    for (size_t i = 20; i < 30; i++)
        set_visibility(reference, test, i, 0, 0.25f);
    set_visibility(reference, test, 30, 0.5f, 0.5f);
}

static shadowdiff_result compare(const dump_frame *reference, const dump_frame *test, const char *receiver) {
    shadowdiff_result r;
    assert_true(shadowdiff_compare(reference, test, &(shadowdiff_settings){.receiver = receiver}, &r, NULL));
    return r;
}

static void assert_counts(const shadowdiff_result *r, long compared, long false_shadow, long false_lit) {
    assert_int_equal(r->compared, compared);
    assert_int_equal(r->false_shadow, false_shadow);
    assert_int_equal(r->false_lit, false_lit);
}

static void test_counts_false_shadow_and_false_lit(void **state) {
    (void)state;
    dump_frame reference, test;
    make_pair(&reference, &test, point_light);
    set_known_verdicts(&reference, &test);
    shadowdiff_result r = compare(&reference, &test, NULL);
    assert_counts(&r, PIXELS, 5, 3);
    assert_float_equal(r.false_shadow_percent, 7.8125, 1e-12);
    assert_float_equal(r.false_lit_percent, 4.6875, 1e-12);
    assert_float_equal(r.misclassified_percent, 12.5, 1e-12);
    free_pair(&reference, &test);
}

static void test_mean_abs_error_on_fractions(void **state) {
    (void)state;
    dump_frame reference, test;
    make_pair(&reference, &test, point_light);
    for (size_t i = 0; i < PIXELS; i++) {
        if (i < 16)
            set_visibility(&reference, &test, i, 0.75f, 0.5f);
        else
            set_visibility(&reference, &test, i, 0.25f, 0.375f);
    }
    shadowdiff_result r = compare(&reference, &test, NULL);
    assert_counts(&r, PIXELS, 0, 0);
    assert_float_equal(r.mean_abs_error, (16 * 0.25 + 48 * 0.125) / PIXELS, 1e-12);
    free_pair(&reference, &test);
}

/* Coloured dumps (a scene with a translucent caster): each channel's MAE
 * over the compared pixels, where both dumps have channels; the one
 * figure decides and classes as before; a dump without them, none. */
static void test_channel_mae_of_coloured_dumps(void **state) {
    (void)state;
    scene_object objects[2] = {{.name = "ground"}, {.name = "box", .translucent = true, .casts = true}};
    scene s = {.lights = {point_light}, .light_count = 1, .objects = objects, .object_count = 2};
    dump_frame reference, test, grey;
    make_pair(&reference, &test, point_light);
    make_frame(&grey, SIZE, SIZE, point_light);
    assert_null(reference.visibility_rgb);
    dump_frame_free(&reference);
    dump_frame_free(&test);
    assert_true(dump_frame_create(&reference, SIZE, SIZE, &s, 0));
    assert_true(dump_frame_create(&test, SIZE, SIZE, &s, 0));
    assert_non_null(reference.visibility_rgb);
    for (size_t i = 0; i < PIXELS; i++) {
        dump_frame *frames[2] = {&reference, &test};
        for (int f = 0; f < 2; f++) {
            frames[f]->ids[i] = GROUND;
            frames[f]->depth[i] = DEPTH;
            set_vec3(frames[f]->normal, i, 0, 1, 0);
            set_vec3(frames[f]->position, i, (float)(i % SIZE), 0, (float)(i / SIZE));
        }
        /* A red glass's shadow on 16 pixels, drawn whole by the test. */
        bool under = i < 16;
        set_vec3(reference.visibility_rgb, i, 1, under ? 0.5f : 1, under ? 0.25f : 1);
        reference.visibility[i] = under ? (1 + 0.5f + 0.25f) / 3 : 1;
        test.visibility[i] = under ? 0 : 1;
        dump_frame_grey_rgb(&test);
    }
    shadowdiff_result r = compare(&reference, &test, NULL);
    assert_true(r.coloured);
    assert_counts(&r, PIXELS, 16, 0);
    assert_float_equal(r.channel_mae[0], 16 * 1.0 / PIXELS, 1e-12);
    assert_float_equal(r.channel_mae[1], 16 * 0.5 / PIXELS, 1e-12);
    assert_float_equal(r.channel_mae[2], 16 * 0.25 / PIXELS, 1e-12);
    /* Against a dump without channels: no channel figure. */
    r = compare(&reference, &grey, NULL);
    assert_false(r.coloured);
    dump_frame_free(&grey);
    free_pair(&reference, &test);
}

static void test_excludes_pixels_without_surface_in_either(void **state) {
    (void)state;
    dump_frame reference, test;
    make_pair(&reference, &test, point_light);
    set_no_surface(&reference, 0); /* each of 0..3 a wrong verdict if it counted */
    set_visibility(&reference, &test, 0, -1, 1);
    set_no_surface(&test, 1); /* visibility -1: "shadowed" if it counted */
    /* Only the id says "no surface" here, so that no depth rule hides it. */
    reference.ids[2] = -1;
    set_visibility(&reference, &test, 2, 0, 1);
    test.ids[3] = -1;
    set_visibility(&reference, &test, 3, 1, 0);
    set_visibility(&reference, &test, 4, 1, 0); /* the one that counts */
    shadowdiff_result r = compare(&reference, &test, NULL);
    assert_counts(&r, PIXELS - 4, 1, 0);
    assert_float_equal(r.false_shadow_percent, 100.0 / (PIXELS - 4), 1e-12);
    free_pair(&reference, &test);
}

static void test_depth_tolerance(void **state) {
    (void)state;
    dump_frame reference, test;
    make_pair(&reference, &test, point_light);
    const struct {
        float test_depth, r, t;
    } pixels[] = {
        {DEPTH * 1.002f, 1, 0},  /* twice the tolerance further: another surface */
        {DEPTH * 0.998f, 0, 1},  /* twice the tolerance nearer */
        {DEPTH * 1.0005f, 1, 0}, /* half the tolerance: the same surface */
        {DEPTH * 0.9995f, 0, 1},
    };
    for (size_t i = 0; i < sizeof pixels / sizeof *pixels; i++) {
        test.depth[i] = pixels[i].test_depth;
        set_visibility(&reference, &test, i, pixels[i].r, pixels[i].t);
    }
    shadowdiff_result r = compare(&reference, &test, NULL);
    assert_counts(&r, PIXELS - 2, 1, 1);
    free_pair(&reference, &test);
}

typedef struct surface {
    float position[3], normal[3];
} surface;

/* Gives the first `count` pixels of the reference these surfaces, each a
 * false shadow if it were compared. */
static void set_reference_surfaces(dump_frame *reference, dump_frame *test, const surface *surfaces, size_t count) {
    for (size_t i = 0; i < count; i++) {
        memcpy(reference->position + 3 * i, surfaces[i].position, sizeof surfaces[i].position);
        memcpy(reference->normal + 3 * i, surfaces[i].normal, sizeof surfaces[i].normal);
        set_visibility(reference, test, i, 1, 0);
    }
}

/* The light at (0, 10, 0): facing it depends on where the surface is. */
static void test_excludes_back_facing_point_light(void **state) {
    (void)state;
    dump_frame reference, test;
    make_pair(&reference, &test, point_light);
    const surface surfaces[] = {
        {{0, 20, 0}, {0, 1, 0}}, /* above the light, facing up */
        {{5, 0, 0}, {1, 0, 0}},  /* right of it, facing right */
        {{0, 0, 0}, {1, 0, 0}},  /* under it, edge on: N . L = 0 */
        {{3, 0, 0}, {0, -1, 0}}, /* facing down; the test's normal faces up */
        {{-5, 0, 0}, {1, 0, 0}}, /* left of it, facing right: compared */
    };
    set_reference_surfaces(&reference, &test, surfaces, sizeof surfaces / sizeof *surfaces);
    set_vec3(test.normal, 5, 0, -1, 0); /* only the reference's normal counts: compared */
    set_visibility(&reference, &test, 5, 0, 1);
    shadowdiff_result r = compare(&reference, &test, NULL);
    assert_counts(&r, PIXELS - 4, 1, 1);
    free_pair(&reference, &test);
}

/* The light straight down, (0, 1, 0, 0). */
static void test_excludes_back_facing_directional_light(void **state) {
    (void)state;
    dump_frame reference, test;
    make_pair(&reference, &test, sun);
    const surface surfaces[] = {
        {{0, 0, 0}, {0, -1, 0}},      /* facing down */
        {{0, 0, 0}, {1, 0, 0}},       /* edge on */
        {{0, 100, 0}, {0, 1, 0}},     /* far above (0, 1, 0), facing up: compared */
        {{0, 0, 0}, {0.6f, 0.8f, 0}}, /* compared */
    };
    set_reference_surfaces(&reference, &test, surfaces, sizeof surfaces / sizeof *surfaces);
    set_visibility(&reference, &test, 3, 0, 1);
    shadowdiff_result r = compare(&reference, &test, NULL);
    assert_counts(&r, PIXELS - 2, 1, 1);
    free_pair(&reference, &test);
}

/* With `grazing`, surfaces within that many degrees of edge-on to the
 * light are left out too; the same pixels count without it. The light
 * straight down, (0, 1, 0, 0): 2 and 4 degrees off edge-on. */
static void test_grazing_leaves_out_near_edge_on(void **state) {
    (void)state;
    dump_frame reference, test;
    make_pair(&reference, &test, sun);
    const surface surfaces[] = {
        {{0, 0, 0}, {0.99939f, 0.03490f, 0}}, /* 2 degrees: left out at 3 */
        {{0, 0, 0}, {0.99756f, 0.06976f, 0}}, /* 4 degrees: compared */
    };
    set_reference_surfaces(&reference, &test, surfaces, sizeof surfaces / sizeof *surfaces);
    set_visibility(&reference, &test, 0, 1, 0);
    set_visibility(&reference, &test, 1, 0, 1);
    shadowdiff_result r = compare(&reference, &test, NULL);
    assert_counts(&r, PIXELS, 1, 1);
    assert_true(shadowdiff_compare(&reference, &test, &(shadowdiff_settings){.grazing_degrees = 3}, &r, NULL));
    assert_counts(&r, PIXELS - 1, 0, 1);
    free_pair(&reference, &test);
}

/* A point light in the ground's plane (stress light_on_ground_point): the
 * reference's hit points come out a rounding off the plane, N . L a few
 * ulps either way, and the edge-on ground is left out, which it was not
 * by sign alone; a millimetre below the plane (a cosine of 2e-4) it is
 * compared. */
static void test_edge_on_within_rounding_left_out(void **state) {
    (void)state;
    dump_frame reference, test;
    make_pair(&reference, &test, (scene_light){.type = SCENE_LIGHT_POINT, .position = {0, 0, 0}});
    const surface surfaces[] = {
        {{5, -8.881784e-16f, 0}, {0, 1, 0}}, /* as the reference had it: left out */
        {{5, 8.881784e-16f, 0}, {0, 1, 0}},  /* above: faces away */
        {{5, -1e-3f, 0}, {0, 1, 0}},         /* compared */
    };
    set_reference_surfaces(&reference, &test, surfaces, sizeof surfaces / sizeof *surfaces);
    set_visibility(&reference, &test, 2, 0, 1);
    for (size_t i = sizeof surfaces / sizeof *surfaces; i < PIXELS; i++)
        set_no_surface(&reference, i);
    shadowdiff_result r = compare(&reference, &test, NULL);
    assert_counts(&r, 1, 0, 1);
    free_pair(&reference, &test);
}

/* Rows 4..7 are the box, except one pixel the test sees as ground. */
static void test_receiver_restricts(void **state) {
    (void)state;
    dump_frame reference, test;
    make_pair(&reference, &test, point_light);
    for (size_t i = PIXELS / 2; i < PIXELS; i++)
        reference.ids[i] = test.ids[i] = BOX;
    test.ids[PIXELS - 1] = GROUND;
    set_visibility(&reference, &test, 0, 1, 0);
    set_visibility(&reference, &test, 1, 1, 0);
    set_visibility(&reference, &test, 40, 0, 1);
    set_visibility(&reference, &test, 41, 0, 1);
    set_visibility(&reference, &test, 42, 0, 1);
    set_visibility(&reference, &test, 43, 1, 0);
    set_visibility(&reference, &test, PIXELS - 1, 1, 0);
    shadowdiff_result all = compare(&reference, &test, NULL);
    shadowdiff_result ground = compare(&reference, &test, "ground");
    shadowdiff_result box = compare(&reference, &test, "box");
    assert_counts(&all, PIXELS, 4, 3);
    assert_counts(&ground, PIXELS / 2, 2, 0);
    assert_counts(&box, PIXELS / 2 - 1, 1, 3);
    assert_float_equal(box.false_lit_percent, 300.0 / (PIXELS / 2 - 1), 1e-12);
    shadowdiff_result unused;
    assert_false(shadowdiff_compare(&reference, &test, &(shadowdiff_settings){.receiver = "teapot"}, &unused, NULL));
    free_pair(&reference, &test);
}

/* ---- the classes: umbra, penumbra, lit by the reference's visibility ---- */

/* A soft truth across the columns (every row the same): two umbra
 * columns, a penumbra ramp of four, two lit ones. */
#define SOFT_TRUTH                                                                                                   \
    { 0, 0, 0.2f, 0.4f, 0.6f, 0.8f, 1, 1 }
/* The same edge, hard: the picture a hard shadow map draws of it. */
#define HARD_EDGE                                                                                                    \
    { 0, 0, 0, 0, 1, 1, 1, 1 }
#define CLASS_CASE_TOLERANCE 1e-6

/* One picture against its truth: the visibilities by column, and on the
 * lit class's pixels with x + y odd (a checkerboard) the test's
 * visibility `speckle` where it is not 0. Expected: misclassified %, MAE,
 * each class's pixel count and MAE (a class with no pixel: 0). */
typedef struct class_case {
    const char *what;
    float reference[SIZE], test[SIZE], speckle;
    double misclassified, mae;
    long pixels[SHADOWDIFF_CLASS_COUNT];
    double class_mae[SHADOWDIFF_CLASS_COUNT];
} class_case;

enum {
    CASE_EXACT,
    CASE_HARD_AGAINST_SOFT,
    CASE_BLURRED,
    CASE_LEAKING,
    CASE_SPECKLED,
    CASE_HARD_TRUTH,
    CLASS_CASE_COUNT
};

static const class_case class_cases[CLASS_CASE_COUNT] = {
    [CASE_EXACT] = {"exact soft shadow", SOFT_TRUTH, SOFT_TRUTH, 0, 0, 0, {16, 32, 16}, {0, 0, 0}},
    /* Steps on the 0.5 line: nothing misclassified, the ramp off by 0.2,
     * 0.4, 0.4, 0.2 in the penumbra. */
    [CASE_HARD_AGAINST_SOFT] = {"hard against soft", SOFT_TRUTH, HARD_EDGE, 0, 0, 0.15, {16, 32, 16}, {0, 0.3, 0}},
    [CASE_BLURRED] = {"blurred everywhere",
                      SOFT_TRUTH,
                      {0.1f, 0.15f, 0.3f, 0.4f, 0.6f, 0.7f, 0.85f, 0.9f},
                      0,
                      0,
                      0.0875,
                      {16, 32, 16},
                      {0.125, 0.05, 0.125}},
    /* Light in the umbra, one column over 0.5: the umbra's error only. */
    [CASE_LEAKING] =
        {"leaking", SOFT_TRUTH, {0.5f, 0.3f, 0.2f, 0.4f, 0.6f, 0.8f, 1, 1}, 0, 12.5, 0.1, {16, 32, 16}, {0.4, 0, 0}},
    /* Half the lit pixels at 0.625: still lit, the lit class's error. */
    [CASE_SPECKLED] =
        {"speckled lit surface", SOFT_TRUTH, SOFT_TRUTH, 0.625f, 0, 0.046875, {16, 32, 16}, {0, 0, 0.1875}},
    /* A hard truth: no penumbra; the old figures are as they always were
     * (column 3 lit, column 7 dark: 16 of 64 misclassified). */
    [CASE_HARD_TRUTH] =
        {"hard truth", HARD_EDGE, {0, 0, 0, 1, 1, 1, 1, 0.25f}, 0, 25, 0.21875, {32, 0, 32}, {0.25, 0, 0.1875}},
};

/* Case c's picture into rows [row0, row0 + SIZE) of the pair. */
static void set_class_case(dump_frame *reference, dump_frame *test, const class_case *c, int row0) {
    for (int y = 0; y < SIZE; y++) {
        for (int x = 0; x < SIZE; x++) {
            size_t i = (size_t)(row0 + y) * SIZE + (size_t)x;
            bool speckled = c->speckle != 0 && c->reference[x] >= SHADOWDIFF_LIT_MIN_VISIBILITY && (x + y) % 2;
            set_visibility(reference, test, i, c->reference[x], speckled ? c->speckle : c->test[x]);
        }
    }
}

static shadowdiff_result compare_class_case(const class_case *c) {
    dump_frame reference, test;
    make_pair(&reference, &test, point_light);
    set_class_case(&reference, &test, c, 0);
    shadowdiff_result r = compare(&reference, &test, NULL);
    free_pair(&reference, &test);
    return r;
}

/* Each wrong picture moves the figure that names its fault, and only
 * that one where the fault is one: a hard shadow of a soft truth
 * misclassifies nothing and is 0.3 off in the penumbra; a leak is the
 * umbra's, a speckle the lit class's. The classes partition the compared pixels. */
static void test_classes_name_the_fault(void **state) {
    (void)state;
    for (int k = 0; k < CLASS_CASE_COUNT; k++) {
        const class_case *c = &class_cases[k];
        shadowdiff_result r = compare_class_case(c);
        print_message("    %s: misclassified %.4f %%, MAE %.5f, umbra %.5f, penumbra %.5f, lit %.5f\n", c->what,
                      r.misclassified_percent, r.mean_abs_error, r.class_mae[SHADOWDIFF_CLASS_UMBRA],
                      r.class_mae[SHADOWDIFF_CLASS_PENUMBRA], r.class_mae[SHADOWDIFF_CLASS_LIT]);
        assert_int_equal(r.compared, PIXELS);
        assert_float_equal(r.misclassified_percent, c->misclassified, CLASS_CASE_TOLERANCE);
        assert_float_equal(r.mean_abs_error, c->mae, CLASS_CASE_TOLERANCE);
        double weighed = 0;
        for (int cl = 0; cl < SHADOWDIFF_CLASS_COUNT; cl++) {
            assert_int_equal(r.class_pixels[cl], c->pixels[cl]);
            assert_float_equal(r.class_mae[cl], c->class_mae[cl], CLASS_CASE_TOLERANCE);
            weighed += r.class_mae[cl] * (double)r.class_pixels[cl];
        }
        assert_float_equal(weighed / PIXELS, r.mean_abs_error, 1e-12);
    }
}

/* The bounds are inclusive: 1/32 is umbra, 31/32 lit, just inside them
 * penumbra; a spot's outside (0) is umbra. */
static void test_class_bounds(void **state) {
    (void)state;
    dump_frame reference, test;
    make_pair(&reference, &test, point_light);
    const float umbra = SHADOWDIFF_UMBRA_MAX_VISIBILITY, lit = SHADOWDIFF_LIT_MIN_VISIBILITY;
    const float penumbra[] = {nextafterf(umbra, 1), nextafterf(lit, 0)};
    for (size_t i = 0; i < PIXELS; i++)
        set_visibility(&reference, &test, i, i < 16 ? 0 : i < 32 ? umbra : 1, 1);
    set_visibility(&reference, &test, 40, lit, 1);
    for (size_t i = 0; i < 2; i++)
        set_visibility(&reference, &test, 50 + i, penumbra[i], 1);
    shadowdiff_result r = compare(&reference, &test, NULL);
    assert_int_equal(r.class_pixels[SHADOWDIFF_CLASS_UMBRA], 32);
    assert_int_equal(r.class_pixels[SHADOWDIFF_CLASS_PENUMBRA], 2);
    assert_int_equal(r.class_pixels[SHADOWDIFF_CLASS_LIT], PIXELS - 34);
    assert_float_equal(r.class_mae[SHADOWDIFF_CLASS_LIT], (1 - (double)lit) / (PIXELS - 34), 1e-9);
    char text[32];
    assert_string_equal(shadowdiff_class_mae_text(&r, SHADOWDIFF_CLASS_UMBRA, 3, text, sizeof text), "0.984");
    free_pair(&reference, &test);
    /* A class with no pixel has no figure, in text too. */
    r = compare_class_case(&class_cases[CASE_HARD_TRUTH]);
    assert_string_equal(shadowdiff_class_mae_text(&r, SHADOWDIFF_CLASS_PENUMBRA, 4, text, sizeof text), "none");
}

/* Every case pooled frame by frame is one comparison of all of them,
 * stacked into one tall picture: the counts summed, every MAE over the
 * sums. */
static void test_classes_pool(void **state) {
    (void)state;
    dump_frame reference, test;
    make_frame(&reference, SIZE, SIZE * CLASS_CASE_COUNT, point_light);
    make_frame(&test, SIZE, SIZE * CLASS_CASE_COUNT, point_light);
    shadowdiff_result pooled = {0};
    for (int k = 0; k < CLASS_CASE_COUNT; k++) {
        shadowdiff_result frame = compare_class_case(&class_cases[k]);
        shadowdiff_result_add(&pooled, &frame);
        set_class_case(&reference, &test, &class_cases[k], SIZE * k);
    }
    shadowdiff_result once = compare(&reference, &test, NULL);
    assert_counts(&pooled, once.compared, once.false_shadow, once.false_lit);
    assert_float_equal(pooled.misclassified_percent, once.misclassified_percent, 1e-12);
    assert_float_equal(pooled.mean_abs_error, once.mean_abs_error, 1e-12);
    for (int c = 0; c < SHADOWDIFF_CLASS_COUNT; c++) {
        assert_int_equal(pooled.class_pixels[c], once.class_pixels[c]);
        assert_float_equal(pooled.class_mae[c], once.class_mae[c], 1e-12);
    }
    /* Pooled with a frame that has no penumbra, the penumbra's MAE is
     * the other frame's, not diluted by a 0. */
    shadowdiff_result soft = compare_class_case(&class_cases[CASE_HARD_AGAINST_SOFT]);
    shadowdiff_result hard = compare_class_case(&class_cases[CASE_HARD_TRUTH]);
    shadowdiff_result_add(&soft, &hard);
    assert_int_equal(soft.class_pixels[SHADOWDIFF_CLASS_PENUMBRA], 32);
    assert_float_equal(soft.class_mae[SHADOWDIFF_CLASS_PENUMBRA], 0.3, CLASS_CASE_TOLERANCE);
    free_pair(&reference, &test);
}

/* Compares expecting no figure: false, `problem`, and one line on stderr
 * holding `expect`. */
static shadowdiff_result expect_no_figure(const dump_frame *reference, const dump_frame *test,
                                          shadowdiff_problem problem, const char *expect) {
    shadowdiff_result r;
    const shadowdiff_settings names = {.reference_name = "REF", .test_name = "TEST"};
    support_capture_stderr();
    bool compared = shadowdiff_compare(reference, test, &names, &r, NULL);
    const char *text = support_release_stderr();
    assert_false(compared);
    assert_int_equal(r.problem, problem);
    assert_int_equal(support_count_lines(text), 1);
    if (!strstr(text, expect))
        fail_msg("expected \"%s\" in \"%s\"", expect, text);
    return r;
}

/* Every percentage would be 0: a perfect technique, so no figure. */
static void test_nothing_compared_is_an_error(void **state) {
    (void)state;
    dump_frame reference, test;
    make_pair(&reference, &test, point_light);
    for (size_t i = 0; i < PIXELS; i++) {
        test.depth[i] = 2 * DEPTH;
        set_visibility(&reference, &test, i, 1, 0);
    }
    shadowdiff_result r =
        expect_no_figure(&reference, &test, SHADOWDIFF_PROBLEM_NOTHING_COMPARED, "REF and TEST: nothing compared");
    assert_counts(&r, 0, 0, 0);
    free_pair(&reference, &test);
}

#define BAD_PIXEL 11 /* (3, 1) */

typedef struct bad_value {
    bool in_reference;
    size_t array; /* offsetof(dump_frame, the array) */
    int components;
    float value;
    bool no_surface;    /* that dump sees no surface at the pixel */
    const char *expect; /* NULL: the rules do not read it, the pixels are compared */
} bad_value;

static float *array_of(dump_frame *d, size_t offset) {
    float *array;
    memcpy(&array, (char *)d + offset, sizeof array);
    return array;
}

/* One bad value in one array of one dump: each the rules read is named
 * with its file and pixel; one they do not read changes nothing. */
static void test_non_finite_is_an_error(void **state) {
    (void)state;
    const bad_value cases[] = {
        {false, offsetof(dump_frame, visibility), 1, NAN, false,
         "TEST/visibility.pfm: nan at pixel (3, 1) where a surface is seen, and 1 non-finite value in all"},
        {true, offsetof(dump_frame, visibility), 1, INFINITY, false, "REF/visibility.pfm: inf at pixel (3, 1)"},
        {false, offsetof(dump_frame, depth), 1, NAN, false, "TEST/depth.pfm: nan at pixel (3, 1)"},
        {true, offsetof(dump_frame, depth), 1, -INFINITY, false, "REF/depth.pfm: -inf at pixel (3, 1)"},
        {false, offsetof(dump_frame, ids), 1, NAN, false, "TEST/ids.pfm: nan at pixel (3, 1), and 1"},
        {true, offsetof(dump_frame, normal), 3, NAN, false, "REF/normal.pfm: nan at pixel (3, 1)"},
        {true, offsetof(dump_frame, position), 3, INFINITY, false, "REF/position.pfm: inf at pixel (3, 1)"},
        {false, offsetof(dump_frame, normal), 3, NAN, false, NULL},
        {false, offsetof(dump_frame, position), 3, INFINITY, false, NULL},
        {false, offsetof(dump_frame, visibility), 1, NAN, true, NULL},
        {true, offsetof(dump_frame, depth), 1, NAN, true, NULL},
    };
    for (size_t c = 0; c < sizeof cases / sizeof *cases; c++) {
        dump_frame reference, test;
        make_pair(&reference, &test, point_light);
        dump_frame *bad = cases[c].in_reference ? &reference : &test;
        if (cases[c].no_surface)
            bad->ids[BAD_PIXEL] = -1;
        array_of(bad, cases[c].array)[cases[c].components * BAD_PIXEL + cases[c].components - 1] = cases[c].value;
        if (cases[c].expect) {
            shadowdiff_result r = expect_no_figure(&reference, &test, SHADOWDIFF_PROBLEM_NOT_FINITE, cases[c].expect);
            assert_counts(&r, 0, 0, 0);
        } else {
            shadowdiff_result r = compare(&reference, &test, NULL);
            assert_int_equal(r.problem, SHADOWDIFF_PROBLEM_NONE);
            assert_counts(&r, cases[c].no_surface ? PIXELS - 1 : PIXELS, 0, 0);
        }
        free_pair(&reference, &test);
    }
}

static void assert_rgba(const unsigned char *rgba, size_t i, int r, int g, int b) {
    assert_int_equal(rgba[4 * i + 0], r);
    assert_int_equal(rgba[4 * i + 1], g);
    assert_int_equal(rgba[4 * i + 2], b);
    assert_int_equal(rgba[4 * i + 3], 255);
}

static void test_heatmap_colours(void **state) {
    (void)state;
    dump_frame reference, test;
    make_pair(&reference, &test, point_light);
    set_visibility(&reference, &test, 0, 1, 0);
    set_visibility(&reference, &test, 1, 0, 1);
    set_no_surface(&reference, 2);
    set_no_surface(&test, 3);
    set_visibility(&reference, &test, 5, 0, 0);
    set_visibility(&reference, &test, 6, 0.5f, 0.75f);
    unsigned char heatmap[PIXELS * 4];
    shadowdiff_result r;
    assert_true(shadowdiff_compare(&reference, &test, NULL, &r, heatmap));
    assert_rgba(heatmap, 0, 255, 0, 0);     /* false shadow: red */
    assert_rgba(heatmap, 1, 0, 0, 255);     /* false lit: blue */
    assert_rgba(heatmap, 2, 0, 0, 0);       /* no surface: black */
    assert_rgba(heatmap, 3, 40, 40, 40);    /* not compared: dark grey */
    assert_rgba(heatmap, 4, 255, 255, 255); /* lit in both */
    assert_rgba(heatmap, 5, 96, 96, 96);    /* shadowed in both */
    assert_rgba(heatmap, 6, 176, 176, 176); /* half lit: 96 + 159 / 2 */
    free_pair(&reference, &test);
}

static void test_rejects_inconsistent_dumps(void **state) {
    (void)state;
    dump_frame reference, test, small;
    shadowdiff_result r;
    make_pair(&reference, &test, point_light);
    make_frame(&small, SIZE, SIZE / 2, point_light);
    assert_false(shadowdiff_compare(&reference, &small, NULL, &r, NULL));
    test.light[1] = 10.01f; /* 1e-3 relative */
    assert_false(shadowdiff_compare(&reference, &test, NULL, &r, NULL));
    test.light[1] = 10.0001f; /* 1e-5 relative: the same light */
    assert_true(shadowdiff_compare(&reference, &test, NULL, &r, NULL));
    test.light[3] = 0; /* a directional light */
    assert_false(shadowdiff_compare(&reference, &test, NULL, &r, NULL));
    test.light[3] = 1;
    test.light_index = 1;
    assert_false(shadowdiff_compare(&reference, &test, NULL, &r, NULL));
    test.light_index = 0;
    test.object_count = 1;
    assert_false(shadowdiff_compare(&reference, &test, NULL, &r, NULL));
    test.object_count = 2;
    strcpy(test.object_names[BOX], "cube");
    assert_false(shadowdiff_compare(&reference, &test, NULL, &r, NULL));
    strcpy(test.object_names[BOX], "box");
    assert_true(shadowdiff_compare(&reference, &test, NULL, &r, NULL));
    free_pair(&reference, &test);
    dump_frame_free(&small);
}

static void assert_floats_equal(const float *a, const float *b, size_t count) {
    assert_memory_equal(a, b, count * sizeof *a);
}

/* Not square and every value different, so that a swapped axis or an
 * unflipped row shows. */
static void test_dump_round_trip(void **state) {
    (void)state;
    const int width = 8, height = 5;
    const size_t n = (size_t)width * (size_t)height;
    dump_frame written, loaded;
    make_frame(&written, width, height, sun);
    written.camera = (scene_camera){.position = {1.5f, -2, 3e6f},
                                    .target = {0.1f, 0, 7},
                                    .up = {0, 0, 1},
                                    .fov_deg = 47.5f,
                                    .near_plane = 0.01f,
                                    .far_plane = 1e5f};
    for (size_t i = 0; i < n; i++) {
        written.visibility[i] = (float)i / (float)n;
        written.depth[i] = 1 + 0.25f * (float)i;
        written.ids[i] = (float)(i % 3) - 1;
        set_vec3(written.normal, i, 0.1f * (float)i, -1, 0.5f);
        set_vec3(written.position, i, (float)i, 2 * (float)i, -(float)i);
    }
    assert_true(dump_write(&written, DIR "/round_trip"));
    assert_true(dump_read(&loaded, DIR "/round_trip"));
    assert_int_equal(loaded.width, width);
    assert_int_equal(loaded.height, height);
    assert_int_equal(loaded.light_index, written.light_index);
    assert_floats_equal(loaded.light, written.light, 4);
    assert_memory_equal(&loaded.camera, &written.camera, sizeof loaded.camera);
    assert_int_equal(loaded.object_count, written.object_count);
    for (int i = 0; i < written.object_count; i++)
        assert_string_equal(loaded.object_names[i], written.object_names[i]);
    assert_floats_equal(loaded.visibility, written.visibility, n);
    assert_floats_equal(loaded.depth, written.depth, n);
    assert_floats_equal(loaded.ids, written.ids, n);
    assert_floats_equal(loaded.normal, written.normal, 3 * n);
    assert_floats_equal(loaded.position, written.position, 3 * n);
    dump_frame_free(&written);
    dump_frame_free(&loaded);
}

/* ---- shimmer ---- */

/* The shimmer frames: a camera SHIMMER_HEIGHT straight above the ground,
 * its picture exactly the ground's SIZE x SIZE unit squares, so pixel
 * (x, y) sees (x + 0.5 + shift, 0, y + 0.5); frame 1 is frame 0 with eye
 * and target moved by 1 along x, so its pixel (x, y) is frame 0's
 * (x + 1, y), and its last column is outside frame 0. */
#define SHIMMER_HEIGHT 10.0f
#define SHIMMER_FOLLOWED (PIXELS - SIZE)

static void make_view_frame(dump_frame *d, float shift) {
    make_frame(d, SIZE, SIZE, sun);
    const float centre = 0.5f * SIZE + shift;
    d->camera = (scene_camera){.position = {centre, SHIMMER_HEIGHT, 0.5f * SIZE},
                               .target = {centre, 0, 0.5f * SIZE},
                               .up = {0, 0, -1},
                               .fov_deg = (float)(2 * atan(0.5 * SIZE / SHIMMER_HEIGHT) * 180 / M_PI),
                               .near_plane = 1,
                               .far_plane = 100};
    for (int y = 0; y < SIZE; y++)
        for (int x = 0; x < SIZE; x++)
            set_vec3(d->position, (size_t)(y * SIZE + x), (float)x + 0.5f + shift, 0, (float)y + 0.5f);
}

typedef struct shimmer_frames {
    dump_frame r0, t0, r1, t1;
} shimmer_frames;

static void make_shimmer_frames(shimmer_frames *f, float shift) {
    make_view_frame(&f->r0, 0);
    make_view_frame(&f->t0, 0);
    make_view_frame(&f->r1, shift);
    make_view_frame(&f->t1, shift);
}

static void free_shimmer_frames(shimmer_frames *f) {
    free_pair(&f->r0, &f->t0);
    free_pair(&f->r1, &f->t1);
}

static size_t pixel(int x, int y) { return (size_t)(y * SIZE + x); }

static shadowdiff_shimmer_result shimmer(const shimmer_frames *f, double grazing_degrees) {
    shadowdiff_shimmer_result r;
    const shadowdiff_settings settings = {.grazing_degrees = grazing_degrees};
    assert_true(shadowdiff_shimmer(&f->r0, &f->t0, &f->r1, &f->t1, &settings, &r));
    assert_int_equal(r.problem, SHADOWDIFF_PROBLEM_NONE);
    return r;
}

static void assert_shimmer(const shadowdiff_shimmer_result *r, long followed, long shimmered, long truth_changed) {
    assert_int_equal(r->followed, followed);
    assert_int_equal(r->shimmered, shimmered);
    assert_int_equal(r->truth_changed, truth_changed);
    assert_float_equal(r->shimmer_percent, 100.0 * (double)shimmered / (double)followed, 1e-12);
}

/* A still camera follows every pixel to itself (pixel centres land in
 * their own squares); a decision that flips counts. */
static void test_shimmer_still_camera_follows_every_pixel(void **state) {
    (void)state;
    shimmer_frames f;
    make_shimmer_frames(&f, 0);
    shadowdiff_shimmer_result r = shimmer(&f, 0);
    assert_shimmer(&r, PIXELS, 0, 0);
    f.t1.visibility[pixel(3, 4)] = 0;
    r = shimmer(&f, 0);
    assert_shimmer(&r, PIXELS, 1, 0);
    assert_int_equal(r.current.false_shadow, 1);
    assert_int_equal(r.previous.false_shadow, 0);
    free_shimmer_frames(&f);
}

/* Frame 1's pixel (x, y) is frame 0's (x + 1, y): a flip of the test
 * where the truth is still counts; where the truth flips too, or only the
 * truth flips, it does not (truth_changed). The same pixel index in both
 * frames, a different world point, is not what is compared. */
static void test_shimmer_counts_flips_where_the_truth_is_still(void **state) {
    (void)state;
    shimmer_frames f;
    make_shimmer_frames(&f, 1);
    f.t1.visibility[pixel(2, 0)] = 0;                                /* t0 (3, 0) lit: counted */
    f.r1.visibility[pixel(4, 0)] = f.t1.visibility[pixel(4, 0)] = 0; /* both flip */
    f.r1.visibility[pixel(0, 1)] = 0;                                /* the truth alone */
    /* Shadowed in frame 0 at (6, 2), in frame 1 at the same world point
     * (5, 2): still; frame 1's (6, 2) is lit, another point. */
    f.r0.visibility[pixel(6, 2)] = f.t0.visibility[pixel(6, 2)] = 0;
    f.r1.visibility[pixel(5, 2)] = f.t1.visibility[pixel(5, 2)] = 0;
    shadowdiff_shimmer_result r = shimmer(&f, 0);
    assert_shimmer(&r, SHIMMER_FOLLOWED, 1, 2);
    assert_float_equal(r.truth_changed_percent, 200.0 / SHIMMER_FOLLOWED, 1e-12);
    free_shimmer_frames(&f);
}

/* A point hidden in frame 0 (another object there, or the same object
 * further than the tolerance: the point was not on the surface seen) is
 * not followed, whatever the test decides. */
static void test_shimmer_leaves_out_disocclusions(void **state) {
    (void)state;
    shimmer_frames f;
    make_shimmer_frames(&f, 1);
    f.r0.ids[pixel(2, 1)] = f.t0.ids[pixel(2, 1)] = BOX; /* frame 1's (1, 1) */
    f.t1.visibility[pixel(1, 1)] = 0;
    /* Frame 0's (4, 3) is 0.2 above frame 1's (3, 3): a fiftieth of its
     * distance of 10, over the tolerance (a hundredth). */
    f.r0.position[3 * pixel(4, 3) + 1] = 0.2f;
    f.t1.visibility[pixel(3, 3)] = 0;
    /* 0.05 above: half the tolerance, within; a flip there counts. */
    f.r0.position[3 * pixel(4, 5) + 1] = 0.05f;
    f.t1.visibility[pixel(3, 5)] = 0;
    shadowdiff_shimmer_result r = shimmer(&f, 0);
    assert_shimmer(&r, SHIMMER_FOLLOWED - 2, 1, 0);
    /* The test seeing another object in frame 0 is left out too. */
    f.t0.ids[pixel(4, 5)] = BOX;
    r = shimmer(&f, 0);
    assert_shimmer(&r, SHIMMER_FOLLOWED - 3, 0, 0);
    free_shimmer_frames(&f);
}

/* shadowdiff's rules decide what is compared in each frame: a reference
 * surface edge-on to the light in frame 1, or in frame 0 where a pixel
 * lands, is not followed; --grazing leaves out the near edge-on ones. */
static void test_shimmer_honours_the_edge_on_rule(void **state) {
    (void)state;
    shimmer_frames f;
    make_shimmer_frames(&f, 1);
    set_vec3(f.r1.normal, pixel(2, 2), 1, 0, 0); /* edge-on to the sun straight above */
    f.t1.visibility[pixel(2, 2)] = 0;
    set_vec3(f.r0.normal, pixel(5, 5), 0, 0, 1); /* frame 1's (4, 5) */
    f.t1.visibility[pixel(4, 5)] = 0;
    /* 10 degrees off edge-on: compared, unless --grazing leaves it out. */
    set_vec3(f.r1.normal, pixel(6, 6), cosf(10 * (float)M_PI / 180), sinf(10 * (float)M_PI / 180), 0);
    f.t1.visibility[pixel(6, 6)] = 0;
    shadowdiff_shimmer_result r = shimmer(&f, 0);
    assert_shimmer(&r, SHIMMER_FOLLOWED - 2, 1, 0);
    r = shimmer(&f, 30);
    assert_shimmer(&r, SHIMMER_FOLLOWED - 3, 0, 0);
    free_shimmer_frames(&f);
}

/* No figure: a broken frame 0, cameras that differ within a frame, frames
 * of different scenes, or nothing followed. */
static void test_shimmer_problems(void **state) {
    (void)state;
    shimmer_frames f;
    shadowdiff_shimmer_result r;
    make_shimmer_frames(&f, 1);
    support_capture_stderr();
    f.t0.visibility[pixel(1, 1)] = NAN;
    bool nan_ok = shadowdiff_shimmer(&f.r0, &f.t0, &f.r1, &f.t1, NULL, &r);
    shadowdiff_problem nan_problem = r.problem;
    f.t0.visibility[pixel(1, 1)] = 1;
    f.t0.camera.position[0] += 1;
    bool camera_ok = shadowdiff_shimmer(&f.r0, &f.t0, &f.r1, &f.t1, NULL, &r);
    shadowdiff_problem camera_problem = r.problem;
    f.t0.camera = f.r0.camera;
    memcpy(f.r0.object_names[BOX], "crate", sizeof "crate");
    memcpy(f.t0.object_names[BOX], "crate", sizeof "crate");
    bool objects_ok = shadowdiff_shimmer(&f.r0, &f.t0, &f.r1, &f.t1, NULL, &r);
    shadowdiff_problem objects_problem = r.problem;
    free_shimmer_frames(&f);
    make_shimmer_frames(&f, SIZE); /* frame 1 wholly beside frame 0 */
    bool beside_ok = shadowdiff_shimmer(&f.r0, &f.t0, &f.r1, &f.t1, NULL, &r);
    shadowdiff_problem beside_problem = r.problem;
    const char *text = support_release_stderr();
    assert_false(nan_ok);
    assert_int_equal(nan_problem, SHADOWDIFF_PROBLEM_NOT_FINITE);
    assert_non_null(strstr(text, "previous test/visibility.pfm: nan at pixel (1, 1)"));
    assert_false(camera_ok);
    assert_int_equal(camera_problem, SHADOWDIFF_PROBLEM_MISMATCH);
    assert_non_null(strstr(text, "previous reference and previous test are seen from different cameras"));
    assert_false(objects_ok);
    assert_int_equal(objects_problem, SHADOWDIFF_PROBLEM_MISMATCH);
    assert_non_null(strstr(text, "previous reference and reference have different objects: 1 is 'crate' and 'box'"));
    assert_false(beside_ok);
    assert_int_equal(beside_problem, SHADOWDIFF_PROBLEM_NOTHING_COMPARED);
    assert_int_equal(r.followed, 0);
    assert_non_null(strstr(text, "no compared pixel followed"));
    assert_int_equal(support_count_lines(text), 4);
    free_shimmer_frames(&f);
}

/* ---- build/shadowdiff ---- */

/* DIR/ref and DIR/test hold the known verdicts (one pixel in eight
 * misclassified);
 * DIR/shimmer_ref0, _test0, _ref1, _test1 two frames with one pixel of
 * shimmer among SHIMMER_FOLLOWED;
 * DIR/small is another size, DIR/moved another light, DIR/far sees
 * everything further away; DIR/nan is DIR/test with a NaN visibility and
 * DIR/inf DIR/ref with an infinite depth, both where a surface is seen. */
static int write_cli_dumps(void **state) {
    (void)state;
    dump_frame reference, test, small, moved;
    make_pair(&reference, &test, point_light);
    set_known_verdicts(&reference, &test);
    make_frame(&small, SIZE, SIZE / 2, point_light);
    make_frame(&moved, SIZE, SIZE, (scene_light){.type = SCENE_LIGHT_POINT, .position = {0, 11, 0}});
    bool ok = dump_write(&reference, DIR "/ref") && dump_write(&test, DIR "/test") &&
              dump_write(&small, DIR "/small") && dump_write(&moved, DIR "/moved");
    for (size_t i = 0; i < PIXELS; i++)
        test.depth[i] = 2 * DEPTH;
    ok = ok && dump_write(&test, DIR "/far");
    for (size_t i = 0; i < PIXELS; i++)
        test.depth[i] = DEPTH;
    test.visibility[BAD_PIXEL] = NAN;
    reference.depth[BAD_PIXEL] = INFINITY;
    ok = ok && dump_write(&test, DIR "/nan") && dump_write(&reference, DIR "/inf");
    free_pair(&reference, &test);
    dump_frame_free(&small);
    dump_frame_free(&moved);
    /* DIR/shimmer_*: one flip of the test where the truth is still. */
    shimmer_frames f;
    make_shimmer_frames(&f, 1);
    f.t1.visibility[pixel(2, 0)] = 0;
    ok = ok && dump_write(&f.r0, DIR "/shimmer_ref0") && dump_write(&f.t0, DIR "/shimmer_test0") &&
         dump_write(&f.r1, DIR "/shimmer_ref1") && dump_write(&f.t1, DIR "/shimmer_test1");
    free_shimmer_frames(&f);
    return ok ? 0 : -1;
}

/* Runs build/shadowdiff with `args`; stdout goes to `out`, stderr to err. */
static int run_shadowdiff(const char *args, char *out, size_t capacity) {
    char command[4096];
    snprintf(command, sizeof command, "(%s %s >" DIR "/stdout.txt)", support_program("shadowdiff"), args);
    int status = support_run(command, err, sizeof err);
    FILE *f = fopen(DIR "/stdout.txt", "r");
    assert_non_null(f);
    size_t length = fread(out, 1, capacity - 1, f);
    out[length] = '\0';
    fclose(f);
    return status;
}

/* Checks the status and that stderr is one line with both strings. */
static void expect_failure(const char *args, int status, const char *expect1, const char *expect2) {
    char out[4096];
    assert_int_equal(run_shadowdiff(args, out, sizeof out), status);
    assert_int_equal(support_count_lines(err), 1);
    assert_non_null(strstr(err, expect1));
    assert_non_null(strstr(err, expect2));
}

static void test_cli_text_report(void **state) {
    (void)state;
    char out[4096];
    assert_int_equal(run_shadowdiff(DIR "/ref " DIR "/test", out, sizeof out), 0);
    assert_string_equal(err, "");
    assert_int_equal(support_count_lines(out), TEXT_LINES);
    assert_non_null(strstr(out, "64 of 64"));
    assert_non_null(strstr(out, "7.812 %"));
    assert_non_null(strstr(out, "4.688 %"));
    assert_non_null(strstr(out, "12.500 %"));
    assert_non_null(strstr(out, "\nmean abs error   0.1331\numbra MAE        0.3750 (12 pixels: "));
    assert_non_null(strstr(out, "\npenumbra MAE     0.0067 (3 pixels: "));
    assert_non_null(strstr(out, "\nlit MAE          0.0816 (49 pixels: "));
    /* All lit: no umbra, no penumbra, and no 0 that reads as perfect. */
    assert_int_equal(run_shadowdiff(DIR "/moved " DIR "/moved", out, sizeof out), 0);
    assert_non_null(strstr(out, "\numbra MAE        none (0 pixels: "));
    assert_non_null(strstr(out, "\npenumbra MAE     none (0 pixels: "));
    assert_non_null(strstr(out, "\nlit MAE          0.0000 (64 pixels: "));
}

static double json_number(const cJSON *root, const char *key) {
    const cJSON *item = cJSON_GetObjectItemCaseSensitive(root, key);
    assert_true(cJSON_IsNumber(item));
    return item->valuedouble;
}

/* Runs build/shadowdiff --json with `args`; the caller deletes the result. */
static cJSON *run_json(const char *args) {
    char command_args[1024], out[4096];
    snprintf(command_args, sizeof command_args, "%s --json", args);
    assert_int_equal(run_shadowdiff(command_args, out, sizeof out), 0);
    assert_int_equal(support_count_lines(out), 1);
    cJSON *root = cJSON_Parse(out);
    assert_non_null(root);
    return root;
}

static void test_cli_json(void **state) {
    (void)state;
    cJSON *root = run_json(DIR "/ref " DIR "/test");
    assert_float_equal(json_number(root, "compared"), PIXELS, 0);
    assert_float_equal(json_number(root, "false_shadow_percent"), 7.8125, 1e-12);
    assert_float_equal(json_number(root, "false_lit_percent"), 4.6875, 1e-12);
    assert_float_equal(json_number(root, "misclassified_percent"), 12.5, 1e-12);
    /* 4 x 1 + 0.01 + 2 x 1 + 0.01 + 10 x 0.25 */
    assert_float_equal(json_number(root, "mean_abs_error"), (8.5 + 2 * (0.5 - 0.49f)) / PIXELS, 1e-12);
    /* Umbra: 2 x 1 + 10 x 0.25; penumbra (0.5, 0.49, 0.5): 2 x 0.01; lit:
     * 4 x 1 over the other 49. */
    assert_float_equal(json_number(root, "umbra_pixels"), 12, 0);
    assert_float_equal(json_number(root, "penumbra_pixels"), 3, 0);
    assert_float_equal(json_number(root, "lit_pixels"), 49, 0);
    assert_float_equal(json_number(root, "umbra_mae"), 4.5 / 12, 1e-12);
    assert_float_equal(json_number(root, "penumbra_mae"), 2 * (0.5 - 0.49f) / 3, 1e-12);
    assert_float_equal(json_number(root, "lit_mae"), 4.0 / 49, 1e-12);
    cJSON_Delete(root);
    /* A class with no pixel: null, not 0. */
    root = run_json(DIR "/moved " DIR "/moved");
    assert_true(cJSON_IsNull(cJSON_GetObjectItemCaseSensitive(root, "umbra_mae")));
    assert_true(cJSON_IsNull(cJSON_GetObjectItemCaseSensitive(root, "penumbra_mae")));
    assert_float_equal(json_number(root, "penumbra_pixels"), 0, 0);
    assert_float_equal(json_number(root, "lit_mae"), 0, 0);
    assert_float_equal(json_number(root, "lit_pixels"), PIXELS, 0);
    cJSON_Delete(root);
}

/* Every pixel is ground: the box has none, so nothing is compared on it. */
static void test_cli_receiver(void **state) {
    (void)state;
    cJSON *ground = run_json(DIR "/ref " DIR "/test --receiver=ground");
    assert_float_equal(json_number(ground, "compared"), PIXELS, 0);
    assert_float_equal(json_number(ground, "false_shadow_percent"), 7.8125, 1e-12);
    cJSON_Delete(ground);
    expect_failure(DIR "/ref " DIR "/test --receiver box --json", EXIT_NOTHING_COMPARED, "nothing compared",
                   "on box");
}

static void test_cli_heatmap(void **state) {
    (void)state;
    char out[4096];
    assert_int_equal(run_shadowdiff("--heatmap " DIR "/heat.png " DIR "/ref " DIR "/test", out, sizeof out), 0);
    int width, height;
    unsigned char *rgba = image_read_png(DIR "/heat.png", &width, &height);
    assert_non_null(rgba);
    assert_int_equal(width, SIZE);
    assert_int_equal(height, SIZE);
    assert_rgba(rgba, 0, 255, 0, 0);
    assert_rgba(rgba, 10, 0, 0, 255);
    assert_rgba(rgba, 63, 255, 255, 255);
    free(rgba);
}

/* No figure on stdout: a script reading it must not find a zero. */
static void test_cli_nothing_compared_fails(void **state) {
    (void)state;
    char out[4096];
    expect_failure(DIR "/ref " DIR "/far", EXIT_NOTHING_COMPARED, DIR "/ref and " DIR "/far", "nothing compared");
    assert_int_equal(run_shadowdiff(DIR "/ref " DIR "/far --json", out, sizeof out), EXIT_NOTHING_COMPARED);
    assert_string_equal(out, "");
}

static void test_cli_non_finite_fails(void **state) {
    (void)state;
    char out[4096];
    expect_failure(DIR "/ref " DIR "/nan", EXIT_NOT_FINITE, DIR "/nan/visibility.pfm: nan at pixel (3, 1)",
                   "where a surface is seen");
    expect_failure(DIR "/inf " DIR "/test --json", EXIT_NOT_FINITE, DIR "/inf/depth.pfm: inf at pixel (3, 1)",
                   "broken dump");
    assert_int_equal(run_shadowdiff(DIR "/ref " DIR "/nan", out, sizeof out), EXIT_NOT_FINITE);
    assert_string_equal(out, "");
}

/* DIR/test misclassifies one pixel in eight (12.5 in percent, the flag's
 * unit): over 12 and 0, not over 12.5 or 100. The
 * report comes first, whole, as without the flag. */
static void test_cli_max_misclassified(void **state) {
    (void)state;
    char out[4096];
    const char *within[] = {"12.5", "100", "12.6"};
    for (size_t i = 0; i < sizeof within / sizeof *within; i++) {
        char args[256];
        snprintf(args, sizeof args, DIR "/ref " DIR "/test --max-misclassified %s", within[i]);
        assert_int_equal(run_shadowdiff(args, out, sizeof out), 0);
        assert_string_equal(err, "");
        assert_int_equal(support_count_lines(out), TEXT_LINES);
    }
    const char *over[] = {"12", "0", "12.49"};
    for (size_t i = 0; i < sizeof over / sizeof *over; i++) {
        char args[256];
        snprintf(args, sizeof args, DIR "/ref " DIR "/test --max-misclassified=%s", over[i]);
        assert_int_equal(run_shadowdiff(args, out, sizeof out), EXIT_OVER_MAX);
        assert_int_equal(support_count_lines(out), TEXT_LINES);
        assert_non_null(strstr(out, "12.500 %"));
        assert_int_equal(support_count_lines(err), 1);
        assert_non_null(strstr(err, DIR "/test: misclassified 12.500 % is over --max-misclassified"));
    }
    assert_int_equal(run_shadowdiff(DIR "/ref " DIR "/test --json --max-misclassified 1", out, sizeof out),
                     EXIT_OVER_MAX);
    cJSON *root = cJSON_Parse(out);
    assert_non_null(root);
    assert_float_equal(json_number(root, "misclassified_percent"), 12.5, 1e-12);
    cJSON_Delete(root);
    /* Nothing compared is its own failure, whatever the limit. */
    expect_failure(DIR "/ref " DIR "/far --max-misclassified 100", EXIT_NOTHING_COMPARED, DIR "/far",
                   "nothing compared");
}

static void test_cli_usage_errors(void **state) {
    (void)state;
    expect_failure(DIR "/ref " DIR "/test --bogus", EXIT_USAGE, "unknown flag", "--bogus");
    expect_failure(DIR "/ref " DIR "/test --receiver", EXIT_USAGE, "missing value", "--receiver");
    expect_failure(DIR "/ref", EXIT_USAGE, "two dump directories", "REF_DIR");
    expect_failure(DIR "/ref " DIR "/test " DIR "/far", EXIT_USAGE, "two dump directories", DIR "/far");
    expect_failure(DIR "/ref " DIR "/test --json=yes", EXIT_USAGE, "takes no value", "--json");
    expect_failure(DIR "/ref " DIR "/test --grazing 90", EXIT_USAGE, "--grazing", "'90'");
    expect_failure(DIR "/ref " DIR "/test --max-misclassified 101", EXIT_USAGE, "--max-misclassified", "'101'");
    expect_failure(DIR "/ref " DIR "/test --max-misclassified -1", EXIT_USAGE, "--max-misclassified", "'-1'");
    expect_failure(DIR "/ref " DIR "/test --max-misclassified 5%", EXIT_USAGE, "--max-misclassified", "'5%'");
}

static void test_cli_runtime_errors(void **state) {
    (void)state;
    expect_failure(DIR "/ref " DIR "/none", EXIT_RUNTIME, DIR "/none/meta.json", "No such file");
    expect_failure(DIR "/ref " DIR "/small", EXIT_RUNTIME, DIR "/small", "8x8 and 8x4");
    expect_failure(DIR "/ref " DIR "/moved", EXIT_RUNTIME, DIR "/moved", "lit differently");
    expect_failure(DIR "/ref " DIR "/test --receiver teapot", EXIT_RUNTIME, "teapot", "objects: ground, box");
    expect_failure(DIR "/ref " DIR "/test --heatmap " DIR "/none/heat.png", EXIT_RUNTIME, DIR "/none/heat.png",
                   "cannot write");
}

#define SHIMMER_ARGS DIR "/shimmer_ref1 " DIR "/shimmer_test1 --previous " DIR "/shimmer_ref0 " DIR "/shimmer_test0"

/* --previous adds the shimmer to the current frame's report, in text and
 * JSON; the previous dumps' problems are the comparison's. */
static void test_cli_shimmer(void **state) {
    (void)state;
    char out[4096];
    assert_int_equal(run_shadowdiff(SHIMMER_ARGS, out, sizeof out), 0);
    assert_string_equal(err, "");
    assert_int_equal(support_count_lines(out), SHIMMER_TEXT_LINES);
    assert_non_null(strstr(out, "shimmer          1.786 % (1 of 56 followed pixels"));
    assert_non_null(strstr(out, "truth changed    0.000 % (0:"));
    assert_non_null(strstr(out, "false shadow     1.562 % (1:"));
    cJSON *root = run_json(SHIMMER_ARGS);
    assert_float_equal(json_number(root, "shimmer_percent"), 100.0 / SHIMMER_FOLLOWED, 1e-12);
    assert_float_equal(json_number(root, "followed"), SHIMMER_FOLLOWED, 0);
    assert_float_equal(json_number(root, "shimmered"), 1, 0);
    assert_float_equal(json_number(root, "truth_changed"), 0, 0);
    assert_float_equal(json_number(root, "compared"), PIXELS, 0);
    cJSON_Delete(root);
    /* Without --previous, no shimmer in the JSON. */
    root = run_json(DIR "/shimmer_ref1 " DIR "/shimmer_test1");
    assert_null(cJSON_GetObjectItemCaseSensitive(root, "shimmer_percent"));
    cJSON_Delete(root);
    expect_failure(DIR "/shimmer_ref1 " DIR "/shimmer_test1 --previous " DIR "/shimmer_ref0", EXIT_USAGE,
                   "--previous", "PREV_REF_DIR PREV_TEST_DIR");
    expect_failure(DIR "/shimmer_ref1 " DIR "/shimmer_test1 --previous " DIR "/shimmer_ref0 " DIR "/none",
                   EXIT_RUNTIME, DIR "/none/meta.json", "No such file");
    expect_failure(DIR "/shimmer_ref1 " DIR "/shimmer_test1 --previous " DIR "/shimmer_ref0 " DIR "/shimmer_test1",
                   EXIT_RUNTIME, DIR "/shimmer_ref0 and " DIR "/shimmer_test1", "different cameras");
    /* DIR/ref's camera is no camera at all: nothing lands in its picture. */
    expect_failure(DIR "/shimmer_ref1 " DIR "/shimmer_test1 --previous " DIR "/ref " DIR "/test --json",
                   EXIT_NOTHING_COMPARED, "no compared pixel followed", "no shimmer figure");
    expect_failure(DIR "/shimmer_ref1 " DIR "/shimmer_test1 --previous " DIR "/ref " DIR "/nan", EXIT_NOT_FINITE,
                   DIR "/nan/visibility.pfm: nan", "broken dump");
}

static void test_cli_help(void **state) {
    (void)state;
    char out[4096];
    assert_int_equal(run_shadowdiff("--help", out, sizeof out), 0);
    assert_non_null(strstr(out, "red false shadow"));
    assert_non_null(strstr(out, "blue false lit"));
    assert_non_null(strstr(out, "--max-misclassified P"));
    assert_non_null(strstr(out, "Exit status: 0 compared; 1 a dump unreadable"));
    assert_non_null(strstr(out, "4 nothing compared"));
    assert_non_null(strstr(out, "--previous PREV_REF_DIR PREV_TEST_DIR"));
    assert_non_null(strstr(out, "shimmer % is the share of followed pixels"));
    assert_non_null(strstr(out, "5 a dump\nholds NaN"));
    assert_non_null(strstr(out, "umbra\n(v <= 1/32), lit (v >= 31/32) and penumbra"));
    assert_non_null(strstr(out, "\"none\" (JSON null)"));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_counts_false_shadow_and_false_lit),
        cmocka_unit_test(test_mean_abs_error_on_fractions),
        cmocka_unit_test(test_channel_mae_of_coloured_dumps),
        cmocka_unit_test(test_excludes_pixels_without_surface_in_either),
        cmocka_unit_test(test_depth_tolerance),
        cmocka_unit_test(test_excludes_back_facing_point_light),
        cmocka_unit_test(test_excludes_back_facing_directional_light),
        cmocka_unit_test(test_grazing_leaves_out_near_edge_on),
        cmocka_unit_test(test_edge_on_within_rounding_left_out),
        cmocka_unit_test(test_receiver_restricts),
        cmocka_unit_test(test_classes_name_the_fault),
        cmocka_unit_test(test_class_bounds),
        cmocka_unit_test(test_classes_pool),
        cmocka_unit_test(test_nothing_compared_is_an_error),
        cmocka_unit_test(test_non_finite_is_an_error),
        cmocka_unit_test(test_heatmap_colours),
        cmocka_unit_test(test_rejects_inconsistent_dumps),
        cmocka_unit_test(test_dump_round_trip),
        cmocka_unit_test(test_shimmer_still_camera_follows_every_pixel),
        cmocka_unit_test(test_shimmer_counts_flips_where_the_truth_is_still),
        cmocka_unit_test(test_shimmer_leaves_out_disocclusions),
        cmocka_unit_test(test_shimmer_honours_the_edge_on_rule),
        cmocka_unit_test(test_shimmer_problems),
        cmocka_unit_test(test_cli_text_report),
        cmocka_unit_test(test_cli_json),
        cmocka_unit_test(test_cli_receiver),
        cmocka_unit_test(test_cli_heatmap),
        cmocka_unit_test(test_cli_nothing_compared_fails),
        cmocka_unit_test(test_cli_non_finite_fails),
        cmocka_unit_test(test_cli_max_misclassified),
        cmocka_unit_test(test_cli_usage_errors),
        cmocka_unit_test(test_cli_runtime_errors),
        cmocka_unit_test(test_cli_shimmer),
        cmocka_unit_test(test_cli_help),
    };
    return cmocka_run_group_tests(tests, write_cli_dumps, NULL);
}
