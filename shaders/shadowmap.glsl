// The camera pass of a shadow map (demos/lib/shadow_map.c, for
// demos/shadowmap.c and demos/psm.c), shared by the 2D map (spot,
// directional, warped) and the cube map (point). u_filter is a
// shadow_map_kernel (SHADOW_MAP_KERNEL_*), u_texel_kind a
// shadow_map_texel_kind (SHADOW_MAP_TEXEL_*): C enums, defined by C before
// this file. The including file defines the functions declared here:
//   shadowmap_texel_world(p)  world size of one map texel at p
//   shadowmap_visibility(p, b) the filtered comparison at p, its map depth
//                             lowered by b first
//   shadowmap_texel_coord(p)  p's position in the map, in texels (for the
//                             lecture's overlay of texel boundaries)
// This adds light u_light's share where the map says it reaches.

float shadowmap_texel_world(vec3 p);
float shadowmap_visibility(vec3 p, float depth_bias);
vec2 shadowmap_texel_coord(vec3 p);

in vec3 v_position;
in vec3 v_normal;

uniform vec3 u_albedo;
uniform int u_light;
uniform float u_constant_bias;   // texels of world distance, towards the light
uniform float u_normal_offset;   // texels, along the normal, times the slope
uniform bool u_show_texels;      // darken the map's texel boundaries
uniform bool u_show_texel_size;  // colour by a texel's size on screen
uniform vec2 u_depth_bias;       // max(x (1 - N.L), y) in map depth (0..1): the tutorials' bias

out vec4 out_color;

// Per-pixel rotation of the Poisson disc: a hash of the pixel, so the same
// frame gives the same picture (no noise texture, no clock).
float shadowmap_pixel_angle() {
    uvec2 q = uvec2(gl_FragCoord.xy);
    uint h = q.x * 1973u + q.y * 9277u;
    h = (h ^ (h >> 13)) * 0x5bd1e995u;
    return float(h ^ (h >> 15)) * (6.2831853 / 4294967296.0);
}

// 16 points of a Poisson disc (minimum distance 0.35), scaled by half of
// u_kernel texels (SHADOW_MAP_POISSON_SCALE_TEXELS: 3). They are not all in
// the unit circle: eight lie outside it, the farthest at radius 1.234, so
// the taps span 3.7 texels across, not 3. The points are kept as they are:
// the defaults were measured with them.
const vec2 shadowmap_poisson[16] = vec2[](
    vec2(-0.94201624, -0.39906216), vec2(0.94558609, -0.76890725), vec2(-0.09418410, -0.92938870),
    vec2(0.34495938, 0.29387760), vec2(-0.91588581, 0.45771432), vec2(-0.81544232, -0.87912464),
    vec2(-0.38277543, 0.27676845), vec2(0.97484398, 0.75648379), vec2(0.44323325, -0.97511554),
    vec2(0.53742981, -0.47373420), vec2(-0.26496911, -0.41893023), vec2(0.79197514, 0.19090188),
    vec2(-0.24188840, 0.99706507), vec2(-0.81409955, 0.91437590), vec2(0.19984126, 0.78641367),
    vec2(0.14383161, -0.14100790));

void main() {
    vec3 n = normalize(gl_FrontFacing ? v_normal : -v_normal);
    vec3 to_light = lighting_to_light(u_light, v_position);
    // Both biases move the point where the map is read, in world units
    // scaled by the map's texel there, so they hold at any map size,
    // distance and scene scale. The normal offset grows with the slope
    // (sin of the angle to the light), where a texel spans most depth.
    float texel = shadowmap_texel_world(v_position);
    float cos_theta = clamp(dot(n, to_light), 0.0, 1.0);
    float sin_theta = sqrt(1.0 - cos_theta * cos_theta);
    vec3 p = v_position + to_light * (u_constant_bias * texel) + n * (u_normal_offset * texel * sin_theta);
    float visibility = shadowmap_visibility(p, max(u_depth_bias.x * (1.0 - cos_theta), u_depth_bias.y));
    vec3 c = visibility * lighting_unshadowed(u_light, v_position, n, u_albedo);
    // Lines one pixel wide where texels meet: how big a texel is on screen
    // is what aliasing is made of.
    vec2 map_texel = shadowmap_texel_coord(v_position);
    vec2 distance_to_edge = abs(fract(map_texel - 0.5) - 0.5) / max(fwidth(map_texel), vec2(1e-6));
    float edge = 1.0 - min(min(distance_to_edge.x, distance_to_edge.y), 1.0);
    if (u_show_texels)
        c *= 1.0 - 0.6 * edge;
    // The aliasing measure of the perspective shadow map papers (dp/ds):
    // a texel's size in pixels, the square root of the pixel area it
    // covers. Blue: a quarter pixel or less, green: one, red: 32 or more.
    if (u_show_texel_size) {
        vec2 dx = dFdx(map_texel), dy = dFdy(map_texel);
        float texel_pixels = inversesqrt(max(abs(dx.x * dy.y - dx.y * dy.x), 1e-12));
        float t = clamp((log2(texel_pixels) + 2.0) / 7.0, 0.0, 1.0), one_pixel = 2.0 / 7.0;
        vec3 heat = t < one_pixel ? mix(vec3(0.1, 0.2, 1.0), vec3(0.1, 0.9, 0.2), t / one_pixel)
                                  : mix(vec3(0.1, 0.9, 0.2), vec3(1.0, 0.1, 0.05), (t - one_pixel) / (1.0 - one_pixel));
        c = heat * (0.4 + 0.6 * min(dot(c, vec3(0.3, 0.6, 0.1)) * 2.0, 1.0));
    }
    out_color = vec4(c, 1.0);
}
