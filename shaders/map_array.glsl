// The camera pass's array maps (shaders/map.frag): a directional
// light's cascades (demos/cascades.c), one orthographic layer per slice of
// the view. Light i's map is u_maps_array[i] (on light i's unit: a light
// has one kind of map), u_light_matrix[i] its light view, and layer k's
// box is element i * MAP_MAX_ARRAY_LAYERS + k of the cascade
// arrays: a scale and an offset from light view to the layer's clip space
// (a diagonal and a translation, not a mat4 each: half the uniforms).

uniform sampler2DArrayShadow u_maps_array[SHADER_PASS_LIGHTS];
uniform sampler2DArray u_depths_array[SHADER_PASS_LIGHTS]; // a soft light's map read as depth (compare mode off)
#if MAP_PASS_TRANSMIT_LIGHTS
uniform sampler2DArray u_transmittances_array[MAP_PASS_TRANSMIT_SLOTS]; // translucent casters' (map_transmitted)
#else
#define u_transmittances_array u_depths_array // no light reads one: no sampler of its own (map.frag)
#endif
// xyz: scale and offset; w: the view depths where the layer's slice ends and starts.
uniform vec4 u_cascade_scale[SHADER_PASS_LIGHTS * MAP_MAX_ARRAY_LAYERS];
uniform vec4 u_cascade_offset[SHADER_PASS_LIGHTS * MAP_MAX_ARRAY_LAYERS];
uniform int u_cascade_count[SHADER_PASS_LIGHTS];
uniform float u_cascade_blend; // the far fraction of a slice mixed into the next layer (0: a hard switch)
uniform vec4 u_view_depth;     // the camera's view depth of a world point p: dot(this, vec4(p, 1))

// The layer the kernel reads: set with the point by map_visibility.
float map_array_layer;

// offset: in map coordinates.
float map_kernel_read(sampler2DArrayShadow map, vec2 offset) {
    return texture(map, vec4(map_point.xy + offset, map_array_layer,
                             map_point.z + dot(map_gradient, offset)));
}

// A texel of the layer's transmittance map (map_flat.glsl).
vec4 map_transmit_fetch(sampler2DArray transmittance, ivec2 texel) {
    return texelFetch(transmittance, ivec3(texel, int(map_array_layer)), 0);
}

// The raw map's texel an offset away: a depth (.r), or moments.
vec4 map_raw_read(sampler2DArray raw, vec2 offset) {
    return texture(raw, vec3(map_point.xy + offset, map_array_layer));
}

// A layer's depth is its box's, orthographic: distance along the light up
// to a constant, 2 / |scale.z| world units to the unit of depth.
float map_soft_distance(sampler2DArray raw, int i, float depth) {
    return 2.0 * depth / abs(u_cascade_scale[i * MAP_MAX_ARRAY_LAYERS + int(map_array_layer)].z);
}

#define MAP_SAMPLER sampler2DArrayShadow
#define MAP_RAW_SAMPLER sampler2DArray
#include "map_light.glsl"
#include "map_flat.glsl"
#include "map_soft.glsl"
#undef MAP_RAW_SAMPLER
#undef MAP_SAMPLER

// Which of light i's layers a point at view depth `depth` reads: x the
// layer whose slice holds it (the first before the first split, the last
// beyond the last), y the weight of the next layer, rising from 0 to 1
// over the blend band at the slice's far end (0 on the last layer).
vec2 map_cascade_at(int i, vec3 p) {
    float depth = dot(u_view_depth, vec4(p, 1.0));
    int base = i * MAP_MAX_ARRAY_LAYERS, last = u_cascade_count[i] - 1, k = 0;
    while (k < last && depth > u_cascade_scale[base + k].w)
        k++;
    float end = u_cascade_scale[base + k].w, band = u_cascade_blend * (end - u_cascade_offset[base + k].w);
    float next = k < last && band > 0.0 ? clamp((depth - (end - band)) / band, 0.0, 1.0) : 0.0;
    return vec2(float(k), next);
}

// Layer k's scale from light view to map coordinates (0..1) and depth.
vec3 map_cascade_scale(int i, int k) {
    return 0.5 * u_cascade_scale[i * MAP_MAX_ARRAY_LAYERS + k].xyz;
}

vec3 map_cascade_uvz(int i, int k, vec3 light_p) {
    vec3 offset = u_cascade_offset[i * MAP_MAX_ARRAY_LAYERS + k].xyz;
    return light_p * map_cascade_scale(i, k) + 0.5 * offset + 0.5;
}

