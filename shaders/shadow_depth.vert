#version 330 core
// Depth from the light (demos/lib/map.c), and the projective technique's
// casters; the texture coordinates for a cut-out object's fragments
// (depth.frag).
layout(location = 0) in vec3 in_position;
layout(location = 2) in vec2 in_uv;

uniform mat4 u_model;
uniform mat4 u_view_projection; // the light's

out vec2 v_uv;

void main() {
    v_uv = in_uv;
    gl_Position = u_view_projection * (u_model * vec4(in_position, 1.0));
}
