#version 330 core
// geometry.vert and geometry.geom in one stage, where there are no
// geometry shaders (WebGL 2): every vertex of a triangle carries the
// triangle's three corners (common/gl/capture.c unshares them), so each
// makes the face's normal and plane itself, as geometry.geom does.
layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_corner0;
layout(location = 2) in vec3 in_corner1;
layout(location = 3) in vec3 in_corner2;
layout(location = 4) in vec2 in_uv;

uniform mat4 u_model;
uniform mat4 u_view_projection;
uniform vec3 u_eye;
#include "geometry_face.glsl"

out vec3 g_world;
flat out vec3 g_face_normal;
flat out vec4 g_plane;
out vec2 v_uv; // for a cut-out object's fragments (geometry.frag)
invariant gl_Position;

void main() {
    vec4 world = u_model * vec4(in_position, 1.0);
    g_world = world.xyz;
    v_uv = in_uv;
    geometry_face((u_model * vec4(in_corner0, 1.0)).xyz, (u_model * vec4(in_corner1, 1.0)).xyz,
                  (u_model * vec4(in_corner2, 1.0)).xyz, u_eye, g_face_normal, g_plane);
    gl_Position = u_view_projection * world;
}
