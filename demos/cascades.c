/* cascades: cascaded shadow maps for directional lights.
 *
 * A directional light's one map spans everything the view sees: near the
 * viewer a texel covers many pixels, far away many texels share a pixel
 * (perspective aliasing). Cascades cut the view frustum into slices by
 * depth and give each slice its own orthographic map, layer k of one
 * MAP_ARRAY (demos/lib/map.h, "Array maps"), so near slices
 * get small texels (Engel, "Cascaded shadow maps", ShaderX5 2006; Dimitrov,
 * "Cascaded shadow maps", NVIDIA 2007). The camera pass reads the layer
 * whose slice holds the fragment's view depth and, over the last --blend
 * of a slice, the next one at a share of the pixels rising to all of them
 * (dithered, one layer filtered a pixel), so the change of texel size
 * shows no seam.
 *
 * Where the slices end (--splits; cascades_fit_array says how):
 *   sdsm       (the default) Lauritzen, Salvi & Lefohn, "Sample
 *              distribution shadow maps", I3D 2011: the logarithmic split
 *              of the depth range the camera actually sees, not near..far;
 *   practical  Zhang, Sun, Xu & Lun, "Parallel-split shadow maps for
 *              large-scale virtual environments", VRCIA 2006: lambda of
 *              the logarithmic split of near..far plus 1 - lambda of the
 *              uniform one (--lambda, 0.9 by default);
 *   uniform    slices of equal depth: far ones get the texels;
 *   log        equal ratios far / near: the split that keeps a texel's
 *              size on screen the same in every slice.
 *
 * Each cascade's box (cascades_slice_box, in demos/lib/cascades_fit.c with
 * the rest of the fit's geometry) is fitted in the light's view to its
 * slice and the receivers in it, and deepened towards the light to every
 * caster that overlaps it. --stabilize (key Z) holds its texel grid
 * while the camera moves: steps (the default: the corner on whole texels,
 * size and heading changing only in steps), sphere (Valient, "Stable
 * rendering of cascaded shadow maps", ShaderX6 2008: the slice's bounding
 * sphere) or off (shadow edges crawl).
 *
 * --map-size gives each cascade's size; auto, the default, is
 * CASCADES_DEFAULT_SIZE (times map_auto_finer for a hard sun that
 * reaches a cut-out caster). Spot and point lights get shadowmap's
 * uniform fit (cascades_fit). For lectures (--overlay): shadowmap's
 * overlays, and "cascades": each cascade's receivers tinted in its colour
 * (the blend band mixing two), a key to the colours with each slice's
 * view depths, and every layer as an inset along the bottom, fitted to
 * the depths it holds (a spot's or point light's map as its inset); the
 * HUD line gives the splits.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cascades_fit.h"
#include "map.h"

/* --map-size auto: each cascade's size. Four cascades of 1024 hold the
 * texels of one 2048 map, the size shadowmap's auto gives the standard
 * scenes at the bench's size (test_shadowmap's test_map_size_from_need),
 * so the comparison is at equal memory and depth-pass fill. */
#define CASCADES_DEFAULT_SIZE 1024
/* The logarithmic split's weight in the practical scheme: 0.9 spends
 * fewer texels far away than Zhang et al.'s 0.75, which misclassifies more
 * on long_view (stabilised by steps) and on city_1000 walked; log alone
 * spends its first slice on the metres in front of the near plane. */
#define CASCADES_DEFAULT_LAMBDA 0.9f
/* The far fraction of a slice blended into the next layer. */
#define CASCADES_DEFAULT_BLEND 0.1f
/* Room at the box's edge beyond the kernel's reach: the snapped corner
 * moves the slice's sphere by up to a texel inside the box. */
#define CASCADES_SNAP_TEXELS 1.0f
/* Stabilised sdsm: the seen range's ends are widened to powers of
 * 2^(1 / RANGE_STEPS) (the far end at most that factor farther, the near
 * one at most that factor nearer), so that walking moves the splits only where an end crosses a
 * step (test_shimmer's test_stabilised_cascades_stand_still). */
#define CASCADES_RANGE_STEPS 4.0f

static const char *const cascades_counts[] = {"4", "5", "6", "7", "8", "1", "2", "3", NULL};
static const char *const cascades_schemes[] = {"sdsm", "practical", "uniform", "log", NULL};
enum { CASCADES_SDSM, CASCADES_PRACTICAL, CASCADES_UNIFORM, CASCADES_LOG };
/* In cascades_stabilize's order (cascades_fit.h), and what the HUD says of each. */
static const char *const cascades_stabilizers[] = {"steps", "sphere", "off", NULL};
static const char *const cascades_stabilized[] = {", stabilized by steps", ", stabilized by the sphere", ""};
static const char *const cascades_overlays[] = {MAP_OVERLAY_NAMES, MAP_ARRAY_OVERLAY_NAMES, NULL};

