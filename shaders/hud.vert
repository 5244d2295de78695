#version 330 core
// Text quads from stb_easy_font, in pixels from the top-left corner.
layout(location = 0) in vec2 in_position;
layout(location = 1) in vec4 in_color;

uniform vec2 u_viewport;
uniform float u_scale;

out vec4 v_color;

void main() {
    vec2 p = in_position * u_scale / u_viewport;
    gl_Position = vec4(p.x * 2.0 - 1.0, 1.0 - p.y * 2.0, 0.0, 1.0);
    v_color = in_color;
}
