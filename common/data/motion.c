#include "motion.h"

#include "camera.h"

const char *const motion_names[] = {"static", "light", "camera", NULL};

void motion_lights(motion_kind kind, double time, const float center[3], const scene_light *base, int count,
                   scene_light *out) {
    for (int i = 0; i < count; i++) {
        out[i] = base[i];
        if (kind == MOTION_LIGHT)
            camera_orbit_light(&out[i], center, (float)time * MOTION_LIGHT_RAD_PER_S, 0);
    }
}

void motion_camera(motion_kind kind, double time, const scene_camera *base, scene_camera *out) {
    *out = *base;
    if (kind == MOTION_CAMERA)
        camera_orbit(out, (float)time * MOTION_CAMERA_RAD_PER_S, 0, 1, CAMERA_ORBIT_ANY);
}
