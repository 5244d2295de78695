/* bvh_gpu: a ray hierarchy (bvh.h) in one RGBA32F texture, for
 * shaders/bvh_trace.glsl: its nodes from texel 0, two a node, then its
 * triangles from texel 2 x node_count, three a triangle. The texture is a
 * texture buffer where the GL has them (context_features.texture_buffers)
 * and they hold every texel (GL_MAX_TEXTURE_BUFFER_SIZE): a read is one
 * index, where a 2D texture's is a row and a column. Elsewhere (WebGL 2
 * has none) it is a 2D texture in rows of BVH_GPU_TEXTURE_WIDTH texels.
 * The programs that trace are told which by BVH_TEXTURE_BUFFER (1 where
 * `buffer` is). Then, where the
 * rays read casters' surfaces (bvh.h's records: cut-out or translucent),
 * four texels a record: its corners' texture coordinates (u0, v0, u1,
 * v1), (u2, v2, base alpha, alpha cutoff), its texture's (first texel,
 * width, height, 4 x wrap along u + wrap along v: texture_wrap; a width
 * of 0 has no texture) and (base colour, 1 translucent or 0); then those
 * textures' level 0, a texel each, bottom row first, the colour decoded
 * to linear light: what scene_object_cut_out and
 * scene_object_transmittance read, on the same unit as the rest.
 *
 *   bvh_gpu g = {0};
 *   bvh_gpu_upload(&g, &hierarchy, "hybrid");   once per scene
 *   bvh_gpu_bind(&g, program, unit);            the program in use
 *   bvh_gpu_destroy(&g);
 *
 * A program that includes bvh_trace.glsl is given BVH_GPU_DEFINES. */
#ifndef BVH_GPU_H
#define BVH_GPU_H

#include <stdbool.h>

#include "bvh.h"
#include "shader.h"

/* Texels a row: GL 3.3 promises 1024-texel textures. */
#define BVH_GPU_TEXTURE_WIDTH 1024
#define BVH_GPU_DEFINES                                                                                              \
    SHADER_DEFINE(BVH_GPU_TEXTURE_WIDTH), SHADER_DEFINE(BVH_MAX_DEPTH), SHADER_DEFINE(BVH_SURFACE_ULPS)

typedef struct bvh_gpu {
    unsigned texture;
    unsigned buffer;                 /* the texture's store where it is a texture buffer, else 0 (2D) */
    int node_count;                  /* 0: no casters, every ray gets through */
    int record_count;                /* > 0: the programs that trace need BVH_RECORDS 1 */
    int records_first, texels_first; /* texels */
    float reach;                     /* the farthest corner of the casters' box from the origin */
} bvh_gpu;

/* b's arrays into g's texture (made, or made again; a texture buffer or
 * 2D, see the top); false after printing one line naming `who` where the
 * GL's largest 2D texture cannot hold them either. */
bool bvh_gpu_upload(bvh_gpu *g, const bvh *b, const char *who);
/* The texture on texture unit `unit` (its target: a texture buffer's or
 * 2D) and the uniforms of `program`, in use. */
void bvh_gpu_bind(const bvh_gpu *g, unsigned program, int unit);
void bvh_gpu_destroy(bvh_gpu *g);

#endif
