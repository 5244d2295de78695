/* Scene packs (common/data/scene_pack.h, the page's glTF scenes): the
 * scene build/bake packs from each glTF scene the page shows reads back
 * as scene_load made it, field by field and bit for bit (meshes,
 * textures, lights, camera), and included in a scene file makes the
 * objects the glTF file itself makes there; a pack cut short, one with bytes beyond its
 * counts and a file that is no pack are one line naming the file. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <cglm/cglm.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"
#include "scene_internal.h" /* scene_include_gltf, which the page's replaces */
#include "scene_pack.h"
#include "support.h"
#include "texture.h"

#define PACK_DIR "out/test/scene_pack"
/* An included object's matrix against the glTF file's own: the same
 * product, rounded in another order, relative to the matrix's largest
 * entry. */
#define PACK_PLACEMENT_TOLERANCE 1e-6f

/* The structs compared whole hold floats (and a light's type) alone. */
_Static_assert(offsetof(scene_camera, reversed_depth) == 12 * sizeof(float), "the camera's floats");
_Static_assert(sizeof(scene_light) == sizeof(scene_light_type) + 14 * sizeof(float), "a light's type and floats");

static const char *const pack_scenes[] = {"assets/scenes/fence.gltf", "assets/scenes/stained_glass.gltf"};

static void assert_same_mesh(const mesh *got, const mesh *expected) {
    assert_int_equal(got->vertex_count, expected->vertex_count);
    assert_int_equal(got->index_count, expected->index_count);
    assert_memory_equal(got->vertices, expected->vertices, expected->vertex_count * sizeof *expected->vertices);
    assert_memory_equal(got->indices, expected->indices, expected->index_count * sizeof *expected->indices);
    assert_memory_equal(got->bounds_min, expected->bounds_min, sizeof expected->bounds_min);
    assert_memory_equal(got->bounds_max, expected->bounds_max, sizeof expected->bounds_max);
}

static void assert_same_texture(const texture *got, const texture *expected) {
    assert_int_equal(got->level_count, expected->level_count);
    assert_int_equal(got->wrap[0], expected->wrap[0]);
    assert_int_equal(got->wrap[1], expected->wrap[1]);
    for (int l = 0; l < expected->level_count; l++) {
        const texture_level *a = &got->levels[l], *b = &expected->levels[l];
        assert_int_equal(a->width, b->width);
        assert_int_equal(a->height, b->height);
        assert_memory_equal(a->rgba, b->rgba, 4 * (size_t)b->width * (size_t)b->height);
    }
}

/* Each texture where the other scene has it: the same index. */
static void assert_same_texture_of(const scene *got, const scene_object *a, const scene *expected,
                                   const scene_object *b) {
    if (!b->base_color) {
        assert_null(a->base_color);
        return;
    }
    assert_non_null(a->base_color);
    assert_int_equal(a->base_color - got->textures, b->base_color - expected->textures);
}

static void assert_same_scene(const scene *got, const scene *expected) {
    assert_memory_equal(got->origin, expected->origin, sizeof expected->origin);
    /* What the pack keeps of the camera, its floats before
     * reversed_depth; the lights, floats after their type. */
    assert_memory_equal(&got->camera, &expected->camera, offsetof(scene_camera, reversed_depth));
    assert_memory_equal(got->ambient, expected->ambient, sizeof expected->ambient);
    assert_int_equal(got->light_count, expected->light_count);
    assert_memory_equal(got->lights, expected->lights, (size_t)expected->light_count * sizeof *expected->lights);
    assert_int_equal(got->texture_count, expected->texture_count);
    for (int t = 0; t < expected->texture_count; t++)
        assert_same_texture(&got->textures[t], &expected->textures[t]);
    assert_int_equal(got->object_count, expected->object_count);
    for (int i = 0; i < expected->object_count; i++) {
        const scene_object *a = &got->objects[i], *b = &expected->objects[i];
        assert_string_equal(a->name, b->name);
        assert_int_equal(a->mesh_kind, b->mesh_kind);
        assert_same_mesh(&a->mesh, &b->mesh);
        assert_memory_equal(a->model, b->model, sizeof b->model);
        assert_memory_equal(a->color, b->color, sizeof b->color);
        assert_same_texture_of(got, a, expected, b);
        assert_memory_equal(&a->alpha_cutoff, &b->alpha_cutoff, sizeof b->alpha_cutoff);
        assert_memory_equal(&a->base_alpha, &b->base_alpha, sizeof b->base_alpha);
        assert_int_equal(a->translucent, b->translucent);
        assert_int_equal(a->single_sided, b->single_sided);
        assert_int_equal(a->casts, b->casts);
        assert_int_equal(a->receives, b->receives);
    }
}

/* Writes the scene of glTF file `path` as a pack at `pack`. */
static void pack_write(const char *path, const char *pack) {
    scene loaded;
    assert_int_equal(system("mkdir -p " PACK_DIR), 0);
    support_capture_stderr();
    assert_true(scene_load(&loaded, path));
    support_release_stderr();
    assert_true(scene_pack_write(pack, &loaded));
    scene_free(&loaded);
}

static void assert_placed_near(const float got[4][4], const float expected[4][4]) {
    float largest = 0;
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            largest = fmaxf(largest, fabsf(expected[c][r]));
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            if (fabsf(got[c][r] - expected[c][r]) > PACK_PLACEMENT_TOLERANCE * largest)
                fail_msg("model[%d][%d]: %g, the glTF file's %g", c, r, got[c][r], expected[c][r]);
}

