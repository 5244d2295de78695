/* light_mask: where the visible receivers lie as a light sees them, a
 * coarse grid over one layer of the light's view, so that a caster whose
 * shadow can reach none of them is culled: the shadow-receiver map of CC
 * shadow volumes (Lloyd, Wendt, Govindaraju & Manocha, EGSR 2004) and of
 * receiver-mask caster culling (Bittner, Mattausch, Silvennoinen &
 * Wimmer, "Shadow caster culling for efficient shadow mapping", I3D 2011).
 *
 * A layer is a clip matrix from world space: a shadow map's layer, or one
 * of light_mask_layers' for a light that has no map. Each cell of the
 * LIGHT_MASK_CELLS x LIGHT_MASK_CELLS grid over its NDC square holds the
 * deepest NDC depth read there, -infinity where nothing is. A read is a
 * convex body given by 8 corners (a screen tile's slab of visible depth,
 * numbered as frustum_box_corners numbers a box's): the cells its part in
 * front of the layer's centre of projection covers, its rectangle grown
 * by the mask's `grow` (NDC: a filter's reach) and clamped to the square,
 * take its deepest depth (+infinity with any_depth: where the reads
 * compare with any depth).
 *
 * light_mask_box_read: a caster's box is needed where a cell of its own
 * rectangle holds a depth at or beyond its nearest. Exact for a shadow:
 * a point in the box's shadow lies beyond a point of the box on the same
 * ray from the light, so in the same cell and deeper (every layer's NDC
 * depth grows along the rays from its centre, for an orthographic and a
 * perspective one). A body through the centre of projection sees the
 * whole layer: a read there makes every box needed (`whole`), a box there
 * is needed.
 *
 * No GL: pure math on points, in float, conservative by
 * LIGHT_MASK_DEPTH_TOLERANCE in NDC depth.
 */
#ifndef LIGHT_MASK_H
#define LIGHT_MASK_H

#include <cglm/cglm.h>
#include <stdbool.h>

#include "scene.h"

#define LIGHT_MASK_CELLS 64
/* A box this far in NDC depth beyond a cell's deepest read still counts. */
#define LIGHT_MASK_DEPTH_TOLERANCE 1e-5f
/* The layers of light_mask_layers: a cube's six faces at most. */
#define LIGHT_MASK_MAX_LAYERS 6

/* Where a read lies in the picture it was seen in: its pixel rectangle
 * (x, y) and window depths (z), lo..hi. */
typedef struct light_mask_seen {
    float lo[3], hi[3];
} light_mask_seen;
/* Nothing seen: where a union starts. */
#define LIGHT_MASK_SEEN_NOTHING                                                                                      \
    {                                                                                                                \
        {INFINITY, INFINITY, INFINITY}, { -INFINITY, -INFINITY, -INFINITY }                                          \
    }

typedef struct light_mask {
    mat4 layer; /* world -> the layer's clip space */
    float grow; /* NDC: how far every read's rectangle grows */
    bool any_depth;
    bool whole;      /* a read saw the whole layer: every box is needed */
    bool empty;      /* nothing read yet */
    bool keeps_seen; /* the cells keep where their reads were seen */
    float deepest[LIGHT_MASK_CELLS * LIGHT_MASK_CELLS];
    /* With keeps_seen: per cell, the union of its reads' light_mask_seen. */
    light_mask_seen seen[LIGHT_MASK_CELLS * LIGHT_MASK_CELLS];
} light_mask;

/* Where a convex body lies in a layer (light_mask_body_part). */
typedef enum light_mask_part_kind {
    LIGHT_MASK_PART_NONE,  /* wholly outside the layer's sides, or behind it */
    LIGHT_MASK_PART_WHOLE, /* through the centre of projection: it sees all */
    LIGHT_MASK_PART_SOME,  /* the rectangle and depths below */
} light_mask_part_kind;
typedef struct light_mask_part {
    light_mask_part_kind kind;
    vec2 lo, hi;            /* its NDC rectangle (not clamped to the square) */
    float nearest, deepest; /* its NDC depths */
} light_mask_part;
/* The part of the convex body with these corners in front of the layer's
 * centre of projection and inside its sides widened by `widen` (NDC).
 * Every line through the centre inside a convex body leaves it through its
 * surface, and the sides pass through the centre: the part of the surface
 * has the body's rectangle and depths, so only the six faces are clipped,
 * and only where a corner lies at or behind the centre. */
light_mask_part light_mask_body_part(const mat4 layer, float widen, const float corners[8][3]);

/* An empty mask over `layer`; keeps_seen: its cells keep where their
 * reads were seen (light_mask_box_seen). */
void light_mask_start(light_mask *m, const mat4 layer, float grow, bool any_depth, bool keeps_seen);
/* Adds the convex body with these corners to what the layer reads; seen:
 * where it was seen (NULL without keeps_seen). */
void light_mask_add(light_mask *m, const float corners[8][3], const light_mask_seen *seen);
/* Whether the box lo..hi has a part in a read cell at or before its
 * deepest depth (see top). */
bool light_mask_box_read(const light_mask *m, const vec3 lo, const vec3 hi);
/* The same, and where what it may shadow was seen: the union of the seen
 * bounds of those cells is grown by theirs into *out (a box it shadows
 * nothing through leaves it as it was). With keeps_seen; a mask that saw
 * its whole layer grows *out to everything (infinite bounds). */
bool light_mask_box_seen(const light_mask *m, const vec3 lo, const vec3 hi, light_mask_seen *out);

/* The layers that cover everything `light` shines on, for a light with no
 * map of its own: a directional light's one orthographic layer, fitted
 * across the bodies (count of them, 8 corners each) that will be added; a
 * positional light's six cube faces, perspective from its position with a
 * near plane at LIGHT_MASK_NEAR_SHARE of the farthest corner (any near
 * keeps the depth's order along a ray; this one keeps its precision).
 * Returns how many (0: no body). */
#define LIGHT_MASK_NEAR_SHARE 1e-3f
int light_mask_layers(const scene_light *light, const float (*bodies)[8][3], int count,
                      mat4 layers[LIGHT_MASK_MAX_LAYERS]);

#endif