static struct {
    map_settings settings;
    int count, scheme, stabilize; /* choices: cascades_counts, cascades_schemes, cascades_stabilizers */
    float lambda, blend;          /* 0: the defaults */
    bool no_blend;
    bool grazed[SCENE_MAX_LIGHTS]; /* the last fit's: the light grazed what is seen (cascades_grazing) */
    map_renderer *maps;
} cascades = {.settings.array_overlays = true};

static const flags_param cascades_params[] = {
    {"cascades", "how many slices of the view, each with its own map", GLFW_KEY_N, FLAGS_CHOICE,
     .index = &cascades.count, .choices = cascades_counts},
    {"splits",
     "where slices end: sdsm (the seen depth range, Lauritzen et al. 2011), practical (Zhang et al. 2006), "
     "uniform, log",
     GLFW_KEY_S, FLAGS_CHOICE, .index = &cascades.scheme, .choices = cascades_schemes},
    {"lambda", "practical splits: the logarithmic split's weight (0: 0.9; uniform is --splits uniform)", 0,
     FLAGS_NUMBER, .number = &cascades.lambda, .fallback = CASCADES_DEFAULT_LAMBDA, .min = 0, .max = 1},
    {"blend", "the far fraction of a slice blended into the next cascade (0: 0.1)", 0, FLAGS_NUMBER,
     .number = &cascades.blend, .fallback = CASCADES_DEFAULT_BLEND, .min = 0, .max = 1},
    {"blend", "a hard switch between cascades: a seam where the texel size changes", GLFW_KEY_B, FLAGS_TOGGLE,
     .disabled = &cascades.no_blend},
    {"stabilize",
     "steps: tight boxes whose grid, size and heading change in steps; sphere: the slice's sphere (Valient "
     "2008); off: shadow edges crawl as the camera moves or turns",
     GLFW_KEY_Z, FLAGS_CHOICE, .index = &cascades.stabilize, .choices = cascades_stabilizers},
    MAP_PARAMS(cascades.settings),
    {"overlay", "for lectures: shadowmap's overlays, and each cascade tinted, with a key, and its map as an inset",
     GLFW_KEY_V, FLAGS_CHOICE, .index = &cascades.settings.overlay, .choices = cascades_overlays},
};

static float cascades_or(float value, float fallback) { return value != 0 ? value : fallback; }

/* ---- the fit ---- */

/* Whether light `light` grazes what the view sees: more of the library's
 * samples of the receivers (map_light_samples) left out as edge-on
 * to it than measured, the rule by which --map-size auto gives a grazing
 * sun its largest map. Seen from such a light the ground is a thin
 * sliver, which a box the size of the slice's sphere gives one row of
 * texels (a sun a fraction of a degree up: the stress suite's
 * grazing_0.1_directional and grazing_0.5_directional), so it gets the
 * steps' boxes, fitted to the receivers, instead. */
static bool cascades_grazing(const technique_frame *f, int light) {
    map_samples measured = map_light_samples(cascades.maps, f, light);
    return measured.grazing > measured.count;
}

/* The directional light's cascades: the splits, then each layer's box.
 * The splits end at the camera's far plane or the receivers' reach,
 * whichever is nearer. sdsm splits the range of view depths the frame's
 * receiver points span (the corners of the visible receivers' boxes
 * clipped to the view, which bound every visible receiver fragment), so
 * no slice is spent on air in front of the nearest receiver (walking the
 * city, the first practical slice can hold no pixel) or beyond the
 * farthest. The paper reduces the depth pre-pass on the GPU; the points
 * are already on the CPU, and reducing the depth buffer would stall the
 * fit on the pre-pass, or make the maps depend on the frame before, for
 * little: the points' range agrees with the pixels' at its near end and
 * can lie farther at its far end, which moves the first of four splits by
 * only its fourth root. make report's "Cascades against one map and the
 * warps, on one ruler" compares the schemes over the frames of a walk and
 * a yaw: the comparison that makes sdsm the default. */
