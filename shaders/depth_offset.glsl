// glPolygonOffset's slope-scaled bias, for the shadow maps' passes that
// redo it (depth.frag, transmittance.frag): u_slope_factor times the
// larger of the depth's screen derivatives.
//
// With MAP_DEPTH_CLAMP_EMULATED (a cube's depth pass where the GL has no
// depth clamp: shadow_depth.vert hands over the light's clip z and w, and
// rasterizes every fragment at z 0) the window depth comes from those,
// and the depth written is it raised by the whole offset (the slope term
// plus u_offset_units steps of the format: 2^-24 of a 24-bit one, 2^-23
// of the depth's power of two in a float one), then clamped to [0, 1],
// as depth clamp does: offset and clamp apply to the rasterized depth
// alone, which this replaces.
uniform float u_slope_factor;

float depth_slope(float z) { return max(abs(dFdx(z)), abs(dFdy(z))); }

#ifdef MAP_DEPTH_CLAMP_EMULATED
in vec2 v_clip_depth;
uniform float u_offset_units;
uniform bool u_depth_float;

const float DEPTH_FIXED_BITS = 24.0;
const float DEPTH_MANTISSA_BITS = 23.0;
const float DEPTH_SMALLEST_NORMAL = 1.17549435e-38;

// The fragment's window depth from the light's clip z and w.
float depth_window() { return 0.5 + 0.5 * v_clip_depth.x / v_clip_depth.y; }

// Window depth z as the GL would test and store it: offset, then clamped.
float depth_offset_clamped(float z) {
    float step = u_depth_float ? exp2(floor(log2(max(abs(z), DEPTH_SMALLEST_NORMAL))) - DEPTH_MANTISSA_BITS)
                               : exp2(-DEPTH_FIXED_BITS);
    return clamp(z + u_slope_factor * depth_slope(z) + u_offset_units * step, 0.0, 1.0);
}
#endif
