/* motion: where the lights and the camera are at a time, one path for the
 * app (--motion, --animate, the space key) and the benchmark (--motion),
 * so that the frames a benchmark times are the frames the app shows. No GL.
 *
 *   static  nothing moves;
 *   light   every light turns about the camera's target, yaw
 *           MOTION_LIGHT_RAD_PER_S radians a second (the app's --animate);
 *   camera  the eye turns about its target, yaw MOTION_CAMERA_RAD_PER_S.
 *
 * Both start from the scene's own positions at time 0 (motion_lights,
 * motion_camera take those and write the moved ones), so frame i of a
 * headless run (time i / 60 s) is the same wherever it is rendered.
 */
#ifndef MOTION_H
#define MOTION_H

#include "scene.h"

typedef enum motion_kind { MOTION_STATIC, MOTION_LIGHT, MOTION_CAMERA } motion_kind;
/* The kinds' names in order, NULL-terminated (a FLAGS_CHOICE list). */
extern const char *const motion_names[];

#define MOTION_LIGHT_RAD_PER_S 0.5f
#define MOTION_CAMERA_RAD_PER_S 0.5f

/* The count lights of `base` at `time`, into `out`. */
void motion_lights(motion_kind kind, double time, const float center[3], const scene_light *base, int count,
                   scene_light *out);
/* The camera `base` at `time`, into `out`. */
void motion_camera(motion_kind kind, double time, const scene_camera *base, scene_camera *out);

#endif
