/* Tests of common/data/scene.c: scene files, good and bad. Run from the
 * repository root (the paths are relative to it). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "support.h"

#include "scene.h"

#define PI 3.14159265358979323846

static void assert_vec3(const float actual[3], double x, double y, double z) {
    assert_float_equal(actual[0], x, 1e-5);
    assert_float_equal(actual[1], y, 1e-5);
    assert_float_equal(actual[2], z, 1e-5);
}

static void assert_identity(const float m[4][4]) {
    for (int column = 0; column < 4; column++) {
        for (int row = 0; row < 4; row++)
            assert_float_equal(m[column][row], column == row, 0);
    }
}

/* p' = M p for a column-major matrix and a point (w = 1). */
static void transform_point(const float m[4][4], const double p[3], double out[3]) {
    for (int row = 0; row < 3; row++) {
        out[row] = m[3][row];
        for (int column = 0; column < 3; column++)
            out[row] += m[column][row] * p[column];
    }
}

/* Turns p about one axis (0: X, 1: Y, 2: Z), right-handed. */
static void rotate_about(int axis, double degrees, double p[3]) {
    int u = (axis + 1) % 3, v = (axis + 2) % 3;
    double c = cos(degrees * PI / 180), s = sin(degrees * PI / 180);
    double pu = p[u], pv = p[v];
    p[u] = c * pu - s * pv;
    p[v] = s * pu + c * pv;
}

static const scene_object *find_object(const scene *s, const char *name) {
    for (int i = 0; i < s->object_count; i++) {
        if (strcmp(s->objects[i].name, name) == 0)
            return &s->objects[i];
    }
    fail_msg("no object \"%s\"", name);
    return NULL;
}

static void assert_empty_scene(const scene *s) {
    assert_null(s->objects);
    assert_int_equal(s->object_count, 0);
    assert_int_equal(s->light_count, 0);
}

static void load_quietly(scene *s, const char *path) {
    support_capture_stderr();
    bool loaded = scene_load(s, path);
    const char *text = support_release_stderr();
    if (!loaded)
        fail_msg("%s did not load: %s", path, text);
    assert_string_equal(text, "");
}

static void test_good_scene_camera_and_lights(void **state) {
    (void)state;
    scene s;
    load_quietly(&s, "tests/data/scene_good.json");
    assert_vec3(s.camera.position, 0, 4, 10);
    assert_vec3(s.camera.target, 0, 1, 0);
    assert_vec3(s.camera.up, 0, 0, -1);
    assert_float_equal(s.camera.fov_deg, 50, 0);
    assert_float_equal(s.camera.near_plane, 0.5, 0);
    assert_float_equal(s.camera.far_plane, 60, 0);
    assert_vec3(s.ambient, 0.2, 0.25, 0.3);

    assert_int_equal(s.light_count, 3);
    const scene_light *point = &s.lights[0], *spot = &s.lights[1], *sun = &s.lights[2];
    assert_int_equal(point->type, SCENE_LIGHT_POINT);
    assert_vec3(point->position, 2, 6, 1);
    assert_vec3(point->color, 1, 0.9, 0.8);
    assert_float_equal(point->intensity, 2.5, 0);
    assert_float_equal(point->radius, 0.25, 0);

    assert_int_equal(spot->type, SCENE_LIGHT_SPOT);
    assert_vec3(spot->position, -3, 5, 3);
    assert_vec3(spot->direction, 0, -1, 0); /* [0, -2, 0], normalized */
    assert_float_equal(spot->inner_angle_deg, 15, 0);
    assert_float_equal(spot->outer_angle_deg, 25, 0);
    assert_vec3(spot->color, 0.5, 0.5, 1);
    assert_float_equal(spot->intensity, 4, 0);
    assert_float_equal(spot->radius, 0, 0);

    assert_int_equal(sun->type, SCENE_LIGHT_DIRECTIONAL);
    double third = 1 / sqrt(3);
    assert_vec3(sun->direction, third, -third, third);
    assert_vec3(sun->color, 1, 1, 1);
    assert_float_equal(sun->intensity, 1, 0);
    scene_free(&s);
    assert_empty_scene(&s);
}

