/* map: the shadow-map library that demos/shadowmap.c (uniform
 * maps), demos/psm.c (warped maps) and demos/cascades.c (array maps for
 * directional lights, the uniform fit for the others) are built on. GL
 * lives here, not in the techniques. Each part of the manual stands beside
 * what it describes: map size, the camera pass and its filters, soft
 * shadows, moment maps, overlays, storage, array maps, caching, the depth
 * pass, fitting and caster culling.
 *
 * Using it. A technique keeps a map_settings and a map_renderer pointer
 * in its static state, lists MAP_PARAMS(its settings) among its
 * parameters (the same flags and keys everywhere), calls map_create /
 * map_destroy from its own init / destroy,
 * and each frame the steps below from its render function, in this order,
 * with its own fitting function: the one place where techniques differ is
 * how a light's map is placed.
 *
 *   1. map_begin: the camera's depth pre-pass, read back
 *      (technique_see) so that the depth passes cull the casters it shows
 *      hidden; the receiver points are the frame's (technique.h), the
 *      corners of the part of every receiver's box inside the camera's
 *      frustum;
 *   2. per light, map_fit_light: fit(frame, light, map, receivers)
 *      places the map (a fit that measures its texels, as psm does, takes
 *      the samples of map_light_samples) and the automatic size
 *      sizes it; false where the light is off or nothing can be shadowed
 *      (then the light is added unshadowed);
 *   3. per light, once every light is fitted, map_draw_depth: the
 *      depth pass renders each layer of a fitted light that its cache
 *      cannot give, with the casters that layer needs (the atlas sized
 *      first for every fitted light's tiles);
 *   4. map_shade, the camera pass: one pass (GL_EQUAL depth) that
 *      shades every light on where its map lets it through, and the
 *      ambient term; each visible pixel is filtered once per light that
 *      adds to it (beyond a light's range, outside its cone or facing away
 *      the filter is skipped), and a light that lights a small part of the
 *      frame is shaded in a pass of its own over it
 *      (shading_split_lights);
 *   5. map_draw_overlays: those of settings->overlay.
 *
 * This header is what a technique uses: the settings and their flags, a
 * light's map as a fit fills it, the five steps, fitting and the caster
 * culling a technique may share. The renderer's programs, caches and
 * helpers between the library's files are in map_internal.h.
 */
#ifndef MAP_H
#define MAP_H

#include <GLFW/glfw3.h>
#include <stdbool.h>

#include "bvh_gpu.h"
#include "map_atlas.h"
#include "technique.h"
#include "warp.h"

/* Map size (--map-size; auto, the default). Fixed sizes are as given.
 * Auto fits the map at MAP_AUTO_MAX_SIZE, measures the mean size
 * on screen of its texels at map_light_samples (the dp/ds of the
 * perspective shadow map papers, warp_sample_texel_pixels: a
 * WARP_SAMPLES_X x WARP_SAMPLES_Y grid of pixels cast onto the receivers' boxes, the same measure psm judges
 * its warps by; samples beyond the light's range or outside the map left
 * out) and takes the smallest power of two from MIN to MAX at which a
 * texel covers at most TEXEL_PIXELS pixels on average
 * (map_auto_size; MAX where most receivers seen are edge-on to the
 * light): shadows no sharper than the pixels that show them, and no depth
 * pass larger than that needs. The size follows the picture's: half as
 * wide a picture, half the size (test_shadowmap's test_map_size_from_need
 * checks the sizes it picks). A cube map has one size for its six faces
 * (one cube texture, so that kernels filter across face edges): the mean
 * is over the samples on all faces. A light with a range whose reach no
 * sample of the grid lands in (a far lamp's pool, between its rows) is
 * measured on a WARP_RECT_SAMPLES_X x WARP_RECT_SAMPLES_Y grid over its
 * reach on screen alone (the bounds of the receivers' boxes clipped to
 * its range), so that a light small on screen gets a map sized by its
 * share of it, and MIN where that grid finds nothing it lights.
 * FALLBACK where nothing can be measured otherwise (no sample of the
 * picture's grid lands on a receiver a light without a range reaches).
 * An array map is not sized here: its fit sets its size.
 *
 * A hard light that reaches a cut-out caster (scene_light_reaches_cut_out)
 * gets texels CUT_OUT_FINER times finer (map_auto_finer; cascades scale
 * their size by it): a cut-out's shadow is mostly edges (a fence's
 * boards, a crown of leaves), and a map misclassifies a band along every
 * hard edge a share of a texel wide. An area light's PCSS is not made
 * finer: its penumbra spans many texels already, and finer texels would
 * only bring its search and filter to MAP_SOFT_MAX_TEXELS sooner. A
 * sun's finer 2D map may take up to CUT_OUT_MAX_SIZE: one map over the
 * whole view, of which a scene has few. A spot's map and a cube's six
 * faces stay within MAX, the largest auto gives any other map, so that
 * many lamps over cut-outs ask no more memory than lamps without them.
 * Every size stays within the GL's largest texture (test_gltf's
 * test_gltf_fence_within_goal_by_auto_maps checks the fence's shadows;
 * test_shadowmap's test_map_size_from_need the sizes). */
#define MAP_AUTO_MIN_SIZE 256
#define MAP_AUTO_MAX_SIZE 4096
/* Memory. The lights' own maps (all but the atlas's tiles) hold at most
 * MAP_MEMORY_TEXELS depth texels together, each layer counted, and none
 * has a side beyond the GL's largest texture: once every light is fitted,
 * before any is drawn (map_bound_memory), the largest map above MIN is
 * halved until they fit, a fixed --map-size's and a cascade's too, and
 * the state line says how many times. So a scene of many spot lights
 * asks at most that memory of the GL however large their maps are asked:
 * two cube maps of MAX, or sixteen 2D maps. */
#define MAP_MEMORY_TEXELS (1 << 28)
#define MAP_AUTO_TEXEL_PIXELS 1.0f
#define MAP_AUTO_FALLBACK_SIZE 2048
#define MAP_AUTO_CUT_OUT_FINER 4
#define MAP_AUTO_CUT_OUT_MAX_SIZE 8192

/* The defaults of the numbers, from `make bench` (see demos/shadowmap.c). */
#define MAP_CONSTANT_TEXELS 1.0f
#define MAP_SLOPE_FACTOR 1.5f
#define MAP_SLOPE_UNITS 1.0f

