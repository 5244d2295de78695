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
// This shades light u_light's share where the map says it reaches, and
// the ambient term where u_ambient is 1 (the first light's pass).

float shadowmap_texel_world(vec3 p);
float shadowmap_visibility(vec3 p, float depth_bias);
vec2 shadowmap_texel_coord(vec3 p);

in vec3 v_position;
in vec3 v_normal;

uniform vec3 u_albedo;
uniform int u_light;
uniform float u_ambient;         // 1: this pass also draws the ambient term
uniform float u_constant_bias;   // texels of world distance, towards the light
uniform float u_normal_offset;   // texels, along the normal, times the slope
uniform bool u_show_texels;      // darken the map's texel boundaries
uniform bool u_show_texel_size;  // colour by a texel's size on screen
uniform vec2 u_depth_bias;       // max(x (1 - N.L), y) in map depth (0..1): the tutorials' bias

out vec4 out_color;

// The pixel hash: two primes, so that neighbouring pixels start far apart,
// then MurmurHash2's multiplier between two xor-shifts to mix the bits.
const uint SHADOWMAP_HASH_PRIME_X = 1973u;
const uint SHADOWMAP_HASH_PRIME_Y = 9277u;
const uint SHADOWMAP_HASH_MULTIPLIER = 0x5bd1e995u;
const int SHADOWMAP_HASH_SHIFT_BEFORE = 13;
const int SHADOWMAP_HASH_SHIFT_AFTER = 15;
// The hash's 2^32 values onto one turn (2 pi radians).
const float SHADOWMAP_HASH_TO_ANGLE = 6.2831853 / 4294967296.0;

// Per-pixel rotation of the Poisson disc: a hash of the pixel, so the same
// frame gives the same picture (no noise texture, no clock).
float shadowmap_pixel_angle() {
    uvec2 q = uvec2(gl_FragCoord.xy);
    uint h = q.x * SHADOWMAP_HASH_PRIME_X + q.y * SHADOWMAP_HASH_PRIME_Y;
    h = (h ^ (h >> SHADOWMAP_HASH_SHIFT_BEFORE)) * SHADOWMAP_HASH_MULTIPLIER;
    return float(h ^ (h >> SHADOWMAP_HASH_SHIFT_AFTER)) * SHADOWMAP_HASH_TO_ANGLE;
}

// 16 points of a Poisson disc (minimum distance 0.35), scaled by half of
// u_kernel texels (SHADOW_MAP_POISSON_SCALE_TEXELS: 3). They are not all in
// the unit circle: eight lie outside it, the farthest at radius 1.234, so
// the taps span 3.7 texels across, not 3. The points are kept as they are:
// the defaults were measured with them.
const int SHADOWMAP_POISSON_TAPS = 16;
const vec2 shadowmap_poisson[SHADOWMAP_POISSON_TAPS] = vec2[](
    vec2(-0.94201624, -0.39906216), vec2(0.94558609, -0.76890725), vec2(-0.09418410, -0.92938870),
    vec2(0.34495938, 0.29387760), vec2(-0.91588581, 0.45771432), vec2(-0.81544232, -0.87912464),
    vec2(-0.38277543, 0.27676845), vec2(0.97484398, 0.75648379), vec2(0.44323325, -0.97511554),
    vec2(0.53742981, -0.47373420), vec2(-0.26496911, -0.41893023), vec2(0.79197514, 0.19090188),
    vec2(-0.24188840, 0.99706507), vec2(-0.81409955, 0.91437590), vec2(0.19984126, 0.78641367),
    vec2(0.14383161, -0.14100790));

// The texel overlay: a floor on the screen derivative of the map position
// (where it does not change across a pixel there are no edges to find, and
// no division by zero), and how much a texel boundary darkens the picture.
const float SHADOWMAP_MIN_TEXEL_FWIDTH = 1e-6;
const float SHADOWMAP_TEXEL_LINE_DARKENING = 0.6;
// The texel-size overlay's heat map runs over log2 of a texel's size in
// pixels from -2 (a quarter pixel) to 5 (32 pixels): shifted by OFFSET and
// divided by RANGE it is 0..1, one pixel at OFFSET / RANGE. The area floor
// keeps a map seen edge-on (no area) finite. Colours: blue below a pixel,
// green at one, red above; shaded by the picture's luminance (Rec. 601's
// weights, rounded) times GAIN, from DARKEST up to DARKEST + SHADE, so the
// scene stays readable under it.
const float SHADOWMAP_HEAT_MIN_AREA = 1e-12;
const float SHADOWMAP_HEAT_LOG2_OFFSET = 2.0;
const float SHADOWMAP_HEAT_LOG2_RANGE = 7.0;
const vec3 SHADOWMAP_HEAT_SMALL = vec3(0.1, 0.2, 1.0);
const vec3 SHADOWMAP_HEAT_ONE_PIXEL = vec3(0.1, 0.9, 0.2);
const vec3 SHADOWMAP_HEAT_LARGE = vec3(1.0, 0.1, 0.05);
const vec3 SHADOWMAP_HEAT_LUMINANCE = vec3(0.3, 0.6, 0.1);
const float SHADOWMAP_HEAT_GAIN = 2.0;
const float SHADOWMAP_HEAT_DARKEST = 0.4;
const float SHADOWMAP_HEAT_SHADE = 0.6;

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
    vec2 distance_to_edge =
        abs(fract(map_texel - 0.5) - 0.5) / max(fwidth(map_texel), vec2(SHADOWMAP_MIN_TEXEL_FWIDTH));
    float edge = 1.0 - min(min(distance_to_edge.x, distance_to_edge.y), 1.0);
    if (u_show_texels)
        c *= 1.0 - SHADOWMAP_TEXEL_LINE_DARKENING * edge;
    // The aliasing measure of the perspective shadow map papers (dp/ds):
    // a texel's size in pixels, the square root of the pixel area it
    // covers. Blue: a quarter pixel or less, green: one, red: 32 or more.
    if (u_show_texel_size) {
        vec2 dx = dFdx(map_texel), dy = dFdy(map_texel);
        float texel_pixels = inversesqrt(max(abs(dx.x * dy.y - dx.y * dy.x), SHADOWMAP_HEAT_MIN_AREA));
        float t = clamp((log2(texel_pixels) + SHADOWMAP_HEAT_LOG2_OFFSET) / SHADOWMAP_HEAT_LOG2_RANGE, 0.0, 1.0);
        float one_pixel = SHADOWMAP_HEAT_LOG2_OFFSET / SHADOWMAP_HEAT_LOG2_RANGE;
        vec3 heat = t < one_pixel ? mix(SHADOWMAP_HEAT_SMALL, SHADOWMAP_HEAT_ONE_PIXEL, t / one_pixel)
                                  : mix(SHADOWMAP_HEAT_ONE_PIXEL, SHADOWMAP_HEAT_LARGE,
                                        (t - one_pixel) / (1.0 - one_pixel));
        float shade = min(dot(c, SHADOWMAP_HEAT_LUMINANCE) * SHADOWMAP_HEAT_GAIN, 1.0);
        c = heat * (SHADOWMAP_HEAT_DARKEST + SHADOWMAP_HEAT_SHADE * shade);
    }
    out_color = vec4(u_ambient * lighting_ambient(u_albedo) + c, 1.0);
}