static void test_good_scene_objects(void **state) {
    (void)state;
    scene s;
    load_quietly(&s, "tests/data/scene_good.json");
    assert_int_equal(s.object_count, 6);
    const char *names[] = {"ground", "crate", "ball", "ring", "pillar", "tetra"};
    const scene_mesh_kind kinds[] = {SCENE_MESH_PLANE, SCENE_MESH_BOX,      SCENE_MESH_SPHERE,
                                     SCENE_MESH_TORUS, SCENE_MESH_CYLINDER, SCENE_MESH_MODEL};
    for (int i = 0; i < s.object_count; i++) {
        assert_string_equal(s.objects[i].name, names[i]);
        assert_int_equal(s.objects[i].mesh_kind, kinds[i]);
        assert_true(s.objects[i].mesh.index_count > 0);
        /* cglm's SIMD matrix code needs this in place. */
        assert_int_equal((uintptr_t)s.objects[i].model % 16, 0);
    }

    const scene_object *ground = find_object(&s, "ground");
    assert_false(ground->casts);
    assert_true(ground->receives);
    assert_vec3(ground->color, 0.5, 0.5, 0.5);
    assert_vec3(ground->mesh.bounds_min, -10, 0, -5);
    assert_vec3(ground->mesh.bounds_max, 10, 0, 5);

    /* Defaults. */
    const scene_object *pillar = find_object(&s, "pillar");
    assert_true(pillar->casts);
    assert_true(pillar->receives);
    assert_vec3(pillar->color, 0.8, 0.8, 0.8);
    assert_identity(pillar->model);
    assert_int_equal(pillar->mesh.vertex_count, 4 * 32 + 2);
    assert_vec3(pillar->mesh.bounds_max, 0.5, 1.5, 0.5);

    const scene_object *ball = find_object(&s, "ball");
    assert_int_equal(ball->mesh.vertex_count, 2 + 5 * 12); /* 12 segments: 12 slices, 5 rings */
    assert_vec3(ball->mesh.bounds_max, 0.75, 0.75, 0.75);
    assert_float_equal(ball->model[0][0], 2, 0); /* "scale": 2 is uniform */
    assert_float_equal(ball->model[1][1], 2, 0);
    assert_float_equal(ball->model[2][2], 2, 0);

    const scene_object *tetra = find_object(&s, "tetra");
    assert_int_equal(tetra->mesh.vertex_count, 4);
    assert_false(tetra->receives);
    assert_vec3(tetra->color, 0.9, 0.1, 0.1);
    scene_free(&s);
}

static void test_model_matrix_order(void **state) {
    (void)state;
    scene s;
    load_quietly(&s, "tests/data/scene_good.json");
    /* "ring": scale [2, 3, 4], rotate [30, 45, 60], translate [1, 2, 3]:
     * scaled, then turned about X, then Y, then Z, then moved. */
    const scene_object *ring = find_object(&s, "ring");
    const double points[][3] = {{0.5, -1, 2}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}};
    for (size_t i = 0; i < sizeof points / sizeof *points; i++) {
        double expected[3] = {points[i][0] * 2, points[i][1] * 3, points[i][2] * 4};
        rotate_about(0, 30, expected);
        rotate_about(1, 45, expected);
        rotate_about(2, 60, expected);
        expected[0] += 1;
        expected[1] += 2;
        expected[2] += 3;
        double actual[3];
        transform_point(ring->model, points[i], actual);
        for (int k = 0; k < 3; k++)
            assert_float_equal(actual[k], expected[k], 1e-5);
    }
    for (int row = 0; row < 3; row++)
        assert_float_equal(ring->model[row][3], 0, 0);
    assert_float_equal(ring->model[3][3], 1, 0);
    scene_free(&s);
}

static void test_world_bounds(void **state) {
    (void)state;
    scene s;
    load_quietly(&s, "tests/data/scene_good.json");
    /* "crate": a 2 x 4 x 6 box turned 90 degrees about Y (x and z swap
     * extents), moved to (1, 2, 3). */
    float min[3], max[3];
    scene_object_world_bounds(find_object(&s, "crate"), min, max);
    assert_vec3(min, -2, 0, 2);
    assert_vec3(max, 4, 4, 4);
    /* The exact box of the transformed mesh box: no vertex of "ring" is
     * outside it, and it touches the mesh's own box corners' images. */
    const scene_object *ring = find_object(&s, "ring");
    scene_object_world_bounds(ring, min, max);
    for (uint32_t v = 0; v < ring->mesh.vertex_count; v++) {
        const float *p = ring->mesh.vertices[v].position;
        double world[3];
        transform_point(ring->model, (const double[3]){p[0], p[1], p[2]}, world);
        for (int k = 0; k < 3; k++)
            assert_true(world[k] >= min[k] - 1e-4 && world[k] <= max[k] + 1e-4);
    }
    scene_free(&s);
}

