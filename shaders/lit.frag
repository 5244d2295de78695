#version 330 core
#include "lighting.glsl"
// The lights of a set (u_light_count of them, their indices in
// u_light_list, from render_use_lit's RENDER_LIGHT_BIT set in
// common/gl/render.h) fully visible, plus ambient when u_ambient is 1: the
// unshadowed picture, or one light's share of it. A list rather than a
// test of each light's bit: llvmpipe would run every light's code, masked,
// for each pass of one light.
in vec3 v_position;
in vec3 v_normal;

uniform vec3 u_albedo;
uniform float u_ambient;
uniform int u_light_count;
uniform int u_light_list[SCENE_MAX_LIGHTS];
#ifdef LIT_SOFT_VISIBILITY
// Light u_soft_light's share scaled by the fraction of its area light
// that reaches the pixel, u_soft_scale times the sum accumulated from
// hard shadows at its points (u_soft_scale the inverse of their number;
// common/gl/soft_visibility.h), or from penumbra wedges
// (demos/lib/volume_wedges.h), which may overshoot [0, 1] and are clamped
// to it; the other lights as they are.
uniform int u_soft_light;
uniform sampler2D u_soft_visibility;
uniform float u_soft_scale;
#endif

out vec4 out_color;

void main() {
    // Two-sided: open meshes (the teapot) show their inside.
    vec3 n = normalize(gl_FrontFacing ? v_normal : -v_normal);
    vec3 c = u_ambient * lighting_ambient(u_albedo);
    for (int k = 0; k < u_light_count; k++) {
        vec3 light = lighting_unshadowed(u_light_list[k], v_position, n, u_albedo);
#ifdef LIT_SOFT_VISIBILITY
        if (u_light_list[k] == u_soft_light)
            light *= clamp(texelFetch(u_soft_visibility, ivec2(gl_FragCoord.xy), 0).r * u_soft_scale, 0.0, 1.0);
#endif
        c += light;
    }
    out_color = vec4(c, 1.0);
}
