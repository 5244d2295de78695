/* depth: the camera passes' depth convention, GL's standard or reversed.
 *
 * camera_check_depth (camera.h) decides per scene: the standard depth
 * (clip z in -w..w, window depth 0 at near and 1 at far, cleared to 1,
 * "nearer" is GL_LESS) in the target's 24-bit fixed-point buffer, which
 * every standard scene keeps; or, for near/far ranges that buffer cannot
 * resolve, reversed depth in a float one: glClipControl(GL_LOWER_LEFT,
 * GL_ZERO_TO_ONE), the camera's reversed projection
 * (raster_view_projection), window depth 1 at near and 0 at far, cleared
 * to 0, "nearer" GL_GREATER (camera.h derives its precision). The view
 * carries the decision (camera_view.reversed_depth) and every pass asks
 * these functions, never the flag itself.
 *
 * Only the camera's passes change: a pass that draws through a matrix of
 * its own (a light's depth map, a lecture's view of a warped space) runs
 * between depth_use_standard and depth_use_camera. With the standard
 * depth every function here leaves GL as it is, so its pictures are
 * exactly those of a build without reversed depth.
 *
 * Reversed depth needs clip control (context.h's clip_control: desktop
 * GL's ARB_clip_control, core in 4.5, whose glClipControl glad loads
 * through the extension, which 4.5 drivers list too); a context without it refuses the scenes that need it at load (one line,
 * camera_check_depth).
 */
#ifndef DEPTH_H
#define DEPTH_H

#include <stdbool.h>
#include "camera.h"

/* The context can draw reversed depth (after context_create). */
bool depth_reversed_available(void);
/* GL_DEPTH_CLAMP on or off where the context has it (context.h's
 * depth_clamp); elsewhere nothing: primitives are clipped by the near and
 * far planes. */
void depth_clamp(bool on);
/* The depth test `standard` (GL_LESS, GL_LEQUAL, GL_GREATER, GL_GEQUAL, or
 * one the convention does not change) in v's convention. */
unsigned depth_func(const camera_view *v, unsigned standard);
/* glPolygonOffset of a camera pass: towards the eye stays towards it. */
void depth_polygon_offset(const camera_view *v, float factor, float units);
/* The depth buffer's clear value: the far end of v's window depth. */
float depth_far(const camera_view *v);
/* v's convention for the camera passes that follow: clip control, clear
 * value, and the depth test "nearer" (render_reset_state's GL_LESS). */
void depth_use_camera(const camera_view *v);
/* GL's standard (clip control, clear 1, GL_LESS) for a pass through a
 * matrix of its own, or at the end of v's frame. */
void depth_use_standard(const camera_view *v);

#endif
