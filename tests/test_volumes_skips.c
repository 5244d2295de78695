/* Shadow volumes' skips never change a decision (README, "Skips"): with
 * caster culling, the view-frustum skip and the kept volumes on, and with
 * --no-skip, the last of three frames dumps the same bytes (visibility,
 * depth, the picture), on the city with the light moving (so that kept
 * volumes are dropped when the light moves) in every counting mode and
 * silhouette path, and on bunny and teapot (tests/test_skip.c has the
 * defaults on the other scenes and motions). And the skips do skip: on the
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

static const char *const dump_files[] = {"visibility.pfm", "depth.pfm", "color.png"};

/* Three frames of `scene` with `flags` and `--motion motion`, skips on and
 * off: the same dump. */
static void assert_same_with_and_without_skips(const char *scene, const char *motion, const char *flags,
                                               const char *name) {
    char on_flags[256], off_flags[512], on[256], off[256];
    snprintf(on_flags, sizeof on_flags, "--frames 3 --motion %s %s", motion, flags);
    snprintf(off_flags, sizeof off_flags, "%s --no-skip", on_flags);
    snprintf(on, sizeof on, OUT "/%s_on", name);
    snprintf(off, sizeof off, OUT "/%s_off", name);
    assert_int_equal(support_dump("volumes", scene, on_flags, on), 0);
    assert_int_equal(support_dump("volumes", scene, off_flags, off), 0);
    const char *differs = support_first_difference(on, off, dump_files, sizeof dump_files / sizeof *dump_files);
    if (differs)
        fail_msg("%s: %s differs between %s and %s", name, differs, on, off);
    printf("    %-12s: identical with and without skips\n", name);
}

/* Forced z-fail (caps kept and reused), forced z-pass and the geometry
 * shader's silhouettes, the light moving. */
static void test_city_every_mode(void **state) {
    (void)state;
    assert_same_with_and_without_skips(CITY, "light", "--mode zfail", "city_zfail");
    assert_same_with_and_without_skips(CITY, "light", "--mode zpass", "city_zpass");
    assert_same_with_and_without_skips(CITY, "light", "--silhouette gpu", "city_gpu");
}

static void test_bunny_and_teapot(void **state) {
    (void)state;
    static const char *const scenes[] = {"bunny", "teapot"};
    for (size_t s = 0; s < sizeof scenes / sizeof *scenes; s++) {
        char path[256];
        snprintf(path, sizeof path, "assets/scenes/%s.json", scenes[s]);
        assert_same_with_and_without_skips(path, "light", "", scenes[s]);
    }
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
        cmocka_unit_test(test_city_casters_culled),
        cmocka_unit_test(test_city_every_mode),
        cmocka_unit_test(test_bunny_and_teapot),
    };
    return cmocka_run_group_tests_name("shadow volumes' skips", tests, NULL, NULL);
}
