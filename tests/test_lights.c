/* Many lights: a scene of more lights than a shader holds is shaded in
 * light groups (common/gl/render.h, "Light groups"), and every light of
 * every group is lit and shadowed as the reference has it.
 * assets/scenes/lamps_64.json (build/scenegen): 64 point lamps on poles,
 * eight groups; and the shadow maps' budget (demos/lib/map.h,
 * "Budget"). Run from the repository root. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>
#include <stdlib.h>

#include "map_internal.h"
#include "render.h"
#include "support.h"

#define LAMPS "assets/scenes/lamps_64.json"
/* Decisions as exact as each technique's on the standard scenes (the
 * volumes' exact, the maps' within a texel's edge: test_shadowmap's
 * bound); a lamp read from another's slot or block misclassifies its
 * whole pool of light. */
#define VOLUMES_MAX_MISCLASSIFIED 0.01
#define MAPS_MAX_MISCLASSIFIED 0.5
/* A lamp's shadow decisions are compared only where it reaches: at least
 * this many pixels of the 640x360 frame, so that a lamp that lit nothing
 * would fail rather than pass. */
#define LAMPS_MIN_LIT_PIXELS 500
/* The picture against the reference's: share of pixels off by more than
 * support_compare_images' step. A lamp read from another group's block,
 * or the ambient term added again by one lamp's pass, shows over the
 * lamp's pool of light (hundreds of pixels at least); what is left is a
 * few pixels of the maps' shadow edges. */
#define LAMPS_MAX_PICTURE_PERCENT 0.02

/* The lamps measured, each lighting thousands of pixels, a sweep
 * (support_sweep_stride): a lamp of the last groups first, whose every
 * slot, unit and block the quick tier proves, then one of group 0's, as
 * every scene of up to eight lights has them, and one of a middle
 * group's. */
static const int lamps[] = {55, 7, 27};
/* The volumes': a lamp of another later group. */
#define VOLUMES_LAMP 41
/* The hybrid's: rays decide every pixel its map (poisson: with rays auto
 * keeps it, map.h) is unsure of, so it is the reference's but for a pixel
 * or two of rounding; a 2x2 test's narrower band lets more through. */
#define HYBRID_LAMP 27
#define HYBRID_MAX_MISCLASSIFIED 0.001

/* Technique `program`'s decisions for lamp `light` against the
 * reference's: at most max_percent misclassified. */
static void expect_lamp_within(const char *program, int light, double max_percent) {
    char name[64], flags[64];
    snprintf(name, sizeof name, "lamp_%d", light);
    snprintf(flags, sizeof flags, "--light %d", light);
    long pixels;
    shadowdiff_result r = support_measure_receiver(program, "lights", name, LAMPS, flags, flags, NULL, &pixels);
    long lit = r.class_pixels[SHADOWDIFF_CLASS_LIT];
    printf("    %s, lamp %d (group %d): %ld lit of %ld compared, misclassified %.4f %%\n", program, light,
           RENDER_LIGHT_GROUP(light), lit, r.compared, r.misclassified_percent);
    assert_true(lit >= LAMPS_MIN_LIT_PIXELS);
    assert_true(r.misclassified_percent <= max_percent);
}

/* The shadow maps (one camera pass per lamp, its map in its group's
 * slot) decide every measured lamp as the reference does. */
static void test_maps_shadow_every_group(void **state) {
    (void)state;
    for (size_t i = 0; i < sizeof lamps / sizeof *lamps; i += (size_t)support_sweep_stride())
        expect_lamp_within("shadowmap", lamps[i], MAPS_MAX_MISCLASSIFIED);
}

/* The volumes (a stencil pass per lamp, lit through its group's block)
 * too: a lamp of the last groups. */
static void test_volumes_shadow_a_later_group(void **state) {
    (void)state;
    expect_lamp_within("volumes", VOLUMES_LAMP, VOLUMES_MAX_MISCLASSIFIED);
}

/* The hybrid too, past eight lights: its map's filter keeps the band
 * its rays need, and its lamps' cube maps are the atlas's tiles
 * (demos/lib/map.h, "Atlas"), as the maps' are. */
static void test_hybrid_exact_past_eight_lights(void **state) {
    (void)state;
    expect_lamp_within("hybrid", HYBRID_LAMP, HYBRID_MAX_MISCLASSIFIED);
    assert_non_null(support_verbose_line("hybrid", LAMPS, "--size 320x180 --frames 1", ": cube map in atlas tiles "));
}

