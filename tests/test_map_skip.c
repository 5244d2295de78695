/* The shadow maps' skips (demos/lib/map.h, "Caster culling" and
 * "Caching"): the culling test in process on hand-made layers, then the
 * programs. A caster between the light and the receivers is needed; one
 * beside the map, behind the light or behind the receivers is not; the
 * kernel's reach keeps casters a few texels beside the receivers. Then
 * the programs on the 1000-object city: the skips cull most casters of
 * every map technique, static and with the lights or the camera moving
 * (that they change no decision there is tests/test_skip.c's, for every
 * technique on the same runs), shadowmap's dumps are the same with skips
 * on and with --no-skip under kernels of every reach and depth (a moment
 * filter's too), and a
 * static run reuses every layer from its second frame on. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "map.h"
#include "support.h"

#define OUT "out/test/map_skip"
#define CITY "assets/scenes/city_1000.json"
#define CITY_LIGHTS 7
#define CITY_CASTERS 1000
/* tests/test_skip.c's size for the city's moving runs: what is culled
 * does not depend on the pixels, and a small frame keeps the run short. */
#define CITY_SIZE "320x180"
/* The hand-made spot: at height LIGHT_Y looking straight down, 90 degrees,
 * near 1, far 20, a MAP_SIZE map; the receiver a square ground patch. */
#define LIGHT_Y 10.0f
#define FOV_DEG 90.0f
#define NEAR 1.0f
#define FAR 20.0f
#define MAP_SIZE 256
#define PATCH 1.0f /* the patch's half side: its NDC x spans +-PATCH / LIGHT_Y */

static const char *const dump_files[] = {"visibility.pfm", "depth.pfm", "color.png"};
static const char *const motions[] = {"static", "light", "camera"};
static const char *const programs[] = {"shadowmap", "psm", "cascades"};

/* The spot's layer: world -> its clip space. */
static void spot_layer(mat4 out) {
    mat4 view, projection;
    glm_lookat((vec3){0, LIGHT_Y, 0}, (vec3){0, 0, 0}, (vec3){0, 0, -1}, view);
    glm_perspective(glm_rad(FOV_DEG), 1, NEAR, FAR, projection);
    glm_mat4_mul(projection, view, out);
}

/* Where the patch's receivers read the spot's layer under `settings`. */
static void patch_reads(const mat4 layer, const map_settings *settings, map_reads *reads) {
    const float box[1][2][3] = {{{-PATCH, 0, -PATCH}, {PATCH, 0, PATCH}}};
    float points[8][3];
    frustum_box_corners(box[0][0], box[0][1], (vec3 *)points);
    map_read_setup setup = {.reach = map_read_reach(settings, MAP_2D, false),
                            .size = MAP_SIZE,
                            .any_depth = settings->kernel_depth == MAP_KERNEL_DEPTH_RECEIVER_PLANE};
    map_layer_reads(layer, &setup, (const float(*)[3])points, 8, box, 1, reads);
}

static bool caster_needed(const mat4 layer, const map_reads *reads, vec3 lo, vec3 hi) {
    return map_caster_read(reads, layer, lo, hi);
}

