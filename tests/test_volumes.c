/* Stencil shadow volumes against the ray-traced reference, with
 * shadowdiff's fixed rules; each test prints the figures it measured.
 * Volumes are exact hard shadows of the same triangles the reference
 * traces, so the bound is tight: VOLUMES_MAX_MISCLASSIFIED_PERCENT of
 * the compared pixels. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "support.h"

#define VOLUMES_MAX_MISCLASSIFIED_PERCENT 0.01
#define CAMERA_IN_SHADOW "assets/scenes/eye_in_shadow.json"
#define NEAR_PLANE_CUT "assets/scenes/eye_near_shadow.json" /* the eye just outside a volume its near plane cuts */
#define LIGHT_IN_NEAR_PLANE "tests/data/vol_light_in_near_plane.json"
#define HUGE_GROUND "tests/data/vol_huge_ground.json"
#define LIGHT_ABOVE_GROUND "tests/data/vol_light_above_ground.json"
#define STACKED_SLABS "assets/scenes/stacked_300.json"
#define STACKED_MESH "assets/scenes/stacked_10000.json"
/* Of the compared pixels, what the wrapped count reads lit at least. */
#define WRAPPED_MIN_FALSE_LIT_PERCENT 1.0

static shadowdiff_result measure(const char *scene, const char *flags, const char *name) {
    return support_measure("volumes", scene, "", flags, name);
}

/* At `size` ("--size WxH", or "" for 640x360). */
static void assert_within_bound_at(const char *scene, const char *size, const char *flags, const char *name) {
    shadowdiff_result r = support_measure("volumes", scene, size, flags, name);
    assert_true(r.compared > 50000);
    assert_true(r.misclassified_percent <= VOLUMES_MAX_MISCLASSIFIED_PERCENT);
}

static void assert_within_bound(const char *scene, const char *flags, const char *name) {
    assert_within_bound_at(scene, "", flags, name);
}

/* Closed (simple, bunny), open (teapot, spider) and open non-manifold
 * (wuson) casters, under spot, point and directional lights, with every
 * counting mode and silhouette path (the geometry shader's sides, for
 * open meshes too, with the CPU's caps for z-fail). */
static void test_every_mesh_every_mode_within_bound(void **state) {
    (void)state;
    static const char *const scenes[] = {"simple", "bunny", "teapot", "spider", "wuson"};
    static const char *const configs[] = {"", "--mode zpass", "--mode zfail", "--silhouette gpu",
                                          "--mode zfail --silhouette gpu"};
    enum { CONFIG_COUNT = sizeof configs / sizeof *configs };
    /* Under the sanitizers every support_sweep_stride()th pair, spread
     * over every scene and config. */
    SUPPORT_SWEEPABLE(CONFIG_COUNT);
    for (size_t pair = 0; pair < sizeof scenes / sizeof *scenes * CONFIG_COUNT;
         pair += (size_t)support_sweep_stride()) {
        size_t i = pair / CONFIG_COUNT, k = pair % CONFIG_COUNT;
        char path[256], name[64];
        snprintf(path, sizeof path, "assets/scenes/%s.json", scenes[i]);
        snprintf(name, sizeof name, "%s_%zu", scenes[i], k);
        assert_within_bound(path, configs[k], name);
    }
}

/* Of the surface pixels of `scene`, the share (percent) whose visibility
 * differs between the volumes drawn with `flags[0]` and with `flags[1]`;
 * `name` names the dumps' folders. */
static double visibility_differ_percent(const char *scene, const char *const flags[2], const char *name) {
    char dirs[2][256];
    dump_frame frames[2];
    for (int k = 0; k < 2; k++) {
        snprintf(dirs[k], sizeof dirs[k], "out/test/volumes/%s_%d", name, k);
        assert_int_equal(support_dump("volumes", scene, flags[k], dirs[k]), 0);
        assert_true(dump_read(&frames[k], dirs[k]));
    }
    long surface = 0, differ = 0;
    for (long p = 0; p < (long)frames[0].width * frames[0].height; p++) {
        surface += frames[0].visibility[p] >= 0;
        differ += frames[0].visibility[p] != frames[1].visibility[p];
    }
    assert_true(surface > 0);
    double percent = 100.0 * (double)differ / (double)surface;
    printf("    %-24s [%s] against [%s]: visibility differs on %ld of %ld (%.4f %%)\n", name, flags[1], flags[0],
           differ, surface, percent);
    dump_frame_free(&frames[0]);
    dump_frame_free(&frames[1]);
    return percent;
}

