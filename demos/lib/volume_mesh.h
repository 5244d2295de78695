/* volume_mesh: a caster's shadow volume built on the CPU from its mesh and
 * welded edge table, and the test of whether z-pass is safe for it. Pure
 * geometry (no GL), so it is unit tested without a context
 * (tests/test_volume_mesh.c); demos/volumes.c draws what it builds.
 * volume_rule.c holds the rules that weigh the triangles (the edge table,
 * the facing test, a light inside a mesh), volume_mesh.c the rest.
 *
 * A volume is a list of homogeneous triangles (or lines) in the space of
 * the mesh, the light given in that space as a point (w = 1) or as the
 * direction towards it (w = 0). Points swept away from the light go to
 * infinity (w = 0): their position is the direction p * light.w -
 * light.xyz.
 *
 * Which meshes: any, closed, open or non-manifold. Every triangle is its
 * own occluder (Aldridge & Woods, "Robust, geometry-independent shadow
 * volumes", 2004): its prism from the triangle away from the light counts
 * +1 inside, whichever way it faces, every face of it facing out. Each
 * triangle weighs +1 when it faces the light, -1 when not; where prisms of
 * neighbouring triangles share a side, the sides cancel, so the side of an
 * edge of the welded edge table (mesh_edges_build) is emitted as many
 * times as its multiplicity, the signed sum of its triangles' weights (a
 * use's direction says which way the triangle runs along the edge): 0
 * inside a smooth surface, 1 or 2 on silhouettes and open borders, up to
 * the number of triangles at a non-manifold edge; a negative multiplicity
 * reverses the side. A consistently oriented closed mesh needs only its
 * light-facing prisms (the back-facing ones cover the same space twice
 * over), so there back-facing triangles weigh 0 and silhouettes 1: the
 * textbook volume. A directional light sends an edge's two far points to
 * one: a side is then one triangle, not two.
 *
 * The rest stands beside its declarations: the parts a volume is built
 * of, trimmed to the light's reach, a triangle edge-on to the light, the
 * closed rule and a light inside a mesh, when z-pass is safe, when a
 * volume misses the view, and depth bounds. Also here, the rest of the
 * technique's CPU geometry: the edge table a volume needs, and the screen
 * rectangle of the receivers, outside which the stencil need not be
 * cleared.
 */
#ifndef VOLUME_MESH_H
#define VOLUME_MESH_H

#include <cglm/cglm.h>
#include <stdbool.h>
#include <stddef.h>

#include "mesh.h"
#include "mesh_point.h"
#include "scene.h"

/* Parts: the sides alone close the volume for z-pass counting (Heidmann
 * 1991), which counts only faces in front of the visible surface. z-fail
 * (Carmack's reverse) counts the faces behind it, so the volume needs
 * caps: every triangle of non-zero weight near (wound the other way round
 * for weight -1, so that its prism still faces out), and its image at
 * infinity, far (none for a directional light: a point). The silhouette
 * lines are the edges of non-zero multiplicity, each once, for overlays;
 * the silhouette edges the same pairs of ends, each edge's as its table
 * has them (a -> b, as its uses' directions count), with its signed
 * multiplicity as both ends' w, for penumbra wedges (volume_wedges.h).
 *
 * What volume_mesh_build emits: the sides (triangles; all z-pass needs),
 * the caps (triangles; z-fail draws them after the sides), or the
 * silhouette edges (lines, or pairs with their multiplicity). Sides and caps apart, so that a volume kept
 * for a light serves either mode, which the camera picks each frame. */
typedef enum volume_mesh_parts {
    VOLUME_MESH_SIDES,
    VOLUME_MESH_CAPS,
    VOLUME_MESH_SILHOUETTE_LINES,
    VOLUME_MESH_SILHOUETTE_EDGES,
} volume_mesh_parts;

/* One caster's volume, rebuilt per light and kept for its storage: zero
 * is an empty one. */
typedef struct volume_mesh {
    float (*vertices)[4]; /* homogeneous, in the mesh's space */
    size_t count, capacity;
    bool out_of_memory;
    signed char *weights; /* scratch: per triangle of the mesh at hand */
    size_t weight_capacity;
} volume_mesh;