/* The camera pass (shaders/map.frag: map.glsl's kernels,
 * map_2d.glsl's, map_cube.glsl's and map_array.glsl's
 * maps, the flat ones' filter map_flat.glsl's, one program per
 * combination of the lights' kinds of map, map_light_kind) moves
 * each point towards the light by the constant bias and along its normal
 * by the normal offset (both in map texels of world distance, so they hold
 * at any map size and scene scale), then filters the hardware comparisons
 * over the kernel of settings->filter:
 *   none     one nearest test;          hw     one bilinear test (2x2);
 *   pcf3/5/7 an N x N grid of bilinear tests;
 *   tent3/5  an N x N tent: each texel's test weighted by the area of a
 *            tent of radius N / 2 texels over it, from ((N + 1)/2)^2
 *            bilinear tests placed and weighted by where the point lies in
 *            its texel (4 and 9 taps for pcfN's 9 and 25, and sharper:
 *            pcfN's weights reach a texel farther; shaders/map.glsl
 *            derives it). A cube map's texel grid is not at hand in
 *            direction space: there the taps are a point's on a texel
 *            corner, across the direction;
 *   poisson  16 bilinear tests on a Poisson disc rotated per pixel by a
 *            hash of the pixel (frames stay deterministic), of scale
 *            MAP_POISSON_SCALE_TEXELS;
 *   vsm, evsm2, evsm4, msm  the moment maps (below, "Moment shadow maps");
 *   auto     (the default) poisson, but none while the constant or the
 *            slope-scaled bias is off (--no-constant-bias, --no-slope-bias,
 *            keys C and L), area lights hard too: a kernel or PCSS
 *            averages acne's stripes into a faint darkening, one nearest
 *            test shows each stripe; and hw in a scene of more lights
 *            than a pass holds (settings->many_lights), where each light
 *            is filtered in a pass of its own over its part of the frame
 *            and the kernel's taps multiply with the lights (on
 *            lamps_64 the bench's sweep puts hw on the front of time
 *            against misclassified pixels, poisson behind both fronts),
 *            but not where rays decide the pixels the kernel is unsure
 *            of (see "Rays"): a 2x2 test's unsure band is too narrow to
 *            hold every pixel the map gets wrong (test_lights).
 *            Any other choice holds with the biases off and with many
 *            lights (map_filter_in_use).
 * The early-out (on; --no-early-out, key E): a kernel of more than four
 * taps reads four on its rim first and stops where they agree wholly,
 * outside any penumbra (nearly every pixel): 4 taps instead of 9 to 49.
 * It changes no decision with any kernel on the standard scenes and
 * long_view (test_shadowmap's test_early_out_changes_no_decision), and
 * snaps penumbra values near 0 or 1 to them.
 * --kernel-depth receiver-plane (Isidoro, GDC 2006; the default) makes each
 * tap compare the receiver's own depth there rather than the centre's
 * (--kernel-depth centre), which speckles flat receivers with partial
 * acne where a tap reaches texels of the receiver itself.
 *
 * The choices of the settings, in the order of their names (the default
 * first): map_filters, map_depths, map_kernel_depths. */
typedef enum map_filter {
    MAP_FILTER_AUTO,
    MAP_FILTER_POISSON,
    MAP_FILTER_NONE,
    MAP_FILTER_HW,
    MAP_FILTER_PCF3,
    MAP_FILTER_PCF5,
    MAP_FILTER_PCF7,
    MAP_FILTER_TENT3,
    MAP_FILTER_TENT5,
    MAP_FILTER_VSM,
    MAP_FILTER_EVSM2,
    MAP_FILTER_EVSM4,
    MAP_FILTER_MSM,
} map_filter;
typedef enum map_depth { MAP_DEPTH_24, MAP_DEPTH_32F } map_depth;
typedef enum map_soft { MAP_SOFT_PCSS, MAP_SOFT_OFF } map_soft;
typedef enum map_kernel_depth {
    MAP_KERNEL_DEPTH_RECEIVER_PLANE,
    MAP_KERNEL_DEPTH_CENTRE,
} map_kernel_depth;

extern const char *const map_sizes[];
extern const char *const map_filters[];
extern const char *const map_depths[];
extern const char *const map_kernel_depths[];
extern const char *const map_softs[];

typedef struct map_settings {
    int map_size;     /* choice: map_sizes */
    int filter;       /* choice: map_filter; read through map_filter_in_use */
    int depth;        /* choice: map_depth */
    int kernel_depth; /* choice: map_kernel_depth */
    int soft;         /* choice: map_soft, what an area light (radius > 0) gets */
    int overlay;      /* choice: the technique's own list, MAP_OVERLAY_NAMES first */
    bool no_constant_bias, no_slope_bias, no_early_out;
    float constant_texels, slope_factor, slope_units, normal_texels; /* 0: defaults */
    float depth_bias_slope, depth_bias_min;                          /* the tutorials' bias; 0: none */
    int shadow_budget; /* lights whose maps are redrawn per frame, at most; 0: every one (see "Budget") */
    /* Not a flag: the scene has more lights than a pass holds
     * (render_light_groups > 1), which map_create sets; auto then stands
     * for hw without rays (above, "The camera pass"). */
    bool many_lights;
    /* Not a flag: the technique's overlay list goes on with
     * MAP_ARRAY_OVERLAY_NAMES (cascades sets it; psm's list goes on
     * with its own). */
    bool array_overlays;
    /* Not flags: the shadow rays (see "Rays" below; demos/hybrid.c sets
     * them), and its overlay list goes on with MAP_RAYS_OVERLAY_NAMES. */
    int rays;        /* map_rays */
    int ray_samples; /* an area light's rays per pixel; 0: MAP_RAY_DEFAULT_SAMPLES */
    bool ray_overlays;
} map_settings;

/* The filter that reads the map: settings->filter, or what auto stands
 * for (above, "The camera pass"). */
map_filter map_filter_in_use(const map_settings *settings);
/* Auto stands for none because a bias is off: what acne there is shows
 * unblurred. */
bool map_auto_unfiltered(const map_settings *settings);
/* Auto stands for none and the slope-scaled bias is off: acne shows, on
 * every standard scene, where surfaces turn away from the light. With
 * the constant bias alone off next to none shows (test_shadowmap's
 * test_state_line_claims_acne_where_it_shows). */
