/* Tests of common/gl/hud.c's layout (no GL): the HUD's lines are wrapped
 * at the framebuffer's width, so nothing is cut at any size, its
 * scale follows the framebuffer's height, and its panel holds them. Then the HUD build/shadows draws
 * for a lecture (its text, which --verbose prints): at most
 * LECTURE_MAX_LINES lines at 1280x720 with the counters left out; the
 * compact HUD keeps the technique's settings and drops the counters; the
 * scene is named, not its path; a map's size says whether it was
 * chosen; compare mode's caption strip keeps every tour step's settings;
 * no line contradicts another. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <ctype.h>
#include <dirent.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "compare.h"
#include "hud.h"
#include "support.h"
#include "tour.h"

#define LECTURE_WIDTH 1280
#define LECTURE_SCALE 2 /* hud_scale_for(720) */
#define LECTURE_MAX_LINES 6
#define HUD_PREFIX "hud: "

/* A HUD as psm shows it: a state line far wider than 640 pixels. */
static const char hud_text[] =
    "3/5 psm: perspective shadow maps (Stamminger & Drettakis 2002), LiSPSM (Wimmer et al. 2004), uniform\n"
    "scene long_view   640x360   frame 0 at 0.000 s\n"
    "light 0: psm 2D map auto: 4096 (light in front of the viewer, virtual camera slid back 43.2); texel on "
    "screen 0.632 px, uniform's 5.63 px\n"
    "a_word_far_too_long_for_any_line_of_a_small_window_so_it_is_broken_where_it_stops_fitting_and_goes_on\n"
    "[W] warp: psm   [M] map-size: auto";

/* The text without its whitespace: what the reader must still get. */
static void ink(const char *text, char *out) {
    for (; *text; text++)
        if (!isspace((unsigned char)*text))
            *out++ = *text;
    *out = '\0';
}

static void test_wrapped_lines_fit_and_lose_nothing(void **state) {
    (void)state;
    static const int sizes[][2] = {{640, 1}, {640, 2}, {1280, 2}, {1920, 3}, {200, 2}};
    for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++) {
        int width = sizes[i][0], scale = sizes[i][1];
        char wrapped[8192], expected[8192], actual[8192];
        int lines = hud_wrap(hud_text, width, scale, wrapped, sizeof wrapped);
        int newlines = 0;
        for (const char *c = wrapped; *c; c++)
            newlines += *c == '\n';
        assert_int_equal(lines, newlines + 1);
        assert_true(lines > 5); /* every size here breaks a line */
        for (char *line = strtok(wrapped, "\n"); line; line = strtok(NULL, "\n")) {
            int pixels = (hud_text_width(line) + 2 * HUD_MARGIN) * scale;
            if (pixels > width)
                fail_msg("%dx at %d px: \"%s\" takes %d px", scale, width, line, pixels);
        }
        hud_wrap(hud_text, width, scale, wrapped, sizeof wrapped);
        ink(hud_text, expected);
        ink(wrapped, actual);
        assert_string_equal(actual, expected);
    }
    /* Wide enough, nothing changes. */
    char wrapped[8192];
    assert_int_equal(hud_wrap("one line", 1920, 1, wrapped, sizeof wrapped), 1);
    assert_string_equal(wrapped, "one line");
}

/* The panel hud_draw puts behind the text holds every wrapped line, its
 * margins included, within the framebuffer's width; what it hides grows
 * with the scale. */
static void test_panel_holds_the_text(void **state) {
    (void)state;
    static const int sizes[][2] = {{640, 360}, {1280, 720}, {1920, 1080}};
    for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++) {
        int width = sizes[i][0], height = sizes[i][1], scale = hud_scale_to_fit(hud_text, width, height, 0, height);
        char wrapped[8192];
        int lines = hud_wrap(hud_text, width, scale, wrapped, sizeof wrapped), panel_width, panel_height;
        hud_panel_size(hud_text, width, height, 0, 0, &panel_width, &panel_height);
        printf("    %dx%d: %d lines at scale %d, panel %dx%d\n", width, height, lines, scale, panel_width,
               panel_height);
        assert_true(panel_height >= (lines * HUD_LINE_UNITS + HUD_MARGIN) * scale);
        assert_true(panel_width >= (hud_text_width(wrapped) + 2 * HUD_MARGIN) * scale);
        assert_true(panel_width <= width && panel_height < height);
    }
}

static void test_scale_follows_height(void **state) {
    (void)state;
    assert_int_equal(hud_scale_for(180), 1);
    assert_int_equal(hud_scale_for(360), 1);
    assert_int_equal(hud_scale_for(720), 2);
    assert_int_equal(hud_scale_for(1080), 3);
    assert_int_equal(hud_scale_for(2160), 6);
    assert_int_equal(hud_scale_for(100000), HUD_MAX_SCALE);
}

static char err[16384];

/* The "hud: " lines of `text` without the prefix, into hud. */
static void hud_lines(const char *text, char *hud, size_t size) {
    size_t n = 0;
    hud[0] = '\0';
    for (const char *at = text; (at = strstr(at, HUD_PREFIX)); at++) {
        at += strlen(HUD_PREFIX);
        size_t length = strcspn(at, "\n");
        n += (size_t)snprintf(hud + n, size - n, "%.*s\n", (int)length, at);
        assert_true(n < size);
    }
}

