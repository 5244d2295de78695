/* glTF 2.0 files as scenes (common/data/scene_gltf.c): what a file of a
 * ground, a box and its mirror image, two cameras, a spot and a sun
 * (tests/data/gltf_scene.gltf) becomes, through either camera; the
 * camera and light fitted to a file without them, said once; Debian's broken glTF files, one line each;
 * and the shadows of the file's scene and of a real model's against the
 * reference. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <cglm/cglm.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image.h"
#include "scene.h"
#include "support.h"

#define GLTF_SCENE "tests/data/gltf_scene.gltf"
#define GLTF_SCENE_BINARY "tests/data/gltf_scene.glb" /* the same scene, binary */
#define GLTF_TEXTURED "tests/data/gltf_textured.gltf"
#define GLTF_CUT_OUT "tests/data/gltf_cut_out.gltf"
#define GLTF_CUT_OUT_ON_PLANE "tests/data/gltf_cut_out_on_plane.json" /* its fence and leaves over a plane */
/* A single-sided wall seen from behind (object GLTF_SIDED_WALL) between
 * the camera and a box (GLTF_SIDED_BOX) that the sun, from the camera's
 * side, shadows through it; a double-sided panel seen from behind. */
#define GLTF_SIDED "tests/data/gltf_sided.gltf"
#define GLTF_SIDED_BOX 1
#define GLTF_SIDED_WALL 2
#define GLTF_STAINED_GLASS "assets/scenes/stained_glass.gltf" /* build/scenegen's */
#define GLTF_FENCE "assets/scenes/fence.gltf"
#define GLTF_INCLUDED "tests/data/gltf_included.json"           /* the three files above in one scene file */
#define GLTF_GLASS_AREA "tests/data/gltf_glass_area.json"       /* the stained glass under an area point light */
#define GLTF_LAMP_ON_GLASS "tests/data/gltf_lamp_on_glass.json" /* a point light just over a pane */
#define GLTF_LAMP_ON_GLASS_SIZE "--size 320x180"
/* Small and with a quarter of the reference's samples: hybrid traces
 * every pixel near a pane's box. */
#define GLTF_GLASS_AREA_SIZE "--size 320x180"
#define GLTF_GLASS_AREA_FLAGS "--ray-samples 64"
#define TESTMODELS_GLTF "/usr/share/assimp/models/glTF2"
#define GLTF_ENGINE TESTMODELS_GLTF "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"
/* glTF 1.0, which assimp reads too (assets/scenes/truck.json includes it). */
#define GLTF_TRUCK "/usr/share/assimp/models/glTF/CesiumMilkTruck/CesiumMilkTruck.gltf"
#define GLTF_TRUCK_SCENE "assets/scenes/truck.json" /* the truck on a ground */
#define GLTF_TOLERANCE 1e-4f
/* The goal of hard shadows on real models (volumes and hybrid are exact
 * but for the pixels where the rasterizer and the reference round apart). */
#define GLTF_MAX_MISCLASSIFIED_PERCENT 0.01
/* Textured pictures against the reference's, which applies the same texel
 * rule (texture.h): the pixels off by more than GLTF_COLOR_TOLERANCE
 * (of 255) in a channel, at most this share (the rasterizer's level of
 * detail is its own approximation of the rule's, per 2x2 pixels), and the
 * mean difference of a channel. */
#define GLTF_COLOR_TOLERANCE 8
#define GLTF_MAX_COLOR_PERCENT 0.02
#define GLTF_MAX_MEAN_COLOR_DIFFERENCE 0.5
/* The shadow maps on alpha-cut casters, against the reference, which
 * honours the cut-outs: the edges of the boards' shadows cost them what
 * any shadow's edge does at their resolution (auto's texels for a light
 * that reaches cut-outs, a quarter of a pixel: the real-scenes goal); and
 * what volumes, which cast a cut-out object's whole shadow, miss by at
 * least. */
#define GLTF_CUT_OUT_MAP_MAX_PERCENT 0.1
/* The real-scenes goal for the maps on the generated fence and tree, at
 * the goal's frame: auto's texels for a light that reaches cut-out
 * casters (MAP_AUTO_CUT_OUT_FINER times finer) bring every map within it;
 * at auto's usual texel of about a pixel, none is. */
#define GLTF_FENCE_MAP_GOAL_PERCENT 0.1
/* Planar and projective on the cut-outs over a plane: what they miss
 * there is the leaves' shadows on one another (a leaf is no plane, and
 * casts onto nothing in projective's texture it is drawn into), and the
 * projective texture's texels at the edges; a caster's whole shadow
 * misses by many times more. */
#define GLTF_CUT_OUT_PLANE_MAX_PERCENT 0.3
#define GLTF_FENCE_GOAL_SIZE "--size 1280x720"
/* The shadow maps on the single-sided wall's shadow: the edges of its
 * shadow, at their resolution. */
#define GLTF_SIDED_MAP_MAX_PERCENT 0.3
/* The hybrid's goal there: its rays cut them out as the reference does. */
#define GLTF_CUT_OUT_HYBRID_MAX_PERCENT 0.01
#define GLTF_CUT_OUT_WHOLE_MIN_PERCENT 1.0
/* Translucent casters' shadows: a transmittance is read to within a
 * float's rounding of the product; the shadow maps' transmittance maps
 * colour the shadows to within the goal's MAE in each channel over the
 * stained-glass scene's compared pixels, hybrid's rays through the panes
 * to within a twentieth of it (the maps' texel edges miss by more), and
 * a shadow drawn whole (the volumes') misses the coloured one by at least
 * the other. Under an area light, hybrid keeps its penumbra goal
 * (test_hybrid's) with glass too. */
#define GLTF_TRANSMITTANCE_TOLERANCE 1e-5f
#define GLTF_COLOURED_SHADOW_MAX_CHANNEL_MAE 0.02
#define GLTF_TRACED_SHADOW_MAX_CHANNEL_MAE 0.001
#define GLTF_WHOLE_SHADOW_MIN_CHANNEL_MAE 0.05
#define GLTF_GLASS_AREA_HYBRID_MAX_PENUMBRA_MAE 0.01
/* Each shade of the stained-glass ground covers at least this many of its
 * 640x360 pixels. */
