/* volume_bounds: where a light's shadow volumes may count, for
 * demos/volumes.c: the screen rectangle of the scene's receivers
 * (volume_mesh_receivers_scissor) and the depth bounds of the visible
 * ones within the light's range (volume_mesh_depth_bounds), and a
 * caster's part of those where what its shadow may fall on was seen
 * (skips_caster_seen). Outside them a volume adds 0 to every visible
 * receiver's count, so a pixel there keeps the cleared stencil. */
#ifndef VOLUME_BOUNDS_H
#define VOLUME_BOUNDS_H

#include <stdbool.h>

#include "technique.h"

/* The scissor's rectangle (x, y, width, height) and, where `bounded`, the
 * depth bounds (window depth). */
typedef struct volume_bounds {
    int rect[4];
    bool bounded;
    float depth[2];
} volume_bounds;

/* The hull's light's: the receivers' rectangle (the frame's, the same for
 * every light: volume_mesh_receivers_scissor), and the depth bounds when
 * `depth_bounds` (the caller has GL_EXT_depth_bounds_test and wants it)
 * and the frame's receivers are all there (not cut short). The bounds are
 * window depths of GL's standard convention: with reversed depth they are
 * left off (they only save fill). */
void volume_bounds_light(const technique_frame *f, const skips_hull *hull, const int receivers_rect[4],
                         bool depth_bounds, volume_bounds *out);
/* Caster i's part of the light's bounds (an empty rectangle where none);
 * false: no masks this frame, the light's unchanged. Counts the caster
 * as narrowed in f->skips->counts where its rectangle is the smaller. */
bool volume_bounds_caster(const technique_frame *f, const skips_hull *hull, int i, const volume_bounds *light,
                          volume_bounds *out);
/* Scissors to b and, where bounded, sets its depth bounds. */
void volume_bounds_use(const volume_bounds *b);

#endif
