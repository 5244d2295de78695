/* shadowmap: the shadow-map machinery of demos/shadowmap.c, shared with
 * demos/psm.c, which renders the same maps through a warped matrix.
 *
 * A technique that uses it keeps a shadowmap_settings and a shadowmap_maps
 * in its static state, lists SHADOWMAP_PARAMS(its settings) among its
 * parameters (map size, filter, depth format, biases: the same flags and
 * keys everywhere), and each frame calls shadowmap_maps_render with a
 * fitting function: the one place where techniques differ is how a
 * light's map is placed. shadowmap_fit_uniform is shadowmap.c's: a cube
 * map for a point light, a perspective or orthographic map fitted to what
 * the camera sees otherwise.
 *
 * A fitting function fills a shadowmap_light: cube or 2D, the matrices
 * world -> the map's clip space, the depth range (for the inset and the
 * HUD), how a texel's world size is found (texel_kind) and which casters
 * to draw (casters: NULL for all). It returns false when nothing can be
 * shadowed; the light is then added unshadowed.
 */
#ifndef SHADOWMAP_H
#define SHADOWMAP_H

#include <GLFW/glfw3.h>
#include <stdbool.h>

#include "frustum.h"
#include "technique.h"

typedef struct shadowmap_settings {
    int map_size;     /* choice */
    int filter;       /* choice */
    int depth;        /* choice */
    int kernel_depth; /* choice */
    int overlay;      /* choice: the technique's own list, SHADOWMAP_OVERLAY_NAMES first */
    bool no_constant_bias, no_slope_bias;
    float constant_texels, slope_factor, slope_units, normal_texels; /* 0: defaults */
    float depth_bias_slope, depth_bias_min; /* the tutorials' bias; 0: none */
} shadowmap_settings;

/* The defaults of the numbers, from `make bench` (see shadowmap.c). */
#define SHADOWMAP_CONSTANT_TEXELS 1.0f
#define SHADOWMAP_SLOPE_FACTOR 1.5f
#define SHADOWMAP_SLOPE_UNITS 1.0f

extern const char *const shadowmap_sizes[];
extern const char *const shadowmap_filters[];
extern const char *const shadowmap_depths[];
extern const char *const shadowmap_kernel_depths[];

/* Overlays for lectures, drawn into the picture: texel boundaries on the
 * receivers, the map's texel size on screen as a heat map, the light
 * frustum in wireframe, light 0's map as an inset. "all": texels, frustum
 * and map. A technique's list may go on after these. */
#define SHADOWMAP_OVERLAY_NAMES "none", "all", "texels", "frustum", "map", "texel-size"
enum { SHADOWMAP_OVERLAY_NONE, SHADOWMAP_OVERLAY_ALL, SHADOWMAP_OVERLAY_TEXELS, SHADOWMAP_OVERLAY_FRUSTUM,
       SHADOWMAP_OVERLAY_MAP, SHADOWMAP_OVERLAY_TEXEL_SIZE, SHADOWMAP_OVERLAY_COUNT };

/* The parameters every shadow-map technique shares, for its params array. */
#define SHADOWMAP_PARAMS(s)                                                                                          \
    {"map-size", "texels on a side", GLFW_KEY_M, TECHNIQUE_CHOICE, .index = &(s).map_size,                         \
     .choices = shadowmap_sizes},                                                                                  \
    {"filter", "what reads the map", GLFW_KEY_F, TECHNIQUE_CHOICE, .index = &(s).filter,                           \
     .choices = shadowmap_filters},                                                                                \
    {"depth", "depth format: 24-bit or 32-bit float", GLFW_KEY_D, TECHNIQUE_CHOICE, .index = &(s).depth,           \
     .choices = shadowmap_depths},                                                                                 \
    {"constant-bias", "acne: surfaces shadow themselves in stripes", GLFW_KEY_C, TECHNIQUE_TOGGLE,                 \
     .disabled = &(s).no_constant_bias},                                                                           \
    {"slope-bias", "acne where surfaces turn away from the light", GLFW_KEY_L, TECHNIQUE_TOGGLE,                   \
     .disabled = &(s).no_slope_bias},                                                                              \
    {"kernel-depth", "what each kernel tap compares: the centre's depth, or the receiver plane's there",           \
     GLFW_KEY_P, TECHNIQUE_CHOICE, .index = &(s).kernel_depth, .choices = shadowmap_kernel_depths},                \
    {"constant-texels", "constant bias, in map texels of world distance", 0, TECHNIQUE_NUMBER,                     \
     .number = &(s).constant_texels, .fallback = SHADOWMAP_CONSTANT_TEXELS, .min = 0.01f, .max = 64},              \
    {"slope-factor", "slope-scaled bias: glPolygonOffset factor", 0, TECHNIQUE_NUMBER,                             \
     .number = &(s).slope_factor, .fallback = SHADOWMAP_SLOPE_FACTOR, .min = 0.01f, .max = 64},                    \
    {"slope-units", "slope-scaled bias: glPolygonOffset units", 0, TECHNIQUE_NUMBER, .number = &(s).slope_units,   \
     .fallback = SHADOWMAP_SLOPE_UNITS, .min = 0.01f, .max = 64},                                                  \
    /* Off by default: on the standard scenes it costs accuracy at contact                                        \
     * shadows and the other two already keep the acne sweep clean. */                                            \
    {"normal-texels", "normal offset, in map texels (0: off)", 0, TECHNIQUE_NUMBER, .number = &(s).normal_texels,  \
     .fallback = 0, .min = 0, .max = 64},                                                                          \
    /* For comparison only: the bias popular tutorials subtract from the                                          \
     * map depth, max(slope (1 - N.L), min), whose size in world units                                            \
     * changes with the light's depth range. */                                                                   \
    {"depth-bias-slope", "tutorial bias: slope, in map depth (0: off)", 0, TECHNIQUE_NUMBER,                       \
     .number = &(s).depth_bias_slope, .fallback = 0, .min = 0, .max = 1},                                          \
    {"depth-bias-min", "tutorial bias: minimum, in map depth (0: off)", 0, TECHNIQUE_NUMBER,                       \
     .number = &(s).depth_bias_min, .fallback = 0, .min = 0, .max = 1}

