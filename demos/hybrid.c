/* hybrid: a shadow map, with shadow rays where the map is unsure.
 *
 * "Shadows in production: often use shadow maps, ray casting as fallback
 * in case of robustness issues." The map decides where it is sure; a
 * ray decides the rest (as Hertel, Hormann & Westermann, "A Hybrid GPU
 * Rendering Pipeline for Alias-Free Hard Shadows", Eurographics 2009
 * Areas Papers, which bound the rays with a conservative map).
 *
 * Each frame is shadowmap's (its uniform fit, filter, biases and PCSS:
 * the same flags), with one change in the camera pass (demos/lib/map.h,
 * "Rays"): a pixel is unsure where the map's filter is neither 0 nor 1
 * (a hard light's kernel taps disagree; PCSS found a blocker but not an
 * umbra), where PCSS says umbra but its blocker search, over the whole
 * cone from the pixel to the light, found a tap unblocked, where a hard
 * light's kernel says lit with the full bias but not with a share of its
 * constant bias (a caster within the bias of its receiver), and, under
 * an area light, where PCSS found no blocker but a caster's box is near
 * the cone from the pixel to the light's disk (its search taps miss thin
 * casters). Shadow rays from the visible point,
 * against the casters' triangles (common/data/bvh.h, in a texture on the
 * GPU), decide the unsure pixels: one to a hard light, exact; an area
 * light's samples as the reference takes them for that pixel (the same
 * points, --ray-samples of them), stopping early where the first ones
 * agree. Everywhere else the map's answer stands. Every tap of the kernel
 * is read (the early-out applies to --rays off alone, the map by
 * itself). --rays all traces every pixel, the plain ray tracer whose
 * cost the map spares. The overlay "unsure" tints the pixels the map
 * could not decide.
 *
 * Translucent casters (glTF's BLEND): the map's transmittance map colours
 * the sure pixels (map.h, "Translucent casters"); a hard light's pixel
 * within a texel of a pane, or an area light's whose cone meets a pane's
 * box, is unsure, and its rays filter their light through the panes as
 * the reference's do.
 *
 * The casters' hierarchy is built once, at init: objects do not move.
 */
#include <stdio.h>
#include <stdlib.h>

#include "map.h"

static const char *const hybrid_overlays[] = {MAP_OVERLAY_NAMES, MAP_RAYS_OVERLAY_NAMES, NULL};
/* --rays, the default first, and what each is in map_rays. */
static const char *const hybrid_rays[] = {"unsure", "off", "all", NULL};
static const map_rays hybrid_ray_modes[] = {MAP_RAYS_UNSURE, MAP_RAYS_OFF, MAP_RAYS_ALL};
/* --ray-samples, the default (the reference's count) first: powers of 4. */
static const char *const hybrid_ray_samples[] = {"256", "64", "1024", NULL};

static struct {
    map_settings settings;
    int rays;        /* choice: hybrid_rays */
    int ray_samples; /* choice: hybrid_ray_samples */
    map_renderer *maps;
    bvh casters;         /* every casting triangle, for the rays */
    bvh_gpu casters_gpu; /* the same, in a texture */
} hybrid = {.settings.ray_overlays = true};

static const flags_param hybrid_params[] = {
    MAP_PARAMS(hybrid.settings),
    {"rays", "shadow rays: where the map is unsure, off (the map alone), or at every pixel (a ray tracer)",
     GLFW_KEY_R, FLAGS_CHOICE, .index = &hybrid.rays, .choices = hybrid_rays},
    {"ray-samples",
     "an area light's rays at an unsure pixel, the reference's points for it (256, its count, by default); a pixel "
     "stops after " FLAGS_TEXT(MAP_RAY_FIRST_SAMPLES) " where they all get through, after " FLAGS_TEXT(
         MAP_RAY_BLOCKED_SAMPLES) " where they are all blocked",
     GLFW_KEY_N, FLAGS_CHOICE, .index = &hybrid.ray_samples, .choices = hybrid_ray_samples},
    {"overlay",
     "for lectures: the map's overlays (see shadowmap), and the pixels where the map is unsure, which rays decide",
     GLFW_KEY_V, FLAGS_CHOICE, .index = &hybrid.settings.overlay, .choices = hybrid_overlays},
};

