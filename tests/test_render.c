/* Screenshot tests, driven by one table of golden cases: a technique, a
 * scene, the technique's flags and the golden's name. Each case is
 * rendered headless at 640x360 on EGL and (but for the lecture pictures)
 * OSMesa; each picture must match tests/golden/NAME.png and the other
 * backend's within the tolerance in support.h (at most a thousandth of
 * the pixels differ by more than 8/255). On a failure the actual image
 * and a diff image are left in out/test/, with the commands that
 * reproduce the case and re-record its golden.
 *
 * The same table re-records, on purpose only (look at the pictures, say
 * why in the commit): `test_render --record [NAME...]` renders every case,
 * or the named ones, on EGL with exactly the flags the check uses, into
 * tests/golden/NAME.png. `make update-golden [ONLY=NAME]` runs it. A
 * technique's name names each of its cases; `test_render --check NAME...`
 * checks the named cases alone (`make test-technique`).
 *
 * The comparison is shown to bite: a scene whose light moved slightly, and
 * each planar fix turned off, must fail it. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hud.h"
#include "image.h"
#include "legend.h"
#include "path.h"
#include "registry.h"
#include "shadowdiff.h"
#include "support.h"
#include "tour.h"
#include "volume_overlay.h"

#define SIZE "640x360"
#define GALLERY_HEIGHT 360 /* SIZE's */
#define GOLDEN_DIR "tests/golden"
#define GOLDEN_MAX_CASES 64
#define GOLDEN_NAME_SIZE 64
/* The gallery names a technique's second picture, made with its
 * gallery_config, NAME-lecture_SCENE.png; its goldens are named alike. */
#define GOLDEN_LECTURE "-lecture_"

typedef struct golden_case {
    const char *technique;       /* its program, $BUILD/TECHNIQUE */
    const char *scene;           /* assets/scenes/SCENE.json */
    const char *flags;           /* the technique's own flags; "" for its defaults */
    char name[GOLDEN_NAME_SIZE]; /* tests/golden/NAME.png */
    /* Checked on EGL alone: the lecture pictures, whose overlays add
     * nothing about the backends to what the standard cases show. */
    bool egl_only;
    const char *size; /* NULL: SIZE */
} golden_case;

/* A picture at a projector's size is of one of the app's switches:
 * TECHNIQUE-SWITCH-WxH_SCENE (--hud, --compare). */
#define GOLDEN_HUD_FLAGS "--hud"

/* A spot, a point and a directional light: every technique in the registry
 * has a golden on each. */
static const char *const golden_standard_scenes[] = {"simple", "bunny", "teapot"};

/* The rows beyond technique x standard scene: the shadow map's lecture
 * picture for a 2D map (simple's spot) and a cube map (bunny's point
 * light); perspective shadow maps where they matter, long_view, with the
 * light in front of the viewer and behind (the inverted case), and the
 * lecture's post-perspective view; cascades on long_view. */
static const golden_case golden_extra_cases[] = {
    {"shadowmap", "simple", "--overlay all", "shadowmap-lecture_simple", true, NULL},
    {"shadowmap", "bunny", "--overlay all", "shadowmap-lecture_bunny", true, NULL},
    {"psm", "long_view", "", "psm_long_view", false, NULL},
    {"psm", "long_view_behind", "", "psm_long_view_behind", false, NULL},
    {"psm", "long_view", "--overlay post-perspective", "psm-lecture_long_view", true, NULL},
    /* The HUD as a slide shows it: psm's state line is the longest, and
     * wraps at both sizes (tests/test_hud.c checks the layout). */
    {"psm", "long_view", GOLDEN_HUD_FLAGS, "psm-hud-1280x720_long_view", true, "1280x720"},
    {"psm", "long_view", GOLDEN_HUD_FLAGS, "psm-hud-1920x1080_long_view", true, "1920x1080"},
    /* Compare mode as a slide: the technique, the truth (test_compare
     * shows each cell is its program's picture), the heat map and its
     * legend with the figures. */
    {"psm", "long_view", "--compare", "psm-compare-1280x720_long_view", true, "1280x720"},
    /* Cascades where they matter, long_view: the default picture, and the
     * lecture's tint of each cascade with the layers' insets. */
    {"cascades", "long_view", "", "cascades_long_view", false, NULL},
    {"cascades", "long_view", "--overlay cascades", "cascades-lecture_long_view", true, NULL},
    /* Projective textures' limits: a receiver between the light and the
     * ball, a table that casts and receives over the floor. */
    {"projective", "projective_limits", "", "projective_projective_limits", false, NULL},
    /* The hybrid where a map alone misclassifies most, long_view, and its
     * lecture picture: the pixels where the map is unsure, which rays
     * decide. */
    {"hybrid", "long_view", "", "hybrid_long_view", false, NULL},
    {"hybrid", "bunny", "--overlay unsure", "hybrid-lecture_bunny", true, NULL},
};

/* Every tour in assets/tours/ is a golden per step, tour-NAME-K.png (K
 * from 1, as --tour --screenshot names them), at a thumbnail's size: the
 * steps' pictures are the technique cases', here to show that each step
 * renders what its file says. EGL only. */
#define TOUR_DIR "assets/tours"
#define TOUR_GOLDEN_PREFIX "tour-"
#define TOUR_SIZE "320x180"
#define TOUR_MAX_TOURS 16

static struct {
    char name[GOLDEN_NAME_SIZE]; /* assets/tours/NAME.json */
    int step_count;
} golden_tours[TOUR_MAX_TOURS];
static int golden_tour_count;

static const char *const golden_backends[] = {"egl", "osmesa"};
#define GOLDEN_BACKEND_COUNT (sizeof golden_backends / sizeof *golden_backends)

static golden_case golden_cases[GOLDEN_MAX_CASES];
static int golden_case_count;
static char err[16384];

