/* target: the off-screen framebuffer every technique draws into.
 *
 * RGBA8 colour and a 24-bit depth / 8-bit stencil renderbuffer, on every
 * backend, so a technique sees the same buffers in a window (where the
 * target is blitted to the screen) as headless; a 32-bit float depth
 * instead for a camera with reversed depth (depth.h), which
 * target_match_depth swaps in before its frame. target_read_rgba returns
 * the pixels top row first, ready for a PNG.
 */
#ifndef TARGET_H
#define TARGET_H

#include <stdbool.h>

typedef struct target {
    unsigned framebuffer, color, depth_stencil;
    int width, height;
    bool reversed_depth; /* the depth buffer is the float one */
} target;

/* With the 24-bit depth. */
bool target_create(target *t, int width, int height);
/* The depth buffer for a view with reversed depth or without, allocated
 * anew only when it changes; false (said on stderr) if it fails. */
bool target_match_depth(target *t, bool reversed_depth);
void target_bind(const target *t);
bool target_read_rgba(const target *t, unsigned char *rgba);
/* The window's back buffer as target_read_rgba reads a target: what the
 * frame drew before it is swapped to the screen. */
bool target_read_window_rgba(int width, int height, unsigned char *rgba);
/* Copies the colour to the bound window framebuffer of the given size. */
void target_blit_to_window(const target *t, int window_width, int window_height);
void target_destroy(target *t);

#endif
