/* The page's glTF scenes: scene packs (scene_pack.h) that build/bake
 * wrote from the glTF files natively, through their camera 0, embedded in
 * the page at the files' own paths, since assimp, which reads them
 * natively (common/data/scene_gltf.c), cannot be linked there. */
#include <stdio.h>

#include "scene_internal.h"
#include "scene_pack.h"

bool scene_load_gltf(scene *s, const char *path, int camera) {
    if (camera == 0)
        return scene_pack_read(s, path);
    *s = (scene){0};
    fprintf(stderr, "%s: --camera %d: the page's glTF scenes are baked through their camera 0 only\n", path, camera);
    return false;
}

bool scene_include_gltf(scene *s, int *capacity, const char *path, const float model[4][4], const char *prefix,
                        bool casts, bool receives) {
    return scene_pack_include(s, capacity, path, model, prefix, casts, receives);
}