static bool golden_make_cases(void) {
    int standard = (int)(sizeof golden_standard_scenes / sizeof *golden_standard_scenes);
    int extra = (int)(sizeof golden_extra_cases / sizeof *golden_extra_cases);
    if (registry_technique_count * standard + extra > GOLDEN_MAX_CASES) {
        fprintf(stderr, "test_render: more golden cases than GOLDEN_MAX_CASES (%d)\n", GOLDEN_MAX_CASES);
        return false;
    }
    for (int t = 0; t < registry_technique_count; t++) {
        for (int s = 0; s < standard; s++) {
            golden_case *c = &golden_cases[golden_case_count++];
            *c = (golden_case){
                .technique = registry_techniques[t]->name, .scene = golden_standard_scenes[s], .flags = ""};
            snprintf(c->name, sizeof c->name, "%s_%s", c->technique, c->scene);
        }
    }
    for (int i = 0; i < extra; i++)
        golden_cases[golden_case_count++] = golden_extra_cases[i];
    return true;
}

static int golden_compare_names(const void *a, const void *b) { return strcmp(a, b); }

/* The tours of assets/tours/, by name, with their step counts. */
static bool golden_make_tours(void) {
    DIR *dir = opendir(TOUR_DIR);
    if (!dir) {
        fprintf(stderr, "test_render: cannot open " TOUR_DIR "\n");
        return false;
    }
    bool ok = true;
    for (struct dirent *e; ok && (e = readdir(dir));) {
        size_t n = strlen(e->d_name);
        if (n <= 5 || strcmp(e->d_name + n - 5, ".json") != 0)
            continue;
        ok = golden_tour_count < TOUR_MAX_TOURS;
        if (ok)
            snprintf(golden_tours[golden_tour_count++].name, GOLDEN_NAME_SIZE, "%.*s", (int)(n - 5), e->d_name);
    }
    closedir(dir);
    qsort(golden_tours, (size_t)golden_tour_count, sizeof *golden_tours, golden_compare_names);
    for (int i = 0; ok && i < golden_tour_count; i++) {
        static tour t;
        char path[256];
        ok = snprintf(path, sizeof path, TOUR_DIR "/%s.json", golden_tours[i].name) < (int)sizeof path &&
             tour_load(&t, path);
        golden_tours[i].step_count = t.step_count;
    }
    if (!ok)
        fprintf(stderr, "test_render: the tours in " TOUR_DIR " could not be listed (at most %d)\n", TOUR_MAX_TOURS);
    return ok;
}

/* DIR/tour-NAME-K.png of tour i's step k (from 1); false if too long. */
static bool golden_tour_step_path(char *out, size_t size, const char *dir, int i, int k) {
    return snprintf(out, size, "%s/" TOUR_GOLDEN_PREFIX "%s-%d.png", dir, golden_tours[i].name, k) < (int)size;
}

/* Whether NAME is a tour step's golden, tour-TOUR-K. */
static bool golden_is_tour_step(const char *name) {
    for (int i = 0; i < golden_tour_count; i++)
        for (int k = 1; k <= golden_tours[i].step_count; k++) {
            char step[2 * GOLDEN_NAME_SIZE];
            if (snprintf(step, sizeof step, TOUR_GOLDEN_PREFIX "%s-%d", golden_tours[i].name, k) < (int)sizeof step &&
                strcmp(step, name) == 0)
                return true;
        }
    return false;
}

/* Every step of tour i, headless on EGL, to DIR/tour-NAME-K.png. */
static bool golden_render_tour(int i, const char *dir) {
    char command[4096];
    return snprintf(command, sizeof command,
                    "%s --backend egl --size " TOUR_SIZE " --tour " TOUR_DIR
                    "/%s.json --screenshot %s/" TOUR_GOLDEN_PREFIX "%s.png",
                    support_program("shadows"), golden_tours[i].name, dir,
                    golden_tours[i].name) < (int)sizeof command &&
           support_run(command, err, sizeof err) == 0;
}

static const golden_case *golden_find(const char *name) {
    for (int i = 0; i < golden_case_count; i++)
        if (strcmp(golden_cases[i].name, name) == 0)
            return &golden_cases[i];
    return NULL;
}

/* Whether a case is among NAMES (its own name or its technique's), or
 * NAMES is empty. */
static bool golden_named(const golden_case *c, int name_count, char **names) {
    bool named = name_count == 0;
    for (int n = 0; n < name_count && !named; n++)
        named = strcmp(names[n], c->name) == 0 || strcmp(names[n], c->technique) == 0;
    return named;
}

/* Whether NAME names some case (its own or its technique's name). */
static bool golden_names_a_case(const char *name) {
    char *names[] = {(char *)name};
    for (int i = 0; i < golden_case_count; i++)
        if (golden_named(&golden_cases[i], 1, names))
            return true;
    return false;
}

/* The case of the same technique and scene with the technique's defaults. */
static const golden_case *golden_plain_of(const golden_case *c) {
    for (int i = 0; i < golden_case_count; i++) {
        const golden_case *p = &golden_cases[i];
        if (!p->flags[0] && strcmp(p->technique, c->technique) == 0 && strcmp(p->scene, c->scene) == 0 && !p->size &&
            !c->size)
            return p;
    }
    return NULL;
}

static const technique *golden_technique(const char *name) {
    for (int t = 0; t < registry_technique_count; t++)
        if (strcmp(registry_techniques[t]->name, name) == 0)
            return registry_techniques[t];
    return NULL;
}

/* The command line that renders `scene_file` with $BUILD/TECHNIQUE and its
 * flags into `screenshot`: what the check runs, prints and re-records. */
static void golden_command(char *out, size_t size, const char *technique, const char *backend,
                           const char *picture_size, const char *scene_file, const char *flags,
                           const char *screenshot) {
    snprintf(out, size, "%s --backend %s --size %s --scene %s%s%s --screenshot %s", support_program(technique),
             backend, picture_size ? picture_size : SIZE, scene_file, flags[0] ? " " : "", flags, screenshot);
}

