// A flat map's filtered comparison, for the camera pass's 2D maps
// (map_2d.glsl) and array maps' layers (map_array.glsl):
// included once by each, after map_light.glsl, for its
// MAP_SAMPLER and MAP_RAW_SAMPLER. The point and its depth
// gradient are set here for the type's map_kernel_read (declared
// once, in map.glsl) and blocker reads.

// The receiver's depth an offset (map coordinates) from the point, along
// its plane where the gradient follows it.
float map_reference_depth(MAP_RAW_SAMPLER raw, vec2 offset) {
    return map_point.z + dot(map_gradient, offset);
}

float map_soft_filter(MAP_SAMPLER map, MAP_RAW_SAMPLER raw, int i, float texel_world, float unit);

// The filtered comparison about uvz (map coordinates and depth) of light
// i's map, its depth lowered by depth_bias first, with the receiver's
// depth gradient for receiver-plane taps: the settings' kernel, or a soft
// light's (map_soft.glsl; texel: a texel's world size at the
// point), or from raw's moments (`moments`, moments.glsl). Outside the
// map nothing was rendered: lit, never a wrapped read.
float map_flat_filter(MAP_SAMPLER map, MAP_RAW_SAMPLER raw, int i, vec3 uvz, vec2 gradient,
                             float depth_bias, bool soft, bool moments, float texel) {
    if (any(lessThan(uvz.xy, vec2(0.0))) || any(greaterThan(uvz.xy, vec2(1.0))))
        return 1.0;
    map_point = vec3(uvz.xy, min(uvz.z - depth_bias, 1.0));
    map_gradient = gradient;
    if (moments)
        return moments_visibility(map_raw_read(raw, vec2(0.0)), map_point.z);
    if (soft)
        return map_soft_filter(map, raw, i, texel, u_map_size[i]);
    if (map_shape == MAP_KERNEL_SINGLE)
        return map_kernel_read(map, vec2(0.0));
    vec2 map_texel = uvz.xy * u_map_size[i];
    return map_kernel_filter(map, map_texel - floor(map_texel + 0.5), u_map_size[i]);
}

// Whether a texel of the 3 x 3 about uvz's (map coordinates and depth,
// clamped to the map) holds translucent casters before the point, its
// depth lowered by depth_bias: the type's map_transmit_fetch reads them.
bool map_flat_translucent_near(MAP_RAW_SAMPLER transmittance, int i, vec3 uvz, float depth_bias) {
    int size = int(u_map_size[i]);
    ivec2 centre = ivec2(floor(uvz.xy * float(size)));
    bool near = false;
    for (int y = -1; y <= 1; y++)
        for (int x = -1; x <= 1; x++) {
            ivec2 texel = clamp(centre + ivec2(x, y), ivec2(0), ivec2(size - 1));
            near = near || map_translucent_before(map_transmit_fetch(transmittance, texel), uvz.z - depth_bias);
        }
    return near;
}
