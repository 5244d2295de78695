/* planar: planar projected shadows (see planar.c). Exposed for its tests:
 * the shadow matrix, the receiver's plane equation and the coplanar test. */
#ifndef PLANAR_H
#define PLANAR_H

#include <stdbool.h>
#include "scene.h"

typedef struct planar_settings {
    bool no_stencil; /* blend darkening straight into the picture */
    bool no_offset;  /* no polygon offset: z-fighting */
    bool no_reject;  /* keep anti-shadows */
} planar_settings;

/* S = (P.L) I - L P^T, column-major: S v lies on the plane P, on the line
 * through v and the homogeneous light L. */
void planar_shadow_matrix(const float plane[4], const float light[4], float out[4][4]);
/* World plane (unit normal, d) of a "plane" mesh object: its local +Y. */
void planar_receiver_plane(const scene_object *o, float plane[4]);
/* Object o lies in the plane, within float rounding: flattened onto it,
 * it is its own shadow, so it casts none there (a mat on the floor). */
bool planar_in_plane(const scene_object *o, const float plane[4]);

#endif
