/* The camera pass's second targets (map.h, "Rays"; map_internal.h): the
 * pixels rays decide, marked by the pass before the one that traces them
 * and turned into the stencil that lets only those through; and the rays
 * counted, read back and summed. Each is a texture the frame's size,
 * attached as the target's second colour buffer for the receivers'
 * passes alone. */
#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>

#include "map_internal.h"
#include "shader.h"

/* Read back as RGBA, the format every GL reads its targets in. */
#define MAP_SECOND_CHANNELS 4
/* The stencil value of a marked pixel, and the bits it takes. */
#define MAP_MARKED_STENCIL 1
#define MAP_MARKED_STENCIL_BITS 0xffu
/* The marks' texture is read between the two camera passes, on the rays'
 * unit: each camera pass binds the casters there again (map_camera_use). */
#define MAP_MARKS_UNIT MAP_RAY_UNIT

/* ---- the second target ---- */

/* t's texture at the target's size (its viewport's far corner), in
 * `format` (an internal format drawable as colour, given as `pixel`s),
 * and its framebuffer for the read-back (false: this GL cannot draw into
 * that format, said once with `what`). */
static bool map_second_texture(const map_renderer *r, map_second_target *t, GLenum format, GLenum pixel,
                               const char *what) {
    int width = r->viewport[0] + r->viewport[2], height = r->viewport[1] + r->viewport[3];
    if (t->texture && t->size[0] == width && t->size[1] == height)
        return true;
    if (!t->texture)
        glGenTextures(1, &t->texture);
    glBindTexture(GL_TEXTURE_2D, t->texture);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)format, width, height, 0, pixel == GL_FLOAT ? GL_RGBA : GL_RED, pixel,
                 NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    t->size[0] = width;
    t->size[1] = height;
    if (!t->framebuffer) {
        glGenFramebuffers(1, &t->framebuffer);
        glBindFramebuffer(GL_FRAMEBUFFER, t->framebuffer);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t->texture, 0);
        t->failed = glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE;
        glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)r->target_framebuffer);
        if (t->failed)
            fprintf(stderr, "shadow maps: %s: this GL cannot draw into the texture\n", what);
    }
    return !t->failed;
}

/* The target framebuffer's colour alone again. */
static void map_second_detach(void) {
    static const GLenum colour[] = {GL_COLOR_ATTACHMENT0};
    glDrawBuffers(1, colour);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, 0, 0);
}

/* Attaches t's texture beside the target framebuffer's colour, both
 * drawn, and clears it to 0 (false: the target cannot take it, said once
 * with `what`, detached again). */
static bool map_second_attach(map_renderer *r, map_second_target *t, const char *what) {
    if (t->failed)
        return false;
    if (r->target_framebuffer == 0) {
        fprintf(stderr, "shadow maps: %s: the frame is drawn into the default framebuffer\n", what);
        t->failed = true;
        return false;
    }
    static const GLenum both[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, t->texture, 0);
    glDrawBuffers(2, both);
    t->failed = glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE;
    if (t->failed) {
        fprintf(stderr, "shadow maps: %s: the frame's target takes no second colour target\n", what);
        map_second_detach();
        return false;
    }
    static const float none[MAP_SECOND_CHANNELS] = {0};
    glDisable(GL_SCISSOR_TEST);
    glClearBufferfv(GL_COLOR, 1, none);
    return true;
}

/* t's viewport pixels, RGBA of `type` (GL_FLOAT or GL_UNSIGNED_BYTE,
 * formats every GL reads its kind of target in), malloc'd (NULL: out of
 * memory, said with `what`). */
static void *map_second_read(const map_renderer *r, const map_second_target *t, GLenum type, const char *what) {
    size_t pixels = (size_t)r->viewport[2] * (size_t)r->viewport[3];
    void *data = malloc(pixels * MAP_SECOND_CHANNELS * (type == GL_FLOAT ? sizeof(float) : 1));
    if (!data) {
        fprintf(stderr, "shadow maps: %s: out of memory\n", what);
        return NULL;
    }
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, t->framebuffer);
    glReadPixels(r->viewport[0], r->viewport[1], r->viewport[2], r->viewport[3], GL_RGBA, type, data);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)r->target_framebuffer);
    return data;
}