/* Reading `path` fails with the one line "PATH: problem". */
static void assert_read_fails(const char *path, const char *problem) {
    scene s;
    support_capture_stderr();
    bool read = scene_pack_read(&s, path);
    const char *said = support_release_stderr();
    assert_false(read);
    assert_int_equal(s.object_count, 0);
    assert_null(s.objects);
    assert_null(s.textures);
    char expected[512];
    snprintf(expected, sizeof expected, "%s: %s\n", path, problem);
    assert_string_equal(said, expected);
}

/* What the scenes hold (textures, a cut-out, a translucent caster, a
 * single-sided object) is checked too, so that the comparison covers
 * them. */
static void test_scene_pack_reads_back_the_scene(void **state) {
    (void)state;
    assert_int_equal(system("mkdir -p " PACK_DIR), 0);
    bool textured = false, cut_out = false, translucent = false, single_sided = false;
    for (size_t k = 0; k < sizeof pack_scenes / sizeof *pack_scenes; k++) {
        scene loaded, read;
        support_capture_stderr();
        assert_true(scene_load(&loaded, pack_scenes[k]));
        support_release_stderr();
        assert_true(scene_pack_write(PACK_DIR "/scene.gltf", &loaded));
        assert_true(scene_pack_read(&read, PACK_DIR "/scene.gltf"));
        assert_same_scene(&read, &loaded);
        for (int i = 0; i < loaded.object_count; i++) {
            textured |= loaded.objects[i].base_color != NULL;
            cut_out |= loaded.objects[i].alpha_cutoff > 0;
            translucent |= loaded.objects[i].translucent;
            single_sided |= loaded.objects[i].single_sided;
        }
        scene_free(&loaded);
        scene_free(&read);
    }
    assert_true(textured && cut_out && translucent && single_sided);
}

/* The page's scene_include_gltf (scene_pack_include) against the native
 * one, which reads the glTF file, under a transform that turns, moves and
 * mirrors: the same objects, names, meshes (mirrored alike), textures and
 * flags (seen from both sides, casting and receiving as the include
 * says), placed alike to the rounding. */
static void test_scene_pack_included(void **state) {
    (void)state;
    pack_write(pack_scenes[0], PACK_DIR "/included.gltf");
    mat4 model;
    glm_translate_make(model, (vec3){1, 2, 3});
    glm_rotate_y(model, glm_rad(30), model);
    glm_scale(model, (vec3){-1, 1, 2});
    scene native = {0}, page = {0};
    int native_capacity = 0, page_capacity = 0;
    support_capture_stderr();
    assert_true(scene_include_gltf(&native, &native_capacity, pack_scenes[0], model, "fence", true, false));
    support_release_stderr();
    assert_true(scene_pack_include(&page, &page_capacity, PACK_DIR "/included.gltf", model, "fence", true, false));
    assert_int_equal(page.texture_count, native.texture_count);
    for (int t = 0; t < native.texture_count; t++)
        assert_same_texture(&page.textures[t], &native.textures[t]);
    assert_int_equal(page.object_count, native.object_count);
    for (int i = 0; i < native.object_count; i++) {
        const scene_object *a = &page.objects[i], *b = &native.objects[i];
        assert_string_equal(a->name, b->name);
        assert_same_mesh(&a->mesh, &b->mesh);
        assert_placed_near(a->model, b->model);
        assert_true(glm_mat4_det((vec4 *)a->model) > 0);
        assert_memory_equal(a->color, b->color, sizeof b->color);
        assert_same_texture_of(&page, a, &native, b);
        assert_memory_equal(&a->alpha_cutoff, &b->alpha_cutoff, sizeof b->alpha_cutoff);
        assert_int_equal(a->translucent, b->translucent);
        assert_false(a->single_sided);
        assert_true(a->casts && !a->receives);
    }
    scene_free(&native);
    scene_free(&page);
}

/* The last pack written cut short in its header, in its first texture
 * and in its last mesh (mesh_pack's own line), with a byte more, and the
 * glTF file itself. */
static void test_scene_pack_bad_files(void **state) {
    (void)state;
    pack_write(pack_scenes[0], PACK_DIR "/fence.gltf");
    assert_int_equal(system("head -c 20 " PACK_DIR "/fence.gltf > " PACK_DIR "/header.gltf && "
                            "head -c 300 " PACK_DIR "/fence.gltf > " PACK_DIR "/texture.gltf && "
                            "head -c -1 " PACK_DIR "/fence.gltf > " PACK_DIR "/mesh.gltf && "
                            "{ cat " PACK_DIR "/fence.gltf; printf x; } > " PACK_DIR "/longer.gltf"),
                     0);
    assert_read_fails(PACK_DIR "/header.gltf", "truncated");
    assert_read_fails(PACK_DIR "/texture.gltf", "truncated");
    assert_read_fails(PACK_DIR "/mesh.gltf", "truncated");
    assert_read_fails(PACK_DIR "/longer.gltf", "longer than its counts");
    assert_read_fails(pack_scenes[0], "not a scene pack (build/bake writes them)");
    assert_read_fails(PACK_DIR "/none.gltf", "cannot open: No such file or directory");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_scene_pack_reads_back_the_scene),
        cmocka_unit_test(test_scene_pack_included),
        cmocka_unit_test(test_scene_pack_bad_files),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
