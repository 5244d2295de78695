/* soft_visibility: an area light's visibility accumulated from hard
 * shadows, for the stencil techniques (Brotman & Badler, "Generating soft
 * shadows with a depth buffer algorithm", IEEE CG&A 4(10), 1984, for
 * shadow volumes; Heckbert & Herf, "Simulating soft shadows with graphics
 * hardware", 1997, for projected shadows).
 *
 * The caller counts each of n points of the light (area_light.h, as the
 * reference takes them) in the stencil buffer as it would for a hard
 * light at that point, sets the stencil test that passes where the point
 * reaches the pixel, and soft_visibility_add adds one there, into a float
 * texture of the frame's size, one per light, that shares the frame's
 * depth and stencil. The light is then shaded once
 * (shading_light_soft): its unshadowed light times the sum over
 * the points added so far. As n grows it converges to what the reference
 * computes, up to the one disk all pixels share (the reference turns the
 * disk towards each pixel). A light's sum is kept from frame to frame, so
 * that points may be added over several (progressive, the window's) while
 * nothing moves.
 *
 *   soft_visibility_init(&v)                   once
 *   soft_visibility_begin(&v, l, n, restart)   light l's sum, of n points
 *   per point not yet added (v.lights[l].points of n): the stencil as for
 *     a hard light, glStencilFunc(lit ...), soft_visibility_add(&v, l, 1),
 *     v.lights[l].points++
 *   shading_light_soft(frame, l, &v, receivers_only)
 *   soft_visibility_destroy(&v)
 *
 * Errors: begin is false after one line on stderr (out of memory, an
 * incomplete framebuffer); the frame's owner checks GL errors.
 */
#ifndef SOFT_VISIBILITY_H
#define SOFT_VISIBILITY_H

#include <stdbool.h>

#include "render.h"

/* The texture unit the soft lit program reads the visibility from. */
#define SOFT_VISIBILITY_UNIT 15

/* The most points --light-samples takes (the last of
 * soft_visibility_sample_counts). */
#define SOFT_VISIBILITY_MAX_SAMPLES 256

/* One light's sum: its texture made on the light's first begin. */
typedef struct soft_visibility_light {
    unsigned framebuffer, texture;
    int samples; /* the points the sum is of; 0: none begun */
    int points;  /* of them, those added so far: the caller's count, which the lit program divides by (0 as 1) */
} soft_visibility_light;

typedef struct soft_visibility {
    unsigned accumulate; /* the program that adds a weight */
    int weight;          /* its u_weight */
    unsigned vao;        /* empty: the pass's triangle is made from gl_VertexID */
    soft_visibility_light lights[SCENE_MAX_LIGHTS];
    unsigned target_framebuffer, depth_stencil; /* the target the textures are for */
    int width, height;
} soft_visibility;

/* --light-samples' choices: how many points of an area light, each a
 * hard shadow, are averaged; the first (1) draws it hard from its
 * centre. */
extern const char *const soft_visibility_sample_counts[];
/* How many points light l (of `technique`, whose --light-samples is
 * `choice`) is sampled at: 1 for a hard light, or an area light drawn
 * hard, which is said once on stderr (bit l of *warned). */
int soft_visibility_samples(const char *technique, int choice, const scene_light *light, int l,
                            scene_light_set *warned);
/* How area light l is drawn at `choice`, for the HUD: with the points in
 * its sum so far while they are fewer than it takes (progressive). */
const char *soft_visibility_area_light_text(const soft_visibility *v, int choice, int l);

bool soft_visibility_init(soft_visibility *v);
/* Light l's sum, of `samples` points, for the bound target's size and
 * stencil: kept as the frames before left it, unless `restart`, the
 * target changed or the sum is of another count, when it starts again
 * from no point. */
bool soft_visibility_begin(soft_visibility *v, int l, int samples, bool restart);
/* Adds `weight` (a point: one) to light l's sum wherever the stencil test
 * as set passes (inside the scissor, where it is on); the target stays
 * bound. */
void soft_visibility_add(soft_visibility *v, int l, float weight);
/* Binds the lit program that scales light `light` by its sum (its
 * visibility the mean of its points added so far, at least one), for the
 * set `lights`, as render_use_lit does, and returns it (NULL where it
 * failed to compile). */
const render_program *soft_visibility_use_lit(const soft_visibility *v, const render_scene *r,
                                              const camera_view *view, int light, scene_light_set lights,
                                              bool ambient);
void soft_visibility_destroy(soft_visibility *v);

#endif
