/* Screenshot tests: each technique on each standard scene (spot,
 * point and directional lights) rendered headless by each backend and
 * compared with tests/golden/ (tolerance in support.h: at most 0.1 %
 * of pixels differ by more than 8/255). On a failure the actual image and a
 * diff image are left in out/test/. `make update-golden` regenerates the
 * goldens, on purpose only.
 *
 * The comparison is shown to bite: a scene whose light moved slightly, and
 * each planar fix turned off, must fail it. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"

#define SIZE "640x360"

static const char *const scenes[] = {"simple", "bunny", "teapot"};
static const char *const techniques[] = {"planar", "shadowmap", "psm", "volumes"};
static char err[16384];

/* Renders `scene_file` with build/TECHNIQUE and extra flags to
 * out/test/NAME.png. */
static void render_with(const char *technique, const char *backend, const char *scene_file, const char *flags,
                        const char *name) {
    char command[2048];
    snprintf(command, sizeof command,
             "%s --backend %s --size " SIZE " --scene %s %s --screenshot out/test/%s.png",
             support_program(technique), backend, scene_file, flags, name);
    assert_int_equal(support_run(command, err, sizeof err), 0);
}

static void render(const char *backend, const char *scene_file, const char *flags, const char *name) {
    render_with("planar", backend, scene_file, flags, name);
}

static double compare_with_golden_of(const char *technique, const char *scene, const char *name) {
    char golden[512], actual[512];
    snprintf(golden, sizeof golden, "tests/golden/%s_%s.png", technique, scene);
    snprintf(actual, sizeof actual, "out/test/%s.png", name);
    return support_compare_images(golden, actual);
}

static double compare_with_golden(const char *scene, const char *name) {
    return compare_with_golden_of("planar", scene, name);
}

static void check_backend(const char *backend) {
    for (size_t t = 0; t < sizeof techniques / sizeof *techniques; t++) {
        for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++) {
            char scene_file[256], name[256];
            snprintf(scene_file, sizeof scene_file, "assets/scenes/%s.json", scenes[i]);
            snprintf(name, sizeof name, "%s_%s_%s", techniques[t], scenes[i], backend);
            render_with(techniques[t], backend, scene_file, "", name);
            double fraction = compare_with_golden_of(techniques[t], scenes[i], name);
            assert_true(fraction >= 0 && fraction <= SUPPORT_MAX_DIFFERING);
        }
    }
}

static bool osmesa_installed(void) {
    return system("ldconfig -p | grep -q libOSMesa.so") == 0;
}

static void test_egl_matches_golden(void **state) {
    (void)state;
    check_backend("egl");
}

static void test_osmesa_matches_golden(void **state) {
    (void)state;
    if (!osmesa_installed()) {
        fprintf(stderr, "    libOSMesa is not installed here: skipped\n");
        skip();
    }
    check_backend("osmesa");
}

/* EGL and OSMesa agree with each other, not just each with the golden. */
static void test_backends_agree(void **state) {
    (void)state;
    if (!osmesa_installed())
        skip();
    for (size_t t = 0; t < sizeof techniques / sizeof *techniques; t++) {
        for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++) {
            char egl[256], osmesa[256];
            snprintf(egl, sizeof egl, "out/test/%s_%s_egl.png", techniques[t], scenes[i]);
            snprintf(osmesa, sizeof osmesa, "out/test/%s_%s_osmesa.png", techniques[t], scenes[i]);
            double fraction = support_compare_images(egl, osmesa);
            assert_true(fraction >= 0 && fraction <= SUPPORT_MAX_DIFFERING);
        }
    }
}

static void test_same_command_same_image(void **state) {
    (void)state;
    render("egl", "assets/scenes/bunny.json", "--frames 3", "determinism_a");
    render("egl", "assets/scenes/bunny.json", "--frames 3", "determinism_b");
    assert_true(support_compare_images("out/test/determinism_a.png", "out/test/determinism_b.png") == 0);
}

