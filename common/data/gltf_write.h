/* gltf_write: a glTF 2.0 file built in memory, for generated scenes
 * (build/scenegen): triangle meshes of one material each, materials of a
 * base colour, an optional RGBA8 texture and an alphaMode, nodes, one
 * camera and KHR_lights_punctual lights. Everything lives in the one
 * .gltf file: the buffer and the images (PNG) as base64 data URIs. No GL.
 *
 * Usage: gltf_write_begin, then the parts in any order (each returns its
 * index, -1 when out of memory), then gltf_write_end, which hands back
 * the document (cJSON) and frees the rest. A node takes a mesh or a
 * camera or a light and a placement. Out of memory anywhere makes
 * gltf_write_end return NULL after one line.
 */
#ifndef GLTF_WRITE_H
#define GLTF_WRITE_H

#include <cJSON.h>
#include <stdbool.h>
#include <stdint.h>

typedef struct gltf_write gltf_write;

typedef struct gltf_vertex {
    float position[3];
    float normal[3];
    float uv[2];
} gltf_vertex;

/* glTF's alphaMode. */
typedef enum gltf_alpha { GLTF_OPAQUE, GLTF_MASK, GLTF_BLEND } gltf_alpha;

typedef struct gltf_material {
    const char *name;
    float color[4];   /* baseColorFactor: linear RGB and alpha */
    int texture;      /* gltf_write_texture's index, or -1 */
    gltf_alpha alpha; /* GLTF_OPAQUE by zero */
    float cutoff;     /* MASK: alphaCutoff; 0: glTF's default */
    bool double_sided;
} gltf_material;

/* A node's placement: translation, then a rotation taking -Z (a camera's
 * and a light's view) to `look` where look is not zero. */
typedef struct gltf_place {
    double translation[3];
    double look[3];
} gltf_place;

gltf_write *gltf_write_begin(const char *generator);
/* An RGBA8 image, top row first, as a texture: its texels repeat, or are
 * clamped to the edge. */
int gltf_write_texture(gltf_write *w, int width, int height, const unsigned char *rgba, bool clamp);
int gltf_write_material(gltf_write *w, const gltf_material *m);
/* A mesh of one primitive: triangles of uint16 indices into `vertices`. */
int gltf_write_mesh(gltf_write *w, const gltf_vertex *vertices, int vertex_count, const uint16_t *indices,
                    int index_count, int material);
int gltf_write_mesh_node(gltf_write *w, const char *name, int mesh);
/* A perspective camera at `eye` looking at `target`, y up. */
int gltf_write_camera(gltf_write *w, const char *name, const double eye[3], const double target[3], double yfov,
                      double aspect, double znear, double zfar);
/* A light: "directional", "point" or "spot" (cones in radians), placed by
 * `place`. */
int gltf_write_light(gltf_write *w, const char *name, const char *type, const float color[3], double intensity,
                     double inner_cone, double outer_cone, const gltf_place *place);
cJSON *gltf_write_end(gltf_write *w);

#endif