bool map_shows_acne(const map_settings *settings);
/* Appends ", filter: none (shows acne)" to a technique's state line (its
 * describe) while map_shows_acne, ", filter: none (a bias is off)" while
 * map_auto_unfiltered otherwise; nothing else. */
void map_describe_filter(const map_settings *settings, char *out, size_t size);

/* Overlays, for lectures (map_overlay.c), drawn into the picture:
 *   texels      the map's texel boundaries on the receivers (camera pass);
 *   texel-size  a heat map of a texel's size in pixels (camera pass);
 *   penumbra    a soft light's receivers coloured by the penumbra radius
 *               PCSS estimated there (world units; camera pass), where
 *               its blocker search found a blocker;
 *   frustum     each layer's frustum in wireframe (map_draw_frustum);
 *   map         light 0's map as an inset of linear depth (a cube's faces
 *               in two rows: +X -X +Y, then -Y +Z -Z; an array's layers
 *               in a row, each an inset), each inset fitted to what its
 *               layer holds and labelled with it (see "The map inset"
 *               below);
 *   all         texels, frustum and map.
 * A technique's overlay list starts with MAP_OVERLAY_NAMES and may
 * go on with its own (psm's post-perspective view: map_warp_view). */
#define MAP_OVERLAY_NAMES "none", "all", "texels", "frustum", "map", "texel-size", "penumbra"
enum {
    MAP_OVERLAY_NONE,
    MAP_OVERLAY_ALL,
    MAP_OVERLAY_TEXELS,
    MAP_OVERLAY_FRUSTUM,
    MAP_OVERLAY_MAP,
    MAP_OVERLAY_TEXEL_SIZE,
    MAP_OVERLAY_PENUMBRA,
    MAP_OVERLAY_COUNT
};
/* An array map's technique lists this one next (and sets the settings'
 * array_overlays): light 0's layers' receivers tinted each in its colour
 * (the blend band mixing two; map_cascade_colors) with a key in
 * the bottom-left corner (each layer's colour, number and slice of view
 * depth: from cascade_split[k] to [k + 1]), and its map as an inset (an
 * array's layers in a row; a spot's or point light's map as "map" shows
 * it). */
#define MAP_ARRAY_OVERLAY_NAMES "cascades"
enum { MAP_OVERLAY_CASCADES = MAP_OVERLAY_COUNT };
/* The settings' overlay is that one. */
#define MAP_SHOWS_CASCADES(st) ((st)->array_overlays && (st)->overlay == MAP_OVERLAY_CASCADES)
/* A technique with rays lists this one next (and sets the settings'
 * ray_overlays): the pixels where the map is unsure tinted
 * (MAP_UNSURE_TINT in shaders/map_light.glsl), traced or not. */
#define MAP_RAYS_OVERLAY_NAMES "unsure"
enum { MAP_OVERLAY_UNSURE = MAP_OVERLAY_COUNT };
#define MAP_SHOWS_UNSURE(st) ((st)->ray_overlays && (st)->overlay == MAP_OVERLAY_UNSURE)

/* Rays (demos/hybrid.c). With rays, the camera pass decides a light at a
 * pixel by shadow rays from the visible point itself (shaders/map.frag's
 * map_ray_visibility, bvh_trace.glsl, against the casters' triangles that
 * map_trace_with gave: a triangle whose plane passes within
 * BVH_SURFACE_ULPS of the point is the surface it leaves), as the
 * reference does: a hard light by one ray to its centre, exact; an area
 * light by the reference's own samples for that pixel
 * (shaders/area_light.glsl, area_light.h's points: ray_samples of them,
 * the reference's count by default), in area_light_progressive_index's
 * order, stopped where the first ones all agree (the pixel is then taken
 * as wholly lit, lit through the same panes, or in umbra): after
 * MAP_RAY_FIRST_SAMPLES where they get through, after
 * MAP_RAY_BLOCKED_SAMPLES where they are all blocked. At an umbra's rim
 * the part of the disk still in sight is a sliver a few samples wide,
 * which an even quarter of the disk's samples can miss (test_hybrid's
 * umbra rim). At every pixel
 * (MAP_RAYS_ALL, a plain ray tracer), or only where the map is unsure
 * (MAP_RAYS_UNSURE): where its filter, the kernel or PCSS, gives a
 * visibility strictly between 0 and 1 (a shadow's edge within the
 * kernel's reach; a blocker found but the light not wholly hidden), and
 * where a hard light's kernel says 1 but not with a share of the
 * constant bias (shaders/map.glsl, MAP_SURE_LIT_BIAS_SHARE: a caster
 * within the bias of its receiver), where PCSS says 0 but its blocker
 * search found a tap unblocked or was clamped short of the light's cone
 * (MAP_SOFT_MAX_TEXELS: the filter's disc, sized by the blockers' mean
 * distance, is narrower than the penumbra where blockers lie at several
 * distances), and where a hard light's transmittance map holds a pane
 * within a texel of the point (its coloured edge is the texel's). A ray's light is filtered through the
 * translucent casters it crosses (bvh_trace.glsl's bvh_transmittance).
 * Where the filter says 0 or 1 the map decides: with rays the kernel reads
 * every tap, as if with --no-early-out (four rim taps agreeing prove
 * nothing of the rest: test_hybrid's sure pixels on wuson need all of
 * them).
 * MAP_RAYS_OFF is the map alone, early-out and all.
 * With the frame's marked pass (skips.h, marked_pass), in a scene of one
 * light group (past one, map.c's map_shade_lights says why not),
 * MAP_RAYS_UNSURE draws the receivers twice: the first pass shades from
 * the map and marks the pixels rays would decide, the second shades only
 * those, tracing (map_rays.c). A hard light's 2D or cube map is read in
 * the first pass by its depth bounds (map_bounds.c) instead of its
 * kernel: 0 or 1 only where every tap must agree, else marked, so that
 * the kernel too runs only in the second pass. The same pixels come out
 * of one pass without it. */
typedef enum map_rays { MAP_RAYS_OFF, MAP_RAYS_UNSURE, MAP_RAYS_ALL } map_rays;
/* The reference's samples of an area light per pixel
 * (RAYTRACE_DEFAULT_LIGHT_SAMPLES: test_hybrid checks they agree), a
 * power of 4, so that every first 4^i samples cover the disk evenly; and
 * the samples after which a pixel whose rays all agree stops: where they
 * get through, and where they are all blocked ("Rays" above). */
