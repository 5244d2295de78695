// Percentage-closer soft shadows (Fernando, "Percentage-closer soft
// shadows", SIGGRAPH 2005 sketch) for an area light (scene "radius" > 0),
// in the camera pass (shaders/map.frag): included once by each kind
// of map's file, after map_light.glsl, for its MAP_SAMPLER
// (comparisons) and MAP_RAW_SAMPLER (the same texture read as depth,
// on a unit of its own). That file defines, before this one,
//   map_raw_read(raw, offset)        the stored texel a tap's offset
//                                           (in the kernel's unit) away (its
//                                           depth: .r);
//   map_reference_depth(raw, offset) the receiver's own depth there
//                                           (its plane, as receiver-plane
//                                           taps follow it), biased as its
//                                           comparisons are;
//   map_soft_distance(raw, i, depth) how far from light i (along its
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
//      nearer is not resolved); an umbra is sure only where every tap
//      of a search not clamped short of the cone is blocked
//      (map_soft_search_unsure: the hybrid traces the rest);
//   2. the penumbra by similar triangles: a disc of radius R (world) at
//      the light, a blocker at distance d_b, the receiver at d_r: a
//      penumbra of radius R (d_r - d_b) / d_b on the receiver; a sun of
//      angular radius a: tan(a) (d_r - d_b);
//   3. percentage-closer filtering over a disc of that radius.
// Both discs are Vogel's golden-angle spirals, rotated per pixel by the
// pixel's hash (no noise over time: frames stay deterministic), clamped
// to the hard default's disc (MAP_POISSON_SCALE_TEXELS / 2: a
// penumbra narrower than that is filtered as a hard shadow is) and
// MAP_SOFT_MAX_TEXELS (C culls casters with that reach).

// Light i's visibility at the point its kind's visibility set up; the
// texel's world size there (texel_world) and the unit of the kind's tap
// offsets per texel (unit: the map's size for map coordinates, 1 for
// texels).
float map_soft_filter(MAP_SAMPLER map, MAP_RAW_SAMPLER raw, int i, float texel_world, float unit) {
    float a = map_pixel_angle();
    mat2 rotation = mat2(cos(a), sin(a), -sin(a), cos(a));
    float d_r = map_soft_distance(raw, i, map_reference_depth(raw, vec2(0.0)));
    // 1. The blocker search, over the light's cone cut at the near plane.
    float cone_world = map_penumbra_world(i, d_r, map_soft_distance(raw, i, 0.0));
    float search = map_soft_texels(cone_world, texel_world) / unit;
    float blocker_distance = 0.0, blocker_weight = 0.0;
    int blocker_count = 0;
    for (int k = 0; k < MAP_SOFT_SEARCH_TAPS; k++) {
        vec2 offset = map_vogel_tap(k, MAP_SOFT_SEARCH_TAPS, rotation) * search;
        float depth = map_raw_read(raw, offset).r;
        if (depth < map_reference_depth(raw, offset)) {
            float distance = map_soft_distance(raw, i, depth);
            float weight = 1.0 / max(d_r - distance, texel_world);
            blocker_distance += weight * distance;
            blocker_weight += weight;
            blocker_count++;
        }
    }
    map_soft_search_unsure =
        blocker_count < MAP_SOFT_SEARCH_TAPS || cone_world > float(MAP_SOFT_MAX_TEXELS) * texel_world;
    if (blocker_weight == 0.0)
        return 1.0;
    // 2. The penumbra's radius from the blockers' weighted distance.
    float d_b = blocker_distance / blocker_weight;
    float world = map_penumbra_world(i, d_r, d_b);
    if (map_show_penumbra)
        map_penumbra_estimate = world;
    float radius = map_soft_texels(world, texel_world) / unit;
    // 3. Percentage-closer filtering over it.
    float sum = 0.0;
    for (int k = 0; k < MAP_SOFT_FILTER_TAPS; k++)
        sum += map_kernel_read(map, map_vogel_tap(k, MAP_SOFT_FILTER_TAPS, rotation) * radius);
    return sum / float(MAP_SOFT_FILTER_TAPS);
}
