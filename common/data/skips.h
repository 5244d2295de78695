/* skips: what a frame need not draw, and the tests that tell, without GL.
 *
 * The frame's owner (technique_host.h: the app and the benchmark) works
 * out per frame what a technique need not do and hands it over as one
 * `skips` (technique_frame.skips); none may change a pixel:
 *   in_view               the objects the camera passes draw (view culling);
 *   lights                the lights that reach anything visible
 *                         (skips_light_on);
 *   lit_by, light_rect    per light, the objects and pixels its lighting
 *                         pass needs (light reach; shading_light_pass);
 *   receivers             the visible receivers' points, for fitting and
 *                         for caster culling (skips_light_hull,
 *                         skips_caster_needed, when cull_casters);
 *   seen                  what the camera's depth pre-pass shows
 *                         (technique_see: hidden casters and objects).
 * A technique counts what they saved in counts, for the HUD and --verbose.
 *
 * Caster culling for one light (skips_light_hull): the hull of the light
 * and the visible receivers it can reach (their bounds, clipped to its
 * range), outside which a caster shadows nothing the camera sees
 * (frustum_light_hull); after technique_see, also the light's masks of the
 * visible pixels within those bounds (light_mask.h: the layers of
 * light_mask_layers), which a caster's box must reach as well.
 */
#ifndef SKIPS_H
#define SKIPS_H

#include <stdbool.h>

#include "frustum.h"
#include "light_mask.h"
#include "scene.h"
#include "visible.h"

/* The receivers the camera sees: the corners of the part of each visible
 * receiver's box inside the view frustum. Enough for a few hundred boxes. */
#define SKIPS_MAX_RECEIVER_POINTS 16384
/* The most corners of one box's part inside a frustum: its 8 and the
 * frustum's 8, and where each one's 12 edges cross the other's 6 faces. */
#define SKIPS_MAX_PART_POINTS (8 + 8 + 2 * 12 * 6)

/* What the skips saved this frame, for the HUD and --verbose: the host
 * fills lights_skipped, techniques the rest (casters per light: those
 * that cast into the light's map or volume, and those culled). */
typedef struct skips_counts {
    int lights_skipped;
    int casters_drawn[SCENE_MAX_LIGHTS], casters_culled[SCENE_MAX_LIGHTS];
    /* Of the culled: those only the masks of what is seen culled; of the
     * drawn: those the masks kept to a smaller part of the frame
     * (skips_caster_seen). */
    int casters_hidden[SCENE_MAX_LIGHTS], casters_narrowed[SCENE_MAX_LIGHTS];
    int objects_hidden; /* in view, behind what the pre-pass shows (technique_see) */
    /* Bit l: a pass of light l drew in its rectangle as technique_see
     * narrowed it to SHADING_NARROW_LIGHT_SHARE of the frame or less
     * (shading_light_pass). */
    scene_light_set lights_narrowed;
    int layers_rendered, layers_reused; /* map layers: a cube map has six */
    int layers_unread;                  /* map layers no receiver reads, not drawn (a cube's faces out of view) */
    int maps_kept;                      /* lights past the maps' budget that kept their maps (map.h, "Budget") */
    int marked_passes;                  /* passes over marked pixels alone (skips.marked_pass) */
} skips_counts;

/* What the camera's depth pre-pass shows (technique_see): the visible
 * pixels' slabs and, made on a light's first skips_light_hull, the masks
 * of where they lie as that light sees them. The host's; a frame's skips
 * point at it. */
typedef struct skips_seen {
    bool read; /* this frame's pixels are read */
    visible pixels;
    /* The host's in_view and lit_by of this frame, which technique_see
     * clears of the objects hidden behind what it read. */
    bool *in_view, *lit_by[SCENE_MAX_LIGHTS];
    /* Light l's pixels: its frame rectangle narrowed to the tiles whose
     * slabs it reaches (skips_light_rect). */
    int light_rect[SCENE_MAX_LIGHTS][4];
    scene_light_set masks_made; /* bit l: light l's masks */
    int mask_count[SCENE_MAX_LIGHTS];
    light_mask (*masks)[LIGHT_MASK_MAX_LAYERS]; /* one row per scene light, the host's */
} skips_seen;

