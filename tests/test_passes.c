/* The shading passes (technique.h, "The shading passes"): after a depth
 * pre-pass the shadow maps shade every light in one pass, the stencil
 * techniques each light once on what it reaches, the first light that is
 * on with the ambient term. Where nothing casts, every technique's
 * picture must then be the unshadowed one: the ambient term drawn once on
 * every object in view, each light added once, in full, inside and
 * outside its rectangle. Each pass rounds its sum to 8 bits, so a pixel
 * of a stencil technique may differ by up to one step per light shaded
 * after the first, and by no more; the one pass of the shadow maps is the
 * unshadowed picture's own sum, exactly. The scene (tests/data/passes_no_casters.json) has a light that
 * reaches nothing (so a later one carries the ambient term), then a spot
 * whose small range lights only the ball (an ambient pass cut to its
 * rectangle would show), a point light with a range, a directional light and an object that takes
 * no shadows. With no light in reach (tests/data/passes_unlit.json) the
 * ambient term alone (shading_ambient) must be the floor's too;
 * with --no-skip every light is shaded, the one out of reach first. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "registry.h"
#include "shading.h"
#include "support.h"

#define OUT "out/test/passes"
#define PASSES_LIT "tests/data/passes_no_casters.json"
#define PASSES_UNLIT "tests/data/passes_unlit.json"
/* PASSES_LIT's lights: light 0 reaches nothing in view. */
#define PASSES_LIGHTS 4

/* The cases: a scene, the flags, and how many 8-bit steps a pixel of a
 * stencil technique may be off the floor's (a step per light shaded after
 * the first). */
static const struct {
    const char *name, *scene, *flags;
    int tolerance;
} passes_cases[] = {
    {"lit", PASSES_LIT, "", PASSES_LIGHTS - 2},
    {"lit_no_skip", PASSES_LIT, "--no-skip", PASSES_LIGHTS - 1},
    {"unlit", PASSES_UNLIT, "", 0},
    {"unlit_no_skip", PASSES_UNLIT, "--no-skip", 0},
};

/* The techniques that shade every light in one pass. */
static const char *const passes_one_pass[] = {"shadowmap", "psm", "cascades"};

static bool passes_is_one_pass(const char *technique) {
    for (size_t i = 0; i < sizeof passes_one_pass / sizeof *passes_one_pass; i++)
        if (strcmp(technique, passes_one_pass[i]) == 0)
            return true;
    return false;
}

static unsigned char *passes_picture(const char *program, size_t c, int *w, int *h) {
    char dir[512], path[600];
    snprintf(dir, sizeof dir, OUT "/%s_%s", program, passes_cases[c].name);
    assert_int_equal(support_dump(program, passes_cases[c].scene, passes_cases[c].flags, dir), 0);
    snprintf(path, sizeof path, "%s/color.png", dir);
    unsigned char *rgba = image_read_png(path, w, h);
    assert_non_null(rgba);
    return rgba;
}

static void test_passes_match_unshadowed(void **state) {
    (void)state;
    for (size_t c = 0; c < sizeof passes_cases / sizeof *passes_cases; c++) {
        int w, h;
        unsigned char *floor = passes_picture("unshadowed", c, &w, &h);
        for (int t = 0; t < registry_technique_count; t++) {
            const char *name = registry_techniques[t]->name;
            if (registry_techniques[t]->cost_floor)
                continue;
            int tw, th, worst = 0;
            unsigned char *picture = passes_picture(name, c, &tw, &th);
            assert_true(tw == w && th == h);
            for (long i = 0; i < (long)w * h * 4; i++)
                if (i % 4 != 3 && abs(picture[i] - floor[i]) > worst)
                    worst = abs(picture[i] - floor[i]);
            int tolerance = passes_is_one_pass(name) ? 0 : passes_cases[c].tolerance;
            fprintf(stderr, "    %s, %s: at most %d/255 off the unshadowed picture (allowed %d)\n", name,
                    passes_cases[c].name, worst, tolerance);
            assert_true(worst <= tolerance);
            free(picture);
        }
        free(floor);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_passes_match_unshadowed)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