static void golden_case_command(char *out, size_t size, const golden_case *c, const char *backend,
                                const char *screenshot) {
    char scene_file[256];
    snprintf(scene_file, sizeof scene_file, "assets/scenes/%s.json", c->scene);
    golden_command(out, size, c->technique, backend, c->size, scene_file, c->flags, screenshot);
}

/* Renders `scene_file` with TECHNIQUE and extra flags to out/test/NAME.png. */
static void render_with(const char *technique, const char *backend, const char *scene_file, const char *flags,
                        const char *name) {
    char command[2048], screenshot[256];
    snprintf(screenshot, sizeof screenshot, "out/test/%s.png", name);
    golden_command(command, sizeof command, technique, backend, NULL, scene_file, flags, screenshot);
    assert_int_equal(support_run(command, err, sizeof err), 0);
}

static void render(const char *backend, const char *scene_file, const char *flags, const char *name) {
    render_with("planar", backend, scene_file, flags, name);
}

/* support_compare_images of the golden of case GOLDEN (which must be in
 * the table) and out/test/NAME.png. */
static double compare_with_golden(const char *golden, const char *name) {
    if (!golden_find(golden))
        fail_msg("%s is not a golden case", golden);
    char golden_path[256], actual[256];
    snprintf(golden_path, sizeof golden_path, GOLDEN_DIR "/%s.png", golden);
    snprintf(actual, sizeof actual, "out/test/%s.png", name);
    return support_compare_images(golden_path, actual);
}

static bool osmesa_installed(void) { return system("ldconfig -p | grep -q libOSMesa.so") == 0; }

static bool within_tolerance(double fraction) { return fraction >= 0 && fraction <= SUPPORT_MAX_DIFFERING; }

/* Fails the case, naming the commands that reproduce its picture on each
 * backend involved and, where a new golden could be the answer, the one
 * that re-records it. */
static void golden_fail(const golden_case *c, const char *what, const char *const *backends, int backend_count,
                        bool offer_record) {
    for (int b = 0; b < backend_count; b++) {
        char command[2048], screenshot[256];
        snprintf(screenshot, sizeof screenshot, "out/test/%s_%s.png", c->name, backends[b]);
        golden_case_command(command, sizeof command, c, backends[b], screenshot);
        fprintf(stderr, "    reproduce: %s\n", command);
    }
    if (offer_record)
        fprintf(stderr, "    re-record (on purpose only): make update-golden ONLY=%s\n", c->name);
    fail_msg("%s: %s", c->name, what);
}

/* One case: rendered on each of its backends, each picture compared with
 * the golden, the backends with each other, and a picture with flags
 * (a lecture overlay) with the technique's plain golden, which it must not
 * match: the overlay draws. Under the sanitizers every case is drawn on
 * EGL and every support_sweep_stride()th on OSMesa too. */
static void test_golden_case(void **state) {
    const golden_case *c = *state;
    bool osmesa_sampled = (c - golden_cases) % support_sweep_stride() == 0;
    int backend_count = c->egl_only || !osmesa_sampled || !osmesa_installed() ? 1 : (int)GOLDEN_BACKEND_COUNT;
    if (!c->egl_only && osmesa_sampled && backend_count == 1)
        fprintf(stderr, "    libOSMesa is not installed here: EGL only\n");
    char actual[GOLDEN_BACKEND_COUNT][GOLDEN_NAME_SIZE + sizeof "_osmesa"];
    for (int b = 0; b < backend_count; b++) {
        char command[2048], screenshot[256];
        snprintf(actual[b], sizeof actual[b], "%s_%s", c->name, golden_backends[b]);
        snprintf(screenshot, sizeof screenshot, "out/test/%s.png", actual[b]);
        golden_case_command(command, sizeof command, c, golden_backends[b], screenshot);
        if (support_run(command, err, sizeof err) != 0)
            golden_fail(c, "the program failed", &golden_backends[b], 1, false);
        if (!within_tolerance(compare_with_golden(c->name, actual[b])))
            golden_fail(c, "does not match its golden", &golden_backends[b], 1, true);
    }
    if (backend_count == (int)GOLDEN_BACKEND_COUNT) {
        char egl[256], osmesa[256];
        snprintf(egl, sizeof egl, "out/test/%s.png", actual[0]);
        snprintf(osmesa, sizeof osmesa, "out/test/%s.png", actual[1]);
        if (!within_tolerance(support_compare_images(egl, osmesa)))
            golden_fail(c, "EGL and OSMesa disagree", golden_backends, backend_count, false);
    }
    const golden_case *plain = golden_plain_of(c);
    if (c->flags[0] && plain && compare_with_golden(plain->name, actual[0]) <= SUPPORT_MAX_DIFFERING)
        golden_fail(c, "its flags change nothing: it matches its technique's plain golden", golden_backends, 1,
                    false);
}

/* The table names every case as the gallery names its picture (TECHNIQUE_
 * SCENE, or TECHNIQUE-lecture_SCENE with the technique's gallery_config,
 * where it has one), of a technique in the registry; and every file in
 * tests/golden/ is a case's. */
