/* Skips never change a decision (README, "Skips"): view culling leaves out
 * only objects with no pixel on screen, a skipped light adds 0 to every
 * visible pixel, a culled caster shadows no visible receiver and a cache
 * holds what would be made again. So with skips on and with --no-skip
 * every technique's dump (visibility, depth, object ids, the picture) is
 * the same byte for byte, on the standard scenes, long_view, the
 * 1000-object city, the dense scene, the street city, the engines and
 * projective textures' limits, static and over frames in which the light
 * or the camera moves. And the skips do skip: most of the city lies outside its street-level view and
 * most of its lights out of reach of it; most of the street city's
 * casters and objects are hidden; nothing of simple is culled. Each switch turns its
 * skip off.
 *
 * The geometry is checked in process first: the box and sphere against a
 * frustum, the hull of a light and a box, a light's reach, a light's mask
 * of what is seen. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "frustum.h"
#include "light_mask.h"
#include "scene.h"
#include "registry.h"
#include "support.h"

#define OUT "out/test/skip"
#define SCENES "assets/scenes"
#define CITY "city_1000"
#define CITY_OBJECTS 1001 /* the ground and 1000 buildings */
#define CITY_LIGHTS 7
#define CITY_SKIPPED_LIGHT "4" /* a point light far to the left of the street */
#define STREET "street"
#define ENGINE "engine"
#define STREET_LAMPS 3 /* its spot lights, none with a range */
/* A test frustum: 90 degrees, square, near 1, far 100, looking down -z. */
#define TEST_FOV_DEG 90.0f
#define TEST_NEAR 1.0f
#define TEST_FAR 100.0f

/* Every technique dumps each case with skips on and with --no-skip, at
 * DUMP_SIZE: what a skip leaves out does not depend on the pixels, and
 * small frames keep the run short. The caches work across frames, so the
 * moving cases and the city's static one render several frames (the dump
 * is the last one's). */
#define DUMP_SIZE "--size 320x180"
static const struct {
    const char *scene, *flags;
} cases[] = {
    {"simple", ""},
    {"bunny", ""},
    {"teapot", ""},
    {"long_view", ""},
    {"simple", "--frames 3 --motion light"},
    {"simple", "--frames 3 --motion camera"},
    {CITY, "--frames 3"},
    {CITY, "--frames 3 --motion light"},
    {CITY, "--frames 3 --motion camera"},
    /* A light the view's objects are out of reach of: skipped, and its
     * dump is still the same (it adds 0 everywhere on screen). */
    {CITY, "--light " CITY_SKIPPED_LIGHT},
    {"dense", "--frames 2 --motion light"},
    /* Scenes whose casters are hidden rather than out of view: the city
     * seen across from its edge with unranged lamps, and two dense real
     * models; hidden casters are culled there (test_hidden_casters_culled). */
    {STREET, "--frames 2"},
    {STREET, "--frames 3 --motion light"},
    {STREET, "--frames 3 --motion camera"},
    {ENGINE, "--frames 2 --motion light"},
    /* A receiver between the light and a caster, one that casts and
     * receives over another (projective textures' limits), the camera
     * moving or the light: what culling leaves out of an image may not
     * be read. */
    {"projective_limits", "--frames 3 --motion camera"},
    {"projective_limits", "--frames 3 --motion light"},
};
SUPPORT_SWEEPABLE(sizeof cases / sizeof *cases); /* test_dumps_identical_with_and_without_skips */
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

/* The hull of a light and a receiver box: what may shadow the box is
 * inside, what cannot is outside (frustum_light_hull). */