static void test_defaults(void **state) {
    (void)state;
    scene s;
    load_quietly(&s, "tests/data/scene_defaults.json");
    assert_vec3(s.camera.up, 0, 1, 0);
    assert_float_equal(s.camera.fov_deg, 45, 0);
    assert_float_equal(s.camera.near_plane, 0.1, 1e-7);
    assert_float_equal(s.camera.far_plane, 100, 0);
    assert_vec3(s.ambient, 0.1, 0.1, 0.1);
    assert_int_equal(s.light_count, 1);
    assert_vec3(s.lights[0].color, 1, 1, 1);
    assert_float_equal(s.lights[0].intensity, 1, 0);
    assert_float_equal(s.lights[0].radius, 0, 0);
    assert_int_equal(s.object_count, 1);
    assert_identity(s.objects[0].model);
    assert_vec3(s.objects[0].color, 0.8, 0.8, 0.8);
    assert_true(s.objects[0].casts);
    assert_true(s.objects[0].receives);
    scene_free(&s);
    scene_free(&s); /* freeing an empty scene is harmless */
}

/* A model without "color" takes its file's (the material covering the
 * most triangles: mesh_material), one with it keeps its own, and a model
 * whose file names no material the default; --verbose's lines give each
 * model's triangles, world bounds and colour. */
static void test_model_colour_and_models_printed(void **state) {
    (void)state;
    scene s;
    load_quietly(&s, "tests/data/scene_model_color.json");
    assert_vec3(find_object(&s, "painted")->color, 0.1f, 0.2f, 0.9f);
    assert_vec3(find_object(&s, "repainted")->color, 0, 1, 0);
    assert_vec3(find_object(&s, "plain")->color, 0.8f, 0.8f, 0.8f);
    support_capture_stderr();
    scene_print_models(&s, "scene.json");
    const char *text = support_release_stderr();
    assert_string_equal(text,
                        "scene.json: objects[0] \"painted\": model of 5 triangles, bounds (0, 0, 0) to (5, 1, 0), "
                        "colour (0.1, 0.2, 0.9)\n"
                        "scene.json: objects[1] \"repainted\": model of 5 triangles, bounds (0, 0, -1) to (5, 1, "
                        "-1), colour (0, 1, 0)\n"
                        "scene.json: objects[2] \"plain\": model of 4 triangles, bounds (0, 0, -2) to (1, 1, -1), "
                        "colour (0.8, 0.8, 0.8)\n");
    scene_free(&s);
    /* Rebased on its camera (scene.h, "Large worlds"), a scene's bounds
     * are still the file's world coordinates. */
    load_quietly(&s, "tests/data/scene_model_rebased.json");
    assert_true(s.origin[0] == 1000);
    support_capture_stderr();
    scene_print_models(&s, "rebased.json");
    text = support_release_stderr();
    scene_free(&s);
    assert_string_equal(text,
                        "rebased.json: objects[0] \"tetrahedron\": model of 4 triangles, bounds (1000, 0, 0) to "
                        "(1001, 1, 1), colour (0.8, 0.8, 0.8)\n");
    /* A model whose materials have textures, drawn in its own colour:
     * said, once for the object; with the scene's colour, nothing. */
    support_capture_stderr();
    bool loaded = scene_load(&s, "tests/data/scene_model_textured.json");
    text = support_release_stderr();
    assert_true(loaded);
    assert_string_equal(text,
                        "tests/data/scene_model_textured.json: objects[0]: 1 of the model's materials have textures, "
                        "which only a glTF scene reads: drawn in the colour (0.5, 0.25, 0.125) alone\n");
    assert_null(s.objects[0].base_color);
    scene_free(&s);
}

/* A light's range: read from the file, and the window it sets (1 at the
 * light, (1 - (d/r)^4)^2 between, exactly 0 from the range on); a light
 * without one reaches everywhere. */
