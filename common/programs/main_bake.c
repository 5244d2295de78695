/* main of build/bake: a model file as a mesh pack (mesh_pack.h), the mesh
 * mesh_load_file makes of it through assimp, for the web build, which
 * cannot link assimp. `bake MODEL PACK`; errors are one line, exit 1. */
#include <stdio.h>

#include "mesh.h"
#include "mesh_pack.h"

int main(int argc, char **argv) {
    if (argc != 3) {
        fprintf(stderr, "usage: %s MODEL PACK (the model as mesh_load_file reads it, for the web build)\n", argv[0]);
        return 2;
    }
    mesh m;
    mesh_material material;
    bool ok = mesh_load_file(&m, argv[1], &material) && mesh_pack_write(argv[2], &m, &material);
    mesh_free(&m);
    return ok ? 0 : 1;
}
