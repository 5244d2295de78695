#version 330 core
// The receivers' pass of demos/projective.c: the casters' black-and-white
// image from the light, projected onto each receiver pixel (lit.vert with
// LIT_PROJECTED: its eye-linear texture coordinates, divided here). The
// fragment survives, and marks the stencil, where the image is black; it
// is discarded where the image is white or where the point lies no
// farther from the light than the nearest caster (the back-projection
// cut, u_cut), which no caster can shadow.
in vec4 v_projected;
in float v_light_depth;

uniform sampler2D u_projected;
uniform float u_nearest; // the casters' nearest depth
uniform bool u_cut;

void main() {
    if ((u_cut && v_light_depth <= u_nearest) || v_projected.w == 0.0)
        discard;
    // The nearest texel, white beyond the image's border.
    ivec2 size = textureSize(u_projected, 0);
    ivec2 texel = ivec2(floor(v_projected.xy / v_projected.w * vec2(size)));
    if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, size)) ||
        texelFetch(u_projected, texel, 0).r * 100.0 >= float(PROJECTIVE_LIT_PERCENT))
        discard;
}