/* Trimmed to the light's reach: a volume need only be right where the
 * light can light a receiver; beyond, the light adds 0 whatever the count.
 * Given a convex region (the reach: a box) holding every such point, the
 * extrusion stops at a surface beyond it, and far caps there close the
 * volume, z-pass too (sides and far caps together, near caps apart). A
 * point inside the reach then lies in as many prisms as before: each
 * trimmed prism is the part of its infinite one before its far cap, and
 * that cap and the parts cut off lie outside the reach. Point light: every
 * swept vertex at one distance R from it, so that sides and caps still
 * meet (no cracks). A chord between two points at R, their directions at
 * most t apart, comes no nearer than R cos(t / 2), a far cap's triangle no
 * nearer than R sqrt(cos t) (|sum w_i v_i|^2 = sum w_i w_j R^2 cos t_ij);
 * a caster whose bounding sphere (radius s, centre at D) spans t <= 2
 * asin(s / D) from the light, cos t >= 1 - 2 (s / D)^2, so R = r /
 * sqrt(cos t), r the reach's farthest corner, keeps every cap and cut
 * beyond r; and R at least the caster's far side (D + s), so that every
 * vertex travels away. A caster that spans too much (s / D above
 * VOLUME_MESH_TRIM_MAX_SPREAD) is not trimmed. Directional light: every
 * swept vertex on one plane across the travel, beyond the reach and the
 * caster. Both grown by VOLUME_MESH_TRIM_MARGIN for rounding.
 *
 * Where a volume's extrusion stops: zero (or NULL) is at infinity. */
typedef struct volume_mesh_trim {
    bool on;
    /* Point light: from the light; directional: along the travel (minus
     * the light's vector), dot(p, travel) for every swept point. */
    float distance;
} volume_mesh_trim;
/* The largest caster radius over its distance from a point light that is
 * trimmed: its chords then span at most 60 degrees, R <= 1.42 r. */
#define VOLUME_MESH_TRIM_MAX_SPREAD 0.5f
/* How far beyond what it must clear a trimmed extrusion stops, relative. */
#define VOLUME_MESH_TRIM_MARGIN 0.01f

/* A triangle edge-on to the light (the light in its plane, within
 * MESH_POINT_EDGE_ON_RECIPROCAL; mesh_point_facing) weighs 0 in either
 * rule: its prism is flat, no space, and its far cap would be ill-posed (a
 * light in the triangle sends its corners to directions all round, whose
 * cap covers the screen by rounding). The sides still close: an edge's
 * multiplicity sums its triangles' weights, whatever they are.
 *
 * The closed rule counts the light-facing triangles a ray from the light
 * crosses: right from outside (it enters before it leaves), but from a
 * light inside a mesh wound outwards every ray leaves first, so that
 * inside a box nothing faces the light and no volume is cast although
 * the box blocks everything outside (test_volumes'
 * test_light_inside_caster: a light inside a box, a bunny, on a box's
 * face). For such a light, or one on the surface (in a face: its
 * triangles edge-on, the others facing away, also nothing cast), the
 * mesh is weighed as an open one (volume_mesh_closed_rule): every prism,
 * each counting +1, sums right from anywhere. Inside or on it:
 * mesh_point_inside. */
/* Whether m's volume for the light takes the closed rule (back-facing
 * triangles weigh 0): a closed edge table e and the light outside. */
bool volume_mesh_closed_rule(const mesh *m, const mesh_edges *e, const float light[4]);

/* The count m's volume for the light (homogeneous, m's space) holds at
 * point p (m's space), under the closed rule or not
 * (volume_mesh_closed_rule): every triangle's prism counts one inside,
 * the back-facing ones' none under the closed rule, so it is the number
 * of such triangles the segment from p to a point light crosses (to a
 * directional one, the ray from p towards it), edge-on ones none. What
 * z-pass must start from where the eye is inside volumes. The point is
 * first nudged by VOLUME_MESH_COUNT_NUDGE of the mesh's size along a skew
 * direction, so that a segment through an edge two triangles share (a
 * box face's diagonal) crosses one of them, not both or neither. */
#define VOLUME_MESH_COUNT_NUDGE 1e-4f
int volume_mesh_count_at(const mesh *m, bool closed, const float light[4], const float p[3]);

/* Replaces v's contents with the volume of mesh m (edge table e) for the
 * light (homogeneous, m's space), trimmed by `trim` (NULL: to infinity);
 * false when out of memory (v then holds part of it). */
bool volume_mesh_build(volume_mesh *v, const mesh *m, const mesh_edges *e, const float light[4],
                       const volume_mesh_trim *trim, volume_mesh_parts parts);
/* The trim of mesh m's volume, the object's model matrix `model`, for the
 * light (homogeneous, m's space) whose receivers in reach lie in the world
 * box [reach_lo, reach_hi]; off where it cannot be trimmed. */
void volume_mesh_trim_for(const mat4 model, const float light[4], const mesh *m, const float reach_lo[3],
                          const float reach_hi[3], volume_mesh_trim *out);
void volume_mesh_free(volume_mesh *v);

