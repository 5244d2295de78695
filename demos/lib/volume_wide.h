/* volume_wide: shadow volumes counted where the 8-bit stencil could wrap,
 * for demos/volumes.c.
 *
 * The stencil holds a pixel's count modulo 256 (volume_count_bound.h):
 * behind a non-zero multiple of 256 volumes it reads 0, lit. Where a
 * light's bound (volume_wide_bound: its needed casters' bounds on a grid
 * of directions) passes VOLUME_COUNT_BOUND_STENCIL_MAX, the same volumes,
 * the same per-caster z-pass or z-fail, bounds and skips, are counted in
 * a float target instead (a colour texture of the frame's size sharing
 * its depth and stencil, soft_visibility.h's), as bgfx's shadow-volume
 * example's "texture as stencil": blending adds +1 or -1 per face
 * (volume.frag's VOLUME_WIDE_COUNT, volume_draw's wide twins), exact up to
 * 2^24. z-pass counts where the depth test passes, front faces +1; z-fail
 * where it would fail, so the test is turned round (GEQUAL for LESS) and
 * the signs with it. Then the count is written back into the stencil
 * (volume_wide_end), so that what reads it is unchanged: 0 where it is
 * 0, 1 or 2 where it is, 3 for any other (the wedges tell 0, 1, 2 and 3
 * or more apart; the lighting, 0 from the rest). Where the bound is at
 * most that, the stencil counts as before, exact.
 *
 *   volume_wide_init(&w, objects)          once
 *   per count: volume_wide_bound(...) > VOLUME_COUNT_BOUND_STENCIL_MAX?
 *     volume_wide_begin(&w, &draw, start) after the stencil's clear, each caster
 *     volume_wide_caster(&w, &draw, view, zfail) before it is drawn,
 *     volume_wide_end(&w, &draw, view) after
 *   volume_wide_destroy(&w)
 *
 * The count overlay reads the target itself (volume_wide_overlay), so
 * that counts past 255 show as they are.
 *
 * Errors: init and begin are false after one line on stderr (out of
 * memory, an incomplete target); the caller then counts in the stencil.
 */
#ifndef VOLUME_WIDE_H
#define VOLUME_WIDE_H

#include <stdbool.h>

#include "soft_visibility.h"
#include "volume_count_bound.h"
#include "volume_draw.h"
#include "volume_plan.h"

/* The stencil values the count is written back as: 0 stays 0, 1 and 2
 * stay, any other count is VOLUME_WIDE_OTHER. */
#define VOLUME_WIDE_OTHER 3
/* Classes the overlay colours: 1, 2, 3, 4 to 255 (or negative), 256 or
 * more. */
#define VOLUME_WIDE_OVERLAY_STEPS 5

/* One caster's bound for the light it was found for. */
typedef struct volume_wide_kept {
    float light[4]; /* homogeneous, world */
    int bound;      /* -1: none yet */
} volume_wide_kept;

/* Zero is an unmade one. */
typedef struct volume_wide {
    soft_visibility target; /* its light 0's texture is the counter */
    unsigned resolve, overlay, vao;
    int resolve_select, resolve_count, overlay_count, overlay_ramp, overlay_alpha;
    volume_count_grid caster_grid, light_grid;
    signed char *convex;     /* per object: -1 not known yet, 0, 1 */
    volume_wide_kept **kept; /* per volume_draw_cache slot, per object; made when first needed */
    int object_count;
} volume_wide;

bool volume_wide_init(volume_wide *w, int object_count);
void volume_wide_destroy(volume_wide *w);
/* The most the plan's volumes can count at a pixel (see
 * volume_count_bound.h), from its needed casters; twice that where every
 * caster counts z-pass whatever the eye sees (`forced_zpass`: its count
 * may be the difference of two). Casters' bounds are kept per plan->cache until
 * the light moves. */
int volume_wide_bound(volume_wide *w, const technique_frame *f, const volume_plan *plan, const mesh_edges *edges,
                      bool forced_zpass);
/* Counting into the float target from here (its whole frame 0, `start`
 * within the scissor as set: the count z-pass starts from), stencil
 * writes off; false after one line on stderr. */
bool volume_wide_begin(volume_wide *w, volume_draw *d, int start);
/* The depth test and sign of the caster about to be drawn. */
void volume_wide_caster(volume_wide *w, volume_draw *d, const camera_view *view, bool zfail);
/* Back to the frame's target, the count written into its stencil within
 * the scissor as set (see top); the stencil test left on. After the
 * count has turned the depth bounds test off. */
void volume_wide_end(volume_wide *w, volume_draw *d, const camera_view *view);
/* Over the whole frame, translucent, the counted target's classes in
 * `ramp`'s colours (VOLUME_WIDE_OVERLAY_STEPS, see there); the largest
 * |count| into *largest. */
void volume_wide_overlay(volume_wide *w, const float (*ramp)[3], float alpha, int *largest);

#endif
