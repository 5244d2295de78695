/* Tests that the ray-traced reference (common/measure/raytrace.c) is exact
 * where the arithmetic allows, in-process; each measuring test prints what
 * it measured.
 *
 *   invariance  one table of cases: tests/data/ref_invariance.json moved
 *               far from the origin, scaled (positions, sizes, ranges,
 *               near and far), or given extreme near/far planes, written as
 *               JSON under OUT_DIR and loaded back (so the scene file's own
 *               float rounding is part of the case), against the scene as
 *               it is: reference against reference by shadowdiff's rules,
 *               the moved dump's light and depths turned back first.
 *   offsets     tests/data/ref_sky_sphere.json (a box and a 5 cm plate on
 *               the ground) keeps its shadows, contact shadows included,
 *               when a sky sphere of radius 5000 that neither casts nor
 *               receives, or a 1e5 ground, makes the scene huge.
 *   cameras     an invalid camera is refused with one line naming the
 *               scene, in-process and by the program.
 *
 * The test scene's coordinates are multiples of 1/16: moving it by 1e6 is
 * then exact in the scene file's floats, whose spacing there is 1/16
 * (simple.json's coordinates would round by up to 1/32, moving its shadows
 * by about a pixel). Meshes are in object space and are transformed in
 * double by the reference, so they do not round at 1e6. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <cglm/cglm.h>
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "path.h"
#include "raytrace.h"
#include "support.h"

#define INVARIANCE_SCENE "tests/data/ref_invariance.json"
#define SKY_SCENE "tests/data/ref_sky_sphere.json"
#define OUT_DIR "out/test/raytrace_invariance"
#define WIDTH 320
#define HEIGHT 180
#define MAX_SCENE_BYTES (1 << 20)
/* Reference against reference: at most this many misclassified,
 * over at least this share of the pixels the unmoved scene compares. */
#define MAX_MISCLASSIFIED_PERCENT 0.01
#define MIN_COMPARED_SHARE 0.99
/* The sky sphere taken out of the way: shrunk to a radius of 0.5 and put
 * under the ground, where it is neither seen nor (it does not cast) in any
 * shadow ray's way. */
#define SKY_SHRINK 1e-4f
#define SKY_BURY_DEPTH 10.0f
/* The 20 m ground made 1e5 across. */
#define HUGE_GROUND_SCALE 5000.0f
#define EXIT_RUNTIME 1

/* The scene's points become point * scale + translate; near and far, where
 * given, replace the scaled ones. */
typedef struct invariance_case {
    const char *name;
    double translate[3];
    double scale;                 /* 0: 1 */
    double near_plane, far_plane; /* 0: the scene's, scaled */
} invariance_case;

static const invariance_case invariance_cases[] = {
    {"translated 1e5", {1e5, 1e5, 1e5}, 0, 0, 0},   {"translated 1e6", {1e6, -1e6, 1e6}, 0, 0, 0},
    {"scaled 1e-3", {0, 0, 0}, 1e-3, 0, 0},         {"scaled 1e4", {0, 0, 0}, 1e4, 0, 0},
    {"near 1e-4 far 1e5", {0, 0, 0}, 0, 1e-4, 1e5}, {"near 0.1 far 1e7", {0, 0, 0}, 0, 0.1, 1e7},
};

static double case_scale(const invariance_case *c) { return c->scale != 0 ? c->scale : 1; }

/* ---- writing a moved scene ---- */

static void set_item(cJSON *parent, const char *key, cJSON *item) {
    assert_non_null(item);
    if (cJSON_GetObjectItemCaseSensitive(parent, key))
        assert_true(cJSON_ReplaceItemInObjectCaseSensitive(parent, key, item));
    else
        assert_true(cJSON_AddItemToObject(parent, key, item));
}

/* parent[key] (3 numbers; `fallback` where absent, NULL: left absent) to
 * point * scale + translate. */
static void move_point(cJSON *parent, const char *key, const double *fallback, const invariance_case *c) {
    const cJSON *old = cJSON_GetObjectItemCaseSensitive(parent, key);
    if (!old && !fallback)
        return;
    double point[3];
    for (int k = 0; k < 3; k++) {
        point[k] = old ? cJSON_GetArrayItem(old, k)->valuedouble : fallback[k];
        point[k] = point[k] * case_scale(c) + c->translate[k];
    }
    set_item(parent, key, cJSON_CreateDoubleArray(point, 3));
}

/* parent[key], a number or an array of numbers (`fallback` where absent,
 * 0: left absent), times `factor`. */
static void scale_numbers(cJSON *parent, const char *key, double fallback, double factor) {
    cJSON *old = cJSON_GetObjectItemCaseSensitive(parent, key);
    if (cJSON_IsArray(old)) {
        for (cJSON *item = old->child; item; item = item->next)
            cJSON_SetNumberValue(item, item->valuedouble * factor);
    } else if (old || fallback != 0) {
        set_item(parent, key, cJSON_CreateNumber((old ? old->valuedouble : fallback) * factor));
    }
}