// A layer's texel in world units: its box over the map's size (the wider
// side's texel, where a box is not square).
float map_cascade_texel(int i, int k) {
    vec3 scale = map_cascade_scale(i, k);
    return 1.0 / (u_map_size[i] * min(abs(scale.x), abs(scale.y)));
}

// The layer this pixel reads: in the blend band the next one where its
// weight exceeds the pixel's hash (a dithered blend: on average the mix
// of the two, for one kernel's reads: a second kernel in a branch costs
// every pixel on llvmpipe, which runs both sides of a branch, and would
// make the cascades' pass far dearer than one map's). By the fragment's own view depth (v_position), not the
// biased point's.
int map_pixel_cascade(int i) {
    vec2 cascade = map_cascade_at(i, v_position);
    return int(cascade.x) + (cascade.y > float(map_pixel_hash()) * MAP_HASH_TO_FRACTION ? 1 : 0);
}

// The biases are measured in the texel of the layer read.
float map_texel_world(sampler2DArrayShadow map, int i, int texel_kind, vec3 p) {
    return map_cascade_texel(i, map_pixel_cascade(i));
}

// Layer k's filtered comparison at p, with the receiver plane from the
// screen derivatives of p in light view (per layer: its scale).
// (Arrays have no depth bounds: lit_p is not read.)
float map_visibility(sampler2DArrayShadow map, sampler2DArray raw, sampler2D bounds, int i, vec3 p, vec3 lit_p,
                     float depth_bias, bool soft, bool moments, float texel, bool needed) {
    vec3 light_p = (u_light_matrix[i] * vec4(p, 1.0)).xyz; /* an orthonormal view: w is 1 */
    vec3 dx = dFdx(light_p), dy = dFdy(light_p);           /* derivatives: before any branch */
    if (!needed)
        return 1.0;
    int k = map_pixel_cascade(i);
    vec3 scale = map_cascade_scale(i, k);
    map_array_layer = float(k);
    return map_flat_filter(map, raw, i, map_cascade_uvz(i, k, light_p),
                                  map_depth_gradient(dx * scale, dy * scale, soft), depth_bias, soft, moments,
                                  texel);
}

vec2 map_texel_coord(sampler2DArrayShadow map, int i, vec3 p) {
    vec3 light_p = (u_light_matrix[i] * vec4(p, 1.0)).xyz;
    return map_cascade_uvz(i, int(map_cascade_at(i, p).x), light_p).xy * u_map_size[i];
}

// The 3 x 3 texels about p's in the layer it reads (map_flat.glsl).
bool map_translucent_near(sampler2DArray transmittance, int i, vec3 p, float depth_bias) {
    int k = map_pixel_cascade(i);
    map_array_layer = float(k);
    return map_flat_translucent_near(transmittance, i, map_cascade_uvz(i, k, (u_light_matrix[i] * vec4(p, 1.0)).xyz),
                                     depth_bias);
}

// The layer the kernel reads (the same pixel's hash), outside it nothing.
vec3 map_transmittance(sampler2DArray transmittance, int i, vec3 p, float depth_bias) {
    int k = map_pixel_cascade(i);
    vec3 uvz = map_cascade_uvz(i, k, (u_light_matrix[i] * vec4(p, 1.0)).xyz);
    if (any(lessThan(uvz.xy, vec2(0.0))) || any(greaterThan(uvz.xy, vec2(1.0))))
        return vec3(1.0);
    return map_transmitted(textureLod(transmittance, vec3(uvz.xy, float(k)), 0.0), uvz.z - depth_bias);
}

// The lecture's cascade overlay: each layer's colour, the blend band
// mixing two, laid over light i's share with MAP_CASCADE_TINT of
// its weight. The colours are C's map_cascade_colors (the key's
// too), set when the program is made.
uniform vec3 u_cascade_colors[MAP_MAX_ARRAY_LAYERS];
const float MAP_CASCADE_TINT = 0.6;

vec3 map_cascade_tint(int i, vec3 c) {
    vec2 cascade = map_cascade_at(i, v_position);
    int k = int(cascade.x);
    vec3 color = mix(u_cascade_colors[k], u_cascade_colors[min(k + 1, MAP_MAX_ARRAY_LAYERS - 1)], cascade.y);
    return mix(c, c * color, MAP_CASCADE_TINT);
}
