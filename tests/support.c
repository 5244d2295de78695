#include "support.h"

#include <setjmp.h>
#include <stdarg.h>
#include <cmocka.h>

#include <fcntl.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include "hud.h"
#include "image.h"
#include "path.h"
#include "map_internal.h"

const char *support_program(const char *name) {
    static char command[4][2048];
    static int next;
    const char *build = getenv("BUILD"), *preload = getenv("TEST_PRELOAD");
    char *out = command[next++ % 4];
    snprintf(out, sizeof command[0], "%s%s%s%s/%s", preload ? "env LD_PRELOAD='" : "", preload ? preload : "",
             preload ? "' " : "", build && *build ? build : "build", name);
    return out;
}

static bool support_whole_matrix(void) {
    const char *tier = getenv("TEST_TIER");
    return tier && strcmp(tier, "all") == 0;
}

int support_sweep_stride(void) {
    if (getenv("TEST_SANITIZER"))
        return SUPPORT_SANITIZER_STRIDE;
    return support_whole_matrix() ? 1 : SUPPORT_QUICK_STRIDE;
}

bool support_sweep_takes(int setting, int scene, int scene_count) {
    return support_whole_matrix() || scene == setting % scene_count;
}

int support_run(const char *command, char *stderr_text, size_t capacity) {
    /* One file per test process: two test programs may run at once. */
    char err_path[64], full[4096];
    snprintf(err_path, sizeof err_path, "out/test/stderr-%ld.txt", (long)getpid());
    snprintf(full, sizeof full, "mkdir -p out/test && %s 2>%s >/dev/null", command, err_path);
    int status = system(full);
    stderr_text[0] = '\0';
    FILE *f = fopen(err_path, "r");
    if (f) {
        size_t n = fread(stderr_text, 1, capacity - 1, f);
        stderr_text[n] = '\0';
        fclose(f);
    }
    if (stderr_text[0])
        fprintf(stderr, "    $ %s\n    %s", command, stderr_text);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* The helpers' frame size, where `flags` give none. */
static const char *support_default_size(const char *flags) { return strstr(flags, "--size") ? "" : "--size 640x360"; }

const char *support_verbose_line(const char *program, const char *scene, const char *flags, const char *marker) {
    static char text[16384];
    char command[2048];
    snprintf(command, sizeof command, "%s %s --scene %s %s %s --verbose", support_program(program),
             support_default_size(flags), scene, flags, strstr(flags, "--frames") ? "" : "--frames 1");
    assert_int_equal(support_run(command, text, sizeof text), 0);
    return strstr(text, marker);
}

int support_count_lines(const char *text) {
    int lines = 0;
    for (const char *p = text; *p; p++)
        lines += *p == '\n';
    return lines;
}

double support_compare_images(const char *golden, const char *actual) {
    int gw, gh, aw, ah;
    unsigned char *g = image_read_png(golden, &gw, &gh), *a = image_read_png(actual, &aw, &ah);
    double fraction = -1;
    if (g && a && gw == aw && gh == ah) {
        unsigned char *diff = malloc((size_t)aw * ah * 4);
        long over = image_compare(g, a, aw, ah, SUPPORT_TOLERANCE, diff);
        fraction = (double)over / ((double)aw * ah);
        if (fraction > SUPPORT_MAX_DIFFERING) {
            char diff_path[1024];
            snprintf(diff_path, sizeof diff_path, "%.*s_diff.png", (int)(strlen(actual) - 4), actual);
            image_write_png(diff_path, aw, ah, diff);
            fprintf(stderr, "    %s: %.3f %% of pixels differ from %s by more than %d/255; diff: %s\n", actual,
                    fraction * 100, golden, SUPPORT_TOLERANCE, diff_path);
        }
        free(diff);
    } else if (g && a) {
        fprintf(stderr, "    %s is %dx%d, %s is %dx%d\n", actual, aw, ah, golden, gw, gh);
    }
    free(g);
    free(a);
    return fraction;
}

int support_dump(const char *program, const char *scene, const char *flags, const char *dir) {
    static char err[16384];
    char command[2048];
    snprintf(command, sizeof command, "%s %s --scene %s %s --dump %s", support_program(program),
             support_default_size(flags), scene, flags, dir);
    return support_run(command, err, sizeof err);
}

/* Dumps are a few MB: room for the largest with margin. */
#define SUPPORT_MAX_COMPARED_BYTES (64 << 20)

const char *support_first_difference(const char *a, const char *b, const char *const *names, size_t count) {
    for (size_t i = 0; i < count; i++) {
        char a_path[1024], b_path[1024];
        snprintf(a_path, sizeof a_path, "%s/%s", a, names[i]);
        snprintf(b_path, sizeof b_path, "%s/%s", b, names[i]);
        size_t a_length, b_length;
        char *a_bytes = path_read_text(a_path, SUPPORT_MAX_COMPARED_BYTES, &a_length);
        char *b_bytes = path_read_text(b_path, SUPPORT_MAX_COMPARED_BYTES, &b_length);
        bool same = a_bytes && b_bytes && a_length == b_length && memcmp(a_bytes, b_bytes, a_length) == 0;
        free(a_bytes);
        free(b_bytes);
        if (!same)
            return names[i];
    }
    return NULL;
}

unsigned char *support_read_png(const char *path, int width, int height) {
    int w, h;
    unsigned char *rgba = image_read_png(path, &w, &h);
    if (!rgba)
        fail_msg("%s: cannot read the picture", path);
    assert_int_equal(w, width);
    assert_int_equal(h, height);
    return rgba;
}

double support_error_share(const unsigned char *rgba, int stride, int x0, int y0, int width, int height) {
    long errors = 0;
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            const unsigned char *p = rgba + ((size_t)(y0 + y) * stride + x0 + x) * 4;
            errors += memcmp(p, shadowdiff_pixel_colors[SHADOWDIFF_PIXEL_FALSE_SHADOW], 3) == 0 ||
                      memcmp(p, shadowdiff_pixel_colors[SHADOWDIFF_PIXEL_FALSE_LIT], 3) == 0;
        }
    return (double)errors / ((double)width * height);
}

