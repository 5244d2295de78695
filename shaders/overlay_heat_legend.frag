#version 330 core
// The texel-size overlay's legend: its colour bar, a texel's size in
// pixels from u_log2_range.x (left) to u_log2_range.y (right), in the
// picture's colours at full brightness (texel_heat.glsl).
#include "texel_heat.glsl"

in vec2 v_uv;

uniform vec2 u_log2_range;

out vec4 out_color;

void main() { out_color = vec4(texel_heat_color(mix(u_log2_range.x, u_log2_range.y, v_uv.x)), 1.0); }