static void move_camera(cJSON *camera, const invariance_case *c) {
    static const double scene_near = 0.1, scene_far = 100; /* scene.h's defaults */
    move_point(camera, "position", NULL, c);
    move_point(camera, "target", NULL, c);
    const cJSON *near_plane = cJSON_GetObjectItemCaseSensitive(camera, "near");
    const cJSON *far_plane = cJSON_GetObjectItemCaseSensitive(camera, "far");
    double near_value =
        c->near_plane != 0 ? c->near_plane : (near_plane ? near_plane->valuedouble : scene_near) * case_scale(c);
    double far_value =
        c->far_plane != 0 ? c->far_plane : (far_plane ? far_plane->valuedouble : scene_far) * case_scale(c);
    set_item(camera, "near", cJSON_CreateNumber(near_value));
    set_item(camera, "far", cJSON_CreateNumber(far_value));
}

/* Writes `source` moved by case c to OUT_DIR/NAME.json (its path in
 * `path`): every point of the camera, lights and objects, and every length
 * (an object's scale, a point or spot light's radius and range). */
static void write_moved_scene(const char *source, const invariance_case *c, const char *name, char *path,
                              size_t size) {
    static const double origin[3] = {0, 0, 0};
    char *text = path_read_text(source, MAX_SCENE_BYTES, NULL);
    assert_non_null(text);
    cJSON *root = cJSON_Parse(text);
    free(text);
    assert_non_null(root);
    move_camera(cJSON_GetObjectItemCaseSensitive(root, "camera"), c);
    const cJSON *item;
    cJSON_ArrayForEach(item, cJSON_GetObjectItemCaseSensitive(root, "lights")) {
        cJSON *light = (cJSON *)item;
        bool directional = strcmp(cJSON_GetObjectItemCaseSensitive(light, "type")->valuestring, "directional") == 0;
        move_point(light, "position", NULL, c);
        scale_numbers(light, "range", 0, case_scale(c));
        if (!directional) /* a directional light's radius is an angle */
            scale_numbers(light, "radius", 0, case_scale(c));
    }
    cJSON_ArrayForEach(item, cJSON_GetObjectItemCaseSensitive(root, "objects")) {
        move_point((cJSON *)item, "translate", origin, c);
        scale_numbers((cJSON *)item, "scale", 1, case_scale(c));
    }
    support_write_json(root, OUT_DIR, name, path, size);
    cJSON_Delete(root);
}

/* ---- rendering and comparing ---- */

static void render(const scene *s, const char *name, dump_frame *frame) {
    const raytrace_settings settings = {.light_samples = 1, .scene_name = name};
    assert_true(raytrace_render(s, WIDTH, HEIGHT, 0, &settings, frame));
}

/* origin: the scene's (scene.h, "Large worlds"), which the dump's light
 * is relative to. */
static void render_file(const char *path, dump_frame *frame, double origin[3]) {
    scene s;
    assert_true(scene_load(&s, path));
    render(&s, path, frame);
    memcpy(origin, s.origin, sizeof s.origin);
    scene_free(&s);
}

/* The pixels `reference` compares with itself: it sees a surface facing
 * the light. */
static long comparable_pixels(const dump_frame *reference) {
    shadowdiff_result self;
    assert_true(shadowdiff_compare(reference, reference, NULL, &self, NULL));
    return self.compared;
}

/* Compares `test` with `reference` and checks the bounds; prints a line. */
static void expect_same_shadows(const char *what, const dump_frame *reference, const dump_frame *test) {
    const shadowdiff_settings settings = {.reference_name = "unmoved", .test_name = what};
    shadowdiff_result r;
    assert_true(shadowdiff_compare(reference, test, &settings, &r, NULL));
    long comparable = comparable_pixels(reference);
    printf("    %-20s %6ld of %6ld pixels compared (%6.2f %%), %ld misclassified (%.4f %%), mean error %.2g\n", what,
           r.compared, comparable, 100.0 * (double)r.compared / (double)comparable, r.false_shadow + r.false_lit,
           r.misclassified_percent, r.mean_abs_error);
    assert_true(comparable > WIDTH * HEIGHT / 4);
    assert_true((double)r.compared >= MIN_COMPARED_SHARE * (double)comparable);
    assert_true(r.misclassified_percent <= MAX_MISCLASSIFIED_PERCENT);
}

/* The moved dump in the unmoved scene's units: its light moved back (in
 * world coordinates: the moved scene's origin added), its depths divided
 * by the scale (positions and normals are the reference's to give). */
static void move_back(dump_frame *f, const invariance_case *c, const double origin[3]) {
    if (f->light[3] != 0)
        for (int k = 0; k < 3; k++)
            f->light[k] = (float)((f->light[k] + origin[k] - c->translate[k]) / case_scale(c));
    for (size_t i = 0; i < (size_t)f->width * (size_t)f->height; i++)
        if (f->ids[i] >= 0)
            f->depth[i] = (float)(f->depth[i] / case_scale(c));
}