/* GPU silhouettes serve open and non-manifold meshes too, with the CPU
 * path's decisions (demos/lib/volume_silhouette.h): on teapot, spider and
 * wuson no CPU volume is built for the sides (the HUD's count), and in
 * z-pass and z-fail the visibility differs from the CPU path's on at most
 * VOLUMES_MAX_MISCLASSIFIED_PERCENT of the surface pixels (the few that
 * differ lie on the mesh itself, where the shader's sides, other triangles
 * over the same quads, round the depth otherwise (see
 * volume_silhouette.h), as they do on closed meshes too). */
static void test_gpu_silhouettes_of_open_meshes_match_cpu(void **state) {
    (void)state;
    static const char *const scenes[] = {"teapot", "spider", "wuson"};
    static const char *const modes[] = {"", "--mode zfail"};
    for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++) {
        char path[256];
        snprintf(path, sizeof path, "assets/scenes/%s.json", scenes[i]);
        const char *line = support_verbose_line("volumes", path, "--silhouette gpu", "volumes built ");
        assert_non_null(line);
        assert_true(strncmp(line, "volumes built 0, kept 0;", 24) == 0);
        for (size_t k = 0; k < sizeof modes / sizeof *modes; k++) {
            char flags[2][128], name[64];
            for (int gpu = 0; gpu < 2; gpu++)
                snprintf(flags[gpu], sizeof flags[gpu], "%s --silhouette %s", modes[k], gpu ? "gpu" : "cpu");
            snprintf(name, sizeof name, "%s_%zu", scenes[i], k);
            const char *const pair[2] = {flags[0], flags[1]};
            assert_true(visibility_differ_percent(path, pair, name) <= VOLUMES_MAX_MISCLASSIFIED_PERCENT);
        }
    }
}

/* Volumes trimmed past the light's reach (--extrude reach) stay within
 * the bound: under ranged lights (the trim's case), closed and open
 * casters, and with the camera in a shadow (auto takes z-fail there). Not
 * bit for bit the infinite volumes' picture: a shadow edge's pixel may
 * flip by the rounding of the shorter sides' depth. */
static void test_trimmed_within_bound(void **state) {
    (void)state;
    assert_within_bound("tests/data/range_lights.json", "--extrude reach", "range_lights_trimmed");
    assert_within_bound("assets/scenes/bunny.json", "--extrude reach", "bunny_trimmed");
    assert_within_bound("assets/scenes/teapot.json", "--extrude reach --mode zfail", "teapot_trimmed_zfail");
    assert_within_bound(CAMERA_IN_SHADOW, "--extrude reach", "camera_in_shadow_trimmed");
}

/* With the camera inside a shadow volume, z-fail (forced or chosen by
 * auto) stays exact; z-pass starts every count one off and fails, which
 * shows the test can see the failure. */
static void test_camera_in_shadow(void **state) {
    (void)state;
    assert_within_bound(CAMERA_IN_SHADOW, "", "camera_in_shadow_auto");
    assert_within_bound(CAMERA_IN_SHADOW, "--mode zfail", "camera_in_shadow_zfail");
    assert_within_bound(CAMERA_IN_SHADOW, "--silhouette gpu", "camera_in_shadow_gpu");
    shadowdiff_result zpass = measure(CAMERA_IN_SHADOW, "--mode zpass", "camera_in_shadow_zpass");
    assert_true(zpass.misclassified_percent > 10 * VOLUMES_MAX_MISCLASSIFIED_PERCENT);
}

/* --mode eye-count: z-pass from the number of volumes that hold the eye,
 * counted on the CPU. Exact with the eye in a shadow; where the eye is
 * just outside a volume that the near plane cuts, exact while depth clamp
 * counts the faces before the near plane, and wrong on part of the screen
 * without it (--no-depth-clamp), where z-fail stays exact: the lecture's
 * reason for z-fail. And it is z-pass where the eye is in no shadow. */
