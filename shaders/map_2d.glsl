// The camera pass's 2D maps (shaders/map.frag): a spot or
// directional light's (demos/shadowmap.c, and demos/cascades.c's spot
// lights), or any light's warped map (demos/psm.c). Light i's map is
// u_maps_2d[i] and the uniforms of index i.

uniform sampler2DShadow u_maps_2d[SHADER_PASS_LIGHTS]; // compare mode on: every read is a test
uniform mat4 u_light_matrix[SHADER_PASS_LIGHTS];       // world -> the light's clip space (an array map: its light view)
uniform float u_texel_scale[SHADER_PASS_LIGHTS];       // world texel: this (orthographic) or this x depth along the axis (perspective)
uniform sampler2D u_depths_2d[SHADER_PASS_LIGHTS];     // a soft light's map read as depth (compare mode off)
uniform mat4 u_light_inverse[SHADER_PASS_LIGHTS];      // a soft light's clip space -> world
#if MAP_PASS_TRANSMIT_LIGHTS
uniform sampler2D u_transmittances_2d[MAP_PASS_TRANSMIT_SLOTS]; // translucent casters' (map_transmitted)
#else
#define u_transmittances_2d u_depths_2d // no light reads one: no sampler of its own (map.frag)
#endif

// A matrix whose map coordinates hardly change with p (degenerate there)
// gives a huge texel rather than a division by zero.
const float MAP_MIN_MAP_DERIVATIVE = 1e-20;

// offset: in map coordinates.
float map_kernel_read(sampler2DShadow map, vec2 offset) {
    return texture(map, vec3(map_point.xy + offset, map_point.z + dot(map_gradient, offset)));
}

// The raw map's texel an offset away: a depth (.r), or moments.
vec4 map_raw_read(sampler2D raw, vec2 offset) { return texture(raw, map_point.xy + offset); }

// A texel of a transmittance map (map_flat.glsl).
vec4 map_transmit_fetch(sampler2D transmittance, ivec2 texel) { return texelFetch(transmittance, texel, 0); }

// Un-projected at the point's place in the map: any projective map's
// depth (a warp's is not distance) back to the world.
float map_soft_distance(sampler2D raw, int i, float depth) {
    vec4 world = u_light_inverse[i] * vec4(map_point.xy * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
    vec3 b = world.xyz / world.w;
    return lights_position[i].w == 0.0 ? dot(b, lights_direction[i].xyz) : distance(b, lights_position[i].xyz);
}

#define MAP_SAMPLER sampler2DShadow
#define MAP_RAW_SAMPLER sampler2D
#include "map_light.glsl"
#include "map_flat.glsl"
#include "map_soft.glsl"
#undef MAP_RAW_SAMPLER
#undef MAP_SAMPLER

// A warped map's texel size changes across the map, and its depth is not
// distance: the texel is how far p moves for its map coordinates to
// change by one texel, from the matrix's derivatives at p. (Along the light
// ray through p they do not change at all, so this measures across it.)
float map_projective_texel(int i, vec3 p) {
    mat4 m = u_light_matrix[i];
    vec4 clip = m * vec4(p, 1.0);
    vec3 w_row = vec3(m[0][3], m[1][3], m[2][3]);
    vec3 du = (vec3(m[0][0], m[1][0], m[2][0]) - clip.x / clip.w * w_row) / clip.w;
    vec3 dv = (vec3(m[0][1], m[1][1], m[2][1]) - clip.y / clip.w * w_row) / clip.w;
    return 2.0 / (u_map_size[i] * max(min(length(du), length(dv)), MAP_MIN_MAP_DERIVATIVE));
}

// By the kind of map: orthographic, perspective (looking along the
// light's direction from its position) or any projective map (a warp).
float map_texel_world(sampler2DShadow map, int i, int texel_kind, vec3 p) {
    if (texel_kind == MAP_TEXEL_ORTHOGRAPHIC)
        return u_texel_scale[i];
    if (texel_kind == MAP_TEXEL_PERSPECTIVE)
        return u_texel_scale[i] * max(dot(p - lights_position[i].xyz, lights_direction[i].xyz), 0.0);
    return map_projective_texel(i, p);
}

// The depth bounds' answer (map.glsl) for taps within the kernel's reach
// of the point, each comparing the receiver plane's depth there (lit:
// lit_shift deeper). Outside the map, lit, as map_flat_filter says.
float map_bounds_visibility(sampler2D bounds, int i, vec3 uvz, vec2 gradient, float depth_bias, float lit_shift) {
    if (any(lessThan(uvz.xy, vec2(0.0))) || any(greaterThan(uvz.xy, vec2(1.0))))
        return 1.0;
    float reach = map_kernel_reach(), size = u_map_size[i];
    vec2 point = uvz.xy * size - 0.5; // from the first texel's centre
    return map_bounds_answer(bounds, ivec2(0), int(size), point - reach, point + reach, point,
                             min(uvz.z - depth_bias, 1.0), gradient / size, 0.0, lit_shift);
}

// p in light i's map: its map coordinates and depth (0..1), and its clip
// w (not positive behind the light).
vec4 map_2d_point(int i, vec3 p) {
    vec4 clip = u_light_matrix[i] * vec4(p, 1.0);
    return vec4(clip.xyz / clip.w * 0.5 + 0.5, clip.w);
}

float map_visibility(sampler2DShadow map, sampler2D raw, sampler2D bounds, int i, vec3 p, vec3 lit_p,
                     float depth_bias, bool soft, bool moments, float texel, bool needed) {
    vec4 point = map_2d_point(i, p);
    vec3 uvz = point.xyz;
    vec2 gradient = map_depth_gradient(dFdx(uvz), dFdy(uvz), soft); /* derivatives: before any branch */
    if (!needed || point.w <= 0.0)
        return 1.0;
    if (map_bounds_light(i))
        return map_bounds_visibility(bounds, i, uvz, gradient, depth_bias, map_2d_point(i, lit_p).z - uvz.z);
    return map_flat_filter(map, raw, i, uvz, gradient, depth_bias, soft, moments, texel);
}

vec2 map_texel_coord(sampler2DShadow map, int i, vec3 p) {
    return map_2d_point(i, p).xy * u_map_size[i];
}

// The 3 x 3 texels about p's (map_flat.glsl).
bool map_translucent_near(sampler2D transmittance, int i, vec3 p, float depth_bias) {
    vec4 point = map_2d_point(i, p);
    return point.w > 0.0 && map_flat_translucent_near(transmittance, i, point.xyz, depth_bias);
}

// Outside the map, or behind the light, nothing filters.
vec3 map_transmittance(sampler2D transmittance, int i, vec3 p, float depth_bias) {
    vec4 point = map_2d_point(i, p);
    if (point.w <= 0.0 || any(lessThan(point.xy, vec2(0.0))) || any(greaterThan(point.xy, vec2(1.0))))
        return vec3(1.0);
    return map_transmitted(textureLod(transmittance, point.xy, 0.0), point.z - depth_bias);
}
