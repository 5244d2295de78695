/* The texel rule both sides apply (common/data/texture.h): the mip chain
 * averaged in linear light, bilinear between texel centres, the level of
 * detail from the footprint, trilinear between levels, OpenGL's wrap
 * modes, and images that are not one refused in one line. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"
#include "texture.h"

#define TEXTURE_TEST_TOLERANCE 1e-5f

static void assert_near(float got, float expected, const char *what) {
    if (fabsf(got - expected) > TEXTURE_TEST_TOLERANCE)
        fail_msg("%s: %g, expected %g", what, got, expected);
}

/* A width x height texture of the greys `codes` (sRGB), alpha 255. */
static void make_greys(texture *t, int width, int height, const unsigned char *codes) {
    unsigned char *rgba = malloc(4 * (size_t)width * (size_t)height);
    assert_non_null(rgba);
    for (int i = 0; i < width * height; i++) {
        memset(rgba + 4 * i, codes[i], 3);
        rgba[4 * i + 3] = 255;
    }
    assert_true(texture_from_pixels(t, "greys", width, height, rgba));
    free(rgba);
}

/* Black and white average to half the light, sRGB code 188, not 128;
 * alpha averages as it is. Each level halves the one above, rounded
 * down. */
static void test_mips_average_linear_light(void **state) {
    (void)state;
    unsigned char rgba[4 * 4] = {0, 0, 0, 0, 255, 255, 255, 255, 255, 255, 255, 255, 0, 0, 0, 0};
    texture t;
    assert_true(texture_from_pixels(&t, "checker", 2, 2, rgba));
    assert_int_equal(t.level_count, 2);
    assert_int_equal(t.levels[1].width, 1);
    assert_int_equal(t.levels[1].rgba[0], texture_linear_to_srgb(0.5f));
    assert_int_equal(t.levels[1].rgba[0], 188);
    assert_int_equal(t.levels[1].rgba[3], 128);
    texture_free(&t);
    static const unsigned char codes[5 * 3] = {0};
    make_greys(&t, 5, 3, codes);
    static const int sizes[][2] = {{5, 3}, {2, 1}, {1, 1}};
    assert_int_equal(t.level_count, 3);
    for (int l = 0; l < 3; l++) {
        assert_int_equal(t.levels[l].width, sizes[l][0]);
        assert_int_equal(t.levels[l].height, sizes[l][1]);
    }
    texture_free(&t);
}

/* At a texel's centre the texel itself; halfway between two, the mean of
 * their light; rows from v = 0 up. */
static void test_bilinear_between_texel_centres(void **state) {
    (void)state;
    static const unsigned char codes[2 * 2] = {0, 255, 100, 200}; /* bottom row first */
    texture t;
    make_greys(&t, 2, 2, codes);
    float rgba[4];
    texture_sample(&t, (const float[2]){0.25f, 0.25f}, 0, rgba);
    assert_near(rgba[0], 0, "bottom left");
    texture_sample(&t, (const float[2]){0.75f, 0.75f}, 0, rgba);
    assert_near(rgba[0], texture_srgb_to_linear(200), "top right");
    texture_sample(&t, (const float[2]){0.5f, 0.25f}, 0, rgba);
    assert_near(rgba[0], 0.5f, "between black and white");
    assert_near(rgba[3], 1, "alpha");
    texture_free(&t);
}

/* The footprint in level-0 texels: one texel is level 0, four level 2; a
 * footprint between two levels blends them by its fraction. */
