/* build/scenegen: the generated scenes it writes are the committed ones
 * (deterministic, and regenerated with `make scenes` after a change), and
 * they are what the generator promises: cities of N objects plus the
 * ground with a sun and street lamps of limited range, most of the lamps
 * out of view and most of the city outside the camera's frustum; a dense
 * scene of closed meshes; glTF scenes of cut-out and translucent casters;
 * a night street of as many lamps as a scene may have.
 * Run from the repository root. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "frustum.h"
#include "mesh.h"
#include "scene.h"
#include "support.h"

#define OUT "out/test/scenes"
#define COMMITTED "assets/scenes"
/* The views are judged at the benchmark's and the screenshots' 16:9. */
#define VIEW_ASPECT (16.0f / 9.0f)
/* city_1000's camera sees a small part of the city: fewer than this
 * share of its objects' boxes meet the view frustum. */
#define MAX_SEEN_SHARE 0.15
#define MIN_LIMITED_LIGHTS 3
#define MIN_DENSE_TRIANGLES 100000
/* lamps_64's buildings: city_300's. */
#define LAMPS_CITY_COUNT 300

static const char *const files[] = {"city_100.json", "city_300.json",      "city_1000.json",     "city_3000.json",
                                    "dense.json",    "stacked_300.json",   "stacked_10000.json", "stacked_10000.obj",
                                    "fence.gltf",    "stained_glass.gltf", "lamps_64.json"};
static const int city_counts[] = {100, 300, 1000, 3000};

static char err[16384];

static int generate(void **state) {
    (void)state;
    char command[512];
    snprintf(command, sizeof command, "rm -rf " OUT " && %s --out " OUT, support_program("scenegen"));
    return support_run(command, err, sizeof err) == 0 ? 0 : -1;
}

static void load(scene *s, const char *name) {
    char path[256];
    snprintf(path, sizeof path, COMMITTED "/%s", name);
    if (!scene_load(s, path))
        fail_msg("%s does not load", path);
}

/* The committed scenes are exactly what the generator writes now. */
static void test_generated_match_committed(void **state) {
    (void)state;
    const char *differs = support_first_difference(OUT, COMMITTED, files, sizeof files / sizeof *files);
    if (differs)
        fail_msg("%s/%s differs from %s/%s: run `make scenes` and commit", OUT, differs, COMMITTED, differs);
}

/* city_counts[i]'s scene; returns its file name. */
static const char *load_city(scene *s, size_t i) {
    static char name[64];
    snprintf(name, sizeof name, "city_%d.json", city_counts[i]);
    load(s, name);
    return name;
}

static bool limited(const scene_light *l) { return l->type != SCENE_LIGHT_DIRECTIONAL && l->range > 0; }

/* N objects plus the ground (first, casting nothing); a sun and at least
 * three lamps of limited range, within the light limit. */
static void test_city_counts_and_lights(void **state) {
    (void)state;
    for (size_t i = 0; i < sizeof city_counts / sizeof *city_counts; i++) {
        scene s;
        load_city(&s, i);
        assert_int_equal(s.object_count, city_counts[i] + 1);
        assert_string_equal(s.objects[0].name, "ground");
        assert_int_equal(s.objects[0].mesh_kind, SCENE_MESH_PLANE);
        assert_false(s.objects[0].casts);
        for (int o = 1; o < s.object_count; o++)
            assert_true(s.objects[o].casts && s.objects[o].receives);
        assert_true(s.light_count <= SCENE_MAX_LIGHTS);
        int suns = 0, lamps = 0;
        for (int l = 0; l < s.light_count; l++) {
            suns += s.lights[l].type == SCENE_LIGHT_DIRECTIONAL;
            lamps += limited(&s.lights[l]);
        }
        assert_int_equal(suns, 1);
        assert_true(lamps >= MIN_LIMITED_LIGHTS);
        scene_free(&s);
    }
}

static void view_of(const scene *s, camera_view *view) { camera_view_compute(&s->camera, VIEW_ASPECT, view); }

/* Entirely outside: beyond one of the frustum's planes by more than r. */
static bool sphere_outside(const vec4 planes[6], const float center[3], float radius) {
    for (int p = 0; p < 6; p++) {
        if (glm_vec3_dot((float *)planes[p], (float *)center) + planes[p][3] < -radius)
            return true;
    }
    return false;
}

/* More than half of the lamps' range spheres lie wholly outside the view. */
static void test_city_lamps_mostly_out_of_view(void **state) {
    (void)state;
    for (size_t i = 0; i < sizeof city_counts / sizeof *city_counts; i++) {
        scene s;
        const char *name = load_city(&s, i);
        camera_view view;
        view_of(&s, &view);
        vec4 planes[6];
        glm_frustum_planes(view.view_projection, planes);
        int lamps = 0, outside = 0;
        for (int l = 0; l < s.light_count; l++) {
            if (!limited(&s.lights[l]))
                continue;
            lamps++;
            outside += sphere_outside(planes, s.lights[l].position, s.lights[l].range);
        }
        printf("    %s: %d of %d lamps out of view\n", name, outside, lamps);
        assert_true(2 * outside > lamps);
        scene_free(&s);
    }
}

/* How many objects but the ground have a world box meeting the frustum. */
static int objects_seen(const scene *s) {
    camera_view view;
    view_of(s, &view);
    vec3 corners[8];
    frustum_corners(view.view_projection, corners);
    int seen = 0;
    for (int o = 1; o < s->object_count; o++) {
        const scene_object *object = &s->objects[o];
        vec3 box[2], world[2];
        glm_vec3_copy((float *)object->mesh.bounds_min, box[0]);
        glm_vec3_copy((float *)object->mesh.bounds_max, box[1]);
        glm_aabb_transform(box, (vec4 *)object->model, world);
        float part[1][3];
        seen += frustum_box_part(view.view_projection, corners, world[0], world[1], part, 1) > 0;
    }
    return seen;
}

