/* Mirrored transforms (a scale with an odd number of negative factors):
 * scene_load takes the mirror into the mesh with its winding reversed
 * (scene.h), so every technique and the reference see the faces
 * counter-clockwise from outside. Two scenes, each the other's mirror
 * image in the plane x = 0 (tests/data/mirror_*.json): in
 * mirror_mirrored, a rotated box, a teapot (open) and the bunny (closed)
 * scaled by -1 in x, a torus by -1 (a point reflection), the ground
 * mirrored too; in mirror_unmirrored their images with positive
 * determinants, and there the symmetric post is the mirrored one. The
 * camera lies in the mirror's plane, so each scene's picture is the
 * other's turned left to right. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "support.h"

#define MIRRORED "tests/data/mirror_mirrored.json"
#define UNMIRRORED "tests/data/mirror_unmirrored.json"

/* The reference's pictures of the two scenes may differ as two renderings
 * of one scene by the golden-image tolerance (float rounding puts a few
 * edge pixels' centres on the other side of an edge); ids and visibility
 * on as few pixels. */
#define MIRROR_MAX_DIFFERING SUPPORT_MAX_DIFFERING

/* Turns every row of a frame's ids, visibility and colour (color.png's:
 * dump_read leaves d->color empty) left to right. */
static void flip_frame(dump_frame *d, unsigned char *rgba) {
    for (int y = 0; y < d->height; y++) {
        for (int x = 0; x < d->width / 2; x++) {
            long a = (long)y * d->width + x, b = (long)y * d->width + (d->width - 1 - x);
            float id = d->ids[a], visibility = d->visibility[a];
            d->ids[a] = d->ids[b], d->ids[b] = id;
            d->visibility[a] = d->visibility[b], d->visibility[b] = visibility;
            for (int c = 0; c < 4; c++) {
                unsigned char colour = rgba[a * 4 + c];
                rgba[a * 4 + c] = rgba[b * 4 + c];
                rgba[b * 4 + c] = colour;
            }
        }
    }
}

/* The reference's dump of `scene` in `dir`, and its picture. */
static unsigned char *reference_dump(const char *scene, const char *dir, dump_frame *out) {
    assert_int_equal(support_dump("raytrace", scene, "", dir), 0);
    assert_true(dump_read(out, dir));
    char path[300];
    int width, height;
    snprintf(path, sizeof path, "%s/color.png", dir);
    unsigned char *rgba = image_read_png(path, &width, &height);
    assert_non_null(rgba);
    assert_true(width == out->width && height == out->height);
    return rgba;
}

/* The reference of the mirrored scene is the unmirrored one's picture
 * turned: same objects at each pixel, same shadows, same colours (a
 * mirror left inside out would show its back faces, shaded from the
 * wrong side: dark where the light falls). */
static void test_reference_sees_mirror_image(void **state) {
    (void)state;
    dump_frame mirrored, unmirrored;
    unsigned char *mirrored_rgba = reference_dump(MIRRORED, "out/test/mirror/reference_mirrored", &mirrored);
    unsigned char *unmirrored_rgba = reference_dump(UNMIRRORED, "out/test/mirror/reference_unmirrored", &unmirrored);
    assert_true(mirrored.width == unmirrored.width && mirrored.height == unmirrored.height);
    flip_frame(&unmirrored, unmirrored_rgba);
    long pixels = (long)mirrored.width * mirrored.height, surface = 0, ids = 0, visibility = 0;
    for (long i = 0; i < pixels; i++) {
        surface += mirrored.ids[i] >= 0;
        ids += mirrored.ids[i] != unmirrored.ids[i];
        visibility += mirrored.ids[i] == unmirrored.ids[i] && mirrored.visibility[i] != unmirrored.visibility[i];
    }
    long colour =
        image_compare(mirrored_rgba, unmirrored_rgba, mirrored.width, mirrored.height, SUPPORT_TOLERANCE, NULL);
    fprintf(stderr,
            "    mirrored against the unmirrored scene turned, of %ld pixels (%ld surface): "
            "ids differ on %ld, visibility on %ld, colour by more than %d/255 on %ld\n",
            pixels, surface, ids, visibility, SUPPORT_TOLERANCE, colour);
    assert_true(surface > pixels / 2);
    assert_true(ids <= pixels * MIRROR_MAX_DIFFERING);
    assert_true(visibility <= pixels * MIRROR_MAX_DIFFERING);
    assert_true(colour <= pixels * MIRROR_MAX_DIFFERING);
    free(mirrored_rgba);
    free(unmirrored_rgba);
    dump_frame_free(&mirrored);
    dump_frame_free(&unmirrored);
}

/* One technique's run on the mirrored scene, with its bound against the
 * reference (the bounds of test_accuracy, test_shadowmap, test_psm and
 * test_volumes): planar shadows only on their plane receiver. */
typedef struct mirror_case {
    const char *program;
    const char *flags;
    const char *receiver; /* NULL: every object */
    double max_misclassified_percent;
} mirror_case;

/* The volumes' bound (test_volumes). */
#define MIRROR_VOLUMES_MAX_MISCLASSIFIED_PERCENT 0.01