static void test_level_of_detail(void **state) {
    (void)state;
    unsigned char codes[8 * 8];
    for (int i = 0; i < 64; i++)
        codes[i] = (unsigned char)((i % 8 + i / 8) % 2 ? 255 : 0);
    texture t;
    make_greys(&t, 8, 8, codes);
    assert_near(texture_lod(&t, (const float[2]){1 / 8.0f, 0}, (const float[2]){0, 1 / 8.0f}), 0, "one texel");
    assert_near(texture_lod(&t, (const float[2]){0, 0}, (const float[2]){0, 4 / 8.0f}), 2, "four texels");
    float level1[4], level2[4], between[4];
    const float uv[2] = {0.3f, 0.6f};
    texture_sample(&t, uv, 1, level1);
    texture_sample(&t, uv, 2, level2);
    texture_sample(&t, uv, 1.25f, between);
    assert_near(between[0], 0.75f * level1[0] + 0.25f * level2[0], "a quarter of the way to level 2");
    texture_sample(&t, uv, 99, between);
    assert_near(between[0], texture_srgb_to_linear(texture_linear_to_srgb(0.5f)), "beyond the last level: the last");
    texture_free(&t);
}

/* GL_REPEAT, GL_MIRRORED_REPEAT and GL_CLAMP_TO_EDGE of a ramp. */
static void test_wrap_modes(void **state) {
    (void)state;
    static const unsigned char codes[4] = {0, 80, 160, 240};
    static const struct {
        texture_wrap wrap;
        float u, same_as;
    } cases[] = {
        {TEXTURE_REPEAT, 1.375f, 0.375f},          {TEXTURE_REPEAT, -0.875f, 0.125f},
        {TEXTURE_MIRRORED_REPEAT, 1.375f, 0.625f}, {TEXTURE_MIRRORED_REPEAT, -0.125f, 0.125f},
        {TEXTURE_MIRRORED_REPEAT, 2.375f, 0.375f}, {TEXTURE_CLAMP_TO_EDGE, 1.6f, 0.875f},
        {TEXTURE_CLAMP_TO_EDGE, -3.0f, 0.125f},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        texture t;
        make_greys(&t, 4, 1, codes);
        t.wrap[0] = cases[i].wrap;
        float a[4], b[4];
        texture_sample(&t, (const float[2]){cases[i].u, 0.5f}, 0, a);
        texture_sample(&t, (const float[2]){cases[i].same_as, 0.5f}, 0, b);
        char what[64];
        snprintf(what, sizeof what, "wrap %d at u %g", cases[i].wrap, cases[i].u);
        assert_near(a[0], b[0], what);
        texture_free(&t);
    }
}

/* Bytes that are no image, and an image too large, are one line naming
 * them. */
static void test_not_an_image(void **state) {
    (void)state;
    static const unsigned char garbage[] = "not a PNG at all";
    texture t;
    support_capture_stderr();
    bool made = texture_from_memory(&t, "scene.gltf: embedded image 0", garbage, sizeof garbage);
    const char *said = support_release_stderr();
    assert_false(made);
    assert_int_equal(t.level_count, 0);
    assert_int_equal(strncmp(said, "scene.gltf: embedded image 0: not an image", 42), 0);
    assert_int_equal(support_count_lines(said), 1);
    /* A PNG header claiming 10000 x 10000 texels: refused from the header,
     * before anything is allocated. */
    static const unsigned char huge[] = {
        0x89, 'P', 'N',  'G',  '\r', '\n', 0x1a, '\n',                             /* the signature */
        0,    0,   0,    13,   'I',  'H',  'D',  'R',                              /* the header's length and type */
        0,    0,   0x27, 0x10, 0,    0,    0x27, 0x10, 8, 6, 0, 0, 0, 0, 0, 0, 0}; /* 10000 x 10000, RGBA8 */
    support_capture_stderr();
    made = texture_from_memory(&t, "huge.png", huge, sizeof huge);
    said = support_release_stderr();
    assert_false(made);
    char expected[128];
    snprintf(expected, sizeof expected, "huge.png: a 10000x10000 image: textures take 1 to %d texels a side\n",
             TEXTURE_MAX_SIZE);
    assert_string_equal(said, expected);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mips_average_linear_light),
        cmocka_unit_test(test_bilinear_between_texel_centres),
        cmocka_unit_test(test_level_of_detail),
        cmocka_unit_test(test_wrap_modes),
        cmocka_unit_test(test_not_an_image),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
