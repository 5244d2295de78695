#version 330 core
// A translucent caster's share of the light, into a shadow map's
// transmittance map (demos/lib/map.c, map_transmit_layer; with
// shadow_depth.vert): rgb its transmittance (surface.glsl), blended
// multiplicatively so that a texel holds the product of every caster
// drawn over it; alpha the fragment's depth, raised by its slope across
// the texel (depth_offset.glsl), blended by MIN: the nearest translucent
// caster, which a receiver must lie beyond to be filtered. With
// MAP_DEPTH_CLAMP_EMULATED the depth tested against the map is written
// here (depth_offset.glsl), and a pane before the near plane holds the
// near depth, as depth clamp draws it.
#include "surface.glsl"
#include "depth_offset.glsl"

layout(location = 0) out vec4 out_transmittance;

void main() {
#ifdef MAP_DEPTH_CLAMP_EMULATED
    float z = depth_window();
    gl_FragDepth = depth_offset_clamped(z);
    float depth = clamp(z, 0.0, 1.0);
#else
    float z = gl_FragCoord.z, depth = z;
#endif
    out_transmittance = vec4(surface_transmittance(), depth + u_slope_factor * depth_slope(z));
}