static void test_light_range(void **state) {
    (void)state;
    scene s;
    assert_true(scene_load(&s, "tests/data/range_lights.json"));
    const scene_light *point = &s.lights[0], *spot = &s.lights[1], *sun = &s.lights[2];
    assert_float_equal(point->range, 7.5f, 0);
    assert_float_equal(spot->range, 5.6f, 0);
    assert_float_equal(sun->range, 0, 0);
    assert_float_equal(scene_light_range_window(point, 0), 1, 0);
    assert_float_equal(scene_light_range_window(point, 3.75f), (15.0f / 16) * (15.0f / 16), 1e-6f);
    assert_float_equal(scene_light_range_window(point, 7.5f), 0, 0);
    assert_float_equal(scene_light_range_window(point, 100), 0, 0);
    assert_true(scene_light_range_window(point, 7.4f) > 0);
    for (float d = 0.1f; d < 7.5f; d += 0.1f)
        assert_true(scene_light_range_window(point, d) < scene_light_range_window(point, d - 0.1f));
    assert_float_equal(scene_light_range_window(sun, 1e6f), 1, 0);
    scene_free(&s);
}

/* The world position of vertex v of o, in float as the GL's vertex shader
 * computes it. */
static void world_vertex(const scene_object *o, uint32_t v, float out[3]) {
    const float *p = o->mesh.vertices[v].position;
    for (int row = 0; row < 3; row++)
        out[row] = o->model[0][row] * p[0] + o->model[1][row] * p[1] + o->model[2][row] * p[2] + o->model[3][row];
}

/* The volume a mesh's world triangles enclose (divergence theorem):
 * positive when they run counter-clockwise seen from outside. */
static double world_signed_volume(const scene_object *o) {
    double volume = 0;
    for (uint32_t i = 0; i < o->mesh.index_count; i += 3) {
        float p[3][3];
        for (int c = 0; c < 3; c++)
            world_vertex(o, o->mesh.indices[i + (uint32_t)c], p[c]);
        volume += ((double)p[0][0] * ((double)p[1][1] * p[2][2] - (double)p[1][2] * p[2][1]) +
                   (double)p[0][1] * ((double)p[1][2] * p[2][0] - (double)p[1][0] * p[2][2]) +
                   (double)p[0][2] * ((double)p[1][0] * p[2][1] - (double)p[1][1] * p[2][0])) /
                  6;
    }
    return volume;
}

static double determinant3(const float m[4][4]) {
    return (double)m[0][0] * ((double)m[1][1] * m[2][2] - (double)m[2][1] * m[1][2]) -
           (double)m[1][0] * ((double)m[0][1] * m[2][2] - (double)m[2][1] * m[0][2]) +
           (double)m[2][0] * ((double)m[0][1] * m[1][2] - (double)m[1][1] * m[0][2]);
}

/* A light inside a closed caster, with the eye outside it, lights nothing
 * the eye sees: the load says so in one line and succeeds. Not for a light
 * just outside the caster though within its bounds, nor one on its surface,
 * nor one in a closed room the eye is in too, nor one in a closed object
 * that casts nothing. */
static void test_light_inside_closed_caster_is_said(void **state) {
    (void)state;
    static const struct {
        const char *path, *said;
    } cases[] = {
        {"tests/data/vol_light_inside_bunny.json",
         "tests/data/vol_light_inside_bunny.json: light 0 lies inside object 1 (bunny): it lights nothing outside "
         "it\n"},
        {"tests/data/vol_light_inside_box.json",
         "tests/data/vol_light_inside_box.json: light 0 lies inside object 1 (box): it lights nothing outside it\n"},
        {"tests/data/scene_light_outside_bunny.json", ""},
        {"tests/data/vol_light_on_box_face.json", ""},
        {"tests/data/scene_light_in_room.json", ""},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        scene s;
        support_capture_stderr();
        bool loaded = scene_load(&s, cases[i].path);
        const char *text = support_release_stderr();
        if (!loaded || strcmp(text, cases[i].said) != 0)
            fail_msg("%s: loaded %d, said \"%s\"; expected \"%s\"", cases[i].path, loaded, text, cases[i].said);
        scene_free(&s);
    }
}

/* tests/data/mirror_mirrored.json and mirror_unmirrored.json are each
 * other's mirror image in x = 0 (see tests/test_mirror.c), mirrored
 * objects in both. Every object gets a positive determinant, its world
 * vertices are bit for bit the mirror images of the other scene's (the
 * mirror went into the mesh: only signs changed), and its world
 * triangles still enclose a positive volume, the same in both: none is
 * inside out. */
