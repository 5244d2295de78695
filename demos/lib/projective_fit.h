/* projective_fit: the frustum through which demos/projective.c draws a
 * light's casters into its texture, and projects it back.
 *
 * A point or spot light gets a perspective frustum round the bounding
 * sphere of the casters it reaches, a directional light an orthographic
 * box round them along its rays; a light inside that sphere gets the
 * widest frustum allowed, aimed at its centre (clamped), and what lies
 * outside casts nothing. The fit is the scene's alone, whatever the camera
 * sees, so that the texture is the same with every skip.
 */
#ifndef PROJECTIVE_FIT_H
#define PROJECTIVE_FIT_H

#include <stdbool.h>

#include <cglm/cglm.h>

#include "scene.h"

/* A positional light's frustum is at most this wide each side: a
 * perspective texture's texels grow without bound towards 90 degrees. */
#define PROJECTIVE_FIT_MAX_HALF_ANGLE_DEG 80.0f

typedef struct projective_frustum {
    bool fitted;  /* the light reaches a caster: what follows holds */
    bool clamped; /* the light lies among its casters, or they span more than the limit */
    bool orthographic;
    float half_angle_deg; /* positional */
    mat4 view_projection;
    float depth_plane[4]; /* depth from the light along its axis */
    float nearest;        /* the casters' nearest depth */
} projective_frustum;

/* Object o is drawn into the texture: it casts, and, unless receivers
 * cast, receives nothing. */
bool projective_fit_casts(const scene_object *o, bool receivers_cast);
/* The frustum of `light` fitted to the casters of s it reaches; corners:
 * room for 8 per object. */
void projective_fit(const scene *s, const scene_light *light, bool receivers_cast, float (*corners)[3],
                    projective_frustum *out);

#endif
