/* shading: the passes that light what a technique's depth pre-pass
 * shows, after render_depth_prepass of the frame's in_view (depth test
 * GL_EQUAL, depth writes off), each light only on what it reaches and in
 * its rectangle (skips.h's lit_by, skips_light_rect), two
 * ways. A technique that can shade every light at once (the shadow maps)
 * draws one pass of every object in view, unscissored and unblended
 * (shading_all_begin). The stencil techniques shade one light per pass
 * (shading_light): every visible pixel is shaded once per light that
 * reaches it, and the ambient term rides on the first light's pass
 * (shading_ambient_light) rather than a pass of its own, so a one-light
 * scene is shaded once. That pass draws every object in view,
 * unscissored (a light adds exactly 0 beyond its range, outside a spot's
 * cone and outside its rectangle), without blending; the others add
 * their light (GL_ONE, GL_ONE) on what they reach, in their rectangle.
 * Sums are quantized to the target's 8 bits once per pass, so a pixel's
 * colour may differ by one step from a single-pass picture of the same
 * lights; decisions do not. An area light's points are summed into its
 * visibility (soft_visibility.h) by shading_sample_area_light.
 */
#ifndef SHADING_H
#define SHADING_H

#include "area_light.h"
#include "soft_visibility.h"
#include "technique.h"

/* A light whose rectangle covers at most this share of the frame is
 * narrowed enough to pay for the read-back of technique_see, and split
 * from the one shading pass (shading_split_lights). */
#define SHADING_NARROW_LIGHT_SHARE 0.25
/* Scissors to light l's rectangle (skips_light_rect; scissor test
 * on) and returns the objects its lighting pass draws: what it reaches. */
const bool *shading_light_pass(const technique_frame *f, int l);

/* The light whose shading pass also draws the ambient term: the first that
 * is on; -1 when none is (shading_ambient). */
int shading_ambient_light(const technique_frame *f);
/* The one shading pass's state; returns the objects it draws: every one
 * in view. */
const bool *shading_all_begin(const technique_frame *f);
/* The lights on whose rectangle covers at most SHADING_NARROW_LIGHT_SHARE
 * of the frame, which the one shading pass leaves to passes of their own,
 * for a shader that pays for every light it holds on every pixel (one
 * whose lights are fixed when it is compiled: llvmpipe runs both sides of
 * a branch). The one pass then shades every object in view with the other
 * lights; light l's own pass (shading_light_pass), with every light,
 * shades again what it reaches in its rectangle. A light adds exactly 0
 * outside its rectangle, so each pixel's sum is the one pass's with every
 * light, bit for bit. None with the skips off (every rectangle the whole
 * frame). Past one light group (render.h), every light on is split, and
 * light l's pass adds its own light alone (shading_split_pass): shading
 * every light again would cost every light in every split rectangle, and
 * a group's pass over the whole frame every light of the group on every
 * pixel. */
scene_light_set shading_split_lights(const technique_frame *f);
/* Split light l's pass: shading_light_pass's scissor and objects, and
 * the lights it shades into *lights, with the ambient term where
 * *ambient: in a scene of one light group every light again, replacing
 * the one pass's pixels; past it l alone, added (blending on, GL_ONE,
 * GL_ONE, which the caller turns off). */
const bool *shading_split_pass(const technique_frame *f, int l, scene_light_set *lights, bool *ambient);
/* The frame's only shading pass when no light is on: the ambient term on
 * every object in view. */
void shading_ambient(const technique_frame *f);
/* Where a stencil says a light is blocked: a pixel is lit where the test
 * `lit` (GL_EQUAL, GL_NOTEQUAL) of (stencil & mask) against ref passes,
 * blocked where `blocked` (its complement) does. receivers_only: objects
 * that take no shadows ("receives": false) are lit whatever the stencil. */
typedef struct shading_stencil {
    unsigned lit, blocked;
    int ref;
    unsigned mask;
    bool receivers_only;
} shading_stencil;
/* Light l's shading pass through such a stencil (see above); where the
 * ambient light is blocked, the ambient term alone. Leaves the stencil
 * test on, blending and the scissor test off. */
void shading_light(const technique_frame *f, int l, const shading_stencil *stencil);
/* Light l's disk (area_light.h) for the techniques that sample it with
 * one set of points for every pixel: facing the middle of the scene's
 * receivers (the origin where none is), so that the points stay where
 * they are while the light does, whatever the camera. */
void shading_area_light_frame(const technique_frame *f, int l, area_light_frame *frame);
/* Light l's visibility from `samples` of its points (area_light_sample_ball
 * of shading_area_light_frame) into v's sum: for each point k not yet
 * in it, `count` leaves the stencil as for a hard light at that point,
 * and the point is added where `lit` passes. In the order
 * area_light_progressive_index gives; f->light_points of them per frame,
 * the sum kept while neither the camera, the light, the scene nor a
 * setting changes, or with f->light_points 0 every point from none. A
 * frame with f->light_points in which any of those changed counts the
 * light's centre alone (k SHADING_LIGHT_CENTRE), the hard technique's
 * picture, so that a moving view shows the hard shadow, not one point's;
 * the sum starts from none on the next. False, after one line on stderr,
 * when v cannot be made for the bound target. Leaves the stencil test
 * off. */
typedef void (*shading_count_point)(const technique_frame *f, int l, int k, const float point[4]);
/* The k a technique's count takes for the light's centre (a hard light). */
#define SHADING_LIGHT_CENTRE (-1)
bool shading_sample_area_light(const technique_frame *f, int l, int samples, soft_visibility *v,
                               const shading_stencil *lit, shading_count_point count);
/* Light l's shading pass with its visibility accumulated in v
 * (soft_visibility.h) instead of a stencil: its unshadowed light times
 * the fraction, on every object but those that take no shadows where
 * receivers_only. Leaves blending and the scissor test off. */
void shading_light_soft(const technique_frame *f, int l, const soft_visibility *v, bool receivers_only);

#endif