static void test_light_hull(void **state) {
    (void)state;
    static const vec3 receiver_lo = {-1, 0, -1}, receiver_hi = {1, 0.1f, 1};
    static const struct {
        const char *what;
        float light[4];
        vec3 lo, hi;
        bool outside;
    } cases[] = {
        {"between the light and the box", {0, 10, 0, 1}, {-0.2f, 4, -0.2f}, {0.2f, 5, 0.2f}, false},
        {"beside the cone to the box", {0, 10, 0, 1}, {3, 4, -0.2f}, {3.4f, 5, 0.2f}, true},
        {"beyond the light", {0, 10, 0, 1}, {-0.2f, 12, -0.2f}, {0.2f, 13, 0.2f}, true},
        {"below the box", {0, 10, 0, 1}, {-0.2f, -2, -0.2f}, {0.2f, -1, 0.2f}, true},
        {"straddling the cone's edge", {0, 10, 0, 1}, {0.5f, 4, -0.2f}, {1.5f, 5, 0.2f}, false},
        {"in the sun's way, far up", {0, 1, 0, 0}, {-0.2f, 500, -0.2f}, {0.2f, 501, 0.2f}, false},
        {"beside the sun's column", {0, 1, 0, 0}, {2, 5, -0.2f}, {3, 6, 0.2f}, true},
        {"slanted sun: up its slope", {1, 1, 0, 0}, {4.5f, 5, -0.2f}, {5.5f, 6, 0.2f}, false},
        {"slanted sun: the other way", {1, 1, 0, 0}, {-5.5f, 5, -0.2f}, {-4.5f, 6, 0.2f}, true},
        {"light inside the box: the box itself", {0, 0.05f, 0, 1}, {2, -1, -1}, {3, 1, 1}, true},
        {"light inside the box, a caster in it", {0, 0.05f, 0, 1}, {0.5f, 0, 0}, {0.6f, 0.05f, 0.1f}, false},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        vec4 planes[FRUSTUM_HULL_MAX_PLANES];
        int n = frustum_light_hull(cases[i].light, receiver_lo, receiver_hi, planes);
        assert_true(n > 0 && n <= FRUSTUM_HULL_MAX_PLANES);
        if (frustum_planes_box_outside((const vec4 *)planes, n, cases[i].lo, cases[i].hi, 1e-5f) != cases[i].outside)
            fail_msg("%s: expected %s the hull", cases[i].what, cases[i].outside ? "outside" : "inside");
    }
}

/* A light reaches a box within its range and a spot's cone; never
 * nothing for a directional light (scene_light_reaches_box), and a range
 * sphere beside the view is outside it (frustum_sphere_outside). */
static void test_light_reach(void **state) {
    (void)state;
    static const vec3 lo = {-1, 0, -1}, hi = {1, 1, 1};
    static const struct {
        const char *what;
        scene_light light;
        bool reaches;
    } cases[] = {
        {"point within range", {.type = SCENE_LIGHT_POINT, .position = {0, 5, 0}, .range = 4.5f}, true},
        {"point out of range", {.type = SCENE_LIGHT_POINT, .position = {0, 5, 0}, .range = 3.5f}, false},
        {"point without a range", {.type = SCENE_LIGHT_POINT, .position = {0, 500, 0}}, true},
        {"spot aimed at it",
         {.type = SCENE_LIGHT_SPOT, .position = {0, 5, 0}, .direction = {0, -1, 0}, .outer_angle_deg = 10},
         true},
        {"spot aimed away",
         {.type = SCENE_LIGHT_SPOT, .position = {0, 5, 0}, .direction = {0, 1, 0}, .outer_angle_deg = 60},
         false},
        {"spot aimed beside",
         {.type = SCENE_LIGHT_SPOT, .position = {10, 5, 0}, .direction = {0, -1, 0}, .outer_angle_deg = 30},
         false},
        {"directional", {.type = SCENE_LIGHT_DIRECTIONAL, .direction = {0, 1, 0}}, true},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++)
        if (scene_light_reaches_box(&cases[i].light, lo, hi) != cases[i].reaches)
            fail_msg("%s: expected %s", cases[i].what, cases[i].reaches ? "reaches" : "does not reach");
    mat4 projection;
    glm_perspective(glm_rad(TEST_FOV_DEG), 1, TEST_NEAR, TEST_FAR, projection);
    assert_false(frustum_sphere_outside(projection, (vec3){0, 0, -10}, 1));
    assert_false(frustum_sphere_outside(projection, (vec3){12, 0, -10}, 3)); /* across the right plane */
    assert_true(frustum_sphere_outside(projection, (vec3){20, 0, -10}, 3));
    assert_true(frustum_sphere_outside(projection, (vec3){0, 0, 10}, 3)); /* behind the eye */
}

