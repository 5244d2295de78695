// A flat map's filtered comparison, for the camera pass's 2D maps
// (shadowmap_2d.glsl) and array maps' layers (shadowmap_array.glsl):
// included once by each, after shadowmap_light.glsl, for its
// SHADOWMAP_SAMPLER. The point and its depth gradient are set here for the
// type's shadowmap_kernel_read (declared once, in shadowmap.glsl).

// The filtered comparison about uvz (map coordinates and depth) of a map
// `size` texels on a side, its depth lowered by depth_bias first, with the
// receiver's depth gradient for receiver-plane taps. Outside the map
// nothing was rendered: lit, never a wrapped read.
float shadowmap_flat_filter(SHADOWMAP_SAMPLER map, vec3 uvz, vec2 gradient, float size, float depth_bias) {
    if (any(lessThan(uvz.xy, vec2(0.0))) || any(greaterThan(uvz.xy, vec2(1.0))))
        return 1.0;
    shadowmap_point = vec3(uvz.xy, min(uvz.z - depth_bias, 1.0));
    shadowmap_gradient = gradient;
    if (shadowmap_shape == SHADOW_MAP_KERNEL_SINGLE)
        return shadowmap_kernel_read(map, vec2(0.0));
    vec2 texel = uvz.xy * size;
    return shadowmap_kernel_filter(map, texel - floor(texel + 0.5), size);
}
