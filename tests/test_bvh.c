/* The ray hierarchy (common/data/bvh.h): on real models every ray gets
 * the answer of the same triangle test run on every triangle (the
 * hierarchy only skips), a cone called clear lets every ray inside it
 * through (the test is conservative), no ray slips through the shared
 * diagonal of a box's face (the test is watertight), paths stay within
 * the GPU's stack on a degenerate pile, and a scene without casters
 * blocks nothing. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdbool.h>
#include <stdlib.h>

#include <cglm/cglm.h>
#include <cmocka.h>

#include "area_light.h"
#include "bvh.h"
#include "scene.h"

/* Random rays per scene, against the flat list. */
#define TEST_BVH_RAYS 20000
/* Random cones on the bunny, and rays checked inside each one called
 * clear. */
#define TEST_BVH_CONES 2000
#define TEST_BVH_CONE_RAYS 64
/* Points along each face diagonal aimed at, and origins per point. */
#define TEST_BVH_DIAGONAL_POINTS 64
#define TEST_BVH_ORIGINS 4
/* Triangles in the degenerate pile: all in one place. */
#define TEST_BVH_PILE 5000

/* A hierarchy of one leaf holding every triangle of b: the triangle test
 * run on each of them, with nothing skipped. */
static bvh test_bvh_flat(const bvh *b, float (*root)[4]) {
    for (int k = 0; k < 3; k++) {
        root[0][k] = INFINITY;
        root[1][k] = -INFINITY;
    }
    for (int i = 0; i < b->triangle_count; i++)
        for (int v = 0; v < 3; v++)
            for (int k = 0; k < 3; k++) {
                root[0][k] = fminf(root[0][k], b->triangles[i][v][k]);
                root[1][k] = fmaxf(root[1][k], b->triangles[i][v][k]);
            }
    root[0][3] = 0;
    root[1][3] = (float)b->triangle_count;
    return (bvh){.nodes = (float(*)[2][4])root,
                 .triangles = b->triangles,
                 .node_count = 1,
                 .triangle_count = b->triangle_count};
}

/* A unit in [0, 1) from the hash of a counter. */
static float test_bvh_unit(uint32_t *counter) { return area_light_unit(area_light_hash((*counter)++)); }

static void test_bvh_agrees_with_flat(const char *path) {
    scene s;
    assert_true(scene_load(&s, path));
    bvh b;
    assert_true(bvh_build(&s, path, &b));
    assert_true(b.node_count > 1);
    assert_true(b.depth <= BVH_MAX_DEPTH);
    float root[2][4];
    bvh flat = test_bvh_flat(&b, root);
    /* Origins in a box twice the casters' size about their centre. */
    float lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        float centre = 0.5f * (root[0][k] + root[1][k]), half = root[1][k] - root[0][k];
        lo[k] = centre - half;
        hi[k] = centre + half;
    }
    uint32_t counter = 1;
    int occluded = 0;
    for (int r = 0; r < TEST_BVH_RAYS; r++) {
        float origin[3], dir[3];
        for (int k = 0; k < 3; k++) {
            origin[k] = lo[k] + (hi[k] - lo[k]) * test_bvh_unit(&counter);
            dir[k] = 2 * test_bvh_unit(&counter) - 1;
        }
        /* Every fourth ray unbounded (a sun), the others segments. */
        float t_max = r % 4 == 0 ? INFINITY : 2 * test_bvh_unit(&counter);
        bool hit = bvh_occluded(&b, origin, dir, t_max);
        assert_int_equal(hit, bvh_occluded(&flat, origin, dir, t_max));
        occluded += hit;
    }
    /* Both answers occur: the rays test something. */
    assert_true(occluded > TEST_BVH_RAYS / 20 && occluded < TEST_BVH_RAYS - TEST_BVH_RAYS / 20);
    bvh_free(&b);
    scene_free(&s);
}

static void test_bunny_agrees_with_every_triangle(void **state) {
    (void)state;
    test_bvh_agrees_with_flat("assets/scenes/bunny.json");
}

static void test_teapot_agrees_with_every_triangle(void **state) {
    (void)state;
    test_bvh_agrees_with_flat("assets/scenes/teapot.json");
}

/* A cone called clear has no caster on any ray from its apex to its end
 * disk (any point within end_radius of the segment's end, here points of
 * the ball of that radius about it, which hold the disk); and the test
 * calls some cones clear and some not. */
