/* warp: the math of warped shadow maps (demos/psm.c), on plain inputs:
 * matrices, points, the scene's lights and objects, a camera view. No GL:
 * every function here can be tested without a context (tests/test_warp.c).
 *
 * The pieces, in the order a frame uses them:
 *
 *   warp_view_of           the camera's forward axis and the depth range of
 *                          the receivers along it (z_n, z_f of the papers)
 *   warp_relevant_casters  the casters that can shadow those receivers,
 *                          their box corners appended after the receivers'
 *   warp_psm               Stamminger & Drettakis 2002 with Kozlov's
 *                          virtual camera (GPU Gems, ch. 14): the map fitted
 *                          in the camera's post-perspective space (PPS),
 *                          the light there a point in front (the usual
 *                          case), a point behind (a light behind the viewer:
 *                          the map's depth row negated, so the depth order
 *                          flips without any GL state) or a direction
 *   warp_lispsm            Wimmer, Scherzer & Purgathofer 2004: a
 *                          perspective along the view as seen from the
 *                          light, of strength warp_lispsm_n_opt
 *   warp_samples           rays through a WARP_SAMPLES_X x WARP_SAMPLES_Y
 *                          grid of pixels to the receivers' boxes, once a
 *                          frame; warp_samples_lit: those a light's map
 *                          is measured at
 *   warp_texel_pixels      at those samples, the mean size in pixels of a
 *                          map texel (the dp/ds of the papers): how the
 *                          warp is judged against the uniform map
 *
 * A warp writes a warp_result: the map's matrix and depth range when it
 * succeeds, and in any case what it found on the way (its space, the case
 * it took or why it gave up), for the HUD and the post-perspective view.
 * Scratch space comes from the caller (no static buffers).
 */
#ifndef WARP_H
#define WARP_H

#include <cglm/cglm.h>
#include <stdbool.h>

#include "camera.h"
#include "scene.h"

/* Wider than this each side, a perspective map starves its edges. */
#define WARP_MAX_HALF_ANGLE_DEG 80.0f
/* The pixel grid the warps are measured on. */
#define WARP_SAMPLES_X 32
#define WARP_SAMPLES_Y 18
#define WARP_SAMPLE_COUNT (WARP_SAMPLES_X * WARP_SAMPLES_Y)
/* The grid over a rectangle of the picture (warp_samples' ndc): one
 * light's reach, a share of the picture, needs fewer cells to find where
 * it lights (at most WARP_SAMPLE_COUNT). */
#define WARP_RECT_SAMPLES_X 8
#define WARP_RECT_SAMPLES_Y 8
/* Faces within 3 degrees of edge-on to the light (sin 3 degrees) are not
 * measured: every map's texels on them are of unbounded length. */
#define WARP_GRAZING_SINE 0.0523f
/* Below this sin(gamma), the angle between the view and the light, LiSPSM's
 * n_opt (which grows as 1 / sin gamma) is taken as infinite. */
#define WARP_MIN_SIN_GAMMA 1e-3f
#define WARP_WHY_MAX 160

/* The camera's forward axis and the depth range of the visible receivers
 * along it (at least the camera's near plane). */
typedef struct warp_view {
    vec3 eye, forward;
    float z_near, z_far;
} warp_view;

/* Which of psm's cases a light took. */
typedef enum warp_psm_case {
    WARP_PSM_NONE,        /* no fit (or not psm) */
    WARP_PSM_IN_FRONT,    /* a point in front of the virtual camera in PPS */
    WARP_PSM_BEHIND,      /* beyond infinity in PPS: the inverted map */
    WARP_PSM_AT_INFINITY, /* a direction in PPS: an orthographic map */
} warp_psm_case;

typedef struct warp_result {
    /* When the warp succeeds: */
    mat4 view_projection; /* world -> the map's clip space */
    float near_plane, far_plane;
    bool orthographic; /* the stored depth is linear */
    /* What it found, success or not: */
    mat4 space; /* world -> the space the warp fits in (PPS for psm) */
    bool has_space;
    char why[WARP_WHY_MAX]; /* the case taken, or why it gave up; left as is where no reason applies */
    warp_psm_case psm_case;
    vec4 light_in_space;    /* psm: the homogeneous light in PPS */
    float slide;            /* psm: how far the virtual camera slid back */
    float n_opt, sin_gamma; /* lispsm */
} warp_result;

/* A point on a receiver where the camera looks, to measure maps at. */
typedef struct warp_sample {
    vec3 position, tangent[2]; /* on a face of a receiver's box */
    vec3 normal;               /* that face's, towards the eye */
    float pixels;              /* pixels per unit area of that face there */
} warp_sample;

/* p transformed by the projective m and divided by w; false if w <= 0
 * (behind the eye of m), where the division would fold the point over. */
