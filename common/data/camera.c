#include "camera.h"

#include <math.h>
#include <stdio.h>

#include "frustum.h"

/* The far corners stop here: beyond every point a loaded scene can hold
 * (CAMERA_MAX_COORDINATE), so the frustum cut there meets the scene as
 * the whole one does, while corners stay finite in float at any field of
 * view and aspect (tan(fov / 2) at most 1e7 for a float below 180
 * degrees, aspect at most 1e5). */
#define CAMERA_CORNER_MAX_DISTANCE 1e24
/* A coordinate whose square, summed over three axes and across the scene,
 * stays below FLT_MAX: the shaders' distances and dot products. */
#define CAMERA_MAX_COORDINATE 1e18

/* The view's unit basis in double, as glm_lookat builds it in float:
 * forward towards the target, side = forward x up, up = side x forward. */
static void camera_basis(const scene_camera *c, double forward[3], double side[3], double up[3]) {
    double length = 0;
    for (int k = 0; k < 3; k++) {
        forward[k] = (double)c->target[k] - c->position[k];
        length += forward[k] * forward[k];
    }
    for (int k = 0; k < 3; k++)
        forward[k] /= sqrt(length);
    double s[3] = {forward[1] * c->up[2] - forward[2] * c->up[1], forward[2] * c->up[0] - forward[0] * c->up[2],
                   forward[0] * c->up[1] - forward[1] * c->up[0]};
    double side_length = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    for (int k = 0; k < 3; k++)
        side[k] = s[k] / side_length;
    up[0] = side[1] * forward[2] - side[2] * forward[1];
    up[1] = side[2] * forward[0] - side[0] * forward[2];
    up[2] = side[0] * forward[1] - side[1] * forward[0];
}

static void camera_corners(const scene_camera *c, float aspect, vec3 out[8]) {
    double forward[3], side[3], up[3];
    camera_basis(c, forward, side, up);
    double half_height = tan(glm_rad(c->fov_deg) * 0.5), half_width = half_height * aspect;
    double distance[2] = {c->near_plane, fmin(c->far_plane, CAMERA_CORNER_MAX_DISTANCE)};
    for (int corner = 0; corner < 8; corner++) {
        double d = distance[corner >> 2], x = corner & 1 ? half_width : -half_width;
        double y = corner & 2 ? half_height : -half_height;
        for (int k = 0; k < 3; k++)
            out[corner][k] = (float)(c->position[k] + d * (forward[k] + x * side[k] + y * up[k]));
    }
}

/* glm_perspective with its far plane at infinity: the same x, y and w
 * rows, and the limit of its depth row (any finite far fills the rest). */
static void camera_perspective_infinite(float fov_rad, float aspect, float near_plane, mat4 out) {
    glm_perspective(fov_rad, aspect, near_plane, 2 * near_plane, out);
    out[2][2] = -1;
    out[3][2] = -2 * near_plane;
}

/* `standard` with the reversed depth row (camera.h, top): clip z =
 * near (z_eye + far) / (far - near) against w = -z_eye, so window depth
 * is 1 at near and 0 at far; near alone with the far plane at infinity
 * (beyond CAMERA_INFINITE_FAR_RATIO, as the standard one). */
static void camera_reversed_projection(const scene_camera *c, const mat4 standard, mat4 out) {
    glm_mat4_copy((vec4 *)standard, out);
    double near_plane = c->near_plane, far_plane = c->far_plane;
    bool infinite = far_plane / near_plane > CAMERA_INFINITE_FAR_RATIO;
    out[2][2] = infinite ? 0.0f : (float)(near_plane / (far_plane - near_plane));
    out[3][2] = infinite ? (float)near_plane : (float)(near_plane * far_plane / (far_plane - near_plane));
}

void camera_view_compute(const scene_camera *c, float aspect, camera_view *out) {
    glm_lookat((float *)c->position, (float *)c->target, (float *)c->up, out->view);
    if ((double)c->far_plane / c->near_plane > CAMERA_INFINITE_FAR_RATIO)
        camera_perspective_infinite(glm_rad(c->fov_deg), aspect, c->near_plane, out->projection);
    else
        glm_perspective(glm_rad(c->fov_deg), aspect, c->near_plane, c->far_plane, out->projection);
    glm_mat4_mul(out->projection, out->view, out->view_projection);
    out->reversed_depth = c->reversed_depth;
    if (c->reversed_depth) {
        camera_reversed_projection(c, out->projection, out->raster_projection);
        glm_mat4_mul(out->raster_projection, out->view, out->raster_view_projection);
    } else {
        glm_mat4_copy(out->projection, out->raster_projection);
        glm_mat4_copy(out->view_projection, out->raster_view_projection);
    }
    glm_vec3_copy((float *)c->position, out->eye);
    if ((double)c->far_plane / c->near_plane <= CAMERA_INVERSE_MAX_RATIO)
        frustum_corners(out->view_projection, out->corners);
    else
        camera_corners(c, aspect, out->corners);
}

/* The world-space distance between two neighbouring depth values of the
 * target at `distance` from the eye along the view (camera.h, top): the
 * inverse of d(window depth) / dz = 1 / (z^2 (1/near - 1/far)). */