#define GLTF_MIN_SHADE_PIXELS 1000

static void assert_vec3_near(const float *got, float x, float y, float z, const char *what) {
    if (fabsf(got[0] - x) > GLTF_TOLERANCE || fabsf(got[1] - y) > GLTF_TOLERANCE ||
        fabsf(got[2] - z) > GLTF_TOLERANCE)
        fail_msg("%s: (%g, %g, %g), expected (%g, %g, %g)", what, got[0], got[1], got[2], x, y, z);
}

static void assert_direction_near(const float *got, float x, float y, float z, const char *what) {
    vec3 expected = {x, y, z};
    glm_vec3_normalize(expected);
    assert_vec3_near(got, expected[0], expected[1], expected[2], what);
}

/* The scene of file `path`, loaded; fails unless its stderr is exactly
 * `expected`, in which each %s is the path. A file of assimp-testmodels
 * skips the test where the package is missing. */
static void gltf_load_saying(const char *path, const char *expected, scene *s) {
    if (access(path, R_OK) != 0) {
        print_message("%s missing (Debian package assimp-testmodels): skipped\n", path);
        skip();
    }
    support_capture_stderr();
    bool loaded = scene_load(s, path);
    const char *said = support_release_stderr();
    assert_true(loaded);
    char text[1024];
    snprintf(text, sizeof text, expected, path, path);
    assert_string_equal(said, text);
}

/* The file's nodes: each mesh an object of its material's colour, placed
 * by its node (the mirrored one's mesh mirrored, its matrix's determinant
 * positive); the camera where its node stands, looking down its -Z with
 * the file's yfov; the spot and the sun from their nodes, cones in
 * degrees, colours times intensity over the brightest channel, the spot's
 * range (which assimp drops: read from the file's own JSON). */
static void gltf_scene_read(const char *path) {
    scene s;
    gltf_load_saying(path, "", &s);
    assert_int_equal(s.object_count, 3);
    static const char *const names[] = {"ground", "box", "mirrored_box"};
    static const float colours[][3] = {{0.7f, 0.7f, 0.7f}, {0.8f, 0.2f, 0.2f}, {0.2f, 0.3f, 0.8f}};
    for (int i = 0; i < 3; i++) {
        assert_string_equal(s.objects[i].name, names[i]);
        assert_vec3_near(s.objects[i].color, colours[i][0], colours[i][1], colours[i][2], names[i]);
        assert_true(glm_mat4_det(s.objects[i].model) > 0);
    }
    float lo[3], hi[3];
    scene_object_world_bounds(&s.objects[2], lo, hi);
    assert_vec3_near(lo, 1.5f, 0, 0.5f, "mirrored box's low corner");
    assert_vec3_near(hi, 2.5f, 1, 1.5f, "mirrored box's high corner");
    vec3 view;
    glm_vec3_sub(s.camera.target, s.camera.position, view);
    glm_vec3_normalize(view);
    assert_vec3_near(s.camera.position, 0, 4, 8, "camera position");
    assert_direction_near(view, 0, -4, -8, "camera view");
    assert_float_equal(s.camera.fov_deg, glm_deg(0.8f), GLTF_TOLERANCE);
    assert_float_equal(s.camera.near_plane, 0.1f, GLTF_TOLERANCE);
    assert_float_equal(s.camera.far_plane, 100, GLTF_TOLERANCE);
    assert_int_equal(s.light_count, 2);
    const scene_light *spot = &s.lights[0], *sun = &s.lights[1];
    assert_int_equal(spot->type, SCENE_LIGHT_SPOT);
    assert_vec3_near(spot->position, 3, 6, 2, "spot position");
    assert_direction_near(spot->direction, -3, -6, -2, "spot direction");
    assert_float_equal(spot->inner_angle_deg, glm_deg(0.3f), GLTF_TOLERANCE);
    assert_float_equal(spot->outer_angle_deg, glm_deg(0.5f), GLTF_TOLERANCE);
    assert_vec3_near(spot->color, 1, 0.9f, 0.8f, "spot colour");
    assert_int_equal(sun->type, SCENE_LIGHT_DIRECTIONAL);
    assert_direction_near(sun->direction, 0.3f, -1, -0.2f, "sun direction");
    assert_vec3_near(sun->color, 0.1f, 0.1f, 0.1f, "sun colour");
    assert_float_equal(spot->range, 15, 0);
    assert_float_equal(sun->range, 0, 0);
    scene_free(&s);
}

/* The file, as text and as binary glTF. */
static void test_gltf_scene_read(void **state) {
    (void)state;
    gltf_scene_read(GLTF_SCENE);
    gltf_scene_read(GLTF_SCENE_BINARY);
}

/* Base-colour textures: one per image and sampler (the arrow twice, with
 * two wrap modes), their levels, the image's top row last (v up), the
 * meshes' texture coordinates (assimp's v = 1 - glTF's); an image file
 * that is missing. */
