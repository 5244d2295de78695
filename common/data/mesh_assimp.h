/* mesh_assimp: model files through assimp (mesh_file.c) for what reads
 * one as more than one mesh: a scene made of a glTF file (scene_gltf.c).
 * The assimp types show here only. */
#ifndef MESH_ASSIMP_H
#define MESH_ASSIMP_H

#include <assimp/scene.h>
#include <stdbool.h>

#include "mesh.h"

/* The file imported with every check of mesh_load_file (the limits,
 * triangulated, welded, smooth normals where it has none), its node graph
 * kept: each node's meshes in the node's space. NULL after "PATH:
 * problem". Free with aiReleaseImport. */
const struct aiScene *mesh_import_graph(const char *path);
/* One of its meshes' triangles into m, sanitized (mesh_sanitize_quietly,
 * adding to *removed; name: for the messages). */
bool mesh_from_assimp(mesh *m, const char *name, const struct aiMesh *am, mesh_removed *removed);
/* The colour a material gives (mesh_material's rule for one material):
 * false for assimp's stand-in and for a colour that is none. */
bool mesh_material_color(const struct aiMaterial *material, float color[3]);

#endif
