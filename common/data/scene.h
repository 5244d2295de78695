/* scene: scene files (JSON, parsed with cJSON) and the scene they describe.
 *
 * A scene file holds:
 *   "camera":  { "position": [x,y,z], "target": [x,y,z],          (required)
 *                "up": [0,1,0], "fov": 45 (vertical, degrees),
 *                "near": 0.1, "far": 100 }
 *   "ambient": [r,g,b]                                              (0.1 each)
 *   "lights":  [ 1..SCENE_MAX_LIGHTS of
 *                { "type": "point" | "spot" | "directional",       (required)
 *                  "position": [x,y,z]        (point, spot: required)
 *                  "direction": [x,y,z]       (spot, directional: required;
 *                                              the way the light travels)
 *                  "color": [1,1,1], "intensity": 1,
 *                  "inner_angle": 20, "outer_angle": 30  (spot, degrees from
 *                                              the axis: full light inside
 *                                              inner, none outside outer)
 *                  "radius": 0   (> 0: an area light, for soft shadows: a
 *                                 sphere of that radius for point and spot
 *                                 lights; for a directional light, the
 *                                 angular radius in degrees of its disc)
 *                  "range": none (point, spot: > 0, how far the light
 *                                 reaches; see scene_light_range_window) } ]
 *   "objects": [ 1..n of
 *                { "name": "ground"   (required; one object's: names pick
 *                                      objects, as shadowdiff --receiver)
 *                  "mesh": { "kind": "plane", "size": [x,z] }      (required)
 *                          | { "kind": "box", "size": [x,y,z] }
 *                          | { "kind": "sphere", "radius": r, "segments": n }
 *                          | { "kind": "torus", "major_radius": R,
 *                              "minor_radius": r, "segments": n }
 *                          | { "kind": "cylinder", "radius": r, "height": h,
 *                              "segments": n }
 *                          | { "kind": "model", "path": "file.obj" }
 *                            (path relative to the scene file, or absolute)
 *                          | { "kind": "gltf", "path": "file.glb" }
 *                            (the file's objects, as a glTF scene's, named
 *                             "NAME/NODE", placed by this transform times
 *                             their nodes', casting and receiving as this
 *                             says; no "color": theirs are the materials')
 *                          ("segments": 0 or absent is the default, 32,
 *                           else MESH_MIN_SEGMENTS..MESH_MAX_SEGMENTS)
 *                  "translate": [0,0,0], "rotate": [0,0,0] (degrees about
 *                  X, then Y, then Z), "scale": [1,1,1] or a number
 *                  (negative factors mirror; zero is an error),
 *                  "color": [0.8,0.8,0.8] (a model without it takes
 *                           its file's colour where the file gives one:
 *                           the base colour, else the diffuse, of the
 *                           material that covers the most triangles, the
 *                           renderer having one colour an object; see
 *                           mesh_material),
 *                  "casts": true, "receives": true } ]
 * Unknown keys are errors (they are usually typos), as are wrong types,
 * non-finite numbers and out-of-range values.
 *
 * Positions are relative to the scene's origin ("Large worlds", at
 * SCENE_REBASE_RATIO below); scene_load says how it fails.
 *
 * glTF scenes: a file named .gltf or .glb is read as a glTF 2.0 scene
 * (scene_gltf.c): an object per node's mesh, its material's colour and
 * base-colour texture (the scene's textures), the first camera (or the
 * one scene_load_camera names), the punctual lights; a camera or light
 * the file lacks is fitted and said.
 */
#ifndef SCENE_H
#define SCENE_H

#include <stdbool.h>
#include <stdint.h>

#include "mesh.h"
#include "texture.h"

#define SCENE_MAX_LIGHTS 64
/* A set of lights as bits: bit l is light l (render_use_lit, the skips). */
typedef uint64_t scene_light_set;
#define SCENE_LIGHT_BIT(l) ((scene_light_set)1 << (l))
#define SCENE_ALL_LIGHTS(count) ((count) >= 64 ? ~(scene_light_set)0 : SCENE_LIGHT_BIT(count) - 1)
_Static_assert(SCENE_MAX_LIGHTS <= 64, "a light set is 64 bits");
#define SCENE_NAME_MAX 64
/* What every picture shows where no object is: the rasterizer clears to
 * it, the reference paints it. */
#define SCENE_BACKGROUND_R 0.06f
#define SCENE_BACKGROUND_G 0.07f
#define SCENE_BACKGROUND_B 0.09f

typedef enum scene_light_type {
    SCENE_LIGHT_POINT,
    SCENE_LIGHT_SPOT,
    SCENE_LIGHT_DIRECTIONAL,
} scene_light_type;

typedef struct scene_camera {
    float position[3];
    float target[3];
    float up[3];
    float fov_deg;
    float near_plane;
    float far_plane;
    /* Not in the file: set by camera_check_depth (camera.h), false until. */
    bool reversed_depth;
} scene_camera;