/* build/shadows' HUD text of `technique` on the scene with `flags` (its
 * "hud: " lines), into hud. */
static void hud_on(const char *scene, const char *technique, const char *flags, char *hud, size_t size) {
    char command[1024];
    snprintf(command, sizeof command,
             "%s --backend egl --technique %s --scene assets/scenes/%s.json --frames 1 --verbose %s",
             support_program("shadows"), technique, scene, flags);
    assert_int_equal(support_run(command, err, sizeof err), 0);
    hud_lines(err, hud, size);
    printf("    HUD of %s on %s with %s:\n%s", technique, scene, flags, hud);
}

/* The same on long_view. */
static void hud_of(const char *technique, const char *flags, char *hud, size_t size) {
    hud_on("long_view", technique, flags, hud, size);
}

static void test_lecture_hud(void **state) {
    (void)state;
    char hud[8192], wrapped[8192];
    hud_of("psm", "--warp lispsm", hud, sizeof hud);
    assert_non_null(strstr(hud, "scene long_view "));
    assert_null(strstr(hud, "assets/scenes"));
    assert_non_null(strstr(hud, "2D map auto: 4096 "));
    assert_non_null(strstr(hud, "[W] warp: lispsm"));
    char *counters = strstr(hud, "\nskips"); /* --verbose shows them (F3 in the window) */
    assert_non_null(counters);
    counters[1] = '\0';
    int lines = hud_wrap(hud, LECTURE_WIDTH, LECTURE_SCALE, wrapped, sizeof wrapped);
    printf("    %d lines at %d pixels\n", lines, LECTURE_WIDTH);
    assert_true(lines <= LECTURE_MAX_LINES);

    hud_of("psm", "--warp lispsm --hud-compact", hud, sizeof hud);
    assert_non_null(strstr(hud, "psm on long_view "));
    assert_non_null(strstr(hud, "[W] warp: lispsm"));
    assert_null(strstr(hud, "skips"));
    assert_null(strstr(hud, "light 0:"));
}

/* A toggle whose feature the GL lacks says so, rather than "on" beside
 * a state line that says the feature is off: volumes' depth bounds, exact
 * depth (gl_PrimitiveID) and depth clamp, which WebGL 2 lacks (--webgl2
 * keeps to what the page has), and llvmpipe the depth bounds too. */
static void test_missing_feature_is_not_on(void **state) {
    (void)state;
    char hud[8192];
    hud_of("volumes", "--webgl2", hud, sizeof hud);
    assert_non_null(strstr(hud, "depth bounds off (no GL_EXT_depth_bounds_test)"));
    assert_non_null(strstr(hud, "[B] depth-bounds: not on this GL"));
    assert_non_null(strstr(hud, "exact depth off (no gl_PrimitiveID)"));
    assert_non_null(strstr(hud, "[E] exact-depth: not on this GL"));
    assert_non_null(strstr(hud, "[C] depth-clamp: not on this GL"));
    /* The GL's own: the toggle and the state line agree. */
    hud_of("volumes", "", hud, sizeof hud);
    bool lacks = strstr(hud, "depth bounds off (no GL_EXT_depth_bounds_test)") != NULL;
    assert_non_null(strstr(hud, lacks ? "[B] depth-bounds: not on this GL" : "[B] depth-bounds: on"));
    assert_non_null(strstr(hud, "[E] exact-depth: on"));
    assert_non_null(strstr(hud, "[C] depth-clamp: on"));
}

/* A setting another one overrides: the line that says what is drawn says
 * why, so that it never contradicts the setting's. A moment filter blurs
 * an area light's shadow whatever --soft says; cascades cut only a
 * directional light's map (simple's is a spot). */
static void test_overridden_setting_says_why(void **state) {
    (void)state;
    char hud[8192];
    hud_on("soft_sun", "shadowmap", "--soft off --filter msm", hud, sizeof hud);
    assert_non_null(strstr(hud, "[Y] soft: off"));
    assert_non_null(strstr(hud, "area light, radius 3 degrees: soft by its moment filter, whatever --soft says"));
    hud_on("simple", "cascades", "", hud, sizeof hud);
    assert_non_null(strstr(hud, "[N] cascades: 4"));
    assert_non_null(strstr(hud, ", no cascades: only a directional light's map is cut in cascades"));
    hud_on("soft_sun", "cascades", "", hud, sizeof hud);
    assert_non_null(strstr(hud, ", 4 cascades ("));
}

/* The HUD sizes compare mode's caption strip is checked at: a projector's. */
static const struct {
    const char *size;
    int width, height;
} hud_strip_sizes[] = {{"1280x720", 1280, 720}, {"1920x1080", 1920, 1080}};

/* Each flag of `flags` ("--filter vsm --no-depth-clamp") as the HUD's
 * settings show it ("filter: vsm", "depth-clamp: OFF") must be in hud. */