static void test_gltf_textures_read(void **state) {
    (void)state;
    scene s;
    gltf_load_saying(GLTF_TEXTURED, "", &s);
    assert_int_equal(s.texture_count, 3);
    static const struct {
        const char *name;
        texture_wrap wrap;
        int size;
    } objects[] = {{"ground", TEXTURE_REPEAT, 64},
                   {"mirrored_box", TEXTURE_MIRRORED_REPEAT, 32},
                   {"clamped_box", TEXTURE_CLAMP_TO_EDGE, 32}};
    assert_int_equal(s.object_count, 3);
    for (int i = 0; i < 3; i++) {
        const texture *t = s.objects[i].base_color;
        assert_string_equal(s.objects[i].name, objects[i].name);
        assert_non_null(t);
        assert_int_equal(t->wrap[0], objects[i].wrap);
        assert_int_equal(t->wrap[1], objects[i].wrap);
        assert_int_equal(t->levels[0].width, objects[i].size);
        assert_int_equal(t->level_count, 1 + (int)log2(objects[i].size));
    }
    assert_ptr_not_equal(s.objects[1].base_color, s.objects[2].base_color);
    /* The checker's marker, in the image's top left corner. */
    const texture_level *checker = &s.objects[0].base_color->levels[0];
    const unsigned char *top_left = checker->rgba + 4 * (size_t)(checker->height - 1) * (size_t)checker->width;
    assert_int_equal(top_left[0], 40);
    assert_int_equal(top_left[2], 200);
    bool far_corner = false;
    for (uint32_t v = 0; v < s.objects[0].mesh.vertex_count; v++) {
        const float *uv = s.objects[0].mesh.vertices[v].uv;
        far_corner |= fabsf(uv[0] - 20) < GLTF_TOLERANCE && fabsf(uv[1] - (1 - 20)) < GLTF_TOLERANCE;
    }
    assert_true(far_corner);
    scene_free(&s);
    /* An image that is not there: one line naming the file and the image,
     * and no scene. */
    support_capture_stderr();
    bool loaded = scene_load(&s, "tests/data/gltf_missing_image.gltf");
    assert_string_equal(support_release_stderr(), "tests/data/gltf_missing_image.gltf: image "
                                                  "tests/data/missing_checker.png: not an image: can't fopen\n");
    assert_false(loaded);
    assert_int_equal(s.object_count, 0);
}

/* PROGRAM's picture against the reference's: the colours within
 * GLTF_COLOR_TOLERANCE (the cut-outs and textures drawn by the
 * reference's rule). */
static void gltf_expect_colors(const char *program, const dump_frame *reference, const dump_frame *test) {
    long pixels = (long)reference->width * reference->height;
    double off = 100.0 *
                 (double)image_compare(reference->color, test->color, reference->width, reference->height,
                                       GLTF_COLOR_TOLERANCE, NULL) /
                 (double)pixels;
    double sum = 0;
    for (long p = 0; p < pixels; p++)
        for (int c = 0; c < 3; c++)
            sum += abs(reference->color[4 * p + c] - test->color[4 * p + c]);
    double mean = sum / (3.0 * (double)pixels);
    print_message("    %s: colours off by more than %d/255: %.4f %% of the pixels; mean difference %.3f/255\n",
                  program, GLTF_COLOR_TOLERANCE, off, mean);
    assert_true(off <= GLTF_MAX_COLOR_PERCENT);
    assert_true(mean <= GLTF_MAX_MEAN_COLOR_DIFFERENCE);
}

/* PROGRAM's picture and decisions of `scene_path` against the
 * reference's: at most max_percent misclassified, and the colours
 * (gltf_expect_colors). */
static void gltf_expect_reference(const char *program, const char *scene_path, const char *name, double max_percent) {
    dump_frame reference, test;
    unsigned char *heatmap;
    shadowdiff_result r = support_measure_dumps(program, scene_path, "", "", name, &reference, &test, &heatmap);
    assert_true(r.compared > 0 && r.misclassified_percent <= max_percent);
    gltf_expect_colors(program, &reference, &test);
    dump_frame_free(&reference);
    dump_frame_free(&test);
    free(heatmap);
}

/* The textured file at street level (a checkered ground to the horizon,
 * the mirrored and clamped arrows): the pictures' colours are the
 * reference's, and the shadows too; the sweep takes every
 * support_sweep_stride()th technique. */
static void test_gltf_textures_match_reference(void **state) {
    (void)state;
    static const char *const programs[] = {"volumes", "hybrid"};
    for (size_t i = 0; i < sizeof programs / sizeof *programs; i += (size_t)support_sweep_stride()) {
        char name[64];
        snprintf(name, sizeof name, "gltf_textured_%s", programs[i]);
        gltf_expect_reference(programs[i], GLTF_TEXTURED, name, GLTF_MAX_MISCLASSIFIED_PERCENT);
    }
}

/* PROGRAM's dumps of `scene_path` against the reference's, named
 * PREFIX_PROGRAM: at most max_percent misclassified, and every pixel sees
 * the object the reference's does. The caller frees the dumps. */
static void gltf_expect_objects(const char *program, const char *scene_path, const char *prefix, double max_percent,
                                dump_frame *reference, dump_frame *test) {
    char name[64];
    snprintf(name, sizeof name, "%s_%s", prefix, program);
    unsigned char *heatmap;
    shadowdiff_result r = support_measure_dumps(program, scene_path, "", "", name, reference, test, &heatmap);
    free(heatmap);
    assert_true(r.compared > 0 && r.misclassified_percent <= max_percent);
    long pixels = (long)reference->width * reference->height, other = 0;
    for (long p = 0; p < pixels; p++)
        other += reference->ids[p] != test->ids[p];
    assert_int_equal(other, 0);
}

/* Cut-out objects (alphaMode MASK): a fence of boards and three leaf
 * cards under a low sun. The shadow maps cut them out of their shadows as
 * the reference does, and every pixel sees the object the reference's
 * does, through the gaps too; volumes cannot cut them, say so once, and
 * cast the fence's whole shadow: far from the reference, whose shadow has
 * the gaps. The hybrid's rays cut them out too, to its goal. Planar and
 * projective say what they cannot honour. The sweep takes every
 * support_sweep_stride()th technique, the hybrid first. */
