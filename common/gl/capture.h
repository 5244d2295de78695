/* capture: fills a dump_frame (dump.h) from the GPU after a technique's
 * frame.
 *
 *   colour      the picture in the target, as it is;
 *   geometry    what each pixel sees (distance, face normal, position,
 *               object), from one extra pass over the scene into float
 *               buffers: that is scene geometry, the same for every
 *               technique, not a shadow decision;
 *   visibility  the technique's OWN decision: its frame is rendered again
 *               with the lights in visibility mode for light K (see
 *               shaders/lighting.glsl), so light K adds exactly 1 where it
 *               can reach and nothing else adds anything; what the
 *               technique's shadow test took away is what is missing.
 *               8-bit precision (steps of 1/255), enough for 0/1 and for
 *               the fractions of filtered shadows. Read from the red
 *               channel, or, `coloured` (a technique whose translucent
 *               casters filter its shadows: technique.h's
 *               coloured_shadows), per channel into visibility_rgb, where
 *               the frame has it, with their mean where they differ.
 *
 * render_frame is the app's frame function: it must render the same frame
 * again (frames are deterministic), with render_scene_update_lights(gpu,
 * visibility_of) taken from the capture's request.
 */
#ifndef CAPTURE_H
#define CAPTURE_H

#include <stdbool.h>
#include "dump.h"
#include "render.h"
#include "target.h"

/* Renders the frame again with frame lights in visibility mode for
 * `visibility_of` (or -1 for normal lights); false on a GL error. */
typedef bool (*capture_render_frame)(int visibility_of);

bool capture_dump(const render_scene *gpu, const camera_view *view, const target *t, int light_index, bool coloured,
                  capture_render_frame render_frame, dump_frame *out);

#endif