/* A light's mask of one visible patch of ground (light_mask.h): a box
 * between the light and the patch shadows it, one beyond the patch, one
 * behind the light and one beside the shadow's path do not, one around
 * a positional light sees everything. */
static void test_light_mask(void **state) {
    (void)state;
    static const vec3 patch_lo = {2, 0, -0.5f}, patch_hi = {3, 0.01f, 0.5f};
    static const scene_light sun = {.type = SCENE_LIGHT_DIRECTIONAL, .direction = {0, -1, 0}};
    static const scene_light lamp = {.type = SCENE_LIGHT_POINT, .position = {0, 5, 0}};
    static const struct {
        const char *what;
        const scene_light *light;
        vec3 lo, hi;
        bool read;
    } cases[] = {
        {"sun: above the patch", &sun, {2.2f, 2, -0.2f}, {2.8f, 3, 0.2f}, true},
        {"sun: beside it", &sun, {5, 2, -0.2f}, {6, 3, 0.2f}, false},
        {"sun: below it", &sun, {2.2f, -3, -0.2f}, {2.8f, -2, 0.2f}, false},
        {"lamp: on the way to the patch", &lamp, {1.05f, 2.3f, -0.2f}, {1.45f, 2.7f, 0.2f}, true},
        {"lamp: beyond the patch", &lamp, {3.55f, -2.7f, -0.2f}, {3.95f, -2.3f, 0.2f}, false},
        {"lamp: behind the lamp", &lamp, {-1.45f, 7.3f, -0.2f}, {-1.05f, 7.7f, 0.2f}, false},
        {"lamp: beside the way", &lamp, {-2, 2, -3}, {-1, 3, -2}, false},
        {"lamp: around the lamp", &lamp, {-0.5f, 4.5f, -0.5f}, {0.5f, 5.5f, 0.5f}, true},
    };
    float patch[1][8][3];
    frustum_box_corners(patch_lo, patch_hi, patch[0]);
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        mat4 layers[LIGHT_MASK_MAX_LAYERS];
        int count = light_mask_layers(cases[i].light, (const float(*)[8][3])patch, 1, layers);
        assert_int_equal(count, cases[i].light->type == SCENE_LIGHT_DIRECTIONAL ? 1 : LIGHT_MASK_MAX_LAYERS);
        bool read = false;
        for (int m = 0; m < count; m++) {
            static light_mask mask;
            light_mask_start(&mask, layers[m], 0, false, false);
            light_mask_add(&mask, (const float(*)[3])patch[0], NULL);
            read = read || light_mask_box_read(&mask, cases[i].lo, cases[i].hi);
        }
        if (read != cases[i].read)
            fail_msg("%s: expected %s", cases[i].what, cases[i].read ? "needed" : "culled");
    }
}

static void dump_dir(const char *technique, size_t c, const char *skips, char *out, size_t size) {
    snprintf(out, size, OUT "/%s_%zu_%s_%s", technique, c, cases[c].scene, skips);
}

/* Every technique on every case (under the sanitizers every
 * support_sweep_stride()th pair of the two, spread over every case and
 * technique: SUPPORT_SWEEPABLE): skips on and --no-skip dump the same. */
static void test_dumps_identical_with_and_without_skips(void **state) {
    (void)state;
    const int case_count = (int)(sizeof cases / sizeof *cases);
    int compared = 0;
    for (int i = 0; i < registry_technique_count * case_count; i += support_sweep_stride()) {
        const char *technique = registry_techniques[i / case_count]->name;
        int c = i % case_count;
        char scene[256], on[256], off[256], on_flags[256], off_flags[sizeof on_flags + 16];
        snprintf(scene, sizeof scene, SCENES "/%s.json", cases[c].scene);
        snprintf(on_flags, sizeof on_flags, DUMP_SIZE " %s", cases[c].flags);
        snprintf(off_flags, sizeof off_flags, "%s --no-skip", on_flags);
        dump_dir(technique, (size_t)c, "on", on, sizeof on);
        dump_dir(technique, (size_t)c, "off", off, sizeof off);
        assert_int_equal(support_dump(technique, scene, on_flags, on), 0);
        assert_int_equal(support_dump(technique, scene, off_flags, off), 0);
        const char *differs = support_first_difference(on, off, dump_files, sizeof dump_files / sizeof *dump_files);
        if (differs)
            fail_msg("%s on %s %s: %s differs between %s and %s", technique, cases[c].scene, cases[c].flags, differs,
                     on, off);
        compared++;
    }
    printf("    %d of %d technique and case pairs: dumps identical with and without skips\n", compared,
           registry_technique_count * case_count);
}

