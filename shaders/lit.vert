#version 330 core
// Scene geometry in world space. gl_Position is invariant so that passes
// which redraw a surface with depth test GL_EQUAL hit exactly the same depth.
layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;

uniform mat4 u_model;
uniform mat3 u_normal_matrix;
uniform mat4 u_view_projection;

out vec3 v_position;
out vec3 v_normal;
invariant gl_Position;

void main() {
    vec4 world = u_model * vec4(in_position, 1.0);
    v_position = world.xyz;
    v_normal = u_normal_matrix * in_normal;
    gl_Position = u_view_projection * world;
}