/* city_1000's camera sees a small part of it, and city_3000 adds nothing
 * to the view: the cities grow away from the camera. */
static void test_city_view_is_small_and_shared(void **state) {
    (void)state;
    scene s;
    load(&s, "city_1000.json");
    int seen = objects_seen(&s), total = s.object_count - 1;
    scene_free(&s);
    printf("    city_1000: %d of %d objects meet the view frustum (%.1f %%)\n", seen, total, 100.0 * seen / total);
    assert_true(seen < MAX_SEEN_SHARE * total);
    load(&s, "city_3000.json");
    int seen_3000 = objects_seen(&s);
    scene_free(&s);
    assert_int_equal(seen_3000, seen);
}

/* At least 100k triangles, every mesh a closed 2-manifold, one light. */
static void test_dense_is_closed_and_large(void **state) {
    (void)state;
    scene s;
    load(&s, "dense.json");
    assert_int_equal(s.light_count, 1);
    long triangles = 0;
    for (int o = 0; o < s.object_count; o++) {
        const mesh *m = &s.objects[o].mesh;
        triangles += m->index_count / 3;
        mesh_topology t;
        mesh_edges e;
        assert_true(mesh_weld(m, &t));
        assert_true(mesh_edges_build(m, &t, &e));
        if (!e.closed)
            fail_msg("dense.json: %s is not closed", s.objects[o].name);
        mesh_edges_free(&e);
        mesh_topology_free(&t);
    }
    printf("    dense: %ld triangles in %d closed meshes\n", triangles, s.object_count);
    assert_true(triangles >= MIN_DENSE_TRIANGLES);
    scene_free(&s);
}

/* The night street: SCENE_MAX_LIGHTS point lamps of limited range and no
 * other light, a pole for each, no lamp inside any pole (its own pole
 * would shadow everything), and the city's buildings and ground. */
static void test_lamps_fill_the_light_limit(void **state) {
    (void)state;
    scene s;
    load(&s, "lamps_64.json");
    assert_int_equal(s.light_count, SCENE_MAX_LIGHTS);
    int poles = 0;
    for (int o = 0; o < s.object_count; o++)
        poles += strncmp(s.objects[o].name, "pole_", strlen("pole_")) == 0;
    assert_int_equal(poles, SCENE_MAX_LIGHTS);
    assert_int_equal(s.object_count, LAMPS_CITY_COUNT + 1 + poles);
    for (int l = 0; l < s.light_count; l++) {
        assert_true(s.lights[l].type == SCENE_LIGHT_POINT && limited(&s.lights[l]));
        for (int o = 0; o < poles; o++) {
            vec3 box[2], world[2];
            glm_vec3_copy(s.objects[o].mesh.bounds_min, box[0]);
            glm_vec3_copy(s.objects[o].mesh.bounds_max, box[1]);
            glm_aabb_transform(box, (vec4 *)s.objects[o].model, world);
            if (glm_aabb_point(world, s.lights[l].position))
                fail_msg("lamps_64.json: lamp %d inside %s", l, s.objects[o].name);
        }
    }
    scene_free(&s);
}

/* The glTF scenes: the fence's boards and the tree's leaves cut out by
 * textures (alphaMode MASK), its trunk and ground opaque, under a sun; the
 * stained glass's three panes translucent (BLEND), one textured, over an
 * opaque ground and box, under a spot; each seen by its file's camera. */
static void test_gltf_scenes_cut_out_and_translucent(void **state) {
    (void)state;
    static const struct {
        const char *file;
        int objects, cut_out, translucent, textured;
        scene_light_type light;
    } scenes[] = {
        {"fence.gltf", 4, 2, 0, 2, SCENE_LIGHT_DIRECTIONAL},
        {"stained_glass.gltf", 5, 0, 3, 1, SCENE_LIGHT_SPOT},
    };
    for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++) {
        scene s;
        support_capture_stderr();
        load(&s, scenes[i].file);
        const char *said = support_release_stderr();
        if (said[0])
            fail_msg("%s: said \"%s\" (a camera or light fitted?)", scenes[i].file, said);
        int cut_out = 0, translucent = 0, textured = 0;
        for (int o = 0; o < s.object_count; o++) {
            cut_out += s.objects[o].alpha_cutoff > 0;
            translucent += s.objects[o].translucent;
            textured += s.objects[o].base_color != NULL;
        }
        assert_int_equal(s.object_count, scenes[i].objects);
        assert_int_equal(cut_out, scenes[i].cut_out);
        assert_int_equal(translucent, scenes[i].translucent);
        assert_int_equal(textured, scenes[i].textured);
        assert_int_equal(s.light_count, 1);
        assert_int_equal(s.lights[0].type, scenes[i].light);
        scene_free(&s);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_generated_match_committed),
        cmocka_unit_test(test_city_counts_and_lights),
        cmocka_unit_test(test_city_lamps_mostly_out_of_view),
        cmocka_unit_test(test_city_view_is_small_and_shared),
        cmocka_unit_test(test_dense_is_closed_and_large),
        cmocka_unit_test(test_gltf_scenes_cut_out_and_translucent),
        cmocka_unit_test(test_lamps_fill_the_light_limit),
    };
    return cmocka_run_group_tests_name("generated scenes", tests, generate, NULL);
}