static void test_eye_count(void **state) {
    (void)state;
    assert_within_bound(CAMERA_IN_SHADOW, "--mode eye-count", "eye_count_in_shadow");
    assert_within_bound(CAMERA_IN_SHADOW, "--mode eye-count --no-depth-clamp", "eye_count_in_shadow_clipped");
    assert_within_bound(NEAR_PLANE_CUT, "--mode eye-count", "eye_count_near");
    assert_within_bound(NEAR_PLANE_CUT, "--mode zfail --no-depth-clamp", "zfail_near_clipped");
    shadowdiff_result cut = measure(NEAR_PLANE_CUT, "--mode eye-count --no-depth-clamp", "eye_count_near_clipped");
    assert_true(cut.misclassified_percent > 10 * VOLUMES_MAX_MISCLASSIFIED_PERCENT);
    assert_within_bound("assets/scenes/teapot.json", "--mode eye-count", "eye_count_teapot");
    const char *line = support_verbose_line("volumes", CAMERA_IN_SHADOW, "--mode eye-count", "volumes: light 0:");
    assert_non_null(line);
    assert_non_null(strstr(line, "from the eye inside 1;"));
    printf("    eye in a shadow: exact; near plane cutting a volume, depth clamp off: %.1f %% misclassified\n",
           cut.misclassified_percent);
}

/* --mode zp-plus (ZP+, demos/lib/volume_near.h): z-pass from each
 * pixel's count on the near plane, drawn from the light, the volumes
 * clipped there. With the eye in a shadow: a closed box with the light
 * behind the near plane and in front of it (the projection's winding
 * flips, which the closed rule's culling follows), a closed real model,
 * and an open non-manifold one under a sun (every triangle counts), each
 * also counted in the float target; and where the near plane cuts a volume
 * the eye is outside of, eye-count's failure without depth clamp. Each is
 * exact against the reference and within VOLUMES_MAX_MISCLASSIFIED_PERCENT
 * of z-fail's decisions (the count's edges on the near plane are drawn by
 * two routes, which may round apart); z-pass fails on every one, which
 * shows the scenes put the eye in a shadow. A light in the near plane's
 * plane, from which nothing projects onto it, counts as auto does: the
 * caster the eye sees in shadow by z-fail, exact. */
static void test_zp_plus(void **state) {
    (void)state;
    static const char *const scenes[] = {CAMERA_IN_SHADOW, "tests/data/vol_eye_in_shadow_light_ahead.json",
                                         "tests/data/vol_eye_in_bunny_shadow.json",
                                         "tests/data/vol_eye_in_wuson_shadow.json"};
    for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++) {
        char name[64];
        snprintf(name, sizeof name, "zp_plus_%zu", i);
        assert_within_bound(scenes[i], "--mode zp-plus", name);
        snprintf(name, sizeof name, "zp_plus_float_%zu", i);
        assert_within_bound(scenes[i], "--mode zp-plus --counter float", name);
        snprintf(name, sizeof name, "zp_plus_against_zfail_%zu", i);
        const char *const pair[2] = {"--mode zfail", "--mode zp-plus"};
        assert_true(visibility_differ_percent(scenes[i], pair, name) <= VOLUMES_MAX_MISCLASSIFIED_PERCENT);
        snprintf(name, sizeof name, "zp_plus_zpass_%zu", i);
        assert_true(measure(scenes[i], "--mode zpass", name).misclassified_percent >
                    10 * VOLUMES_MAX_MISCLASSIFIED_PERCENT);
    }
    assert_within_bound(NEAR_PLANE_CUT, "--mode zp-plus", "zp_plus_near_plane_cut");
    const char *line = support_verbose_line("volumes", CAMERA_IN_SHADOW, "--mode zp-plus", "volumes: light 0:");
    assert_non_null(line);
    assert_non_null(strstr(line, "z-fail, 1 from the near plane's count;"));
    assert_within_bound(LIGHT_IN_NEAR_PLANE, "--mode zp-plus", "zp_plus_light_in_near_plane");
    line = support_verbose_line("volumes", LIGHT_IN_NEAR_PLANE, "--mode zp-plus", "volumes: light 0:");
    assert_non_null(line);
    assert_non_null(strstr(line, "1 z-fail, 0 from the near plane's count;"));
}