#define MAP_RAY_DEFAULT_SAMPLES 256
#define MAP_RAY_FIRST_SAMPLES 64
#define MAP_RAY_BLOCKED_SAMPLES 128

/* The map inset. Light 0's map is reduced on the GPU
 * (shaders/overlay_reduce.frag) to blocks of texels, a block to at most
 * a pixel of the inset, each holding the nearest and the farthest depth
 * stored in it among the texels that hold one (below the cleared 1): the
 * inset shows each block's nearest (a caster narrower than a pixel still
 * shows), and the reduction, read back (a few hundred blocks on a side at
 * most), gives each layer's range. Each inset (a cube's one for its six
 * faces) shows linear depth from its nearest held depth, black, to its
 * farthest, MAP_INSET_FAR_GREY_PERCENT grey, what holds nothing
 * white. A label above it gives that range in the light view's units (a
 * perspective map's distance from the light, an orthographic one's depth
 * past its near plane) beside its swatch: an array layer's colour, else
 * the ramp's two ends. A layer that holds nothing is drawn as the
 * legend's panel, labelled "empty". The reduction is made again only
 * when the depth pass renders a layer of light 0's map. */

/* The parameters every shadow-map technique shares, for its params array. */
/* clang-format off: a flag a line or two, as the techniques' own tables */
#define MAP_PARAMS(s)                                                                                                             \
    {"map-size",                                                                                                                  \
     "texels on a side; auto: a texel about a pixel where shadows are seen (cascades: 1024 a cascade)",                           \
     GLFW_KEY_M,                                                                                                                  \
     FLAGS_CHOICE,                                                                                                                \
     .index = &(s).map_size,                                                                                                      \
     .choices = map_sizes},                                                                                                       \
        {"filter",                                                                                                                \
         "what reads the map; auto: poisson (hw past eight lights), none (area lights hard) while a bias is off",                 \
         GLFW_KEY_F,                                                                                                              \
         FLAGS_CHOICE,                                                                                                            \
         .index = &(s).filter,                                                                                                    \
         .choices = map_filters},                                                                                                 \
        {"depth",                                                                                                                 \
         "depth format: 24-bit or 32-bit float",                                                                                  \
         GLFW_KEY_D,                                                                                                              \
         FLAGS_CHOICE,                                                                                                            \
         .index = &(s).depth,                                                                                                     \
         .choices = map_depths},                                                                                                  \
        {"constant-bias",                                                                                                         \
         "acne: stripes where the slope-scaled bias alone is too little (everywhere with it off too)", GLFW_KEY_C,                \
         FLAGS_TOGGLE, .disabled = &(s).no_constant_bias},                                                                        \
        {"slope-bias", "acne where surfaces turn away from the light", GLFW_KEY_L, FLAGS_TOGGLE,                                  \
         .disabled = &(s).no_slope_bias},                                                                                         \
        {"early-out", "wide kernels: four rim taps first, the whole kernel only where they disagree", GLFW_KEY_E,                 \
         FLAGS_TOGGLE, .disabled = &(s).no_early_out},                                                                            \
        {"soft",                                                                                                                  \
         "area lights (radius > 0): pcss, soft shadows that harden at contact; off: hard, from the centre",                       \
         GLFW_KEY_Y,                                                                                                              \
         FLAGS_CHOICE,                                                                                                            \
         .index = &(s).soft,                                                                                                      \
         .choices = map_softs},                                                                                                   \
        {"kernel-depth",                                                                                                          \
         "what each kernel tap compares: the receiver plane's depth there, or the centre's",                                      \
         GLFW_KEY_P,                                                                                                              \
         FLAGS_CHOICE,                                                                                                            \
         .index = &(s).kernel_depth,                                                                                              \
         .choices = map_kernel_depths},                                                                                           \
        {"constant-texels",                                                                                                       \
         "constant bias, in map texels of world distance",                                                                        \
         0,                                                                                                                       \
         FLAGS_NUMBER,                                                                                                            \
         .number = &(s).constant_texels,                                                                                          \
         .fallback = MAP_CONSTANT_TEXELS,                                                                                         \
         .min = 0.01f,                                                                                                            \
         .max = 64},                                                                                                              \
        {"slope-factor",                                                                                                          \
         "slope-scaled bias: glPolygonOffset factor",                                                                             \
         0,                                                                                                                       \
         FLAGS_NUMBER,                                                                                                            \
         .number = &(s).slope_factor,                                                                                             \
         .fallback = MAP_SLOPE_FACTOR,                                                                                            \
         .min = 0.01f,                                                                                                            \
         .max = 64},                                                                                                              \
        {"slope-units",                                                                                                           \
         "slope-scaled bias: glPolygonOffset units",                                                                              \
         0,                                                                                                                       \
         FLAGS_NUMBER,                                                                                                            \
         .number = &(s).slope_units,                                                                                              \
         .fallback = MAP_SLOPE_UNITS,                                                                                             \
         .min = 0.01f,                                                                                                            \
         .max =                                                                                                                   \
             64}, /* Off by default: on the standard scenes it costs accuracy at contact                                        \
     * shadows and the other two already keep the acne sweep clean. */ \
        {"normal-texels",                                                                                                         \
         "normal offset, in map texels (0: off)",                                                                                 \
         0,                                                                                                                       \
         FLAGS_NUMBER,                                                                                                            \
         .number = &(s).normal_texels,                                                                                            \
         .fallback = 0,                                                                                                           \
         .min = 0,                                                                                                                \
         .max =                                                                                                                   \
             64}, /* For comparison only: the bias popular tutorials subtract from the                                          \
     * map depth, max(slope (1 - N.L), min), whose size in world units                                            \
     * changes with the light's depth range. */ \
        {"depth-bias-slope",                                                                                                      \
         "tutorial bias: slope, in map depth (0: off)",                                                                           \
         0,                                                                                                                       \
         FLAGS_NUMBER,                                                                                                            \
         .number = &(s).depth_bias_slope,                                                                                         \
         .fallback = 0,                                                                                                           \
         .min = 0,                                                                                                                \
         .max = 1},                                                                                                               \
        {"depth-bias-min",                                                                                                        \
         "tutorial bias: minimum, in map depth (0: off)",                                                                         \
         0,                                                                                                                       \
         FLAGS_NUMBER,                                                                                                            \
         .number = &(s).depth_bias_min,                                                                                           \
         .fallback = 0,                                                                                                           \
         .min = 0,                                                                                                                \
         .max = 1},                                                                                                               \
    {                                                                                                                             \
        "shadow-budget",                                                                                                          \
            "lights whose maps are redrawn in a frame, at most, the longest waiting first; the others drawn as when "             \
            "their maps were (0: no budget)",                                                                                     \
            0, FLAGS_INT, .integer = &(s).shadow_budget, .min = 0, .max = SCENE_MAX_LIGHTS, .what = "a light count",              \
                          .value_name = "N"                                                                                       \
    }
