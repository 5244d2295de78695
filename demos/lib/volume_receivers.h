/* volume_receivers: the depth the shadow volumes are counted against,
 * exact on triangles that are huge seen from the eye (demos/volumes.c).
 *
 * The rasterizer finds a fragment's depth by interpolating across its
 * triangle from the corners, in float: far from the corners the rounding
 * grows with the triangle's size over the fragment's distance from the
 * eye. A shadow edge on a receiver lies where a volume's side crosses the
 * receiver's depth, so that error moves it: a ground of two triangles
 * 1e5 across, seen from 10 units away (the stress cases huge_ground_*,
 * test_volumes' test_huge_ground), lies many depth-buffer steps too far,
 * and the volumes' shadow edges on it move by whole pixels, where on the
 * same ground tessellated near the eye they hold; the larger the ground,
 * the farther they move.
 *
 * An object in view is huge this frame as render_object_huge says
 * (render.h: its longest edge against its box's distance from the eye). For the counting,
 * volume_receivers_depth draws the depth of every object in view, the
 * huge ones through volume_receiver_depth.frag: lit.vert as the depth
 * pre-pass has it (the same pixels), each fragment's depth where the eye
 * ray through the pixel's centre meets its triangle's plane. The planes
 * come from the CPU in double, relative to the eye (unit normal, the
 * eye's distance), so nothing the shader computes is larger than what it
 * looks at. The shading passes test GL_EQUAL against their own rasterized
 * depth: after the counting the caller draws the pre-pass's depth again
 * (volume_receivers_depth, exact false). Neither touches the stencil.
 *
 * Where no object is huge (every standard scene: none comes near
 * render_object_huge's ratio) the caller takes neither pass: nothing
 * changes there. A mesh with more triangles than a 2D texture holds
 * (GL_MAX_TEXTURE_SIZE squared) is never huge: it keeps the rasterized
 * depth; so does every object where the shader cannot know its triangle
 * (GLSL ES has no gl_PrimitiveID: context.h's primitive_id).
 */
#ifndef VOLUME_RECEIVERS_H
#define VOLUME_RECEIVERS_H

#include <stdbool.h>

#include "technique.h"

/* Zero is an unmade one. */
typedef struct volume_receivers {
    render_program program;              /* lit.vert, volume_receiver_depth.frag */
    int projection, zero_to_one, planes; /* its own uniforms (and eye_ray.glsl's) */
    int object_count;
    unsigned *textures;  /* per object: its planes; 0 where it can never be huge */
    int width;           /* the planes' rows' texels (GL_MAX_TEXTURE_SIZE) */
    bool *huge;          /* per object, this frame */
    float *scratch;      /* the planes of the largest candidate, 4 floats a texel */
    float planes_eye[3]; /* the eye the planes are relative to */
    bool planes_made;
} volume_receivers;

bool volume_receivers_init(volume_receivers *r, const render_scene *gpu);
void volume_receivers_destroy(volume_receivers *r);

/* Marks the objects in view that are huge seen from f's eye, and makes
 * their planes for it; returns how many are. */
int volume_receivers_update(volume_receivers *r, const technique_frame *f);

/* Clears the depth and draws every object in view's, the huge ones exact
 * (`exact`) or all as render_depth_prepass does; leaves the depth state
 * the pre-pass leaves (GL_EQUAL, no writes). The stencil test must be off
 * and the scissor is turned off: the shading passes read the whole frame. */
void volume_receivers_depth(const volume_receivers *r, const technique_frame *f, bool exact);

#endif