/* A frame's skips (see the top of this file). */
typedef struct skips {
    const scene *scene; /* this frame's lights and objects */
    /* Object i meets this frame's view (render_cull_view; all true with
     * culling off; NULL: all): a technique culls its camera passes with
     * it (render_draw_objects), never a pass that sees from elsewhere. */
    const bool *in_view;
    /* Bit l: light l reaches a visible object (scene_light_reaches_box);
     * every light with --no-light-reach. A technique renders neither a
     * shadow pass nor a lighting pass for the others: they add exactly 0
     * to every visible pixel (skips_light_on). */
    scene_light_set lights;
    /* Per light on: the objects in view that it reaches (in_view without
     * the skip), and the pixel rectangle (x, y, width, height) outside of
     * which it adds 0 (its range's screen bounds; the whole frame without
     * a range or the skip). Its lighting pass needs no more
     * (shading_light_pass). */
    const bool *lit_by[SCENE_MAX_LIGHTS];
    int light_rect[SCENE_MAX_LIGHTS][4];
    const float (*receivers)[3];
    int receiver_count;
    float receivers_lo[3], receivers_hi[3]; /* their bounds; empty (lo > hi) when none */
    bool cull_casters;                      /* skips_caster_needed culls (--no-caster-cull: never) */
    /* A technique may shade its costly pixels (a hybrid's rays) in a pass
     * of their own, over the pixels a first pass marked, so that the
     * others run none of that code (--no-marked-pass: one pass). */
    bool marked_pass;
    /* Without --no-hidden-cull, unless the skip sleeps
     * (technique_host.h): where technique_see keeps what the pre-pass
     * shows (its masks cull casters only with cull_casters); else NULL. */
    skips_seen *seen;
    skips_counts *counts;
} skips;

/* Light l reaches the view this frame. */
bool skips_light_on(const skips *s, int l);
/* Light l's pixel rectangle (x, y, width, height), outside of which it
 * adds exactly 0: s->light_rect[l], narrowed after technique_see to the
 * tiles whose slabs the light reaches (its range, a spot's cone): every
 * visible point lies in a slab of its own tile. */
const int *skips_light_rect(const skips *s, int l);
/* The slabs technique_see read this frame; NULL when it read none. */
const visible *skips_seen_pixels(const skips *s);
/* After technique_see read s->seen's pixels: each slab's lights on that
 * reach it (visible.lights), and each light's rectangle narrowed to the
 * tiles of the slabs it reaches (skips_light_rect); a directional light
 * reaches every one. */
void skips_narrow_light_rects(const skips *s);

/* Caster culling for one light (see the top of this file). */
typedef struct skips_hull {
    int light;
    bool empty;  /* no visible receiver in reach: no caster is needed */
    vec3 lo, hi; /* the visible receivers' bounds clipped to the light's range (unless empty) */
    vec4 planes[FRUSTUM_HULL_MAX_PLANES];
    int plane_count;
    float margin;            /* world units: FRUSTUM_BOX_TOLERANCE of the hull's size */
    const light_mask *masks; /* NULL: none (no technique_see this frame) */
    int mask_count;
} skips_hull;
void skips_light_hull(const skips *s, int light, skips_hull *out);
/* The hull of one point of light l's area (homogeneous, world) and the
 * visible receivers the light reaches; without masks (those are of what
 * the centre sees). */
void skips_point_hull(const skips *s, int light, const float point[4], skips_hull *out);
/* Object i casts and its shadow may reach a visible receiver for the
 * hull's light (always, when s->cull_casters is off); counts it, drawn or
 * culled (and hidden, where only the masks culled it), in s->counts. */
bool skips_caster_needed(const skips *s, const skips_hull *hull, int object);
/* Where object's shadow for the hull's light may fall on what is seen:
 * the union of the pixels (x, y) and window depths (z) of the visible
 * slabs in the mask cells its box reads, into *out (empty: nowhere).
 * False without masks (no technique_see this frame): anywhere. Exact as
 * light_mask_box_read: every visible point in its shadow lies there. */
bool skips_caster_seen(const skips *s, const skips_hull *hull, int object, light_mask_seen *out);

#endif