static void test_mirrored_objects(void **state) {
    (void)state;
    scene mirrored, unmirrored;
    load_quietly(&mirrored, "tests/data/mirror_mirrored.json");
    load_quietly(&unmirrored, "tests/data/mirror_unmirrored.json");
    assert_int_equal(mirrored.object_count, unmirrored.object_count);
    for (int i = 0; i < mirrored.object_count; i++) {
        const scene_object *a = &mirrored.objects[i], *b = &unmirrored.objects[i];
        assert_true(determinant3(a->model) > 0 && determinant3(b->model) > 0);
        assert_int_equal(a->mesh.vertex_count, b->mesh.vertex_count);
        assert_int_equal(a->mesh.index_count, b->mesh.index_count);
        for (uint32_t v = 0; v < a->mesh.vertex_count; v++) {
            float pa[3], pb[3];
            world_vertex(a, v, pa);
            world_vertex(b, v, pb);
            if (!(pa[0] == -pb[0] && pa[1] == pb[1] && pa[2] == pb[2]))
                fail_msg("%s: vertex %u: (%.9g %.9g %.9g) is not the mirror of (%.9g %.9g %.9g)", a->name, v, pa[0],
                         pa[1], pa[2], pb[0], pb[1], pb[2]);
        }
        /* The ground is open and flat: no volume to measure. */
        if (a->mesh_kind == SCENE_MESH_PLANE)
            continue;
        double va = world_signed_volume(a), vb = world_signed_volume(b);
        assert_true(va > 0);
        assert_float_equal(va, vb, 1e-9 * vb);
    }
    scene_free(&mirrored);
    scene_free(&unmirrored);
}

/* A scene 1e6 from the world's origin (scene.h, "Large worlds"): every
 * position relative to the eye keeps a scene-at-the-origin's precision.
 * In world floats, 1e6 away, each would be off by up to 0.03. */
static void test_far_from_origin(void **state) {
    (void)state;
    scene s;
    load_quietly(&s, "tests/data/scene_far_from_origin.json");
    const double eye[3] = {1000000.3, 250004.1, -999987.3};
    for (int k = 0; k < 3; k++)
        assert_true(s.origin[k] == (double)(float)eye[k]);
    const float *camera = s.camera.position;
    float light[3], box[3], target[3];
    const scene_object *b = find_object(&s, "box");
    for (int k = 0; k < 3; k++) {
        target[k] = s.camera.target[k] - camera[k];
        light[k] = s.lights[0].position[k] - camera[k];
        box[k] = b->model[3][k] - camera[k];
    }
    assert_vec3(target, -0.3, -3.1, -12.7);
    assert_vec3(light, 2.2, 1.9, -11.2);
    assert_vec3(box, -1.5, -3.3, -12.4);
    /* An object without "translate" sits at the world's origin. */
    const float *ground = find_object(&s, "ground")->model[3];
    assert_vec3(ground, -s.origin[0], -s.origin[1], -s.origin[2]);
    scene_free(&s);
    /* Near the origin a scene keeps its own numbers. */
    load_quietly(&s, "tests/data/scene_good.json");
    for (int k = 0; k < 3; k++)
        assert_true(s.origin[k] == 0);
    scene_free(&s);
}

typedef struct bad_scene {
    const char *path;
    const char *problem; /* expected in the message, after the path */
} bad_scene;

