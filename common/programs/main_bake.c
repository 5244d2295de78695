/* main of build/bake: for the web build, which cannot link assimp, a model
 * file as a mesh pack (mesh_pack.h), the mesh mesh_load_file makes of it,
 * or a glTF scene as a scene pack (scene_pack.h), the scene scene_load
 * makes of it through its camera 0. `bake MODEL PACK`; errors are one
 * line, exit 1. */
#include <stdio.h>

#include "mesh.h"
#include "mesh_pack.h"
#include "scene.h"
#include "scene_pack.h"

int main(int argc, char **argv) {
    if (argc != 3) {
        fprintf(stderr,
                "usage: %s MODEL PACK (a model file as mesh_load_file reads it, a .gltf or .glb as scene_load "
                "reads it: a pack for the web build)\n",
                argv[0]);
        return 2;
    }
    bool ok;
    if (scene_is_gltf(argv[1])) {
        scene s;
        ok = scene_load(&s, argv[1]) && scene_pack_write(argv[2], &s);
        scene_free(&s);
    } else {
        mesh m;
        mesh_material material;
        ok = mesh_load_file(&m, argv[1], &material) && mesh_pack_write(argv[2], &m, &material);
        mesh_free(&m);
    }
    return ok ? 0 : 1;
}
