/* mesh_point: where a point, homogeneous (w 1: a position; w 0: a
 * direction, at infinity), stands against a triangle mesh: which way each
 * triangle faces it, whether it lies inside the mesh, and the point in an
 * object's own space. The shadow volumes weigh triangles by it
 * (demos/lib/volume_mesh.h); the shadow maps ask whether the eye or a
 * light is inside a closed caster, and a scene's load whether a light is
 * (scene.h). No GL.
 */
#ifndef MESH_POINT_H
#define MESH_POINT_H

#include <stdbool.h>

#include <cglm/cglm.h>

#include "mesh.h"

/* The way towards the point from position p, not normalized: the
 * point's position less p, or a direction itself. */
void mesh_point_from(const float *p, const float point[4], float out[3]);

/* A triangle is edge-on to a point whose distance from its plane is at
 * most the sum of its corners' distances from the point over this (for
 * a direction: the sine of its angle to the plane, over 3): far above
 * float rounding of positions moved into an object's space, and
 * symmetric in the corners, so that a neighbour's test from other corners
 * (the volumes' geometry shader's) differs only by rounding. An int: that
 * shader gets it as a define. */
#define MESH_POINT_EDGE_ON_RECIPROCAL 100000
/* +1 when triangle (a, b, c) (as it is wound) faces the point, -1 when it
 * faces away, 0 when it is edge-on to it (see above). */
int mesh_point_facing(const float *a, const float *b, const float *c, const float point[4]);

/* The winding number above which a point is inside a closed mesh, or on
 * it (1/2); and above which it is inside, off its surface. */
#define MESH_POINT_INSIDE_WINDING 0.25
#define MESH_POINT_WITHIN_WINDING 0.75
/* The generalized winding number of mesh m (closed, wound outwards) about
 * the point (m's space): the triangles' signed solid angles over 4 pi
 * (Jacobson et al. 2013), 1 inside, 0 outside, 1/2 on the surface, where
 * the triangle holding the point is edge-on and counts 0, whichever side
 * of it rounding put the point (-1 inside a mesh wound inwards). 0 for a
 * point outside the mesh's bounds (and a margin for that rounding), where
 * it costs nothing, and for a direction. */
double mesh_point_winding(const mesh *m, const float point[4]);
/* Whether the point (m's space) lies inside mesh m (closed, wound
 * outwards) or on its surface: its winding number above
 * MESH_POINT_INSIDE_WINDING. */
bool mesh_point_inside(const mesh *m, const float point[4]);

/* The point (world) in the space of an object whose model matrix is
 * `model`. */
void mesh_point_to_object(const mat4 model, const float point[4], float out[4]);

#endif
