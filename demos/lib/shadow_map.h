/* shadow_map: the shadow-map library that demos/shadowmap.c (uniform
 * maps), demos/psm.c (warped maps) and demos/cascades.c (array maps for
 * directional lights, the uniform fit for the others) are built on. GL
 * lives here, not in the techniques. Each part of the manual stands beside
 * what it describes: map size, the camera pass and its filters, soft
 * shadows, moment maps, overlays, storage, array maps, caching, the depth
 * pass, fitting and caster culling.
 *
 * Using it. A technique keeps a shadow_map_settings and a
 * shadow_map_renderer in its static state, lists SHADOW_MAP_PARAMS(its
 * settings) among its parameters (the same flags and keys everywhere),
 * calls shadow_map_init / shadow_map_destroy from its own init / destroy,
 * and each frame the steps below from its render function, in this order,
 * with its own fitting function: the one place where techniques differ is
 * how a light's map is placed.
 *
 *   1. shadow_map_begin: the camera's depth pre-pass, read back
 *      (technique_see) so that the depth passes cull the casters it shows
 *      hidden; the receiver points are the frame's (technique.h), the
 *      corners of the part of every receiver's box inside the camera's
 *      frustum;
 *   2. per light, shadow_map_fit_light: fit(frame, light, map, receivers)
 *      places the map (a fit that measures its texels, as psm does, takes
 *      the samples of shadow_map_light_samples) and the automatic size
 *      sizes it; false where the light is off or nothing can be shadowed
 *      (then the light is added unshadowed);
 *   3. per fitted light, shadow_map_draw_depth: the depth pass renders
 *      each layer that its cache cannot give, with the casters that layer
 *      needs;
 *   4. shadow_map_shade, the camera pass: one pass (GL_EQUAL depth) that
 *      shades every light on where its map lets it through, and the
 *      ambient term; each visible pixel is filtered once per light that
 *      adds to it (beyond a light's range, outside its cone or facing away
 *      the filter is skipped), and a light that lights a small part of the
 *      frame is shaded in a pass of its own over it
 *      (shading_split_lights);
 *   5. shadow_map_draw_overlays: those of settings->overlay.
 */
#ifndef SHADOW_MAP_H
#define SHADOW_MAP_H

#include <GLFW/glfw3.h>
#include <stdbool.h>

#include "technique.h"
#include "warp.h"

/* Map size (--map-size; auto, the default). Fixed sizes are as given.
 * Auto fits the map at SHADOW_MAP_AUTO_MAX_SIZE, measures the mean size
 * on screen of its texels at shadow_map_light_samples (the dp/ds of the
 * perspective shadow map papers, warp_sample_texel_pixels: a
 * WARP_SAMPLES_X x WARP_SAMPLES_Y grid of pixels cast onto the receivers' boxes, the same measure psm judges
 * its warps by; samples beyond the light's range or outside the map left
 * out) and takes the smallest power of two from MIN to MAX at which a
 * texel covers at most TEXEL_PIXELS pixels on average
 * (shadow_map_auto_size; MAX where most receivers seen are edge-on to the
 * light): shadows no sharper than the pixels that show them, and no depth
 * pass larger than that needs. The size follows the picture's: half as
 * wide a picture, half the size (test_shadowmap's test_map_size_from_need
 * checks the sizes it picks). A cube map has one size for its six faces
 * (one cube texture, so that kernels filter across face edges): the mean
 * is over the samples on all faces. FALLBACK where nothing can be measured
 * (no sample of the pixel grid lands on a receiver the light reaches). An
 * array map is not sized here: its fit sets its size. */
#define SHADOW_MAP_AUTO_MIN_SIZE 256
#define SHADOW_MAP_AUTO_MAX_SIZE 4096
#define SHADOW_MAP_AUTO_TEXEL_PIXELS 1.0f
#define SHADOW_MAP_AUTO_FALLBACK_SIZE 2048

/* The defaults of the numbers, from `make bench` (see demos/shadowmap.c). */
#define SHADOW_MAP_CONSTANT_TEXELS 1.0f
#define SHADOW_MAP_SLOPE_FACTOR 1.5f
#define SHADOW_MAP_SLOPE_UNITS 1.0f

/* The camera pass (shaders/shadowmap.frag: shadowmap.glsl's kernels,
 * shadowmap_2d.glsl's, shadowmap_cube.glsl's and shadowmap_array.glsl's
 * maps, the flat ones' filter shadowmap_flat.glsl's, one program per
 * combination of the lights' kinds of map, shadow_map_light_kind) moves
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
 *            pcfN's weights reach a texel farther; shaders/shadowmap.glsl
 *            derives it). A cube map's texel grid is not at hand in
 *            direction space: there the taps are a point's on a texel
 *            corner, across the direction;
 *   poisson  16 bilinear tests on a Poisson disc rotated per pixel by a
 *            hash of the pixel (frames stay deterministic), of scale
 *            SHADOW_MAP_POISSON_SCALE_TEXELS;
 *   vsm, evsm2, evsm4, msm  the moment maps (below, "Moment shadow maps");
 *   auto     (the default) poisson, but none while the constant or the
 *            slope-scaled bias is off (--no-constant-bias, --no-slope-bias,
 *            keys C and L), area lights hard too: a kernel or PCSS
 *            averages acne's stripes into a faint darkening, one nearest
 *            test shows each stripe. Any other choice holds with the
 *            biases off (shadow_map_filter_in_use).
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
 * first): shadow_map_filters, shadow_map_depths, shadow_map_kernel_depths. */
typedef enum shadow_map_filter {
    SHADOW_MAP_FILTER_AUTO,
    SHADOW_MAP_FILTER_POISSON,
    SHADOW_MAP_FILTER_NONE,
    SHADOW_MAP_FILTER_HW,
    SHADOW_MAP_FILTER_PCF3,
    SHADOW_MAP_FILTER_PCF5,
    SHADOW_MAP_FILTER_PCF7,
    SHADOW_MAP_FILTER_TENT3,
    SHADOW_MAP_FILTER_TENT5,
    SHADOW_MAP_FILTER_VSM,
    SHADOW_MAP_FILTER_EVSM2,
    SHADOW_MAP_FILTER_EVSM4,
    SHADOW_MAP_FILTER_MSM,
} shadow_map_filter;
typedef enum shadow_map_depth { SHADOW_MAP_DEPTH_24, SHADOW_MAP_DEPTH_32F } shadow_map_depth;
typedef enum shadow_map_soft { SHADOW_MAP_SOFT_PCSS, SHADOW_MAP_SOFT_OFF } shadow_map_soft;
typedef enum shadow_map_kernel_depth {
    SHADOW_MAP_KERNEL_DEPTH_RECEIVER_PLANE,
    SHADOW_MAP_KERNEL_DEPTH_CENTRE,
} shadow_map_kernel_depth;

