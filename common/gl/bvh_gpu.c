#include "bvh_gpu.h"

#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

bool bvh_gpu_upload(bvh_gpu *g, const bvh *b, const char *who) {
    long long texels = 2LL * b->node_count + 3LL * b->triangle_count;
    long long rows = texels / BVH_GPU_TEXTURE_WIDTH + 1;
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (rows > max_size) {
        fprintf(stderr, "%s: %d triangles need a ray texture of %lld rows, more than this GL's %d\n", who,
                b->triangle_count, rows, max_size);
        return false;
    }
    float(*data)[4] = calloc((size_t)(rows * BVH_GPU_TEXTURE_WIDTH), sizeof *data);
    if (!data) {
        fprintf(stderr, "%s: out of memory for the ray texture of %d triangles\n", who, b->triangle_count);
        return false;
    }
    if (b->node_count > 0) { /* a scene without casters has no arrays */
        memcpy(data, b->nodes, (size_t)b->node_count * sizeof *b->nodes);
        memcpy(data + 2 * b->node_count, b->triangles, (size_t)b->triangle_count * sizeof *b->triangles);
    }
    if (!g->texture)
        glGenTextures(1, &g->texture);
    glBindTexture(GL_TEXTURE_2D, g->texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, BVH_GPU_TEXTURE_WIDTH, (GLsizei)rows, 0, GL_RGBA, GL_FLOAT, data);
    glBindTexture(GL_TEXTURE_2D, 0);
    free(data);
    g->node_count = b->node_count;
    g->reach = 0;
    for (int k = 0; k < 3 && b->node_count > 0; k++)
        g->reach += fmaxf(b->nodes[0][0][k] * b->nodes[0][0][k], b->nodes[0][1][k] * b->nodes[0][1][k]);
    g->reach = sqrtf(g->reach);
    return true;
}

void bvh_gpu_bind(const bvh_gpu *g, unsigned program, int unit) {
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_2D, g->texture);
    glActiveTexture(GL_TEXTURE0);
    glUniform1i(shader_uniform(program, "u_bvh"), unit);
    glUniform1i(shader_uniform(program, "u_bvh_node_count"), g->node_count);
    glUniform1f(shader_uniform(program, "u_bvh_reach"), g->reach);
}

void bvh_gpu_destroy(bvh_gpu *g) {
    glDeleteTextures(1, &g->texture);
    *g = (bvh_gpu){0};
}