typedef struct scene_light {
    scene_light_type type;
    float position[3];  /* point, spot */
    float direction[3]; /* spot, directional: unit, the way light travels */
    float color[3];
    float intensity;
    float inner_angle_deg; /* spot */
    float outer_angle_deg; /* spot */
    float radius;          /* > 0: area light (directional: degrees) */
    float range;           /* point, spot: > 0, it reaches no farther; 0: unlimited */
} scene_light;

typedef enum scene_mesh_kind {
    SCENE_MESH_PLANE,
    SCENE_MESH_BOX,
    SCENE_MESH_SPHERE,
    SCENE_MESH_TORUS,
    SCENE_MESH_CYLINDER,
    SCENE_MESH_MODEL,
} scene_mesh_kind;

typedef struct scene_object {
    char name[SCENE_NAME_MAX];
    scene_mesh_kind mesh_kind;
    mesh mesh; /* in object space */
    /* object -> world, column-major (cglm mat4). Aligned like a mat4, so
     * cglm's SIMD code can use it in place. Its determinant is positive:
     * where the scale mirrors (an odd number of negative factors), the
     * mesh is the mirror image (mesh_reflect_x, winding reversed) and the
     * matrix scales x by -scale[0], so every consumer, in world or object
     * space, sees counter-clockwise faces from outside. */
    _Alignas(16) float model[4][4];
    float color[3];
    /* NULL, or one of the scene's textures (texture.h): its base colour
     * then color times the texture's at the mesh's texture coordinates. */
    const texture *base_color;
    /* A cut-out object (glTF's alphaMode MASK) where alpha_cutoff > 0: it
     * has no surface where its alpha, base_alpha times the texture's, is
     * below the cutoff (scene_object_cut_out); 0: opaque. */
    float alpha_cutoff, base_alpha;
    /* A translucent caster (glTF's alphaMode BLEND): drawn opaque where it
     * is seen, it lets through, per channel, the share
     * scene_object_transmittance gives of the light its shadow rays cross
     * it with. */
    bool translucent;
    /* Seen from its front only (glTF's doubleSided false): the camera's
     * passes and rays see none of its triangles from behind; its shadow
     * is cast from both sides. False: both sides seen, the back lit with
     * the normal reversed (a JSON scene's objects). */
    bool single_sided;
    bool casts;
    bool receives;
} scene_object;

/* Large worlds: every position in the scene (camera, lights, objects'
 * translations) is relative to the scene's origin, subtracted in double
 * from the file's numbers before they are rounded to float. The origin is
 * the camera's eye (as a float) where the eye lies farther from the
 * world's origin than SCENE_REBASE_RATIO times its distance to the
 * target, else the world's origin: a float keeps 24 bits of its own
 * magnitude, so 1e6 from the origin the world's coordinates would be
 * rounded to 0.06 while the eye sees centimetres; relative to the eye
 * they keep the precision of a scene at the origin (the "floating
 * origin" of large-world engines). Every consumer (techniques, maps and
 * their fits, the reference, the dumps' positions) works in this frame,
 * so the origin never needs adding back. It is chosen once, at load: a
 * camera that travels far from where it started loses precision as a
 * camera that far from the world's origin would.
 *
 * Below this many target distances from the world's origin the eye
 * stays in world coordinates: near the eye they then carry at most 2 bits
 * less than relative to the eye, and every scene built by hand (eye
 * within 1.0 target distance of the origin) keeps its own numbers. */
#define SCENE_REBASE_RATIO 4.0

typedef struct scene {
    double origin[3]; /* world coordinates of the point every position here is relative to */
    scene_camera camera;
    float ambient[3];
    scene_light lights[SCENE_MAX_LIGHTS];
    int light_count;
    scene_object *objects;
    int object_count;
    texture *textures; /* what objects' base_color point to */
    int texture_count;
} scene;

/* Reports the first problem as one line "FILE: where: problem"
 * (FILE:LINE for JSON syntax) on stderr and returns false, leaving the
 * scene empty (safe to scene_free). A light (not a sun) inside a caster
 * whose mesh is closed (mesh_edges_build_welded), off its surface
 * (mesh_point_winding), while the eye is outside it, lights nothing the
 * eye sees: said in one line, "FILE: light N lies inside object M (NAME):
 * it lights nothing outside it", and the scene loads. Each object's world
 * bounds are tried first, so the check costs little in a large scene. */
bool scene_load(scene *s, const char *path);
/* scene_load with the file's camera `camera` (a program's --camera N): a
 * glTF file's cameras in its order from 0, a JSON scene's only camera 0;
 * another is an error, "FILE: --camera N: the file has cameras 0 to M"
 * (or "camera 0 only"). */
bool scene_load_camera(scene *s, const char *path, int camera);
/* Whether path names a glTF file (.gltf, .glb): scene_load reads it as
 * a glTF scene, any other as a JSON scene file. */
bool scene_is_gltf(const char *path);
/* The extensions of the files a scene is read from (JSON and glTF),
 * NULL-terminated. */
extern const char *const scene_extensions[];
/* The largest N a program's --camera N takes. */
#define SCENE_MAX_CAMERA_INDEX 65535
void scene_free(scene *s);

