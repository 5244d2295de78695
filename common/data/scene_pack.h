/* scene_pack: a glTF scene as scene_load_gltf made it, in a file that
 * needs no importer: what the web build reads where native programs read
 * the glTF file through assimp (the page cannot link it), written by
 * build/bake.
 *
 * The file, little-endian: SCENE_PACK_MAGIC (8 bytes), uint32 object,
 * texture and light counts, double origin[3], the camera (float
 * position[3], target[3], up[3], fov_deg, near_plane, far_plane), float
 * ambient[3]; each light: uint32 type, float position[3], direction[3],
 * color[3], intensity, inner_angle_deg, outer_angle_deg, radius, range;
 * each texture: uint32 wrap[2] and level count, and each level's uint32
 * width and height and its RGBA bytes (texture.h's levels, the mip chain
 * as made); each object: its name (SCENE_NAME_MAX bytes), uint32
 * mesh_kind, float model[16] (column-major), color[3], int32 base-colour
 * texture (its index among the textures, -1 for none), float
 * alpha_cutoff, base_alpha, uint32 translucent, single_sided, casts and
 * receives (0 or 1), then its mesh as a mesh pack (mesh_pack.h, without
 * colour). Numbers are as the scene holds them, so the scene read back is
 * the one written, bit for bit; the camera's reversed_depth is not kept
 * (camera_check_depth sets it after any load).
 *
 * A new module rather than mesh_pack's: a scene pack holds a scene
 * (scene.h), of which a mesh knows nothing, and each of its meshes is a
 * mesh pack.
 *
 * Errors are one line "PATH: problem" on stderr, the scene left empty
 * (safe to scene_free). */
#ifndef SCENE_PACK_H
#define SCENE_PACK_H

#include <stdbool.h>

#include "scene.h"

#define SCENE_PACK_MAGIC "SHSCENE"

bool scene_pack_write(const char *path, const scene *s);
/* The scene as written; a file that is not one, is truncated or longer,
 * or whose counts, flags or texture indices are out of range is an
 * error. */
bool scene_pack_read(scene *s, const char *path);
/* The pack's objects appended to s as scene_include_gltf appends a glTF
 * file's (scene_internal.h): each named "PREFIX/NAME", placed by `model`
 * times its own matrix (the pack's origin added back), mirrored into its
 * mesh where that product mirrors, seen from both sides, casting and
 * receiving as given, with its texture; the pack's lights and camera
 * are not read. To the placement's rounding the objects the glTF file
 * itself gives. False after a line; what was appended before is s's to
 * free. */
bool scene_pack_include(scene *s, int *capacity, const char *path, const float model[4][4], const char *prefix,
                        bool casts, bool receives);

#endif
