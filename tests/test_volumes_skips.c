/* Shadow volumes' skips never change a decision (README, "Skips"): with
 * caster culling, the view-frustum skip and the kept volumes on, and with
 * --no-skip, the last of three frames dumps the same bytes (visibility,
 * depth, the picture), on the city static and with the light or the
 * camera moving (so that kept volumes are reused, and dropped when the
 * light moves), in every counting mode and silhouette path, and on the
 * standard and dense scenes. And the skips do skip: on the city every
 * light counts each caster once, and culls most. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "path.h"
#include "support.h"

#define OUT "out/test/volumes_skips"
#define CITY "assets/scenes/city_1000.json"
#define CITY_CASTERS 1000
#define CITY_LIGHTS 7
#define MAX_DUMP_BYTES (64 << 20)

static const char *const dump_files[] = {"visibility.pfm", "depth.pfm", "color.png"};

static bool same_file(const char *a_dir, const char *b_dir, const char *name) {
    char a_path[512], b_path[512];
    snprintf(a_path, sizeof a_path, "%s/%s", a_dir, name);
    snprintf(b_path, sizeof b_path, "%s/%s", b_dir, name);
    size_t a_length, b_length;
    char *a = path_read_text(a_path, MAX_DUMP_BYTES, &a_length), *b = path_read_text(b_path, MAX_DUMP_BYTES, &b_length);
    bool same = a && b && a_length == b_length && memcmp(a, b, a_length) == 0;
    free(a);
    free(b);
    return same;
}

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
    for (size_t f = 0; f < sizeof dump_files / sizeof *dump_files; f++)
        if (!same_file(on, off, dump_files[f]))
            fail_msg("%s: %s differs between %s and %s", name, dump_files[f], on, off);
    printf("    %-12s: identical with and without skips\n", name);
}

static void test_city_every_motion(void **state) {
    (void)state;
    static const char *const motions[] = {"static", "light", "camera"};
    for (size_t m = 0; m < sizeof motions / sizeof *motions; m++) {
        char name[64];
        snprintf(name, sizeof name, "city_%s", motions[m]);
        assert_same_with_and_without_skips(CITY, motions[m], "", name);
    }
}

/* Forced z-fail (caps kept and reused), forced z-pass and the geometry
 * shader's silhouettes, the light moving. */
static void test_city_every_mode(void **state) {
    (void)state;
    assert_same_with_and_without_skips(CITY, "light", "--mode zfail", "city_zfail");
    assert_same_with_and_without_skips(CITY, "light", "--mode zpass", "city_zpass");
    assert_same_with_and_without_skips(CITY, "light", "--silhouette gpu", "city_gpu");
}

static void test_standard_and_dense_scenes(void **state) {
    (void)state;
    static const char *const scenes[] = {"simple", "bunny", "teapot", "dense"};
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
    for (int l = 0; l < CITY_LIGHTS; l++) {
        int light, drawn, culled, length;
        assert_int_equal(sscanf(counts, "%d: %d/%d%n", &light, &drawn, &culled, &length), 3);
        assert_int_equal(light, l);
        assert_int_equal(drawn + culled, CITY_CASTERS);
        assert_true(2 * culled > CITY_CASTERS);
        counts += length;
    }
    printf("    city: %.*s\n", (int)strcspn(line, "\n"), line);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_city_casters_culled),
        cmocka_unit_test(test_city_every_motion),
        cmocka_unit_test(test_city_every_mode),
        cmocka_unit_test(test_standard_and_dense_scenes),
    };
    return cmocka_run_group_tests_name("shadow volumes' skips", tests, NULL, NULL);
}