/* Whether the scene loaded from `file` has light `light` (a program's
 * --light K); false after "FILE: --light K: the scene has lights 0 to
 * N" (or "light 0 only"). */
bool scene_check_light_flag(const scene *s, const char *file, int light);

/* Whether object o is cut out (see scene_object) at the point of triangle
 * `triangle` whose barycentric weights (of its three corners) are
 * `weight`: its alpha read at the texture's level 0, bilinear, whatever
 * the distance (the cut-out's shape is the texture's own), as
 * shaders/surface.glsl reads it. False for an opaque object. */
bool scene_object_cut_out(const scene_object *o, uint32_t triangle, const float weight[3]);
/* Whether any object of s is cut out. */
bool scene_has_cut_outs(const scene *s);
/* Whether light l reaches (scene_light_reaches_box) the box of a cut-out
 * object of s that casts shadows. */
bool scene_light_reaches_cut_out(const scene *s, const scene_light *l);
/* The share of light, per channel, that translucent object o lets through
 * at the point of `triangle` of barycentric `weight`: (1 - a) + a C, C
 * its colour times its texture's and a base_alpha times the texture's
 * alpha, read at level 0 (the cut-outs' rule), as blending would filter a
 * view through it. */
void scene_object_transmittance(const scene_object *o, uint32_t triangle, const float weight[3], float out[3]);
/* How many objects of s are translucent casters. */
int scene_translucent_casters(const scene *s);

/* --verbose: one line on stderr for each object whose mesh is a model
 * file, "FILE: objects[i] "NAME": model of N triangles, bounds (x, y, z)
 * to (x, y, z), colour (r, g, b) times a WxH texture", the corners of its
 * box in the file's world coordinates (the origin added back), for
 * placing and scaling it, and its base colour (the texture where it has
 * one). */
void scene_print_models(const scene *s, const char *file);

/* A light's reach: what its contribution at `distance` from its position
 * is multiplied by. With a range r, (1 - (d / r)^4)^2 for d < r and 0
 * beyond: the window of Karis, "Real shading in Unreal Engine 4"
 * (SIGGRAPH 2013 course), 1 at the light, smooth, and exactly 0 (with a
 * flat tangent) at the range, so a light can be skipped where it cannot
 * reach. There is no distance attenuation besides (the lighting model has
 * none), so without a range it is 1 everywhere. shaders/lighting.glsl
 * computes the same; the light reaches where this is above 0. */
float scene_light_range_window(const scene_light *l, float distance);
/* The unit an area light's radius is given in, as words follow a number:
 * " degrees" for a sun's angular radius, "" for a point or spot light's
 * (the scene's units). */
const char *scene_light_radius_unit(const scene_light *l);

/* Whether light l can reach any point of the box lo..hi: within its range
 * (a sphere) and inside a spot's outer cone; a directional light, or a
 * point light without a range, reaches everything. Conservative, by the
 * margins SCENE_REACH_*: false means every point of the box gets exactly
 * 0 from the light, in lighting.glsl as here, so skipping the light there
 * changes no pixel. */
bool scene_light_reaches_box(const scene_light *l, const float lo[3], const float hi[3]);
/* The cube around light l's range (grown by SCENE_REACH_RANGE_MARGIN),
 * beyond which it adds exactly 0; false for a light without one (a sun,
 * or no range). */
bool scene_light_range_box(const scene_light *l, float lo[3], float hi[3]);
/* Clips the box lo..hi to the cube around light l's range (grown by
 * SCENE_REACH_RANGE_MARGIN; unchanged for a light without one): what lies
 * beyond gets exactly 0 from it. False when nothing is left. */
bool scene_light_clip_to_range(const scene_light *l, float lo[3], float hi[3]);
/* The reach test's margins: the range grows by this fraction, the cone by
 * this angle, far more than float rounding in the shader's test. */
#define SCENE_REACH_RANGE_MARGIN 1e-3f
#define SCENE_REACH_ANGLE_MARGIN_RAD 1e-3f

/* A light as a homogeneous point: (position, 1), or (towards the light, 0)
 * for a directional light, a point at infinity. */
void scene_light_homogeneous(const scene_light *l, float out[4]);

/* The matrix that takes the object's normals to world space: the inverse
 * transpose of the model matrix's upper 3x3, so that non-uniform scale
 * keeps them perpendicular to the surface. Column-major (cglm mat3). */
void scene_object_normal_matrix(const scene_object *o, float out[3][3]);

/* Corner k (0..2) of triangle t of object o, in world space, in double:
 * what needs a huge triangle's true extent or plane, or its float
 * vertices rounded once (the ray hierarchy's). */
void scene_object_world_corner(const scene_object *o, uint32_t t, int k, double out[3]);
/* World-space bounds of one object's mesh under its model matrix. */
void scene_object_world_bounds(const scene_object *o, float min[3], float max[3]);
/* The box of every receiving object's world bounds; empty (min > max)
 * when none receives. */
void scene_receivers_bounds(const scene *s, float min[3], float max[3]);

#endif
