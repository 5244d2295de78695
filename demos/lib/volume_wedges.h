/* volume_wedges: penumbra wedges, the soft shadow volumes of Assarsson &
 * Akenine-Moller ("A geometry-based soft shadow volume algorithm using
 * graphics hardware", SIGGRAPH 2003) and Assarsson, Dougherty, Mounier &
 * Akenine-Moller ("An optimized soft shadow volume algorithm with
 * real-time performance", Graphics Hardware 2003), for demos/volumes.c's
 * --soft wedges.
 *
 * An area light's visibility starts from its centre's hard shadow, the
 * stencil count n of the ordinary volumes of the casters that take the
 * closed rule: 1 - n (a caster's edges give back what it covers of the
 * disk, so where two casters cover the centre the sum starts from -1), n
 * counted up to VOLUME_WEDGES_DEEPEST. The open rule counts every layer of
 * a mesh (a ray through an open teapot crosses two), which would subtract
 * the disk twice: those casters are counted apart and take off 1 where
 * they cover the centre, and their silhouette edges count a fold
 * (multiplicity 2, both layers) once.
 *
 * Then every silhouette edge, found from the centre in the CPU edge table
 * with its multiplicity (volume_mesh.h, open and non-manifold meshes too),
 * adds the share of the light's disk it uncovers or covers at each pixel
 * (wedge_area.h) wherever that can be non-zero: inside the edge's wedge, a
 * convex polyhedron bounding every point from which the edge crosses the
 * light's ball (a directional light's cone of directions). Its faces: the
 * front and back planes through the edge tangent to the ball, and at each
 * end a side plane through the end, tilted out by the angle the ball spans
 * there, so that the cone from the ball through the end stays inside; the
 * far vertices at infinity (w = 0), or cut off past the box of the frame's
 * visible receivers, on the plane of the box's face that all four far
 * edges leave through soonest (the wedge's part beyond holds no receiver,
 * and seen from the eye it would cover the screen up to the light's
 * vanishing point).
 *
 * Drawn back faces only, depth clamp on, it covers each pixel of it once,
 * wherever the eye is, and a depth test keeps the pixels whose point is
 * not beyond its back face; the fragment reconstructs the pixel's point
 * from a copy of the depth buffer and adds the edge's term, blended, into
 * the visibility target (soft_visibility.h), which the shading clamps to
 * [0, 1]. An edge whose line or end comes within the ball has no such
 * wedge and is left out (counted for the HUD).
 *
 * What it gets wrong, by construction: the silhouette is the centre's, not
 * each point's of the light; and edges of different casters overlapping on
 * the disk each subtract their own share, so that overlapping penumbrae
 * darken twice (the umbra overestimated); an open mesh's layers beyond a
 * fold's two (a spout before a body) are counted by their edges but taken
 * off once at the centre, and light leaks into the umbra there.
 *
 *   volume_wedges_init(&w)                          once
 *   per area light, after its plan:
 *     volume_wedges_light(&w, f, l, &plan, group, edges, &visibility,
 *                         stencil_mask, count)
 *       (its counts from the centre, then every silhouette edge's wedge)
 *     shading_light_soft(...)
 *   volume_wedges_destroy(&w)
 */
#ifndef VOLUME_WEDGES_H
#define VOLUME_WEDGES_H

#include <stdbool.h>
#include <stddef.h>

#include "soft_visibility.h"
#include "technique.h"
#include "volume_mesh.h"
#include "volume_plan.h"

/* One edge's wedge: front and back faces two triangles each, the ends'
 * sides one each, the far face at infinity two. */
#define VOLUME_WEDGES_EDGE_VERTICES 24
/* How far beyond the visible receivers' box a wedge ends, relative to
 * the box's diagonal: rounding's margin. */
#define VOLUME_WEDGES_TRIM_MARGIN 0.01f
/* The ball (or cone) the wedge is built round is the light's grown by
 * this, relative, so that rounding keeps it conservative. */
#define VOLUME_WEDGES_GROWTH 1.01f
/* The least cosine between an edge and its ends' side planes' normals:
 * below, the edge points nearly at the light and has no wedge. */
#define VOLUME_WEDGES_MIN_SIDE 0.001f

/* Each pixel's point is lifted towards the light by its distance from
 * the eye over this before the edges are projected from it: the depth
 * buffer's point lies a rounding off the surface, and a surface's own
 * silhouette edges beside it would project across the whole disk. An
 * int: the shader gets it as a define. */
#define VOLUME_WEDGES_LIFT_RECIPROCAL 1000

/* The deepest centre count the visibility starts from (deeper counts as
 * this). */
#define VOLUME_WEDGES_DEEPEST 3

/* A wedge's vertex: homogeneous position (world), and the edge's ends
 * (world), the first with the edge's multiplicity as w. */
typedef struct volume_wedges_vertex {
    float position[4], a[4], b[4];
} volume_wedges_vertex;

/* One of the passes' programs and its uniforms. */
typedef struct volume_wedges_program {
    unsigned id;
    int view_projection, inverse_view_projection, depth_to_ndc, far_depth, light, size, depth, eye;
} volume_wedges_program;

typedef struct volume_wedges {
    volume_wedges_program wedge;
    unsigned vao, buffer;
    size_t buffer_capacity;
    volume_wedges_vertex *vertices; /* the light at hand's wedges */
    size_t count, capacity;
    volume_mesh edges;            /* the caster at hand's silhouette edges */
    const float *box_lo, *box_hi; /* where the wedges end: past the frame's visible receivers */
    unsigned depth_framebuffer, depth_texture;
    int width, height, depth_format;
    int wedge_count, skipped_count; /* light 0, last frame */
} volume_wedges;

bool volume_wedges_init(volume_wedges *w);
void volume_wedges_destroy(volume_wedges *w);
/* The caller's count of a plan's volumes into the bound target's stencil
 * (cleared in its rectangle first), with the stencil test on after it. */
typedef void (*volume_wedges_count)(const technique_frame *f, const volume_plan *plan);
/* Light l's visibility into v by wedges, from its plan (volume_plan.h):
 * the plan's casters of each rule counted apart (`group`: per object, the
 * caller's scratch) and the centre's share added from each count
 * (stencil_mask: the stencil's bits), then every wedge. False
 * after one line on stderr. */
bool volume_wedges_light(volume_wedges *w, const technique_frame *f, int l, const volume_plan *plan,
                         volume_plan_caster *group, const mesh_edges *edges, soft_visibility *v,
                         unsigned stencil_mask, volume_wedges_count count);
/* The wedge of edge a -> b (world) for the light (homogeneous, world; a
 * direction unit) whose ball has radius `reach` (a directional light's
 * cone: the sine of its angular radius) as triangles, each face towards
 * the outside counter-clockwise, cut off past the box [box_lo, box_hi]
 * (NULL: at infinity): VOLUME_WEDGES_EDGE_VERTICES homogeneous points
 * into out, or 0 when it has none (see top). No GL. */
int volume_wedges_edge(const float a[3], const float b[3], const float light[4], float reach, const float *box_lo,
                       const float *box_hi, float out[VOLUME_WEDGES_EDGE_VERTICES][4]);

#endif
