/* volume_silhouette: the sides of shadow volumes found on the GPU
 * (--silhouette gpu), by a geometry shader over GL_TRIANGLES_ADJACENCY
 * (shaders/volume_silhouette.geom), for any mesh: closed, open or
 * non-manifold, with the decisions of the CPU path (demos/lib/volume_mesh.h,
 * whose "Which meshes" is the rule both follow). The adjacency it reads is
 * volume_silhouette_adjacency's.
 *
 * The shader, per triangle, edge by edge (a -> b, as the triangle runs):
 * - closed meshes (VOLUME_SILHOUETTE_CLOSED): only light-facing triangles
 *   emit (the back-facing ones weigh 0), the side of each edge whose
 *   neighbour faces away: silhouettes once, the textbook volume;
 * - open meshes (VOLUME_SILHOUETTE_OPEN): every triangle emits, +1 when
 *   it faces the light, -1 when not (its sides reversed): the side of
 *   each border edge, and of each other edge where the triangle across
 *   lies on the same side as this one of the plane through the edge and
 *   the light (seen from the light the surface folds there: a
 *   silhouette). The shader tests it as "the facing of (a, across, b)
 *   differs from mine": (a, across, b) is the neighbour's own winding
 *   when it runs b -> a, the reverse when it runs a -> b, and the fold is
 *   the same either way. Summed over an edge's triangles (a reversed side
 *   counting -1), the sides are the CPU's multiplicity: 2 w on a
 *   silhouette between two triangles (one side from each), and on a
 *   border each triangle's own (at a non-manifold edge, pairs of opposite
 *   sides drawn over the same quad cancel in the stencil).
 * A triangle edge-on to the light weighs 0 in both (no prism; its
 * neighbours' sides close the volume), and a closed mesh takes the open
 * rule for a light inside it or on it (volume_mesh_closed_rule, decided
 * on the CPU per caster and light: u_topology), as on the CPU; the
 * shader's test is then "the weight of (a, across, b) differs from mine",
 * weights -1, 0 and 1 as mesh_point_facing and the rule give them.
 * The shader emits the sides alone: z-fail's caps come from the CPU
 * (volume_silhouette_draw says why).
 */
#ifndef VOLUME_SILHOUETTE_H
#define VOLUME_SILHOUETTE_H

#include <stdbool.h>
#include <stdint.h>

#include "mesh.h"
#include "render.h"

/* Which rule the shader follows for a mesh (u_topology; see the top). */
enum { VOLUME_SILHOUETTE_CLOSED, VOLUME_SILHOUETTE_OPEN };

/* GL_TRIANGLES_ADJACENCY indices per triangle: each corner, then the
 * vertex across. */
#define VOLUME_SILHOUETTE_INDICES_PER_TRIANGLE 6

/* Adjacency: six indices per triangle, each corner and then the vertex
 * across the edge it starts (the third vertex of the triangle on the
 * other side). An edge of the welded edge table with exactly two uses has
 * that one triangle across, whichever way it runs, where the two hold the
 * edge's ends at the same positions (mesh_edge_uses_meet: the weld's
 * tolerance may pair positions a few ulps apart, and the neighbour is
 * judged from this triangle's ends). A border has none across (an open
 * edge: one use; two uses at other positions, which makes the mesh open,
 * mesh_edges_build_welded) or no single one (a non-manifold edge: three
 * or more); its index across is then the triangle's own third
 * vertex, the mark the shader reads (same index, so the same position, bit
 * for bit). A closed mesh has no border: its indices are those of
 * mesh_adjacency_indices.
 *
 * The adjacency indices of mesh m, whose welded edge table is e, into out
 * (VOLUME_SILHOUETTE_INDICES_PER_TRIANGLE per triangle), borders marked
 * as above. */
void volume_silhouette_adjacency(const mesh *m, const mesh_edges *e, uint32_t *out);

/* One caster on the GPU: its vertex buffer with its adjacency indices.
 * Zero is none. */
typedef struct volume_silhouette_mesh {
    unsigned vao, index_buffer;
    int index_count;
    int topology; /* VOLUME_SILHOUETTE_CLOSED or _OPEN */
} volume_silhouette_mesh;

/* The program, for every caster. Zero is unloaded. */
typedef struct volume_silhouette {
    render_program program;
    int light, topology, color; /* uniform locations */
} volume_silhouette;

/* The define that makes volume.frag count into a float target
 * (demos/lib/volume_wide.h). */
#define VOLUME_SILHOUETTE_WIDE_DEFINE "VOLUME_WIDE_COUNT"
/* False after printing why; `wide`: the program that counts into a
 * float target (volume.frag's VOLUME_WIDE_COUNT), else into the stencil. */
bool volume_silhouette_load(volume_silhouette *s, bool wide);
void volume_silhouette_destroy(volume_silhouette *s);
/* Mesh m (edge table e) over its vertex buffer `vertex_buffer` (of
 * mesh_vertex, as render_scene uploads it); false after printing why. */
bool volume_silhouette_mesh_init(volume_silhouette_mesh *out, const mesh *m, const mesh_edges *e,
                                 unsigned vertex_buffer);
void volume_silhouette_mesh_free(volume_silhouette_mesh *m);
/* The facing tests are the CPU's expression in object space; the
 * neighbour's is taken from this triangle's corners, so a triangle edge-on
 * to the light could be judged otherwise than by itself (on the tests'
 * scenes none is: the same expressions in C give every edge the CPU's
 * multiplicity). What differs is rasterization: a side from the shader
 * is the CPU's quad in other triangles (split along the other diagonal,
 * from other leading vertices, emitted by a geometry shader, whose
 * triangles llvmpipe rasterizes at slightly other depths, even split as
 * the CPU splits), so where a side starts at its surface's depth (a
 * caster's own terminator) a pixel may round the other way: a few pixels'
 * visibility differs from --silhouette cpu's, within the bound of
 * test_volumes' test_gpu_silhouettes_of_open_meshes_match_cpu.
 *
 * The shader emits the sides alone: z-fail's caps come from the CPU (kept
 * like its sides, demos/lib/volume_draw.h) through volume.vert, the vertex
 * path of the depth pre-pass (lit.vert's invariant expression, the same
 * uniforms), since caps must lie at exactly the depth of their surface
 * and llvmpipe rasterizes a geometry shader's triangles at slightly other
 * depths than a vertex shader's (caps from the shader speckle their own
 * surfaces with false shadow; from the vertex path they are as exact as
 * the CPU's). The mesh's own vertices of a side come placed by the
 * vertex stage too (volume_adjacency.vert), for the same reason.
 *
 * The sides of m's volume from the light (homogeneous, in m's space),
 * the object's model matrix `model` (16 floats, column-major), seen from
 * `view`; a closed mesh by the open rule unless `closed_rule` (false for
 * a light inside it or on it: volume_mesh_closed_rule). */
void volume_silhouette_draw(const volume_silhouette *s, const volume_silhouette_mesh *m, const camera_view *view,
                            const float *model, const float light[4], bool closed_rule);

#endif