static const bad_scene bad_scenes[] = {
    {"tests/data/scene_missing_field.json", ": camera.target: missing required field"},
    {"tests/data/scene_wrong_type.json", ": lights[0].intensity: expected a number, got a string"},
    {"tests/data/scene_unknown_mesh_kind.json",
     ": objects[1].mesh.kind: unknown mesh kind \"cone\" (expected plane, box, sphere, torus, cylinder, model or gltf)"},
    {"tests/data/scene_unknown_key.json", ": objects[0]: unknown key \"colour\" (expected name, mesh, translate, "
                                          "rotate, scale, color, casts or receives), did you mean \"color\"?"},
    {"tests/data/scene_key_of_other_light_type.json",
     ": lights[0]: unknown key \"position\" (expected type, direction, color, intensity or radius)"},
    {"tests/data/scene_duplicate_key.json", ": objects[0].name: duplicate key"},
    {"tests/data/scene_range_zero.json", ": lights[0].range: must be positive (got 0)"},
    {"tests/data/scene_range_directional.json",
     ": lights[0]: unknown key \"range\" (expected type, direction, color, intensity or radius)"},
    {"tests/data/scene_missing_model.json",
     ": objects[0] \"statue\": tests/data/no_such_model.obj: cannot open: No such file or directory"},
    {"tests/data/scene_bad_model.json",
     ": objects[0] \"junk\": tests/data/mesh_only_degenerate.obj: no triangles left after removing 2 degenerate"},
    {"tests/data/scene_syntax_error.json", ":4: JSON syntax error near '\"'"},
    {"tests/data/scene_empty.json", ":1: JSON syntax error at the end of the file"},
    {"tests/data/scene_top_level_array.json", ": expected an object at the top level, got an array"},
    {"tests/data/scene_null_value.json", ": camera: expected an object, got null"},
    {"tests/data/scene_nonfinite_size.json", ": objects[0].mesh.size[1]: must be a finite number (got inf)"},
    {"tests/data/scene_negative_size.json", ": objects[0].mesh.radius: must be positive (got -1)"},
    {"tests/data/scene_torus_radii.json",
     ": objects[0] \"donut\": torus: minor_radius (2) must be smaller than major_radius (1)"},
    {"tests/data/scene_bad_segments.json", ": objects[0].mesh.segments: expected a whole number"},
    {"tests/data/scene_negative_segments.json",
     ": objects[0].mesh.segments: must be 3 to 1024, or 0 for the default (got -4)"},
    {"tests/data/scene_duplicate_name.json",
     ": objects[2].name: \"box\" is objects[1]'s name too: each must be one object's"},
    {"tests/data/scene_too_many_lights.json", ": lights: too many entries: 65 (at most 64)"},
    {"tests/data/scene_no_objects.json", ": objects: must not be empty"},
    {"tests/data/scene_spot_outer_below_inner.json",
     ": lights[0].outer_angle: must not be less than inner_angle (20 < 30)"},
    {"tests/data/scene_spot_outer_90.json", ": lights[0].outer_angle: must be less than 90 degrees (got 90)"},
    {"tests/data/scene_zero_direction.json", ": lights[0].direction: must not be zero"},
    {"tests/data/scene_camera_up_parallel.json",
     ": camera.up: must be non-zero and not parallel to the view direction"},
    {"tests/data/mirror_zero_scale.json", ": objects[0].scale: must not be zero: it flattens the object (got 0)"},
    {"tests/data/mirror_tiny_scale_axis.json",
     ": objects[0].scale[1]: must not be zero: it flattens the object (got 1e-50)"},
    {"tests/data/scene_name_too_long.json", ": objects[0].name: must be 1 to 63 bytes long (got 64)"},
    {"tests/data/no_such_scene.json", ": cannot open: No such file or directory"},
    {"tests/data", ": cannot read: Is a directory"},
};

/* Each bad file fails with one line: "PATH" then the problem. */
static void test_bad_scenes(void **state) {
    (void)state;
    for (size_t i = 0; i < sizeof bad_scenes / sizeof *bad_scenes; i++) {
        const bad_scene *bad = &bad_scenes[i];
        scene s;
        support_capture_stderr();
        bool loaded = scene_load(&s, bad->path);
        const char *text = support_release_stderr();
        if (loaded)
            fail_msg("%s: loaded, expected \"%s\"", bad->path, bad->problem);
        assert_empty_scene(&s);
        char expected[512];
        snprintf(expected, sizeof expected, "%s%s", bad->path, bad->problem);
        const char *newline = strchr(text, '\n');
        bool one_line = newline && newline[1] == '\0';
        if (!one_line || strncmp(text, expected, strlen(expected)) != 0) {
            fail_msg("%s: expected one line starting \"%s\", got \"%s\"", bad->path, expected, text);
        }
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_good_scene_camera_and_lights),
        cmocka_unit_test(test_good_scene_objects),
        cmocka_unit_test(test_model_matrix_order),
        cmocka_unit_test(test_world_bounds),
        cmocka_unit_test(test_defaults),
        cmocka_unit_test(test_model_colour_and_models_printed),
        cmocka_unit_test(test_light_range),
        cmocka_unit_test(test_light_inside_closed_caster_is_said),
        cmocka_unit_test(test_mirrored_objects),
        cmocka_unit_test(test_far_from_origin),
        cmocka_unit_test(test_bad_scenes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