static void hud_expect_settings(const char *hud, const char *flags) {
    char *copy = strdup(flags), shown[TOUR_TEXT_MAX + 16];
    assert_non_null(copy);
    for (char *rest = copy, *flag; (flag = strtok_r(rest, " ", &rest));) {
        assert_true(strncmp(flag, "--", 2) == 0);
        if (strncmp(flag, "--no-", 5) == 0)
            snprintf(shown, sizeof shown, "%s: OFF", flag + 5);
        else
            snprintf(shown, sizeof shown, "%s: %s", flag + 2, strtok_r(rest, " ", &rest));
        if (!strstr(hud, shown))
            fail_msg("\"%s\" is not on the HUD", shown);
    }
    free(copy);
}

/* Compare mode's caption strip (compare.h) over every tour's compare
 * steps, at a projector's sizes: the caption, the technique and its
 * settings (all of them, or those not at their defaults) fit in its
 * COMPARE_STRIP_LINES lines at the picture's HUD scale, each setting the
 * step's flags make among them. The steps are played as one tour, whose
 * headless run prints each step's HUD (--verbose). */
static void test_compare_strip_keeps_the_settings(void **state) {
    (void)state;
    /* In the plain pass alone: each step traces its truth, and what the
     * sanitizers would watch is the HUD's text, which the other tests
     * here build. */
    if (getenv("TEST_SANITIZER")) {
        print_message("the compare strips: the plain pass checks them\n");
        skip();
    }
    static tour t;
    static char step_flags[TOUR_MAX_STEPS][TOUR_TEXT_MAX];
    cJSON *root = cJSON_CreateObject(), *steps = cJSON_AddArrayToObject(root, "steps");
    cJSON_AddStringToObject(root, "title", "every tour's compare steps");
    int count = 0;
    DIR *tours = opendir("assets/tours");
    assert_non_null(tours);
    for (const struct dirent *e; (e = readdir(tours));) {
        char path[PATH_MAX], scene[PATH_MAX];
        if (!strstr(e->d_name, ".json"))
            continue;
        snprintf(path, sizeof path, "assets/tours/%s", e->d_name);
        assert_true(tour_load(&t, path));
        for (int k = 0; k < t.step_count; k++) {
            const tour_step *s = &t.steps[k];
            if (!s->compare)
                continue;
            assert_true(count < TOUR_MAX_STEPS);
            assert_non_null(realpath(s->scene, scene));
            cJSON *step = cJSON_CreateObject();
            cJSON_AddStringToObject(step, "scene", scene);
            cJSON_AddStringToObject(step, "technique", s->technique);
            cJSON_AddStringToObject(step, "flags", s->flags);
            cJSON_AddStringToObject(step, "caption", s->caption);
            cJSON_AddBoolToObject(step, "compare", true);
            cJSON_AddItemToArray(steps, step);
            snprintf(step_flags[count++], TOUR_TEXT_MAX, "%s", s->flags);
        }
    }
    closedir(tours);
    assert_true(count > 0);
    char file[PATH_MAX];
    support_write_json(root, "out/test/hud", "compare_steps", file, sizeof file);
    cJSON_Delete(root);
    static char log[1 << 17], hud[1 << 16], wrapped[8192];
    for (size_t i = 0; i < sizeof hud_strip_sizes / sizeof *hud_strip_sizes; i++) {
        char command[PATH_MAX + 256];
        snprintf(command, sizeof command, "%s --backend egl --size %s --tour %s --verbose",
                 support_program("shadows"), hud_strip_sizes[i].size, file);
        assert_int_equal(support_run(command, log, sizeof log), 0);
        hud_lines(log, hud, sizeof hud);
        for (int k = 0; k < count; k++) {
            char start[64];
            snprintf(start, sizeof start, "step %d/%d ", k + 1, count);
            char *block = strstr(hud, start);
            if (!block)
                fail_msg("at %s, no HUD of step %d: %s", hud_strip_sizes[i].size, k + 1, hud);
            char *end = strstr(block, "\nstep ");
            if (end)
                *end = '\0';
            int scale = hud_scale_for(hud_strip_sizes[i].height);
            int lines = hud_wrap(block, hud_strip_sizes[i].width, scale, wrapped, sizeof wrapped);
            printf("    %s, %d lines at scale %d:\n%s\n", hud_strip_sizes[i].size, lines, scale, wrapped);
            assert_true(lines <= COMPARE_STRIP_LINES);
            hud_expect_settings(block, step_flags[k]);
            assert_true(step_flags[k][0] || strstr(block, "] ") || strstr(block, "settings: the defaults"));
            if (end)
                *end = '\n';
        }
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_wrapped_lines_fit_and_lose_nothing),
        cmocka_unit_test(test_scale_follows_height),
        cmocka_unit_test(test_panel_holds_the_text),
        cmocka_unit_test(test_lecture_hud),
        cmocka_unit_test(test_missing_feature_is_not_on),
        cmocka_unit_test(test_overridden_setting_says_why),
        cmocka_unit_test(test_compare_strip_keeps_the_settings),
    };
    return cmocka_run_group_tests_name("hud", tests, NULL, NULL);
}