/* A point light inside a closed caster, or in one of its faces: the
 * caster blocks everything outside it (the reference agrees), so it is
 * weighed as an open mesh for that light, and the triangles edge-on to
 * the light weigh 0 (demos/lib/volume_mesh.h). Weighed as closed, such a
 * caster shadows nearly everything it does not; the open rule alone leaves
 * the edge-on triangles' far caps, round the light, covering the screen;
 * an empty volume must not end the run on a GL error. The camera of the
 * face's scene
 * is below the face: a surface in the light's plane is lit by nothing,
 * its shadow a tie. */
static void test_light_inside_caster(void **state) {
    (void)state;
    static const char *const scenes[] = {"vol_light_inside_box", "vol_light_inside_bunny", "vol_light_on_box_face"};
    static const char *const configs[] = {"", "--silhouette gpu"};
    for (size_t i = 0; i < sizeof scenes / sizeof *scenes; i++) {
        for (size_t k = 0; k < sizeof configs / sizeof *configs; k++) {
            char path[256], name[64];
            snprintf(path, sizeof path, "tests/data/%s.json", scenes[i]);
            snprintf(name, sizeof name, "%s_%zu", scenes[i] + strlen("vol_"), k);
            assert_within_bound(path, configs[k], name);
        }
    }
}

/* A closed box whose -z face holds its top edge's ends 0.2 weld cells
 * above the top face's, which has a sliver along that edge 1.5 cells
 * wide: the weld pairs the edge, but the geometry shader judged the
 * sliver from the face's ends and found it facing away from the low
 * light, an unmatched side, where the CPU path is exact. Such a mesh
 * counts as open (mesh_edges_build_welded), so every path is exact. */
static void test_welded_sliver(void **state) {
    (void)state;
    static const char *const configs[] = {"", "--silhouette gpu", "--mode zfail --silhouette gpu"};
    for (size_t k = 0; k < sizeof configs / sizeof *configs; k++) {
        char name[64];
        snprintf(name, sizeof name, "welded_sliver_%zu", k);
        assert_within_bound("tests/data/vol_welded_sliver.json", configs[k], name);
    }
}

/* A 1000-object city from one street, under its sun (the lamps in view
 * misclassify nothing), at 1280x720 (a large window's picture) and at
 * 640x360, within the volumes' bound against the exact reference. */
