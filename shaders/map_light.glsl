// One light's share in the camera pass (shaders/map.frag), for maps
// of the sampler type MAP_SAMPLER (and MAP_RAW_SAMPLER, the
// same map read as depth, for soft lights, or its moment map, for moment
// filters): included once by each kind's
// file (map_2d.glsl: sampler2DShadow, map_cube.glsl:
// samplerCubeShadow, map_array.glsl: sampler2DArrayShadow), which
// defines for its type, before this file,
//   map_kernel_read(map, offset)  one tap (a kernel tap's offset, in
//                                        the unit the kind filters in) about
//                                        the point its visibility set up;
// and after it
//   map_texel_world(map, i, k, p) world size of a texel of light i's
//                                        map at p (k: the texel's kind, a
//                                        MAP_TEXEL_*, for 2D maps);
//   map_visibility(map, raw, bounds, i, p, lit_p, b, soft, moments,
//                  texel, needed)
//                                        the filtered comparison at p, its
//                                        map depth lowered by b first, by
//                                        the settings' kernel or, soft, by
//                                        map_soft.glsl's, or with
//                                        `moments` from raw's moments
//                                        (moments.glsl), or in a marking
//                                        pass by its depth bounds
//                                        (map.glsl, map_bounds_light),
//                                        which say lit only where lit at
//                                        lit_p (on the ray from p to the
//                                        light) too (texel: a
//                                        texel's world size there; the
//                                        screen derivatives it takes come
//                                        first, in uniform control flow;
//                                        needed false then reads no map: the
//                                        share is 0 there whatever it says);
//   map_texel_coord(map, i, p)    p's position in the map, in texels
//                                        (the lecture's texel overlays);
//   map_translucent_near(transmittance, i, p, b)  whether a texel within
//                                        one of p's holds translucent
//                                        casters before p;
//   map_transmittance(transmittance, i, p, b)  the share of each channel
//                                        light i's translucent casters let
//                                        through to p, its map depth lowered
//                                        by b (map.glsl, map_transmitted).
// GLSL picks each by the sampler's type: the same names for both kinds.

float map_texel_world(MAP_SAMPLER map, int i, int texel_kind, vec3 p);
float map_visibility(MAP_SAMPLER map, MAP_RAW_SAMPLER raw, sampler2D bounds, int i, vec3 p, vec3 lit_p,
                            float depth_bias, bool soft, bool moments, float texel, bool needed);
vec2 map_texel_coord(MAP_SAMPLER map, int i, vec3 p);
vec3 map_transmittance(MAP_RAW_SAMPLER transmittance, int i, vec3 p, float depth_bias);
bool map_translucent_near(MAP_RAW_SAMPLER transmittance, int i, vec3 p, float depth_bias);

// The kernel's visibility: the early-out's rim, then where it disagrees
// (or without the early-out) the weighted sum of every tap.
float map_kernel_filter(MAP_SAMPLER map, vec2 fraction, float unit) {
    mat2 rotation = map_kernel_rotation();
    if (map_shape == MAP_KERNEL_TENT)
        map_tent_place(fraction);
    vec4 rim;
    if (map_kernel_early_out()) {
        for (int k = 0; k < MAP_RIM_TAPS; k++)
            rim[k] = map_kernel_read(map, map_kernel_tap(map_kernel_rim(k), rotation, unit).xy);
        float agreed = map_rim_agreement(rim);
        if (agreed >= 0.0)
            return agreed;
    }
    // The rim's taps are not read twice: the sum takes them in their
    // place in the list, so that it is the one without the early-out.
    float sum = 0.0;
    for (int i = 0; i < map_kernel_loop_taps(); i++) {
        vec3 tap = map_kernel_tap(i, rotation, unit);
        int k = map_kernel_early_out() ? map_kernel_rim_index(i) : -1;
        sum += tap.z * (k >= 0 ? rim[k] : map_kernel_read(map, tap.xy));
    }
    return sum / map_kernel_norm();
}

