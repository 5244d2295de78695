/* recipe_probe's accuracy cases (tests/recipe/follow.sh copies this file
 * to tests/test_recipe_probe.c, as README's "Adding a technique" asks):
 * against the reference on the standard scenes, a technique that draws no
 * shadow darkens no pixel the reference lights, and misses its shadows. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>

#include "support.h"

static const char *const recipe_probe_scenes[] = {"simple", "bunny", "teapot"};

static void test_no_false_shadow_on_standard_scenes(void **state) {
    (void)state;
    for (size_t i = 0; i < sizeof recipe_probe_scenes / sizeof *recipe_probe_scenes; i++) {
        char path[256];
        snprintf(path, sizeof path, "assets/scenes/%s.json", recipe_probe_scenes[i]);
        shadowdiff_result r = support_measure("recipe_probe", path, "", "", recipe_probe_scenes[i]);
        assert_true(r.compared > SUPPORT_STANDARD_MIN_COMPARED);
        assert_true(r.false_shadow_percent == 0);
        assert_true(r.false_lit_percent > 0);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_no_false_shadow_on_standard_scenes),
    };
    return cmocka_run_group_tests_name("recipe_probe against the reference", tests, NULL, NULL);
}
