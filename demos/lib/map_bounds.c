/* A 2D map's depth bounds (map_internal.h, map_bounds_update): per cell
 * of MAP_BOUNDS_CELL_TEXELS texels on a side, its least and greatest
 * depth, which a marking pass reads instead of the kernel
 * (shaders/map_2d.glsl, map_bounds_visibility): a pixel whose kernel
 * could only agree is decided there, and only the others run the kernel
 * and the rays, in the marked pass. */
#include <glad/gl.h>

#include "map_internal.h"
#include "shader.h"

/* The depths are read on the 2D comparisons' unit (its program reads no
 * other), through the depth sampler: compare mode off. */
#define MAP_BOUNDS_UNIT MAP_2D

static bool map_bounds_program(map_renderer *r) {
    static const char *const files[] = {"viewport_triangle.vert", "map_bounds.frag"};
    static const shader_define defines[] = {SHADER_DEFINE(MAP_BOUNDS_CELL_TEXELS), {NULL, 0}};
    if (!r->bounds_program)
        r->bounds_program = shader_load_program(files, 2, defines);
    r->bounds_failed = !r->bounds_program; /* the loader said why */
    return !r->bounds_failed;
}

bool map_bounds_update(map_renderer *r, map_light *m) {
    map_texture *t = &m->texture;
    if (r->bounds_failed || m->kind != MAP_2D)
        return false;
    if (t->bounds_current)
        return true;
    if (!map_bounds_program(r))
        return false;
    int cells = (m->size + MAP_BOUNDS_CELL_TEXELS - 1) / MAP_BOUNDS_CELL_TEXELS;
    if (!t->bounds) {
        glGenTextures(1, &t->bounds);
        glBindTexture(GL_TEXTURE_2D, t->bounds);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RG32F, cells, cells, 0, GL_RG, GL_FLOAT, NULL);
        map_texture_filter(GL_TEXTURE_2D, GL_NEAREST);
    }
    r->bounds_failed = !map_color_target(&r->bounds_framebuffer, t->bounds, GL_TEXTURE_2D, 0,
                                         "each pixel of the marking pass reads its whole kernel");
    if (!r->bounds_failed) {
        GLboolean depth_test = glIsEnabled(GL_DEPTH_TEST);
        glDisable(GL_DEPTH_TEST);
        glViewport(0, 0, cells, cells);
        glActiveTexture(GL_TEXTURE0 + MAP_BOUNDS_UNIT);
        glBindTexture(GL_TEXTURE_2D, t->id);
        glBindSampler(MAP_BOUNDS_UNIT, r->depth_sampler);
        glActiveTexture(GL_TEXTURE0);
        glUseProgram(r->bounds_program);
        glUniform1i(shader_uniform(r->bounds_program, "u_depths"), MAP_BOUNDS_UNIT);
        glBindVertexArray(r->screen_vao);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glBindVertexArray(0);
        glBindSampler(MAP_BOUNDS_UNIT, 0);
        if (depth_test)
            glEnable(GL_DEPTH_TEST);
        t->bounds_current = true;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)r->target_framebuffer);
    glViewport(r->viewport[0], r->viewport[1], r->viewport[2], r->viewport[3]);
    return t->bounds_current;
}

void map_bounds_destroy(map_renderer *r) {
    shader_delete_program(r->bounds_program);
    glDeleteFramebuffers(1, &r->bounds_framebuffer);
}
