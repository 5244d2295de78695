/* The web build's model files: mesh packs (mesh_pack.h) that build/bake
 * wrote from the models natively, embedded in the page at the models'
 * own paths, since assimp cannot be linked there. */
#include "mesh.h"
#include "mesh_pack.h"

bool mesh_load_file(mesh *m, const char *path, mesh_material *material) { return mesh_pack_read(m, path, material); }