/* clang-format on */

/* Moment shadow maps (map_moments.c, shaders/moments.glsl): the
 * filters vsm, evsm2, evsm4 and msm filter the map before the camera pass
 * instead of its reads: the depth pass draws the receivers that cast
 * nothing too, then each layer it rendered becomes moments of the depth,
 * blurred by a separable box, in a float colour texture beside the depth
 * texture (texture.moments), which the camera pass reads once, bilinear,
 * on the light's depth unit. They replace the kernel and PCSS alike: an
 * area light's box is its casters' mean penumbra wide (one width, no
 * contact hardening). Which moments a filter stores (the shaders'
 * MAP_PASS_MOMENTS): */
typedef enum map_moments {
    MAP_MOMENTS_NONE,
    MAP_MOMENTS_VSM,   /* d, d^2: Chebyshev's bound */
    MAP_MOMENTS_EVSM2, /* e^(c d), its square */
    MAP_MOMENTS_EVSM4, /* and -e^(-c d), its square */
    MAP_MOMENTS_MSM,   /* d, d^2, d^3, d^4: Hamburger 4MSM */
} map_moments;
/* The box's radius in texels (the box is 2 radius + 1 texels across, its
 * two end texels weighted by the fraction): a hard light's, and the most an
 * area light's may take (a wider one shrinks an auto-sized map, else is
 * clamped): the blur's cost grows with its width. */
#define MAP_MOMENTS_HARD_BLUR_TEXELS 1
#define MAP_MOMENTS_MAX_BLUR_TEXELS 12
/* The moments a filter stores; MAP_MOMENTS_NONE for the kernels. */
map_moments map_filter_moments(int filter);

/* How the camera pass finds the world size of a texel at a point (the
 * shaders' u_texel_kind). */
typedef enum map_texel_kind {
    MAP_TEXEL_ORTHOGRAPHIC, /* texel_scale */
    MAP_TEXEL_PERSPECTIVE,  /* texel_scale x depth along the light's axis */
    MAP_TEXEL_PROJECTIVE,   /* from the matrix's derivatives: any warp */
} map_texel_kind;

/* Storage (map_light). A map has a kind and layers: MAP_2D has
 * one layer (spot, directional, any warped map), MAP_CUBE six, the
 * faces in GL's order (MAP_FACE_*), MAP_ARRAY layer_count
 * of them (1..MAP_MAX_ARRAY_LAYERS) in one GL_TEXTURE_2D_ARRAY, for
 * cascades (one layer per slice of the view). Each layer has its own
 * matrix, layer_view_projection[layer] (world -> that layer's clip space);
 * the depth range, texel measure and caster list are the map's. The
 * texture is (re)made only when kind, size, layer count, depth format or
 * filter change; every kind compares in hardware (compare mode on, clamped
 * to its edges). */
typedef enum map_kind { MAP_2D, MAP_CUBE, MAP_ARRAY } map_kind;
/* A cube's faces in GL's order (GL_TEXTURE_CUBE_MAP_POSITIVE_X + face). */
enum {
    MAP_FACE_POSITIVE_X,
    MAP_FACE_NEGATIVE_X,
    MAP_FACE_POSITIVE_Y,
    MAP_FACE_NEGATIVE_Y,
    MAP_FACE_POSITIVE_Z,
    MAP_FACE_NEGATIVE_Z,
    MAP_CUBE_FACES
};
/* Translucent casters (scene_object's translucent: glTF's alphaMode
 * BLEND) leave the depth pass where the scene has them. A transmittance
 * map beside the depth texture, of its kind, size and layers, RGBA16F and
 * read nearest, takes them instead: after each
 * layer's depth pass, cleared to 1, they are drawn into it
 * (shaders/transmittance.frag) depth-tested against the layer's opaque
 * depths without writing them, rgb multiplied by each caster's
 * transmittance (1 - a) + a C, the texture read at level 0 by the
 * reference's rule, so that a texel holds the product of every pane the
 * light crosses before the nearest opaque caster; alpha, blended by MIN,
 * the nearest of their depths, raised by its slope across the texel as
 * the slope-scaled bias raises the opaque ones. The camera pass multiplies
 * a light's share by the rgb where the biased point lies beyond that
 * depth by more than a half float's rounding, a translucent receiver's
 * own transmittance divided out (shaders/map.glsl, map_transmitted): a
 * pane does not filter itself, and one under another is filtered by that
 * one alone. The shadow is coloured as the reference's (a red pane's
 * pink, two panes' the product), with the texel's hard edge: the kernel
 * filters the opaque shadow alone. The cache holds a layer's
 * transmittance with its depths. A light whose unit the GL lacks
 * (MAP_TRANSMIT_UNITS), or a GL that cannot draw into the texture, casts
 * them whole: said once. */