unsigned char *support_screenshot(const char *program, const char *scene, const char *flags, const char *name) {
    static char err[16384];
    char command[2048], path[512];
    snprintf(path, sizeof path, "out/test/%s.png", name);
    snprintf(command, sizeof command, "mkdir -p out/test && %s --size %dx%d --scene %s %s --screenshot %s",
             support_program(program), SUPPORT_SCREENSHOT_WIDTH, SUPPORT_SCREENSHOT_HEIGHT, scene, flags, path);
    if (support_run(command, err, sizeof err) != 0)
        fail_msg("%s failed: %s", command, err);
    return support_read_png(path, SUPPORT_SCREENSHOT_WIDTH, SUPPORT_SCREENSHOT_HEIGHT);
}

const unsigned char *support_pixel(const unsigned char *rgba, int width, int height, int x, int y) {
    return rgba + ((size_t)(height - 1 - y) * (size_t)width + (size_t)x) * 4;
}

/* rect clipped to the picture: x0, y0, x1, y1 (exclusive). */
static void support_clip(const int rect[4], int width, int height, int out[4]) {
    out[0] = rect[0] < 0 ? 0 : rect[0];
    out[1] = rect[1] < 0 ? 0 : rect[1];
    out[2] = rect[0] + rect[2] > width ? width : rect[0] + rect[2];
    out[3] = rect[1] + rect[3] > height ? height : rect[1] + rect[3];
}

static bool support_same_color(const unsigned char *p, const unsigned char rgb[3]) {
    for (int c = 0; c < 3; c++)
        if (abs((int)p[c] - (int)rgb[c]) > 1)
            return false;
    return true;
}

