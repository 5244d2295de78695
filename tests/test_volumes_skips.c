/* Shadow volumes' skips never change a decision (README, "Skips"): with
 * caster culling, the view-frustum skip and the kept volumes on, and with
 * --no-skip, the last of three frames dumps the same bytes (visibility,
 * depth, the picture), on the city with the light moving (so that kept
 * volumes are dropped when the light moves) in every counting mode and
 * silhouette path, on bunny and teapot (tests/test_skip.c has the
 * defaults on the other scenes and motions), and for every point of an
 * area light (each with its own plan and kept volumes, kept while the
 * camera moves and dropped when the light does). And the skips do skip: on the
 * city every light in reach counts each caster once, and culls most. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"

#define OUT "out/test/volumes_skips"
#define CITY "assets/scenes/city_1000.json"
#define CITY_CASTERS 1000
#define CITY_LIGHTS 7

static const char *const dump_files[] = {"visibility.pfm", "depth.pfm", "ids.pfm", "color.png"};

/* tests/test_skip.c's size for its runs with and without the skips: what
 * a skip leaves out does not depend on the pixels, and a small frame keeps
 * the runs short (a volume's cost is mostly its fill). */
#define DUMP_SIZE "--size 320x180"

/* Three frames of `scene` at DUMP_SIZE with `flags` and `--motion motion`,
 * and with `off` (flags turning skips off) too: the same dump. */
static void assert_same_with_and_without(const char *scene, const char *motion, const char *flags,
                                         const char *off_flag, const char *name) {
    char on_flags[256], off_flags[512], on[256], off[256];
    snprintf(on_flags, sizeof on_flags, DUMP_SIZE " --frames 3 --motion %s %s", motion, flags);
    snprintf(off_flags, sizeof off_flags, "%s %s", on_flags, off_flag);
    snprintf(on, sizeof on, OUT "/%s_on", name);
    snprintf(off, sizeof off, OUT "/%s_off", name);
    assert_int_equal(support_dump("volumes", scene, on_flags, on), 0);
    assert_int_equal(support_dump("volumes", scene, off_flags, off), 0);
    const char *differs = support_first_difference(on, off, dump_files, sizeof dump_files / sizeof *dump_files);
    if (differs)
        fail_msg("%s: %s differs between %s and %s", name, differs, on, off);
    printf("    %-17s: identical with and without %s\n", name, off_flag);
}

/* The depth bounds (GL_EXT_depth_bounds_test, where present) change no
 * decision either: on and off, the same dumps on the city (ranged lights)
 * and on dense; and llvmpipe has no such extension, which the HUD says. */
static void test_depth_bounds(void **state) {
    (void)state;
    const char *renderer = support_verbose_line("volumes", CITY, "", "GL renderer: ");
    assert_non_null(renderer);
    const char *line = support_verbose_line("volumes", CITY, "", "depth bounds ");
    assert_non_null(line);
    bool off = strncmp(line, "depth bounds off (no GL_EXT_depth_bounds_test)", 46) == 0;
    assert_true(off || strncmp(line, "depth bounds on", 15) == 0);
    if (strncmp(renderer, "GL renderer: llvmpipe", 21) == 0)
        assert_true(off);
    printf("    %.*s\n", (int)strcspn(line, "\n"), line);
    assert_same_with_and_without(CITY, "light", "", "--no-depth-bounds", "city_bounds");
    assert_same_with_and_without("assets/scenes/dense.json", "static", "", "--no-depth-bounds", "dense_bounds");
}

/* Forced z-fail (caps kept and reused), forced z-pass, the eye's count
 * and ZP+'s near-plane count (each also with the eye in a shadow and the
 * camera moving) and the geometry shader's silhouettes, the light
 * moving. */
static void test_city_every_mode(void **state) {
    (void)state;
    assert_same_with_and_without(CITY, "light", "--mode zfail", "--no-skip", "city_zfail");
    assert_same_with_and_without(CITY, "light", "--mode zpass", "--no-skip", "city_zpass");
    assert_same_with_and_without(CITY, "light", "--silhouette gpu", "--no-skip", "city_gpu");
    assert_same_with_and_without(CITY, "light", "--mode eye-count", "--no-skip", "city_eye_count");
    assert_same_with_and_without("assets/scenes/eye_in_shadow.json", "camera", "--mode eye-count", "--no-skip",
                                 "eye_in_shadow");
    assert_same_with_and_without(CITY, "light", "--mode zp-plus", "--no-skip", "city_zp_plus");
    assert_same_with_and_without("assets/scenes/eye_in_shadow.json", "camera", "--mode zp-plus", "--no-skip",
                                 "eye_in_shadow_zp_plus");
}

static void test_bunny_and_teapot(void **state) {
    (void)state;
    static const char *const scenes[] = {"bunny", "teapot"};
    for (size_t s = 0; s < sizeof scenes / sizeof *scenes; s++) {
        char path[256];
        snprintf(path, sizeof path, "assets/scenes/%s.json", scenes[s]);
        assert_same_with_and_without(path, "light", "", "--no-skip", scenes[s]);
    }
}

static void test_area_light_points(void **state) {
    (void)state;
    static const char *const motions[] = {"camera", "light"};
    for (size_t m = 0; m < sizeof motions / sizeof *motions; m++) {
        char name[64];
        snprintf(name, sizeof name, "soft_table_%s", motions[m]);
        assert_same_with_and_without("assets/scenes/soft_table.json", motions[m], "--light-samples 16", "--no-skip",
                                     name);
    }
    assert_same_with_and_without("assets/scenes/soft_sun.json", "camera", "--light-samples 16 --mode zfail",
                                 "--no-skip", "soft_sun_zfail");
}

