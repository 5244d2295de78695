/* bvh: a bounding volume hierarchy over the triangles of a scene's
 * casters, in world space, for shadow rays that only ask whether anything
 * lies between a point and a light. No GL: the GPU reads the same arrays
 * from textures (shaders/bvh_trace.glsl), the tests from here.
 *
 * Built once per scene on the CPU, top down, each node split where the
 * surface area heuristic, evaluated at BVH_BINS bins of the triangles'
 * centroids along each axis, costs least (Wald, "On fast Construction of
 * SAH-based Bounding Volume Hierarchies", IEEE RT 2007); a node of at most
 * BVH_LEAF_TRIANGLES triangles is a leaf.
 * Below BVH_SAH_DEPTH levels a node is split at the median of its
 * centroids along its widest axis instead, which halves it: no path is
 * longer than BVH_MAX_DEPTH nodes, the GPU's traversal stack.
 *
 * Written here rather than taken from Embree (which the reference traces
 * with): the web build has no Embree, and its hierarchy is not ours to
 * read, while the page runs the same technique from the same arrays.
 *
 * Layout, depth first, node 0 the root: a node is two vec4, (lo, a) and
 * (hi, b); an inner node's first child follows it and a is its second
 * child's index, b 0; a leaf has a its first triangle and b (> 0) its
 * triangle count. A triangle is three vec4, its vertices; the first
 * vertex's w is 0, or for a triangle of a cut-out or translucent object
 * (scene.h) 1 + its index in records: a ray passes it where a cut-out
 * has no surface (scene_object_cut_out at the hit's barycentric
 * weights), and through a translucent one filtered by its transmittance
 * there (scene_object_transmittance), as the reference's rays; the
 * others' w are unused. Indices are stored as floats, exact below BVH_MAX_INDEX.
 *
 * A ray meets a triangle by Woop, Benthin and Wald's watertight test
 * ("Watertight Ray/Triangle Intersection", JCGT 2(1), 2013): no ray slips
 * between two triangles that share an edge, which a shadow ray along a
 * silhouette would otherwise do; and a box by the slab test with its far
 * end widened by Ize's bound ("Robust BVH Ray Traversal", JCGT 2(2),
 * 2013), so that rounding never culls a box the ray meets. */
#ifndef BVH_H
#define BVH_H

#include <stdbool.h>

#include "scene.h"

#define BVH_BINS 16
#define BVH_LEAF_TRIANGLES 4
#define BVH_SAH_DEPTH 40
#define BVH_MAX_DEPTH 64
/* A ray leaves its surface: a triangle whose plane passes within this
 * many float ulps of the largest coordinate of the ray's origin is that
 * surface (its own triangle, a neighbour its rounding tilts), never an
 * occluder, as the reference's RAYTRACE_SURFACE_ULPS; wider, for the
 * rasterizer's interpolated positions. */
#define BVH_SURFACE_ULPS 64
/* Floats hold integers exactly up to 2^24. */
#define BVH_MAX_INDEX (1 << 24)

/* A triangle whose surface the rays read (a cut-out or translucent
 * object's): the object, the triangle's index in its mesh. */
typedef struct bvh_record {
    const scene_object *object;
    uint32_t triangle;
} bvh_record;

typedef struct bvh {
    float (*nodes)[2][4];     /* node_count */
    float (*triangles)[3][4]; /* triangle_count, in leaf order */
    bvh_record *records;      /* record_count, in leaf order */
    int node_count, triangle_count, record_count;
    int depth; /* the longest path, in nodes */
} bvh;

/* The hierarchy of every triangle of the objects of `s` that cast; false
 * after printing one line naming `who` and the problem (out of memory,
 * more triangles than BVH_MAX_INDEX), with nothing to free. A scene
 * without casters has an empty one (no nodes): every ray gets through. */
bool bvh_build(const scene *s, const char *who, bvh *out);
void bvh_free(bvh *b);

/* The share of each channel of light that gets through the segment
 * origin + t dir, 0 < t < t_max (dir need not be unit; t_max INFINITY
 * for a directional light), past every triangle other than the surface
 * the ray leaves (BVH_SURFACE_ULPS): 0 where an opaque one meets it, else
 * the product of the transmittances of the translucent ones it crosses
 * (1 where none). The same tests, in the same order of operations, as the
 * shader's. */
void bvh_transmittance(const bvh *b, const float origin[3], const float dir[3], float t_max, float out[3]);
/* Whether no light gets through the segment (bvh_transmittance 0). */
bool bvh_occluded(const bvh *b, const float origin[3], const float dir[3], float t_max);
/* Whether no caster can meet the cone from origin along the segment
 * origin + t dir, 0 < t < t_max, whose radius grows linearly from 0 to
 * end_radius at t_max (every ray from a point to an area light's disk
 * facing it lies in it): no leaf's box, grown by the cone's radius where
 * the segment crosses it, meets the segment. Conservative: false where a
 * box is merely near. The same tests as the shader's. */
bool bvh_cone_clear(const bvh *b, const float origin[3], const float dir[3], float t_max, float end_radius);
/* How far from the world's origin the casters' box reaches: its farthest
 * corner's distance (0 without casters). A ray to a sun from p meets
 * every caster it can within |p| + this. */
float bvh_reach(const bvh *b);

#endif