static const mirror_case mirror_cases[] = {
    {"planar", "", "ground", 0.05},
    {"shadowmap", "", NULL, 0.5},
    {"psm", "", NULL, 0.5},
    {"volumes", "", NULL, MIRROR_VOLUMES_MAX_MISCLASSIFIED_PERCENT},
    {"volumes", "--mode zfail", NULL, MIRROR_VOLUMES_MAX_MISCLASSIFIED_PERCENT},
    {"volumes", "--silhouette gpu", NULL, MIRROR_VOLUMES_MAX_MISCLASSIFIED_PERCENT},
    {"volumes", "--mode zfail --silhouette gpu", NULL, MIRROR_VOLUMES_MAX_MISCLASSIFIED_PERCENT},
};

static void test_every_technique_within_bound(void **state) {
    (void)state;
    for (size_t i = 0; i < sizeof mirror_cases / sizeof *mirror_cases; i++) {
        const mirror_case *c = &mirror_cases[i];
        char name[64];
        snprintf(name, sizeof name, "mirror_%zu", i);
        dump_frame reference, test;
        unsigned char *heatmap;
        shadowdiff_result r =
            support_measure_dumps(c->program, MIRRORED, "", c->flags, name, &reference, &test, &heatmap);
        if (c->receiver) {
            const shadowdiff_settings settings = {.receiver = c->receiver};
            assert_true(shadowdiff_compare(&reference, &test, &settings, &r, NULL));
            fprintf(stderr, "    %-26s on %s: %ld compared, misclassified %.4f %%\n", name, c->receiver, r.compared,
                    r.misclassified_percent);
        }
        if (!(r.compared > 50000 && r.misclassified_percent <= c->max_misclassified_percent)) {
            fail_msg("%s %s: %.4f %% misclassified of %ld pixels (bound %.2f %%)", c->program, c->flags,
                     r.misclassified_percent, r.compared, c->max_misclassified_percent);
        }
        free(heatmap);
        dump_frame_free(&reference);
        dump_frame_free(&test);
    }
}

/* A model file's own mirrored node (tests/data/mirror_node.gltf: a wedge
 * and, sharing its mesh, its image scaled by -1 in x) against the same two
 * wedges placed by the scene, the mirror as the scene's scale
 * (mirror_node_scene.json, from mirror_wedge.obj): the same picture in the
 * reference (what is surface, its shadows, its colours; object ids differ,
 * one object there being two here), and the volumes, which weigh closed
 * meshes by their winding, within their bound. */
#define NODE_MIRRORED "tests/data/mirror_node.json"
#define NODE_SCENE_MIRRORED "tests/data/mirror_node_scene.json"

static void test_mirrored_node_renders_as_scene_mirror(void **state) {
    (void)state;
    dump_frame node, scene;
    unsigned char *node_rgba = reference_dump(NODE_MIRRORED, "out/test/mirror/reference_node", &node);
    unsigned char *scene_rgba = reference_dump(NODE_SCENE_MIRRORED, "out/test/mirror/reference_node_scene", &scene);
    assert_true(node.width == scene.width && node.height == scene.height);
    long pixels = (long)node.width * node.height, surface = 0, visibility = 0;
    for (long i = 0; i < pixels; i++) {
        surface += (node.ids[i] >= 0) != (scene.ids[i] >= 0);
        visibility += node.ids[i] >= 0 && scene.ids[i] >= 0 && node.visibility[i] != scene.visibility[i];
    }
    long colour = image_compare(node_rgba, scene_rgba, node.width, node.height, SUPPORT_TOLERANCE, NULL);
    fprintf(stderr,
            "    mirrored node against the scene's mirror, of %ld pixels: surface differs on %ld, "
            "visibility on %ld, colour by more than %d/255 on %ld\n",
            pixels, surface, visibility, SUPPORT_TOLERANCE, colour);
    assert_true(surface <= pixels * MIRROR_MAX_DIFFERING);
    assert_true(visibility <= pixels * MIRROR_MAX_DIFFERING);
    assert_true(colour <= pixels * MIRROR_MAX_DIFFERING);
    free(node_rgba);
    free(scene_rgba);
    dump_frame_free(&node);
    dump_frame_free(&scene);
    static const char *const volume_flags[] = {"", "--mode zfail"};
    for (size_t i = 0; i < sizeof volume_flags / sizeof *volume_flags; i++) {
        char name[64];
        snprintf(name, sizeof name, "mirror_node_%zu", i);
        dump_frame reference, test;
        unsigned char *heatmap;
        shadowdiff_result r =
            support_measure_dumps("volumes", NODE_MIRRORED, "", volume_flags[i], name, &reference, &test, &heatmap);
        assert_true(r.compared > pixels / 2);
        assert_true(r.misclassified_percent <= MIRROR_VOLUMES_MAX_MISCLASSIFIED_PERCENT);
        free(heatmap);
        dump_frame_free(&reference);
        dump_frame_free(&test);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_reference_sees_mirror_image),
        cmocka_unit_test(test_every_technique_within_bound),
        cmocka_unit_test(test_mirrored_node_renders_as_scene_mirror),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
