#version 330 core
// Only the naive path (stencil off) writes colour: it multiplies what is
// there by one half per layer, which is what makes overlaps double-dark.
// With SURFACE_CUT_OUT (a cut-out caster's program) nothing is drawn where
// the caster has no surface.
#ifdef SURFACE_CUT_OUT
#include "surface.glsl"
#endif

out vec4 out_color;
#ifdef SHADER_NO_CLIP_DISTANCES
in vec2 v_clip_distances; // planar_shadow.vert's, where no plane clips
#endif

void main() {
#ifdef SURFACE_CUT_OUT
    if (surface_cut_out())
        discard;
#endif
#ifdef SHADER_NO_CLIP_DISTANCES
    if (any(lessThan(v_clip_distances, vec2(0.0))))
        discard;
#endif
    out_color = vec4(0.5);
}