static void test_golden_table_is_consistent(void **state) {
    (void)state;
    for (int i = 0; i < golden_case_count; i++) {
        const golden_case *c = &golden_cases[i];
        const technique *t = golden_technique(c->technique);
        if (!t)
            fail_msg("%s: %s is not in the registry", c->name, c->technique);
        bool lecture = strstr(c->name, GOLDEN_LECTURE) != NULL;
        char expected[GOLDEN_NAME_SIZE];
        if (c->size) {
            /* One of the app's switches at a projector's size:
             * TECHNIQUE-SWITCH-WxH_SCENE. */
            bool one_switch = strncmp(c->flags, "--", 2) == 0 && !strchr(c->flags, ' ');
            snprintf(expected, sizeof expected, "%s-%s-%s_%s", c->technique, c->flags + 2, c->size, c->scene);
            if (!one_switch || strcmp(c->name, expected) != 0)
                fail_msg("%s: a picture at a projector's size is %s, with one switch", c->name, expected);
            continue;
        }
        snprintf(expected, sizeof expected, "%s%s%s", c->technique, lecture ? GOLDEN_LECTURE : "_", c->scene);
        if (strcmp(c->name, expected) != 0)
            fail_msg("%s: the gallery would call this picture %s", c->name, expected);
        if (lecture != (c->flags[0] != '\0'))
            fail_msg("%s: only a lecture picture has flags", c->name);
        if (lecture && t->gallery_config && strcmp(c->flags, t->gallery_config) != 0)
            fail_msg("%s: flags \"%s\", but the gallery uses \"%s\"", c->name, c->flags, t->gallery_config);
    }
    DIR *dir = opendir(GOLDEN_DIR);
    assert_non_null(dir);
    for (struct dirent *e; (e = readdir(dir));) {
        size_t n = strlen(e->d_name);
        if (e->d_name[0] == '.')
            continue;
        char name[256];
        snprintf(name, sizeof name, "%.*s", n > 4 ? (int)(n - 4) : (int)n, e->d_name);
        if (n <= 4 || strcmp(e->d_name + n - 4, ".png") != 0 || (!golden_find(name) && !golden_is_tour_step(name))) {
            closedir(dir);
            fail_msg(GOLDEN_DIR "/%s is no golden case's", e->d_name);
        }
    }
    closedir(dir);
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
    assert_true(compare_with_golden("planar_simple", "light_moved") > SUPPORT_MAX_DIFFERING);
}

static void test_each_fix_shows_when_off(void **state) {
    (void)state;
    render("egl", "assets/scenes/simple.json", "--no-stencil", "no_stencil");
    assert_true(compare_with_golden("planar_simple", "no_stencil") > SUPPORT_MAX_DIFFERING);
    render("egl", "assets/scenes/simple.json", "--no-offset", "no_offset");
    assert_true(compare_with_golden("planar_simple", "no_offset") > SUPPORT_MAX_DIFFERING);
    /* A sphere sunk half into the ground: without rejection its buried
     * half throws an anti-shadow onto the ground on the light's side. */
    render("egl", "tests/data/anti_shadow.json", "", "reject_on");
    render("egl", "tests/data/anti_shadow.json", "--no-reject", "reject_off");
    assert_true(support_compare_images("out/test/reject_on.png", "out/test/reject_off.png") > SUPPORT_MAX_DIFFERING);
}

/* The texel overlay at a 2048 map, a third of a pixel a texel on simple:
 * a line at every texel would darken nearly every lit pixel (moire); the
 * lines every 2^k texels, at least MAP_TEXEL_LINE_MIN_PIXELS (4)
 * apart, darken a share of them, between these fractions of the
 * picture's pixels (the test prints the share); a line at every texel
 * would darken more than the upper one, every lit pixel. */
#define TEXEL_GRID_MAX_DARKENED 0.35
#define TEXEL_GRID_MIN_DARKENED 0.05
static void test_texel_grid_is_not_moire(void **state) {
    (void)state;
    render_with("shadowmap", "egl", "assets/scenes/simple.json", "--map-size 2048", "texel_grid_off");
    render_with("shadowmap", "egl", "assets/scenes/simple.json", "--map-size 2048 --overlay texels", "texel_grid_on");
    double darkened = support_compare_images("out/test/texel_grid_off.png", "out/test/texel_grid_on.png");
    fprintf(stderr, "    texel grid at 2048: %.4f of the pixels darkened\n", darkened);
    assert_true(darkened > TEXEL_GRID_MIN_DARKENED && darkened < TEXEL_GRID_MAX_DARKENED);
}

/* Without any bias the shadow map shadows the lit ground with acne. Plain
 * to see only without the kernel: the Poisson disc averages the stripes
 * into a faint darkening, `--filter none` shows each stripe dark, and so
 * the default filter, auto, is none while a bias is off (the same
 * picture). Plain: a pixel darker by more than ACNE_PLAIN_DROP of 255 in
 * its brightest channel; unfiltered, more pixels are plainly darker than
 * with the disc (more than ACNE_UNFILTERED_OVER_FILTERED times as many),
 * while the disc's acne differs from the biased picture on many more
 * pixels, mostly by less. */
#define ACNE_PLAIN_DROP 64
#define ACNE_UNFILTERED_OVER_FILTERED 1.2
#define ACNE_CHANNELS 4 /* image_read_png: RGBA */
#define ACNE_COLOR_CHANNELS 3
static double plainly_darker(const char *reference, const char *actual) {
    int rw, rh, aw, ah;
    unsigned char *r = image_read_png(reference, &rw, &rh), *a = image_read_png(actual, &aw, &ah);
    assert_true(r && a && rw == aw && rh == ah);
    long darker = 0;
    for (long p = 0; p < (long)aw * ah; p++) {
        bool plain = false;
        for (int k = 0; k < ACNE_COLOR_CHANNELS; k++)
            plain = plain || r[p * ACNE_CHANNELS + k] - a[p * ACNE_CHANNELS + k] > ACNE_PLAIN_DROP;
        darker += plain;
    }
    free(r);
    free(a);
    return (double)darker / ((double)aw * ah);
}

static void test_shadowmap_without_bias_shows_acne(void **state) {
    (void)state;
    render_with("shadowmap", "egl", "assets/scenes/simple.json",
                "--filter poisson --no-constant-bias --no-slope-bias", "shadowmap_disc_no_bias");
    assert_true(compare_with_golden("shadowmap_simple", "shadowmap_disc_no_bias") > SUPPORT_MAX_DIFFERING);
    render_with("shadowmap", "egl", "assets/scenes/simple.json", "--filter none", "shadowmap_unfiltered");
    render_with("shadowmap", "egl", "assets/scenes/simple.json", "--filter none --no-constant-bias --no-slope-bias",
                "shadowmap_unfiltered_no_bias");
    render_with("shadowmap", "egl", "assets/scenes/simple.json", "--no-constant-bias --no-slope-bias",
                "shadowmap_no_bias");
    assert_true(
        support_compare_images("out/test/shadowmap_unfiltered_no_bias.png", "out/test/shadowmap_no_bias.png") == 0);
    double filtered = plainly_darker(GOLDEN_DIR "/shadowmap_simple.png", "out/test/shadowmap_disc_no_bias.png");
    double unfiltered =
        plainly_darker("out/test/shadowmap_unfiltered.png", "out/test/shadowmap_unfiltered_no_bias.png");
    fprintf(stderr, "    acne plainly darker: %.4f of the pixels (poisson), %.4f (--filter none)\n", filtered,
            unfiltered);
    assert_true(unfiltered > ACNE_UNFILTERED_OVER_FILTERED * filtered);
}

