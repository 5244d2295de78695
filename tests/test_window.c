/* The window under real input: X key and mouse events (xdotool) into
 * build/shadows under Xvfb, as a lecturer's hands would send them
 * (tests/window_input.sh is the script; its top comment lists the steps).
 * What they must do: F12 writes a numbered picture that never overwrites
 * and prints its path; a drag orbits the camera; 0 puts camera and light
 * back exactly as loaded; 3 switches to the third technique; Escape
 * closes the window with exit 0. Without --no-hud, F12's picture is the
 * window's with its HUD (the rows below the HUD as without it), and a
 * scene that does not load (Page Down) says why on the HUD. In a tour,
 * the step's caption is dimmed and says what changed while the technique
 * or a setting differs from the step's, and is itself again once they
 * are the step's (support_expect_captions). --fullscreen starts on
 * the whole screen, and F11 goes back to the window as it was (the same
 * picture) and to the whole screen again. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "path.h"
#include "support.h"

#define WINDOW_DIR "out/test/window"
#define WINDOW_SCENE "assets/scenes/simple.json"
#define WINDOW_SCENES "tests/data/window_scenes" /* simple's copy, then a broken scene */
#define WINDOW_HEIGHT 360
#define WINDOW_HUD_ROWS 120      /* the full HUD's at most, at 640x360 */
#define WINDOW_SCREEN_WIDTH 1024 /* support_xvfb_run's screen */
#define WINDOW_SCREEN_HEIGHT 768

static char err[16384];

static void test_keys_and_mouse_in_a_real_window(void **state) {
    (void)state;
    const char *xvfb = support_xvfb_run();
    if (!support_have_command("xdotool")) {
        fprintf(stderr, "    xdotool is not installed here: skipped\n");
        skip();
    }
    /* A picture from an earlier run, which F12 must not overwrite. */
    assert_int_equal(system("rm -rf " WINDOW_DIR " && mkdir -p " WINDOW_DIR " && echo earlier > " WINDOW_DIR
                            "/screenshot-planar-1.png"),
                     0);
    char command[2048];
    snprintf(command, sizeof command,
             "timeout 300 %s bash tests/window_input.sh \"%s\" " WINDOW_SCENE " " WINDOW_SCENES
             "/a_simple.json " SUPPORT_CAPTION_TOUR " " SUPPORT_CAPTION_SIZE " " WINDOW_DIR,
             xvfb, support_program("shadows"));
    int status = support_run(command, err, sizeof err);
    if (status != 0) {
        char *app_err = path_read_text(WINDOW_DIR "/stderr.txt", 1 << 16, NULL);
        fprintf(stderr, "    the app's stderr:\n%s\n", app_err ? app_err : "(none)");
        free(app_err);
    }
    assert_int_equal(status, 0);

    char *earlier = path_read_text(WINDOW_DIR "/screenshot-planar-1.png", 1 << 10, NULL);
    assert_non_null(earlier);
    assert_string_equal(earlier, "earlier\n");
    free(earlier);
    /* Every picture's path on stdout, in order. */
    char *out = path_read_text(WINDOW_DIR "/stdout.txt", 1 << 16, NULL);
    assert_non_null(out);
    static const char *const saved[] = {"screenshot-planar-2.png", "screenshot-planar-3.png",
                                        "screenshot-planar-4.png", "screenshot-shadowmap-1.png"};
    const char *at = out;
    for (size_t k = 0; k < sizeof saved / sizeof *saved; k++) {
        at = strstr(at, saved[k]);
        if (!at)
            fail_msg("stdout does not name %s next: %s", saved[k], out);
    }
    free(out);

    /* The drag moved the view; reset brought it back, byte for byte. */
    const char *loaded = WINDOW_DIR "/screenshot-planar-2.png", *dragged = WINDOW_DIR "/screenshot-planar-3.png",
               *reset = WINDOW_DIR "/screenshot-planar-4.png", *other = WINDOW_DIR "/screenshot-shadowmap-1.png";
    assert_true(support_compare_images(loaded, dragged) > SUPPORT_MAX_DIFFERING);
    assert_true(support_compare_images(loaded, reset) == 0);
    /* The other technique: its own shadows (PCF edges), not planar's. */
    assert_true(support_compare_images(loaded, other) > 0);

    /* With the HUD: F12 keeps it, over the same picture. */
    out = path_read_text(WINDOW_DIR "/stdout2.txt", 1 << 16, NULL);
    assert_non_null(out);
    assert_non_null(strstr(out, "screenshot-planar-5.png"));
    free(out);
    int width, height, hud_width, hud_height;
    unsigned char *clean = image_read_png(loaded, &width, &height);
    unsigned char *with_hud = image_read_png(WINDOW_DIR "/screenshot-planar-5.png", &hud_width, &hud_height);
    assert_non_null(clean);
    assert_non_null(with_hud);
    assert_int_equal(width, hud_width);
    assert_int_equal(height, WINDOW_HEIGHT);
    assert_int_equal(hud_height, WINDOW_HEIGHT);
    size_t row = (size_t)width * 4;
    assert_true(memcmp(clean, with_hud, WINDOW_HUD_ROWS * row) != 0);
    assert_memory_equal(clean + WINDOW_HUD_ROWS * row, with_hud + WINDOW_HUD_ROWS * row,
                        (WINDOW_HEIGHT - WINDOW_HUD_ROWS) * row);
    free(with_hud);
    free(clean);
    /* The broken scene: why, on the HUD. */
    char *hud = path_read_text(WINDOW_DIR "/stderr2.txt", 1 << 16, NULL);
    assert_non_null(hud);
    const char *note = strstr(hud, "hud: did NOT load: ");
    if (!note || !strstr(note, "b_broken.json:"))
        fail_msg("the HUD does not say why the scene did not load: %s", hud);
    free(hud);

    /* The tour's caption, true, changed and true again. */
    hud = path_read_text(WINDOW_DIR "/stderr3.txt", 1 << 20, NULL);
    assert_non_null(hud);
    static const char *const captions[SUPPORT_CAPTION_PICTURES] = {
        WINDOW_DIR "/screenshot-shadowmap-2.png", WINDOW_DIR "/screenshot-volumes-1.png",
        WINDOW_DIR "/screenshot-shadowmap-3.png", WINDOW_DIR "/screenshot-shadowmap-4.png"};
    support_expect_captions(hud, captions);
    free(hud);

    /* Fullscreen, the window, fullscreen again. */
    const struct {
        const char *path;
        int width, height;
    } fullscreen[] = {
        {WINDOW_DIR "/screenshot-planar-6.png", WINDOW_SCREEN_WIDTH, WINDOW_SCREEN_HEIGHT},
        {WINDOW_DIR "/screenshot-planar-7.png", width, WINDOW_HEIGHT},
        {WINDOW_DIR "/screenshot-planar-8.png", WINDOW_SCREEN_WIDTH, WINDOW_SCREEN_HEIGHT},
    };
    for (size_t k = 0; k < sizeof fullscreen / sizeof *fullscreen; k++) {
        unsigned char *picture = image_read_png(fullscreen[k].path, &hud_width, &hud_height);
        if (!picture || hud_width != fullscreen[k].width || hud_height != fullscreen[k].height)
            fail_msg("%s: %dx%d, not %dx%d", fullscreen[k].path, picture ? hud_width : 0, picture ? hud_height : 0,
                     fullscreen[k].width, fullscreen[k].height);
        free(picture);
    }
    assert_true(support_compare_images(loaded, fullscreen[1].path) == 0);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_keys_and_mouse_in_a_real_window),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