/* The light 0.25 units away from where simple.json has it. */
static void test_moved_light_fails_comparison(void **state) {
    (void)state;
    render("egl", "tests/data/simple_light_moved.json", "", "light_moved");
    assert_true(compare_with_golden("simple", "light_moved") > SUPPORT_MAX_DIFFERING);
}

static void test_each_fix_shows_when_off(void **state) {
    (void)state;
    render("egl", "assets/scenes/simple.json", "--no-stencil", "no_stencil");
    assert_true(compare_with_golden("simple", "no_stencil") > SUPPORT_MAX_DIFFERING);
    render("egl", "assets/scenes/simple.json", "--no-offset", "no_offset");
    assert_true(compare_with_golden("simple", "no_offset") > SUPPORT_MAX_DIFFERING);
    /* A sphere sunk half into the ground: without rejection its buried
     * half throws an anti-shadow onto the ground on the light's side. */
    render("egl", "tests/data/anti_shadow.json", "", "reject_on");
    render("egl", "tests/data/anti_shadow.json", "--no-reject", "reject_off");
    assert_true(support_compare_images("out/test/reject_on.png", "out/test/reject_off.png") >
                SUPPORT_MAX_DIFFERING);
}

/* Without any bias the shadow map shadows the lit ground with acne. */
static void test_shadowmap_without_bias_shows_acne(void **state) {
    (void)state;
    render_with("shadowmap", "egl", "assets/scenes/simple.json",
                "--no-constant-bias --no-slope-bias", "shadowmap_no_bias");
    assert_true(compare_with_golden_of("shadowmap", "simple", "shadowmap_no_bias") > SUPPORT_MAX_DIFFERING);
}

/* The lecture overlays (texels, frusta, the map as an inset) for a 2D map
 * (simple's spot) and a cube map (bunny's point light): they draw into the
 * picture, and what they draw matches its golden. */
static void test_shadowmap_overlays_match_golden(void **state) {
    (void)state;
    static const char *const overlay_scenes[] = {"simple", "bunny"};
    for (size_t i = 0; i < sizeof overlay_scenes / sizeof *overlay_scenes; i++) {
        char scene_file[256], name[256];
        snprintf(scene_file, sizeof scene_file, "assets/scenes/%s.json", overlay_scenes[i]);
        snprintf(name, sizeof name, "shadowmap_overlay_%s", overlay_scenes[i]);
        render_with("shadowmap", "egl", scene_file, "--overlay all", name);
        assert_true(compare_with_golden_of("shadowmap", overlay_scenes[i], name) > SUPPORT_MAX_DIFFERING);
        double fraction = compare_with_golden_of("shadowmap-overlay", overlay_scenes[i], name);
        assert_true(fraction >= 0 && fraction <= SUPPORT_MAX_DIFFERING);
    }
}

/* Perspective shadow maps where they matter, long_view, with the light in
 * front of the viewer and behind (the inverted case), on both headless
 * backends; the lecture's post-perspective view; the texel-size heat map
 * draws into the picture. */
static void test_psm_long_view_matches_golden(void **state) {
    (void)state;
    static const char *const scenes[] = {"long_view", "long_view_behind"};
    static const char *const backends[] = {"egl", "osmesa"};
    for (size_t b = 0; b < (osmesa_installed() ? 2u : 1u); b++) {
        for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++) {
            char scene_file[256], name[256];
            snprintf(scene_file, sizeof scene_file, "assets/scenes/%s.json", scenes[i]);
            snprintf(name, sizeof name, "psm_%s_%s", scenes[i], backends[b]);
            render_with("psm", backends[b], scene_file, "", name);
            double fraction = compare_with_golden_of("psm", scenes[i], name);
            assert_true(fraction >= 0 && fraction <= SUPPORT_MAX_DIFFERING);
        }
    }
    render_with("psm", "egl", "assets/scenes/long_view.json", "--overlay post-perspective", "psm_overlay_long_view");
    assert_true(compare_with_golden_of("psm", "long_view", "psm_overlay_long_view") > SUPPORT_MAX_DIFFERING);
    double fraction = compare_with_golden_of("psm-overlay", "long_view", "psm_overlay_long_view");
    assert_true(fraction >= 0 && fraction <= SUPPORT_MAX_DIFFERING);
    render_with("psm", "egl", "assets/scenes/long_view.json", "--overlay texel-size", "psm_texel_size_long_view");
    assert_true(compare_with_golden_of("psm", "long_view", "psm_texel_size_long_view") > SUPPORT_MAX_DIFFERING);
}

