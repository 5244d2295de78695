/* volume_plan: for demos/volumes.c, every decision a light's count takes
 * before anything is drawn: which casters' volumes count, each z-pass or
 * z-fail, and where (the skips, README "Skips"), none of which changes a
 * count on a visible receiver, the only pixels the stencil decides.
 *
 * A caster's volume is left out when its count is 0 on every visible
 * receiver. A volume that misses the view has no fragment (counted as
 * culled). A point inside a caster's volume lies beyond the caster on a
 * segment from the light, so outside the hull of the light and the
 * visible receivers' bounds (convex) it contains no visible receiver point
 * (skips_caster_needed): z-fail counts there exactly that, 0, and so
 * does z-pass where it starts from 0, which auto takes only where
 * volume_mesh_zpass_safe says; forced z-pass keeps casters that may shadow
 * the eye (they count there), and as it counts them on pixels outside them
 * too, they keep the light's bounds. The light's volumes count only in the
 * screen rectangle of every receiver's box and, with the depth bounds,
 * between the depths of the visible receivers within its range
 * (volume_bounds_light); after technique_see, a volume counts only in the
 * pixels and depths where what its shadow may fall on was seen
 * (volume_bounds_caster).
 */
#ifndef VOLUME_PLAN_H
#define VOLUME_PLAN_H

#include <stdbool.h>

#include "technique.h"
#include "volume_bounds.h"

/* --mode: z-pass (no caps) where safe, else z-fail (caps); or one forced;
 * or z-pass from the count of the volumes that hold the eye (the
 * lecture's first answer to an eye in shadow, wrong where the near plane
 * cuts a volume the eye is outside of); or ZP+, z-pass from each pixel's
 * count on the near plane, drawn from the light (volume_near.h), for the
 * casters that are not safe. ZP+ projects onto the near plane from the
 * light, so where the light lies in that plane (within
 * VOLUME_PLAN_NEAR_TOLERANCE of the terms of its equation) the light
 * counts as auto does. */
typedef enum volume_plan_mode {
    VOLUME_PLAN_AUTO,
    VOLUME_PLAN_ZPASS,
    VOLUME_PLAN_ZFAIL,
    VOLUME_PLAN_EYE_COUNT,
    VOLUME_PLAN_ZP_PLUS
} volume_plan_mode;
#define VOLUME_PLAN_NEAR_TOLERANCE 1e-4f
/* Whether the mode counts every caster z-pass, whatever the eye sees. */
bool volume_plan_forced_zpass(volume_plan_mode mode);

/* How caster i's volume counts for the light at hand. */
typedef struct volume_plan_caster {
    bool needed;   /* it casts a volume for the light */
    bool zfail;    /* counted behind the surface, with caps; else in front */
    bool near;     /* ZP+: counted in front from its count on the near plane */
    bool narrowed; /* within `bounds`, not the light's */
    volume_bounds bounds;
} volume_plan_caster;

/* A light's plan. */
typedef struct volume_plan {
    int light;
    int cache;       /* the cache that keeps the volumes (volume_draw_cache): the caller's */
    vec4 position;   /* homogeneous, world; aligned as cglm loads it */
    vec4 near_plane; /* ZP+: the near plane, world, oriented towards the light */
    skips_hull hull;
    volume_bounds bounds;        /* where the light's volumes may count */
    volume_plan_caster *casters; /* per object, the caller's */
    bool reported;               /* the HUD's figures are this count's */
} volume_plan;

/* Whether a caster takes z-fail, with caps, given whether z-pass is safe
 * for it (volume_mesh_zpass_safe) and whether the eye may see through it:
 * a single-sided object (scene_object) seen from behind. z-pass, from 0
 * or from the near plane's count, counts the sides in front of the
 * visible surface, and an eye ray that enters a volume through its caster
 * crosses none; z-fail counts behind the surface, where the caps close
 * every volume, so such a caster takes it unless z-pass is forced. */
bool volume_plan_zfail(volume_plan_mode mode, bool zpass_safe, bool seen_through);
/* Light l's plan with every skip, for its centre (point NULL) or one
 * point of its area (homogeneous, world; the masks of what is seen are
 * the centre's, so a point's plan culls by its hull alone);
 * `receivers_rect`: every receiver's box on screen
 * (volume_mesh_receivers_scissor); `depth_bounds`: the GL has them and
 * they are on. */
void volume_plan_light(const technique_frame *f, int l, const float point[4], volume_plan_mode mode,
                       const int receivers_rect[4], bool depth_bounds, volume_plan_caster *casters,
                       volume_plan *plan);
/* The number of the plan's casters' volumes that hold the eye, tested on
 * the CPU against each (volume_mesh_count_at; edges: per object, the
 * casters' tables, for the rule each takes): what --mode eye-count starts
 * z-pass from. */
int volume_plan_eye_count(const technique_frame *f, const volume_plan *plan, const mesh_edges *edges);
/* Light l's plan with no skip, for a light at `position` (homogeneous,
 * world): every caster's volume, each z-pass or z-fail as the mode says
 * there, under whatever scissor is on. */
void volume_plan_every_caster(const technique_frame *f, int l, const float position[4], volume_plan_mode mode,
                              volume_plan_caster *casters, volume_plan *plan);

#endif