static void test_clear_cones_let_every_ray_through(void **state) {
    (void)state;
    scene s;
    assert_true(scene_load(&s, "assets/scenes/bunny.json"));
    bvh b;
    assert_true(bvh_build(&s, "bunny", &b));
    float lo[3], hi[3], size = 0;
    for (int k = 0; k < 3; k++) {
        lo[k] = b.nodes[0][0][k];
        hi[k] = b.nodes[0][1][k];
        size = fmaxf(size, hi[k] - lo[k]);
    }
    uint32_t counter = 11;
    int clear = 0;
    for (int c = 0; c < TEST_BVH_CONES; c++) {
        float origin[3], end[3], dir[3];
        for (int k = 0; k < 3; k++) {
            float centre = 0.5f * (lo[k] + hi[k]);
            origin[k] = centre + size * (2 * test_bvh_unit(&counter) - 1);
            end[k] = centre + 2 * size * (2 * test_bvh_unit(&counter) - 1);
            dir[k] = end[k] - origin[k];
        }
        float radius = 0.2f * size * test_bvh_unit(&counter);
        if (!bvh_cone_clear(&b, origin, dir, 1, radius))
            continue;
        clear++;
        for (int r = 0; r < TEST_BVH_CONE_RAYS; r++) {
            float target[3], to[3];
            for (int k = 0; k < 3; k++) {
                target[k] = end[k] + radius * (2 * test_bvh_unit(&counter) - 1) / sqrtf(3.0f);
                to[k] = target[k] - origin[k];
            }
            assert_false(bvh_occluded(&b, origin, to, 1));
        }
    }
    assert_true(clear > TEST_BVH_CONES / 20 && clear < TEST_BVH_CONES - TEST_BVH_CONES / 20);
    bvh_free(&b);
    scene_free(&s);
}

/* Corner k of triangle t of object o in world space, as the hierarchy
 * rounds it. */
static void test_bvh_world(const scene_object *o, uint32_t t, int k, float out[3]) {
    double corner[3];
    scene_object_world_corner(o, t, k, corner);
    for (int row = 0; row < 3; row++)
        out[row] = (float)corner[row];
}

/* Rays aimed at points of the diagonal that a box face's two triangles
 * share, from outside that face (along its normal, and across it by up
 * to the box's size): the segment meets the box only at its end, so it
 * is blocked there exactly when no ray slips between the two triangles,
 * and not before. */
static void test_face_diagonals_block(void **state) {
    (void)state;
    scene s;
    assert_true(scene_load(&s, "assets/scenes/flat_boxes.json"));
    uint32_t counter = 7;
    int rays = 0;
    for (int i = 0; i < s.object_count; i++) {
        const scene_object *o = &s.objects[i];
        if (!o->casts)
            continue;
        /* The box alone: nothing else lies on the rays. */
        scene alone = {.objects = &s.objects[i], .object_count = 1};
        bvh b;
        assert_true(bvh_build(&alone, "flat_boxes", &b));
        float lo[3], hi[3];
        scene_object_world_bounds(o, lo, hi);
        float size = fmaxf(fmaxf(hi[0] - lo[0], hi[1] - lo[1]), hi[2] - lo[2]);
        /* mesh_make_box: a face is two triangles in a row, sharing two
         * vertices. */
        for (uint32_t k = 0; k + 6 <= o->mesh.index_count; k += 6) {
            const uint32_t *first = &o->mesh.indices[k], *second = &o->mesh.indices[k + 3];
            int shared[2]; /* corners of the first triangle */
            int found = 0;
            for (int u = 0; u < 3; u++)
                for (int v = 0; v < 3; v++)
                    if (first[u] == second[v] && found < 2)
                        shared[found++] = u;
            assert_int_equal(found, 2);
            float corner[3][3], p0[3], p1[3], e1[3], e2[3], normal[3];
            for (int v = 0; v < 3; v++)
                test_bvh_world(o, k / 3, v, corner[v]);
            glm_vec3_copy(corner[shared[0]], p0);
            glm_vec3_copy(corner[shared[1]], p1);
            glm_vec3_sub(corner[1], corner[0], e1);
            glm_vec3_sub(corner[2], corner[0], e2);
            glm_vec3_cross(e1, e2, normal);
            glm_vec3_normalize(normal);
            for (int j = 1; j < TEST_BVH_DIAGONAL_POINTS; j++) {
                float f = (float)j / TEST_BVH_DIAGONAL_POINTS, target[3];
                glm_vec3_lerp(p0, p1, f, target);
                for (int n = 0; n < TEST_BVH_ORIGINS; n++) {
                    float origin[3], dir[3];
                    for (int row = 0; row < 3; row++)
                        origin[row] = target[row] + size * (normal[row] + (2 * test_bvh_unit(&counter) - 1));
                    /* Keep the origin on the face's outer side. */
                    float out = glm_vec3_dot(
                        normal, (float[]){origin[0] - target[0], origin[1] - target[1], origin[2] - target[2]});
                    if (out < 0.25f * size)
                        glm_vec3_muladds(normal, 0.25f * size - out, origin);
                    glm_vec3_sub(target, origin, dir);
                    assert_true(bvh_occluded(&b, origin, dir, 1.5f));
                    assert_false(bvh_occluded(&b, origin, dir, 0.5f));
                    rays++;
                }
            }
        }
        bvh_free(&b);
    }
    assert_true(rays > 0);
    scene_free(&s);
}

