/* Compare mode (common/programs/compare.h) as a lecturer's slide uses it:
 * `--compare --screenshot` writes four cells, and each must be exactly
 * what the separate programs give for that view at the cell's size:
 *   top left     the technique's own screenshot,
 *   top right    build/raytrace's picture (the truth panel is the
 *                reference, byte for byte),
 *   bottom left  build/shadowdiff's heat map of the two dumps, its errors
 *                grown to discs,
 * and the figures it prints are shadowdiff's. Over a spot (simple), a
 * point light (bunny) and a directional one (long_view), for a uniform map
 * and a warped one, and an area light (soft_table: the figures of
 * shadowdiff's classes, its penumbra's among them; the hard lights'
 * penumbra "none"); the HUD stays in the caption strip above the cells
 * at a lecture's sizes and the heat map's errors are drawn large enough
 * to see; the same command gives the same bytes, the window
 * (under Xvfb, scripted with --frames) gives the same picture, and
 * --compare with --gallery is refused. In-process: the frame loop never
 * waits for the truth, which is shown row by row as it comes (rows not
 * traced repeat the nearest traced one above) and ends as the reference. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <threads.h>
#include <time.h>

#include <cjson/cJSON.h>

#include "compare.h"
#include "context.h"
#include "hud.h"
#include "path.h"
#include "shader.h"
#include "support.h"

#define DIR "out/test/compare"
#define WIDTH 640
#define HEIGHT 360
#define STRIP compare_strip_height(HEIGHT)
#define CELL_WIDTH (WIDTH / 2)
#define CELL_HEIGHT ((HEIGHT - STRIP) / 2)
/* The lecture sizes at which the HUD must cover no cell. */
static const int lecture_sizes[][2] = {{1280, 720}, {1920, 1080}};
#define EXIT_USAGE 2
/* The figures are printed with 4 decimals (%) and 5 (error). */
#define PERCENT_PRINTED 5e-5
#define ERROR_PRINTED 5e-6

typedef struct compare_case {
    const char *technique, *scene;
} compare_case;

static const compare_case compare_cases[] = {
    {"shadowmap", "simple"},
    {"shadowmap", "bunny"},
    {"psm", "long_view"},
    {"shadowmap", "soft_table"},
};

static char err[16384];

/* Runs `command` (its own redirections inside a subshell: support_run
 * sends the outer stdout away). */
static void run(const char *command) {
    char full[2100];
    snprintf(full, sizeof full, "( %s )", command);
    int status = support_run(full, err, sizeof err);
    if (status != 0)
        fail_msg("%s failed (exit status %d): %s", command, status, err);
}

/* The cell at (x0, y0) of a WIDTH x HEIGHT picture against an image of the
 * cell's size (a heat map's errors magnified as compare mode draws them):
 * whether every byte agrees. */
static bool cell_is(const unsigned char *picture, int x0, int y0, const char *path, bool heat_map) {
    unsigned char *cell = support_read_png(path, CELL_WIDTH, CELL_HEIGHT);
    if (heat_map)
        assert_true(
            shadowdiff_heatmap_magnify(cell, CELL_WIDTH, CELL_HEIGHT, shadowdiff_magnify_radius(CELL_HEIGHT)));
    bool same = true;
    for (int y = 0; y < CELL_HEIGHT && same; y++)
        same = memcmp(picture + ((size_t)(y0 + y) * WIDTH + (size_t)x0) * 4, cell + (size_t)y * CELL_WIDTH * 4,
                      (size_t)CELL_WIDTH * 4) == 0;
    free(cell);
    return same;
}

/* "NAME VALUE" after `key` in the compare line. */
static double figure_after(const char *line, const char *key) {
    const char *at = strstr(line, key);
    if (!at)
        fail_msg("no \"%s\" in: %s", key, line);
    return strtod(at + strlen(key), NULL);
}

/* Each class's "CLASS MAE E (N px)" in the compare line is shadowdiff's
 * JSON's CLASS_mae and CLASS_pixels, "none" where the JSON's MAE is null.
 * Returns whether the line gave the penumbra a figure. */
