/* volume_count_bound: how deep a light's shadow volumes can stack over a
 * pixel, so that demos/volumes.c counts in the 8-bit stencil only where
 * it cannot wrap (volume_wide.h counts the rest). Pure geometry (no GL):
 * tests/test_volume_count_bound.c checks it without a context.
 *
 * The stencil counts with wrapping increments, so a pixel holds its count
 * modulo 256 and reads as lit (0) when the count is a non-zero multiple
 * of 256: exact wherever |count| < 256. A pixel's count is, per caster,
 * the number of its volume's prisms around the surface point (z-fail, or
 * z-pass from an eye outside every volume), each triangle's prism
 * counting +1 or -1 (volume_mesh.h): at most the caster's triangles that
 * weigh non-zero and that the segment from the light to the point
 * crosses. So, per caster and light position, a bound:
 * - a convex closed mesh under the closed rule: 1 (a ray from the light
 *   enters it once), found once per mesh by testing every vertex against
 *   every face plane (up to VOLUME_COUNT_BOUND_CONVEX_MAX_WORK tests);
 * - any other: its weighing triangles binned by the directions from the
 *   light that can cross them (a grid, below), the fullest bin's count:
 *   a ray crosses only triangles of its own bin.
 * A light's bound sums its casters' bounds on the same grid, each over
 * the directions its world box covers, and takes the fullest bin: casters
 * whose shadows never meet are not added together. Forced z-pass counts
 * from an eye that may be inside volumes, the difference of two such
 * counts: twice the bound.
 *
 * The grid of directions (volume_count_grid): for a point light the six
 * faces of a cube round it, so many bins a side, each
 * direction in the face whose axis is largest; a triangle covers, on a
 * face, the rectangle of the images of its part inside the face's
 * pyramid (clipped to it), the whole face where that part reaches the
 * light. An item is a list of triangles (a caster's box: its twelve,
 * whose directions are the box's), covering the union of theirs. For a
 * directional light one plane across its direction, the grid over the
 * rectangle the items cover (an extent pass first). Every
 * rectangle is grown by VOLUME_COUNT_BOUND_MARGIN for rounding. The bound
 * is safe (never below a pixel's count), not tight: it takes every
 * triangle a bin's directions may cross, at any depth.
 */
#ifndef VOLUME_COUNT_BOUND_H
#define VOLUME_COUNT_BOUND_H

#include <stdbool.h>

#include "mesh.h"

/* The largest |count| the 8-bit stencil holds exactly. */
#define VOLUME_COUNT_BOUND_STENCIL_MAX 255
/* Bins on a side of a face of the grid of directions: a mesh's (small
 * detailed parts then share few bins) and a light's, of casters' boxes. */
#define VOLUME_COUNT_BOUND_MESH_BINS 256
#define VOLUME_COUNT_BOUND_LIGHT_BINS 64
/* Faces of the grid: a cube's for a point light; one for a directional. */
#define VOLUME_COUNT_BOUND_FACES 6
/* How much a rectangle of the grid grows each side, relative to its
 * coordinates' size (and at least this in absolute terms). */
#define VOLUME_COUNT_BOUND_MARGIN 1e-4f
/* Vertex-plane tests one mesh's convexity check may take; a mesh that
 * needs more is binned instead. */
#define VOLUME_COUNT_BOUND_CONVEX_MAX_WORK (1 << 22)
/* How far behind every face plane a convex mesh's vertices lie, relative
 * to its bounding box's diagonal. */
#define VOLUME_COUNT_BOUND_CONVEX_TOLERANCE 1e-5f

/* A grid of directions from one light (see top). Zero is an unmade one. */
typedef struct volume_count_grid {
    float light[4]; /* homogeneous, in the items' space */
    bool directional;
    float axis_u[3], axis_v[3]; /* directional: the plane's axes */
    float lo[2], hi[2];         /* directional: the extent of the items */
    int bins;                   /* on a side of a face */
    int *cells;                 /* per face, (bins + 1)^2 differences, then sums */
} volume_count_grid;

/* A grid of `bins` on a side; false after printing why (out of memory). */
bool volume_count_grid_init(volume_count_grid *g, int bins);
void volume_count_grid_free(volume_count_grid *g);
/* A grid for the light (homogeneous): then volume_count_grid_extent for
 * every item (which only a directional light needs), then
 * volume_count_grid_start, volume_count_grid_add for every item, and
 * volume_count_grid_max. */
void volume_count_grid_begin(volume_count_grid *g, const float light[4]);
void volume_count_grid_extent(volume_count_grid *g, const float (*triangles)[3][3], int count);
void volume_count_grid_start(volume_count_grid *g);
/* Adds `weight` to every bin whose directions may meet one of the
 * triangles. */
void volume_count_grid_add(volume_count_grid *g, const float (*triangles)[3][3], int count, int weight);
/* The fullest bin. */
int volume_count_grid_max(const volume_count_grid *g);

/* Whether closed mesh m is convex: every vertex behind or on every
 * triangle's plane (wound outwards). False where it would take more than
 * VOLUME_COUNT_BOUND_CONVEX_MAX_WORK tests. */
bool volume_count_bound_convex(const mesh *m);
/* The most prisms of m's volume for the light (homogeneous, m's space)
 * around any point: 1 for a convex mesh under the closed rule
 * (`closed_rule`, `convex`), else the fullest bin of its weighing
 * triangles, on g. */
int volume_count_bound_mesh(volume_count_grid *g, const mesh *m, bool closed_rule, bool convex, const float light[4]);

#endif