/* A pile of equal triangles has no centroid to split by: the median
 * split halves it, and the paths stay within BVH_MAX_DEPTH. */
static void test_pile_stays_within_the_stack(void **state) {
    (void)state;
    mesh_vertex vertices[3] = {{.position = {0, 0, 0}, .normal = {0, 0, 1}},
                               {.position = {1, 0, 0}, .normal = {0, 0, 1}},
                               {.position = {0, 1, 0}, .normal = {0, 0, 1}}};
    uint32_t *indices = malloc(3 * TEST_BVH_PILE * sizeof *indices);
    assert_non_null(indices);
    for (int i = 0; i < 3 * TEST_BVH_PILE; i++)
        indices[i] = (uint32_t)(i % 3);
    scene_object pile = {.mesh = {vertices, indices, 3, 3 * TEST_BVH_PILE}, .casts = true};
    glm_mat4_identity(pile.model);
    scene s = {.objects = &pile, .object_count = 1};
    bvh b;
    assert_true(bvh_build(&s, "pile", &b));
    assert_int_equal(b.triangle_count, TEST_BVH_PILE);
    assert_true(b.depth <= BVH_MAX_DEPTH);
    assert_true(bvh_occluded(&b, (float[]){0.25f, 0.25f, 1}, (float[]){0, 0, -1}, 2));
    assert_false(bvh_occluded(&b, (float[]){0.25f, 0.25f, 1}, (float[]){0, 0, -1}, 0.5f));
    assert_false(bvh_occluded(&b, (float[]){0.75f, 0.75f, 1}, (float[]){0, 0, -1}, INFINITY));
    bvh_free(&b);
    free(indices);
}

/* Translucent panes (scene_object's translucent): a ray through both
 * keeps each channel's product of their transmittances (1 - a) + a C,
 * one through neither keeps all of it, one that also meets an opaque
 * square none; bvh_occluded only that last. */
static void test_translucent_panes_filter_rays(void **state) {
    (void)state;
    /* A unit square at height z, two triangles. */
    mesh_vertex squares[3][4];
    static uint32_t square_indices[6] = {0, 1, 2, 0, 2, 3};
    static const float heights[3] = {1, 2, 3};
    static const float corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    scene_object objects[3] = {
        {.color = {0.95f, 0.15f, 0.1f}, .base_alpha = 0.7f, .translucent = true, .casts = true},
        {.color = {0.2f, 0.35f, 0.95f}, .base_alpha = 0.6f, .translucent = true, .casts = true},
        {.color = {1, 1, 1}, .base_alpha = 1, .casts = true},
    };
    for (int o = 0; o < 3; o++) {
        for (int v = 0; v < 4; v++)
            squares[o][v] =
                (mesh_vertex){.position = {corners[v][0], corners[v][1], heights[o]}, .normal = {0, 0, 1}};
        objects[o].mesh =
            (mesh){.vertices = squares[o], .indices = square_indices, .vertex_count = 4, .index_count = 6};
        glm_mat4_identity(objects[o].model);
    }
    /* The opaque square covers x > 0.5 alone. */
    for (int v = 0; v < 4; v++)
        squares[2][v].position[0] = 0.5f + 0.5f * corners[v][0];
    scene s = {.objects = objects, .object_count = 3};
    bvh b;
    assert_true(bvh_build(&s, "panes", &b));
    assert_int_equal(b.record_count, 4);
    float red[3], blue[3], through[3];
    scene_object_transmittance(&objects[0], 0, (const float[3]){1, 0, 0}, red);
    scene_object_transmittance(&objects[1], 0, (const float[3]){1, 0, 0}, blue);
    bvh_transmittance(&b, (float[]){0.25f, 0.5f, 0}, (float[]){0, 0, 1}, 4, through);
    for (int k = 0; k < 3; k++)
        assert_float_equal(through[k], red[k] * blue[k], 1e-6);
    assert_false(bvh_occluded(&b, (float[]){0.25f, 0.5f, 0}, (float[]){0, 0, 1}, 4));
    bvh_transmittance(&b, (float[]){0.25f, 0.5f, 0}, (float[]){0, 0, 1}, 1.5f, through);
    for (int k = 0; k < 3; k++)
        assert_float_equal(through[k], red[k], 1e-6);
    bvh_transmittance(&b, (float[]){1.5f, 0.5f, 0}, (float[]){0, 0, 1}, 4, through);
    for (int k = 0; k < 3; k++)
        assert_float_equal(through[k], 1, 0);
    bvh_transmittance(&b, (float[]){0.75f, 0.5f, 0}, (float[]){0, 0, 1}, 4, through);
    for (int k = 0; k < 3; k++)
        assert_float_equal(through[k], 0, 0);
    assert_true(bvh_occluded(&b, (float[]){0.75f, 0.5f, 0}, (float[]){0, 0, 1}, 4));
    bvh_free(&b);
}