// Light i's share at this fragment (normal n) where its map (texels of
// kind texel_kind) lets it through, filtered as a soft light's where
// `soft` (an area light: map_soft.glsl), from its moment map where
// `moments`, filtered per channel by its transmittance map where
// `transmits` (map.h, "Translucent casters"), with the lecture's
// overlays. Where the light adds nothing unshadowed (beyond its range,
// outside a spot's cone, facing away) or reaches only through a closed
// caster (map_through_closed) the filter is skipped: the share is 0
// whatever it would say.
vec3 map_share(MAP_SAMPLER map, MAP_RAW_SAMPLER raw, MAP_RAW_SAMPLER transmittance, sampler2D bounds, int i,
               int texel_kind, bool soft, bool moments, bool transmits, vec3 n) {
    vec3 to_light = lighting_to_light(i, v_position);
    // Both biases move the point where the map is read, in world units
    // scaled by the map's texel there, so they hold at any map size,
    // distance and scene scale. The normal offset grows with the slope
    // (sin of the angle to the light), where a texel spans most depth.
    float texel = map_texel_world(map, i, texel_kind, v_position);
    float cos_theta = clamp(dot(n, to_light), 0.0, 1.0);
    float sin_theta = sqrt(1.0 - cos_theta * cos_theta);
    vec3 normal_offset = n * (u_normal_offset * texel * sin_theta);
    vec3 p = v_position + to_light * (u_constant_bias * texel) + normal_offset;
    vec3 unshadowed =
        map_through_closed(i, to_light) ? vec3(0.0) : lighting_unshadowed(i, v_position, n, surface_albedo);
    bool needed = unshadowed != vec3(0.0) || map_show_texel_size;
    map_penumbra_estimate = MAP_NO_PENUMBRA;
    map_soft_search_unsure = false;
    // Rays (map.h, "Rays"): where the map's filter is unsure (strictly
    // between 0 and 1), or at every pixel without reading the map, shadow
    // rays decide, as the reference's (which needs no horizon's share).
    // A hard light's map lit by the full bias is sure only where it is
    // lit by MAP_SURE_LIT_BIAS_SHARE of it too: the depth bounds ask that
    // of p_near at once, the kernel in a read of its own, first. Where
    // p_near lies on p's ray from the light (a sun's rays are parallel; a
    // positional light's pass through both without a normal offset) it
    // reads the same taps as p, each against a depth further from the
    // light, so a tap lit there is lit at p: p_near wholly lit makes the
    // pixel sure and lit, partly lit unsure (p is lit at least as much),
    // and only a pixel p_near finds wholly in shadow reads p.
    bool lit = unshadowed != vec3(0.0);
    bool sure_lit_read = !soft && map_rays == MAP_RAYS_UNSURE;
    vec3 p_near = v_position + to_light * (MAP_SURE_LIT_BIAS_SHARE * u_constant_bias * texel) + normal_offset;
    float depth_bias = max(u_depth_bias.x * (1.0 - cos_theta), u_depth_bias.y);
    // The read at p_near: a marking pass makes it too for a light its
    // kernel reads (not its depth bounds), so that its marks hold every
    // pixel the tracing pass would trace. Both reads stand in uniform
    // control flow (near_read is every pixel's), which their screen
    // derivatives need; needed false reads no map, and says 1.
    bool near_read = sure_lit_read && !(map_mark_rays && map_bounds_light(i));
    float near_visibility = 1.0;
    if (near_read)
        near_visibility =
            map_visibility(map, raw, bounds, i, p_near, p_near, depth_bias, soft, moments, texel, needed && lit);
    bool near_decides = near_read && (u_normal_offset == 0.0 || lights_position[i].w == 0.0);
    float visibility =
        map_visibility(map, raw, bounds, i, p, sure_lit_read ? p_near : p, depth_bias, soft, moments, texel,
                       needed && map_rays != MAP_RAYS_ALL && !(near_decides && near_visibility > 0.0));
    bool unsure = lit && ((visibility > 0.0 && visibility < 1.0) || (visibility == 1.0 && near_visibility < 1.0));
    // An area light's pixel PCSS calls wholly lit or wholly in shadow is
    // sure only where its blocker search proves it too. Lit: the search
    // taps can miss a thin caster, so only where no caster's box is near
    // the cone. In shadow: the filter's disc is sized by the blockers'
    // mean distance, narrower than the penumbra where blockers lie at
    // several distances (a leg before a body), so only where the search,
    // over the whole cone, found every tap blocked.
    if (soft && lit && map_rays != MAP_RAYS_OFF) {
        if (visibility == 1.0)
            unsure = !map_light_cone_clear(i);
        else if (visibility == 0.0)
            unsure = map_soft_search_unsure;
    }
    // A translucent caster's shadow is the texel's, hard and unfiltered:
    // with rays, a hard light's pixel within a texel of one is unsure
    // (the rays filter through the panes as the reference's do; an area
    // light's cone meets their boxes).
    if (transmits && !soft && lit && map_rays == MAP_RAYS_UNSURE && visibility > 0.0)
        unsure = unsure || map_translucent_near(transmittance, i, p, depth_bias);
    bool traced = lit && (map_rays == MAP_RAYS_ALL || (map_rays == MAP_RAYS_UNSURE && unsure));
    // A marking pass leaves the pixel to the tracing pass after it, which
    // draws it again whole: what it shades here is drawn over.
    map_rays_marked = map_rays_marked || (map_mark_rays && traced);
    traced = traced && !map_mark_rays;
    vec3 through;
    if (traced) {
        through = map_ray_visibility(i, soft);
    } else {
        if (soft)
            visibility *= map_horizon_share(i, normalize(map_face_normal), to_light, v_position);
        through = vec3(visibility);
        if (transmits && needed && visibility > 0.0)
            through *= map_transmittance(transmittance, i, p, depth_bias);
    }
    vec3 c = through * unshadowed;
    if (map_show_unsure && (unsure || traced))
        c = mix(c, MAP_UNSURE_TINT, MAP_UNSURE_TINT_SHARE);
    // Lines one pixel wide where texels meet: how big a texel is on screen
    // is what aliasing is made of. A grid finer than two pixels a line is
    // above the picture's Nyquist limit: it shows moire, not texels (a
    // 2048 map on simple: a third of a pixel a texel). So the lines run
    // every 2^k texels, k the least (per pixel, from the screen derivative)
    // that puts them MAP_TEXEL_LINE_MIN_PIXELS apart or more: every
    // texel where texels are that big, else blocks of 2, 4, 8... texels.
    vec2 map_texel = map_texel_coord(map, i, v_position);
    vec2 texels_per_pixel = max(fwidth(map_texel), vec2(MAP_MIN_TEXEL_FWIDTH));
    float block = exp2(max(ceil(log2(max(texels_per_pixel.x, texels_per_pixel.y) *
                                     MAP_TEXEL_LINE_MIN_PIXELS)), 0.0));
    vec2 distance_to_edge = abs(fract(map_texel / block - 0.5) - 0.5) * block / texels_per_pixel;
    float edge = 1.0 - min(min(distance_to_edge.x, distance_to_edge.y), 1.0);
    if (map_show_texels)
        c *= 1.0 - MAP_TEXEL_LINE_DARKENING * edge;
    // The aliasing measure of the perspective shadow map papers (dp/ds):
    // a texel's size in pixels, the square root of the pixel area it
    // covers. Blue: a quarter pixel or less, green: one, red: 32 or more.
    if (map_show_texel_size) {
        vec2 dx = dFdx(map_texel), dy = dFdy(map_texel);
        float texel_pixels = inversesqrt(max(abs(dx.x * dy.y - dx.y * dy.x), MAP_HEAT_MIN_AREA));
        c = texel_heat_shade(texel_heat_color(log2(texel_pixels)), c);
    }
    // PCSS's estimate of the penumbra's radius in world units, on the
    // texel-size ramp moved to the penumbra overlay's ends (map.h);
    // left as it is where the blocker search found nothing.
    if (map_show_penumbra && map_penumbra_estimate != MAP_NO_PENUMBRA)
        c = texel_heat_shade(texel_heat_color(log2(max(map_penumbra_estimate, MAP_MIN_PENUMBRA)) -
                                              float(MAP_PENUMBRA_LOG2_MIN - MAP_HEAT_LOG2_MIN)),
                             c);
    return c;
}
