/* mesh_build: what the mesh constructors share (mesh.c's generators,
 * mesh_file.c's import, mesh_pack.c's reader). Not for other modules. */
#ifndef MESH_BUILD_H
#define MESH_BUILD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mesh.h"

/* Reports "NAME: problem" (to the handler of mesh_set_error_handler, else
 * stderr) and empties the mesh (when given one), so that every failure
 * path leaves it safe to free. Returns false. */
bool mesh_fail(mesh *m, const char *name, const char *format, ...) __attribute__((format(printf, 3, 4)));
/* Room for the given counts; vertex_count and index_count stay 0 and serve
 * as the write cursors of mesh_push_vertex and mesh_push_triangle. */
bool mesh_alloc(mesh *m, const char *name, size_t vertex_count, size_t index_count);
uint32_t mesh_push_vertex(mesh *m, const float position[3], const float normal[3]);
void mesh_push_triangle(mesh *m, uint32_t a, uint32_t b, uint32_t c);

#endif