static bool expect_class_figures(const char *line, const cJSON *figures) {
    bool penumbra = false;
    for (int k = 0; k < SHADOWDIFF_CLASS_COUNT; k++) {
        char key[64], label[64];
        snprintf(label, sizeof label, ", %s MAE ", shadowdiff_class_names[k]); /* not "penumbra" for "umbra" */
        const char *at = strstr(line, label);
        if (!at)
            fail_msg("no \"%s\" in: %s", label, line);
        at += strlen(label);
        snprintf(key, sizeof key, "%s_pixels", shadowdiff_class_names[k]);
        double pixels = cJSON_GetObjectItem(figures, key)->valuedouble;
        snprintf(key, sizeof key, "%s_mae", shadowdiff_class_names[k]);
        const cJSON *mae = cJSON_GetObjectItem(figures, key);
        char *end;
        if (cJSON_IsNull(mae)) {
            assert_true(strncmp(at, SHADOWDIFF_NO_FIGURE " (0 px)", strlen(SHADOWDIFF_NO_FIGURE " (0 px)")) == 0);
            assert_true(pixels == 0);
            continue;
        }
        assert_true(fabs(strtod(at, &end) - mae->valuedouble) <= ERROR_PRINTED);
        assert_true(strncmp(end, " (", 2) == 0);
        assert_true(fabs(strtod(end + 2, NULL) - pixels) < 0.5);
        assert_true(pixels > 0);
        penumbra = penumbra || k == SHADOWDIFF_CLASS_PENUMBRA;
    }
    return penumbra;
}

static void test_cells_are_the_programs_pictures(void **state) {
    (void)state;
    assert_true(path_make_directories(DIR));
    for (size_t i = 0; i < sizeof compare_cases / sizeof *compare_cases; i++) {
        const compare_case *c = &compare_cases[i];
        char command[2048], prefix[256], scene[256];
        snprintf(prefix, sizeof prefix, DIR "/%s_%s", c->technique, c->scene);
        snprintf(scene, sizeof scene, "assets/scenes/%s.json", c->scene);
        snprintf(command, sizeof command,
                 "%s --backend egl --technique %s --scene %s --size %dx%d --compare --screenshot %s.png > %s.txt",
                 support_program("shadows"), c->technique, scene, WIDTH, HEIGHT, prefix, prefix);
        run(command);
        snprintf(command, sizeof command,
                 "%s --backend egl --technique %s --scene %s --size %dx%d --screenshot %s_technique.png "
                 "--dump %s_dump",
                 support_program("shadows"), c->technique, scene, CELL_WIDTH, CELL_HEIGHT, prefix, prefix);
        run(command);
        snprintf(command, sizeof command, "%s --scene %s --size %dx%d --screenshot %s_truth.png --dump %s_reference",
                 support_program("raytrace"), scene, CELL_WIDTH, CELL_HEIGHT, prefix, prefix);
        run(command);
        snprintf(command, sizeof command, "%s %s_reference %s_dump --json --heatmap %s_heatmap.png > %s_figures.json",
                 support_program("shadowdiff"), prefix, prefix, prefix, prefix);
        run(command);

        char path[300];
        snprintf(path, sizeof path, "%s.png", prefix);
        unsigned char *picture = support_read_png(path, WIDTH, HEIGHT);
        snprintf(path, sizeof path, "%s_technique.png", prefix);
        if (!cell_is(picture, 0, STRIP, path, false))
            fail_msg("%s: the technique's cell is not %s", prefix, path);
        snprintf(path, sizeof path, "%s_truth.png", prefix);
        if (!cell_is(picture, CELL_WIDTH, STRIP, path, false))
            fail_msg("%s: the truth's cell is not build/raytrace's %s", prefix, path);
        snprintf(path, sizeof path, "%s_heatmap.png", prefix);
        if (!cell_is(picture, 0, STRIP + CELL_HEIGHT, path, true))
            fail_msg("%s: the heat map's cell is not build/shadowdiff's %s, magnified", prefix, path);
        free(picture);

        snprintf(path, sizeof path, "%s.txt", prefix);
        char *line = path_read_text(path, 1 << 16, NULL);
        snprintf(path, sizeof path, "%s_figures.json", prefix);
        char *json = path_read_text(path, 1 << 16, NULL);
        assert_non_null(line);
        assert_non_null(json);
        cJSON *figures = cJSON_Parse(json);
        assert_non_null(figures);
        double misclassified = cJSON_GetObjectItem(figures, "misclassified_percent")->valuedouble;
        double error = cJSON_GetObjectItem(figures, "mean_abs_error")->valuedouble;
        double compared = cJSON_GetObjectItem(figures, "compared")->valuedouble;
        printf("    %s on %s: %s", c->technique, c->scene, line);
        char rows[64];
        snprintf(rows, sizeof rows, "truth %d/%d rows", CELL_HEIGHT, CELL_HEIGHT);
        assert_true(strstr(line, rows) != NULL);
        assert_true(fabs(figure_after(line, "misclassified ") - misclassified) <= PERCENT_PRINTED);
        assert_true(fabs(figure_after(line, "mean absolute error ") - error) <= ERROR_PRINTED);
        assert_true(fabs(figure_after(strstr(line, "error "), ", ") - compared) < 0.5);
        bool soft = strncmp(c->scene, "soft_", strlen("soft_")) == 0;
        if (expect_class_figures(line, figures) != soft)
            fail_msg("%s on %s: the penumbra %s a figure: %s", c->technique, c->scene, soft ? "lacks" : "has", line);
        cJSON_Delete(figures);
        free(json);
        free(line);
    }
}

