/* cascades_fit: the geometry of demos/cascades.c's fit, also exposed for
 * its tests: the split schemes, the seen depth range sdsm splits, the
 * receivers' reach, and a cascade's box (its fit and stabilisation). No
 * GL. */
#ifndef CASCADES_FIT_H
#define CASCADES_FIT_H

#include <stdbool.h>
#include "camera.h"
#include "scene.h"

/* The split distances of `count` slices of near..far, splits[0..count]
 * (view depths, splits[0] = near, splits[count] = far): the practical
 * scheme of Zhang et al. 2006, lambda of the logarithmic split (near
 * (far / near)^(i / count)) plus 1 - lambda of the uniform one (near +
 * (far - near) i / count); lambda 0 is the uniform scheme, 1 the
 * logarithmic. */
void cascades_splits(int count, float lambda, float near_plane, float far_plane, float *splits);

/* The view depths of `view` that the points (the frame's receiver points)
 * span, within near..far: sdsm's range. False where no point lies in it. */
bool cascades_seen_depths(const camera_view *view, const float (*points)[3], int n, float near_plane, float far_plane,
                          float *lo, float *hi);

/* x rounded (by `round`: floorf or ceilf) to a power of 2^(1/steps): what
 * the stabilised fit lets change only in steps. */
float cascades_power_step(float x, float steps, float (*round)(float));

/* How far from `eye` any receiver of s can be, rounded up to a power of
 * two (see cascades_fit.c): where the splits end when the camera's far
 * plane lies beyond. */
float cascades_receivers_reach(const scene *s, const float eye[3]);

/* How a cascade's box keeps its texel grid while the camera moves
 * (--stabilize, in this order; cascades_fit.c says why each, at
 * CASCADES_SIDE_STEPS and cascades_slice_sphere). */
typedef enum cascades_stabilize {
    CASCADES_STABILIZE_STEPS,  /* the tight box, its sides and heading in steps, its corner on whole texels */
    CASCADES_STABILIZE_SPHERE, /* the slice's bounding sphere, its corner on whole texels */
    CASCADES_STABILIZE_OFF,    /* the tight box as it falls */
} cascades_stabilize;

/* The cascades' light view (world -> light space, orthonormal, looking
 * along -z): along `direction`, its origin the world's. By steps and off
 * it is then turned about the light's axis so that view's direction, as
 * the light sees it, is +y (the heading, which the boxes are aligned
 * with), by steps to a multiple of a sixteenth of a turn; the sphere's
 * is not turned, nor is any where the view is along the light (no
 * heading). */
void cascades_light_view(const float direction[3], const camera_view *view, cascades_stabilize stabilize,
                         mat4 light_view);

/* lo..hi (empty, lo > hi, when called) grown to the light-space bounds of
 * the parts of s's receivers' boxes inside the slice of view's frustum
 * between view depths a and b: still empty where none is in it. */
void cascades_slice_receivers(const scene *s, const camera_view *view, const mat4 light_view, float a, float b,
                              vec3 lo, vec3 hi);

/* The box in light view space (light_view: cascades_light_view's) of the
 * slice of view's frustum between view depths a and b, for a map `size`
 * texels on a side whose outer `margin` texels on each side are kept for
 * the kernel's taps. Steps and off: the slice's bounds, clipped to the
 * bounds of the receivers in the slice (receivers_lo..hi, light space)
 * where those are tighter; by steps each side rounded up to a power of
 * 2^(1/8) and the corner on a whole number of texels. The sphere: the
 * slice's bounding sphere (its size depends on a, b and the projection
 * alone, never on where the camera looks), the corner on whole texels. */
void cascades_slice_box(const camera_view *view, const mat4 light_view, float a, float b, int size, float margin,
                        cascades_stabilize stabilize, const float receivers_lo[3], const float receivers_hi[3],
                        float lo[3], float hi[3]);

#endif
