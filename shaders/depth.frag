#version 330 core
// Depth only: the shadow maps' depth pass (shadow_depth.vert) and the
// camera's depth pre-pass (lit.vert, common/gl/render.h) write nothing
// else; with SURFACE_CUT_OUT (a cut-out object's program) what the object
// lacks is discarded.
#ifdef SURFACE_CUT_OUT
#include "surface.glsl"
#endif

void main() {
#ifdef SURFACE_CUT_OUT
    if (surface_cut_out())
        discard;
#endif
}