/* The corners of the near-plane rectangle of `view_projection`, in world
 * space, in order round the rectangle (NDC x, y: -1 -1, 1 -1, 1 1, -1 1). */
void volume_mesh_near_rectangle(const mat4 view_projection, vec3 out[4]);
/* When z-pass is safe: z-pass counts wrong only where the eye ray starts
 * inside a volume, that is where a point of the camera's near-plane
 * rectangle is in the caster's shadow. Any occluder of a point of that
 * rectangle lies in the convex hull of the light (a point, or a direction
 * swept to infinity) and the rectangle; so a caster whose world box lies
 * wholly outside one face of that hull (four faces through the light and
 * an edge of the rectangle, and the rectangle's own plane) is safe. The
 * test is conservative and has no tolerance: a box touching the hull, or
 * straddling every one of its face planes, is not safe.
 *
 * True when no point of the near rectangle (volume_mesh_near_rectangle)
 * can be in the shadow of a caster whose world box is [lo, hi], from the
 * light (homogeneous, world space). */
bool volume_mesh_zpass_safe(const float lo[3], const float hi[3], const float light[4], const vec3 rectangle[4]);

/* When a volume misses the view: every point of a caster's volume is a
 * combination with non-negative weights of the homogeneous corners of its
 * world box (c, 1) and of those corners swept away from the light, (c -
 * light.xyz, 0) for a point light, (-light.xyz, 0), the direction of
 * travel, for a directional one: a vertex on the mesh is a convex
 * combination of the corners, its image at infinity the same combination
 * of their images, and a triangle's points combine its vertices with
 * non-negative weights, which is also how the GL clips it. A clip plane
 * is a linear function of those homogeneous points (a row combination of
 * the view-projection matrix), so when it is negative at each of the 16
 * it is negative on the whole volume, and no fragment of it is drawn. The
 * planes: x and y against w (w + x, w - x, w + y, w - y), and w itself
 * (the eye's plane: a point with w < 0 fails one of the four). Not the
 * near and far planes: with depth clamp (which the volumes are drawn
 * with) they clip nothing, and faces beyond them still count.
 *
 * True when the volume of a caster whose world box is [lo, hi], from the
 * light (homogeneous, world), has no point that survives clipping to
 * `view_projection` with depth clamp on, so that it covers no pixel (see
 * "When a volume misses the view" above). Conservative: false for a
 * volume that touches the view, or nearly (FRUSTUM_CLIP_TOLERANCE). */
bool volume_mesh_misses_view(const float lo[3], const float hi[3], const float light[4], const mat4 view_projection);

/* Depth bounds (GL_EXT_depth_bounds_test): a fragment is dropped where
 * the depth already stored at its pixel lies outside [lo, hi], whatever
 * its own depth, so each pixel takes all of its stencil updates or none.
 * Every pixel a light can light shows a visible receiver's point within
 * its reach: in the hull of the receivers' points (technique_frame's
 * receivers) and in the box round its range. Window depth is monotone in
 * the eye's distance along the view axis, which is linear, so over a
 * convex set it lies between its corners' depths: [lo, hi] is the
 * intersection of the two sets' ranges, grown by
 * VOLUME_MESH_DEPTH_BOUNDS_MARGIN for rounding; a pixel outside it keeps
 * the cleared count and is lit, where the light adds 0.
 *
 * Window depth (glDepthRange 0..1) the depth bounds grow by each side:
 * far more than a 24-bit depth buffer's step or float rounding. */
#define VOLUME_MESH_DEPTH_BOUNDS_MARGIN (1.0f / 65536)
/* The window-depth bounds (see "Depth bounds") of the points (world, in
 * front of the eye) within the box [reach_lo, reach_hi] (world; NULL: no
 * box), into out[0] <= out[1]; false when there is no point, nothing to
 * count for. */
bool volume_mesh_depth_bounds(const mat4 view_projection, const float (*points)[3], int count,
                              const float reach_lo[3], const float reach_hi[3], float out[2]);

/* The NDC rectangle (x, y) of the world boxes of the scene's receivers: no
 * light reaches pixels outside it, so the stencil need not be cleared
 * there. Not clamped to [-1, 1]; empty (lo > hi) when nothing receives.
 * False when a box reaches behind the eye (no rectangle bounds it). */
bool volume_mesh_receivers_ndc(const scene *s, const mat4 view_projection, float lo[2], float hi[2]);
/* That rectangle in pixels of a width x height viewport, rounded out and
 * clipped to it: x, y, width, height for glScissor. The whole viewport
 * when a box reaches behind the eye. */
void volume_mesh_receivers_scissor(const scene *s, const mat4 view_projection, int width, int height, int out[4]);

#endif