int support_grey_spread(const unsigned char *rgba, int width, int height, const int rect[4], int max_grey,
                        long *count) {
    long histogram[256] = {0}, n = 0;
    int r[4];
    support_clip(rect, width, height, r);
    for (int y = r[1]; y < r[3]; y++)
        for (int x = r[0]; x < r[2]; x++) {
            const unsigned char *p = support_pixel(rgba, width, height, x, y);
            if (p[0] == p[1] && p[1] == p[2] && p[0] <= max_grey) {
                histogram[p[0]]++;
                n++;
            }
        }
    *count = n;
    if (n == 0)
        return 0;
    int low = -1, high = 0;
    long seen = 0;
    for (int g = 0; g < 256; g++) {
        seen += histogram[g];
        if (low < 0 && seen * 20 >= n)
            low = g;
        if (seen * 20 < n * 19)
            high = g + 1;
    }
    return high - low > 0 ? high - low : 0;
}

long support_count_color(const unsigned char *rgba, int width, int height, const int rect[4],
                         const unsigned char rgb[3]) {
    long n = 0;
    int r[4];
    support_clip(rect, width, height, r);
    for (int y = r[1]; y < r[3]; y++)
        for (int x = r[0]; x < r[2]; x++)
            n += support_same_color(support_pixel(rgba, width, height, x, y), rgb);
    return n;
}

bool support_find_square(const unsigned char *rgba, int width, int height, const int rect[4],
                         const unsigned char rgb[3], int side) {
    int r[4];
    support_clip(rect, width, height, r);
    for (int y = r[1]; y + side <= r[3]; y++)
        for (int x = r[0]; x + side <= r[2]; x++) {
            bool all = true;
            for (int dy = 0; all && dy < side; dy++)
                for (int dx = 0; all && dx < side; dx++)
                    all = support_same_color(support_pixel(rgba, width, height, x + dx, y + dy), rgb);
            if (all)
                return true;
        }
    return false;
}

unsigned char *support_expect_insets_fitted(const char *program, const char *scene, const char *flags,
                                            const char *name, int kind, int layer_count, unsigned empty) {
    unsigned char *rgba = support_screenshot(program, scene, flags, name);
    int max_grey = (MAP_INSET_FAR_GREY_PERCENT * 255 + 99) / 100;
    int insets = map_inset_count((map_kind)kind, layer_count);
    bool ok = true;
    for (int k = 0; k < insets; k++) {
        int rect[4];
        long held;
        map_inset_rect((map_kind)kind, layer_count, k, SUPPORT_SCREENSHOT_WIDTH, SUPPORT_SCREENSHOT_HEIGHT, rect);
        int spread =
            support_grey_spread(rgba, SUPPORT_SCREENSHOT_WIDTH, SUPPORT_SCREENSHOT_HEIGHT, rect, max_grey, &held);
        bool expected_empty = (empty >> k) & 1u;
        fprintf(stderr, "    %s inset %d: %ld pixels of held depth, grey spread %d (5th to 95th percentile)%s\n",
                name, k, held, spread, expected_empty ? ", an empty layer" : "");
        if (!expected_empty)
            ok = ok && held >= SUPPORT_INSET_MIN_HELD && spread >= SUPPORT_INSET_MIN_SPREAD;
    }
    if (!ok) {
        free(rgba);
        fail_msg("%s: an inset is blank or flat", name);
    }
    return rgba;
}

bool support_have_command(const char *name) {
    char command[256];
    snprintf(command, sizeof command, "command -v %s >/dev/null 2>&1", name);
    return system(command) == 0;
}

#define SUPPORT_XVFB_LOCK "/tmp/shadows-test-xvfb.lock"