static void test_no_casters_block_nothing(void **state) {
    (void)state;
    scene s;
    assert_true(scene_load(&s, "assets/scenes/bunny.json"));
    for (int i = 0; i < s.object_count; i++)
        s.objects[i].casts = false;
    bvh b;
    assert_true(bvh_build(&s, "bunny", &b));
    assert_int_equal(b.node_count, 0);
    assert_false(bvh_occluded(&b, (float[]){0, 1, 0}, (float[]){0, -1, 0}, INFINITY));
    bvh_free(&b);
    scene_free(&s);
}

/* A cut-out fence (tests/data/gltf_cut_out.gltf: boards cut out of a
 * quad from (-2, 0, 0) to (2, 1.5, 0), its texture twice across): a ray
 * through it is blocked where the fence has a surface, by its texture's
 * alpha (texture.h's rule), and passes through the gaps. Points whose
 * alpha lies within TEST_BVH_ALPHA_MARGIN of the cutoff are left out:
 * which side rounding puts them on is not the question. */
#define TEST_BVH_FENCE_STEPS 97
#define TEST_BVH_ALPHA_MARGIN 0.02f
static void test_cut_outs_let_rays_through(void **state) {
    (void)state;
    scene s;
    assert_true(scene_load(&s, "tests/data/gltf_cut_out.gltf"));
    const scene_object *fence = &s.objects[1];
    assert_true(fence->alpha_cutoff > 0 && fence->base_color);
    bvh b;
    assert_true(bvh_build(&s, "fence", &b));
    assert_true(b.record_count > 0);
    int blocked = 0, passed = 0;
    for (int i = 1; i < TEST_BVH_FENCE_STEPS; i++)
        for (int j = 1; j < TEST_BVH_FENCE_STEPS; j++) {
            float x = -2 + 4.0f * (float)i / TEST_BVH_FENCE_STEPS, y = 1.5f * (float)j / TEST_BVH_FENCE_STEPS;
            /* assimp's texture coordinates: u across twice, v up. */
            float uv[2] = {(x + 2) / 2, y / 1.5f}, texel[4];
            texture_sample(fence->base_color, uv, 0, texel);
            if (fabsf(texel[3] - fence->alpha_cutoff) < TEST_BVH_ALPHA_MARGIN)
                continue;
            bool solid = texel[3] >= fence->alpha_cutoff;
            bool occluded = bvh_occluded(&b, (float[]){x, y, 1}, (float[]){0, 0, -2}, 1);
            if (occluded != solid)
                fail_msg("the ray through (%g, %g) is %s, where the fence's alpha is %g", x, y,
                         occluded ? "blocked" : "let through", texel[3]);
            blocked += occluded;
            passed += !occluded;
        }
    assert_true(blocked > 0 && passed > 0);
    bvh_free(&b);
    scene_free(&s);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bunny_agrees_with_every_triangle),
        cmocka_unit_test(test_teapot_agrees_with_every_triangle),
        cmocka_unit_test(test_clear_cones_let_every_ray_through),
        cmocka_unit_test(test_face_diagonals_block),
        cmocka_unit_test(test_pile_stays_within_the_stack),
        cmocka_unit_test(test_no_casters_block_nothing),
        cmocka_unit_test(test_cut_outs_let_rays_through),
        cmocka_unit_test(test_translucent_panes_filter_rays),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
