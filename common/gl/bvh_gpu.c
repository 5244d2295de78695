#include "bvh_gpu.h"

#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "context.h"

/* BVH_GPU_RECORD_TEXELS a record (see the top). */
#define BVH_GPU_RECORD_TEXELS 4
#define BVH_GPU_WRAP_BASE 4

/* The texels that b's records' textures need, each texture's once (a
 * tree's leaves share one): each record's first texel into first[] (-1
 * without texture), and whether it writes them into writes[]; returns
 * their count, or -1 out of memory. */
static long long bvh_gpu_texel_count(const bvh *b, long long *first, bool *writes) {
    const texture **seen = calloc((size_t)b->record_count + 1, sizeof *seen);
    long long *seen_first = calloc((size_t)b->record_count + 1, sizeof *seen_first);
    long long count = seen && seen_first ? 0 : -1;
    for (int i = 0, distinct = 0; count >= 0 && i < b->record_count; i++) {
        const texture *t = b->records[i].object->base_color;
        int k = 0;
        while (k < distinct && seen[k] != t)
            k++;
        writes[i] = t && k == distinct;
        if (writes[i]) {
            seen[distinct] = t;
            seen_first[distinct++] = count;
            count += (long long)t->levels[0].width * t->levels[0].height;
        }
        first[i] = t ? seen_first[k] : -1;
    }
    free(seen);
    free(seen_first);
    return count;
}

/* The records and their textures' texels into data, from texel
 * g->records_first. */
static void bvh_gpu_records(const bvh_gpu *g, const bvh *b, const long long *first, const bool *writes,
                            float (*data)[4]) {
    float(*record)[4] = data + g->records_first;
    float(*texels)[4] = data + g->texels_first;
    for (int i = 0; i < b->record_count; i++, record += BVH_GPU_RECORD_TEXELS) {
        const scene_object *o = b->records[i].object;
        const uint32_t *corner = o->mesh.indices + 3 * b->records[i].triangle;
        const float *uv0 = o->mesh.vertices[corner[0]].uv, *uv1 = o->mesh.vertices[corner[1]].uv,
                    *uv2 = o->mesh.vertices[corner[2]].uv;
        const texture *t = o->base_color;
        memcpy(record[0], (const float[4]){uv0[0], uv0[1], uv1[0], uv1[1]}, sizeof record[0]);
        memcpy(record[1], (const float[4]){uv2[0], uv2[1], o->base_alpha, o->alpha_cutoff}, sizeof record[1]);
        memcpy(record[3], (const float[4]){o->color[0], o->color[1], o->color[2], o->translucent ? 1.0f : 0.0f},
               sizeof record[3]);
        if (!t)
            continue;
        const texture_level *level = &t->levels[0];
        memcpy(record[2],
               (const float[4]){(float)first[i], (float)level->width, (float)level->height,
                                (float)(BVH_GPU_WRAP_BASE * (int)t->wrap[0] + (int)t->wrap[1])},
               sizeof record[2]);
        for (long long k = 0; writes[i] && k < (long long)level->width * level->height; k++) {
            const unsigned char *rgba = level->rgba + 4 * k;
            float *texel = texels[first[i] + k];
            for (int c = 0; c < 3; c++)
                texel[c] = texture_srgb_to_linear(rgba[c]);
            texel[3] = rgba[3] / 255.0f;
        }
    }
}

bool bvh_gpu_upload(bvh_gpu *g, const bvh *b, const char *who) {
    long long *first = calloc((size_t)b->record_count + 1, sizeof *first);
    bool *writes = calloc((size_t)b->record_count + 1, sizeof *writes);
    long long surface_texels = first && writes ? bvh_gpu_texel_count(b, first, writes) : -1;
    if (surface_texels < 0) {
        fprintf(stderr, "%s: out of memory for the ray texture of %d triangles\n", who, b->triangle_count);
        free(first);
        free(writes);
        return false;
    }
    long long records_first = 2LL * b->node_count + 3LL * b->triangle_count;
    long long texels_first = records_first + (long long)BVH_GPU_RECORD_TEXELS * b->record_count;
    long long texels = texels_first + surface_texels;
    long long rows = texels / BVH_GPU_TEXTURE_WIDTH + 1;
    GLint max_size = 0, max_buffer = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (context_current_features()->texture_buffers)
        glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_buffer);
    bool buffer = texels < max_buffer;
    if (texels >= BVH_MAX_INDEX || (!buffer && rows > max_size)) {
        fprintf(stderr,
                "%s: %d triangles and their surfaces' textures need a ray texture of %lld rows, more than "
                "this GL's %d or the %d texels indices reach\n",
                who, b->triangle_count, rows, max_size, BVH_MAX_INDEX);
        free(first);
        free(writes);
        return false;
    }
    float(*data)[4] = calloc((size_t)(rows * BVH_GPU_TEXTURE_WIDTH), sizeof *data);
    if (!data) {
        fprintf(stderr, "%s: out of memory for the ray texture of %d triangles\n", who, b->triangle_count);
        free(first);
        free(writes);
        return false;
    }
    bvh_gpu_destroy(g); /* a texture's target is fixed once bound: made anew */
    g->record_count = b->record_count;
    g->records_first = (int)records_first;
    g->texels_first = (int)texels_first;
    if (b->node_count > 0) { /* a scene without casters has no arrays */
        memcpy(data, b->nodes, (size_t)b->node_count * sizeof *b->nodes);
        memcpy(data + 2 * b->node_count, b->triangles, (size_t)b->triangle_count * sizeof *b->triangles);
        bvh_gpu_records(g, b, first, writes, data);
    }
    free(first);
    free(writes);
    glGenTextures(1, &g->texture);
    if (buffer) {
        /* One texel at least: a scene without casters has none. */
        glGenBuffers(1, &g->buffer);
        glBindBuffer(GL_TEXTURE_BUFFER, g->buffer);
        glBufferData(GL_TEXTURE_BUFFER, (GLsizeiptr)((texels + 1) * (long long)sizeof *data), data, GL_STATIC_DRAW);
        glBindBuffer(GL_TEXTURE_BUFFER, 0);
        glBindTexture(GL_TEXTURE_BUFFER, g->texture);
        glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, g->buffer);
        glBindTexture(GL_TEXTURE_BUFFER, 0);
    } else {
        glBindTexture(GL_TEXTURE_2D, g->texture);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, BVH_GPU_TEXTURE_WIDTH, (GLsizei)rows, 0, GL_RGBA, GL_FLOAT, data);
        glBindTexture(GL_TEXTURE_2D, 0);
    }
    free(data);
    g->node_count = b->node_count;
    g->reach = bvh_reach(b);
    return true;
}

void bvh_gpu_bind(const bvh_gpu *g, unsigned program, int unit) {
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(g->buffer ? GL_TEXTURE_BUFFER : GL_TEXTURE_2D, g->texture);
    glActiveTexture(GL_TEXTURE0);
    glUniform1i(shader_uniform(program, "u_bvh"), unit);
    glUniform1i(shader_uniform(program, "u_bvh_node_count"), g->node_count);
    glUniform1f(shader_uniform(program, "u_bvh_reach"), g->reach);
    glUniform1i(shader_uniform_optional(program, "u_bvh_records_first"), g->records_first);
    glUniform1i(shader_uniform_optional(program, "u_bvh_texels_first"), g->texels_first);
}

void bvh_gpu_destroy(bvh_gpu *g) {
    glDeleteTextures(1, &g->texture);
    glDeleteBuffers(1, &g->buffer);
    *g = (bvh_gpu){0};
}