const char *support_xvfb_run(void) {
    if (!support_have_command("xvfb-run")) {
        fprintf(stderr, "    xvfb-run is not installed here: skipped\n");
        skip();
    }
    /* One virtual X server at a time (flock on SUPPORT_XVFB_LOCK): the two
     * builds' test passes run side by side, and two xvfb-run -a started
     * together can take the same display, where one script's keys reach
     * the other's window. */
    return "flock " SUPPORT_XVFB_LOCK " env -u LD_PRELOAD xvfb-run -a -s '-screen 0 1024x768x24'";
}

/* What each F12 of support_expect_captions finds changed; NULL: nothing. */
static const char *const support_caption_changes[SUPPORT_CAPTION_PICTURES] = {NULL, "technique volumes", NULL,
                                                                              "constant-bias OFF"};

/* The brightest grey (the least of a pixel's channels) where the HUD's
 * first line begins ("step"), at the scale the HUD takes at `height`. */
static int support_caption_brightness(const unsigned char *rgba, int width, int height) {
    int scale = hud_scale_for(height), brightest = 0;
    int x0 = HUD_MARGIN * scale, x1 = x0 + hud_text_width("step") * scale;
    for (int y = HUD_MARGIN * scale; y < (HUD_MARGIN + HUD_LETTER_UNITS) * scale; y++)
        for (int x = x0; x < x1 && x < width; x++) {
            const unsigned char *p = rgba + ((size_t)y * (size_t)width + (size_t)x) * 4;
            int grey = p[0] < p[1] ? p[0] : p[1];
            grey = grey < p[2] ? grey : p[2];
            brightest = grey > brightest ? grey : brightest;
        }
    return brightest;
}

void support_expect_captions(const char *log, const char *const pictures[SUPPORT_CAPTION_PICTURES]) {
    const char *block = strstr(log, "hud: step ");
    for (int k = 0; k < SUPPORT_CAPTION_PICTURES; k++) {
        if (!block) {
            fail_msg("F12 %d printed no HUD: %s", k + 1, log);
            return;
        }
        const char *next = strstr(block + 1, "hud: step ");
        int length = next ? (int)(next - block) : (int)strlen(block);
        char expected[128];
        snprintf(expected, sizeof expected, "hud: step %d/", SUPPORT_CAPTION_STEP);
        const char *changed = strstr(block, "hud: changed: ");
        bool said = changed && changed < block + length;
        printf("    F12 %d: %.*s", k + 1, length, block);
        assert_true(strncmp(block, expected, strlen(expected)) == 0);
        if (support_caption_changes[k]) {
            snprintf(expected, sizeof expected, "hud: changed: %s\n", support_caption_changes[k]);
            assert_true(said && strncmp(changed, expected, strlen(expected)) == 0);
        } else {
            assert_false(said);
        }
        int width, height;
        unsigned char *rgba = image_read_png(pictures[k], &width, &height);
        assert_non_null(rgba);
        int brightest = support_caption_brightness(rgba, width, height);
        free(rgba);
        printf("    %s: the caption's brightest grey %d\n", pictures[k], brightest);
        if (support_caption_changes[k])
            assert_true(brightest <= HUD_DIMMED_GREY);
        else
            assert_int_equal(brightest, HUD_WHITE);
        block = next;
    }
}

static FILE *support_capture_file;
static int support_saved_stderr = -1;

void support_capture_stderr(void) {
    fflush(stderr);
    support_capture_file = tmpfile();
    if (!support_capture_file)
        return; /* then nothing is captured and the caller's checks fail */
    support_saved_stderr = dup(STDERR_FILENO);
    dup2(fileno(support_capture_file), STDERR_FILENO);
}

const char *support_release_stderr(void) {
    static char captured[8192];
    captured[0] = '\0';
    if (!support_capture_file)
        return captured;
    fflush(stderr);
    dup2(support_saved_stderr, STDERR_FILENO);
    close(support_saved_stderr);
    rewind(support_capture_file);
    size_t length = fread(captured, 1, sizeof captured - 1, support_capture_file);
    captured[length] = '\0';
    fclose(support_capture_file);
    support_capture_file = NULL;
    return captured;
}

