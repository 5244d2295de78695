#version 330 core
// Lines and quads drawn over the picture for lectures (demos/lib/map_overlay.c):
// world-space lines (u_view_projection) or a screen quad (identity).
layout(location = 0) in vec3 in_position;

uniform mat4 u_view_projection;

out vec2 v_uv;

void main() {
    v_uv = in_position.xy * 0.5 + 0.5;
    gl_Position = u_view_projection * vec4(in_position, 1.0);
}
