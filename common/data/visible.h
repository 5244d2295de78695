/* visible: what the camera sees, read back from the depth buffer after
 * the frame's depth pre-pass, as small convex bodies that hold every
 * visible point, for culling what cannot reach them (light_mask.h).
 *
 * The frame is cut into VISIBLE_TILE_PIXELS-square tiles. A tile with a
 * pixel nearer than the depth buffer's clear value is a slab: the tile's
 * square on the screen between the least and the greatest depth of its
 * pixels, each widened by VISIBLE_DEPTH_STEPS steps of the buffer (what
 * the rasterizer's rounding moves a tested depth by), unprojected into
 * world space in double from the depth row the camera rasterized with.
 * A deep tile (its farthest pixel beyond VISIBLE_SPLIT_RATIO times its
 * nearest: a facade's edge against the street's far end) is cut by
 * distance into VISIBLE_DEPTH_BINS bins, even in its logarithm, each bin
 * that holds a pixel a slab of its own depths. Every visible point (a
 * pixel's centre at its stored depth) lies in a slab of its tile; what is
 * drawn of the sky lies in none. Each tile also keeps its farthest depth,
 * against which a box is hidden (visible_box_hidden).
 *
 * No GL here: the frame's owner reads the depth into
 * visible_depth_buffer (technique_see: one glReadPixels a frame, which on
 * a GPU waits for the pre-pass, the price of skipping what the pre-pass
 * shows hidden), then visible_build makes the slabs.
 */
#ifndef VISIBLE_H
#define VISIBLE_H

#include <stdbool.h>

#include "camera.h"
#include "light_mask.h"

#define VISIBLE_TILE_PIXELS 16
#define VISIBLE_DEPTH_STEPS 8
#define VISIBLE_SPLIT_RATIO 1.25
#define VISIBLE_DEPTH_BINS 8

/* Zero is an empty one. */
typedef struct visible {
    int count;             /* slabs this frame */
    float (*slabs)[8][3];  /* corners numbered as frustum_box_corners' */
    light_mask_seen *seen; /* per slab: its tile's pixels and its window depths */
    /* per slab: the lights on that reach it (SCENE_LIGHT_BIT; made by
     * skips_narrow_light_rects, which knows the lights) */
    scene_light_set *lights;
    float *farthest; /* per tile, rows from the bottom: its farthest depth, the clear value where sky */
    int tiles_x, tiles_y;
    float *depth; /* the frame's window depths, bottom row first */
    int width, height;
} visible;

/* Where a frame's depth (width x height window depths, bottom row first)
 * is to be read; NULL after printing why (out of memory). */
float *visible_depth_buffer(visible *v, int width, int height);
/* v's slabs from the depth read into its buffer, drawn through view;
 * `clear` is the buffer's clear value, the depth of the sky. */
void visible_build(visible *v, const camera_view *view, float clear);
void visible_destroy(visible *v);
/* Whether every point of the box lo..hi lies behind what v saw there: its
 * nearest window depth (its corners', all beyond the near plane) more
 * than VISIBLE_DEPTH_STEPS steps beyond the farthest depth of every tile
 * its screen rectangle, a pixel wider, covers. Then none of its fragments
 * passes a test against that depth (the shading passes' GL_EQUAL), unless
 * the rasterizer moves its depths by more than that margin: not for an
 * object huge seen from the eye (render_object_huge), which the caller
 * keeps. */
bool visible_box_hidden(const visible *v, const camera_view *view, const vec3 lo, const vec3 hi);

#endif