/* Atlas. In a scene of more lights than a pass holds
 * (settings->many_lights), a hard point light's cube map is six square
 * tiles of one shadow atlas, a 2D depth texture shared by every such
 * light (map_atlas.h places the tiles), instead of a cube texture of its
 * own: the memory follows what the camera sees, not the lights. The
 * atlas's side is planned once every light is fitted, before any is
 * drawn (map_atlas_plan): the least power of two whose square holds
 * MAP_ATLAS_ROOM times the area the tiles ask, up to MAP_ATLAS_SIZE (or
 * the GL's largest). It is made again, every tile placed afresh (the
 * largest first, which packs them whole) and every tiled light drawn
 * whatever the budget, where the tiles outgrow it or half its side would
 * do: a GL may hold the whole texture in memory however little of it is
 * drawn (llvmpipe does). A light's
 * tiles are sized by its share of the screen, --map-size auto's rule
 * (map_auto_size), but a face on which that rule measures no sample of
 * the screen takes MAP_ATLAS_MIN_TILE (each face sized by its own few
 * samples alone misclassified more of lamps_64's pixels than the light's
 * one size); with --map-size N every face asks N. A face keeps its tile
 * while it is asked at the same size, so that the cache holds across
 * frames. Where the lights ask more than the largest atlas holds
 * (MAP_ATLAS_ROOM times over), every tile above MAP_ATLAS_MIN_TILE is
 * halved until they fit, so that memory stays the atlas's however many
 * lights ask how much (the state line says how many times). Where the
 * atlas has no room left, a face takes the largest free tile below its
 * size, and a light with no room at all for a face keeps a cube map of
 * its own: both counted in the state line
 * (map_describe_storage). Faces out of view get tiles too, but are not
 * drawn (see "Caching"); a light the skips leave out takes none, which
 * moves other tiles but changes no pixel (shaders/map_tiles.glsl,
 * MAP_TILE_SUBTEXELS). The camera pass reads a face's tile by the
 * cube's rule (its face and (s, t)), each tap clamped half a texel
 * inside its tile, where a cube map's seamless filter would blend in
 * the next face's texels. A light that is soft, read by moments or takes
 * a transmittance map keeps its own cube map. With rays (demos/hybrid.c)
 * rays decide where a tiled light's kernel is unsure, as on a cube map;
 * a read within half a texel of its tile's edge takes that edge's texel
 * where a cube's seamless filter would blend in the next face's, whose
 * tile the kernel's other taps read. The map overlay shows the atlas. */
#define MAP_ATLAS_SIZE 16384
/* The atlas's side is the least power of two up to MAP_ATLAS_SIZE whose
 * square holds this many times the area the frame's tiles ask: room for
 * them to change size as the camera moves before it must be made again. */
#define MAP_ATLAS_ROOM 2

/* An array map's most layers: the most cascades. */
#define MAP_MAX_ARRAY_LAYERS 8
/* Room for the layers of any kind. */
#define MAP_MAX_LAYERS MAP_MAX_ARRAY_LAYERS
_Static_assert(MAP_MAX_LAYERS >= MAP_CUBE_FACES, "a map holds a cube's faces");

/* The GL texture behind a map, and what it was made with. */
typedef struct map_texture {
    unsigned id;
    unsigned moments; /* a moment filter's blurred moments (the map's kind) */
    unsigned blur[2]; /* one layer's moments, then those blurred along x */
    /* A 2D or cube map's depth bounds (map_bounds.c), and whether they
     * are its layers' as they stand. */
    unsigned bounds;
    bool bounds_current;
    unsigned transmittance; /* its transmittance map, of its kind (below); 0: none */
    map_kind kind;
    int size, layer_count, depth, filter;
} map_texture;

/* Array maps (demos/cascades.c's cascades). Every layer is an orthographic
 * box of one light view, cascade_view (world -> light space, orthonormal),
 * so a layer is that view, then a scale and an offset per axis
 * (cascade_scale, cascade_offset: its glm_ortho's diagonal and
 * translation; map_cascade_layer sets them with its
 * layer_view_projection). The camera pass reads layer k where the
 * camera's view depth lies between cascade_split[k] and [k + 1] (beyond
 * the ends, the nearest layer), and over the last cascade_blend of a
 * slice reads layer k + 1 at a share of the pixels rising linearly to 1
 * (dithered by a hash of the pixel: each pixel filters one layer), so the
 * switch of texel size shows no seam; the box of layer k + 1 covers that
 * band. Per layer the shader has 2 vec4 (scale, offset; their w the
 * slice's ends), not a mat4: a program with array lights holds 2 x
 * SHADER_PASS_LIGHTS x MAP_MAX_ARRAY_LAYERS vec4 of them, where mat4s
 * would take twice that. A layer's world texel is 2 / (size x its smaller
 * xy scale): the constant and normal-offset biases are measured in the
 * texel of the layer read. An array light's sampler is on its own unit,
 * as any light's map (a light has one kind of map). --map-size auto does
 * not size an array map: the fit sets its size (a cascade's texels are
 * sized by their count, not measured).
 *
 * One light's map: what it was fitted to, and its texture. */
typedef struct map_light {
    map_kind kind;
    int layer_count;                            /* 1 (2D), MAP_CUBE_FACES, or 1..MAP_MAX_ARRAY_LAYERS (array) */
    int size;                                   /* texels on a side, set before fitting */
    mat4 layer_view_projection[MAP_MAX_LAYERS]; /* world -> each layer's clip space */
    float near_plane, far_plane;
    map_texel_kind texel_kind;
    float texel_scale;
    bool orthographic;   /* the stored depth is linear (the inset shows it as it is) */
    const bool *casters; /* objects to draw into the map; NULL: every caster */
    /* An array map's layers (see "Array maps" above): */
    mat4 cascade_view;
    float cascade_scale[MAP_MAX_ARRAY_LAYERS][3], cascade_offset[MAP_MAX_ARRAY_LAYERS][3];
    float cascade_split[MAP_MAX_ARRAY_LAYERS + 1]; /* camera view depths */
    float cascade_blend;                           /* fraction of a slice */
    float blur_texels[MAP_MAX_LAYERS];             /* a moment filter's box radius per layer */
    map_texture texture;
    /* A cube map in the atlas (see "Atlas"): its faces' tiles; each
     * tile's size is asked by the fit, its place given by the depth pass. */
    bool tiled;
    map_tile tiles[MAP_CUBE_FACES];
} map_light;

/* The frame a fit takes: f->fit, where the host holds the fit to another
 * camera (technique.h), else f itself. */
const technique_frame *map_fit_frame(const technique_frame *f);
typedef bool (*map_fit_function)(const technique_frame *f, int light, map_light *m, const float (*receivers)[3],
                                 int receiver_count);