/* A lamp inside a caster's box, a hair from its wall (nearer than a cube
 * face's near plane, which keeps the depth's precision): the wall is
 * drawn at the near depth and its box is not culled for lying before the
 * near plane, so the ground outside is in the box's shadow, as the
 * reference has it; with depth clamp, and with --webgl2, where the GL
 * has none and the depth pass clamps the depth itself (a clipped wall
 * lights most of the ground). */
#define LAMP_IN_BOX "tests/data/map_lamp_in_box.json"
#define LAMP_IN_BOX_MAX_MISCLASSIFIED 0.05
static void test_maps_shadow_from_a_lamp_inside_a_box(void **state) {
    (void)state;
    static const struct {
        const char *name, *flags;
    } runs[] = {{"lamp_in_box", ""}, {"lamp_in_box_webgl2", "--webgl2"}};
    for (size_t i = 0; i < sizeof runs / sizeof *runs; i++) {
        long pixels;
        shadowdiff_result r = support_measure_receiver("shadowmap", "lights", runs[i].name, LAMP_IN_BOX, "",
                                                       runs[i].flags, NULL, &pixels);
        assert_true(r.compared > 0 && r.misclassified_percent <= LAMP_IN_BOX_MAX_MISCLASSIFIED);
    }
}

/* The shadow maps' picture, every lamp summed over the groups with the
 * ambient term once, is the reference's. */
static void test_picture_sums_every_group(void **state) {
    (void)state;
    char command[1024], err[4096];
    snprintf(command, sizeof command,
             "mkdir -p out/test/lights && %s --scene " LAMPS
             " --size 640x360 --screenshot out/test/lights/reference.png",
             support_program("raytrace"));
    assert_int_equal(support_run(command, err, sizeof err), 0);
    unsigned char *picture = support_screenshot("shadows", LAMPS, "--technique shadowmap", "lights/shadowmap");
    assert_non_null(picture);
    free(picture);
    double percent = support_compare_images("out/test/lights/reference.png", "out/test/lights/shadowmap.png");
    printf("    shadowmap's picture: %.3f %% of pixels off the reference's\n", percent);
    assert_true(percent >= 0 && percent <= LAMPS_MAX_PICTURE_PERCENT);
}

/* The frames of the tests that compare two runs' dumps: small, since
 * what they compare is exact. */
#define COMPARED_FLAGS "--technique shadowmap --size 320x180 --light 27"

/* Dumps of `flags` (COMPARED_FLAGS with more) into out/test/lights/NAME. */
static void lamps_dump(const char *name, const char *flags, char *dir, size_t size) {
    char all[256];
    snprintf(dir, size, "out/test/lights/%s", name);
    snprintf(all, sizeof all, COMPARED_FLAGS " %s", flags);
    assert_int_equal(support_dump("shadows", LAMPS, all, dir), 0);
}

static const char *const dump_files[] = {"visibility.pfm", "color.png"};

/* The first `files` of dump_files are the same in the dumps of two runs
 * (lamps_dump's); else fails naming the first that differs, and `what`. */
static void expect_same_dumps(const char *name_a, const char *flags_a, const char *name_b, const char *flags_b,
                              size_t files, const char *what) {
    char a[128], b[128];
    lamps_dump(name_a, flags_a, a, sizeof a);
    lamps_dump(name_b, flags_b, b, sizeof b);
    const char *differs = support_first_difference(a, b, dump_files, files);
    if (differs)
        fail_msg("%s differs %s", differs, what);
}

/* Where `marker` starts in the verbose output of one frame of the
 * street (COMPARED_FLAGS), or NULL. */
static const char *street_frame_text(const char *marker) {
    return support_verbose_line("shadows", LAMPS, COMPARED_FLAGS " --frames 1", marker);
}

/* The state line (its first line alone) of one frame of the street with
 * `flags`, into line (size bytes). */
static void street_state_line(const char *flags, char *line, size_t size) {
    const char *at = support_verbose_line("shadows", LAMPS, flags, "hud: light ");
    assert_non_null(at);
    snprintf(line, size, "%.*s", (int)strcspn(at, "\n"), at);
}

/* The caster culling leaves out the visible pixels a lamp cannot reach,
 * and cube faces no visible pixel reads are not drawn (map_cull.c): they
 * change no pixel of lamp 27's or of the picture, and some faces are
 * left undrawn. */
static void test_skips_change_nothing_on_the_street(void **state) {
    (void)state;
    expect_same_dumps("skips_on", "--frames 1", "skips_off", "--frames 1 --no-skip", 2, "with --no-skip");
    assert_non_null(street_frame_text("layers out of view, not drawn "));
}