static void test_same_command_same_bytes(void **state) {
    (void)state;
    assert_true(path_make_directories(DIR));
    const char *names[] = {"again.png"};
    for (int k = 0; k < 2; k++) {
        char command[1024];
        snprintf(command, sizeof command,
                 "%s --backend egl --technique psm --scene assets/scenes/long_view.json --size %dx%d --compare "
                 "--motion light --frames 3 --screenshot " DIR "/run%d/again.png > /dev/null",
                 support_program("shadows"), WIDTH, HEIGHT, k);
        char dir[64];
        snprintf(dir, sizeof dir, DIR "/run%d", k);
        assert_true(path_make_directories(dir));
        run(command);
    }
    assert_null(support_first_difference(DIR "/run0", DIR "/run1", names, 1));
}

/* The window, scripted with --frames, waits for the truth as a headless
 * run does, and shows the same picture. */
static void test_window_shows_the_same(void **state) {
    (void)state;
    const char *xvfb = support_xvfb_run();
    char command[1024];
    snprintf(command, sizeof command,
             "%s %s --backend glfw --technique shadowmap --size %dx%d --compare "
             "--frames 2 --screenshot " DIR "/window.png > /dev/null",
             xvfb, support_program("shadows"), WIDTH, HEIGHT);
    run(command);
    snprintf(command, sizeof command,
             "%s --backend egl --technique shadowmap --size %dx%d --compare --screenshot " DIR "/headless.png "
             "> /dev/null",
             support_program("shadows"), WIDTH, HEIGHT);
    run(command);
    double differing = support_compare_images(DIR "/headless.png", DIR "/window.png");
    assert_true(differing >= 0 && differing <= SUPPORT_MAX_DIFFERING);
}

/* psm on long_view at a lecture's sizes, with the HUD and without: the
 * HUD is in the caption strip and nowhere else (every row below it the
 * same bytes), and the heat map's errors, a few hundredths of a percent,
 * cover a visible share of its cell. */
static void test_hud_covers_no_cell_and_errors_show(void **state) {
    (void)state;
    assert_true(path_make_directories(DIR));
    for (size_t k = 0; k < sizeof lecture_sizes / sizeof *lecture_sizes; k++) {
        int width = lecture_sizes[k][0], height = lecture_sizes[k][1];
        char paths[2][128], command[1024];
        for (int hud = 0; hud < 2; hud++) {
            snprintf(paths[hud], sizeof paths[hud], DIR "/lecture_%dx%d%s.png", width, height, hud ? "_hud" : "");
            snprintf(command, sizeof command,
                     "%s --backend egl --technique psm --scene assets/scenes/long_view.json --size %dx%d --compare "
                     "%s --screenshot %s > " DIR "/lecture.txt",
                     support_program("shadows"), width, height, hud ? "--hud" : "", paths[hud]);
            run(command);
        }
        unsigned char *plain = support_read_png(paths[0], width, height);
        unsigned char *with_hud = support_read_png(paths[1], width, height);
        int strip = compare_strip_height(height), cell_width = width / 2, cell_height = (height - strip) / 2;
        size_t row = (size_t)width * 4;
        if (memcmp(plain + strip * row, with_hud + strip * row, (size_t)(height - strip) * row) != 0)
            fail_msg("%dx%d: the HUD reaches below its %d-pixel strip", width, height, strip);
        if (memcmp(plain, with_hud, (size_t)strip * row) == 0)
            fail_msg("%dx%d: no HUD in the strip", width, height);
        double share = support_error_share(plain, width, 0, strip + cell_height, cell_width, cell_height);
        char *line = path_read_text(DIR "/lecture.txt", 1 << 16, NULL);
        assert_non_null(line);
        double misclassified = figure_after(line, "misclassified ");
        printf("    %dx%d: misclassified %.4f %%, error discs cover %.3f %% of the heat map's cell\n", width, height,
               misclassified, 100 * share);
        assert_true(misclassified > 0);
        assert_true(share >= SUPPORT_VISIBLE_ERROR_SHARE);
        free(line);
        free(with_hud);
        free(plain);
    }
}

static void test_refused_with_gallery(void **state) {
    (void)state;
    char command[1024];
    snprintf(command, sizeof command,
             "%s --backend egl --compare --gallery " DIR "/gallery assets/scenes/simple.json",
             support_program("shadows"));
    assert_int_equal(support_run(command, err, sizeof err), EXIT_USAGE);
    assert_int_equal(support_count_lines(err), 1);
    assert_non_null(strstr(err, "--compare and --gallery"));
}