static void test_caster_cases(void **state) {
    (void)state;
    mat4 layer;
    spot_layer(layer);
    /* poisson with centre depths: a read's depth bounds what it compares */
    const map_settings settings = {.kernel_depth = MAP_KERNEL_DEPTH_CENTRE};
    map_reads reads;
    patch_reads(layer, &settings, &reads);
    assert_false(reads.empty);
    static const struct {
        const char *what;
        vec3 lo, hi;
        bool needed;
    } cases[] = {
        {"between the light and the receivers", {-0.5f, 4, -0.5f}, {0.5f, 5, 0.5f}, true},
        {"on the receivers", {-0.2f, 0, -0.2f}, {0.2f, 0.3f, 0.2f}, true},
        {"across the light's plane, over the receivers", {-0.1f, 8, -0.1f}, {0.1f, 11, 0.1f}, true},
        {"beside the map", {30, 4, 0}, {32, 5, 2}, false},
        {"in the map, beside the receivers", {4, 4, -0.5f}, {5, 5, 0.5f}, false},
        {"behind the light", {-1, 12, -1}, {1, 13, 1}, false},
        {"behind the receivers", {-0.5f, -3, -0.5f}, {0.5f, -2, 0.5f}, false},
    };
    /* The same from the boxes alone (a receiver list too long to trust). */
    const float box[1][2][3] = {{{-PATCH, 0, -PATCH}, {PATCH, 0, PATCH}}};
    map_reads by_boxes;
    map_read_setup setup = {.reach = map_read_reach(&settings, MAP_2D, false), .size = MAP_SIZE};
    map_layer_reads(layer, &setup, NULL, 0, box, 1, &by_boxes);
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        if (caster_needed(layer, &reads, (float *)cases[i].lo, (float *)cases[i].hi) != cases[i].needed)
            fail_msg("caster %s: expected %s", cases[i].what, cases[i].needed ? "needed" : "culled");
        if (caster_needed(layer, &by_boxes, (float *)cases[i].lo, (float *)cases[i].hi) != cases[i].needed)
            fail_msg("caster %s, by the boxes: expected %s", cases[i].what, cases[i].needed ? "needed" : "culled");
    }
}

/* A caster just above the ground, 2.5 texels beside the patch seen from the
 * light: inside the Poisson disc's reach, outside one nearest tap's. */
static void test_kernel_margin(void **state) {
    (void)state;
    mat4 layer;
    spot_layer(layer);
    const float low = 0.4f, high = 0.5f, gap_texels = 2.5f;
    float patch_edge = PATCH / LIGHT_Y, texel = 2.0f / MAP_SIZE;
    vec3 lo = {(patch_edge + gap_texels * texel) * (LIGHT_Y - low), low, -PATCH}, hi = {lo[0] + 0.5f, high, PATCH};
    map_reads reads;
    const map_settings poisson = {.kernel_depth = MAP_KERNEL_DEPTH_CENTRE},
                       nearest = {.filter = MAP_FILTER_NONE, .kernel_depth = MAP_KERNEL_DEPTH_CENTRE};
    patch_reads(layer, &poisson, &reads);
    assert_true(caster_needed(layer, &reads, lo, hi));
    patch_reads(layer, &nearest, &reads);
    assert_false(caster_needed(layer, &reads, lo, hi));
    /* Wider kernels reach farther. */
    static const map_filter order[] = {MAP_FILTER_NONE,    MAP_FILTER_HW,   MAP_FILTER_PCF3,
                                       MAP_FILTER_POISSON, MAP_FILTER_PCF5, MAP_FILTER_PCF7};
    for (size_t i = 1; i < sizeof order / sizeof *order; i++) {
        map_settings a = {.filter = order[i - 1]}, b = {.filter = order[i]};
        assert_true(map_read_reach(&a, MAP_2D, false) < map_read_reach(&b, MAP_2D, false));
    }
    /* A tent N reads the texels pcfN does (centres within (N + 1) / 2
     * texels), from nearer taps: the same reach, not less. */
    static const map_filter tents[][2] = {{MAP_FILTER_TENT3, MAP_FILTER_PCF3}, {MAP_FILTER_TENT5, MAP_FILTER_PCF5}};
    for (size_t i = 0; i < sizeof tents / sizeof *tents; i++)
        for (map_kind kind = MAP_2D; kind <= MAP_CUBE; kind++) {
            map_settings tent = {.filter = tents[i][0]}, grid = {.filter = tents[i][1]};
            assert_true(map_read_reach(&tent, kind, false) >= map_read_reach(&grid, kind, false));
        }
    /* A moment map's texel holds its blur's box: a read reaches its
     * radius past the bilinear footprint, an area light's the widest. */
    static const map_filter moment_filters[] = {MAP_FILTER_VSM, MAP_FILTER_EVSM2, MAP_FILTER_EVSM4, MAP_FILTER_MSM};
    const map_settings hw = {.filter = MAP_FILTER_HW};
    for (size_t i = 0; i < sizeof moment_filters / sizeof *moment_filters; i++) {
        map_settings moments = {.filter = moment_filters[i]};
        assert_true(map_read_reach(&moments, MAP_2D, false) >=
                    map_read_reach(&hw, MAP_2D, false) + MAP_MOMENTS_HARD_BLUR_TEXELS);
        assert_true(map_read_reach(&moments, MAP_2D, true) >=
                    map_read_reach(&hw, MAP_2D, false) + MAP_MOMENTS_MAX_BLUR_TEXELS);
        patch_reads(layer, &moments, &reads);
        assert_true(caster_needed(layer, &reads, lo, hi));
    }
    /* Receiver-plane taps compare depths beyond the receivers': a caster
     * behind them is needed then, and culled with centre depths. */
    const map_settings plane = {.kernel_depth = MAP_KERNEL_DEPTH_RECEIVER_PLANE};
    vec3 below_lo = {-0.5f, -3, -0.5f}, below_hi = {0.5f, -2, 0.5f};
    patch_reads(layer, &plane, &reads);
    assert_true(caster_needed(layer, &reads, below_lo, below_hi));
    patch_reads(layer, &poisson, &reads);
    assert_false(caster_needed(layer, &reads, below_lo, below_hi));
}