/* The state line describes a light that has a map this frame (a lamp's
 * cube map, in the atlas's tiles: demos/lib/map.h, "Atlas"), not light
 * 0, which has none on the street, and the share of the atlas held: the
 * atlas is sized to what its tiles ask, the least power of two that holds
 * MAP_ATLAS_ROOM times their area (so they hold more than a fourth of
 * that share), smaller than MAP_ATLAS_SIZE in the small frame. */
static void test_state_line_describes_a_mapped_lamp(void **state) {
    (void)state;
    char line[512];
    street_state_line(COMPARED_FLAGS " --frames 1", line, sizeof line);
    assert_non_null(strstr(line, ": cube map in atlas tiles auto: "));
    assert_null(strstr(line, "atlas full"));
    assert_null(strstr(line, "light 0:"));
    const char *atlas = strstr(line, ", atlas ");
    int side = 0, held = 0;
    assert_true(atlas && sscanf(atlas, ", atlas %d: %d %% held", &side, &held) == 2);
    printf("    the street at 320x180: atlas %d, %d %% held\n", side, held);
    assert_true(side < MAP_ATLAS_SIZE);
    assert_true(held <= 100 / MAP_ATLAS_ROOM && held > 100 / (4 * MAP_ATLAS_ROOM));
}

/* Lamps that ask more than the largest atlas holds share it (map.h,
 * "Atlas"): every face of the street's lamps asked at 1024 texels is
 * more than MAP_ATLAS_SIZE's square over MAP_ATLAS_ROOM, so the tiles are
 * halved to fit, and no lamp is left a cube map of its own beside a full
 * atlas (memory the atlas does not bound: lamps without a range, each
 * asking the largest tiles, took gigabytes so). */
static void test_lamps_past_the_atlas_share_it(void **state) {
    (void)state;
    char line[512];
    street_state_line("--technique shadowmap --size 320x180 --map-size 1024", line, sizeof line);
    printf("    %s\n", line);
    assert_non_null(strstr(line, ", tiles halved "));
    assert_null(strstr(line, "atlas full"));
}

/* The map overlay shows the atlas (map.h, "Atlas"): where no tile is
 * drawn it is cleared to the far plane when made, not whatever its memory
 * held (black on llvmpipe, over most of the inset): at most
 * ATLAS_INSET_MAX_BLACK of the inset's pixels are black, the nearest
 * depth's colour. */
#define ATLAS_INSET_MAX_BLACK 0.05
static void test_atlas_overlay_shows_no_stray_memory(void **state) {
    (void)state;
    unsigned char *rgba =
        support_screenshot("shadows", LAMPS, "--technique shadowmap --overlay map", "lights/atlas_overlay");
    assert_non_null(rgba);
    int rect[4];
    map_inset_rect(MAP_2D, 1, 0, SUPPORT_SCREENSHOT_WIDTH, SUPPORT_SCREENSHOT_HEIGHT, rect);
    static const unsigned char black[3] = {0, 0, 0};
    long count = support_count_color(rgba, SUPPORT_SCREENSHOT_WIDTH, SUPPORT_SCREENSHOT_HEIGHT, rect, black);
    free(rgba);
    double share = (double)count / ((double)rect[2] * rect[3]);
    printf("    the atlas's inset: %.1f %% black\n", 100.0 * share);
    assert_true(share <= ATLAS_INSET_MAX_BLACK);
}

/* The atlas's kind in the browser's dialect (shaders/map_tiles.glsl
 * reads it through a struct that holds its sampler): --glsl-es draws the
 * street's decisions and picture byte for byte as desktop GLSL does. */
static void test_atlas_in_glsl_es(void **state) {
    (void)state;
    expect_same_dumps("desktop", "--frames 1", "glsl_es", "--frames 1 --glsl-es", 2, "with --glsl-es");
}

/* The atlas's tiles follow the camera across frames, each face keeping
 * its tile while asked at the same size and its cache with it: with the
 * camera moving, the fourth frame's decisions and picture are those of a
 * run that caches nothing (--no-skip places the tiles the same). */
static void test_atlas_tiles_follow_the_camera(void **state) {
    (void)state;
    expect_same_dumps("camera_skips_on", "--motion camera --frames 4", "camera_skips_off",
                      "--motion camera --frames 4 --no-skip", 2, "with --no-skip, the camera moving");
}

/* Past eight lights the maps' auto filter stands for hw (map.h, "The
 * camera pass"): the same pixels as --filter hw, and the state line says
 * so. */
