/* mesh: one triangle-mesh layout for every technique.
 *
 * A mesh is an indexed triangle list of mesh_vertex (position, shading
 * normal, texture coordinates), with its axis-aligned bounds. Meshes come from procedural
 * generators (mesh_make_*) or from model files through assimp
 * (mesh_load_file). Every constructor ends in mesh_sanitize, which removes
 * triangles that are degenerate (zero area once positions are welded) or
 * that touch a non-finite vertex, warning once with the mesh's name, so
 * techniques never see them.
 *
 * mesh_weld builds the welded-position view of the topology that silhouette
 * and edge-based techniques need: vertices that share a position (within a
 * tolerance relative to the mesh's size) get one id, so UV or normal seams
 * do not split edges. mesh_topology_count_edges classifies the welded edges
 * (boundary: used by one triangle, manifold: two, non-manifold: three+);
 * mesh_edges_build lists them with the triangles that use each.
 *
 * Errors: functions returning bool print one line "NAME: problem" to stderr
 * (or hand it to the handler set with mesh_set_error_handler) and return
 * false; the mesh is left empty (safe to mesh_free).
 */
#ifndef MESH_H
#define MESH_H

#include <stdbool.h>
#include <stdint.h>

typedef struct mesh_vertex {
    float position[3];
    float normal[3];
    float uv[2]; /* texture coordinates (texture.h's convention); 0 where the mesh has none */
} mesh_vertex;

typedef struct mesh {
    mesh_vertex *vertices;
    uint32_t *indices; /* 3 per triangle */
    uint32_t vertex_count;
    uint32_t index_count;
    float bounds_min[3];
    float bounds_max[3];
} mesh;

typedef struct mesh_topology {
    uint32_t *position_of_vertex; /* vertex index -> welded position id */
    float (*positions)[3];        /* welded positions */
    uint32_t position_count;
} mesh_topology;

typedef struct mesh_edge_counts {
    uint32_t boundary;     /* edges used by exactly one triangle */
    uint32_t manifold;     /* edges used by exactly two triangles */
    uint32_t non_manifold; /* edges used by three or more */
} mesh_edge_counts;

#define MESH_MIN_SEGMENTS 3
#define MESH_MAX_SEGMENTS 1024

/* Procedural meshes, centred on the origin, Y up. segments 0 means the
 * default (32); otherwise MESH_MIN_SEGMENTS..MESH_MAX_SEGMENTS (a negative
 * count is an error, as any other outside). All are closed 2-manifolds
 * once welded, except the plane. The torus needs minor < major radius. */
bool mesh_make_plane(mesh *m, float size_x, float size_z);
bool mesh_make_box(mesh *m, float size_x, float size_y, float size_z);
bool mesh_make_sphere(mesh *m, float radius, int segments);
bool mesh_make_torus(mesh *m, float major_radius, float minor_radius, int segments);
bool mesh_make_cylinder(mesh *m, float radius, float height, int segments);

/* What a model file may hold once its nodes' transforms are applied
 * (instances counted each time): far above any model this suite renders
 * in real time (the largest asset has 3674 triangles), far below what
 * would exhaust memory (the limit takes 600 MB of indices, at most 3.6 GB
 * of vertices). A triangle soup has three vertices per triangle. */
#define MESH_MAX_TRIANGLES 50000000
#define MESH_MAX_VERTICES (3 * MESH_MAX_TRIANGLES)

/* What a model file's materials say of its colour (mesh_load_file). A
 * material's colour is its base colour (AI_MATKEY_BASE_COLOR: glTF's
 * baseColorFactor), else its diffuse one (an OBJ's Kd); only a material
 * the file names counts: a file without materials (OFF, PLY, an OBJ
 * without its .mtl, a glTF primitive without one) gets assimp's stand-in,
 * unnamed or AI_DEFAULT_MATERIAL_NAME, whose colour is assimp's, not the
 * file's. A mesh has one colour, so of several the one that covers the
 * most triangles is the model's (materials of one colour count together;
 * a tie goes to the first material). A colour with a negative or
 * non-finite channel does not count. */
typedef struct mesh_material {
    bool has_color; /* false: no material of the file gives one */
    float color[3]; /* linear RGB, as the file gives it */
    /* The file's materials that name a base-colour or diffuse texture,
     * which a model does not read (a glTF scene does: scene.h). */
    unsigned textured;
} mesh_material;

