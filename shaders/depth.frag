#version 330 core
// Depth only: the shadow maps' depth pass (shadow_depth.vert) and the
// camera's depth pre-pass (lit.vert, common/gl/render.h) write nothing
// else; with SURFACE_CUT_OUT (a cut-out object's program) what the object
// lacks is discarded.
//
// With MAP_DEPTH_CLAMP_EMULATED the depth is written here: the light's
// window depth, raised by glPolygonOffset's rule (u_slope_factor times the
// larger of its screen derivatives, plus u_offset_units steps of the
// format: 2^-24 of a 24-bit one, 2^-23 of the depth's power of two in a
// float one), then clamped to [0, 1], as depth clamp does; offset and
// clamp apply to the rasterized depth alone, which this replaces.
#ifdef SURFACE_CUT_OUT
#include "surface.glsl"
#endif

#ifdef MAP_DEPTH_CLAMP_EMULATED
in vec2 v_clip_depth;
uniform float u_slope_factor;
uniform float u_offset_units;
uniform bool u_depth_float;

const float DEPTH_FIXED_BITS = 24.0;
const float DEPTH_MANTISSA_BITS = 23.0;
const float DEPTH_SMALLEST_NORMAL = 1.17549435e-38;
#endif

void main() {
#ifdef SURFACE_CUT_OUT
    if (surface_cut_out())
        discard;
#endif
#ifdef MAP_DEPTH_CLAMP_EMULATED
    float z = 0.5 + 0.5 * v_clip_depth.x / v_clip_depth.y;
    float slope = max(abs(dFdx(z)), abs(dFdy(z)));
    float step = u_depth_float ? exp2(floor(log2(max(abs(z), DEPTH_SMALLEST_NORMAL))) - DEPTH_MANTISSA_BITS)
                               : exp2(-DEPTH_FIXED_BITS);
    gl_FragDepth = clamp(z + u_slope_factor * slope + u_offset_units * step, 0.0, 1.0);
#endif
}
