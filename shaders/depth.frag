#version 330 core
// Depth only: the shadow maps' depth pass (shadow_depth.vert) and the
// camera's depth pre-pass (lit.vert, common/gl/render.h) write nothing
// else; with SURFACE_CUT_OUT (a cut-out object's program) what the object
// lacks is discarded. With MAP_DEPTH_CLAMP_EMULATED the depth is written
// here, offset and clamped (depth_offset.glsl).
#ifdef SURFACE_CUT_OUT
#include "surface.glsl"
#endif
#ifdef MAP_DEPTH_CLAMP_EMULATED
#include "depth_offset.glsl"
#endif

void main() {
#ifdef SURFACE_CUT_OUT
    if (surface_cut_out())
        discard;
#endif
#ifdef MAP_DEPTH_CLAMP_EMULATED
    gl_FragDepth = depth_offset_clamped(depth_window());
#endif
}