/* A cube face reads only what its side of the light sees, and a receiver
 * near its edge reads it through the kernel. */
static void test_cube_face(void **state) {
    (void)state;
    mat4 view, projection, face;
    glm_lookat((vec3){0, 0, 0}, (vec3){1, 0, 0}, (vec3){0, -1, 0}, view); /* +X */
    glm_perspective(glm_rad(FOV_DEG), 1, NEAR, FAR, projection);
    glm_mat4_mul(projection, view, face);
    const map_settings settings = {0};
    map_read_setup setup = {.reach = map_read_reach(&settings, MAP_CUBE, false), .size = MAP_SIZE, .cube = true};
    /* A ground patch below the light, on the +X side, beyond 45 degrees. */
    const float box[1][2][3] = {{{2, -3, -1}, {8, -3, 1}}};
    map_reads reads;
    float points[8][3];
    frustum_box_corners(box[0][0], box[0][1], (vec3 *)points);
    map_layer_reads(face, &setup, (const float(*)[3])points, 8, box, 1, &reads);
    assert_false(reads.empty);
    assert_true(caster_needed(face, &reads, (vec3){4, -2, -0.5f}, (vec3){5, -1, 0.5f}));    /* between */
    assert_false(caster_needed(face, &reads, (vec3){-5, -2, -0.5f}, (vec3){-4, -1, 0.5f})); /* the -X side */
    assert_false(caster_needed(face, &reads, (vec3){4, 2, -0.5f}, (vec3){5, 3, 0.5f}));     /* above the light */
}

/* ---- the programs ---- */

/* Runs `program` on the city for `frames` frames with `flags` (and a dump
 * into `dir` unless NULL); returns its --verbose caster line. */
static const char *run_city(const char *program, int frames, const char *flags, const char *dir) {
    static char text[16384];
    char command[2048];
    int n = snprintf(command, sizeof command, "%s --scene " CITY " --size " CITY_SIZE " --frames %d --verbose %s",
                     support_program(program), frames, flags);
    if (dir)
        snprintf(command + n, sizeof command - (size_t)n, " --dump %s", dir);
    assert_int_equal(support_run(command, text, sizeof text), 0);
    const char *line = strstr(text, "[X] caster culling: ");
    assert_non_null(line);
    return line;
}

/* The culled and reused counts of a caster line; counted: the casters
 * counted at all (the lights out of the view's reach count none). */
