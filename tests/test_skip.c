/* Skips never change a decision (README, "Skips"): view culling leaves out
 * only objects with no pixel on screen, so with skips on and with
 * --no-skip every technique's dump (visibility, depth, object ids, the
 * picture) is the same byte for byte, on the standard scenes, long_view
 * and the 1000-object city. And the culling does cull: most of the city
 * lies outside its street-level view, nothing of simple does.
 *
 * The box test itself (frustum_box_outside) is checked in process first:
 * in front, behind the eye, beyond the far plane, across the frustum. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "frustum.h"
#include "path.h"
#include "registry.h"
#include "support.h"

#define OUT "out/test/skip"
#define SCENES "assets/scenes"
#define CITY "city_1000"
#define CITY_OBJECTS 1001 /* the ground and 1000 buildings */
#define MAX_DUMP_BYTES (64 << 20)
/* A test frustum: 90 degrees, square, near 1, far 100, looking down -z. */
#define TEST_FOV_DEG 90.0f
#define TEST_NEAR 1.0f
#define TEST_FAR 100.0f

static const char *const scenes[] = {"simple", "bunny", "teapot", "long_view", CITY};
/* What a dump holds that a technique or the capture decides. */
static const char *const dump_files[] = {"visibility.pfm", "depth.pfm", "ids.pfm", "color.png"};


static void test_box_outside(void **state) {
    (void)state;
    mat4 projection;
    glm_perspective(glm_rad(TEST_FOV_DEG), 1, TEST_NEAR, TEST_FAR, projection);
    static const struct {
        vec3 lo, hi;
        bool outside;
    } boxes[] = {
        {{-1, -1, -11}, {1, 1, -9}, false},      /* in front */
        {{-1, -1, 9}, {1, 1, 11}, true},         /* behind the eye */
        {{-1, -1, -120}, {1, 1, -110}, true},    /* beyond the far plane */
        {{30, -1, -11}, {32, 1, -9}, true},      /* off to the right */
        {{-50, -1, -50}, {50, 1, 50}, false},    /* around the eye, across the whole frustum */
        {{-1, -1, -0.5f}, {1, 1, 0.5f}, true},   /* around the eye, inside the near plane */
        {{10, -1, -11}, {12, 1, -9}, false},     /* across the right plane */
        {{-200, 0, -200}, {200, 0, 200}, false}, /* a flat ground through the view */
    };
    for (size_t i = 0; i < sizeof boxes / sizeof *boxes; i++) {
        if (frustum_box_outside(projection, boxes[i].lo, boxes[i].hi) != boxes[i].outside)
            fail_msg("box %zu: expected %s", i, boxes[i].outside ? "outside" : "not outside");
    }
}

static void dump_dir(const char *technique, const char *scene, const char *skips, char *out, size_t size) {
    snprintf(out, size, OUT "/%s_%s_%s", technique, scene, skips);
}

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

/* Every technique on every scene: skips on and --no-skip dump the same. */
static void test_dumps_identical_with_and_without_skips(void **state) {
    (void)state;
    for (int t = 0; t < registry_technique_count; t++) {
        const char *technique = registry_techniques[t]->name;
        for (size_t s = 0; s < sizeof scenes / sizeof *scenes; s++) {
            char scene[256], on[256], off[256];
            snprintf(scene, sizeof scene, SCENES "/%s.json", scenes[s]);
            dump_dir(technique, scenes[s], "on", on, sizeof on);
            dump_dir(technique, scenes[s], "off", off, sizeof off);
            assert_int_equal(support_dump(technique, scene, "", on), 0);
            assert_int_equal(support_dump(technique, scene, "--no-skip", off), 0);
            for (size_t f = 0; f < sizeof dump_files / sizeof *dump_files; f++) {
                if (!same_file(on, off, dump_files[f]))
                    fail_msg("%s on %s: %s differs between %s and %s", technique, scenes[s], dump_files[f], on, off);
            }
        }
        printf("    %s: %zu scenes, dumps identical with and without skips\n", technique,
               sizeof scenes / sizeof *scenes);
    }
}

/* The --verbose culling line of one frame of the floor on `scene`. */
static const char *culling_line(const char *scene, const char *flags) {
    char scene_file[256];
    snprintf(scene_file, sizeof scene_file, SCENES "/%s.json", scene);
    return support_verbose_line("unshadowed", scene_file, flags, "view culling: ");
}

static void culling_counts(const char *scene, int *drawn, int *culled) {
    const char *line = culling_line(scene, "");
    assert_non_null(line);
    assert_int_equal(sscanf(line, "view culling: objects drawn %d / culled %d", drawn, culled), 2);
    printf("    %s: objects drawn %d / culled %d\n", scene, *drawn, *culled);
}

/* The city's street-level view sees a small part of it. */
static void test_city_mostly_culled(void **state) {
    (void)state;
    int drawn, culled;
    culling_counts(CITY, &drawn, &culled);
    assert_int_equal(drawn + culled, CITY_OBJECTS);
    assert_true(2 * culled > CITY_OBJECTS);
    assert_true(drawn > 0);
}

/* Everything of simple is in view: nothing culled. */
static void test_simple_nothing_culled(void **state) {
    (void)state;
    int drawn, culled;
    culling_counts("simple", &drawn, &culled);
    assert_true(drawn > 0);
    assert_int_equal(culled, 0);
}

/* Each switch turns culling off: its own and the program-wide one. */
static void test_switches_turn_culling_off(void **state) {
    (void)state;
    static const char *const flags[] = {"--no-view-cull", "--no-skip"};
    for (size_t i = 0; i < sizeof flags / sizeof *flags; i++) {
        const char *line = culling_line(CITY, flags[i]);
        assert_non_null(line);
        assert_true(strncmp(line, "view culling: OFF", strlen("view culling: OFF")) == 0);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_box_outside),
        cmocka_unit_test(test_city_mostly_culled),
        cmocka_unit_test(test_simple_nothing_culled),
        cmocka_unit_test(test_switches_turn_culling_off),
        cmocka_unit_test(test_dumps_identical_with_and_without_skips),
    };
    return cmocka_run_group_tests_name("skips", tests, NULL, NULL);
}