/* The wide count (demos/lib/volume_wide.h) decides as the 8-bit stencil
 * wherever that cannot wrap: on the standard scenes the bound keeps the
 * stencil (the HUD: "stencil: 8-bit exact"), and counting them in the
 * float target anyway (--counter float) gives the same dumps, in every
 * way of counting (z-pass, z-fail, the eye's count, GPU silhouettes, an
 * area light's points, wedges); where a bound passes 255 but no pixel's
 * count reaches 256 (the engine's many parts under z-pass and z-fail, 300
 * staggered casters) the dumps are the same in the stencil
 * (--counter stencil). On stacked_300, whose ground lies in exactly 256
 * volumes, they differ: the comparison can fail. Counted wide, the skips
 * change no decision either (the light moving: each caster's bound is
 * found again for the light's new position), on the slabs and, under
 * z-fail, on the open mesh of 10,000 stacked triangles. The forced cases
 * are swept (support_sweep_stride). The quick tier counts the engine
 * under z-pass alone (tests/test_volumes.c measures the wide count under
 * z-fail against the reference, on volumes deeper than the stencil), and
 * the skips counted wide on the slabs alone (the same bounds found again
 * as the light moves; the mesh's 10,000 volumes over the view are the
 * whole tier's). */
static void test_wide_count_decides_the_same(void **state) {
    (void)state;
    static const char *const standard[] = {"simple", "bunny", "teapot", "long_view"};
    for (size_t s = 0; s < sizeof standard / sizeof *standard; s++) {
        char path[256];
        snprintf(path, sizeof path, "assets/scenes/%s.json", standard[s]);
        const char *line = support_verbose_line("volumes", path, "", "volumes: light 0: ");
        assert_non_null(line);
        const char *counter = strstr(line, "; stencil: 8-bit exact (bound ");
        if (!counter || counter > line + strcspn(line, "\n"))
            fail_msg("%s: the count left the 8-bit stencil: %.*s", standard[s], (int)strcspn(line, "\n"), line);
        printf("    %-9s: %.*s\n", standard[s], (int)strcspn(counter + 2, ";\n"), counter + 2);
    }
    const char *line = support_verbose_line("volumes", "assets/scenes/engine.json", "", "volumes: light 0: ");
    assert_non_null(line);
    assert_non_null(strstr(line, "; count: float"));
    static const struct {
        const char *scene, *motion, *flags, *name;
    } forced[] = {
        {"assets/scenes/teapot.json", "light", "", "teapot_float"},
        {"assets/scenes/bunny.json", "static", "--mode zfail --silhouette gpu", "bunny_float_zfail_gpu"},
        {"assets/scenes/eye_in_shadow.json", "static", "--mode eye-count", "eye_count_float"},
        {"assets/scenes/soft_table.json", "static", "--light-samples 16", "soft_table_float"},
        {"assets/scenes/soft_sun.json", "static", "--soft wedges", "soft_sun_wedges_float"},
    };
    for (size_t i = 0; i < sizeof forced / sizeof *forced; i += (size_t)support_sweep_stride())
        assert_same_with_and_without(forced[i].scene, forced[i].motion, forced[i].flags, "--counter float",
                                     forced[i].name);
    assert_same_with_and_without("assets/scenes/engine.json", "static", "", "--counter stencil", "engine_wide");
    if (support_sweep_stride() == 1)
        assert_same_with_and_without("assets/scenes/engine.json", "static", "--mode zfail", "--counter stencil",
                                     "engine_wide_zfail");
    assert_same_with_and_without("tests/data/volumes_300_casters.json", "light", "", "--counter stencil",
                                 "casters_300_wide");
    assert_same_with_and_without("assets/scenes/stacked_300.json", "light", "", "--no-skip", "stacked_300_skips");
    if (support_sweep_stride() == 1)
        assert_same_with_and_without("assets/scenes/stacked_10000.json", "light", "--mode zfail", "--no-skip",
                                     "stacked_10000_skips");
    char on[256], off[256];
    snprintf(on, sizeof on, OUT "/stacked_wide");
    snprintf(off, sizeof off, OUT "/stacked_wrapped");
    assert_int_equal(support_dump("volumes", "assets/scenes/stacked_300.json", "", on), 0);
    assert_int_equal(support_dump("volumes", "assets/scenes/stacked_300.json", "--counter stencil", off), 0);
    assert_non_null(support_first_difference(on, off, dump_files, 1));
}

static void test_city_casters_culled(void **state) {
    (void)state;
    const char *line = support_verbose_line("volumes", CITY, "", "[X] caster culling: ");
    assert_non_null(line);
    const char *counts = strstr(line, "per light: ");
    assert_non_null(counts);
    counts += strlen("per light: ");
    int lit = 0;
    for (int l = 0; l < CITY_LIGHTS; l++) {
        int light, drawn, culled, length;
        assert_int_equal(sscanf(counts, "%d: %d/%d%n", &light, &drawn, &culled, &length), 3);
        assert_int_equal(light, l);
        counts += length;
        if (drawn + culled == 0)
            continue; /* a light out of the view's reach: skipped */
        lit++;
        assert_int_equal(drawn + culled, CITY_CASTERS);
        assert_true(2 * culled > CITY_CASTERS);
    }
    assert_true(lit > 0);
    printf("    city: %.*s\n", (int)strcspn(line, "\n"), line);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_city_casters_culled), cmocka_unit_test(test_depth_bounds),
        cmocka_unit_test(test_city_every_mode),     cmocka_unit_test(test_bunny_and_teapot),
        cmocka_unit_test(test_area_light_points),   cmocka_unit_test(test_wide_count_decides_the_same),
    };
    return cmocka_run_group_tests_name("shadow volumes' skips", tests, NULL, NULL);
}
