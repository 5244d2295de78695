/* Tests of common/data/tour.c (tour files, good and bad) and of how
 * build/shadows --tour checks a tour's techniques and flags before it
 * renders anything. Run from the repository root. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "support.h"
#include "tour.h"

#define TOUR_DATA "tests/data/"

static char err[4096];

/* Defaults where the file says nothing; the scene beside the tour file,
 * an absolute one as it is. */
static void test_good_tour(void **state) {
    (void)state;
    static tour t;
    assert_true(tour_load(&t, TOUR_DATA "tour_good.json"));
    assert_string_equal(t.title, "A test tour");
    assert_int_equal(t.step_count, 2);
    const tour_step *a = &t.steps[0], *b = &t.steps[1];
    assert_string_equal(a->scene, TOUR_DATA "../../assets/scenes/simple.json");
    assert_string_equal(a->technique, "planar");
    assert_string_equal(a->flags, "");
    assert_string_equal(a->caption, "");
    assert_true(a->seconds == TOUR_DEFAULT_SECONDS);
    assert_int_equal(a->motion, MOTION_STATIC);
    assert_int_equal(a->frame_count, (int)(TOUR_DEFAULT_SECONDS * TOUR_FPS));
    assert_int_equal(a->shown_frame, a->frame_count - 1);
    assert_string_equal(b->scene, "/abs/scene.json");
    assert_string_equal(b->flags, "--warp uniform");
    assert_string_equal(b->caption, "uniform");
    assert_int_equal(b->motion, MOTION_CAMERA);
    assert_int_equal(b->frame_count, 30);
    assert_int_equal(b->shown_frame, 3);
}

/* Each bad file fails with its one line, naming the step and the key. */
static void test_bad_tours(void **state) {
    (void)state;
    static const struct {
        const char *file, *line;
    } cases[] = {
        {"tour_unknown_key.json", "steps[1]: unknown key \"captoin\" (expected scene, technique, flags, caption, "
                                  "seconds, motion or frame)"},
        {"tour_bad_motion.json", "steps[0].motion: unknown motion \"orbit\" (expected static, light or camera)"},
        {"tour_bad_frame.json", "steps[0].frame: must be a frame of the step, 0 to 59 (got 60)"},
        {"tour_bad_seconds.json", "steps[0].seconds: expected a number, got a string"},
        {"tour_no_scene.json", "steps[0].scene: missing required field"},
        {"tour_no_steps.json", "steps: expected 1 to 32 steps, got 0"},
        {"tour_syntax_error.json", "2: JSON syntax error near '}'"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        static tour t;
        char path[256], expected[512];
        snprintf(path, sizeof path, TOUR_DATA "%s", cases[i].file);
        support_capture_stderr();
        bool loaded = tour_load(&t, path);
        const char *text = support_release_stderr();
        snprintf(expected, sizeof expected, "%s%s%s\n", path, cases[i].line[0] == '2' ? ":" : ": ", cases[i].line);
        if (loaded || strcmp(text, expected) != 0)
            fail_msg("%s: loaded %d, said \"%s\", expected \"%s\"", cases[i].file, loaded, text, expected);
    }
}

/* A technique not in the registry, or flags it does not take, stop the
 * run before it opens a context: exit 1, the step named. */
static void test_tour_checks_techniques_and_flags(void **state) {
    (void)state;
    static const struct {
        const char *file, *line;
    } cases[] = {
        {"tour_unknown_technique.json", "steps[1].technique: unknown technique \"shadowvolumes\""},
        {"tour_bad_flags.json", "steps[0].flags: planar: unknown flag '--no-stencl'"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char command[512];
        snprintf(command, sizeof command, "%s --tour " TOUR_DATA "%s --screenshot out/test/never.png",
                 support_program("shadows"), cases[i].file);
        assert_int_equal(support_run(command, err, sizeof err), 1);
        if (!strstr(err, cases[i].line))
            fail_msg("%s: said \"%s\", expected \"%s\"", cases[i].file, err, cases[i].line);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_good_tour),
        cmocka_unit_test(test_bad_tours),
        cmocka_unit_test(test_tour_checks_techniques_and_flags),
    };
    return cmocka_run_group_tests_name("tours", tests, NULL, NULL);
}
