/* A map's depth bounds (map_internal.h, map_bounds_update): per cell of
 * MAP_BOUNDS_CELL_TEXELS texels on a side, a plane fitted to its depths
 * and the two heights of it between which every depth lies
 * (shaders/map_bounds.frag), which a marking pass reads instead of the
 * kernel (shaders/map.glsl, map_bounds_answer): a pixel whose kernel could
 * only agree is decided there, and only the others run the kernel and the
 * rays, in the marked pass. */
#include <glad/gl.h>

#include "map_internal.h"
#include "shader.h"

/* A 2D map's or a cube map's program. */
static bool map_bounds_program(map_renderer *r, map_kind kind) {
    static const char *const files[] = {"viewport_triangle.vert", "map_bounds.frag"};
    const shader_define defines[] = {
        SHADER_DEFINE(MAP_BOUNDS_CELL_TEXELS), {"MAP_BOUNDS_CUBE", kind == MAP_CUBE}, {NULL, 0}};
    unsigned *program = &r->bounds_programs[kind == MAP_CUBE];
    if (!*program)
        *program = shader_load_program(files, 2, defines);
    r->bounds_failed = !*program; /* the loader said why */
    return !r->bounds_failed;
}

bool map_bounds_update(map_renderer *r, map_light *m) {
    map_texture *t = &m->texture;
    if (r->bounds_failed || m->kind == MAP_ARRAY)
        return false;
    if (t->bounds_current)
        return true;
    if (!map_bounds_program(r, m->kind))
        return false;
    unsigned program = r->bounds_programs[m->kind == MAP_CUBE];
    int cells = (m->size + MAP_BOUNDS_CELL_TEXELS - 1) / MAP_BOUNDS_CELL_TEXELS, width = cells * m->layer_count;
    if (!t->bounds) {
        glGenTextures(1, &t->bounds);
        glBindTexture(GL_TEXTURE_2D, t->bounds);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, cells, 0, GL_RGBA, GL_FLOAT, NULL);
        map_texture_filter(GL_TEXTURE_2D, GL_NEAREST);
    }
    r->bounds_failed = !map_color_target(&r->bounds_framebuffer, t->bounds, GL_TEXTURE_2D, 0,
                                         "each pixel of the marking pass reads its whole kernel");
    if (!r->bounds_failed) {
        /* The depths on their kind's comparison unit (the program reads
         * no other), through the depth sampler: compare mode off. */
        GLuint unit = (GLuint)m->kind;
        GLboolean depth_test = glIsEnabled(GL_DEPTH_TEST);
        glDisable(GL_DEPTH_TEST);
        glViewport(0, 0, width, cells);
        glActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(map_target(m->kind), t->id);
        glBindSampler(unit, r->depth_sampler);
        glActiveTexture(GL_TEXTURE0);
        glUseProgram(program);
        glUniform1i(shader_uniform(program, "u_depths"), (GLint)unit);
        glUniform1i(shader_uniform(program, "u_size"), m->size);
        glBindVertexArray(r->screen_vao);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glBindVertexArray(0);
        glBindSampler(unit, 0);
        if (depth_test)
            glEnable(GL_DEPTH_TEST);
        t->bounds_current = true;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)r->target_framebuffer);
    glViewport(r->viewport[0], r->viewport[1], r->viewport[2], r->viewport[3]);
    return t->bounds_current;
}

void map_bounds_destroy(map_renderer *r) {
    for (int i = 0; i < 2; i++)
        shader_delete_program(r->bounds_programs[i]);
    glDeleteFramebuffers(1, &r->bounds_framebuffer);
}