extern const char *const shadow_map_sizes[];
extern const char *const shadow_map_filters[];
extern const char *const shadow_map_depths[];
extern const char *const shadow_map_kernel_depths[];
extern const char *const shadow_map_softs[];

typedef struct shadow_map_settings {
    int map_size;     /* choice: shadow_map_sizes */
    int filter;       /* choice: shadow_map_filter; read through shadow_map_filter_in_use */
    int depth;        /* choice: shadow_map_depth */
    int kernel_depth; /* choice: shadow_map_kernel_depth */
    int soft;         /* choice: shadow_map_soft, what an area light (radius > 0) gets */
    int overlay;      /* choice: the technique's own list, SHADOW_MAP_OVERLAY_NAMES first */
    bool no_constant_bias, no_slope_bias, no_early_out;
    float constant_texels, slope_factor, slope_units, normal_texels; /* 0: defaults */
    float depth_bias_slope, depth_bias_min;                          /* the tutorials' bias; 0: none */
    /* Not a flag: the technique's overlay list goes on with
     * SHADOW_MAP_ARRAY_OVERLAY_NAMES (cascades sets it; psm's list goes on
     * with its own). */
    bool array_overlays;
} shadow_map_settings;

/* The filter that reads the map: settings->filter, or what auto stands
 * for (above, "The camera pass"). */
shadow_map_filter shadow_map_filter_in_use(const shadow_map_settings *settings);
/* Auto stands for none because a bias is off: acne shows unblurred. */
bool shadow_map_shows_acne(const shadow_map_settings *settings);
/* Appends ", filter: none (shows acne)" to a technique's state line (its
 * describe) while shadow_map_shows_acne; nothing otherwise. */
void shadow_map_describe_filter(const shadow_map_settings *settings, char *out, size_t size);

/* The texel-size heat map's ends, log2 of a texel's size in pixels: blue
 * at a quarter pixel and below, green at one, red at 32 and more. The
 * shaders (texel_heat.glsl) and the legend take them from here. */
#define SHADOW_MAP_HEAT_LOG2_MIN (-2)
#define SHADOW_MAP_HEAT_LOG2_MAX 5
/* The penumbra overlay's ends, log2 of the penumbra radius PCSS estimated
 * (world units): the texel-size ramp moved to start at 1/64 unit (blue),
 * green at 1/16, red at 2 and more. */
#define SHADOW_MAP_PENUMBRA_LOG2_MIN (-6)
#define SHADOW_MAP_PENUMBRA_LOG2_MAX                                                                                 \
    (SHADOW_MAP_PENUMBRA_LOG2_MIN + SHADOW_MAP_HEAT_LOG2_MAX - SHADOW_MAP_HEAT_LOG2_MIN)
/* Overlays, for lectures (shadow_map_overlay.c), drawn into the picture:
 *   texels      the map's texel boundaries on the receivers (camera pass);
 *   texel-size  a heat map of a texel's size in pixels (camera pass);
 *   penumbra    a soft light's receivers coloured by the penumbra radius
 *               PCSS estimated there (world units; camera pass), where
 *               its blocker search found a blocker;
 *   frustum     each layer's frustum in wireframe (shadow_map_draw_frustum);
 *   map         light 0's map as an inset of linear depth (a cube's faces
 *               in two rows: +X -X +Y, then -Y +Z -Z; an array's layers
 *               in a row, each an inset), each inset fitted to what its
 *               layer holds and labelled with it (see "The map inset"
 *               below);
 *   all         texels, frustum and map.
 * A technique's overlay list starts with SHADOW_MAP_OVERLAY_NAMES and may
 * go on with its own (psm's post-perspective view: shadow_map_warp_view). */
#define SHADOW_MAP_OVERLAY_NAMES "none", "all", "texels", "frustum", "map", "texel-size", "penumbra"
enum {
    SHADOW_MAP_OVERLAY_NONE,
    SHADOW_MAP_OVERLAY_ALL,
    SHADOW_MAP_OVERLAY_TEXELS,
    SHADOW_MAP_OVERLAY_FRUSTUM,
    SHADOW_MAP_OVERLAY_MAP,
    SHADOW_MAP_OVERLAY_TEXEL_SIZE,
    SHADOW_MAP_OVERLAY_PENUMBRA,
    SHADOW_MAP_OVERLAY_COUNT
};
/* An array map's technique lists this one next (and sets the settings'
 * array_overlays): light 0's layers' receivers tinted each in its colour
 * (the blend band mixing two; shadow_map_cascade_colors) with a key in
 * the bottom-left corner (each layer's colour, number and slice of view
 * depth: from cascade_split[k] to [k + 1]), and its map as an inset (an
 * array's layers in a row; a spot's or point light's map as "map" shows
 * it). */
#define SHADOW_MAP_ARRAY_OVERLAY_NAMES "cascades"
enum { SHADOW_MAP_OVERLAY_CASCADES = SHADOW_MAP_OVERLAY_COUNT };
/* The settings' overlay is that one. */
#define SHADOW_MAP_SHOWS_CASCADES(st) ((st)->array_overlays && (st)->overlay == SHADOW_MAP_OVERLAY_CASCADES)