/* The --verbose line of one frame of `technique` on `scene` (a name in
 * SCENES) that starts with `marker` (support_verbose_line). */
static const char *verbose_line(const char *technique, const char *scene, const char *flags, const char *marker) {
    char scene_file[256];
    snprintf(scene_file, sizeof scene_file, SCENES "/%s.json", scene);
    return support_verbose_line(technique, scene_file, flags, marker);
}

/* The --verbose culling line of one frame of the floor on `scene`. */
static const char *culling_line(const char *scene, const char *flags) {
    return verbose_line("unshadowed", scene, flags, "view culling: ");
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

/* Most of the city's lights are out of the street's reach. */
static void test_city_lights_skipped(void **state) {
    (void)state;
    const char *line = culling_line(CITY, "");
    const char *reach = line ? strstr(line, "light reach: ") : NULL;
    int skipped, count;
    assert_non_null(reach);
    assert_int_equal(sscanf(reach, "light reach: lights skipped %d of %d", &skipped, &count), 2);
    printf("    %s: lights skipped %d of %d\n", CITY, skipped, count);
    assert_int_equal(count, CITY_LIGHTS);
    assert_true(skipped >= 3 && skipped < count);
    reach = strstr(culling_line("simple", ""), "light reach: ");
    assert_non_null(reach);
    assert_int_equal(sscanf(reach, "light reach: lights skipped %d of %d", &skipped, &count), 2);
    assert_int_equal(skipped, 0);
}

/* Light 0's casters drawn by `technique` on `scene` with `flags`. */
static int casters_drawn(const char *technique, const char *scene, const char *flags) {
    const char *line = verbose_line(technique, scene, flags, "[X] caster culling: ");
    int drawn, culled;
    assert_non_null(line);
    assert_int_equal(sscanf(line, "[X] caster culling: casters drawn / culled per light: 0: %d/%d", &drawn, &culled),
                     2);
    return drawn;
}

/* Across the street city's view most buildings stand behind the first
 * rows, inside the hull of the sun and the visible ground: culled as
 * hidden, by the volumes and by the shadow map, and drawn with
 * --no-hidden-cull. */
static void test_hidden_casters_culled(void **state) {
    (void)state;
    /* The engines cast in full view: nothing is hidden. The volumes
     * still draw each engine's only where its shadow may be seen; the
     * map has nothing to gain, and the skip sleeps instead of reading the
     * depth back every frame. */
    static const struct {
        const char *technique, *on_engine;
    } cases[] = {
        {"volumes", "hidden casters: culled / narrowed per light 0: 0/2"},
        {"shadowmap", "hidden casters: nothing to cull: asleep"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        int hidden = casters_drawn(cases[i].technique, STREET, "");
        int boxes = casters_drawn(cases[i].technique, STREET, "--no-hidden-cull");
        printf("    %s on %s: light 0 draws %d casters, %d with --no-hidden-cull\n", cases[i].technique, STREET,
               hidden, boxes);
        if (!(hidden > 0 && 2 * hidden < boxes))
            fail_msg("%s: %d casters drawn, not under half of %d", cases[i].technique, hidden, boxes);
        const char *line = verbose_line(cases[i].technique, ENGINE, "", "[X] caster culling: ");
        assert_non_null(line);
        if (!strstr(line, cases[i].on_engine))
            fail_msg("%s on %s: expected \"%s\"", cases[i].technique, ENGINE, cases[i].on_engine);
    }
}

/* Along the street most buildings in the view's frustum stand behind the
 * first rows: the floor's lit pass, as every shading pass, leaves them
 * out, and draws them all with --no-hidden-cull. */
static void test_hidden_objects_left_out(void **state) {
    (void)state;
    const char *line = culling_line(STREET, "");
    int drawn, culled, hidden;
    assert_non_null(line);
    assert_int_equal(sscanf(line, "view culling: objects drawn %d / culled %d", &drawn, &culled), 2);
    const char *objects = strstr(line, "objects hidden ");
    assert_non_null(objects);
    assert_int_equal(sscanf(objects, "objects hidden %d", &hidden), 1);
    printf("    %s: %d objects in view, %d of them hidden\n", STREET, drawn, hidden);
    if (!(2 * hidden > drawn && hidden < drawn))
        fail_msg("%d of %d objects in view hidden: expected most, not all", hidden, drawn);
    line = culling_line(STREET, "--no-hidden-cull");
    assert_non_null(line);
    assert_null(strstr(line, "objects hidden"));
}

/* Along the street each lamp lights a few tiles of what is seen: every
 * technique draws it in its rectangle narrowed to them (the shadow maps
 * then shade it in a pass of its own, shading_split_lights), and in
 * the frame's rectangle with --no-hidden-cull (the quick tier that on
 * every support_sweep_stride()th technique: the rectangles are the
 * skips', common to all, and test_switches_turn_skips_off has the
 * switch). */
static void test_lights_narrowed(void **state) {
    (void)state;
    static const char *const techniques[] = {"planar", "projective", "shadowmap", "psm", "cascades", "volumes"};
    for (size_t i = 0; i < sizeof techniques / sizeof *techniques; i++) {
        const char *line = verbose_line(techniques[i], STREET, "", "[X] caster culling: ");
        const char *narrowed = line ? strstr(line, "lights narrowed ") : NULL;
        int count;
        assert_non_null(narrowed);
        assert_int_equal(sscanf(narrowed, "lights narrowed %d", &count), 1);
        printf("    %s on %s: lights narrowed %d\n", techniques[i], STREET, count);
        assert_int_equal(count, STREET_LAMPS);
        if (i % (size_t)support_sweep_stride() != 0)
            continue;
        line = verbose_line(techniques[i], STREET, "--no-hidden-cull", "[X] caster culling: ");
        assert_non_null(line);
        assert_null(strstr(line, "lights narrowed"));
    }
}

/* Each switch turns its skip off: its own and the program-wide one. */
static void test_switches_turn_skips_off(void **state) {
    (void)state;
    static const struct {
        const char *flag, *off;
    } switches[] = {
        {"--no-view-cull", "view culling: OFF"},
        {"--no-light-reach", "light reach: OFF"},
        {"--no-caster-cull", "caster culling: OFF"},
        {"--no-hidden-cull", "hidden casters: OFF"},
        {"--no-cache", "caching: OFF"},
    };
    for (size_t i = 0; i < sizeof switches / sizeof *switches; i++) {
        const char *line = culling_line(CITY, switches[i].flag);
        assert_non_null(line);
        for (size_t k = 0; k < sizeof switches / sizeof *switches; k++)
            if ((strstr(line, switches[k].off) != NULL) != (k == i))
                fail_msg("%s: \"%s\" expected %s", switches[i].flag, switches[k].off, k == i ? "" : "absent");
    }
    const char *line = culling_line(CITY, "--no-skip");
    assert_non_null(line);
    for (size_t k = 0; k < sizeof switches / sizeof *switches; k++)
        if (!strstr(line, switches[k].off))
            fail_msg("--no-skip: \"%s\" expected", switches[k].off);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_box_outside),           cmocka_unit_test(test_city_mostly_culled),
        cmocka_unit_test(test_simple_nothing_culled), cmocka_unit_test(test_light_hull),
        cmocka_unit_test(test_light_reach),           cmocka_unit_test(test_light_mask),
        cmocka_unit_test(test_city_lights_skipped),   cmocka_unit_test(test_switches_turn_skips_off),
        cmocka_unit_test(test_hidden_casters_culled), cmocka_unit_test(test_hidden_objects_left_out),
        cmocka_unit_test(test_lights_narrowed),       cmocka_unit_test(test_dumps_identical_with_and_without_skips),
    };
    return cmocka_run_group_tests_name("skips", tests, NULL, NULL);
}
