#version 330 core
#include "lighting.glsl"
#include "surface.glsl"
// The lights of the set LIT_LIGHTS (bit i: slot i of the bound light
// group, common/gl/render.h), fully visible, plus ambient
// when u_ambient is 1: the unshadowed picture, or one light's share of it.
// C compiles one program per set on its first use (render_lit_load), so
// that each light's code is there only when it is in the set and reads
// its block entries at constant indices, as the shadow maps' camera pass
// does (map.frag): read from a list in uniforms, llvmpipe would run
// the loop's every access as a gather, for every pixel.
in vec3 v_position;
in vec3 v_normal;

uniform float u_ambient;
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

// Light i's share at this fragment, whose normal (towards the eye) is n.
vec3 lit_light(int i, vec3 n) {
    vec3 light = lighting_unshadowed(i, v_position, n, surface_albedo);
#ifdef LIT_SOFT_VISIBILITY
    if (i == u_soft_light)
        light *= clamp(texelFetch(u_soft_visibility, ivec2(gl_FragCoord.xy), 0).r * u_soft_scale, 0.0, 1.0);
#endif
    return light;
}

#if SHADER_PASS_LIGHTS != 8
#error "lit.frag lists SHADER_PASS_LIGHTS lights one by one: one LIT_LIGHT line each"
#endif
// Light i's share where it is in the set (a constant: else no code).
#define LIT_LIGHT(i) \
    if (((LIT_LIGHTS >> i) & 1) != 0) \
        c += lit_light(i, n)

void main() {
    // Two-sided: open meshes (the teapot) show their inside.
    vec3 n = normalize(gl_FrontFacing ? v_normal : -v_normal);
    surface_begin();
    vec3 c = u_ambient * lighting_ambient(surface_albedo);
    LIT_LIGHT(0);
    LIT_LIGHT(1);
    LIT_LIGHT(2);
    LIT_LIGHT(3);
    LIT_LIGHT(4);
    LIT_LIGHT(5);
    LIT_LIGHT(6);
    LIT_LIGHT(7);
    out_color = vec4(c, 1.0);
}
