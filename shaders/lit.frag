#version 330 core
#include "lighting.glsl"
// The lights of the set u_lights (bit i: light i, RENDER_LIGHT_BIT in
// common/gl/render.h) fully visible, plus ambient when u_ambient is 1: the
// unshadowed picture, or one light's share of it.
in vec3 v_position;
in vec3 v_normal;

uniform vec3 u_albedo;
uniform float u_ambient;
uniform uint u_lights;

out vec4 out_color;

void main() {
    // Two-sided: open meshes (the teapot) show their inside.
    vec3 n = normalize(gl_FrontFacing ? v_normal : -v_normal);
    vec3 c = u_ambient * lighting_ambient(u_albedo);
    for (int i = 0; i < lights_count.x; i++)
        if ((u_lights & (1u << uint(i))) != 0u)
            c += lighting_unshadowed(i, v_position, n, u_albedo);
    out_color = vec4(c, 1.0);
}