static bool cascades_fit_array(const technique_frame *f, int light, map_light *m) {
    const scene_light *l = &f->gpu->scene->lights[light];
    const scene_camera *camera = &f->gpu->scene->camera;
    /* Only the sphere's boxes need the grazing check (WARP_SAMPLE_COUNT rays a frame). */
    cascades_stabilize stabilize = (cascades_stabilize)cascades.stabilize;
    cascades.grazed[light] = stabilize == CASCADES_STABILIZE_SPHERE && cascades_grazing(f, light);
    if (cascades.grazed[light])
        stabilize = CASCADES_STABILIZE_STEPS;
    int count = atoi(cascades_counts[cascades.count]);
    float near_plane = camera->near_plane;
    float far_plane = fminf(camera->far_plane, cascades_receivers_reach(f->gpu->scene, f->view->eye));
    float lambda = cascades.scheme == CASCADES_UNIFORM     ? 0
                   : cascades.scheme == CASCADES_PRACTICAL ? cascades_or(cascades.lambda, CASCADES_DEFAULT_LAMBDA)
                                                           : 1;
    if (cascades.scheme == CASCADES_SDSM) {
        float seen_near, seen_far;
        if (!cascades_seen_depths(f->view, f->skips->receivers, f->skips->receiver_count, near_plane, far_plane,
                                  &seen_near, &seen_far))
            return false;
        if (stabilize != CASCADES_STABILIZE_OFF) {
            /* Stabilised, the seen range too changes only in steps. */
            seen_near = fmaxf(near_plane, cascades_power_step(seen_near, CASCADES_RANGE_STEPS, floorf));
            seen_far = fminf(far_plane, cascades_power_step(seen_far, CASCADES_RANGE_STEPS, ceilf));
        }
        near_plane = seen_near;
        far_plane = seen_far;
    }
    int size = map_settings_size(&cascades.settings);
    m->size = size ? size : CASCADES_DEFAULT_SIZE * map_auto_finer(&cascades.settings, f->gpu->scene, l);
    m->kind = MAP_ARRAY;
    m->layer_count = count;
    m->casters = NULL;
    m->orthographic = true;
    m->texel_kind = MAP_TEXEL_ORTHOGRAPHIC;
    m->cascade_blend = cascades.no_blend ? 0 : cascades_or(cascades.blend, CASCADES_DEFAULT_BLEND);
    cascades_splits(count, lambda, near_plane, far_plane, m->cascade_split);
    cascades_light_view(l->direction, f->view, stabilize, m->cascade_view);
    float margin = map_read_reach(&cascades.settings, MAP_ARRAY, l->radius > 0) + cascades.settings.normal_texels +
                   CASCADES_SNAP_TEXELS;
    for (int k = 0; k < count; k++) {
        const float *split = m->cascade_split;
        /* From where the slice before starts blending into this one. */
        float start = k > 0 ? split[k] - m->cascade_blend * (split[k] - split[k - 1]) : split[k];
        vec3 lo, hi;
        vec3 receivers_lo = {INFINITY, INFINITY, INFINITY}, receivers_hi = {-INFINITY, -INFINITY, -INFINITY};
        mat4 projection;
        if (stabilize != CASCADES_STABILIZE_SPHERE) /* a sphere's box is the slice's, whatever the receivers */
            cascades_slice_receivers(f->gpu->scene, f->view, m->cascade_view, start, split[k + 1], receivers_lo,
                                     receivers_hi);
        cascades_slice_box(f->view, m->cascade_view, start, split[k + 1], m->size, margin, stabilize, receivers_lo,
                           receivers_hi, lo, hi);
        float near_depth, far_depth;
        map_depth_range(-map_nearest_caster(f->gpu->scene, m->cascade_view, lo, hi, true), -lo[2], &near_depth,
                        &far_depth);
        glm_ortho(lo[0], hi[0], lo[1], hi[1], near_depth, far_depth, projection);
        map_cascade_layer(m, k, projection);
        if (k == 0) {
            m->near_plane = near_depth;
            m->texel_scale = fmaxf(hi[0] - lo[0], hi[1] - lo[1]) / (float)m->size;
        }
        m->far_plane = far_depth;
    }
    return true;
}

/* Cascades for a directional light; shadowmap's uniform fit (a
 * perspective map or a cube) for the others: cascades answer the
 * perspective aliasing of a map that spans the whole view, and a spot's or
 * point light's perspective already puts its texels near the light, where
 * its shadows are sharpest; slicing it by the camera's depth would not
 * follow where its texels go. */
static bool cascades_fit(const technique_frame *f, int light, map_light *m, const float (*receivers)[3],
                         int receiver_count) {
    if (f->gpu->scene->lights[light].type != SCENE_LIGHT_DIRECTIONAL)
        return map_fit_uniform(f->gpu->scene, light, m, receivers, receiver_count);
    return cascades_fit_array(f, light, m);
}