/* Caching. Per light and layer the renderer keeps what the layer holds:
 * its matrix (bit for bit), the casters drawn, a moment filter's blur
 * width, and per light the texture, size, depth format, filter and slope
 * bias. A layer is reused, with no depth pass, while the scene and the
 * light have not changed (f->changed), those are the same and the casters
 * it needs are among those drawn: a layer with more casters than needed
 * decides every read as one with exactly those. A remade texture, a frame
 * with the light skipped or unfitted, or any change empties the light's
 * cache. A layer that no receiver reads this frame (with caster culling
 * on, its planned reads empty: a cube's face turned from all the camera
 * sees) is not drawn at all: nothing reads what it would hold (but under
 * a budget, below, where a kept map is read whole). Counted
 * in f->skips->counts (casters per light: drawn into any layer, or
 * culled; layers rendered, reused and left undrawn out of view).
 *
 * Budget (--shadow-budget N; 0, the default: none). A light whose map
 * the cache cannot give whole (it moved, the scene changed, its fit did)
 * waits for map_shade, which redraws the maps of N of the waiting lights,
 * those that waited the most frames first (then in their order); each
 * other is drawn for a frame more as it was when its map was: its map,
 * the fit it was drawn with and the light where it was then
 * (render_scene_light_as), so that its light and its shadow update at a
 * lower rate together. A light's first map is drawn whatever the budget.
 * Unlike the skips, the budget changes decisions: a kept light lags,
 * which the bench's figures under motion measure. Counted in
 * f->skips->counts->maps_kept.
 *
 * A technique's maps and their GL objects (map_internal.h). */
typedef struct map_renderer map_renderer;
/* gpu: the scene whose object count sizes the caster sets; its lights and
 * the settings give the first camera program, compiled now. NULL after
 * printing why. */
map_renderer *map_create(map_settings *settings, const render_scene *gpu);
/* Frees r and its GL objects; nothing for NULL. */
void map_destroy(map_renderer *r);
/* Light l's map as this frame's fit left it. */
const map_light *map_of_light(const map_renderer *r, int l);
/* The light a technique's state line (its describe) is about, into *l:
 * the first with a map this frame. False, the line being "no light has a
 * map this frame" (written into out), where none has one: before the
 * first frame, or where no light reaches what is seen. */
bool map_described_light(const map_renderer *r, int *l, char *out, size_t size);
/* Appends where light l's map is stored beyond its texture:
 * ", transmittance map: coloured shadows" where it has one (see
 * "Translucent casters" above); where it is in the atlas (see "Atlas"),
 * the atlas's side, the share of it the frame's tiles hold, and the
 * faces given less than asked this frame. */
void map_describe_storage(const map_renderer *r, int l, char *out, size_t size);
/* The casters' hierarchy the camera pass's rays trace against (kept, not
 * copied: it outlives r's frames); NULL: no rays, whatever the settings. */
void map_trace_with(map_renderer *r, const bvh_gpu *casters);
/* The frame's steps (see the top of this file), in their order. Step 1:
 * the camera's depth pre-pass; notes the target the camera pass will draw
 * into (the framebuffer and viewport bound now) and forgets the last
 * frame's maps. */
void map_begin(map_renderer *r, const technique_frame *f);
/* Step 2: fit places light l's map, of any kind (an array map with its
 * size set), at the size of the settings (auto: sized after the fit), and
 * a moment filter's blur is set. False, with no map this frame, where the
 * light is off, no receiver is visible or the fit fails. */
bool map_fit_light(map_renderer *r, const map_settings *settings, const technique_frame *f, int l,
                   map_fit_function fit);
/* Step 3, after step 2 for every light: the depth pass of light l, if
 * fitted (see "Caching" above): its layers from its cache, or rendered
 * with the casters each needs (and a moment filter's blurred). */
void map_draw_depth(map_renderer *r, const map_settings *settings, const technique_frame *f, int l);
/* Step 4: the camera pass, into the target map_begin found. With
 * the eye inside a closed caster (r->closed: its welded edge table, as
 * the volumes weigh it; the eye inside by its winding number), a face
 * that a light outside the mesh reaches on the eye's side is in the
 * mesh's shadow without a read: the light came through the mesh
 * (shaders/map.frag, map_through_closed). */
void map_shade(map_renderer *r, const map_settings *settings, const technique_frame *f);

/* The camera pass's rays (see "Rays") of the last frame that counted
 * them (technique_frame.counters), the pixels those that draw the
 * picture took (a light shaded again in its own rectangle counts there
 * once); false where none has, or the GL cannot count them (said once
 * on stderr). */
bool map_rays_counted(const map_renderer *r, technique_rays *out);

/* The samples light l's map is measured at this frame: where the camera
 * sees receivers, those the light can light (warp_samples_lit), and how
 * many it left out as edge-on to the light. The rays are cast once a
 * frame, on the first call, and only by a frame that measures: the
 * automatic size or a fit like psm's. The samples stay the renderer's
 * until its next call. */
typedef struct map_samples {
    const warp_sample *samples;
    int count, grazing;
    /* The picture's grid found nothing in the light's reach, and a grid
     * was cast over that reach on screen alone (map.c, map_reach_ndc):
     * these are its samples (none: the light lights nothing seen larger
     * than its cells). */
    bool reach_sampled;
} map_samples;
map_samples map_light_samples(map_renderer *r, const technique_frame *f, int l);
/* The map's size in the settings; 0: auto. */
int map_settings_size(const map_settings *settings);
/* How many times finer auto makes the texels of light's map in s:
 * MAP_AUTO_CUT_OUT_FINER where it is hard (not map_light_soft) and
 * reaches a cut-out caster, else 1. */
int map_auto_finer(const map_settings *settings, const scene *s, const scene_light *light);

/* The map as HUD lines name it: its kind and size as chosen ("2D map
 * auto: 4096" where --map-size is auto, "cube map 1024" where it is
 * given; "cube map in atlas tiles auto: 1024", its largest face's, where
 * it is in the atlas). */
void map_size_text(const map_settings *settings, const map_light *m, char *out, size_t size);

/* ---- fitting (map_fit.c) ---- */

/* Fitting (map_fit.c, no GL). map_fit_uniform is
 * demos/shadowmap.c's placement, cascades' for spot and point lights and
 * the fallback of every warp:
 *   spot         a perspective map around the cone, or around the
 *                receivers where they lie in a narrower one (the light
 *                far from them), from the nearest caster in front of the
 *                light to the farthest receiver; a spot wider than 85
 *                degrees as a point light;
 *   directional  an orthographic box around the receivers seen along the
 *                light, deepened towards it to every caster whose box
 *                overlaps them seen from the light (caster selection: so
 *                casters outside the view still cast);
 *   point        one perspective map around the receivers where they lie
 *                in a cone of at most 45 degrees, else a cube map, from
 *                the nearest caster to the farthest receiver.
 * A fit fills the map's kind, layer matrices, depth range (for the inset
 * and the HUD), texel_kind / texel_scale (how the camera pass finds a
 * texel's world size, which the constant and normal-offset biases are
 * measured in) and casters (which objects the depth pass draws; NULL:
 * every caster). */