/* In-process: the truth of an area light (many shadow rays a pixel, so
 * it takes a while) seen as it comes. The "technique" is the reference
 * itself, so the figures must say it agrees everywhere. */
#define PROGRESS_SCENE "assets/scenes/simple.json"
#define PROGRESS_LIGHT_RADIUS 0.3f
#define PROGRESS_LIGHT_SAMPLES 64
#define PROGRESS_TIMEOUT_SECONDS 120
#define PROGRESS_POLL_NS 1000000L /* a millisecond: many polls a band */

static scene progress_scene;
static const raytrace_settings progress_settings = {.light_samples = PROGRESS_LIGHT_SAMPLES};

static bool capture_reference(int light, dump_frame *out) {
    return raytrace_render(&progress_scene, CELL_WIDTH, CELL_HEIGHT, light, &progress_settings, out);
}

/* The truth's cell of the picture read back: every row is the truth's row,
 * or for a row not traced yet, the nearest traced row above. */
static void expect_truth_cell(const compare *c) {
    unsigned char *picture = malloc((size_t)WIDTH * HEIGHT * 4);
    assert_non_null(picture);
    assert_true(target_read_rgba(&c->picture, picture));
    int source = 0;
    for (int y = 0; y < CELL_HEIGHT; y++) {
        source = c->traced[y] ? y : source;
        const unsigned char *shown = picture + ((size_t)(STRIP + y) * WIDTH + CELL_WIDTH) * 4;
        assert_memory_equal(shown, c->shown.dump.color + (size_t)source * CELL_WIDTH * 4, (size_t)CELL_WIDTH * 4);
    }
    free(picture);
}

static void test_frame_loop_never_waits(void **state) {
    (void)state;
    context ctx;
    target cell;
    compare c;
    shader_set_directory("shaders");
    const context_settings settings = {.backend = CONTEXT_EGL};
    assert_true(context_create(&ctx, &settings));
    assert_true(hud_init());
    assert_true(scene_load(&progress_scene, PROGRESS_SCENE));
    progress_scene.lights[0].radius = PROGRESS_LIGHT_RADIUS;
    assert_true(compare_create(&c, WIDTH, HEIGHT, &progress_settings, NULL));
    assert_true(target_create(&cell, c.cell_width, c.cell_height));

    /* The first frame comes back before the truth is there. */
    assert_true(compare_update(&c, &progress_scene, 0, capture_reference, false));
    assert_false(c.shown.complete);
    bool partial_seen = false;
    time_t start = time(NULL);
    while (!c.shown.complete && time(NULL) - start < PROGRESS_TIMEOUT_SECONDS) {
        thrd_sleep(&(struct timespec){.tv_nsec = PROGRESS_POLL_NS}, NULL);
        assert_true(compare_update(&c, &progress_scene, 0, capture_reference, false));
        if (c.shown.rows > 0 && c.shown.rows < CELL_HEIGHT && !partial_seen) {
            partial_seen = true;
            assert_true(compare_draw(&c, &cell));
            expect_truth_cell(&c);
        }
    }
    assert_true(c.shown.complete);
    assert_true(partial_seen);
    assert_true(compare_draw(&c, &cell));
    expect_truth_cell(&c);
    dump_frame reference;
    assert_true(raytrace_render(&progress_scene, CELL_WIDTH, CELL_HEIGHT, 0, &progress_settings, &reference));
    assert_memory_equal(reference.color, c.shown.dump.color, (size_t)CELL_WIDTH * CELL_HEIGHT * 4);
    dump_frame_free(&reference);
    assert_true(c.measured);
    assert_true(c.result.compared > 0);
    assert_int_equal(c.result.false_shadow + c.result.false_lit, 0);

    /* A moved light restarts it; going away mid-trace does not hang. */
    progress_scene.lights[0].direction[0] += 0.2f;
    assert_true(compare_update(&c, &progress_scene, 0, capture_reference, false));
    assert_false(c.shown.complete);
    compare_forget(&c);
    target_destroy(&cell);
    compare_destroy(&c);
    scene_free(&progress_scene);
    hud_destroy();
    context_destroy(&ctx);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cells_are_the_programs_pictures),
        cmocka_unit_test(test_same_command_same_bytes),
        cmocka_unit_test(test_window_shows_the_same),
        cmocka_unit_test(test_refused_with_gallery),
        cmocka_unit_test(test_hud_covers_no_cell_and_errors_show),
        cmocka_unit_test(test_frame_loop_never_waits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