static void test_auto_filter_is_hw_past_eight_lights(void **state) {
    (void)state;
    expect_same_dumps("filter_auto", "--frames 1", "filter_hw", "--frames 1 --filter hw", 2,
                      "between --filter auto and --filter hw");
    assert_non_null(street_frame_text(", filter: hw (many lights)"));
}

/* While nothing moves no map is due: a budget changes no pixel. */
static void test_budget_changes_nothing_while_still(void **state) {
    (void)state;
    expect_same_dumps("still_free", "--frames 3", "still_budget", "--frames 3 --shadow-budget 1", 2,
                      "with --shadow-budget 1, nothing moving");
}

/* Every lamp moving, one map a frame: the first frame draws every map
 * (a light's first is drawn whatever the budget), the next the longest
 * waiting in their order, lamp 0 first; lamp 27 keeps its first map and
 * is drawn as it was then, its light and its shadow alike, so its
 * decisions on frame 3 are frame 1's, and the HUD counts the kept maps. */
static void test_budget_draws_a_kept_light_as_it_was(void **state) {
    (void)state;
    expect_same_dumps("moving_first", "--motion light --frames 1", "moving_kept",
                      "--motion light --frames 3 --shadow-budget 1", 1,
                      "between lamp 27 on frame 1 and on frame 3 past the budget");
    const char *line = support_verbose_line(
        "shadows", LAMPS, COMPARED_FLAGS " --motion light --frames 3 --shadow-budget 1", "maps kept past the budget");
    assert_non_null(line);
}

/* Many spots, each asking a map of SPOTS_SIZE (--map-size), ask more
 * than the lights' own maps may hold (map.h, "Memory"): the first of the
 * largest are halved, one at a time, until the sum fits, as many times as
 * that sum says, and the state line says how many (light 0, the first,
 * is one of them). At the automatic sizes the same spots fit whole. */
#define SPOTS "tests/data/many_spots.json"
#define SPOTS_COUNT 24
#define SPOTS_SIZE 4096
#define SPOTS_FLAGS "--technique shadowmap --size 320x180"
/* Whether the first line of `text` holds `part`. */
static bool first_line_has(const char *text, const char *part) {
    const char *at = strstr(text, part);
    return at && at + strlen(part) <= text + strcspn(text, "\n");
}

static void test_own_maps_halved_to_fit_the_memory(void **state) {
    (void)state;
    int halvings = 0;
    double side = SPOTS_SIZE;
    for (double texels = SPOTS_COUNT * side * side; texels > MAP_MEMORY_TEXELS; halvings++)
        texels -= side * side - side / 2 * side / 2;
    assert_true(halvings > 0 && halvings < SPOTS_COUNT);
    const char *line =
        support_verbose_line("shadows", SPOTS, SPOTS_FLAGS " --map-size " FLAGS_TEXT(SPOTS_SIZE), "hud: light 0: ");
    assert_non_null(line);
    printf("    %.*s\n", (int)strcspn(line, "\n"), line);
    char expected[64];
    snprintf(expected, sizeof expected, "maps halved %d times to fit the memory", halvings);
    assert_true(first_line_has(line, expected));
    snprintf(expected, sizeof expected, "2D map %d, ", SPOTS_SIZE / 2);
    assert_true(first_line_has(line, expected));
    line = support_verbose_line("shadows", SPOTS, SPOTS_FLAGS, "hud: light 0: ");
    assert_non_null(line);
    assert_false(first_line_has(line, "maps halved"));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_maps_shadow_every_group),
        cmocka_unit_test(test_volumes_shadow_a_later_group),
        cmocka_unit_test(test_hybrid_exact_past_eight_lights),
        cmocka_unit_test(test_maps_shadow_from_a_lamp_inside_a_box),
        cmocka_unit_test(test_picture_sums_every_group),
        cmocka_unit_test(test_skips_change_nothing_on_the_street),
        cmocka_unit_test(test_state_line_describes_a_mapped_lamp),
        cmocka_unit_test(test_lamps_past_the_atlas_share_it),
        cmocka_unit_test(test_atlas_tiles_follow_the_camera),
        cmocka_unit_test(test_atlas_in_glsl_es),
        cmocka_unit_test(test_atlas_overlay_shows_no_stray_memory),
        cmocka_unit_test(test_auto_filter_is_hw_past_eight_lights),
        cmocka_unit_test(test_budget_changes_nothing_while_still),
        cmocka_unit_test(test_budget_draws_a_kept_light_as_it_was),
        cmocka_unit_test(test_own_maps_halved_to_fit_the_memory),
    };
    return cmocka_run_group_tests_name("many lights", tests, NULL, NULL);
}