/* ---- the technique ---- */

static bool cascades_init(const render_scene *gpu) {
    cascades.maps = map_create(&cascades.settings, gpu);
    return cascades.maps != NULL;
}

static void cascades_destroy(void) {
    map_destroy(cascades.maps);
    cascades.maps = NULL;
}

static const char *cascades_area_light(const scene_light *light, int l) {
    (void)l;
    return map_area_light_text(&cascades.settings, light);
}

/* The frame: shadowmap.c's passes, a directional light's map an array
 * of cascades, one layer a slice of the view. */
static void cascades_render(const technique_frame *f) {
    map_renderer *r = cascades.maps;
    const map_settings *settings = &cascades.settings;
    /* 1. The camera's depth pre-pass: what is seen. */
    map_begin(r, f);
    /* 2. Per light, the splits, then each cascade's box around its slice
     * and the receivers in it (cascades_fit_array). */
    for (int l = 0; l < f->gpu->scene->light_count; l++)
        map_fit_light(r, settings, f, l, cascades_fit);
    /* 3. Depth from each fitted light into each layer. */
    for (int l = 0; l < f->gpu->scene->light_count; l++)
        map_draw_depth(r, settings, f, l);
    /* 4. Shading: each pixel reads the layer of its view depth, blended
     * into the next over the last part of a slice. */
    map_shade(r, settings, f);
    /* 5. The lecture's overlays. */
    map_draw_overlays(r, settings, f);
}

/* Light 0's map, and for cascades the split distances and the world size
 * of the nearest cascade's texel. */
static void cascades_describe(char *out, size_t size) {
    int l;
    if (!map_described_light(cascades.maps, &l, out, size))
        return;
    const map_light *m = map_of_light(cascades.maps, l);
    char map[64];
    map_size_text(&cascades.settings, m, map, sizeof map);
    int n = snprintf(out, size, "light %d: %s", l, map);
    if (m->kind == MAP_ARRAY) {
        n += snprintf(out + n, size - (size_t)n, ", %d cascades (%s%s), splits", m->layer_count,
                      cascades_schemes[cascades.scheme],
                      cascades.grazed[l] ? ", stabilized by steps: the light grazes what is seen"
                                         : cascades_stabilized[cascades.stabilize]);
        for (int k = 0; k <= m->layer_count && (size_t)n < size; k++)
            n += snprintf(out + n, size - (size_t)n, " %.3g", m->cascade_split[k]);
        if ((size_t)n < size)
            snprintf(out + n, size - (size_t)n, "; nearest texel %.3g", m->texel_scale);
    } else if ((size_t)n < size) { /* the settings' cascades, splits and blend are a directional light's */
        snprintf(out + n, size - (size_t)n, ", no cascades: only a directional light's map is cut in cascades");
    }
    map_describe_filter(&cascades.settings, out, size);
    map_describe_storage(cascades.maps, l, out, size);
}

/* The sweep: each split scheme at the default 4 x 1024, then the count
 * and size at equal texels (2 x 2048 against 4 x 1024) and beyond, and
 * stabilisation and the blend off; an area light drawn hard (what PCSS costs
 * and buys), and two moment filters. */
static const char *const cascades_bench_configs[] = {
    "",
    "practical: --splits practical",
    "uniform: --splits uniform",
    "log: --splits log",
    "2x2048: --cascades 2 --map-size 2048",
    "4x2048: --map-size 2048",
    "8x1024: --cascades 8",
    "--splits practical --stabilize sphere",
    "--stabilize off",
    "--no-blend",
    "hard: --soft off",
    "--filter evsm4",
    "--filter msm",
};

const technique cascades_technique = {
    .name = "cascades",
    .title = "cascaded shadow maps (Engel 2006; splits: Zhang et al. 2006, SDSM: Lauritzen et al. 2011)",
    .params = cascades_params,
    .param_count = (int)(sizeof cascades_params / sizeof *cascades_params),
    .bench_configs = cascades_bench_configs,
    .bench_config_count = (int)(sizeof cascades_bench_configs / sizeof *cascades_bench_configs),
    .init = cascades_init,
    .render = cascades_render,
    .destroy = cascades_destroy,
    .area_light = cascades_area_light,
    .describe = cascades_describe,
    .coloured_shadows = true, /* the transmittance maps (map.h, "Translucent casters") */
    .gallery_config = "--overlay cascades",
};