/* Each shadow-volume overlay draws into the picture. */
static void test_volumes_overlays_show(void **state) {
    (void)state;
    static const char *const overlays[] = {"volumes", "silhouettes", "counts"};
    for (size_t i = 0; i < sizeof overlays / sizeof *overlays; i++) {
        char flags[64], name[64];
        snprintf(flags, sizeof flags, "--overlay %s", overlays[i]);
        snprintf(name, sizeof name, "volumes_overlay_%s", overlays[i]);
        render_with("volumes", "egl", "assets/scenes/teapot.json", flags, name);
        assert_true(compare_with_golden_of("volumes", "teapot", name) > SUPPORT_MAX_DIFFERING);
    }
}

/* The GLFW window, under a virtual X server, shows the same picture. */
static void test_window_matches_golden(void **state) {
    (void)state;
    if (!support_have_command("xvfb-run")) {
        fprintf(stderr, "    xvfb-run is not installed here: skipped\n");
        skip();
    }
    char command[1024];
    snprintf(command, sizeof command,
             "xvfb-run -a -s '-screen 0 1024x768x24' %s --backend glfw --size " SIZE
             " --frames 2 --screenshot out/test/planar_simple_glfw.png",
             support_program("planar"));
    assert_int_equal(support_run(command, err, sizeof err), 0);
    double fraction = compare_with_golden("simple", "planar_simple_glfw");
    assert_true(fraction >= 0 && fraction <= SUPPORT_MAX_DIFFERING);
}

static void test_gallery_writes_every_technique(void **state) {
    (void)state;
    char command[1024];
    snprintf(command, sizeof command,
             "rm -rf out/test/gallery && %s --size " SIZE
             " --gallery out/test/gallery assets/scenes/simple.json assets/scenes/teapot.json",
             support_program("shadows"));
    assert_int_equal(support_run(command, err, sizeof err), 0);
    assert_true(support_compare_images("tests/golden/planar_simple.png", "out/test/gallery/planar_simple.png") <=
                SUPPORT_MAX_DIFFERING);
    assert_true(support_compare_images("tests/golden/planar_teapot.png", "out/test/gallery/planar_teapot.png") <=
                SUPPORT_MAX_DIFFERING);
    /* A technique's lecture picture shows its overlay: psm's post-perspective view. */
    assert_true(support_compare_images("out/test/gallery/psm_teapot.png", "out/test/gallery/psm-lecture_teapot.png") >
                SUPPORT_MAX_DIFFERING);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_egl_matches_golden),
        cmocka_unit_test(test_osmesa_matches_golden),
        cmocka_unit_test(test_psm_long_view_matches_golden),
        cmocka_unit_test(test_backends_agree),
        cmocka_unit_test(test_same_command_same_image),
        cmocka_unit_test(test_moved_light_fails_comparison),
        cmocka_unit_test(test_each_fix_shows_when_off),
        cmocka_unit_test(test_shadowmap_without_bias_shows_acne),
        cmocka_unit_test(test_shadowmap_overlays_match_golden),
        cmocka_unit_test(test_volumes_overlays_show),
        cmocka_unit_test(test_window_matches_golden),
        cmocka_unit_test(test_gallery_writes_every_technique),
    };
    return cmocka_run_group_tests_name("screenshots", tests, NULL, NULL);
}
