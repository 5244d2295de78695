/* scene_internal: what the scene loaders share (scene.c's JSON files,
 * scene_gltf.c's glTF files, scene_pack.c's packs of them, and the page's
 * glTF loader over those). Not for other modules. */
#ifndef SCENE_INTERNAL_H
#define SCENE_INTERNAL_H

#include "scene.h"

/* The ambient light where a file gives none. */
#define SCENE_DEFAULT_AMBIENT 0.1f

/* The origin ("Large worlds", scene.h), from the camera as read (world
 * coordinates): its eye where the eye lies farther from the world's
 * origin than SCENE_REBASE_RATIO times its distance to the target, else
 * the world's origin. */
void scene_choose_origin(const scene_camera *c, double origin[3]);
/* Room in s->objects (of *capacity) for one more object, the array
 * doubled where full (SCENE_FIRST_CAPACITY from none); false after
 * "FILE: out of memory for N objects". */
#define SCENE_FIRST_CAPACITY 16
bool scene_reserve_object(scene *s, int *capacity, const char *file);
/* Room in s->textures for `more` zeroed textures after its own, the
 * array moved where it must be and its objects' base_color with it;
 * false after "FILE: out of memory for N textures". */
bool scene_reserve_textures(scene *s, size_t more, const char *file);
/* o placed by `world`: its model matrix, where `world` mirrors (a
 * negative determinant) the mirror moved into the mesh (mesh_reflect_x)
 * and the matrix's x column negated, so that the model keeps a positive
 * determinant and every world position is the same. */
void scene_object_place(scene_object *o, const float world[4][4]);
/* A glTF file's object's name: its node's, this long at most (room for a
 * suffix that makes it one object's), after a scene file's prefix of
 * SCENE_GLTF_PREFIX_MAX bytes at most and a slash where a scene file
 * includes the file. */
#define SCENE_GLTF_NODE_NAME_MAX 40
#define SCENE_GLTF_PREFIX_MAX (SCENE_NAME_MAX - SCENE_GLTF_NODE_NAME_MAX - 2)
/* A glTF 2.0 file (.gltf, .glb) as a scene: scene_load_camera's contract. */
bool scene_load_gltf(scene *s, const char *path, int camera);
/* A glTF file's objects appended to s (a scene file's object of mesh kind
 * "gltf"), s->objects grown within *capacity: each node's mesh placed by
 * `model` times the node's transform, named "PREFIX/NODE", casting and
 * receiving as given; the file's cameras and lights are not read. False
 * after a line naming the file and the problem; what was appended before
 * is s's to free. */
bool scene_include_gltf(scene *s, int *capacity, const char *path, const float model[4][4], const char *prefix,
                        bool casts, bool receives);

#endif
