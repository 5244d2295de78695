/* Tests of common/data/path.c: the names the window's screenshots get. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "path.h"

#define DIR "out/test/path"

static void touch(const char *path) {
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fclose(f);
}

/* Each name is the first unused, whatever an earlier run left. */
static void test_numbered_names_never_overwrite(void **state) {
    (void)state;
    assert_true(path_make_directories(DIR));
    char path[256];
    for (int n = 1; n <= 3; n++) {
        snprintf(path, sizeof path, DIR "/shot-%d.png", n);
        unlink(path);
    }
    assert_true(path_numbered_unused(DIR "/shot", "png", path, sizeof path));
    assert_string_equal(path, DIR "/shot-1.png");
    touch(path);
    touch(DIR "/shot-3.png");
    assert_true(path_numbered_unused(DIR "/shot", "png", path, sizeof path));
    assert_string_equal(path, DIR "/shot-2.png");
    touch(path);
    assert_true(path_numbered_unused(DIR "/shot", "png", path, sizeof path));
    assert_string_equal(path, DIR "/shot-4.png");
    char small[8];
    assert_false(path_numbered_unused(DIR "/shot", "png", small, sizeof small));
}

static void test_stem(void **state) {
    (void)state;
    char stem[16];
    assert_true(path_stem("assets/scenes/simple.json", stem, sizeof stem));
    assert_string_equal(stem, "simple");
    assert_false(path_stem("a/very_long_scene_name.json", stem, sizeof stem));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_numbered_names_never_overwrite),
        cmocka_unit_test(test_stem),
    };
    return cmocka_run_group_tests_name("path", tests, NULL, NULL);
}
