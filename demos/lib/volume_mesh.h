/* volume_mesh: a caster's shadow volume built on the CPU from its mesh and
 * welded edge table, and the test of whether z-pass is safe for it. Pure
 * geometry (no GL), so it is unit tested without a context
 * (tests/test_volume_mesh.c); demos/volumes.c draws what it builds.
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
 * Parts: the sides alone close the volume for z-pass counting (Heidmann
 * 1991), which counts only faces in front of the visible surface. z-fail
 * (Carmack's reverse) counts the faces behind it, so the volume needs
 * caps: every triangle of non-zero weight near (wound the other way round
 * for weight -1, so that its prism still faces out), and its image at
 * infinity, far (none for a directional light: a point). The silhouette
 * lines are the edges of non-zero multiplicity, each once, for overlays.
 *
 * When z-pass is safe: z-pass counts wrong only where the eye ray starts
 * inside a volume, that is where a point of the camera's near-plane
 * rectangle is in the caster's shadow. Any occluder of a point of that
 * rectangle lies in the convex hull of the light (a point, or a direction
 * swept to infinity) and the rectangle; so a caster whose world box lies
 * wholly outside one face of that hull (four faces through the light and
 * an edge of the rectangle, and the rectangle's own plane) is safe. The
 * test is conservative and has no tolerance: a box touching the hull, or
 * straddling every one of its face planes, is not safe.
 *
 * When a volume misses the view: every point of a caster's volume is a
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
 * Also here, the rest of the technique's CPU geometry: the edge table a
 * volume needs, and the screen rectangle of the receivers, outside which
 * the stencil need not be cleared.
 */
#ifndef VOLUME_MESH_H
#define VOLUME_MESH_H

#include <cglm/cglm.h>
#include <stdbool.h>
#include <stddef.h>

#include "mesh.h"
#include "scene.h"

/* What volume_mesh_build emits: the sides (triangles; all z-pass needs),
 * the caps (triangles; z-fail draws them after the sides), or the
 * silhouette edges (lines). Sides and caps apart, so that a volume kept
 * for a light serves either mode, which the camera picks each frame. */
typedef enum volume_mesh_parts {
    VOLUME_MESH_SIDES,
    VOLUME_MESH_CAPS,
    VOLUME_MESH_SILHOUETTE_LINES,
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

/* The welded edge table of m (mesh_weld, mesh_edges_build) that volumes
 * are built from; false after printing why. */
bool volume_mesh_edges_build(const mesh *m, mesh_edges *e);
/* Replaces v's contents with the volume of mesh m (edge table e) for the
 * light (homogeneous, m's space); false when out of memory (v then holds
 * part of it). */
bool volume_mesh_build(volume_mesh *v, const mesh *m, const mesh_edges *e, const float light[4],
                       volume_mesh_parts parts);
void volume_mesh_free(volume_mesh *v);

/* The light (homogeneous, world) in the space of an object whose model
 * matrix is `model`: the space its volume is built in. */
void volume_mesh_object_light(const mat4 model, const float light[4], float out[4]);

/* The corners of the near-plane rectangle of `view_projection`, in world
 * space, in order round the rectangle (NDC x, y: -1 -1, 1 -1, 1 1, -1 1). */
void volume_mesh_near_rectangle(const mat4 view_projection, vec3 out[4]);
/* True when no point of the near rectangle (volume_mesh_near_rectangle)
 * can be in the shadow of a caster whose world box is [lo, hi], from the
 * light (homogeneous, world space). */
bool volume_mesh_zpass_safe(const float lo[3], const float hi[3], const float light[4], const vec3 rectangle[4]);

/* True when the volume of a caster whose world box is [lo, hi], from the
 * light (homogeneous, world), has no point that survives clipping to
 * `view_projection` with depth clamp on, so that it covers no pixel (see
 * "When a volume misses the view" above). Conservative: false for a
 * volume that touches the view, or nearly (FRUSTUM_CLIP_TOLERANCE). */
bool volume_mesh_misses_view(const float lo[3], const float hi[3], const float light[4],
                             const mat4 view_projection);

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
