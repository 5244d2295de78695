/* mesh_pack: a model as mesh_load_file made it, in a file that needs no
 * importer: what the web build reads where native programs use assimp
 * (the page cannot link it), written by build/bake.
 *
 * The file: MESH_PACK_MAGIC (8 bytes), then little-endian uint32 vertex
 * and index counts, a uint32 0 or 1 (mesh_material.has_color), float
 * colour[3], bounds_min[3], bounds_max[3], the vertices (mesh_vertex: eight
 * floats each) and the indices (uint32). Floats are IEEE 754 binary32 as
 * the mesh holds them, so the mesh read back is the one written, bit for
 * bit. The hosts that build and read it (x86-64, wasm32) are
 * little-endian.
 *
 * Errors are one line "PATH: problem", as mesh.h's. */
#ifndef MESH_PACK_H
#define MESH_PACK_H

#include <stdbool.h>
#include <stdio.h>

#include "mesh.h"

#define MESH_PACK_MAGIC "SHMESH2"

/* material may be NULL (no colour). */
bool mesh_pack_write(const char *path, const mesh *m, const mesh_material *material);
/* The mesh and its material as written; a file that is not one, is
 * truncated, or whose indices leave the vertices is an error. */
bool mesh_pack_read(mesh *m, const char *path, mesh_material *material);

/* The same pack within a larger file (a scene pack's meshes,
 * scene_pack.h), at f's position, which it leaves after the pack. Writing
 * says nothing (false: a write failed, errno says why); reading's lines
 * name `path`, and what follows the pack is the caller's to read. */
bool mesh_pack_put(FILE *f, const mesh *m, const mesh_material *material);
bool mesh_pack_get(FILE *f, const char *path, mesh *m, mesh_material *material);

#endif
