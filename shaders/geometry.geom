#version 330 core
// Each triangle's face normal and plane (geometry_face.glsl) for every
// pixel it covers.
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

in vec3 v_world[];
in vec2 v_corner_uv[];
out vec3 g_world;
out vec2 v_uv;
flat out vec3 g_face_normal;
flat out vec4 g_plane;

uniform vec3 u_eye;
#include "geometry_face.glsl"

void main() {
    vec3 n;
    vec4 plane;
    geometry_face(v_world[0], v_world[1], v_world[2], u_eye, n, plane);
    for (int i = 0; i < 3; i++) {
        g_world = v_world[i];
        v_uv = v_corner_uv[i];
        g_face_normal = n;
        g_plane = plane;
        gl_Position = gl_in[i].gl_Position;
        EmitVertex();
    }
    EndPrimitive();
}