static void test_moved_and_scaled_scenes_give_the_same_reference(void **state) {
    (void)state;
    dump_frame unmoved;
    double origin[3];
    render_file(INVARIANCE_SCENE, &unmoved, origin);
    for (size_t k = 0; k < sizeof invariance_cases / sizeof *invariance_cases; k++) {
        const invariance_case *c = &invariance_cases[k];
        char name[32], path[256];
        snprintf(name, sizeof name, "case_%zu", k);
        write_moved_scene(INVARIANCE_SCENE, c, name, path, sizeof path);
        dump_frame moved;
        render_file(path, &moved, origin);
        move_back(&moved, c, origin);
        expect_same_shadows(c->name, &unmoved, &moved);
        dump_frame_free(&moved);
    }
    dump_frame_free(&unmoved);
}

/* ---- offsets ---- */

static int object_named(const scene *s, const char *name) {
    for (int i = 0; i < s->object_count; i++)
        if (strcmp(s->objects[i].name, name) == 0)
            return i;
    fail_msg("%s: no object '%s'", SKY_SCENE, name);
    return -1;
}

static long shadowed_on(const dump_frame *f, int object) {
    long count = 0;
    for (size_t i = 0; i < (size_t)f->width * (size_t)f->height; i++)
        count += f->ids[i] == object && f->visibility[i] < SHADOWDIFF_LIT_THRESHOLD;
    return count;
}

static void test_offsets_ignore_the_size_of_the_scene(void **state) {
    (void)state;
    scene s;
    assert_true(scene_load(&s, SKY_SCENE));
    int sky = object_named(&s, "sky"), ground = object_named(&s, "ground");
    float(*sky_model)[4] = s.objects[sky].model, (*ground_model)[4] = s.objects[ground].model;
    float full_sky[4][4];
    memcpy(full_sky, sky_model, sizeof full_sky);
    glm_mat4_identity(sky_model);
    glm_scale_uni(sky_model, SKY_SHRINK);
    sky_model[3][1] = -SKY_BURY_DEPTH;
    dump_frame small, with_sky, huge_ground;
    render(&s, SKY_SCENE, &small);
    memcpy(sky_model, full_sky, sizeof full_sky);
    render(&s, SKY_SCENE, &with_sky);
    glm_mat4_identity(sky_model);
    glm_scale_uni(sky_model, SKY_SHRINK);
    sky_model[3][1] = -SKY_BURY_DEPTH;
    ground_model[0][0] *= HUGE_GROUND_SCALE;
    ground_model[2][2] *= HUGE_GROUND_SCALE;
    render(&s, SKY_SCENE, &huge_ground);
    printf("    shadowed ground pixels: %ld (small scene), %ld (sky sphere r 5000), %ld (ground 1e5)\n",
           shadowed_on(&small, ground), shadowed_on(&with_sky, ground), shadowed_on(&huge_ground, ground));
    assert_true(shadowed_on(&small, ground) > 0);
    expect_same_shadows("sky sphere r 5000", &small, &with_sky);
    expect_same_shadows("ground 1e5", &small, &huge_ground);
    dump_frame_free(&small);
    dump_frame_free(&with_sky);
    dump_frame_free(&huge_ground);
    scene_free(&s);
}

/* ---- cameras ---- */

static void test_invalid_camera_refused(void **state) {
    (void)state;
    scene s;
    assert_true(scene_load(&s, INVARIANCE_SCENE));
    const scene_camera good = s.camera;
    scene_camera bad[4] = {good, good, good, good};
    bad[0].position[1] = NAN;
    bad[1].fov_deg = 0;
    bad[2].near_plane = bad[2].far_plane;
    for (int k = 0; k < 3; k++) /* up along the view */
        bad[3].up[k] = good.target[k] - good.position[k];
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        s.camera = bad[k];
        dump_frame f;
        const raytrace_settings settings = {.scene_name = INVARIANCE_SCENE};
        support_capture_stderr();
        bool ok = raytrace_render(&s, WIDTH, HEIGHT, 0, &settings, &f);
        const char *text = support_release_stderr();
        printf("    %s", text);
        assert_false(ok);
        assert_int_equal(support_count_lines(text), 1);
        assert_non_null(strstr(text, INVARIANCE_SCENE));
        assert_non_null(strstr(text, "camera"));
    }
    scene_free(&s);

    /* In a file scene_load refuses it first, naming the file. */
    const invariance_case near_above_far = {"near above far", {0, 0, 0}, 0, 5, 1};
    char path[256], command[512], err[4096];
    write_moved_scene(INVARIANCE_SCENE, &near_above_far, "near_above_far", path, sizeof path);
    snprintf(command, sizeof command, "%s --size 32x18 --scene %s", support_program("raytrace"), path);
    assert_int_equal(support_run(command, err, sizeof err), EXIT_RUNTIME);
    printf("    %s", err);
    assert_int_equal(support_count_lines(err), 1);
    assert_non_null(strstr(err, path));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_moved_and_scaled_scenes_give_the_same_reference),
        cmocka_unit_test(test_offsets_ignore_the_size_of_the_scene),
        cmocka_unit_test(test_invalid_camera_refused),
    };
    return cmocka_run_group_tests_name("ray-traced reference: invariance", tests, NULL, NULL);
}