/* Loads every triangle of a model file (all its meshes, node transforms
 * applied, the winding reversed under a mirroring one: counter-clockwise
 * from outside) through assimp; generates smooth normals where the file has
 * none. Its colour goes into *material (which may be NULL; see
 * mesh_material).
 * Files with no triangles, unreadable or malformed files are an error, and
 * so are files over the limits above (checked before they are welded,
 * smoothed or copied) and OFF or PLY files whose header claims more
 * vertices, faces or elements than the file's size can hold (checked before
 * assimp reads them: it allocates what the header claims). */
bool mesh_load_file(mesh *m, const char *path, mesh_material *material);

/* Removes degenerate and non-finite triangles (warning "name: removed ..."),
 * recomputes bounds; an error if no triangle is left. */
bool mesh_sanitize(mesh *m, const char *name);
/* What mesh_sanitize removed. */
typedef struct mesh_removed {
    uint32_t degenerate, non_finite;
} mesh_removed;
/* mesh_sanitize without its warning: what it removed is added to
 * *removed, for a caller that sanitizes many meshes to say once. */
bool mesh_sanitize_quietly(mesh *m, const char *name, mesh_removed *removed);

/* The mesh's mirror image in its x = 0 plane: every position's and
 * normal's x negated and every triangle's winding reversed, so the faces
 * that were counter-clockwise seen from outside still are (a reflection
 * alone would turn them clockwise, inside out), and the bounds follow.
 * Exact: negation rounds nothing. scene_load takes a mirroring scale into
 * the mesh with it (see scene.h). */
void mesh_reflect_x(mesh *m);

void mesh_free(mesh *m);

/* A caller that puts errors in its own context installs a handler; it gets
 * NAME and problem separately, without a newline. NULL restores the default
 * (stderr). scene_load installs its own while it builds each object (to name
 * the scene file and object), then restores the default. Warnings always go
 * to stderr. */
typedef void (*mesh_error_handler)(const char *name, const char *problem, void *user_data);
void mesh_set_error_handler(mesh_error_handler handler, void *user_data);

bool mesh_weld(const mesh *m, mesh_topology *t);
mesh_edge_counts mesh_topology_count_edges(const mesh *m, const mesh_topology *t);
void mesh_topology_free(mesh_topology *t);

/* The edge table of the welded topology, for silhouettes: every welded edge
 * once, with every triangle corner that starts it. A use's direction is +1
 * where the triangle runs along the edge from a to b, -1 from b to a; a
 * consistently oriented closed 2-manifold (`closed`) has exactly two uses
 * per edge, one each way. a and b are the vertex indices of the first use,
 * so drawing with them repeats the mesh's own positions bit for bit. */
typedef struct mesh_edge_use {
    uint32_t corner; /* index into m->indices; the triangle is corner / 3 */
    int direction;
} mesh_edge_use;

typedef struct mesh_edge {
    uint32_t a, b;                 /* vertex indices */
    uint32_t first_use, use_count; /* into uses */
} mesh_edge;

typedef struct mesh_edges {
    mesh_edge *edges;
    mesh_edge_use *uses; /* 3 per triangle, grouped by edge */
    uint32_t edge_count;
    bool closed;
} mesh_edges;

bool mesh_edges_build(const mesh *m, const mesh_topology *t, mesh_edges *e);
void mesh_edges_free(mesh_edges *e);
/* The welded edge table of m (mesh_weld, mesh_edges_build) that shadow
 * volumes are built from and the shadow maps ask closedness of; false
 * after printing why. The weld pairs vertices within a tolerance, so two
 * triangles may meet at an edge whose ends they hold at positions a few
 * ulps apart; a mesh counts as closed here only where every edge's two
 * triangles meet at one position, bit for bit (mesh_edge_uses_meet),
 * since the volumes' geometry shader judges a neighbour from the
 * triangle's own ends of the edge and its neighbour's third vertex: from
 * other positions a needle or sliver neighbour's facing comes out at
 * random, and an unmatched side draws streaks of false shadow
 * (tests/data/vol_welded_sliver.json, test_volumes' test_welded_sliver;
 * the CPU path is exact there either way). Such a mesh takes the volumes'
 * open rule, which is exact for any mesh. */
bool mesh_edges_build_welded(const mesh *m, mesh_edges *e);
/* Whether edge uses u and v (of one edge of m's table) run between the
 * same two positions, bit for bit. */
bool mesh_edge_uses_meet(const mesh *m, const mesh_edge_use *u, const mesh_edge_use *v);

/* Index buffer for GL_TRIANGLES_ADJACENCY (6 per triangle: each corner, then
 * the vertex across the edge it starts). Only a closed mesh has one: false
 * otherwise, out untouched. */
bool mesh_adjacency_indices(const mesh *m, const mesh_edges *e, uint32_t *out);

#endif