static void test_gltf_cut_outs(void **state) {
    (void)state;
    scene s;
    gltf_load_saying(GLTF_CUT_OUT, "", &s);
    assert_float_equal(s.objects[0].alpha_cutoff, 0, 0);
    assert_float_equal(s.objects[1].alpha_cutoff, 0.4f, GLTF_TOLERANCE);
    assert_float_equal(s.objects[2].alpha_cutoff, 0.5f, GLTF_TOLERANCE);
    scene_free(&s);
    static const struct {
        const char *program;
        double max_percent;
    } cases[] = {
        {"hybrid", GLTF_CUT_OUT_HYBRID_MAX_PERCENT},
        {"shadowmap", GLTF_CUT_OUT_MAP_MAX_PERCENT},
        {"cascades", GLTF_CUT_OUT_MAP_MAX_PERCENT},
        {"psm", GLTF_CUT_OUT_MAP_MAX_PERCENT},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i += (size_t)support_sweep_stride()) {
        /* What each pixel sees: the same object, through the gaps too. */
        dump_frame reference, test;
        gltf_expect_objects(cases[i].program, GLTF_CUT_OUT, "gltf_cut_out", cases[i].max_percent, &reference, &test);
        dump_frame_free(&reference);
        dump_frame_free(&test);
    }
    /* What each technique that cannot honour the scene says, once. */
    static const struct {
        const char *program, *said;
    } notes[] = {
        {"volumes", "volumes: cut-out objects (alphaMode MASK) cast the shadow of their whole surface"},
        {"planar", "planar: no object is a receiving plane"},
        {"projective", "projective: every receiver casts too"},
    };
    for (size_t i = 0; i < sizeof notes / sizeof *notes; i++) {
        char command[512], said[4096];
        snprintf(command, sizeof command,
                 "%s --size 64x36 --frames 2 --screenshot out/test/gltf_cut_out.png --scene %s",
                 support_program(notes[i].program), GLTF_CUT_OUT);
        assert_int_equal(support_run(command, said, sizeof said), 0);
        if (strncmp(said, notes[i].said, strlen(notes[i].said)) != 0 || support_count_lines(said) != 1)
            fail_msg("%s: expected one line starting \"%s\", got \"%s\"", notes[i].program, notes[i].said, said);
    }
    shadowdiff_result whole = support_measure("volumes", GLTF_CUT_OUT, "", "", "gltf_cut_out_volumes");
    assert_true(whole.misclassified_percent > GLTF_CUT_OUT_WHOLE_MIN_PERCENT);
}

/* Planar's flattened casters and projective's caster texture cut the
 * cut-outs out as the reference does (a cut-out caster's program discards
 * where it has no surface). */
static void test_gltf_cut_outs_on_a_plane(void **state) {
    (void)state;
    static const char *const programs[] = {"planar", "projective"};
    for (size_t i = 0; i < sizeof programs / sizeof *programs; i++) {
        char name[64];
        snprintf(name, sizeof name, "gltf_cut_out_on_plane_%s", programs[i]);
        shadowdiff_result r = support_measure(programs[i], GLTF_CUT_OUT_ON_PLANE, "", "", name);
        assert_true(r.compared > 0 && r.misclassified_percent <= GLTF_CUT_OUT_PLANE_MAX_PERCENT);
    }
}

/* The fence and tree of cut-out leaves at the goal's frame, every map at
 * its defaults: auto sizes them for the cut-outs. The sweep takes every
 * support_sweep_stride()th technique. */
static void test_gltf_fence_within_goal_by_auto_maps(void **state) {
    (void)state;
    static const char *const programs[] = {"shadowmap", "psm", "cascades"};
    for (size_t i = 0; i < sizeof programs / sizeof *programs; i += (size_t)support_sweep_stride()) {
        char name[64];
        snprintf(name, sizeof name, "gltf_fence_%s", programs[i]);
        shadowdiff_result r = support_measure(programs[i], GLTF_FENCE, GLTF_FENCE_GOAL_SIZE, "", name);
        assert_true(r.compared > 0 && r.misclassified_percent <= GLTF_FENCE_MAP_GOAL_PERCENT);
    }
}

/* doubleSided (glTF's material): a single-sided object is seen from its
 * front only, and casts from both sides. Every pixel sees through the
 * wall, which the camera sees from behind, to the object the reference
 * sees; the wall shadows the box all the same; the double-sided panel's
 * back is lit as the reference lights it (its normal reversed). The
 * sweep takes every support_sweep_stride()th technique, the hybrid
 * first; the maps' colours differ at their shadows' edges, so only the
 * exact techniques' colours are compared. */
static void test_gltf_sided(void **state) {
    (void)state;
    scene s;
    gltf_load_saying(GLTF_SIDED, "", &s);
    static const bool single_sided[] = {true, true, true, false}; /* ground, box, wall, panel */
    assert_int_equal(s.object_count, 4);
    for (int i = 0; i < s.object_count; i++)
        assert_int_equal(s.objects[i].single_sided, single_sided[i]);
    scene_free(&s);
    static const struct {
        const char *program;
        double max_percent;
        bool colors;
    } cases[] = {
        {"hybrid", GLTF_MAX_MISCLASSIFIED_PERCENT, true},  {"shadowmap", GLTF_SIDED_MAP_MAX_PERCENT, false},
        {"cascades", GLTF_SIDED_MAP_MAX_PERCENT, false},   {"psm", GLTF_SIDED_MAP_MAX_PERCENT, false},
        {"volumes", GLTF_MAX_MISCLASSIFIED_PERCENT, true},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i += (size_t)support_sweep_stride()) {
        dump_frame reference, test;
        gltf_expect_objects(cases[i].program, GLTF_SIDED, "gltf_sided", cases[i].max_percent, &reference, &test);
        long pixels = (long)reference.width * reference.height, wall = 0, shadowed = 0;
        for (long p = 0; p < pixels; p++) {
            wall += reference.ids[p] == GLTF_SIDED_WALL;
            shadowed += reference.ids[p] == GLTF_SIDED_BOX && reference.visibility[p] < 0.5f;
        }
        print_message("    %s: %ld pixels see the wall; %ld of the box's shadowed\n", cases[i].program, wall,
                      shadowed);
        assert_int_equal(wall, 0);
        assert_true(shadowed >= GLTF_MIN_SHADE_PIXELS);
        if (cases[i].colors)
            gltf_expect_colors(cases[i].program, &reference, &test);
        dump_frame_free(&reference);
        dump_frame_free(&test);
    }
}