/* The texel-size heat map draws into psm's picture. */
static void test_psm_texel_size_shows(void **state) {
    (void)state;
    render_with("psm", "egl", "assets/scenes/long_view.json", "--overlay texel-size", "psm_texel_size_long_view");
    assert_true(compare_with_golden("psm_long_view", "psm_texel_size_long_view") > SUPPORT_MAX_DIFFERING);
}

/* The texel-size heat map has its legend: at 640x360 (font unit 1) its
 * bar runs from x 468 to 628 on rows 325 to 333 (map_overlay.c's
 * sizes), blue at a quarter pixel, red at 32, on a dark panel. */
enum { LEGEND_ROW = 329, LEGEND_BLUE_X = 470, LEGEND_RED_X = 625, LEGEND_PANEL_X = 550, LEGEND_PANEL_ROW = 323 };
#define LEGEND_DARK 40            /* the panel's channels at most */
#define LEGEND_SWATCH_TOLERANCE 3 /* summed over the channels: rounding to bytes */
static const unsigned char *legend_pixel(const unsigned char *image, int width, int x, int y) {
    return image + ((size_t)y * (size_t)width + (size_t)x) * ACNE_CHANNELS;
}

static void test_texel_size_has_legend(void **state) {
    (void)state;
    render_with("shadowmap", "egl", "assets/scenes/simple.json", "--overlay texel-size", "texel_size_legend");
    int w, h;
    unsigned char *image = image_read_png("out/test/texel_size_legend.png", &w, &h);
    assert_non_null(image);
    const unsigned char *blue = legend_pixel(image, w, LEGEND_BLUE_X, LEGEND_ROW);
    const unsigned char *red = legend_pixel(image, w, LEGEND_RED_X, LEGEND_ROW);
    const unsigned char *panel = legend_pixel(image, w, LEGEND_PANEL_X, LEGEND_PANEL_ROW);
    assert_true(blue[2] > blue[0] && blue[2] > blue[1]);
    assert_true(red[0] > red[1] && red[0] > red[2]);
    assert_true(panel[0] <= LEGEND_DARK && panel[1] <= LEGEND_DARK && panel[2] <= LEGEND_DARK);
    free(image);
}

/* The post-perspective view draws for the uniform map too (its own clip
 * space), not only for the warps. */
static void test_post_perspective_shows_for_uniform(void **state) {
    (void)state;
    render_with("psm", "egl", "assets/scenes/long_view.json", "--warp uniform", "psm_uniform_long_view");
    render_with("psm", "egl", "assets/scenes/long_view.json", "--warp uniform --overlay post-perspective",
                "psm_uniform_post_perspective_long_view");
    assert_true(support_compare_images("out/test/psm_uniform_long_view.png",
                                       "out/test/psm_uniform_post_perspective_long_view.png") >
                SUPPORT_MAX_DIFFERING);
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
        assert_true(compare_with_golden("volumes_teapot", name) > SUPPORT_MAX_DIFFERING);
    }
}

/* The counts overlay has its legend in the bottom-right corner: under a
 * title line, a line per step of the ramp with its swatch, opaque (the
 * overlay itself is translucent, so nowhere else in the picture shows the
 * ramp's own colour). At 640x360 the font unit is 1 pixel: line k's
 * swatch spans rows HEIGHT - margin - legend height + margin + 12 k, 8
 * tall (legend.h, hud.h). */
static void test_volumes_counts_have_legend(void **state) {
    (void)state;
    render_with("volumes", "egl", "assets/scenes/teapot.json", "--overlay counts", "volumes_counts_legend");
    int w, h;
    unsigned char *image = image_read_png("out/test/volumes_counts_legend.png", &w, &h);
    assert_non_null(image);
    int top = h - HUD_MARGIN - legend_height_units(1 + VOLUME_OVERLAY_COUNT_STEPS);
    for (int k = 0; k < VOLUME_OVERLAY_COUNT_STEPS; k++) {
        int y = top + HUD_MARGIN + (1 + k) * HUD_LINE_UNITS + HUD_LETTER_UNITS / 2, found = 0;
        for (int x = w / 2; x < w; x++) {
            const unsigned char *p = legend_pixel(image, w, x, y);
            int off = 0;
            for (int c = 0; c < 3; c++)
                off += abs(p[c] - (int)(volume_overlay_count_ramp[k][c] * 255 + 0.5f));
            found += off <= LEGEND_SWATCH_TOLERANCE;
        }
        assert_int_equal(found, HUD_LETTER_UNITS); /* the swatch's width, on its row alone */
    }
    free(image);
}

/* The GLFW window, under a virtual X server, shows the same picture. */
static void test_window_matches_golden(void **state) {
    (void)state;
    const char *xvfb = support_xvfb_run();
    char command[1024];
    snprintf(command, sizeof command,
             "%s %s --backend glfw --size " SIZE " --frames 2 --screenshot out/test/planar_simple_glfw.png", xvfb,
             support_program("planar"));
    assert_int_equal(support_run(command, err, sizeof err), 0);
    assert_true(within_tolerance(compare_with_golden("planar_simple", "planar_simple_glfw")));
}

/* The gallery writes every technique's picture of each scene, under the
 * name of its golden case where it has one, and that case's golden is
 * what it shows; a technique's lecture picture shows its overlay. */
/* The share of a page's screenshot that is not the page's background
 * (#15171c): its pictures, where they loaded. */
