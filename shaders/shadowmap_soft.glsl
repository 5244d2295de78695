// Percentage-closer soft shadows (Fernando, "Percentage-closer soft
// shadows", SIGGRAPH 2005 sketch) for an area light (scene "radius" > 0),
// in the camera pass (shaders/shadowmap.frag): included once by each kind
// of map's file, after shadowmap_light.glsl, for its SHADOW_MAP_SAMPLER
// (comparisons) and SHADOW_MAP_RAW_SAMPLER (the same texture read as depth,
// on a unit of its own). That file defines, before this one,
//   shadow_map_raw_read(raw, offset)        the stored texel a tap's offset
//                                           (in the kernel's unit) away (its
//                                           depth: .r);
//   shadow_map_reference_depth(raw, offset) the receiver's own depth there
//                                           (its plane, as receiver-plane
//                                           taps follow it), biased as its
//                                           comparisons are;
//   shadow_map_soft_distance(raw, i, depth) how far from light i (along its
//                                           rays; a directional light: along
//                                           its direction, up to a constant)
//                                           a stored depth at the point lies.
// (The raw sampler picks each by its type: the same names for every kind.)
//
// The three steps, each in the light's own measure:
//   1. the blocker search: the depths stored inside the region of the map
//      through which the light's disc sees the point, its rays' cone cut
//      at the map's near plane (the nearest caster); of those nearer the
//      light than the receiver, their distance from the light averaged
//      with weights 1 / (d_r - d_b): a blocker nearer the receiver hides
//      more of the light from it, so a thin caster standing on the
//      receiver, whose top and foot both fall in the search, casts the
//      foot's narrow penumbra where the foot is (at least a texel of gap:
//      nearer is not resolved);
//   2. the penumbra by similar triangles: a disc of radius R (world) at
//      the light, a blocker at distance d_b, the receiver at d_r: a
//      penumbra of radius R (d_r - d_b) / d_b on the receiver; a sun of
//      angular radius a: tan(a) (d_r - d_b);
//   3. percentage-closer filtering over a disc of that radius.
// Both discs are Vogel's golden-angle spirals, rotated per pixel by the
// pixel's hash (no noise over time: frames stay deterministic), clamped
// to the hard default's disc (SHADOW_MAP_POISSON_SCALE_TEXELS / 2: a
// penumbra narrower than that is filtered as a hard shadow is) and
// SHADOW_MAP_SOFT_MAX_TEXELS (C culls casters with that reach).

// Light i's visibility at the point its kind's visibility set up; the
// texel's world size there (texel_world) and the unit of the kind's tap
// offsets per texel (unit: the map's size for map coordinates, 1 for
// texels).
float shadow_map_soft_filter(SHADOW_MAP_SAMPLER map, SHADOW_MAP_RAW_SAMPLER raw, int i, float texel_world, float unit) {
    float a = shadow_map_pixel_angle();
    mat2 rotation = mat2(cos(a), sin(a), -sin(a), cos(a));
    float d_r = shadow_map_soft_distance(raw, i, shadow_map_reference_depth(raw, vec2(0.0)));
    // 1. The blocker search, over the light's cone cut at the near plane.
    float search = shadow_map_soft_texels(shadow_map_penumbra_world(i, d_r, shadow_map_soft_distance(raw, i, 0.0)),
                                          texel_world) / unit;
    float blocker_distance = 0.0, blocker_weight = 0.0;
    for (int k = 0; k < SHADOW_MAP_SOFT_SEARCH_TAPS; k++) {
        vec2 offset = shadow_map_vogel_tap(k, SHADOW_MAP_SOFT_SEARCH_TAPS, rotation) * search;
        float depth = shadow_map_raw_read(raw, offset).r;
        if (depth < shadow_map_reference_depth(raw, offset)) {
            float distance = shadow_map_soft_distance(raw, i, depth);
            float weight = 1.0 / max(d_r - distance, texel_world);
            blocker_distance += weight * distance;
            blocker_weight += weight;
        }
    }
    if (blocker_weight == 0.0)
        return 1.0;
    // 2. The penumbra's radius from the blockers' weighted distance.
    float d_b = blocker_distance / blocker_weight;
    float world = shadow_map_penumbra_world(i, d_r, d_b);
    if (shadow_map_show_penumbra)
        shadow_map_penumbra_estimate = world;
    float radius = shadow_map_soft_texels(world, texel_world) / unit;
    // 3. Percentage-closer filtering over it.
    float sum = 0.0;
    for (int k = 0; k < SHADOW_MAP_SOFT_FILTER_TAPS; k++)
        sum += shadow_map_kernel_read(map, shadow_map_vogel_tap(k, SHADOW_MAP_SOFT_FILTER_TAPS, rotation) * radius);
    return sum / float(SHADOW_MAP_SOFT_FILTER_TAPS);
}
