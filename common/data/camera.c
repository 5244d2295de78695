#include "camera.h"

void camera_view_compute(const scene_camera *c, float aspect, camera_view *out) {
    glm_lookat((float *)c->position, (float *)c->target, (float *)c->up, out->view);
    glm_perspective(glm_rad(c->fov_deg), aspect, c->near_plane, c->far_plane, out->projection);
    glm_mat4_mul(out->projection, out->view, out->view_projection);
    glm_vec3_copy((float *)c->position, out->eye);
}

/* The rotation that turns `offset` (from a centre) by yaw about `up` and
 * by pitch towards `up`, stopping 1 degree short of the pole so the basis
 * never degenerates. */
static void camera_orbit_rotation(const float offset[3], const float up_in[3], float yaw, float pitch, mat4 r) {
    vec3 up, side;
    glm_vec3_normalize_to((float *)up_in, up);
    float elevation = asinf(glm_clamp(glm_vec3_dot((float *)offset, up) / glm_vec3_norm((float *)offset), -1, 1));
    float limit = glm_rad(89.0f);
    pitch = glm_clamp(elevation + pitch, -limit, limit) - elevation;
    glm_vec3_cross(up, (float *)offset, side);
    glm_rotate_make(r, yaw, up);
    if (glm_vec3_norm(side) > 0) {
        mat4 tilt;
        glm_rotate_make(tilt, -pitch, side);
        glm_mat4_mul(r, tilt, r);
    }
}

void camera_orbit(scene_camera *c, float yaw_rad, float pitch_rad, float zoom) {
    vec3 offset;
    mat4 r;
    glm_vec3_sub(c->position, c->target, offset);
    camera_orbit_rotation(offset, c->up, yaw_rad, pitch_rad, r);
    glm_mat4_mulv3(r, offset, 0, offset);
    glm_vec3_scale(offset, zoom, offset);
    glm_vec3_add(c->target, offset, c->position);
}

void camera_orbit_light(scene_light *l, const float center[3], float yaw_rad, float pitch_rad) {
    static const float up[3] = {0, 1, 0};
    vec3 offset;
    mat4 r;
    if (l->type == SCENE_LIGHT_DIRECTIONAL)
        glm_vec3_negate_to(l->direction, offset);
    else
        glm_vec3_sub(l->position, (float *)center, offset);
    camera_orbit_rotation(offset, up, yaw_rad, pitch_rad, r);
    glm_mat4_mulv3(r, l->direction, 0, l->direction);
    glm_mat4_mulv3(r, offset, 0, offset);
    if (l->type != SCENE_LIGHT_DIRECTIONAL)
        glm_vec3_add((float *)center, offset, l->position);
}
