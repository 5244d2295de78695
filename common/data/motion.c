#include "motion.h"

#include <math.h>

#include "camera.h"

const char *const motion_names[] = {"static", "light", "camera", "dolly", "lamp", "lamps", NULL};

/* Light `light` (at its place at time 0) on its circle at `time`: it
 * turns about the circle's centre, beside its place along -x. */
static void motion_lamp(scene_light *light, double time, const float center[3]) {
    float reach = light->range > 0 ? light->range : glm_vec3_distance(light->position, (float *)center);
    float radius = MOTION_LAMP_RADIUS_SHARE * reach;
    float middle[3] = {light->position[0] - radius, light->position[1], light->position[2]};
    camera_orbit_light(light, light->type == SCENE_LIGHT_DIRECTIONAL ? center : middle,
                       (float)time * MOTION_LAMP_RAD_PER_S, 0);
}

void motion_lights(motion_kind kind, double time, const float center[3], const scene_light *base, int count, int lamp,
                   scene_light *out) {
    for (int i = 0; i < count; i++) {
        out[i] = base[i];
        if (kind == MOTION_LIGHT)
            camera_orbit_light(&out[i], center, (float)time * MOTION_LIGHT_RAD_PER_S, 0);
        if ((kind == MOTION_LAMP && i == lamp) || kind == MOTION_LAMPS)
            motion_lamp(&out[i], time, center);
    }
}

void motion_camera(motion_kind kind, double time, const scene_camera *base, scene_camera *out) {
    *out = *base;
    if (kind == MOTION_CAMERA)
        camera_orbit(out, (float)time * MOTION_CAMERA_RAD_PER_S, 0, 1, CAMERA_ORBIT_ANY);
    if (kind == MOTION_DOLLY) {
        /* A triangle wave: seconds walked forward so far, less those
         * walked back, at one speed throughout. */
        double leg = fmod(time, 2 * MOTION_DOLLY_LEG_S);
        double forward_s = leg <= MOTION_DOLLY_LEG_S ? leg : 2 * MOTION_DOLLY_LEG_S - leg;
        float along = (float)forward_s * MOTION_DOLLY_SPEED;
        for (int k = 0; k < 3; k++) {
            float step = along * (base->target[k] - base->position[k]);
            out->position[k] = base->position[k] + step;
            out->target[k] = base->target[k] + step;
        }
    }
}

bool motion_moves_camera(motion_kind kind) { return kind == MOTION_CAMERA || kind == MOTION_DOLLY; }
