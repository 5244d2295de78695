#version 330 core
// Depth from the light (demos/lib/map.c): only the depth buffer is
// written, so the fragment stage is empty.
layout(location = 0) in vec3 in_position;

uniform mat4 u_model;
uniform mat4 u_view_projection; // the light's

void main() {
    gl_Position = u_view_projection * (u_model * vec4(in_position, 1.0));
}
