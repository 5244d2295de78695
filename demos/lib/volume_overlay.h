/* volume_overlay: the shadow volumes' lecture overlays (--overlay), drawn
 * over the finished picture for light 0:
 * - volumes: every caster's CPU volume sides, faint faces (many overlap)
 *   with clearer edges;
 * - silhouettes: its silhouette edges (VOLUME_MESH_SILHOUETTE_LINES) in
 *   opaque red, over everything;
 * - counts: the stencil count at each pixel as colour, 1, 2, 3 and "this
 *   many or more" by a ramp from blue to red, translucent so the picture
 *   shows through, with a legend of the ramp; the caller counts the
 *   light into the stencil first; or, where the stencil could wrap
 *   (volume_wide.h), from the wide count, with a class for 256 and more
 *   and the largest count in the legend.
 * All with volume_draw's CPU program and stream, at the volumes' reach
 * (volume_draw_reach).
 */
#ifndef VOLUME_OVERLAY_H
#define VOLUME_OVERLAY_H

#include <stdbool.h>

#include "volume_counter.h"
#include "volume_draw.h"
#include "volume_wide.h"

/* What --overlay draws. */
typedef enum volume_overlay_kind {
    VOLUME_OVERLAY_NONE,
    VOLUME_OVERLAY_VOLUMES,
    VOLUME_OVERLAY_SILHOUETTES,
    VOLUME_OVERLAY_COUNTS
} volume_overlay_kind;

/* The counts' ramp: counts 1 .. VOLUME_OVERLAY_COUNT_STEPS - 1 each their
 * colour, the last step for that many and more; the overlay draws it
 * translucent, its legend (legend.h, the bottom-right corner) opaque. */
#define VOLUME_OVERLAY_COUNT_STEPS 4
extern const float volume_overlay_count_ramp[VOLUME_OVERLAY_COUNT_STEPS][3];

/* Overlay `kind` of light 0 over the finished picture, of every caster
 * under c's mode (no skip), its CPU volumes trimmed where `trim`
 * (volume_draw_reach); casters: per object, room for the plan. The counts
 * recount light 0 (the stencil holds the last light's). */
void volume_overlay_draw(volume_overlay_kind kind, const technique_frame *f, volume_counter *c,
                         volume_plan_caster *casters, bool trim);
/* Every caster's volume sides (`faces`) or its silhouette lines, for the
 * light (homogeneous, world). */
void volume_overlay_shapes(volume_draw *d, const technique_frame *f, const float light[4], bool faces);
/* The stencil's counts as colour over the whole screen, stencil test on;
 * leaves it off. */
void volume_overlay_counts(volume_draw *d, unsigned stencil_mask);
/* The wide count's classes as colour over the whole screen (the caller
 * counted the light wide), with their legend; leaves the stencil test
 * off. */
void volume_overlay_wide_counts(volume_wide *w);

#endif