bool warp_project(const mat4 m, const float p[3], float out[3]);
bool warp_finite(const mat4 m);
/* A perspective frustum from `eye` just around `points`: its axis through
 * their centroid, its sides and depth range fitted. False when a point
 * lies behind the eye or the frustum would be wider than
 * WARP_MAX_HALF_ANGLE_DEG each side. */
bool warp_frustum_around(const float eye[3], const float (*points)[3], int n, mat4 out, float *near_plane,
                         float *far_plane);

/* False when the receivers have no depth range ahead of the camera. */
bool warp_view_of(const camera_view *c, const float (*receivers)[3], int n, warp_view *v);

/* The casters of `s` that can shadow the receivers points[0 .. receiver_count)
 * of light l, marked in `mask` (one per object), their box corners appended
 * after the receivers in `points` (capacity points in all). Directional
 * light: boxes that overlap the receivers seen along the light. Spot and
 * point: boxes that meet the box around the light and the receivers (which
 * holds every segment between them). Returns the new point count, or -1
 * when they do not fit. */
int warp_relevant_casters(const scene *s, const scene_light *l, float (*points)[3], int receiver_count, int capacity,
                          bool *mask);

/* LiSPSM's warp strength: (z_n + sqrt(z_n z_f)) / sin(gamma). */
float warp_lispsm_n_opt(float z_near, float z_far, float sin_gamma);

/* The warps, fitted to `points` (n of them: receivers first, then casters;
 * lispsm fits its depth range along the view to the first receiver_count);
 * `scratch` holds n points. False when the warp cannot be placed here. */
bool warp_psm(const camera_view *c, const scene_light *l, const warp_view *v, const float (*points)[3], int n,
              float (*scratch)[3], warp_result *out);
bool warp_lispsm(const scene_light *l, const warp_view *v, const float (*points)[3], int receiver_count, int n,
                 float (*scratch)[3], warp_result *out);

/* The world boxes (lo, hi) of the receivers of `s`, in its order, into
 * `out` (room for its objects): how many. */
int warp_receiver_boxes(const scene *s, float (*out)[2][3]);
/* Of the n boxes, in their order, those a ray of `view` through the NDC
 * rectangle `ndc` (x0, y0, x1, y1) may enter: whose screen bounds meet
 * it, or that reach behind the eye. Into `out` (room for n): how many. */
int warp_boxes_seen_in(const float (*boxes)[2][3], int n, const camera_view *view, const float ndc[4],
                       float (*out)[2][3]);
/* Rays through the pixel grid of a width x height picture of `view` to
 * the receivers' boxes (warp_receiver_boxes); each hit is a sample, with
 * the pixel area on the face it hit. The grid spans the picture, or with
 * `ndc` (x0, y0, x1, y1 in NDC, within -1..1) that rectangle of it alone,
 * WARP_RECT_SAMPLES_X x WARP_RECT_SAMPLES_Y cells (the boxes
 * warp_boxes_seen_in keeps for it are enough). `out` holds
 * WARP_SAMPLE_COUNT; returns how many. The picture's are the same for
 * every light: a frame takes them once. */
int warp_samples(const float (*boxes)[2][3], int box_count, const camera_view *view, int width, int height,
                 const float ndc[4], warp_sample *out);
/* Those of the n samples that light l's map is measured at, into `out`
 * (room for n); returns how many. Faces nearly edge-on to l
 * (WARP_GRAZING_SINE) are left out (how many, in *grazing unless NULL),
 * faces turned away count (boxes stand for surfaces that may well face
 * the light), and outside a spot's cone the cone decides, not the map;
 * beyond a positional light's range it lights nothing: those are
 * dropped, not counted edge-on (a far lamp's walls seen edge-on do not
 * make it a grazing light). */
int warp_samples_lit(const warp_sample *samples, int n, const scene_light *l, warp_sample *out, int *grazing);
/* The cube face point p falls on from `light`: by its major axis, in GL's
 * order (+x -x +y -y +z -z). */
int warp_cube_face(const float light[3], const float p[3]);
/* The size in pixels of a texel of a size x size map at one sample (on the
 * sample's face, the square root of a pixel's area over a texel's):
 * INFINITY outside the map, NAN where it cannot be measured (the face
 * seen edge-on by the map). The map is one matrix (layer_count 1) or a
 * cube's six faces in GL's order, the point read from the face of its
 * major axis from `light_position`. */
float warp_sample_texel_pixels(const mat4 *layer_view_projection, int layer_count, int size,
                               const float light_position[3], const warp_sample *sample);
/* Their mean over the samples: INFINITY if one lies outside the map or
 * none can be measured. */
float warp_texel_pixels(const mat4 *layer_view_projection, int layer_count, int size, const float light_position[3],
                        const warp_sample *samples, int n);

#endif
