/* Tests of common/data/path.c: the names the window's screenshots get,
 * the order it pages through scenes in. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "path.h"
#include "scene.h"

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

/* Page Up/Down's order: the directory's scene files (.json, .gltf, .glb
 * in any case) by name, wrapping. */
static void test_next_in_directory(void **state) {
    (void)state;
    assert_true(path_make_directories(DIR "/pages") && path_make_directories(DIR "/empty"));
    static const char *const files[] = {"b.json", "a.json", "c.txt", "d.json", "e.gltf", "f.GLB", "g.gltf.txt"};
    char path[256];
    for (size_t i = 0; i < sizeof files / sizeof *files; i++) {
        snprintf(path, sizeof path, DIR "/pages/%s", files[i]);
        touch(path);
    }
    static const struct {
        const char *from;
        int step;
        const char *to;
    } cases[] = {
        {"b.json", 1, "d.json"}, {"d.json", 1, "e.gltf"}, {"f.GLB", 1, "a.json"},  {"a.json", -1, "f.GLB"},
        {"a.json", 2, "d.json"}, {"c.txt", 1, "a.json"},  {"x.json", -1, "f.GLB"}, {"f.GLB", -3, "b.json"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char from[256], expected[256];
        snprintf(from, sizeof from, DIR "/pages/%s", cases[i].from);
        snprintf(expected, sizeof expected, DIR "/pages/%s", cases[i].to);
        assert_true(path_next_in_directory(from, scene_extensions, cases[i].step, path, sizeof path));
        assert_string_equal(path, expected);
    }
    assert_false(path_next_in_directory(DIR "/empty/a.json", scene_extensions, 1, path, sizeof path));
    assert_false(path_next_in_directory(DIR "/missing/a.json", scene_extensions, 1, path, sizeof path));
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
        cmocka_unit_test(test_next_in_directory),
        cmocka_unit_test(test_stem),
    };
    return cmocka_run_group_tests_name("path", tests, NULL, NULL);
}
