/* The page's glTF scenes: none. assimp, which reads them natively
 * (common/data/scene_gltf.c), is not built for the browser; the page's
 * scenes are its JSON ones, their models baked into mesh packs. */
#include <stdio.h>

#include "scene_internal.h"

bool scene_load_gltf(scene *s, const char *path, int camera) {
    (void)camera;
    *s = (scene){0};
    fprintf(stderr, "%s: glTF scenes are read by the native programs only (assimp is not in the page)\n", path);
    return false;
}

bool scene_include_gltf(scene *s, int *capacity, const char *path, const float model[4][4], const char *prefix,
                        bool casts, bool receives) {
    (void)s, (void)capacity, (void)model, (void)prefix, (void)casts, (void)receives;
    fprintf(stderr, "%s: glTF files are read by the native programs only (assimp is not in the page)\n", path);
    return false;
}