static void line_counts(const char *line, int *culled, int *counted, int *reused, int *layers) {
    const char *per_light = strstr(line, "per light:");
    assert_non_null(per_light);
    per_light += strlen("per light:");
    *culled = *counted = 0;
    for (int l = 0; l < CITY_LIGHTS; l++) {
        int index, drawn, light_culled, used;
        assert_int_equal(sscanf(per_light, " %d: %d/%d%n", &index, &drawn, &light_culled, &used), 3);
        assert_int_equal(index, l);
        /* psm's warped maps start from the casters its warp found relevant. */
        assert_true(drawn + light_culled <= CITY_CASTERS);
        *culled += light_culled;
        *counted += drawn + light_culled;
        per_light += used;
    }
    const char *cache = strstr(line, "map layers reused ");
    assert_non_null(cache);
    assert_int_equal(sscanf(cache, "map layers reused %d of %d", reused, layers), 2);
}

/* Most of the city casts into no light's layers that matter. */
static void test_most_casters_culled(void **state) {
    (void)state;
    for (size_t p = 0; p < sizeof programs / sizeof *programs; p++)
        for (size_t m = 0; m < sizeof motions / sizeof *motions; m++) {
            char flags[256];
            snprintf(flags, sizeof flags, "--motion %s", motions[m]);
            int culled, counted, reused, layers;
            line_counts(run_city(programs[p], 3, flags, NULL), &culled, &counted, &reused, &layers);
            assert_true(counted > 0 && 2 * culled > counted);
            printf("    %s, %s: casters culled %d of %d\n", programs[p], motions[m], culled, counted);
        }
}

/* Settings that change the kernel's reach and depth: still identical.
 * The quick tier takes every support_sweep_stride()th: the widest grid
 * and the moment map's blur, the reaches farthest from the default's
 * (tests/test_skip.c's city runs); test_kernel_margin orders every
 * filter's reach and the two kernel depths' in process. */
static void test_dumps_identical_other_kernels(void **state) {
    (void)state;
    static const char *const configs[] = {"--filter pcf7", "--filter none --map-size 512 --kernel-depth centre",
                                          "--filter tent3 --kernel-depth centre", "--filter tent5",
                                          /* a moment map's blur reaches farther, and reads every depth */
                                          "--filter msm"};
    _Static_assert(sizeof configs / sizeof *configs == SUPPORT_QUICK_STRIDE + 1, "the last config in the quick tier");
    for (size_t c = 0; c < sizeof configs / sizeof *configs; c += (size_t)support_sweep_stride()) {
        char on[256], off[256], flags[256];
        snprintf(on, sizeof on, OUT "/shadowmap_config%zu_on", c);
        snprintf(off, sizeof off, OUT "/shadowmap_config%zu_off", c);
        run_city("shadowmap", 1, configs[c], on);
        snprintf(flags, sizeof flags, "%s --no-skip", configs[c]);
        run_city("shadowmap", 1, flags, off);
        const char *differs = support_first_difference(on, off, dump_files, sizeof dump_files / sizeof *dump_files);
        if (differs)
            fail_msg("shadowmap %s: %s differs", configs[c], differs);
        printf("    shadowmap %s: dumps identical with and without skips\n", configs[c]);
    }
}

/* Static: the first frame renders every layer, each later one reuses them
 * all; with --no-skip nothing is cached. */
static void test_static_reuses_every_layer(void **state) {
    (void)state;
    for (int frames = 1; frames <= 3; frames++) {
        int culled, counted, reused, layers;
        line_counts(run_city("shadowmap", frames, "", NULL), &culled, &counted, &reused, &layers);
        assert_true(layers > 0);
        assert_int_equal(reused, frames == 1 ? 0 : layers);
        printf("    static, frame %d: map layers reused %d of %d\n", frames, reused, layers);
    }
    assert_non_null(strstr(run_city("shadowmap", 2, "--no-skip", NULL), "caching: OFF"));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_caster_cases),        cmocka_unit_test(test_kernel_margin),
        cmocka_unit_test(test_cube_face),           cmocka_unit_test(test_static_reuses_every_layer),
        cmocka_unit_test(test_most_casters_culled), cmocka_unit_test(test_dumps_identical_other_kernels),
    };
    return cmocka_run_group_tests_name("shadow map skips", tests, NULL, NULL);
}
