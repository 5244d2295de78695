/* volume_cache: one light's shadow volumes kept on the GPU, so that they
 * are drawn again without being built again (demos/lib/volume_draw.c).
 *
 * One vertex buffer holds, for each object, the parts of its volume that
 * were kept (VOLUME_MESH_SIDES and VOLUME_MESH_CAPS apart: the camera
 * picks z-pass or z-fail each frame, and either takes what is kept), one
 * after another in the order they were kept. volume_cache_forget drops
 * them all (the light moved) and keeps the buffer for the next ones. The
 * buffer doubles as it fills, its contents copied over, within a byte
 * budget the caller shares between its caches; what does not fit is not
 * kept (the caller draws it another way).
 *
 * Vertices are homogeneous, in the object's space, as volume_mesh builds
 * them; the caller binds the program and the object's model matrix.
 */
#ifndef VOLUME_CACHE_H
#define VOLUME_CACHE_H

#include <stdbool.h>
#include <stddef.h>

#include "volume_mesh.h"

/* The parts kept, indexed by volume_mesh_parts: sides and caps (never the
 * overlays' lines). */
#define VOLUME_CACHE_PARTS 2
_Static_assert(VOLUME_MESH_SIDES < VOLUME_CACHE_PARTS && VOLUME_MESH_CAPS < VOLUME_CACHE_PARTS,
               "the kept parts index the ranges");
/* A kept vertex: homogeneous, four floats. */
#define VOLUME_CACHE_VERTEX_BYTES (4 * sizeof(float))

/* Where a part lies in the buffer, in vertices; count < 0: not kept. */
typedef struct volume_cache_range {
    int first, count;
} volume_cache_range;

/* Zero is an unmade cache. */
typedef struct volume_cache {
    unsigned vao, buffer;
    size_t used, capacity; /* vertices */
    volume_cache_range (*ranges)[VOLUME_CACHE_PARTS];
    int object_count;
} volume_cache;

/* An empty cache for `object_count` objects; false after printing why. */
bool volume_cache_init(volume_cache *c, int object_count);
void volume_cache_free(volume_cache *c);
/* Drops every kept part. */
void volume_cache_forget(volume_cache *c);
bool volume_cache_has(const volume_cache *c, int object, volume_mesh_parts part);
/* Keeps v as the object's part, growing the buffer while *bytes (every
 * cache's buffers) stays within max_bytes; false if it does not fit. */
bool volume_cache_keep(volume_cache *c, int object, volume_mesh_parts part, const volume_mesh *v, size_t *bytes,
                       size_t max_bytes);
/* Draws a kept part (volume_cache_has) as triangles. */
void volume_cache_draw(const volume_cache *c, int object, volume_mesh_parts part);
/* Points vertex array `vao` at homogeneous vertices in `buffer`: the
 * cache's layout, for any other buffer of volume vertices too. */
void volume_cache_vertex_array(unsigned vao, unsigned buffer);

#endif
