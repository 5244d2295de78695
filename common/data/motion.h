/* motion: where the lights and the camera are at a time, one path for the
 * app (--motion, --animate, the space key) and the benchmark (--motion),
 * so that the frames a benchmark times are the frames the app shows. No GL.
 *
 *   static  nothing moves;
 *   light   every light turns about the camera's target, yaw
 *           MOTION_LIGHT_RAD_PER_S radians a second (the app's --animate);
 *   lamp    one light alone (the programs' --light K) circles its own
 *           place, MOTION_LAMP_RAD_PER_S radians a second on a
 *           horizontal circle of MOTION_LAMP_RADIUS_SHARE of its range
 *           (of its distance from the camera's target without one): a
 *           lamp moving among many still ones, whose maps a cache keeps;
 *   lamps   every light on its own such circle: many lights moving, each
 *           staying where it was (a street lamp on its pole, not in the
 *           next building), every map due every frame;
 *   camera  the eye turns about its target, yaw MOTION_CAMERA_RAD_PER_S;
 *   dolly   the eye and its target move together along the view direction,
 *           MOTION_DOLLY_SPEED of their distance a second, forward for
 *           MOTION_DOLLY_LEG_S seconds then back as long, and again: a
 *           translation without rotation (camera is a rotation without
 *           translation), at a speed relative to the view, so it is the
 *           same walk in a scene of any scale, and one that never leaves
 *           the scene (it stays between the scene's eye and
 *           MOTION_DOLLY_SPEED * MOTION_DOLLY_LEG_S of the way to the
 *           target).
 *
 * Both start from the scene's own positions at time 0 (motion_lights,
 * motion_camera take those and write the moved ones), so frame i of a
 * headless run (time i / 60 s) is the same wherever it is rendered.
 */
#ifndef MOTION_H
#define MOTION_H

#include <stdbool.h>
#include "scene.h"

typedef enum motion_kind {
    MOTION_STATIC,
    MOTION_LIGHT,
    MOTION_CAMERA,
    MOTION_DOLLY,
    MOTION_LAMP,
    MOTION_LAMPS
} motion_kind;
/* The kinds' names in order, NULL-terminated (a FLAGS_CHOICE list). */
extern const char *const motion_names[];

/* Frame i of a headless run is at i / MOTION_FRAME_RATE seconds: the
 * app's --frames, the benchmark's frames and raytrace's --frames agree. */
#define MOTION_FRAME_RATE 60.0
#define MOTION_LIGHT_RAD_PER_S 0.5f
#define MOTION_CAMERA_RAD_PER_S 0.5f
#define MOTION_DOLLY_SPEED 0.5f
#define MOTION_DOLLY_LEG_S 1.0
#define MOTION_LAMP_RAD_PER_S 3.0f
#define MOTION_LAMP_RADIUS_SHARE 0.05f

/* Whether `kind` moves the camera (camera, dolly): what a tour's path
 * excludes, and where the benchmark measures shimmer. */
bool motion_moves_camera(motion_kind kind);

/* The count lights of `base` at `time`, into `out`; `lamp`: the light
 * MOTION_LAMP moves. */
void motion_lights(motion_kind kind, double time, const float center[3], const scene_light *base, int count, int lamp,
                   scene_light *out);
/* The camera `base` at `time`, into `out`. */
void motion_camera(motion_kind kind, double time, const scene_camera *base, scene_camera *out);

#endif