#define GALLERY_PAGE_BACKGROUND 0x15, 0x17, 0x1c
#define GALLERY_PAGE_MIN_PICTURE_SHARE 0.3

/* out/test/gallery/index.html shows every picture of the gallery beside
 * its scene's reference and, measured, its heat map and figures (the
 * penumbra's MAE "none" on these hard scenes); in
 * Chromium (headless) the pictures load and fill the page. */
static void expect_gallery_page(const char *const *scenes, size_t scene_count) {
    char *html = path_read_text("out/test/gallery/index.html", 1 << 20, NULL);
    assert_non_null(html);
    int measured = 0, expected_measured = 0;
    for (const char *c = html; (c = strstr(c, "<td>misclassified ")); c++)
        measured++;
    for (int t = 0; t < registry_technique_count; t++) {
        const technique *tech = registry_techniques[t];
        for (size_t s = 0; s < scene_count; s++) {
            char needle[256];
            const char *const kinds[][2] = {{"_", ".png"}, {"_", "_heatmap.png"}, {GOLDEN_LECTURE, ".png"}};
            for (int k = 0; k < (tech->gallery_config ? 3 : 2); k++) {
                snprintf(needle, sizeof needle, "src=\"%s%s%s%s\"", tech->name, kinds[k][0], scenes[s], kinds[k][1]);
                if (!strstr(html, needle))
                    fail_msg("index.html has no %s", needle);
            }
            snprintf(needle, sizeof needle, "src=\"reference_%s.png\"", scenes[s]);
            assert_non_null(strstr(html, needle));
            /* the summary's cell links to the picture's section */
            snprintf(needle, sizeof needle, "<td><a href=\"#%s_%s\">", tech->name, scenes[s]);
            if (!strstr(html, needle))
                fail_msg("index.html's summary has no %s", needle);
            snprintf(needle, sizeof needle, "<section id=\"%s_%s\">", tech->name, scenes[s]);
            if (!strstr(html, needle))
                fail_msg("index.html has no %s", needle);
            expected_measured++;
        }
    }
    for (int k = 0; k < SHADOWDIFF_PIXEL_KIND_COUNT; k++) { /* the heat map's key: each colour, named */
        char needle[256];
        const unsigned char *rgb = shadowdiff_pixel_colors[k];
        snprintf(needle, sizeof needle, "background:#%02x%02x%02x\"></span>%s", rgb[0], rgb[1], rgb[2],
                 shadowdiff_pixel_names[k]);
        if (!strstr(html, needle))
            fail_msg("index.html's key has no %s", needle);
    }
    char note[64]; /* how wide the heat maps draw an error */
    snprintf(note, sizeof note, "each error drawn %d px wide", 2 * shadowdiff_magnify_radius(GALLERY_HEIGHT) + 1);
    if (!strstr(html, note))
        fail_msg("index.html's key does not say \"%s\"", note);
    /* shadowmap's errors on simple, a few hundredths of a percent, show */
    int width, height;
    unsigned char *heat = image_read_png("out/test/gallery/shadowmap_simple_heatmap.png", &width, &height);
    assert_non_null(heat);
    double share = support_error_share(heat, width, 0, 0, width, height);
    free(heat);
    fprintf(stderr, "    shadowmap_simple_heatmap.png: error discs over %.3f %% of it\n", 100 * share);
    assert_true(share >= SUPPORT_VISIBLE_ERROR_SHARE);
    int hard_penumbrae = 0; /* the standard scenes' lights have no radius */
    for (const char *c = html; (c = strstr(c, "<td>penumbra MAE " SHADOWDIFF_NO_FIGURE " (0 px)</td>")); c++)
        hard_penumbrae++;
    free(html);
    assert_int_equal(measured, expected_measured);
    assert_int_equal(hard_penumbrae, expected_measured);
    if (!support_have_command("chromium")) {
        fprintf(stderr, "    chromium is not installed here: the page is not opened\n");
        return;
    }
    char command[1024];
    snprintf(command, sizeof command,
             "chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=1400,1800 "
             "--screenshot=out/test/gallery_page.png \"file://$PWD/out/test/gallery/index.html\" >/dev/null 2>&1");
    assert_int_equal(system(command), 0);
    unsigned char *rgba = image_read_png("out/test/gallery_page.png", &width, &height);
    assert_non_null(rgba);
    static const unsigned char background[3] = {GALLERY_PAGE_BACKGROUND};
    long other = 0;
    for (long i = 0; i < (long)width * height; i++)
        other += memcmp(rgba + i * 4, background, 3) != 0;
    free(rgba);
    fprintf(stderr, "    the gallery's page in Chromium: %.0f %% of it pictures and text\n",
            100.0 * (double)other / ((double)width * height));
    assert_true((double)other > GALLERY_PAGE_MIN_PICTURE_SHARE * width * height);
}

static void test_gallery_writes_every_technique(void **state) {
    (void)state;
    static const char *const scenes[] = {"simple", "teapot"};
    char command[1024];
    snprintf(command, sizeof command,
             "rm -rf out/test/gallery && %s --size " SIZE
             " --gallery out/test/gallery assets/scenes/simple.json assets/scenes/teapot.json",
             support_program("shadows"));
    assert_int_equal(support_run(command, err, sizeof err), 0);
    for (int t = 0; t < registry_technique_count; t++) {
        const technique *tech = registry_techniques[t];
        for (size_t s = 0; s < sizeof scenes / sizeof *scenes; s++) {
            char name[GOLDEN_NAME_SIZE], lecture[GOLDEN_NAME_SIZE];
            snprintf(name, sizeof name, "%s_%s", tech->name, scenes[s]);
            snprintf(lecture, sizeof lecture, "%s" GOLDEN_LECTURE "%s", tech->name, scenes[s]);
            const char *const pictures[] = {name, lecture};
            for (int p = 0; p < (tech->gallery_config ? 2 : 1); p++) {
                char path[512], gallery_name[256];
                snprintf(gallery_name, sizeof gallery_name, "gallery/%s", pictures[p]);
                snprintf(path, sizeof path, "out/test/%s.png", gallery_name);
                FILE *f = fopen(path, "rb");
                if (!f)
                    fail_msg("the gallery did not write %s", path);
                fclose(f);
                if (golden_find(pictures[p]))
                    assert_true(within_tolerance(compare_with_golden(pictures[p], gallery_name)));
            }
            if (tech->gallery_config) {
                char plain[256], with_overlay[256];
                snprintf(plain, sizeof plain, "out/test/gallery/%s.png", name);
                snprintf(with_overlay, sizeof with_overlay, "out/test/gallery/%s.png", lecture);
                assert_true(support_compare_images(plain, with_overlay) > SUPPORT_MAX_DIFFERING);
            }
        }
    }
    expect_gallery_page(scenes, sizeof scenes / sizeof *scenes);
}

