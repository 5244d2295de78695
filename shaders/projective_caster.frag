#version 330 core
// The casters black on the white projective texture (demos/projective.c),
// drawn through the light's frustum by shadow_depth.vert; with
// SURFACE_CUT_OUT (a cut-out caster's program) nothing where it has no
// surface.
#ifdef SURFACE_CUT_OUT
#include "surface.glsl"
#endif

out vec4 out_shade;

void main() {
#ifdef SURFACE_CUT_OUT
    if (surface_cut_out())
        discard;
#endif
    out_shade = vec4(0.0);
}