/* The parameters every shadow-map technique shares, for its params array. */
/* clang-format off: a flag a line or two, as the techniques' own tables */
#define SHADOW_MAP_PARAMS(s)                                                                                                      \
    {"map-size",                                                                                                                  \
     "texels on a side; auto: a texel about a pixel where shadows are seen (cascades: 1024 a cascade)",                           \
     GLFW_KEY_M,                                                                                                                  \
     FLAGS_CHOICE,                                                                                                                \
     .index = &(s).map_size,                                                                                                      \
     .choices = shadow_map_sizes},                                                                                                \
        {"filter",                                                                                                                \
         "what reads the map; auto: poisson, but none (area lights hard) while a bias is off, so that acne shows",                \
         GLFW_KEY_F,                                                                                                              \
         FLAGS_CHOICE,                                                                                                            \
         .index = &(s).filter,                                                                                                    \
         .choices = shadow_map_filters},                                                                                          \
        {"depth",                                                                                                                 \
         "depth format: 24-bit or 32-bit float",                                                                                  \
         GLFW_KEY_D,                                                                                                              \
         FLAGS_CHOICE,                                                                                                            \
         .index = &(s).depth,                                                                                                     \
         .choices = shadow_map_depths},                                                                                           \
        {"constant-bias", "acne: surfaces shadow themselves in stripes", GLFW_KEY_C, FLAGS_TOGGLE,                                \
         .disabled = &(s).no_constant_bias},                                                                                      \
        {"slope-bias", "acne where surfaces turn away from the light", GLFW_KEY_L, FLAGS_TOGGLE,                                  \
         .disabled = &(s).no_slope_bias},                                                                                         \
        {"early-out", "wide kernels: four rim taps first, the whole kernel only where they disagree", GLFW_KEY_E,                 \
         FLAGS_TOGGLE, .disabled = &(s).no_early_out},                                                                            \
        {"soft",                                                                                                                  \
         "area lights (radius > 0): pcss, soft shadows that harden at contact; off: hard, from the centre",                       \
         GLFW_KEY_Y,                                                                                                              \
         FLAGS_CHOICE,                                                                                                            \
         .index = &(s).soft,                                                                                                      \
         .choices = shadow_map_softs},                                                                                            \
        {"kernel-depth",                                                                                                          \
         "what each kernel tap compares: the receiver plane's depth there, or the centre's",                                      \
         GLFW_KEY_P,                                                                                                              \
         FLAGS_CHOICE,                                                                                                            \
         .index = &(s).kernel_depth,                                                                                              \
         .choices = shadow_map_kernel_depths},                                                                                    \
        {"constant-texels",                                                                                                       \
         "constant bias, in map texels of world distance",                                                                        \
         0,                                                                                                                       \
         FLAGS_NUMBER,                                                                                                            \
         .number = &(s).constant_texels,                                                                                          \
         .fallback = SHADOW_MAP_CONSTANT_TEXELS,                                                                                  \
         .min = 0.01f,                                                                                                            \
         .max = 64},                                                                                                              \
        {"slope-factor",                                                                                                          \
         "slope-scaled bias: glPolygonOffset factor",                                                                             \
         0,                                                                                                                       \
         FLAGS_NUMBER,                                                                                                            \
         .number = &(s).slope_factor,                                                                                             \
         .fallback = SHADOW_MAP_SLOPE_FACTOR,                                                                                     \
         .min = 0.01f,                                                                                                            \
         .max = 64},                                                                                                              \
        {"slope-units",                                                                                                           \
         "slope-scaled bias: glPolygonOffset units",                                                                              \
         0,                                                                                                                       \
         FLAGS_NUMBER,                                                                                                            \
         .number = &(s).slope_units,                                                                                              \
         .fallback = SHADOW_MAP_SLOPE_UNITS,                                                                                      \
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
    {                                                                                                                             \
        "depth-bias-min", "tutorial bias: minimum, in map depth (0: off)", 0, FLAGS_NUMBER,                                       \
            .number = &(s).depth_bias_min, .fallback = 0, .min = 0, .max = 1                                                      \
    }
/* clang-format on */

/* The shape of the camera pass's kernel (the shaders' u_filter). The
 * C/GLSL contract: the kernel shapes, texel kinds and cube faces are C
 * enums passed to the shaders as defines (common/gl/shader.h); the shaders
 * compare with their names. */
typedef enum shadow_map_kernel {
    SHADOW_MAP_KERNEL_SINGLE,  /* one test: nearest or bilinear by the texture's filter */
    SHADOW_MAP_KERNEL_GRID,    /* N x N bilinear tests a texel apart (u_kernel: N) */
    SHADOW_MAP_KERNEL_POISSON, /* the rotated Poisson disc (u_kernel: its scale in texels) */
    SHADOW_MAP_KERNEL_TENT,    /* an N x N tent from ((N + 1)/2)^2 bilinear tests (u_kernel: N) */
} shadow_map_kernel;
/* The Poisson disc's scale: its unit circle is this many texels across,
 * the scale that misclassifies least on the standard scenes. Its points
 * reach radius 1.234 of that circle, so the taps span 3.7 texels (see
 * shaders/shadowmap.glsl). */
#define SHADOW_MAP_POISSON_SCALE_TEXELS 3

/* Soft shadows. An area light (radius > 0) with --soft pcss, the default,
 * is filtered by percentage-closer soft shadows instead of the kernel
 * (shaders/shadowmap_soft.glsl: a blocker search, the penumbra by similar
 * triangles, a filter of its width), its taps on the receiver's plane; the
 * blocker search reads the map's depths on unit SHADOW_MAP_DEPTH_UNITS +
 * light through r->depth_sampler (compare mode off). Its bit of the key's
 * soft_lights compiles that code in: a light of radius 0 runs the code it
 * always did. The blocker search's and the filter's taps, and the most
 * radius of either disc in texels, which caster culling allows for
 * (shadow_map_read_reach); the least is the hard default's disc's,
 * SHADOW_MAP_POISSON_SCALE_TEXELS / 2. */
#define SHADOW_MAP_SOFT_SEARCH_TAPS 16
#define SHADOW_MAP_SOFT_FILTER_TAPS 32
#define SHADOW_MAP_SOFT_MAX_TEXELS 48

/* Moment shadow maps (shadow_map_moments.c, shaders/moments.glsl): the
 * filters vsm, evsm2, evsm4 and msm filter the map before the camera pass
 * instead of its reads: the depth pass draws the receivers that cast
 * nothing too, then each layer it rendered becomes moments of the depth,
 * blurred by a separable box, in a float colour texture beside the depth
 * texture (texture.moments), which the camera pass reads once, bilinear,
 * on the light's depth unit. They replace the kernel and PCSS alike: an
 * area light's box is its casters' mean penumbra wide (one width, no
 * contact hardening). Which moments a filter stores (the shaders'
 * SHADOW_MAP_PASS_MOMENTS): */
typedef enum shadow_map_moments {
    SHADOW_MAP_MOMENTS_NONE,
    SHADOW_MAP_MOMENTS_VSM,   /* d, d^2: Chebyshev's bound */
    SHADOW_MAP_MOMENTS_EVSM2, /* e^(c d), its square */
    SHADOW_MAP_MOMENTS_EVSM4, /* and -e^(-c d), its square */
    SHADOW_MAP_MOMENTS_MSM,   /* d, d^2, d^3, d^4: Hamburger 4MSM */
} shadow_map_moments;
/* The box's radius in texels (the box is 2 radius + 1 texels across, its
 * two end texels weighted by the fraction): a hard light's, and the most an
 * area light's may take (a wider one shrinks an auto-sized map, else is
 * clamped): the blur's cost grows with its width. */
#define SHADOW_MAP_MOMENTS_HARD_BLUR_TEXELS 1
#define SHADOW_MAP_MOMENTS_MAX_BLUR_TEXELS 12
/* The moments a filter stores; SHADOW_MAP_MOMENTS_NONE for the kernels. */
shadow_map_moments shadow_map_filter_moments(int filter);

/* How the camera pass finds the world size of a texel at a point (the
 * shaders' u_texel_kind). */
typedef enum shadow_map_texel_kind {
    SHADOW_MAP_TEXEL_ORTHOGRAPHIC, /* texel_scale */
    SHADOW_MAP_TEXEL_PERSPECTIVE,  /* texel_scale x depth along the light's axis */
    SHADOW_MAP_TEXEL_PROJECTIVE,   /* from the matrix's derivatives: any warp */
} shadow_map_texel_kind;

/* Storage (shadow_map). A map has a kind and layers: SHADOW_MAP_2D has
 * one layer (spot, directional, any warped map), SHADOW_MAP_CUBE six, the
 * faces in GL's order (SHADOW_MAP_FACE_*), SHADOW_MAP_ARRAY layer_count
 * of them (1..SHADOW_MAP_MAX_ARRAY_LAYERS) in one GL_TEXTURE_2D_ARRAY, for
 * cascades (one layer per slice of the view). Each layer has its own
 * matrix, layer_view_projection[layer] (world -> that layer's clip space);
 * the depth range, texel measure and caster list are the map's. The
 * texture is (re)made only when kind, size, layer count, depth format or
 * filter change; every kind compares in hardware (compare mode on, clamped
 * to its edges). */
typedef enum shadow_map_kind { SHADOW_MAP_2D, SHADOW_MAP_CUBE, SHADOW_MAP_ARRAY } shadow_map_kind;
/* A cube's faces in GL's order (GL_TEXTURE_CUBE_MAP_POSITIVE_X + face). */
enum {
    SHADOW_MAP_FACE_POSITIVE_X,
    SHADOW_MAP_FACE_NEGATIVE_X,
    SHADOW_MAP_FACE_POSITIVE_Y,
    SHADOW_MAP_FACE_NEGATIVE_Y,
    SHADOW_MAP_FACE_POSITIVE_Z,
    SHADOW_MAP_FACE_NEGATIVE_Z,
    SHADOW_MAP_CUBE_FACES
};
/* An array map's most layers: the most cascades. */
#define SHADOW_MAP_MAX_ARRAY_LAYERS 8
/* Room for the layers of any kind. */
#define SHADOW_MAP_MAX_LAYERS SHADOW_MAP_MAX_ARRAY_LAYERS
_Static_assert(SHADOW_MAP_MAX_LAYERS >= SHADOW_MAP_CUBE_FACES, "a map holds a cube's faces");

/* The GL texture behind a map, and what it was made with. */
typedef struct shadow_map_texture {
    unsigned id;
    unsigned moments; /* a moment filter's blurred moments (the map's kind) */
    unsigned blur[2]; /* one layer's moments, then those blurred along x */
    shadow_map_kind kind;
    int size, layer_count, depth, filter;
} shadow_map_texture;

/* Array maps (demos/cascades.c's cascades). Every layer is an orthographic
 * box of one light view, cascade_view (world -> light space, orthonormal),
 * so a layer is that view, then a scale and an offset per axis
 * (cascade_scale, cascade_offset: its glm_ortho's diagonal and
 * translation; shadow_map_cascade_layer sets them with its
 * layer_view_projection). The camera pass reads layer k where the
 * camera's view depth lies between cascade_split[k] and [k + 1] (beyond
 * the ends, the nearest layer), and over the last cascade_blend of a
 * slice reads layer k + 1 at a share of the pixels rising linearly to 1
 * (dithered by a hash of the pixel: each pixel filters one layer), so the
 * switch of texel size shows no seam; the box of layer k + 1 covers that
 * band. Per layer the shader has 2 vec4 (scale, offset; their w the
 * slice's ends), not a mat4: a program with array lights holds 2 x
 * SCENE_MAX_LIGHTS x SHADOW_MAP_MAX_ARRAY_LAYERS vec4 of them, where mat4s
 * would take twice that. A layer's world texel is 2 / (size x its smaller
 * xy scale): the constant and normal-offset biases are measured in the
 * texel of the layer read. An array light's sampler is on its own unit,
 * as any light's map (a light has one kind of map). --map-size auto does
 * not size an array map: the fit sets its size (a cascade's texels are
 * sized by their count, not measured).
 *
 * One light's map: what it was fitted to, and its texture. */
typedef struct shadow_map {
    shadow_map_kind kind;
    int layer_count; /* 1 (2D), SHADOW_MAP_CUBE_FACES, or 1..SHADOW_MAP_MAX_ARRAY_LAYERS (array) */
    int size;        /* texels on a side, set before fitting */
    mat4 layer_view_projection[SHADOW_MAP_MAX_LAYERS]; /* world -> each layer's clip space */
    float near_plane, far_plane;
    shadow_map_texel_kind texel_kind;
    float texel_scale;
    bool orthographic;   /* the stored depth is linear (the inset shows it as it is) */
    const bool *casters; /* objects to draw into the map; NULL: every caster */
    /* An array map's layers (see "Array maps" above): */
    mat4 cascade_view;
    float cascade_scale[SHADOW_MAP_MAX_ARRAY_LAYERS][3], cascade_offset[SHADOW_MAP_MAX_ARRAY_LAYERS][3];
    float cascade_split[SHADOW_MAP_MAX_ARRAY_LAYERS + 1]; /* camera view depths */
    float cascade_blend;                                  /* fraction of a slice */
    float blur_texels[SHADOW_MAP_MAX_LAYERS];             /* a moment filter's box radius per layer */
    shadow_map_texture texture;
} shadow_map;

/* What light i is in the camera pass (the shaders'
 * SHADOW_MAP_LIGHT_KIND_<i>): off, on without a map (nothing it reaches
 * receives: added unshadowed), with a 2D map, a cube map or an array map. */
typedef enum shadow_map_light_kind {
    SHADOW_MAP_LIGHT_OFF,
    SHADOW_MAP_LIGHT_UNSHADOWED,
    SHADOW_MAP_LIGHT_2D,
    SHADOW_MAP_LIGHT_CUBE,
    SHADOW_MAP_LIGHT_ARRAY
} shadow_map_light_kind;
/* Light i's kind, and its map's shadow_map_texel_kind, in bits
 * SHADOW_MAP_LIGHT_KIND_BITS i and up of a key's kinds and texel_kinds. */
#define SHADOW_MAP_LIGHT_KIND_BITS 3
_Static_assert(SCENE_MAX_LIGHTS *SHADOW_MAP_LIGHT_KIND_BITS <= 32, "a combination of kinds fits an unsigned");
/* The camera programs kept: the keys a run goes through (lights coming
 * into reach, a point light's warp falling back to a cube, the kernels a
 * lecturer or the benchmark tries) are compiled once each, the oldest
 * dropped beyond this many. */
#define SHADOW_MAP_CAMERA_PROGRAMS 16
/* Texture units: light i's map, of any kind, on unit i; the samplers a
 * program holds but does not read (an array's elements below the last one
 * used stay active) on one unit per sampler type after those, the
 * comparisons' at SHADOW_MAP_IDLE_UNITS + t, the depths' at
 * SHADOW_MAP_IDLE_UNITS + SHADOW_MAP_SAMPLER_TYPES + t: samplers of two
 * types on one unit would fail every draw. */
#define SHADOW_MAP_IDLE_UNITS SCENE_MAX_LIGHTS
/* A soft light's map is also read as depth (compare mode off, by
 * r->depth_sampler): light i's on unit SHADOW_MAP_DEPTH_UNITS + i, after
 * the idle units of the comparison and the depth samplers' types; a
 * moment filter's light reads its moments there (the same sampler
 * types). GL 3.3 promises 16 units, which hold the depth units of the
 * first lights only: a light whose depth unit the GL lacks
 * (r->texture_units) is drawn hard (a moment filter's with one bilinear
 * test), and says so. */
#define SHADOW_MAP_SAMPLER_TYPES 3
#define SHADOW_MAP_DEPTH_UNITS (SHADOW_MAP_IDLE_UNITS + 2 * SHADOW_MAP_SAMPLER_TYPES)

/* What a camera program is compiled for (shaders/shadowmap.frag's
 * SHADOW_MAP_LIGHT_KIND_<i>, SHADOW_MAP_TEXEL_KIND_<i> and
 * SHADOW_MAP_PASS_*): whatever chooses code rather than a number, so
 * that a program holds only the code it runs. As uniforms every pixel
 * would run every choice's code: llvmpipe runs both sides of a branch,
 * masked. All unsigned: keys compare with memcmp. */
typedef struct shadow_map_camera_key {
    unsigned kinds, texel_kinds; /* per light (SHADOW_MAP_LIGHT_KIND_BITS) */
    unsigned shape, kernel;      /* shadow_map_kernel, N or the disc's scale */
    unsigned soft_lights;        /* bit i: light i is soft (shadowmap_soft.glsl) */
    unsigned moments;            /* shadow_map_moments of the filter */
    unsigned moment_lights;      /* bit i: light i reads its moment map */
    unsigned early_out, receiver_plane, show_texels, show_texel_size, show_cascades, show_penumbra;
} shadow_map_camera_key;

/* The camera pass's program (lit.vert with shadowmap.frag) for one key,
 * and its uniforms: the pass's, then each light's (-1 where its kind has
 * none). */
typedef struct shadow_map_camera_program {
    render_program program;
    shadow_map_camera_key key;
    int constant_bias, normal_offset, depth_bias, closed_outside, view_depth, cascade_blend;
    struct {
        int map_size, light_matrix, light_inverse, light_size, texel_scale, near_plane, far_plane, cascade_count;
        int cascade_scale, cascade_offset; /* the light's first layer's element */
    } lights[SCENE_MAX_LIGHTS];
} shadow_map_camera_program;

/* overlay.vert with overlay_lines.frag: world-space lines in one colour. */
typedef struct shadow_map_lines_program {
    render_program program;
    int color;
} shadow_map_lines_program;

/* overlay.vert with overlay_map.frag: a map's reduction as an inset of
 * linear depth. */
typedef struct shadow_map_inset_program {
    render_program program;
    int reduced, kind, layer, size, factor, orthographic, near_plane, far_plane, held;
} shadow_map_inset_program;

/* overlay.vert with overlay_reduce.frag, for a map of one kind: the
 * inset's reduction, loaded when an inset first needs it. */
typedef struct shadow_map_reduce_program {
    render_program program;
    int factor, layer;
} shadow_map_reduce_program;

/* overlay.vert with overlay_heat_legend.frag: the texel-size legend's bar. */
typedef struct shadow_map_legend_program {
    render_program program;
    int log2_range;
} shadow_map_legend_program;

/* Vertices in the overlay buffer: a frustum's 12 edges take 24 line
 * ends; the legend's panel, ticks and labels, two triangles a rectangle
 * (its three labels: about 70 of stb_easy_font's quads); the buffer holds
 * the larger. */
#define SHADOW_MAP_OVERLAY_VERTICES 24
#define SHADOW_MAP_LEGEND_VERTICES 1200

/* A moment blur pass (shaders/shadow_moments.frag) and its uniforms. */
typedef struct shadow_map_blur_program {
    unsigned id;
    int radius, axis, layer;
} shadow_map_blur_program;

/* What a light's map was rendered with (the cache's key): all ints, so
 * that it compares with memcmp. */
typedef struct shadow_map_depth_key {
    unsigned texture;
    int size, depth, filter, no_slope_bias;
    float slope_factor, slope_units;
} shadow_map_depth_key;

/* Caching. Per light and layer the renderer keeps what the layer holds:
 * its matrix (bit for bit), the casters drawn, a moment filter's blur
 * width, and per light the texture, size, depth format, filter and slope
 * bias. A layer is reused, with no depth pass, while the scene and the
 * light have not changed (f->changed), those are the same and the casters
 * it needs are among those drawn: a layer with more casters than needed
 * decides every read as one with exactly those. A remade texture, a frame
 * with the light skipped or unfitted, or any change empties the light's
 * cache. Counted in f->counts (casters per light: drawn into any layer, or
 * culled; layers rendered and reused).
 *
 * What each layer of a light's map holds. */
typedef struct shadow_map_cache {
    shadow_map_depth_key key;
    bool valid[SHADOW_MAP_MAX_LAYERS];
    mat4 layer_view_projection[SHADOW_MAP_MAX_LAYERS];
    float blur_texels[SHADOW_MAP_MAX_LAYERS];
    bool *drawn[SHADOW_MAP_MAX_LAYERS]; /* per object: drawn into the layer */
} shadow_map_cache;

/* A technique's maps and their GL objects. */
typedef struct shadow_map_renderer {
    render_program depth;
    shadow_map_camera_program camera[SHADOW_MAP_CAMERA_PROGRAMS];
    int camera_count, camera_oldest;
    shadow_map_lines_program lines;
    shadow_map_inset_program inset;
    shadow_map_legend_program legend;
    unsigned framebuffer, overlay_vao, overlay_buffer;
    /* The moment maps' passes: per moment kind the depths' moments from
     * each kind of map, and the box along an axis; their framebuffer and
     * the empty vertex array of their full-screen triangle (loaded as
     * needed). */
    shadow_map_blur_program blur_depth[SHADOW_MAP_MOMENTS_MSM + 1][SHADOW_MAP_ARRAY + 1], blur_moments;
    unsigned blur_framebuffer, blur_vao;
    /* The map inset's reduction (shadow_map_overlay.c) of light 0's map:
     * per kind its program; an RG32F array texture, a layer per map layer
     * and inset_blocks texels on a side (blocks of inset_factor texels on
     * a side), and its framebuffer; each layer's nearest and farthest held
     * depth. Current until the depth pass renders a layer of light 0's
     * map (made again only then: a cached map is not reduced again);
     * failed (said once): no inset is drawn. */
    shadow_map_reduce_program reduce[SHADOW_MAP_ARRAY + 1];
    unsigned inset_texture, inset_framebuffer;
    int inset_blocks, inset_layers, inset_factor;
    float inset_held[SHADOW_MAP_MAX_LAYERS][2];
    bool inset_current, inset_failed;
    bool blur_failed;        /* said once: moment filters read one bilinear depth test */
    unsigned depth_sampler;  /* a map read as depth: compare mode off, nearest */
    int texture_units;       /* GL_MAX_TEXTURE_IMAGE_UNITS */
    unsigned soft_warned;    /* bit i: light i's treatment said on stderr */
    unsigned moments_warned; /* bit i: light i's lack of a moment unit said on stderr */
    shadow_map maps[SCENE_MAX_LIGHTS];
    shadow_map_cache caches[SCENE_MAX_LIGHTS];
    int object_count;                    /* the scene's, at init: the sets' size */
    bool *needed[SHADOW_MAP_MAX_LAYERS]; /* this frame's casters of each layer of one light */
    float (*receiver_boxes)[2][3];       /* one light's visible receivers' boxes within its range */
    light_mask *masks;                   /* one light's layers' masks of the visible pixels */
    bool *closed;                        /* per object: a caster whose mesh is closed */
    /* Where the camera sees receivers (warp_samples; -1: not cast yet this
     * frame), and those light sample_light is measured at
     * (warp_samples_lit): shadow_map_light_samples. */
    warp_sample hits[WARP_SAMPLE_COUNT], samples[WARP_SAMPLE_COUNT];
    int hit_count, sample_count, sample_light;
    int grazing_count; /* of sample_light's: the hits left out as edge-on to it */
    /* This frame's, from shadow_map_begin on: the target the camera pass
     * draws into, and which lights have a map. */
    int target_framebuffer, viewport[4];
    bool fitted[SCENE_MAX_LIGHTS];
} shadow_map_renderer;

/* The frame a fit takes: f->fit, where the host holds the fit to another
 * camera (technique.h), else f itself. */
const technique_frame *shadow_map_fit_frame(const technique_frame *f);
typedef bool (*shadow_map_fit_function)(const technique_frame *f, int light, shadow_map *m,
                                        const float (*receivers)[3], int receiver_count);

/* gpu: the scene whose object count sizes the caster sets; its lights and
 * the settings give the first camera program, compiled now. */
bool shadow_map_init(shadow_map_renderer *r, const shadow_map_settings *settings, const render_scene *gpu);
void shadow_map_destroy(shadow_map_renderer *r);
/* The frame's steps (see the top of this file), in their order. Step 1:
 * the camera's depth pre-pass; notes the target the camera pass will draw
 * into (the framebuffer and viewport bound now) and forgets the last
 * frame's maps. */
void shadow_map_begin(shadow_map_renderer *r, const technique_frame *f);
/* Step 2: fit places light l's map, of any kind (an array map with its
 * size set), at the size of the settings (auto: sized after the fit), and
 * a moment filter's blur is set. False, with no map this frame, where the
 * light is off, no receiver is visible or the fit fails. */
bool shadow_map_fit_light(shadow_map_renderer *r, const shadow_map_settings *settings, const technique_frame *f,
                          int l, shadow_map_fit_function fit);
/* Step 3: the depth pass of fitted light l (see "Caching" above): its
 * layers from its cache, or rendered with the casters each needs (and a
 * moment filter's blurred). */
void shadow_map_draw_depth(shadow_map_renderer *r, const shadow_map_settings *settings, const technique_frame *f,
                           int l);
/* Step 4: the camera pass, into the target shadow_map_begin found. With
 * the eye inside a closed caster (r->closed: its welded edge table, as
 * the volumes weigh it; the eye inside by its winding number), a face
 * that a light outside the mesh reaches on the eye's side is in the
 * mesh's shadow without a read: the light came through the mesh
 * (shaders/shadowmap.frag, shadow_map_through_closed). */
void shadow_map_shade(shadow_map_renderer *r, const shadow_map_settings *settings, const technique_frame *f);
/* The depth pass of a fitted map of any kind, uncached (the tests'):
 * (re)makes its texture when needed, then renders every layer from its matrix, with glPolygonOffset
 * as the slope-scaled bias (unless --no-slope-bias; an array map's layers
 * attached one at a time, glFramebufferTextureLayer), and a moment
 * filter's blurs each. Leaves r->framebuffer (or the blur's) bound and
 * the viewport at the map's size: the caller binds its target again. */
void shadow_map_render_depth(shadow_map_renderer *r, const shadow_map_settings *settings, const render_scene *gpu,
                             shadow_map *m);
/* The samples light l's map is measured at this frame, in r->samples
 * (returns how many): where the camera sees receivers, those the light
 * can light (warp_samples_lit). The rays are cast once a frame, on the
 * first call, and only by a frame that measures: the automatic size or a
 * fit like psm's. */
int shadow_map_light_samples(shadow_map_renderer *r, const technique_frame *f, int l);
/* The map's size in the settings; 0: auto. */
int shadow_map_settings_size(const shadow_map_settings *settings);
/* --map-size auto's size for the fitted map m of the light at
 * light_position, from the samples the light is measured at (see
 * SHADOW_MAP_AUTO_*): a texel's size on screen scales as 1 / size, so the
 * mean at m->size gives the size at which it is TEXEL_PIXELS, rounded up
 * to a power of two. Samples beyond the light's range (it lights nothing
 * there) and outside the map are not measured. Where more of the samples
 * were left out as edge-on to the light (`grazing`, warp_samples_lit)
 * than measured, the faces measured are not where its shadows are seen:
 * on those faces every texel is unboundedly long and only its width
 * across the light can shrink, so the map takes the most texels, MAX
 * (else a sun a fraction of a degree above the ground, measured on the
 * casters' sides alone, gets a small map and every long shadow edge on
 * the ground follows one texel's rounding: test_shadowmap's stress
 * extremes, tests/data/shadowmap_grazing_sun.json). */
int shadow_map_auto_size(const shadow_map *m, const scene_light *light, const warp_sample *samples, int n,
                         int grazing);
/* A kind's GL texture target, and the image of a 2D map's or a cube
 * face's layer (GLenums). */
unsigned shadow_map_target(shadow_map_kind kind);
unsigned shadow_map_layer_image(shadow_map_kind kind, int layer);
/* The bound texture of `target` filtered by `filter` (GL_NEAREST or
 * GL_LINEAR), its reads clamped to its edges. */
void shadow_map_texture_filter(unsigned target, int filter);
/* "2D", "cube" or "array", for HUD lines. */
const char *shadow_map_kind_name(shadow_map_kind kind);
/* The map as HUD lines name it: its kind and size as chosen ("2D map
 * auto: 4096" where --map-size is auto, "cube map 1024" where it is
 * given). */
void shadow_map_size_text(const shadow_map_settings *settings, const shadow_map *m, char *out, size_t size);

/* ---- fitting (shadow_map_fit.c) ---- */

/* Fitting (shadow_map_fit.c, no GL). shadow_map_fit_uniform is
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
bool shadow_map_fit_uniform(const scene *s, int light, shadow_map *m, const float (*receivers)[3],
                            int receiver_count);
/* The depth (view space, along -z) of the nearest caster that can shadow
 * the receivers in lo..hi seen through `view`: of a directional light
 * (orthographic) every caster whose box overlaps lo..hi across the view,
 * of a positional one every caster with a part in front of it; hi[2]
 * where none is nearer. */
float shadow_map_nearest_caster(const scene *s, const mat4 view, const vec3 lo, const vec3 hi, bool orthographic);
/* A depth range in view space, near..far (distances along -z), widened by
 * the fit's margin so the points it was fitted to are not clipped by
 * rounding. */
void shadow_map_depth_range(float near_plane, float far_plane, float *near_out, float *far_out);
/* Layer `layer` of an array map is the orthographic `projection` of
 * m->cascade_view (glm_ortho: a diagonal and a translation): sets its
 * scale, offset and layer_view_projection. */
void shadow_map_cascade_layer(shadow_map *m, int layer, const mat4 projection);

/* ---- caster culling (shadow_map_cull.c) ---- */

/* Caster culling (shadow_map_cull.c, no GL; with f->cull_casters). Each
 * layer (a cube's faces each on its own) draws only the casters that can
 * shadow a visible receiver through it. Where receivers read a layer, in
 * its clip space: the NDC rectangle and deepest depth of both the frame's
 * receiver points and the surfaces of the visible receivers' boxes within
 * the light's range inside the layer's sides (a cube's widened by the
 * kernel, whose taps cross its edges), the tighter of the two, grown by
 * the kernel's reach (shadow_map_read_reach: its farthest tap, the
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
 * surface), and light 0's map while the inset shows it. The fit never
 * depends on culling. */

/* How a layer is read: the kernel's reach in texels from a point's
 * projection (shadow_map_read_reach), the map's size, whether it is a cube
 * face (taps cross its edges and compare their own direction's depth,
 * about `center`, the light) and whether taps compare any depth
 * (receiver-plane). */
typedef struct shadow_map_read_setup {
    float reach;
    int size;
    bool cube, any_depth;
    float center[3];
} shadow_map_read_setup;
/* Where receivers read a layer: an NDC rectangle (grown by the reach,
 * within [-1, 1]) and the deepest NDC depth they compare; empty: none. */
typedef struct shadow_map_reads {
    bool empty;
    float lo[2], hi[2], max_depth;
} shadow_map_reads;
/* area: the light has a radius (soft under pcss, or a moment filter's
 * wide blur). */
float shadow_map_read_reach(const shadow_map_settings *settings, shadow_map_kind kind, bool area);
/* Light `light` of the settings' technique gets soft shadows: an area
 * light, with --soft pcss, read by no moment filter, and not while auto
 * shows acne. */
bool shadow_map_light_soft(const shadow_map_settings *settings, const scene_light *light);
/* The technique's area_light words (technique.h) under the settings. */
const char *shadow_map_area_light_text(const shadow_map_settings *settings, const scene_light *light);
/* The reads of the layer of matrix `layer` by the receiver points (NULL:
 * no bound from them) and by the surfaces of the receiver boxes (lo, hi). */
void shadow_map_layer_reads(const mat4 layer, const shadow_map_read_setup *setup, const float (*points)[3],
                            int point_count, const float (*boxes)[2][3], int box_count, shadow_map_reads *out);
/* The caster box lo..hi may change a read of the layer. */
bool shadow_map_caster_read(const shadow_map_reads *reads, const mat4 layer, const vec3 lo, const vec3 hi);
/* The boxes of f's receivers that meet the view, clipped to light's range
 * (at most the scene's object count); returns how many. */
int shadow_map_light_receivers(const technique_frame *f, int light, float (*boxes)[2][3]);
/* r->needed[layer]: the casters each layer of light l's fitted map needs
 * (every candidate where it does not cull); counts them in f->counts. */
void shadow_map_plan_casters(shadow_map_renderer *r, const shadow_map_settings *settings, const technique_frame *f,
                             int l);

/* ---- moment maps (shadow_map_moments.c) ---- */

/* The box radius of a moment filter's blur, in texels of each layer of
 * light l's fitted map m, into blur (see shadow_map_moments.c): a hard
 * light's SHADOW_MAP_MOMENTS_HARD_BLUR_TEXELS, an area light's the mean
 * penumbra its casters cast at their feet, unclamped; each caster's
 * shadow is traced once for every layer. */
void shadow_map_moments_blur_texels(const scene *s, int l, const shadow_map *m, float blur[SHADOW_MAP_MAX_LAYERS]);
/* (Re)makes a moment filter's textures beside m's depth texture (or
 * deletes them for the kernels). */
void shadow_map_moments_prepare(shadow_map *m, shadow_map_moments moments);
/* The depths of layer `layer` as blurred moments (their moments, then
 * the box along x and along y); false (said
 * once, r->blur_failed) where a pass cannot run. Leaves its framebuffer
 * bound. */
bool shadow_map_moments_blur(shadow_map_renderer *r, const shadow_map *m, shadow_map_moments moments, int layer);
void shadow_map_moments_destroy(shadow_map_renderer *r);

/* Passes that read a map's depths a texel at a time (the moment blur's
 * first, the map inset's reduction) include shaders/map_texel.glsl: their
 * defines go on with SHADOW_MAP_TEXEL_DEFINES, the names it compares
 * with, and shadow_map_texel_units puts its samplers on their units (the
 * program in use): a map of kind k is read on unit k. */
#define SHADOW_MAP_TEXEL_DEFINES                                                                                     \
    SHADER_DEFINE(SHADOW_MAP_CUBE), SHADER_DEFINE(SHADOW_MAP_ARRAY), SHADER_DEFINE(SHADOW_MAP_FACE_POSITIVE_X),      \
        SHADER_DEFINE(SHADOW_MAP_FACE_NEGATIVE_X), SHADER_DEFINE(SHADOW_MAP_FACE_POSITIVE_Y),                        \
        SHADER_DEFINE(SHADOW_MAP_FACE_NEGATIVE_Y), SHADER_DEFINE(SHADOW_MAP_FACE_POSITIVE_Z)
void shadow_map_texel_units(unsigned program);
/* *framebuffer (made on first use), bound, with `texture`'s image `image`
 * (GL_TEXTURE_2D, a cube face's, or layer `layer` of GL_TEXTURE_2D_ARRAY)
 * as its colour: complete, or said on stderr with what is done `instead`,
 * and false. */
bool shadow_map_color_target(unsigned *framebuffer, unsigned texture, unsigned image, int layer, const char *instead);

/* ---- overlays (shadow_map_overlay.c) ---- */

/* The 12 edges of the frustum of `frustum` (its clip cube mapped back to
 * world space), drawn through `view_projection`. */
void shadow_map_draw_frustum(shadow_map_renderer *r, const mat4 frustum, const mat4 view_projection);
/* Step 5 of the frame: those of settings->overlay drawn after the camera
 * pass, for the lights with a map this frame: frusta, the map inset (see
 * below), the cascades' key, the texel-size and penumbra heat maps'
 * legends (a colour bar with labelled ticks). */
void shadow_map_draw_overlays(shadow_map_renderer *r, const shadow_map_settings *settings, const technique_frame *f);

/* Each array layer's colour in the cascades overlay, one table for the
 * camera pass's tint (shaders/shadowmap_array.glsl's u_cascade_colors,
 * set from it when a camera program is made) and the key's swatches. */
extern const float shadow_map_cascade_colors[SHADOW_MAP_MAX_ARRAY_LAYERS][3];

/* The map inset. Light 0's map is reduced on the GPU
 * (shaders/overlay_reduce.frag) to blocks of texels, a block to at most
 * a pixel of the inset, each holding the nearest and the farthest depth
 * stored in it among the texels that hold one (below the cleared 1): the
 * inset shows each block's nearest (a caster narrower than a pixel still
 * shows), and the reduction, read back (a few hundred blocks on a side at
 * most), gives each layer's range. Each inset (a cube's one for its six
 * faces) shows linear depth from its nearest held depth, black, to its
 * farthest, SHADOW_MAP_INSET_FAR_GREY_PERCENT grey, what holds nothing
 * white. A label above it gives that range in the light view's units (a
 * perspective map's distance from the light, an orthographic one's depth
 * past its near plane) beside its swatch: an array layer's colour, else
 * the ramp's two ends. A layer that holds nothing is drawn as the
 * legend's panel, labelled "empty". The reduction is made again only
 * when the depth pass renders a layer of light 0's map. */
#define SHADOW_MAP_INSET_FAR_GREY_PERCENT 75
/* How many insets a map of `kind` with `layer_count` layers has (an
 * array's layers one each; any other map one), and where inset `inset`
 * lies in a viewport of width x height pixels: x, y, width and height in
 * pixels from the viewport's bottom-left corner. */
int shadow_map_inset_count(shadow_map_kind kind, int layer_count);
void shadow_map_inset_rect(shadow_map_kind kind, int layer_count, int inset, int width, int height, int rect[4]);

/* A warp's space in a second viewport (psm's post-perspective view): the
 * scene carried into `space` and clipped to its clip cube, the cube's
 * edges and the map's frustum there (map_view_projection: world -> map
 * clip), seen from above one side, in the bottom-left half of the picture. */
typedef struct shadow_map_warp_view {
    render_program program; /* post_perspective.vert/.frag */
    int space;
} shadow_map_warp_view;
bool shadow_map_warp_view_init(shadow_map_warp_view *w);
void shadow_map_warp_view_destroy(shadow_map_warp_view *w);
void shadow_map_warp_view_draw(const shadow_map_warp_view *w, shadow_map_renderer *r, const technique_frame *f,
                               const mat4 space, const mat4 map_view_projection);

#endif
