/* The camera pass's rays counted (map.h, "Rays"; map_internal.h,
 * map_ray_counts_begin): a second colour target beside the frame's, for
 * the receivers' passes alone, read back and summed. */
#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>

#include "map_internal.h"

/* Read back as RGBA floats, the format every GL reads a float target in. */
#define MAP_COUNTS_CHANNELS 4

static void map_ray_counts_fail(map_renderer *r, const char *why) {
    if (!r->counts_failed)
        fprintf(stderr, "shadow maps: the rays are not counted: %s\n", why);
    r->counts_failed = true;
}

/* The counts' texture at the target's size (its viewport's far corner). */
static bool map_ray_counts_texture(map_renderer *r) {
    int width = r->viewport[0] + r->viewport[2], height = r->viewport[1] + r->viewport[3];
    if (r->counts_texture && r->counts_size[0] == width && r->counts_size[1] == height)
        return true;
    if (!r->counts_texture)
        glGenTextures(1, &r->counts_texture);
    if (!r->counts_framebuffer)
        glGenFramebuffers(1, &r->counts_framebuffer);
    glBindTexture(GL_TEXTURE_2D, r->counts_texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, r->counts_framebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, r->counts_texture, 0);
    bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)r->target_framebuffer);
    r->counts_size[0] = width;
    r->counts_size[1] = height;
    if (!complete)
        map_ray_counts_fail(r, "this GL cannot draw into an RGBA32F texture");
    return complete;
}

bool map_ray_counts_begin(map_renderer *r) {
    if (r->counts_failed)
        return false;
    if (r->target_framebuffer == 0) {
        map_ray_counts_fail(r, "the frame is drawn into the default framebuffer");
        return false;
    }
    if (!map_ray_counts_texture(r))
        return false;
    static const GLenum both[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, r->counts_texture, 0);
    glDrawBuffers(2, both);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        map_ray_counts_fail(r, "the frame's target takes no second colour target");
        map_ray_counts_end(r); /* detaches it; failed, it reads nothing back */
        return false;
    }
    static const float none[MAP_COUNTS_CHANNELS] = {0};
    glDisable(GL_SCISSOR_TEST);
    glClearBufferfv(GL_COLOR, 1, none);
    return true;
}

void map_ray_counts_end(map_renderer *r) {
    static const GLenum colour[] = {GL_COLOR_ATTACHMENT0};
    glDrawBuffers(1, colour);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, 0, 0);
    if (r->counts_failed)
        return;
    /* The viewport's pixels: R the rays, G the lights traced. */
    size_t pixels = (size_t)r->viewport[2] * (size_t)r->viewport[3];
    float *counts = malloc(pixels * MAP_COUNTS_CHANNELS * sizeof *counts);
    if (!counts) {
        map_ray_counts_fail(r, "out of memory");
        return;
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r->counts_framebuffer);
    glReadPixels(r->viewport[0], r->viewport[1], r->viewport[2], r->viewport[3], GL_RGBA, GL_FLOAT, counts);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)r->target_framebuffer);
    technique_rays sums = {.pixels = (long)pixels};
    for (size_t i = 0; i < pixels; i++) {
        sums.rays += (long)counts[i * MAP_COUNTS_CHANNELS];
        sums.traced += (long)counts[i * MAP_COUNTS_CHANNELS + 1];
    }
    free(counts);
    r->counted = sums;
    r->has_counted = true;
}

void map_ray_counts_destroy(map_renderer *r) {
    glDeleteTextures(1, &r->counts_texture);
    glDeleteFramebuffers(1, &r->counts_framebuffer);
}

bool map_rays_counted(const map_renderer *r, technique_rays *out) {
    if (!r->has_counted)
        return false;
    *out = r->counted;
    return true;
}