/* A soft scene's gallery row gives each class's MAE and pixels, the
 * penumbra's a figure; the classes' pixels sum to the compared ones, and
 * their MAEs weighed by them to the whole MAE (printed with 5 decimals).
 * The row's figures, not the picture, are checked: a frame of a quarter
 * of SIZE's pixels (the gallery traces the area light's reference itself,
 * every pixel's samples) still holds a wide penumbra. */
#define GALLERY_PAGE_MAE_PRINTED 2e-5
#define GALLERY_SOFT_SIZE "320x180"
static void test_gallery_soft_scene_has_penumbra(void **state) {
    (void)state;
    char command[1024];
    snprintf(command, sizeof command,
             "rm -rf out/test/gallery_soft && %s --size " GALLERY_SOFT_SIZE
             " --gallery out/test/gallery_soft assets/scenes/soft_table.json --technique shadowmap",
             support_program("shadows"));
    assert_int_equal(support_run(command, err, sizeof err), 0);
    char *html = path_read_text("out/test/gallery_soft/index.html", 1 << 20, NULL);
    assert_non_null(html);
    const char *at = strstr(html, "<td>misclassified ");
    assert_non_null(at);
    double misclassified, mae;
    long compared, total = 0;
    int n = 0;
    assert_int_equal(sscanf(at,
                            "<td>misclassified %lf %%</td><td>mean absolute error %lf</td><td>%ld pixels "
                            "compared</td>%n",
                            &misclassified, &mae, &compared, &n),
                     3);
    at += n;
    double weighed = 0;
    for (int k = 0; k < SHADOWDIFF_CLASS_COUNT; k++) {
        char prefix[64];
        snprintf(prefix, sizeof prefix, "<td>%s MAE ", shadowdiff_class_names[k]);
        const char *found = strstr(at, prefix);
        if (!found || found - at > (ptrdiff_t)strlen("</tr><tr>"))
            fail_msg("index.html: no %s where expected: %.80s", prefix, at);
        at = found;
        at += strlen(prefix);
        double class_mae;
        long pixels;
        n = 0;
        if (sscanf(at, "%lf (%ld px)</td>%n", &class_mae, &pixels, &n) != 2 || n == 0)
            fail_msg("index.html: %s has no figure: %.80s", shadowdiff_class_names[k], at);
        at += n;
        total += pixels;
        weighed += class_mae * (double)pixels;
        if (k == SHADOWDIFF_CLASS_PENUMBRA)
            assert_true(pixels > 0 && class_mae > 0);
    }
    free(html);
    assert_int_equal(total, compared);
    assert_float_equal(weighed / (double)compared, mae, GALLERY_PAGE_MAE_PRINTED);
}

/* Every step of every tour matches its golden; the same tour rendered
 * again gives the same files, byte for byte. */
static void test_tours_match_goldens(void **state) {
    (void)state;
    assert_true(path_make_directories("out/test/tours") && path_make_directories("out/test/tours_again"));
    for (int i = 0; i < golden_tour_count; i++) {
        if (!golden_render_tour(i, "out/test/tours"))
            fail_msg("tour %s: the program failed", golden_tours[i].name);
        for (int k = 1; k <= golden_tours[i].step_count; k++) {
            char golden[256], actual[256];
            assert_true(golden_tour_step_path(golden, sizeof golden, GOLDEN_DIR, i, k) &&
                        golden_tour_step_path(actual, sizeof actual, "out/test/tours", i, k));
            if (!within_tolerance(support_compare_images(golden, actual)))
                fail_msg("%s does not match its golden %s (re-record on purpose only: make update-golden "
                         "ONLY=" TOUR_GOLDEN_PREFIX "%s)",
                         actual, golden, golden_tours[i].name);
        }
    }
    assert_true(golden_tour_count > 0);
    assert_true(golden_render_tour(0, "out/test/tours_again"));
    char names[TOUR_MAX_STEPS][GOLDEN_NAME_SIZE * 2];
    const char *list[TOUR_MAX_STEPS];
    for (int k = 0; k < golden_tours[0].step_count; k++) {
        assert_true(snprintf(names[k], sizeof names[k], TOUR_GOLDEN_PREFIX "%s-%d.png", golden_tours[0].name, k + 1) <
                    (int)sizeof names[k]);
        list[k] = names[k];
    }
    const char *different =
        support_first_difference("out/test/tours", "out/test/tours_again", list, (size_t)golden_tours[0].step_count);
    if (different)
        fail_msg("tour %s rendered twice: %s differs", golden_tours[0].name, different);
}

/* "no golden case NAME" on stderr, and the cases whose names contain it
 * (a technique's or a scene's name: its cases), or none. */
static void golden_say_unknown(const char *name) {
    fprintf(stderr, "test_render --record: no golden case %s; the cases containing it:", name);
    int listed = 0;
    for (int i = 0; i < golden_case_count; i++) {
        if (!strstr(golden_cases[i].name, name))
            continue;
        fprintf(stderr, " %s", golden_cases[i].name);
        listed++;
    }
    for (int i = 0; i < golden_tour_count; i++) {
        if (!strstr(golden_tours[i].name, name))
            continue;
        fprintf(stderr, " " TOUR_GOLDEN_PREFIX "%s", golden_tours[i].name);
        listed++;
    }
    fprintf(stderr, "%s\n", listed ? "" : " none (the names are tests/golden/'s, without .png)");
}

