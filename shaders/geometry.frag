#version 330 core
in vec3 g_world;
flat in vec3 g_face_normal;

uniform vec3 u_eye;
uniform float u_object;

layout(location = 0) out vec4 out_normal_distance; // face normal towards the eye, distance
layout(location = 1) out vec4 out_position_id;     // world position, object index

void main() {
    vec3 n = normalize(g_face_normal);
    vec3 to_eye = u_eye - g_world;
    out_normal_distance = vec4(dot(n, to_eye) < 0.0 ? -n : n, length(to_eye));
    out_position_id = vec4(g_world, u_object);
}
