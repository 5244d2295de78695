/* shadowmap: shadow maps with bias and percentage-closer filtering, for
 * spot, directional and point lights.
 *
 * Williams, "Casting curved shadows on curved surfaces", SIGGRAPH 1978:
 * render depth from the light, then test each camera fragment's depth in
 * the light against the map. Reeves, Salesin & Cook, "Rendering antialiased
 * shadows with depth maps", SIGGRAPH 1987: filter the results of the tests
 * (never the depths) over a kernel: percentage-closer filtering.
 *
 * A spot gets a perspective map around its cone (outside it the spot
 * lights nothing: the cone decides there, not the map), a directional
 * light an orthographic map, a point light a cube map of six 90-degree
 * faces, read with seamless filtering so that kernels cross face edges.
 *
 * Each frame the map is fitted to the visible receivers and the casters
 * whose shadow can reach them, even outside the view (the HUD shows its
 * depth range). The machinery, shared with demos/psm.c and
 * demos/cascades.c, is demos/lib/map.h ("The camera pass": the
 * filters, --filter, and the early-out, --no-early-out, key E; "Moment
 * shadow maps"); this file is the uniform placement and the settings.
 *
 * Bias, with its size as a number: constant (a toggle; the point moves
 * towards the light by N map texels of world distance), slope-scaled (a
 * toggle; glPolygonOffset factor in the depth pass, which grows with the
 * caster's depth slope) and normal offset (N texels along the normal,
 * times the sine of the light's angle; 0 by default): texel-sized, they
 * hold at every map size, distance and scene scale. Receiver-plane depth
 * bias (--kernel-depth receiver-plane, the default; Isidoro, GDC 2006)
 * makes each tap of a wide kernel compare the receiver's own depth there:
 * taps at the centre's depth (--kernel-depth centre) speckle flat and
 * slanted receivers with partial acne, which the lit class's MAE sees and
 * misclassified % does not (assets/scenes/flat_boxes*.json,
 * test_shadowmap's test_receiver_plane_removes_partial_acne). Turning
 * the constant or the slope-scaled bias off (keys C, L) also reads the
 * map with one nearest test while the filter is auto, the default, so
 * that acne shows as stripes rather than averaged away (map.h,
 * "The camera pass"); a filter chosen holds.
 *
 * The defaults (poisson, the auto filter with the biases on; constant 1 texel, slope factor 1.5, no normal
 * offset, receiver-plane taps, early-out on) are, in the bench's shadowmap
 * sweep, the setting on the technique's Pareto fronts (misclassified % and
 * lit MAE, every standard scene and the flat boxes) that misclassifies
 * least without darkening lit surfaces and that no textbook configuration
 * beats on both, with no acne at any elevation (test_shadowmap's
 * test_no_acne_at_any_elevation). make report's "Shadow maps" has the
 * figures.
 */
#include <stdio.h>

#include "map.h"

static const char *const shadowmap_overlays[] = {MAP_OVERLAY_NAMES, NULL};

static struct {
    map_settings settings;
    map_renderer *maps;
} shadowmap;

static const flags_param shadowmap_params[] = {
    MAP_PARAMS(shadowmap.settings),
    {"overlay",
     "for lectures: texel boundaries on receivers, the light frustum, the map as an inset fitted to the depths "
     "it holds, texel size on screen, the penumbra radius PCSS estimated",
     GLFW_KEY_V, FLAGS_CHOICE, .index = &shadowmap.settings.overlay, .choices = shadowmap_overlays},
};

static bool shadowmap_init(const render_scene *gpu) {
    shadowmap.maps = map_create(&shadowmap.settings, gpu);
    return shadowmap.maps != NULL;
}

static void shadowmap_destroy(void) {
    map_destroy(shadowmap.maps);
    shadowmap.maps = NULL;
}

static const char *shadowmap_area_light(const scene_light *light, int l) {
    (void)l;
    return map_area_light_text(&shadowmap.settings, light);
}

/* The frame: Williams's two passes, the depth pass per light, then the
 * camera pass comparing each pixel's depth in the light with the map. */
