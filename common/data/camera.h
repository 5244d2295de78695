/* camera: view and projection matrices from a scene camera, and the orbit
 * the interactive window drives (drag to orbit, scroll to zoom).
 *
 * The projection is OpenGL's standard perspective (depth -1..1), vertical
 * field of view, as every technique and the ray-traced reference use.
 */
#ifndef CAMERA_H
#define CAMERA_H

#include <cglm/cglm.h>
#include "scene.h"

typedef struct camera_view {
    mat4 view, projection, view_projection;
    vec3 eye;
} camera_view;

void camera_view_compute(const scene_camera *c, float aspect, camera_view *out);
/* Turns the eye about the target: yaw about the up axis, pitch towards it
 * (kept short of the poles), distance scaled by zoom. */
void camera_orbit(scene_camera *c, float yaw_rad, float pitch_rad, float zoom);
/* Turns a light about `center` the same way (direction turns with it). */
void camera_orbit_light(scene_light *l, const float center[3], float yaw_rad, float pitch_rad);

#endif
