#version 330 core
in vec3 g_world;
flat in vec3 g_face_normal;
flat in vec4 g_plane;

uniform vec3 u_eye;
uniform float u_object;
// The object is huge seen from the eye (common/gl/render.h): its position
// interpolated from corners far away is off, so the pixel's eye ray meets
// its triangle's plane instead.
uniform bool u_exact;
#include "eye_ray.glsl"
// A cut-out object's program (SURFACE_CUT_OUT): no surface where it has
// none.
#ifdef SURFACE_CUT_OUT
#include "surface.glsl"
#endif

layout(location = 0) out vec4 out_normal_distance; // face normal towards the eye, distance
layout(location = 1) out vec4 out_position_id;     // world position, object index

void main() {
#ifdef SURFACE_CUT_OUT
    if (surface_cut_out())
        discard;
#endif
    vec3 n = normalize(g_face_normal);
    vec3 to_eye = u_eye - g_world;
    vec3 world = g_world;
    if (u_exact) {
        vec3 ray = eye_ray_world();
        float t = g_plane.w / dot(g_plane.xyz, ray);
        if (t > 0.0 && !isinf(t)) { // else edge-on, or no normal: the interpolated one
            to_eye = -t * ray;
            world = u_eye - to_eye;
        }
    }
    out_normal_distance = vec4(dot(n, to_eye) < 0.0 ? -n : n, length(to_eye));
    out_position_id = vec4(world, u_object);
}
