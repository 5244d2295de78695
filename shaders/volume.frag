#version 330 core
// Volumes only count in the stencil (colour writes off); the lecture
// overlays draw them in u_color. With VOLUME_WIDE_COUNT they count in a
// float target instead (demos/lib/volume_wide.h), added by blending: a
// front face adds u_color, a back face takes it away (u_color.r: 1 for
// z-pass, -1 for z-fail, whose faces count behind the surface). With
// VOLUME_NEAR_COUNT it draws ZP+'s near-plane count (volume_near.vert),
// keeping only the part of a caster on the light's side of the plane,
// each face adding u_color.
uniform vec4 u_color;
#ifdef VOLUME_NEAR_COUNT
in float v_light_side;
#endif

out vec4 out_color;

void main() {
#ifdef VOLUME_NEAR_COUNT
    if (v_light_side < 0.0)
        discard;
#endif
#if defined(VOLUME_WIDE_COUNT) && !defined(VOLUME_NEAR_COUNT)
    out_color = gl_FrontFacing ? u_color : -u_color;
#else
    out_color = u_color;
#endif
}