static void test_city_within_bound(void **state) {
    (void)state;
    static const struct {
        const char *size, *flags, *name;
    } cases[] = {
        {"--size 1280x720", "", "city_1000_1280"},
        {"--size 1280x720", "--silhouette gpu", "city_1000_1280_gpu"},
        {"", "", "city_1000_640"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++)
        assert_within_bound_at("assets/scenes/city_1000.json", cases[i].size, cases[i].flags, cases[i].name);
}

/* 300 casters stacked along one line to the light: counts beyond 255 wrap
 * in the 8-bit stencil and still come out right. */
static void test_300_overlapping_casters(void **state) {
    (void)state;
    assert_within_bound("tests/data/volumes_300_casters.json", "", "casters_300_auto");
    assert_within_bound("tests/data/volumes_300_casters.json", "--mode zfail", "casters_300_zfail");
}

/* Volumes deeper than the 8-bit stencil (demos/lib/volume_wide.h): 256
 * wide slabs under 44 narrow ones (the ground round the narrow ones'
 * shadow in exactly 256 volumes), and one open mesh of 10,000 stacked
 * triangles (bands of multiples of 256, up to 10,000 deep), counted wide
 * within the bound in every mode; with --counter stencil the wrapped
 * stencil reads those bands lit, far past the bound, which shows the test
 * can fail. The mesh's every frame draws 10,000 volumes over the view:
 * the quick tier counts it in the default mode alone, the slabs in every
 * mode and wrapped (the same wide count, the same proof that a wrapped
 * count fails), and the whole tier adds the mesh's z-fail with GPU
 * silhouettes and its wrapped count. */
static void test_deeper_than_stencil(void **state) {
    (void)state;
    assert_within_bound(STACKED_SLABS, "", "stacked_300_auto");
    assert_within_bound(STACKED_SLABS, "--mode zfail", "stacked_300_zfail");
    assert_within_bound(STACKED_SLABS, "--silhouette gpu", "stacked_300_gpu");
    assert_within_bound(STACKED_MESH, "", "stacked_10000_auto");
    shadowdiff_result slabs = measure(STACKED_SLABS, "--counter stencil", "stacked_300_wrapped");
    assert_true(slabs.false_lit_percent > WRAPPED_MIN_FALSE_LIT_PERCENT);
    if (support_sweep_stride() > 1)
        return;
    assert_within_bound(STACKED_MESH, "--mode zfail --silhouette gpu", "stacked_10000_zfail_gpu");
    shadowdiff_result layers = measure(STACKED_MESH, "--counter stencil", "stacked_10000_wrapped");
    assert_true(layers.false_lit_percent > WRAPPED_MIN_FALSE_LIT_PERCENT);
}

/* A ground 1e5 across, two triangles, seen from 10 units away (the stress
 * case huge_ground_1e5_spot): against the depth the rasterizer
 * interpolates from corners 5e4 away, the shadow edges on it moved by a
 * pixel or two; against its exact depth (demos/lib/volume_receivers.h)
 * they hold in every mode; with --no-exact-depth they exceed the bound,
 * which shows the test can fail. */
static void test_huge_ground(void **state) {
    (void)state;
    assert_within_bound(HUGE_GROUND, "", "huge_ground_auto");
    assert_within_bound(HUGE_GROUND, "--mode zfail --silhouette gpu", "huge_ground_zfail_gpu");
    shadowdiff_result rasterized = measure(HUGE_GROUND, "--no-exact-depth", "huge_ground_rasterized");
    assert_true(rasterized.misclassified_percent > VOLUMES_MAX_MISCLASSIFIED_PERCENT);
}

/* A point light 1e-3 above the ground (the stress case
 * light_above_ground_1e-3_point): the box's shadow is a wedge to the
 * ground's edge, cast by the box's bottom 1e-3, and the volume's lower
 * sides lie within 1e-3 of the ground's plane. Volumes are built from the
 * geometry, so they keep it within the bound, CPU and GPU silhouettes
 * alike, where the shadow maps, whose texels are far larger than the
 * sliver seen from the light, lose it. */
static void test_light_above_ground(void **state) {
    (void)state;
    assert_within_bound(LIGHT_ABOVE_GROUND, "", "light_above_ground_auto");
    assert_within_bound(LIGHT_ABOVE_GROUND, "--silhouette gpu", "light_above_ground_gpu");
}

/* Degenerate triangles and NaN vertices are dropped with a warning naming
 * the mesh; the rest still casts exactly. */
static void test_bad_triangles_skipped(void **state) {
    (void)state;
    char err[16384], command[1024];
    snprintf(command, sizeof command,
             "%s --backend egl --size 640x360 --scene tests/data/volumes_bad_triangles.json --frames 1",
             support_program("volumes"));
    assert_int_equal(support_run(command, err, sizeof err), 0);
    assert_non_null(strstr(err, "mesh_degenerate_triangles.obj"));
    assert_non_null(strstr(err, "mesh_nan_vertex.obj"));
    assert_within_bound("tests/data/volumes_bad_triangles.json", "", "bad_triangles");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_mesh_every_mode_within_bound),
        cmocka_unit_test(test_gpu_silhouettes_of_open_meshes_match_cpu),
        cmocka_unit_test(test_camera_in_shadow),
        cmocka_unit_test(test_trimmed_within_bound),
        cmocka_unit_test(test_light_inside_caster),
        cmocka_unit_test(test_welded_sliver),
        cmocka_unit_test(test_city_within_bound),
        cmocka_unit_test(test_300_overlapping_casters),
        cmocka_unit_test(test_deeper_than_stencil),
        cmocka_unit_test(test_eye_count),
        cmocka_unit_test(test_zp_plus),
        cmocka_unit_test(test_huge_ground),
        cmocka_unit_test(test_light_above_ground),
        cmocka_unit_test(test_bad_triangles_skipped),
    };
    return cmocka_run_group_tests_name("shadow volumes against the reference", tests, NULL, NULL);
}