static void shadowmap_render(const technique_frame *f) {
    map_renderer *r = shadowmap.maps;
    const map_settings *settings = &shadowmap.settings;
    /* 1. The camera's depth pre-pass: what is seen. */
    map_begin(r, f);
    /* 2. Each light's map fitted to the visible receivers: the light's
     * own perspective (a spot), its direction (an orthographic map), or a
     * cube map (a point light). */
    for (int l = 0; l < f->gpu->scene->light_count; l++)
        map_fit_light(r, settings, f, l, map_fit_uniform_light);
    /* 3. Depth from each fitted light (layers the cache holds are kept). */
    for (int l = 0; l < f->gpu->scene->light_count; l++)
        map_draw_depth(r, settings, f, l);
    /* 4. Shading: each pixel's depth in the light against the map, the
     * tests filtered over the kernel. */
    map_shade(r, settings, f);
    /* 5. The lecture's overlays. */
    map_draw_overlays(r, settings, f);
}

static void shadowmap_describe(char *out, size_t size) {
    int l;
    if (!map_described_light(shadowmap.maps, &l, out, size))
        return;
    const map_light *m = map_of_light(shadowmap.maps, l);
    char map[64];
    map_size_text(&shadowmap.settings, m, map, sizeof map);
    int n = snprintf(out, size, "light %d: %s, depth range %.3g .. %.3g", l, map, m->near_plane, m->far_plane);
    if (map_filter_moments(map_filter_in_use(&shadowmap.settings)) != MAP_MOMENTS_NONE && n > 0 && (size_t)n < size)
        snprintf(out + n, size - (size_t)n, ", moment blur %.3g texels", m->blur_texels[0]);
    map_describe_filter(&shadowmap.settings, out, size);
    map_describe_storage(shadowmap.maps, l, out, size);
}

/* The sweep: map size x filter x bias (poisson named, auto's choice but
 * where a scene has many lights; the tents, the early-out off, the
 * moment filters; the biases off at the default's disc, --filter poisson,
 * since auto would read them unfiltered), and two configurations popular tutorials use ("label:
 * flags"), so the report shows where our biases stand at the same cost:
 * LearnOpenGL's bias max(0.05 (1 - N.L), 0.005) with 3x3 PCF at 1024
 * (against --map-size 1024 --filter pcf3), and polygon offset (1.25,
 * 1.75) with 3x3 PCF at 2048 (against --filter pcf3); and eight maps a
 * frame at most, which changes a frame only where more lights move
 * (map.h, "Budget"). */
static const char *const shadowmap_bench_configs[] = {
    "",
    "--map-size 1024",
    "--map-size 1024 --filter pcf3",
    "--map-size 2048",
    "--map-size 4096",
    "--filter none",
    "--filter poisson",
    "--filter hw",
    "--filter pcf3",
    "--filter pcf5",
    "--filter pcf5 --no-early-out",
    "--filter tent3",
    "--filter tent3 --map-size 1024",
    "--filter tent3 --map-size 4096",
    "--filter tent5",
    "--filter tent5 --no-early-out",
    "--no-early-out",
    "--kernel-depth centre",
    "--filter vsm",
    "--filter evsm2",
    "--filter evsm4",
    "--filter msm",
    "--normal-texels 1",
    "hard: --soft off",
    "wide pcf (fake soft): --soft off --filter pcf7",
    "--no-slope-bias --filter poisson",
    "--no-constant-bias --no-slope-bias --filter poisson",
    "textbook depth bias: --map-size 1024 --filter pcf3 --kernel-depth centre --no-constant-bias --no-slope-bias "
    "--depth-bias-slope 0.05 --depth-bias-min 0.005",
    "textbook polygon offset: --map-size 2048 --filter pcf3 --kernel-depth centre --no-constant-bias "
    "--slope-factor 1.25 --slope-units 1.75",
    "--shadow-budget 8",
};

const technique shadowmap_technique = {
    .name = "shadowmap",
    .title = "shadow maps (Williams 1978) with bias and PCF (Reeves et al. 1987)",
    .params = shadowmap_params,
    .param_count = (int)(sizeof shadowmap_params / sizeof *shadowmap_params),
    .bench_configs = shadowmap_bench_configs,
    .bench_config_count = (int)(sizeof shadowmap_bench_configs / sizeof *shadowmap_bench_configs),
    .init = shadowmap_init,
    .render = shadowmap_render,
    .destroy = shadowmap_destroy,
    .area_light = shadowmap_area_light,
    .describe = shadowmap_describe,
    .coloured_shadows = true, /* the transmittance maps (map.h, "Translucent casters") */
    /* The lecture picture: the texel boundaries, the frusta and the inset,
     * as the overlay goldens show them. */
    .gallery_config = "--overlay all",
};