/* How the camera pass finds the world size of a texel at a point, which
 * the constant and normal-offset biases are measured in. */
typedef enum shadowmap_texel_kind {
    SHADOWMAP_TEXEL_ORTHOGRAPHIC, /* texel_scale */
    SHADOWMAP_TEXEL_PERSPECTIVE,  /* texel_scale x depth along the axis */
    SHADOWMAP_TEXEL_PROJECTIVE,   /* from the matrix's derivatives: any warp */
} shadowmap_texel_kind;

/* One light's map: what it was fitted to, and its texture. */
typedef struct shadowmap_light {
    bool cube;
    int size;                /* texels on a side, set before fitting */
    mat4 view_projection[6]; /* world -> clip: one, or one per cube face */
    float near_plane, far_plane;
    shadowmap_texel_kind texel_kind;
    float texel_scale;
    bool orthographic;    /* the stored depth is linear (the inset shows it as it is) */
    const bool *casters;  /* objects to draw into the map; NULL: every caster */
    unsigned texture;
    int texture_size, texture_depth, texture_filter; /* what the texture was made with */
    bool texture_cube;
} shadowmap_light;

/* A program and its uniform locations, found once when it is loaded. */
typedef struct shadowmap_program {
    render_program program;
    int map, light, filter, receiver_plane, show_texels, show_texel_size, kernel, map_size, constant_bias,
        normal_offset, depth_bias, light_origin, near_plane, far_plane, light_matrix, texel_kind, orthographic, texel_scale,
        light_axis, color, cube_map, cube;
} shadowmap_program;

/* GL objects of a technique's maps. */
typedef struct shadowmap_maps {
    render_program depth;
    shadowmap_program camera_2d, camera_cube, lines, inset;
    unsigned framebuffer, overlay_vao, overlay_buffer;
    shadowmap_light lights[SCENE_MAX_LIGHTS];
} shadowmap_maps;

typedef bool (*shadowmap_fit_function)(const technique_frame *f, int light, shadowmap_light *m,
                                       const float (*receivers)[3], int receiver_count);

bool shadowmap_maps_init(shadowmap_maps *k);
void shadowmap_maps_destroy(shadowmap_maps *k);
/* The whole frame: each light's map fitted by `fit` and rendered, then
 * ambient and each light added where its map lets it through, then the
 * overlays of settings->overlay. */
void shadowmap_maps_render(shadowmap_maps *k, const shadowmap_settings *settings, const technique_frame *f,
                           shadowmap_fit_function fit);
/* The map's size in the settings. */
int shadowmap_settings_size(const shadowmap_settings *settings);

/* shadowmap.c's placement: the light's own perspective (a spot), its
 * direction (an orthographic map), or a cube map (a point light). */
bool shadowmap_fit_uniform(const technique_frame *f, int light, shadowmap_light *m, const float (*receivers)[3],
                           int receiver_count);

/* The points shadows are decided for: the corners of the part of every
 * receiver's box inside the camera's frustum. Returns how many (at most
 * max_points; SHADOWMAP_MAX_RECEIVER_POINTS is enough for 50 receivers). */
#define SHADOWMAP_MAX_RECEIVER_POINTS 8192
int shadowmap_receiver_points(const technique_frame *f, float (*points)[3], int max_points);
/* The 12 edges of the frustum of `frustum` (its clip cube mapped back to
 * world space), drawn through `view_projection`. */
void shadowmap_draw_frustum(shadowmap_maps *k, const mat4 frustum, const mat4 view_projection);

#endif
