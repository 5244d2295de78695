// The camera pass's tiled cube maps (shaders/map.frag): a point light's
// six faces as square tiles of one 2D depth texture, the shadow atlas
// (map.h, "Atlas"), read by the cube's rule (map_cube.glsl): the face a
// direction falls on and its (s, t) there, in that face's tile. Light i's
// faces are u_tiles[MAP_CUBE_FACES i + face].

// The atlas behind a type of its own: GLSL picks this kind's functions
// (map_light.glsl) by it, and its sampler is the 2D maps' type.
struct map_atlas {
    sampler2DShadow depths;
};
uniform map_atlas u_atlas;
uniform vec4 u_tiles[SHADER_PASS_LIGHTS * MAP_CUBE_FACES]; // per face: its corner (x, y) and side, atlas texels
uniform float u_atlas_size;                                // texels on a side

// The light whose taps map_kernel_read reads (set by map_visibility).
int map_tile_light;

// Light i's tile of the face direction d falls on.
vec4 map_tile_of(int i, vec3 d, out vec2 st) { return u_tiles[i * MAP_CUBE_FACES + map_cube_face(d, st)]; }

// A read's place in its tile is rounded to this fraction of a texel, so
// that its corner's whole texels add to it exactly in a float (a tile's
// corner is below 2^14, which leaves 9 bits of a float's 24 for the
// fraction) and the filter's weights are the same wherever the tile lies:
// a tile moved (another light took a tile first) changes no pixel.
const float MAP_TILE_SUBTEXELS = 256.0;

// Where direction d reads light i's atlas, (u, v): on its face's tile,
// half a texel inside its edges (a tile's neighbours are other faces,
// other lights: a cube's seamless filter would read the next face
// instead), at MAP_TILE_SUBTEXELS.
vec2 map_tile_uv(int i, vec3 d) {
    vec2 st;
    vec4 tile = map_tile_of(i, d, st);
    vec2 texel = clamp(st * tile.z, vec2(0.5), vec2(tile.z - 0.5));
    return (tile.xy + floor(texel * MAP_TILE_SUBTEXELS + 0.5) / MAP_TILE_SUBTEXELS) / u_atlas_size;
}

// A texel at direction d from light i: map_face_step over its tile's side.
float map_tile_step(int i, vec3 d) {
    vec2 st;
    return map_face_step(d, map_tile_of(i, d, st).z);
}

float map_kernel_read(map_atlas map, vec2 offset) {
    return texture(map.depths, vec3(map_tile_uv(map_tile_light, map_tap_direction(offset)), map_tap_depth(offset)));
}

#define MAP_SAMPLER map_atlas
#define MAP_RAW_SAMPLER map_atlas
#include "map_light.glsl"
#undef MAP_RAW_SAMPLER
#undef MAP_SAMPLER

float map_texel_world(map_atlas map, int i, int texel_kind, vec3 p) {
    return map_tile_step(i, p - lights_position[i].xyz);
}

// A tiled light is hard and read by its kernel (map_tiles_wanted): raw,
// soft, moments and bounds are never asked of it.
float map_visibility(map_atlas map, map_atlas raw, sampler2D bounds, int i, vec3 p, vec3 lit_p, float depth_bias,
                     bool soft, bool moments, float texel, bool needed) {
    vec3 d = p - lights_position[i].xyz;
    vec3 receiver_normal = normalize(cross(dFdx(p), dFdy(p))); /* before any branch */
    if (!needed)
        return 1.0;
    vec2 range = vec2(u_near[i], u_far[i]);
    if (map_shape == MAP_KERNEL_SINGLE)
        return texture(map.depths, vec3(map_tile_uv(i, d), map_face_depth(d, range) - depth_bias));
    map_tile_light = i;
    map_kernel_about(d, receiver_normal, depth_bias, range, map_tile_step(i, d), false);
    return map_kernel_filter(map, vec2(0.0), 1.0);
}

// In texels of the atlas.
vec2 map_texel_coord(map_atlas map, int i, vec3 p) { return map_tile_uv(i, p - lights_position[i].xyz) * u_atlas_size; }

// A tiled light takes no transmittance map (map_tiles_wanted): nothing
// translucent before p, everything let through.
bool map_translucent_near(map_atlas transmittance, int i, vec3 p, float depth_bias) { return false; }
vec3 map_transmittance(map_atlas transmittance, int i, vec3 p, float depth_bias) { return vec3(1.0); }