/* A run traces each reference once: the references, by what decides them
 * (the scene file's text, which a test may rewrite under one path, the
 * size and the build), FNV-1a hashed. */
#define SUPPORT_MAX_REFERENCES 256
#define SUPPORT_FNV_OFFSET 14695981039346656037ull
#define SUPPORT_FNV_PRIME 1099511628211ull

static uint64_t support_hash(uint64_t hash, const char *bytes, size_t length) {
    for (size_t i = 0; i < length; i++)
        hash = (hash ^ (unsigned char)bytes[i]) * SUPPORT_FNV_PRIME;
    return hash;
}

/* The folder of references: $TEST_REFERENCES, shared by a run's
 * processes, or this process's out/test/reference. */
static const char *support_references(void) {
    const char *shared = getenv("TEST_REFERENCES");
    return shared && *shared ? shared : "out/test/reference";
}

/* DIR/HASH: the reference of `scene` at `size`, traced unless this process
 * or another of the run traced it before. Under an exclusive lock on
 * DIR/HASH.lock the first process traces it, the others wait, and each
 * finds DIR/HASH/done after it. */
static void support_reference(const char *scene, const char *size, char *dir, size_t capacity) {
    static uint64_t traced[SUPPORT_MAX_REFERENCES];
    static int traced_count;
    size_t length;
    char *text = path_read_text(scene, SUPPORT_MAX_SCENE_BYTES, &length);
    assert_non_null(text);
    const char *build = getenv("BUILD") ? getenv("BUILD") : "build";
    uint64_t key = support_hash(support_hash(SUPPORT_FNV_OFFSET, text, length), size, strlen(size) + 1);
    key = support_hash(key, build, strlen(build) + 1);
    free(text);
    const char *folder = support_references();
    snprintf(dir, capacity, "%s/%016llx", folder, (unsigned long long)key);
    for (int i = 0; i < traced_count; i++)
        if (traced[i] == key)
            return;
    char lock_path[PATH_MAX], done_path[PATH_MAX];
    snprintf(lock_path, sizeof lock_path, "%s.lock", dir);
    snprintf(done_path, sizeof done_path, "%s/done", dir);
    assert_true(path_make_directories(folder));
    int lock = open(lock_path, O_CREAT | O_RDWR, 0644);
    assert_true(lock >= 0);
    assert_int_equal(flock(lock, LOCK_EX), 0);
    if (access(done_path, F_OK) != 0) {
        assert_int_equal(support_dump("raytrace", scene, size, dir), 0);
        FILE *done = fopen(done_path, "w");
        assert_non_null(done);
        assert_int_equal(fclose(done), 0);
    }
    close(lock);
    if (traced_count < SUPPORT_MAX_REFERENCES)
        traced[traced_count++] = key;
}

shadowdiff_result support_measure_dumps(const char *program, const char *scene, const char *size, const char *flags,
                                        const char *name, dump_frame *reference, dump_frame *test,
                                        unsigned char **heatmap) {
    char reference_dir[256], test_dir[256], test_flags[1024];
    support_reference(scene, size, reference_dir, sizeof reference_dir);
    snprintf(test_dir, sizeof test_dir, "out/test/%s/%s", program, name);
    snprintf(test_flags, sizeof test_flags, "%s %s", size, flags);
    assert_int_equal(support_dump(program, scene, test_flags, test_dir), 0);
    assert_true(dump_read(reference, reference_dir));
    assert_true(dump_read(test, test_dir));
    *heatmap = malloc((size_t)reference->width * reference->height * 4);
    assert_non_null(*heatmap);
    shadowdiff_result r;
    assert_true(shadowdiff_compare(reference, test, NULL, &r, *heatmap));
    fprintf(stderr,
            "    %-26s %s: %ld compared, false-shadow %.4f %% (%ld), false-lit %.4f %% (%ld), "
            "misclassified %.4f %%\n",
            name, flags, r.compared, r.false_shadow_percent, r.false_shadow, r.false_lit_percent, r.false_lit,
            r.misclassified_percent);
    return r;
}

