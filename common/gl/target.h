/* target: the off-screen framebuffer every technique draws into.
 *
 * RGBA8 colour and a 24-bit depth / 8-bit stencil renderbuffer, on every
 * backend, so a technique sees the same buffers in a window (where the
 * target is blitted to the screen) as headless. target_read_rgba returns
 * the pixels top row first, ready for a PNG.
 */
#ifndef TARGET_H
#define TARGET_H

#include <stdbool.h>

typedef struct target {
    unsigned framebuffer, color, depth_stencil;
    int width, height;
} target;

bool target_create(target *t, int width, int height);
void target_bind(const target *t);
bool target_read_rgba(const target *t, unsigned char *rgba);
/* Copies the colour to the bound window framebuffer of the given size. */
void target_blit_to_window(const target *t, int window_width, int window_height);
void target_destroy(target *t);

#endif