/* --camera N: the file's camera N, where its node places it (the second
 * a street-level view); one the file lacks, or any but 0 of a JSON scene,
 * is one line naming the file and the cameras there are. */
static void test_gltf_camera_flag(void **state) {
    (void)state;
    scene s;
    support_capture_stderr();
    bool loaded = scene_load_camera(&s, GLTF_SCENE, 1);
    assert_string_equal(support_release_stderr(), "");
    assert_true(loaded);
    vec3 view;
    glm_vec3_sub(s.camera.target, s.camera.position, view);
    glm_vec3_normalize(view);
    assert_vec3_near(s.camera.position, -3, 0.3f, 4, "camera 1's position");
    assert_direction_near(view, 3, 0.2f, -4, "camera 1's view");
    assert_float_equal(s.camera.fov_deg, glm_deg(1.0f), GLTF_TOLERANCE);
    assert_float_equal(s.camera.near_plane, 0.05f, GLTF_TOLERANCE);
    scene_free(&s);
    static const struct {
        const char *path;
        int camera;
        const char *said;
    } cases[] = {
        {GLTF_SCENE, 2, GLTF_SCENE ": --camera 2: the file has cameras 0 to 1\n"},
        {"assets/scenes/simple.json", 1, "assets/scenes/simple.json: --camera 1: the scene has camera 0 only\n"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        support_capture_stderr();
        loaded = scene_load_camera(&s, cases[i].path, cases[i].camera);
        assert_string_equal(support_release_stderr(), cases[i].said);
        assert_false(loaded);
        assert_int_equal(s.object_count, 0);
    }
}

/* A file without a camera or a light gets both, each said in one line: a
 * camera looking at the bounds' centre with all of them in view, a sun. */
static void test_gltf_fitted(void **state) {
    (void)state;
    scene s;
    gltf_load_saying(TESTMODELS_GLTF "/BoxTextured-glTF/BoxTextured.gltf",
                     "%s: no camera: one fitted to the scene's bounds\n%s: no light: a sun from above added\n", &s);
    float lo[3], hi[3], centre[3];
    scene_object_world_bounds(&s.objects[0], lo, hi);
    glm_vec3_center(lo, hi, centre);
    assert_vec3_near(s.camera.target, centre[0], centre[1], centre[2], "fitted camera's target");
    float distance = glm_vec3_distance(s.camera.position, s.camera.target);
    float radius = 0.5f * glm_vec3_distance(lo, hi);
    assert_true(radius / distance < sinf(glm_rad(0.5f * s.camera.fov_deg)));
    assert_true(s.camera.near_plane < distance - radius && s.camera.far_plane > distance + radius);
    assert_int_equal(s.light_count, 1);
    assert_int_equal(s.lights[0].type, SCENE_LIGHT_DIRECTIONAL);
    scene_free(&s);
}

/* A real model of many meshes, some with degenerate triangles: what its
 * meshes lost is said in one line for the file, not one per mesh; it has a
 * camera, and no light. */
static void test_gltf_says_each_thing_once(void **state) {
    (void)state;
    scene s;
    gltf_load_saying(GLTF_ENGINE,
                     "warning: %s: removed 11160 degenerate and 0 non-finite triangles from its meshes\n"
                     "%s: no light: a sun from above added\n",
                     &s);
    assert_true(s.object_count > 1);
    scene_free(&s);
}

/* The ground's pixels of the reference whose channels are `rgb`. */
static long gltf_pixels_of(const dump_frame *d, const float rgb[3]) {
    long count = 0;
    for (long p = 0; p < (long)d->width * d->height; p++) {
        bool same = d->ids[p] == 0;
        for (int k = 0; k < 3 && same; k++)
            same = fabsf(d->visibility_rgb[3 * p + k] - rgb[k]) <= GLTF_TRANSMITTANCE_TOLERANCE;
        count += same;
    }
    return count;
}

/* How a technique draws a translucent caster's shadow. */
typedef enum gltf_glass_shadow { GLTF_GLASS_WHOLE, GLTF_GLASS_COLOURED, GLTF_GLASS_TRACED } gltf_glass_shadow;

/* r's channel MAE, printed under `label`: within the goal where `shadow`
 * colours shadows, within GLTF_TRACED_SHADOW_MAX_CHANNEL_MAE where rays
 * filter them, else at least a whole shadow's. */
static void gltf_expect_channels(const char *label, const shadowdiff_result *r, gltf_glass_shadow shadow) {
    fprintf(stderr, "    %s: channel MAE %.4f %.4f %.4f\n", label, r->channel_mae[0], r->channel_mae[1],
            r->channel_mae[2]);
    assert_true(r->coloured);
    for (int k = 0; k < 3; k++)
        if (shadow == GLTF_GLASS_WHOLE
                ? r->channel_mae[k] < GLTF_WHOLE_SHADOW_MIN_CHANNEL_MAE
                : r->channel_mae[k] > (shadow == GLTF_GLASS_TRACED ? GLTF_TRACED_SHADOW_MAX_CHANNEL_MAE
                                                                   : GLTF_COLOURED_SHADOW_MAX_CHANNEL_MAE))
            fail_msg("%s: channel %d's MAE %.4f", label, k, r->channel_mae[k]);
}

/* Stained glass's channel MAE of `program` (gltf_expect_channels); the
 * reference's dump left in *reference where it is not NULL. */
static void gltf_glass_channels(const char *program, gltf_glass_shadow shadow, dump_frame *reference) {
    dump_frame kept, test;
    unsigned char *heatmap;
    shadowdiff_result r =
        support_measure_dumps(program, GLTF_STAINED_GLASS, "", "", "gltf_glass", &kept, &test, &heatmap);
    free(heatmap);
    if (reference)
        *reference = kept;
    else
        dump_frame_free(&kept);
    dump_frame_free(&test);
    static const char *const names[] = {"whole", "coloured", "traced"};
    char label[128];
    snprintf(label, sizeof label, "%s, %s shadows", program, names[shadow]);
    gltf_expect_channels(label, &r, shadow);
}

/* Translucent casters (alphaMode BLEND, assets/scenes/stained_glass.gltf:
 * a red pane over a blue one, a window of four colours, an opaque box):
 * the reference's shadow rays filter the spot's light through each pane
 * they cross (scene_object_transmittance), so the ground under the red
 * pane alone, the blue alone and both holds their transmittances and
 * their product, the box's shadow none; the one figure is the channels'
 * mean where they differ. The shadow maps colour theirs through their
 * transmittance maps (their dumps coloured too, their state lines naming
 * the maps), and hybrid's rays filter their light through the panes
 * where a pane lies within a texel; volumes cast whole shadows, say so
 * once, and shadowdiff measures what that costs per channel. A scene
 * without translucent casters has no coloured dump. */
static void test_gltf_translucent_shadows(void **state) {
    (void)state;
    scene s;
    gltf_load_saying(GLTF_STAINED_GLASS, "", &s);
    static const bool translucent[] = {false, true, true, true, false}; /* ground, red, blue, window, box */
    assert_int_equal(s.object_count, sizeof translucent / sizeof *translucent);
    for (int i = 0; i < s.object_count; i++)
        assert_int_equal(s.objects[i].translucent, translucent[i]);
    float red[3], blue[3], both[3];
    const float corner[3] = {1, 0, 0};
    scene_object_transmittance(&s.objects[1], 0, corner, red);
    scene_object_transmittance(&s.objects[2], 0, corner, blue);
    /* (1 - a) + a C of each material's factors: a 0.7 of (0.95, 0.15, 0.1), a 0.6 of (0.2, 0.35, 0.95). */
    assert_vec3_near(red, 0.965f, 0.405f, 0.37f, "red glass");
    assert_vec3_near(blue, 0.52f, 0.61f, 0.97f, "blue glass");
    glm_vec3_mul(red, blue, both);
    scene_free(&s);

    /* shadowmap's channels (its reference dump kept) and hybrid's in
     * every tier; the whole tier adds psm and cascades (on this scene both
     * fall back to shadowmap's spot map) and volumes. */
    static const struct {
        const char *program;
        gltf_glass_shadow shadow;
    } glass[] = {{"shadowmap", GLTF_GLASS_COLOURED},
                 {"hybrid", GLTF_GLASS_TRACED},
                 {"psm", GLTF_GLASS_COLOURED},
                 {"cascades", GLTF_GLASS_COLOURED},
                 {"volumes", GLTF_GLASS_WHOLE}};
    enum { GLTF_GLASS_EVERY_TIER = 2 };
    dump_frame reference;
    gltf_glass_channels(glass[0].program, glass[0].shadow, &reference);
    const float *shades[] = {red, blue, both, (const float[3]){0, 0, 0}};
    for (size_t k = 0; k < sizeof shades / sizeof *shades; k++) {
        long pixels = gltf_pixels_of(&reference, shades[k]);
        fprintf(stderr, "    ground under (%g, %g, %g): %ld pixels\n", shades[k][0], shades[k][1], shades[k][2],
                pixels);
        assert_true(pixels > GLTF_MIN_SHADE_PIXELS);
    }
    for (long p = 0; p < (long)reference.width * reference.height; p++) {
        const float *c = reference.visibility_rgb + 3 * p;
        if (c[0] != c[1] || c[1] != c[2])
            assert_float_equal(reference.visibility[p], (c[0] + c[1] + c[2]) / 3.0f, 0);
    }
    dump_frame_free(&reference);
    for (size_t i = 1; i < sizeof glass / sizeof *glass; i++)
        if (i < GLTF_GLASS_EVERY_TIER || support_sweep_stride() == 1)
            gltf_glass_channels(glass[i].program, glass[i].shadow, NULL);

    static const struct {
        const char *program;
        bool coloured;
    } programs[] = {{"shadowmap", true}, {"cascades", true}, {"psm", true}, {"volumes", false}, {"hybrid", true}};
    for (size_t i = 0; i < sizeof programs / sizeof *programs; i += (size_t)support_sweep_stride()) {
        char command[512], said[4096], expected[256] = "";
        const char *name = programs[i].program;
        snprintf(command, sizeof command,
                 "%s --size 64x36 --frames 2 --screenshot out/test/gltf_glass.png --scene %s", support_program(name),
                 GLTF_STAINED_GLASS);
        if (!programs[i].coloured)
            snprintf(expected, sizeof expected,
                     "%s: 3 translucent objects (alphaMode BLEND) cast the shadow of their whole surface: %s draws "
                     "no coloured shadows\n",
                     name, name);
        assert_int_equal(support_run(command, said, sizeof said), 0);
        if (strcmp(said, expected) != 0)
            fail_msg("%s: expected \"%s\", got \"%s\"", name, expected, said);
    }
    /* The state line (the HUD's, --verbose) names the transmittance map
     * where the scene has translucent casters, and only there. */
    static const struct {
        const char *scene;
        bool transmits;
    } lines[] = {{GLTF_STAINED_GLASS, true}, {GLTF_SCENE, false}};
    for (size_t i = 0; i < sizeof lines / sizeof *lines; i++) {
        char command[512], said[8192];
        snprintf(command, sizeof command,
                 "%s --size 64x36 --frames 1 --verbose --screenshot out/test/gltf_glass.png --scene %s",
                 support_program("shadowmap"), lines[i].scene);
        assert_int_equal(support_run(command, said, sizeof said), 0);
        if ((strstr(said, ", transmittance map: coloured shadows") != NULL) != lines[i].transmits)
            fail_msg("%s: the state line %s the transmittance map: \"%s\"", lines[i].scene,
                     lines[i].transmits ? "lacks" : "names", said);
    }
    /* The same directory, dumped again from a scene without them. */
    assert_int_equal(support_dump("shadowmap", GLTF_STAINED_GLASS, "", "out/test/gltf_rgb"), 0);
    assert_int_equal(access("out/test/gltf_rgb/visibility_rgb.pfm", R_OK), 0);
    assert_int_equal(support_dump("shadowmap", GLTF_SCENE, "", "out/test/gltf_rgb"), 0);
    assert_int_not_equal(access("out/test/gltf_rgb/visibility_rgb.pfm", F_OK), 0);
}

/* A lamp resting on a pane (GLTF_LAMP_ON_GLASS: nearer the red pane than
 * its cube's near plane, a thousandth of its far one): the pane is drawn
 * into the transmittance map at the near depth, as depth clamp draws it,
 * so that the ground under it is red as the reference's; with depth clamp,
 * and with --webgl2, where the GL has none and the pass clamps the depth
 * itself (a clipped pane colours nothing: the channels miss by a
 * whole shadow's). Hybrid's sure pixels take the same map's colour. */
static void test_gltf_pane_nearer_than_the_near_plane(void **state) {
    (void)state;
    static const struct {
        const char *program, *flags, *name;
    } runs[] = {{"shadowmap", "", "gltf_lamp_on_glass"},
                {"shadowmap", "--webgl2", "gltf_lamp_on_glass_webgl2"},
                {"hybrid", "--webgl2", "gltf_lamp_on_glass_webgl2"}};
    for (size_t i = 0; i < sizeof runs / sizeof *runs; i++) {
        shadowdiff_result r = support_measure(runs[i].program, GLTF_LAMP_ON_GLASS, GLTF_LAMP_ON_GLASS_SIZE,
                                              runs[i].flags, runs[i].name);
        char label[128];
        snprintf(label, sizeof label, "%s %s", runs[i].program, runs[i].flags);
        gltf_expect_channels(label, &r, GLTF_GLASS_COLOURED);
    }
}

/* The stained glass under an area light (GLTF_GLASS_AREA): hybrid's rays
 * average each channel over the reference's points of the light, so its
 * coloured penumbrae keep its goal, where the transmittance map's hard
 * texel edge misses it (shadowmap's PCSS filters the opaque shadow
 * alone). */
static void test_gltf_glass_under_an_area_light(void **state) {
    (void)state;
    /* In the plain pass alone: what it checks is the shaders' arithmetic;
     * the sanitizers watch the same records' packing in the stained
     * glass's hybrid dump. */
    if (getenv("TEST_SANITIZER")) {
        print_message("glass under an area light: the plain pass checks it\n");
        skip();
    }
    dump_frame reference, test;
    unsigned char *heatmap;
    shadowdiff_result r =
        support_measure_dumps("hybrid", GLTF_GLASS_AREA, GLTF_GLASS_AREA_SIZE, GLTF_GLASS_AREA_FLAGS,
                              "gltf_glass_area", &reference, &test, &heatmap);
    free(heatmap);
    dump_frame_free(&reference);
    dump_frame_free(&test);
    fprintf(stderr, "    hybrid, glass under an area light: penumbra MAE %.4f over %ld pixels\n",
            r.class_mae[SHADOWDIFF_CLASS_PENUMBRA], r.class_pixels[SHADOWDIFF_CLASS_PENUMBRA]);
    assert_true(r.coloured && r.class_pixels[SHADOWDIFF_CLASS_PENUMBRA] > 0);
    assert_true(r.class_mae[SHADOWDIFF_CLASS_PENUMBRA] <= GLTF_GLASS_AREA_HYBRID_MAX_PENUMBRA_MAE);
}

/* A scene file's object of mesh kind "gltf" (tests/data/gltf_included.json):
 * each node's mesh an object named after the scene file's object, placed
 * by its transform times the node's, casting as it says; textures and
 * cut-outs as a glTF scene's, after the textures of the files before; a
 * bad include one line. */
static void test_gltf_included_by_a_scene_file(void **state) {
    (void)state;
    scene included, alone;
    assert_true(scene_load(&included, GLTF_INCLUDED));
    assert_true(scene_load(&alone, GLTF_SCENE));
    mat4 placed, expected;
    glm_translate_make(placed, (vec3){6, 0, -2});
    glm_rotate_y(placed, glm_rad(90), placed);
    glm_scale_uni(placed, 0.5f);
    for (int i = 0; i < alone.object_count; i++) {
        char name[SCENE_NAME_MAX + sizeof "boxes/"];
        snprintf(name, sizeof name, "boxes/%s", alone.objects[i].name);
        const scene_object *o = NULL;
        for (int k = 0; k < included.object_count; k++)
            if (strcmp(included.objects[k].name, name) == 0)
                o = &included.objects[k];
        if (!o)
            fail_msg("%s: no object %s", GLTF_INCLUDED, name);
        assert_false(o->casts);
        assert_true(o->receives);
        assert_int_equal(o->mesh.index_count, alone.objects[i].mesh.index_count);
        glm_mat4_mul(placed, (vec4 *)alone.objects[i].model, expected);
        for (int column = 0; column < 4; column++)
            assert_vec3_near(o->model[column], expected[column][0], expected[column][1], expected[column][2], name);
    }
    int textured = 0, cut_out = 0;
    for (int k = 0; k < included.object_count; k++) {
        const scene_object *o = &included.objects[k];
        if (o->base_color) {
            assert_true(o->base_color >= included.textures &&
                        o->base_color < included.textures + included.texture_count);
            assert_true(o->base_color->level_count > 0);
            textured++;
        }
        cut_out += o->alpha_cutoff > 0;
    }
    /* The fence's two cut-out objects; the checker's three textured. */
    assert_int_equal(cut_out, 2);
    assert_true(textured >= 5);
    scene_free(&included);
    scene_free(&alone);

    static const struct {
        const char *object, *problem;
    } bad[] = {
        {"{\"name\": \"g\", \"mesh\": {\"kind\": \"gltf\", \"path\": \"gltf_scene.gltf\"}, \"color\": [1, 0, 0]}",
         ": objects[0].color: a glTF file's objects take their materials' colours\n"},
        {"{\"name\": \"g\", \"mesh\": {\"kind\": \"gltf\", \"path\": \"no_such.gltf\"}}",
         ": objects[0].mesh.path: out/test/gltf/no_such.gltf: No such file or directory\n"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char text[1024];
        snprintf(text, sizeof text,
                 "{\"camera\": {\"position\": [0, 2, 5], \"target\": [0, 0, 0]}, \"lights\": [{\"type\": "
                 "\"directional\", \"direction\": [0, -1, 0]}], \"objects\": [%s]}",
                 bad[i].object);
        cJSON *root = cJSON_Parse(text);
        assert_non_null(root);
        char path[256];
        support_write_json(root, "out/test/gltf", "included_bad", path, sizeof path);
        cJSON_Delete(root);
        scene s;
        support_capture_stderr();
        bool loaded = scene_load(&s, path);
        const char *said = support_release_stderr();
        assert_false(loaded);
        const char *newline = strchr(said, '\n');
        if (!newline || newline[1] != '\0' || !strstr(said, bad[i].problem))
            fail_msg("expected one line with \"%s\", got \"%s\"", bad[i].problem, said);
        fprintf(stderr, "    %s", said);
    }
}

/* Debian's broken glTF files: each one line naming the file and the
 * problem, and no scene. */
static void test_gltf_bad_files(void **state) {
    (void)state;
    static const struct {
        const char *path, *problem;
    } cases[] = {
        {"/MissingBin/BoxTextured.gltf", ": GLTF: could not open referenced file \"BoxTextured0.bin\""},
        {"/IndexOutOfRange/AllIndicesOutOfRange.gltf", ": Mesh \"Mesh\" has no faces"},
        {"/RecursiveNodes/RecursiveNodes.gltf", ": GLTF: Object at index 0 in array \"nodes\" has recursive"},
        {"/TestNoRootNode/NoScene.gltf", ": GLTF: No scene"},
        {"/TestNoRootNode/SceneWithoutNodes.gltf", ": no triangles in any node's mesh"},
        {"/wrongTypes/badArray.gltf", ": Member \"primitives\" was not of type \"array\""},
        {"/SchemaFailures/sceneWrongType.gltf", ": Member \"scene\" was not of type \"uint\""},
        {"/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", ": node \"nodes_1\": no triangles left"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char path[512], expected[1024];
        snprintf(path, sizeof path, TESTMODELS_GLTF "%s", cases[i].path);
        if (access(path, R_OK) != 0) {
            print_message("%s missing (Debian package assimp-testmodels): skipped\n", path);
            continue;
        }
        scene s;
        support_capture_stderr();
        bool loaded = scene_load(&s, path);
        const char *said = support_release_stderr();
        assert_false(loaded);
        assert_int_equal(s.object_count, 0);
        snprintf(expected, sizeof expected, "%s%s", path, cases[i].problem);
        const char *newline = strchr(said, '\n');
        if (!newline || newline[1] != '\0' || strncmp(said, expected, strlen(expected)) != 0)
            fail_msg("%s: expected one line starting \"%s\", got \"%s\"", path, expected, said);
        fprintf(stderr, "    %s", said);
    }
}

/* The shadows: volumes and hybrid against the reference on a real model
 * nobody tuned for (its fitted sun), on the file's scene (its spot), on
 * the generated fence and tree of cut-out leaves (the hybrid's rays cut
 * them out) and on a textured real model a scene file includes over a
 * ground (its window frames' shadows lie within the map's constant bias
 * of the body: the hybrid's sure-lit read sends them to the rays);
 * the sweep takes every support_sweep_stride()th case, the truck's
 * hybrid first. */
static void test_gltf_shadows_match_reference(void **state) {
    (void)state;
    static const struct {
        const char *scene, *program;
        const char *model; /* the file the scene needs */
    } cases[] = {
        {GLTF_TRUCK_SCENE, "hybrid", GLTF_TRUCK}, {GLTF_SCENE, "volumes", GLTF_SCENE},
        {GLTF_ENGINE, "volumes", GLTF_ENGINE},    {GLTF_SCENE, "hybrid", GLTF_SCENE},
        {GLTF_FENCE, "hybrid", GLTF_FENCE},       {GLTF_TRUCK_SCENE, "volumes", GLTF_TRUCK},
        {GLTF_ENGINE, "hybrid", GLTF_ENGINE},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i += (size_t)support_sweep_stride()) {
        if (access(cases[i].model, R_OK) != 0) {
            print_message("%s missing (Debian package assimp-testmodels): skipped\n", cases[i].model);
            continue;
        }
        char name[64];
        snprintf(name, sizeof name, "gltf_%zu", i);
        shadowdiff_result r = support_measure(cases[i].program, cases[i].scene, "", "", name);
        assert_true(r.compared > 0 && r.misclassified_percent <= GLTF_MAX_MISCLASSIFIED_PERCENT);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gltf_scene_read),
        cmocka_unit_test(test_gltf_camera_flag),
        cmocka_unit_test(test_gltf_textures_read),
        cmocka_unit_test(test_gltf_textures_match_reference),
        cmocka_unit_test(test_gltf_cut_outs),
        cmocka_unit_test(test_gltf_cut_outs_on_a_plane),
        cmocka_unit_test(test_gltf_fence_within_goal_by_auto_maps),
        cmocka_unit_test(test_gltf_sided),
        cmocka_unit_test(test_gltf_fitted),
        cmocka_unit_test(test_gltf_says_each_thing_once),
        cmocka_unit_test(test_gltf_translucent_shadows),
        cmocka_unit_test(test_gltf_pane_nearer_than_the_near_plane),
        cmocka_unit_test(test_gltf_glass_under_an_area_light),
        cmocka_unit_test(test_gltf_included_by_a_scene_file),
        cmocka_unit_test(test_gltf_bad_files),
        cmocka_unit_test(test_gltf_shadows_match_reference),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