static double camera_depth_step(const scene_camera *c, double distance) {
    return distance * distance * (1.0 / c->near_plane - 1.0 / c->far_plane) / ldexp(1, CAMERA_DEPTH_BITS);
}

/* The same with reversed depth in float (camera.h, top): at most the
 * distance's share of one ulp. */
static double camera_reversed_depth_step(double distance) { return distance * ldexp(1, -CAMERA_FLOAT_DEPTH_BITS); }

bool camera_check_depth(scene *s, const char *file, bool reversed_available) {
    scene_camera *c = &s->camera;
    vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i < s->object_count; i++) {
        vec3 object_lo, object_hi;
        scene_object_world_bounds(&s->objects[i], object_lo, object_hi);
        glm_vec3_minv(lo, object_lo, lo);
        glm_vec3_maxv(hi, object_hi, hi);
    }
    double largest = 0, size = 0;
    for (int k = 0; k < 3; k++) {
        largest = fmax(largest, fmax(fmax(fabs(lo[k]), fabs(hi[k])), fabs(c->position[k])));
        size += ((double)hi[k] - lo[k]) * ((double)hi[k] - lo[k]);
    }
    size = sqrt(size);
    if (!(largest <= CAMERA_MAX_COORDINATE)) {
        fprintf(stderr,
                "%s: camera: the scene reaches %g from the origin: beyond %g, squared distances overflow a "
                "float\n",
                file, largest, CAMERA_MAX_COORDINATE);
        return false;
    }
    /* The farthest corner of the scene's box along the view, within far. */
    double forward[3], side[3], up[3], farthest = 0;
    camera_basis(c, forward, side, up);
    for (int corner = 0; corner < 8; corner++) {
        double depth = 0;
        for (int k = 0; k < 3; k++)
            depth += ((corner >> k & 1 ? hi[k] : lo[k]) - (double)c->position[k]) * forward[k];
        farthest = fmax(farthest, depth);
    }
    farthest = fmin(farthest, c->far_plane);
    double step = camera_depth_step(c, farthest), reversed_step = camera_reversed_depth_step(farthest);
    c->reversed_depth = false;
    if (step <= CAMERA_MAX_DEPTH_STEP * size)
        return true;
    if (reversed_available && reversed_step <= CAMERA_MAX_DEPTH_STEP * size) {
        c->reversed_depth = true;
        return true;
    }
    if (reversed_step <= CAMERA_MAX_DEPTH_STEP * size)
        fprintf(stderr,
                "%s: camera: near %g and far %g: the %d-bit depth step %.3g at the scene's farthest point "
                "(%.3g away) is above %g of its size %.3g, and the GL context has no ARB_clip_control for reversed "
                "depth; raise near\n",
                file, (double)c->near_plane, (double)c->far_plane, CAMERA_DEPTH_BITS, step, farthest,
                CAMERA_MAX_DEPTH_STEP, size);
    else
        fprintf(stderr,
                "%s: camera: near %g and far %g: the depth step at the scene's farthest point (%.3g away), "
                "%.3g with %d bits and %.3g reversed in float, is above %g of its size %.3g; raise near\n",
                file, (double)c->near_plane, (double)c->far_plane, farthest, step, CAMERA_DEPTH_BITS, reversed_step,
                CAMERA_MAX_DEPTH_STEP, size);
    return false;
}

/* The rotation that turns `offset` (from a centre) by yaw about `up` and
 * by pitch towards `up`, stopping 1 degree short of the pole so the basis
 * never degenerates. */
static void camera_orbit_rotation(const float offset[3], const float up_in[3], float yaw, float pitch,
                                  float lowest_deg, mat4 r) {
    vec3 up, side;
    glm_vec3_normalize_to((float *)up_in, up);
    float elevation = asinf(glm_clamp(glm_vec3_dot((float *)offset, up) / glm_vec3_norm((float *)offset), -1, 1));
    float limit = glm_rad(CAMERA_ORBIT_POLE_DEG);
    /* An eye already below the floor may rise to it, never sink. */
    float lowest = fminf(glm_rad(lowest_deg), elevation);
    pitch = glm_clamp(elevation + pitch, fmaxf(lowest, -limit), limit) - elevation;
    glm_vec3_cross(up, (float *)offset, side);
    glm_rotate_make(r, yaw, up);
    if (glm_vec3_norm(side) > 0) {
        mat4 tilt;
        glm_rotate_make(tilt, -pitch, side);
        glm_mat4_mul(r, tilt, r);
    }
}

void camera_orbit(scene_camera *c, float yaw_rad, float pitch_rad, float zoom, float lowest_deg) {
    vec3 offset;
    mat4 r;
    glm_vec3_sub(c->position, c->target, offset);
    camera_orbit_rotation(offset, c->up, yaw_rad, pitch_rad, lowest_deg, r);
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
    camera_orbit_rotation(offset, up, yaw_rad, pitch_rad, CAMERA_ORBIT_ANY, r);
    glm_mat4_mulv3(r, l->direction, 0, l->direction);
    glm_mat4_mulv3(r, offset, 0, offset);
    if (l->type != SCENE_LIGHT_DIRECTIONAL)
        glm_vec3_add((float *)center, offset, l->position);
}