shadowdiff_result support_measure_receiver(const char *program, const char *group, const char *name,
                                           const char *scene, const char *reference_flags, const char *flags,
                                           const char *receiver, long *receiver_pixels) {
    char reference_dir[256], test_dir[256], heatmap_path[300];
    snprintf(reference_dir, sizeof reference_dir, "out/test/%s/%s_reference", group, name);
    snprintf(test_dir, sizeof test_dir, "out/test/%s/%s", group, name);
    assert_int_equal(support_dump("raytrace", scene, reference_flags, reference_dir), 0);
    assert_int_equal(support_dump(program, scene, flags, test_dir), 0);
    dump_frame reference, test;
    assert_true(dump_read(&reference, reference_dir));
    assert_true(dump_read(&test, test_dir));
    unsigned char *heatmap = malloc((size_t)reference.width * reference.height * 4);
    assert_non_null(heatmap);
    const shadowdiff_settings settings = {.receiver = receiver};
    shadowdiff_result r;
    assert_true(shadowdiff_compare(&reference, &test, &settings, &r, heatmap));
    snprintf(heatmap_path, sizeof heatmap_path, "%s_heatmap.png", test_dir);
    assert_true(image_write_png(heatmap_path, reference.width, reference.height, heatmap));
    int id = -1;
    for (int i = 0; receiver && i < reference.object_count; i++)
        if (strcmp(reference.object_names[i], receiver) == 0)
            id = i;
    *receiver_pixels = 0;
    for (long i = 0; i < (long)reference.width * reference.height; i++)
        *receiver_pixels += receiver ? reference.ids[i] == id : reference.ids[i] >= 0;
    fprintf(stderr,
            "    %-24s %-12s on %s: %ld compared of %ld; false-shadow %.4f %% (%ld), false-lit %.4f %% (%ld), "
            "misclassified %.4f %%\n",
            name, flags, receiver ? receiver : "every object", r.compared, *receiver_pixels, r.false_shadow_percent,
            r.false_shadow, r.false_lit_percent, r.false_lit, r.misclassified_percent);
    free(heatmap);
    dump_frame_free(&reference);
    dump_frame_free(&test);
    return r;
}

cJSON *support_read_json(const char *path) {
    char *text = path_read_text(path, SUPPORT_MAX_SCENE_BYTES, NULL);
    assert_non_null(text);
    cJSON *root = cJSON_Parse(text);
    free(text);
    assert_non_null(root);
    return root;
}

void support_write_json(const cJSON *root, const char *dir, const char *name, char *path, size_t size) {
    char *text = cJSON_Print(root);
    assert_non_null(text);
    assert_true(path_make_directories(dir));
    snprintf(path, size, "%s/%s.json", dir, name);
    FILE *file = fopen(path, "w");
    assert_non_null(file);
    assert_true(fputs(text, file) >= 0);
    assert_int_equal(fclose(file), 0);
    free(text);
}

shadowdiff_result support_measure(const char *program, const char *scene, const char *size, const char *flags,
                                  const char *name) {
    dump_frame reference, test;
    unsigned char *heatmap;
    shadowdiff_result r = support_measure_dumps(program, scene, size, flags, name, &reference, &test, &heatmap);
    free(heatmap);
    dump_frame_free(&reference);
    dump_frame_free(&test);
    return r;
}

void support_standard_scenes_within(const char *program, double max_percent) {
    static const char *const scenes[] = {"simple", "bunny", "teapot"};
    for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++) {
        char path[256];
        snprintf(path, sizeof path, "assets/scenes/%s.json", scenes[i]);
        shadowdiff_result r = support_measure(program, path, "", "", scenes[i]);
        assert_true(r.compared > SUPPORT_STANDARD_MIN_COMPARED);
        assert_true(r.misclassified_percent <= max_percent);
    }
}
