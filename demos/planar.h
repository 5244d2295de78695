/* planar: planar projected shadows (see planar.c). Exposed for its tests:
 * the receiver's plane equation and which casters cast nothing on it (the
 * shadow matrix is frustum_plane_projection). */
#ifndef PLANAR_H
#define PLANAR_H

#include <stdbool.h>
#include "scene.h"

typedef struct planar_settings {
    bool no_stencil;   /* blend darkening straight into the picture */
    bool no_offset;    /* no polygon offset: z-fighting */
    bool no_reject;    /* keep anti-shadows */
    int light_samples; /* choice: soft_visibility_sample_counts; the first (1) draws an area light hard */
} planar_settings;

/* World plane (unit normal, d) of a "plane" mesh object: its local +Y. */
void planar_receiver_plane(const scene_object *o, float plane[4]);
/* No part of object o lies on the light's side of the plane (oriented
 * towards the light), within float rounding: in the plane, flattened onto
 * it, o is its own shadow (a mat on the floor); beyond it, only its faces
 * in the plane would pass the clip distances, and the light reaches the
 * receiver there (a box on the ground, lit from below). It casts none. */
bool planar_casts_nothing(const scene_object *o, const float plane[4]);

#endif
