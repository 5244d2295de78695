/* volume_near: ZP+'s start of the count, for demos/lib/volume_counter.h
 * (Hornus, Hoberock, Lefebvre & Hart, "ZP+: correct Z-pass stencil
 * shadows", I3D 2005: the lecture's "clip the shadow volumes to the view
 * frustum").
 *
 * Without depth clamp the near plane clips the volume faces before it,
 * so z-pass counts the faces between the near plane and the surface; it
 * is right when each pixel starts from the number of volumes holding the
 * point where its eye ray meets the near plane. That number is the count
 * of the caster triangles crossed by the segment from that point to the
 * light (volume_mesh_count_at): every triangle's prism counts one, in a
 * closed mesh only the light-facing ones'. Those triangles are exactly
 * the ones that cover the point when drawn from the light onto the near
 * plane (frustum_plane_projection) and on through the camera, keeping the
 * part between the light and the plane. So each caster whose volume may
 * reach the near-plane rectangle is drawn once more that way, before its
 * sides, each fragment adding one, with no depth test. The projection
 * keeps a triangle's winding when the light lies behind the near plane (on
 * the eye's side) and reverses it when the light lies in front (the eye
 * sees the plane from behind), so culling by the facing the GL sees
 * leaves a closed mesh's light-facing triangles.
 *
 * Exact where the near plane cuts a volume the eye lies outside of (where
 * --mode eye-count fails) with no caps at infinity (z-fail's cost). The
 * count's edges on the plane are each a silhouette edge's image drawn by
 * two routes (a side clipped at the plane, a projected triangle), so a
 * pixel on one may round either way.
 */
#ifndef VOLUME_NEAR_H
#define VOLUME_NEAR_H

#include <stdbool.h>

#include "technique.h"

/* Zero is an unmade one. */
typedef struct volume_near {
    render_program stencil, wide; /* into the stencil; into volume_wide.h's float target */
    int stencil_projection, stencil_plane, wide_projection, wide_plane, wide_color;
} volume_near;

/* False after one line on stderr. */
bool volume_near_init(volume_near *n);
void volume_near_destroy(volume_near *n);
/* Adds caster i's count at the near plane, for the light at `light`
 * (homogeneous, world) whose near plane is `plane` (frustum_near_plane,
 * oriented towards the light), to the stencil, or to the float target
 * while `wide`; `closed`: the caster weighs under the closed rule
 * (volume_mesh_closed_rule). Sets the depth test, culling and stencil ops
 * it needs; the caller sets its own after. */
void volume_near_caster(volume_near *n, const technique_frame *f, int i, const float light[4], const float plane[4],
                        bool closed, bool wide);

#endif