/* ---- the marks ---- */

#define MAP_MARKS_WHAT "unsure pixels are not traced in a pass of their own"

bool map_ray_marks_begin(map_renderer *r) {
    map_second_target *t = &r->marks;
    r->marked_pixels = 0;
    if (!t->failed && !r->marks_program) {
        static const char *const files[] = {"viewport_triangle.vert", "map_marks.frag"};
        r->marks_program = shader_load_program(files, 2, NULL);
        t->failed = !r->marks_program; /* the loader said why */
    }
    return !t->failed && map_second_texture(r, t, GL_R8, GL_UNSIGNED_BYTE, MAP_MARKS_WHAT) &&
           map_second_attach(r, t, MAP_MARKS_WHAT);
}

void map_ray_marks_end(map_renderer *r, bool count) {
    map_second_detach();
    unsigned char *marks =
        count ? map_second_read(r, &r->marks, GL_UNSIGNED_BYTE, "the marks are not counted") : NULL;
    size_t pixels = (size_t)r->viewport[2] * (size_t)r->viewport[3];
    for (size_t i = 0; marks && i < pixels; i++)
        r->marked_pixels += marks[i * MAP_SECOND_CHANNELS] != 0;
    free(marks);
    GLboolean depth_test = glIsEnabled(GL_DEPTH_TEST);
    glDisable(GL_DEPTH_TEST);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glStencilMask(MAP_MARKED_STENCIL_BITS);
    glClear(GL_STENCIL_BUFFER_BIT); /* the scissor is off: map_second_attach */
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, MAP_MARKED_STENCIL, MAP_MARKED_STENCIL_BITS);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glUseProgram(r->marks_program);
    glUniform1i(shader_uniform(r->marks_program, "u_marks"), MAP_MARKS_UNIT);
    glActiveTexture(GL_TEXTURE0 + MAP_MARKS_UNIT);
    glBindTexture(GL_TEXTURE_2D, r->marks.texture);
    glActiveTexture(GL_TEXTURE0);
    glBindVertexArray(r->screen_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (depth_test)
        glEnable(GL_DEPTH_TEST);
    glStencilFunc(GL_EQUAL, MAP_MARKED_STENCIL, MAP_MARKED_STENCIL_BITS);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
}

/* ---- the counts ---- */

#define MAP_COUNTS_WHAT "the rays are not counted"

bool map_ray_counts_begin(map_renderer *r) {
    map_second_target *t = &r->counts;
    return !t->failed && map_second_texture(r, t, GL_RGBA32F, GL_FLOAT, MAP_COUNTS_WHAT) &&
           map_second_attach(r, t, MAP_COUNTS_WHAT);
}

void map_ray_counts_end(map_renderer *r) {
    map_second_detach();
    float *counts = map_second_read(r, &r->counts, GL_FLOAT, MAP_COUNTS_WHAT);
    if (!counts) {
        r->counts.failed = true;
        return;
    }
    /* The viewport's pixels: R the rays, G the lights traced. */
    size_t pixels = (size_t)r->viewport[2] * (size_t)r->viewport[3];
    technique_rays sums = {.pixels = (long)pixels, .marked = r->marked_pixels};
    for (size_t i = 0; i < pixels; i++) {
        sums.rays += (long)counts[i * MAP_SECOND_CHANNELS];
        sums.traced += (long)counts[i * MAP_SECOND_CHANNELS + 1];
    }
    free(counts);
    r->counted = sums;
    r->has_counted = true;
}

void map_rays_destroy(map_renderer *r) {
    map_second_target *targets[] = {&r->counts, &r->marks};
    for (size_t i = 0; i < sizeof targets / sizeof *targets; i++) {
        glDeleteTextures(1, &targets[i]->texture);
        glDeleteFramebuffers(1, &targets[i]->framebuffer);
    }
    shader_delete_program(r->marks_program);
}

bool map_rays_counted(const map_renderer *r, technique_rays *out) {
    if (!r->has_counted)
        return false;
    *out = r->counted;
    return true;
}