static bool hybrid_init(const render_scene *gpu) {
    hybrid.settings.rays = hybrid_ray_modes[hybrid.rays];
    hybrid.maps = map_create(&hybrid.settings, gpu);
    if (!hybrid.maps || !bvh_build(gpu->scene, "hybrid", &hybrid.casters) ||
        !bvh_gpu_upload(&hybrid.casters_gpu, &hybrid.casters, "hybrid"))
        return false;
    map_trace_with(hybrid.maps, &hybrid.casters_gpu);
    return true;
}

static void hybrid_destroy(void) {
    map_destroy(hybrid.maps);
    hybrid.maps = NULL;
    bvh_gpu_destroy(&hybrid.casters_gpu);
    bvh_free(&hybrid.casters);
}

static const char *hybrid_area_light(const scene_light *light, int l) {
    (void)l;
    return map_area_light_text(&hybrid.settings, light);
}

/* The frame: shadowmap's passes, the camera pass tracing where the map
 * is unsure. */
static void hybrid_render(const technique_frame *f) {
    map_renderer *r = hybrid.maps;
    map_settings *settings = &hybrid.settings;
    /* 1. The camera's depth pre-pass: what is seen. */
    map_begin(r, f);
    /* 2. Each light's map fitted to the visible receivers, as
     * shadowmap's. */
    for (int l = 0; l < f->gpu->scene->light_count; l++)
        map_fit_light(r, settings, f, l, map_fit_uniform_light);
    /* 3. Depth from each fitted light. */
    for (int l = 0; l < f->gpu->scene->light_count; l++)
        map_draw_depth(r, settings, f, l);
    /* 4. Shading: the map where its kernel's taps agree, a shadow ray
     * where they do not. */
    settings->rays = hybrid_ray_modes[hybrid.rays];
    settings->ray_samples = atoi(hybrid_ray_samples[hybrid.ray_samples]);
    map_shade(r, settings, f);
    /* 5. The lecture's overlays. */
    map_draw_overlays(r, settings, f);
}

static bool hybrid_counted_rays(technique_rays *out) { return map_rays_counted(hybrid.maps, out); }

/* The HUD: the map, the rays' mode, and with the counters (F3,
 * --verbose) the share of the pixels traced and the rays. */
static void hybrid_describe(char *out, size_t size) {
    int l;
    if (!map_described_light(hybrid.maps, &l, out, size))
        return;
    const map_light *m = map_of_light(hybrid.maps, l);
    char map[64], counted[128] = "counted with F3 or --verbose";
    map_size_text(&hybrid.settings, m, map, sizeof map);
    technique_rays rays;
    if (hybrid_counted_rays(&rays) && rays.pixels > 0)
        snprintf(counted, sizeof counted, "%ld of %ld pixels traced (%.2f %%), %ld rays, %ld marked", rays.traced,
                 rays.pixels, 100.0 * (double)rays.traced / (double)rays.pixels, rays.rays, rays.marked);
    snprintf(out, size, "light %d: %s; rays %s (%s), %d casting triangles", l, map, hybrid_rays[hybrid.rays], counted,
             hybrid.casters.triangle_count);
    map_describe_filter(&hybrid.settings, out, size);
    map_describe_storage(hybrid.maps, l, out, size);
}

/* The sweep: the map alone, the hybrid at three map sizes, and the ray
 * tracer the map spares. */
static const char *const hybrid_bench_configs[] = {
    "", "--map-size 1024", "--map-size 4096", "map alone: --rays off", "every pixel: --rays all",
};

const technique hybrid_technique = {
    .name = "hybrid",
    .title = "shadow maps with shadow rays where the map is unsure (Hertel et al. 2009)",
    .params = hybrid_params,
    .param_count = (int)(sizeof hybrid_params / sizeof *hybrid_params),
    .bench_configs = hybrid_bench_configs,
    .bench_config_count = (int)(sizeof hybrid_bench_configs / sizeof *hybrid_bench_configs),
    .init = hybrid_init,
    .render = hybrid_render,
    .destroy = hybrid_destroy,
    .area_light = hybrid_area_light,
    .describe = hybrid_describe,
    .rays = hybrid_counted_rays,
    .gallery_config = "--overlay unsure",
    .coloured_shadows = true, /* the transmittance maps, and rays through the panes */
};