/* The uniform placement of light `light` of `s` (see "Fitting" above). */
bool map_fit_uniform(const scene *s, int light, map_light *m, const float (*receivers)[3], int receiver_count);
/* The same as a map_fit_function, for map_fit_light: the fit of
 * demos/shadowmap.c and demos/hybrid.c. */
bool map_fit_uniform_light(const technique_frame *f, int light, map_light *m, const float (*receivers)[3],
                           int receiver_count);
/* The depth (view space, along -z) of the nearest caster that can shadow
 * the receivers in lo..hi seen through `view`: of a directional light
 * (orthographic) every caster whose box overlaps lo..hi across the view,
 * of a positional one every caster with a part in front of it; hi[2]
 * where none is nearer. */
float map_nearest_caster(const scene *s, const mat4 view, const vec3 lo, const vec3 hi, bool orthographic);
/* A depth range in view space, near..far (distances along -z), widened by
 * the fit's margin so the points it was fitted to are not clipped by
 * rounding. */
void map_depth_range(float near_plane, float far_plane, float *near_out, float *far_out);
/* Layer `layer` of an array map is the orthographic `projection` of
 * m->cascade_view (glm_ortho: a diagonal and a translation): sets its
 * scale, offset and layer_view_projection. */
void map_cascade_layer(map_light *m, int layer, const mat4 projection);

/* ---- caster culling (map_cull.c) ---- */

/* Caster culling (map_cull.c, no GL; with f->skips->cull_casters). Each
 * layer (a cube's faces each on its own) draws only the casters that can
 * shadow a visible receiver through it. Where receivers read a layer, in
 * its clip space: the NDC rectangle and deepest depth of both the frame's
 * receiver points and the surfaces of the visible receivers' boxes within
 * the light's range inside the layer's sides (a cube's widened by the
 * kernel, whose taps cross its edges), the tighter of the two, grown by
 * the kernel's reach (map_read_reach: its farthest tap, the
 * bilinear footprint, a texel of safety; a cube's taps stretched) and
 * clamped to the layer. A caster's box is needed unless it lies beyond one
 * of the layer's clip planes, or, wholly in front of the centre of
 * projection, its rectangle misses that one or its nearest depth lies
 * beyond the deepest read (any depth with receiver-plane taps; a cube tap
 * compares its own direction's depth, bounded by the point pushed away
 * from the light by the tap's offset; a moment filter's box holds every
 * depth, and reaches its blur's width). Exact: the constant bias moves a
 * point along its ray to the light, which keeps its place in every map,
 * and the depth a culled caster would have stored is never one a read
 * compares with. Not culled: with a normal offset (the point leaves its
 * surface), and light 0's map while the inset shows it. After the depth
 * pre-pass (technique_see) a caster must also reach the layer's mask of
 * the visible pixels (light_mask.h), made of the slabs (visible.h) the
 * light reaches (scene_light_reaches_box: beyond its range or outside its
 * cone a pixel reads no map), where a layer is read at all. The fit never
 * depends on culling. */

/* How a layer is read: the kernel's reach in texels from a point's
 * projection (map_read_reach), the map's size, whether it is a cube
 * face (taps cross its edges and compare their own direction's depth,
 * about `center`, the light) and whether taps compare any depth
 * (receiver-plane). */
typedef struct map_read_setup {
    float reach;
    int size;
    bool cube, any_depth;
    float center[3];
} map_read_setup;
/* Where receivers read a layer: an NDC rectangle (grown by the reach,
 * within [-1, 1]) and the deepest NDC depth they compare; empty: none.
 * near_drawn: the layer draws the casters before its near plane (a cube
 * face's, at its near depth: map.c's map_depth_begin), which no read
 * then lets through. */
typedef struct map_reads {
    bool empty, near_drawn;
    float lo[2], hi[2], max_depth;
} map_reads;
/* area: the light has a radius (soft under pcss, or a moment filter's
 * wide blur). */
float map_read_reach(const map_settings *settings, map_kind kind, bool area);
/* Light `light` of the settings' technique gets soft shadows: an area
 * light, with --soft pcss, read by no moment filter, and not while auto
 * is unfiltered. */
bool map_light_soft(const map_settings *settings, const scene_light *light);
/* The technique's area_light words (technique.h) under the settings. */
const char *map_area_light_text(const map_settings *settings, const scene_light *light);
/* The reads of the layer of matrix `layer` by the receiver points (NULL:
 * no bound from them) and by the surfaces of the receiver boxes (lo, hi). */
void map_layer_reads(const mat4 layer, const map_read_setup *setup, const float (*points)[3], int point_count,
                     const float (*boxes)[2][3], int box_count, map_reads *out);
/* The caster box lo..hi may change a read of the layer. */
bool map_caster_read(const map_reads *reads, const mat4 layer, const vec3 lo, const vec3 hi);
/* The boxes of f's receivers that meet the view, clipped to light's range
 * (at most the scene's object count); returns how many. */
int map_light_receivers(const technique_frame *f, int light, float (*boxes)[2][3]);

/* Step 5 of the frame: those of settings->overlay drawn after the camera
 * pass, for the lights with a map this frame: frusta, the map inset (see
 * below), the cascades' key, the texel-size and penumbra heat maps'
 * legends (a colour bar with labelled ticks). */
void map_draw_overlays(map_renderer *r, const map_settings *settings, const technique_frame *f);

/* A warp's space in a second viewport (psm's post-perspective view): the
 * scene carried into `space` and clipped to its clip cube, the cube's
 * edges and the map's frustum there (map_view_projection: world -> map
 * clip), seen from above one side, in the bottom-left half of the picture. */
typedef struct map_warp_view {
    render_program program; /* post_perspective.vert/.frag */
    int space;
} map_warp_view;
bool map_warp_view_init(map_warp_view *w);
void map_warp_view_destroy(map_warp_view *w);
void map_warp_view_draw(const map_warp_view *w, map_renderer *r, const technique_frame *f, const mat4 space,
                        const mat4 map_view_projection);

#endif
