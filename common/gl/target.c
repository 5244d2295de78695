#include "target.h"

#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "context.h"

/* The camera's depth bound (camera_check_depth) counts on this format's
 * 24 bits of depth. */
_Static_assert(CAMERA_DEPTH_BITS == 24, "the target's depth is GL_DEPTH24_STENCIL8");

static unsigned target_depth_format(bool reversed_depth) {
    return reversed_depth ? GL_DEPTH32F_STENCIL8 : GL_DEPTH24_STENCIL8;
}

static bool target_complete(target *t) {
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        fprintf(stderr, "target: %dx%d framebuffer incomplete (0x%04x)\n", t->width, t->height, status);
        target_destroy(t);
        return false;
    }
    return true;
}

bool target_create(target *t, int width, int height) {
    *t = (target){.width = width, .height = height};
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
    if (width < 1 || height < 1 || width > max_size || height > max_size) {
        fprintf(stderr, "target: size %dx%d outside 1..%d\n", width, height, (int)max_size);
        return false;
    }
    glGenRenderbuffers(1, &t->color);
    glBindRenderbuffer(GL_RENDERBUFFER, t->color);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glGenRenderbuffers(1, &t->depth_stencil);
    glBindRenderbuffer(GL_RENDERBUFFER, t->depth_stencil);
    glRenderbufferStorage(GL_RENDERBUFFER, target_depth_format(false), width, height);
    glGenFramebuffers(1, &t->framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, t->framebuffer);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t->color);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, t->depth_stencil);
    return target_complete(t) && context_gl_ok("target_create");
}

bool target_match_depth(target *t, bool reversed_depth) {
    if (t->reversed_depth == reversed_depth)
        return true;
    t->reversed_depth = reversed_depth;
    glBindRenderbuffer(GL_RENDERBUFFER, t->depth_stencil);
    glRenderbufferStorage(GL_RENDERBUFFER, target_depth_format(reversed_depth), t->width, t->height);
    glBindFramebuffer(GL_FRAMEBUFFER, t->framebuffer);
    return target_complete(t) && context_gl_ok("target_match_depth");
}

void target_bind(const target *t) {
    glBindFramebuffer(GL_FRAMEBUFFER, t->framebuffer);
    glViewport(0, 0, t->width, t->height);
}

/* The bound read framebuffer's width x height pixels, top row first,
 * opaque. */
static bool target_read_bound(int width, int height, unsigned char *rgba) {
    size_t row = (size_t)width * 4;
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    /* Pictures are opaque: alpha is the techniques' scratch (blending
     * passes leave anything there), never part of the image. */
    for (size_t i = 3; i < row * (size_t)height; i += 4)
        rgba[i] = 255;
    /* GL's rows start at the bottom. */
    unsigned char *swap = malloc(row);
    if (!swap) {
        fprintf(stderr, "target: out of memory\n");
        return false;
    }
    for (int y = 0; y < height / 2; y++) {
        unsigned char *a = rgba + (size_t)y * row, *b = rgba + (size_t)(height - 1 - y) * row;
        memcpy(swap, a, row);
        memcpy(a, b, row);
        memcpy(b, swap, row);
    }
    free(swap);
    return context_gl_ok("target_read_rgba");
}

bool target_read_rgba(const target *t, unsigned char *rgba) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, t->framebuffer);
    return target_read_bound(t->width, t->height, rgba);
}

bool target_read_window_rgba(int width, int height, unsigned char *rgba) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    return target_read_bound(width, height, rgba);
}

void target_blit_to_window(const target *t, int window_width, int window_height) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, t->framebuffer);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBlitFramebuffer(0, 0, t->width, t->height, 0, 0, window_width, window_height, GL_COLOR_BUFFER_BIT, GL_LINEAR);
}

void target_destroy(target *t) {
    glDeleteFramebuffers(1, &t->framebuffer);
    glDeleteRenderbuffers(1, &t->color);
    glDeleteRenderbuffers(1, &t->depth_stencil);
    *t = (target){0};
}