/* Whether each of NAMES names a case or a tour's golden; the first that
 * does not is said with the cases containing it. */
static bool golden_names_known(int name_count, char **names) {
    for (int i = 0; i < name_count; i++) {
        if (!golden_names_a_case(names[i]) &&
            strncmp(names[i], TOUR_GOLDEN_PREFIX, strlen(TOUR_GOLDEN_PREFIX)) != 0) {
            golden_say_unknown(names[i]);
            return false;
        }
    }
    return true;
}

/* `make update-golden ONLY=NAME` with a technique's name records each of
 * its cases and no other; another name that is no case's (a scene's)
 * lists the cases containing it, or says there are none. */
static void test_a_technique_names_its_cases(void **state) {
    (void)state;
    char *hybrid[] = {"hybrid"};
    int named = 0;
    for (int i = 0; i < golden_case_count; i++) {
        const golden_case *c = &golden_cases[i];
        assert_int_equal(golden_named(c, 1, hybrid), strcmp(c->technique, "hybrid") == 0);
        named += golden_named(c, 1, hybrid);
    }
    assert_true(named >= (int)(sizeof golden_standard_scenes / sizeof *golden_standard_scenes));
    assert_true(golden_names_known(1, hybrid));
    support_capture_stderr();
    char *scene[] = {"bunny"};
    assert_false(golden_names_known(1, scene));
    const char *said = support_release_stderr();
    assert_non_null(strstr(said, "no golden case bunny; the cases containing it: "));
    assert_non_null(strstr(said, " hybrid_bunny"));
    support_capture_stderr();
    golden_say_unknown("no_such_case");
    said = support_release_stderr();
    assert_non_null(strstr(said, "no golden case no_such_case; the cases containing it: none"));
}

/* --record [NAME...]: each case, or the named ones, on EGL into its golden. */
static int golden_record(int name_count, char **names) {
    int tours_named = 0;
    for (int i = 0; i < golden_tour_count; i++) {
        char name[2 * GOLDEN_NAME_SIZE];
        bool named = name_count == 0;
        if (snprintf(name, sizeof name, TOUR_GOLDEN_PREFIX "%s", golden_tours[i].name) >= (int)sizeof name)
            return 1;
        for (int n = 0; n < name_count; n++)
            named = named || strcmp(names[n], name) == 0;
        tours_named += named && name_count > 0;
        if (named && !golden_render_tour(i, GOLDEN_DIR)) {
            fprintf(stderr, "test_render --record: tour %s failed: %s", golden_tours[i].name, err);
            return 1;
        }
    }
    if (!golden_names_known(name_count, names))
        return 1;
    for (int i = 0; i < golden_case_count; i++) {
        const golden_case *c = &golden_cases[i];
        if (!golden_named(c, name_count, names))
            continue;
        char command[2048], golden[256];
        snprintf(golden, sizeof golden, GOLDEN_DIR "/%s.png", c->name);
        golden_case_command(command, sizeof command, c, "egl", golden);
        if (support_run(command, err, sizeof err) != 0) {
            fprintf(stderr, "test_render --record: failed: %s\n", command);
            return 1;
        }
        printf("%s\n", golden);
    }
    return 0;
}

int main(int argc, char **argv) {
    if (!golden_make_cases() || !golden_make_tours())
        return 1;
    bool record = argc > 1 && strcmp(argv[1], "--record") == 0;
    bool check = argc > 1 && strcmp(argv[1], "--check") == 0;
    if (record)
        return golden_record(argc - 2, argv + 2);
    if ((argc > 1 && !check) || (check && (argc == 2 || !golden_names_known(argc - 2, argv + 2)))) {
        fprintf(stderr, "usage: %s [--record [NAME...] | --check NAME...]\n", argv[0]);
        return 2;
    }
    static const struct CMUnitTest others[] = {
        cmocka_unit_test(test_same_command_same_image),
        cmocka_unit_test(test_moved_light_fails_comparison),
        cmocka_unit_test(test_each_fix_shows_when_off),
        cmocka_unit_test(test_shadowmap_without_bias_shows_acne),
        cmocka_unit_test(test_texel_grid_is_not_moire),
        cmocka_unit_test(test_texel_size_has_legend),
        cmocka_unit_test(test_psm_texel_size_shows),
        cmocka_unit_test(test_post_perspective_shows_for_uniform),
        cmocka_unit_test(test_volumes_overlays_show),
        cmocka_unit_test(test_volumes_counts_have_legend),
        cmocka_unit_test(test_window_matches_golden),
        cmocka_unit_test(test_gallery_writes_every_technique),
        cmocka_unit_test(test_gallery_soft_scene_has_penumbra),
        cmocka_unit_test(test_tours_match_goldens),
        cmocka_unit_test(test_a_technique_names_its_cases),
    };
    enum { OTHER_COUNT = sizeof others / sizeof *others };
    static struct CMUnitTest tests[1 + GOLDEN_MAX_CASES + OTHER_COUNT];
    size_t count = 0;
    tests[count++] = (struct CMUnitTest)cmocka_unit_test(test_golden_table_is_consistent);
    /* --check NAME...: the named cases alone. */
    int name_count = check ? argc - 2 : 0;
    for (int i = 0; i < golden_case_count; i++)
        if (golden_named(&golden_cases[i], name_count, argv + 2))
            tests[count++] = (struct CMUnitTest){
                .name = golden_cases[i].name, .test_func = test_golden_case, .initial_state = &golden_cases[i]};
    for (size_t i = 0; i < OTHER_COUNT && !check; i++)
        tests[count++] = others[i];
    /* What cmocka_run_group_tests_name expands to, with the count known
     * only now (the table grows with the registry). */
    return _cmocka_run_group_tests("screenshots", tests, count, NULL, NULL);
}
