#version 330 core
// A translucent caster's share of the light, into a shadow map's
// transmittance map (demos/lib/map.c, map_transmit_layer; with
// shadow_depth.vert): rgb its transmittance (surface.glsl), blended
// multiplicatively so that a texel holds the product of every caster
// drawn over it; alpha the fragment's depth, raised by its slope across
// the texel (u_slope_factor times the larger of its screen derivatives,
// glPolygonOffset's rule), blended by MIN: the nearest translucent
// caster, which a receiver must lie beyond to be filtered.
#include "surface.glsl"

uniform float u_slope_factor;

layout(location = 0) out vec4 out_transmittance;

void main() {
    float z = gl_FragCoord.z;
    float slope = max(abs(dFdx(z)), abs(dFdy(z)));
    out_transmittance = vec4(surface_transmittance(), z + u_slope_factor * slope);
}
