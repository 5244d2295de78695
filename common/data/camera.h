/* camera: view and projection matrices from a scene camera, and the orbit
 * the interactive window drives (drag to orbit, scroll to zoom).
 *
 * The projection is OpenGL's standard perspective (depth -1..1), vertical
 * field of view, as every technique and the ray-traced reference use.
 * Where far / near passes CAMERA_INFINITE_FAR_RATIO it is the same
 * perspective with its far plane at infinity: in float the finite one's
 * depth row already rounds to it there, and 2 near far may overflow.
 *
 * Depth precision: the target stores window depth in CAMERA_DEPTH_BITS
 * fixed-point bits (common/gl/target.c), so at distance z along the view
 * a depth step is z^2 (1/near - 1/far) / 2^bits in world units: it grows
 * with z^2 / near, hardly with far. Every raster program runs
 * camera_check_depth after scene_load. A camera whose step at the scene's
 * farthest point is at most CAMERA_MAX_DEPTH_STEP of the scene's size
 * keeps that buffer and GL's standard depth (every standard scene does).
 * Beyond, it takes reversed depth into a float buffer where the context
 * can (ARB_clip_control, common/gl/render.h): window depth
 * near (far - z) / (z (far - near)), or near / z with the far plane at
 * infinity, 1 at near and 0 at far. Its float keeps
 * CAMERA_FLOAT_DEPTH_BITS bits of its own size wherever it is, so an ulp
 * is at most depth 2^-23, and with |d depth / dz| = near far /
 * (z^2 (far - near)) (near / z^2 at infinity) the step in world units is
 * at most (far - z) / far z 2^-23 <= z 2^-23: relative to the distance,
 * whatever near is. A camera whose step is too large even so, or that
 * needs reversed depth where the context has none, is refused; the
 * reference, exact at any range, refuses none.
 */
#ifndef CAMERA_H
#define CAMERA_H

#include <cglm/cglm.h>
#include "scene.h"

/* Beyond this far / near, 2 near / far is below half a float ulp of 1: the
 * finite projection's depth row rounds to the infinite one's. */
#define CAMERA_INFINITE_FAR_RATIO 33554432.0 /* 2^25 */
/* Inverting the float view_projection puts the far corners within about
 * far / near float ulps (6e-4 of their distance here) of the camera's;
 * it loses the far plane once far / near passes about 1e7 (the depth row
 * is then the infinite projection's, its far corners at infinity: NaN,
 * and every receiver point with them). Up to this ratio the corners are
 * the inverse's, so that the standard scenes (up to 6000) keep their
 * goldens and figures; beyond it the camera's. */
#define CAMERA_INVERSE_MAX_RATIO 1e4
/* Bits of window depth in the target's depth buffer (GL_DEPTH24_STENCIL8). */
#define CAMERA_DEPTH_BITS 24
/* Mantissa bits of the reversed depth's float buffer (GL_DEPTH32F_STENCIL8). */
#define CAMERA_FLOAT_DEPTH_BITS 23
/* The largest depth step the raster accepts at the scene's farthest point,
 * as a fraction of the scene's size: about 1/8000, just above what the
 * standard scenes need (long_view: 1.08e-4), and where the techniques
 * stayed within their accuracy bounds (tests/test_range.c). */
#define CAMERA_MAX_DEPTH_STEP 1.25e-4

typedef struct camera_view {
    mat4 view, projection, view_projection;
    vec3 eye;
    /* The frustum's corners in world space, numbered as frustum_corners
     * numbers them (bit 0 x, bit 1 y, bit 2 the far plane). Up to
     * CAMERA_INVERSE_MAX_RATIO, frustum_corners of view_projection;
     * beyond, computed in double from the camera itself. */
    vec3 corners[8];
    /* The camera's reversed_depth (see top). The CPU's tests and fits use
     * view_projection, GL's standard clip space, either way; the camera
     * passes draw through raster_view_projection: view_projection, or
     * with reversed depth the same x, y and w rows and the reversed depth
     * row (computed from near and far in double, never from the standard
     * one, whose depth row has lost near by then). */
    bool reversed_depth;
    mat4 raster_projection, raster_view_projection;
} camera_view;

void camera_view_compute(const scene_camera *c, float aspect, camera_view *out);
/* Whether the target's depth resolves scene s (loaded from `file`) seen
 * by its camera; sets s->camera.reversed_depth to the depth it takes
 * (see top); reversed_available: the context can draw reversed depth.
 * If it cannot be resolved, says why in one line "FILE: camera: problem"
 * on stderr and returns false. Refused: coordinates whose squares
 * overflow a float (the shaders' distances and dot products), and a
 * depth step at the scene's farthest point along the view (at most far)
 * above CAMERA_MAX_DEPTH_STEP of the scene's size (the diagonal of the
 * box around every object) with standard depth, and with reversed depth
 * too or where it is not available. */
bool camera_check_depth(scene *s, const char *file, bool reversed_available);
/* How high above the target's plane across the up axis an orbit keeps
 * the eye, as an elevation angle: CAMERA_ORBIT_ANY lets it pass under (to
 * short of the pole), CAMERA_ORBIT_ABOVE keeps it above, so that a drag
 * never takes the camera under the ground it looks at. */
#define CAMERA_ORBIT_POLE_DEG 89.0f
#define CAMERA_ORBIT_ANY (-CAMERA_ORBIT_POLE_DEG)
#define CAMERA_ORBIT_ABOVE 1.0f
/* Turns the eye about the target: yaw about the up axis, pitch towards it
 * (kept short of the poles and, where it starts from at least that
 * high, at or above lowest_deg of elevation), distance scaled by zoom. */
void camera_orbit(scene_camera *c, float yaw_rad, float pitch_rad, float zoom, float lowest_deg);
/* Turns a light about `center` the same way (direction turns with it). */
void camera_orbit_light(scene_light *l, const float center[3], float yaw_rad, float pitch_rad);

#endif
