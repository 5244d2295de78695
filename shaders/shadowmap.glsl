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
// The early-out's rim: four of the outermost points, about a quarter turn
// apart (at 203, 321, 38 and 132 degrees before the rotation).
const int SHADOWMAP_POISSON_RIM[4] = int[](0, 1, 7, 13);

// The kernel, the same uniforms for both kinds of map.
uniform int u_filter;     // SHADOW_MAP_KERNEL_*: one tap, N x N grid, Poisson disc, N x N tent
uniform int u_kernel;     // N, or the disc's scale in texels
uniform float u_map_size;
uniform bool u_early_out; // wide kernels: four rim taps first, the rest only where they disagree

// The kernels as lists of taps, for both kinds of map: tap i's offset from
// the point, in texels (a 2D map's grid; the plane across the direction of
// a cube map) divided by `unit` (the map's size, for offsets in map
// coordinates; 1 for texels), and its weight. The weighted sum over every
// tap divided by shadowmap_kernel_norm() is the visibility. `fraction` is
// the point's place from its nearest texel corner, -0.5..0.5 texels on
// each axis, which the tent places its taps by.
//
// The tent (SHADOW_MAP_KERNEL_TENT, u_kernel N = 3 or 5) is percentage-
// closer filtering weighted by a tent of radius N / 2 texels centred on
// the point, each texel's comparison counted as the square it covers:
// a texel weighs the tent's area over its square. Such weights sum to 1
// wherever the point is, are never negative, and are separable: a 1D tent
// of area 1 on each axis. On an axis the tent (the point within half a
// texel of its nearest corner) covers at most N + 1 texels, from that
// corner - (N + 1)/2 on: (N + 1)/2 pairs of neighbours. One bilinear
// comparison between a pair's two texel centres, at b / (a + b) of the
// way from the first, returns (a first + b second) / (a + b): weighted by
// a + b it is the pair's share exactly. So a pair is one tap per axis,
// and the N x N tent is ((N + 1)/2)^2 bilinear taps (4 for tent3, 9 for
// tent5), where pcfN takes N^2 (and its weights, a sum of bilinear hats,
// reach a texel farther: pcfN blurs more than tentN).

// The tent's area left of x (x from its centre), for a tent of area 1;
// both axes at once.
vec2 shadowmap_tent_below(vec2 x, float radius) {
    vec2 outside = max(radius - abs(x), 0.0);
    vec2 tail = outside * outside / (2.0 * radius * radius);
    return mix(1.0 - tail, tail, lessThan(x, vec2(0.0)));
}

// The tent's taps on each axis (x and y at once), for the pixel's point:
// pair p's offset and weight, the tent's area over its two squares.
const int SHADOWMAP_TENT_MAX_PAIRS = 3; /* tent5's */
vec2 shadowmap_tent_offset[SHADOWMAP_TENT_MAX_PAIRS], shadowmap_tent_weight[SHADOWMAP_TENT_MAX_PAIRS];

int shadowmap_tent_pairs() { return (u_kernel + 1) / 2; }

// Pair p's squares run from corner to corner + 2 (texels from the point):
// the first pair's corner lies (N + 1)/2 texels before the point's
// nearest corner, each next one 2 on; a pair's upper area is the next
// one's lower.
void shadowmap_tent_place(vec2 fraction) {
    float radius = 0.5 * float(u_kernel);
    vec2 corner = -fraction - float(shadowmap_tent_pairs());
    vec2 below = shadowmap_tent_below(corner, radius);
    for (int p = 0; p < shadowmap_tent_pairs(); p++) {
        vec2 middle = shadowmap_tent_below(corner + 1.0, radius);
        vec2 above = shadowmap_tent_below(corner + 2.0, radius);
        // Never 0: every pair overlaps the tent by half a texel or more.
        shadowmap_tent_weight[p] = above - below;
        // From the first texel's centre (corner + 0.5) towards the second's.
        shadowmap_tent_offset[p] = corner + 0.5 + (above - middle) / shadowmap_tent_weight[p];
        below = above;
        corner += 2.0;
    }
}

int shadowmap_kernel_taps() {
    if (u_filter == SHADOW_MAP_KERNEL_POISSON)
        return SHADOWMAP_POISSON_TAPS;
    if (u_filter == SHADOW_MAP_KERNEL_TENT)
        return shadowmap_tent_pairs() * shadowmap_tent_pairs();
    return u_kernel * u_kernel;
}

// The grid and the disc weigh every tap 1 and divide by the count (their
// sums are the ones before the tents, bit for bit); the tent's weights
// already sum to 1.
float shadowmap_kernel_norm() {
    return u_filter == SHADOW_MAP_KERNEL_TENT ? 1.0 : float(shadowmap_kernel_taps());
}

// The disc's rotation for this pixel; the identity for the other kernels.
mat2 shadowmap_kernel_rotation() {
    if (u_filter != SHADOW_MAP_KERNEL_POISSON)
        return mat2(1.0);
    float a = shadowmap_pixel_angle();
    return mat2(cos(a), sin(a), -sin(a), cos(a));
}

// Tap i of the kernel (the tent's placed by shadowmap_tent_place).
vec3 shadowmap_kernel_tap(int i, mat2 rotation, float unit) {
    if (u_filter == SHADOW_MAP_KERNEL_POISSON)
        return vec3(rotation * shadowmap_poisson[i] * (0.5 * float(u_kernel) / unit), 1.0);
    if (u_filter == SHADOW_MAP_KERNEL_TENT) {
        int x = i % shadowmap_tent_pairs(), y = i / shadowmap_tent_pairs();
        return vec3(vec2(shadowmap_tent_offset[x].x, shadowmap_tent_offset[y].y) / unit,
                    shadowmap_tent_weight[x].x * shadowmap_tent_weight[y].y);
    }
    int half_kernel = u_kernel / 2;
    return vec3(vec2(i % u_kernel - half_kernel, i / u_kernel - half_kernel) / unit, 1.0);
}

// The early-out (u_early_out, for kernels of more than four taps): four
// taps on the kernel's rim first, the middles of the sides of the grid of
// taps (pcfN's, the tent's pairs) or the disc's SHADOWMAP_POISSON_RIM.
// Where all four are wholly lit or wholly shadowed the point is taken to
// be outside any penumbra (nearly every pixel is) and that is the answer;
// elsewhere the whole kernel decides, rim included, so that its sum is the
// one without the early-out. It differs only where a feature thinner than
// the kernel hides between the rim taps. The middles of the sides, not the
// corners: their gaps are 1/sqrt(2) as wide (on long_view the corners let
// tent5's shadows slip through: 1.47 -> 1.75 % misclassified; the middles
// change no decision on any standard scene or long_view, with any kernel).
const int SHADOWMAP_RIM_TAPS = 4;

bool shadowmap_kernel_early_out() { return u_early_out && shadowmap_kernel_taps() > SHADOWMAP_RIM_TAPS; }

// Rim tap k's index, k = 0..3: the middles of the sides of the side x side
// grid of taps (side odd), in the order the taps are listed.
int shadowmap_kernel_rim(int k) {
    if (u_filter == SHADOW_MAP_KERNEL_POISSON)
        return SHADOWMAP_POISSON_RIM[k];
    int side = u_filter == SHADOW_MAP_KERNEL_TENT ? shadowmap_tent_pairs() : u_kernel;
    int middle = side / 2;
    return k == 0 ? middle : k == 1 ? middle * side : k == 2 ? middle * side + side - 1 : (side - 1) * side + middle;
}

// What four rim taps agree on: 0 or 1 where they are all that, else -1.
float shadowmap_rim_agreement(vec4 rim) {
    return rim == vec4(0.0) || rim == vec4(1.0) ? rim.x : -1.0;
}

// One tap at `offset` (a kernel tap's, in the unit the including file
// filters in) about the point its shadowmap_visibility set up: the
// including file defines it.
float shadowmap_kernel_read(vec2 offset);

// The kernel's visibility: the early-out's rim, then where it disagrees
// (or without the early-out) the weighted sum of every tap.
float shadowmap_kernel_filter(vec2 fraction, float unit) {
    mat2 rotation = shadowmap_kernel_rotation();
    if (u_filter == SHADOW_MAP_KERNEL_TENT)
        shadowmap_tent_place(fraction);
    if (shadowmap_kernel_early_out()) {
        vec4 rim;
        for (int k = 0; k < SHADOWMAP_RIM_TAPS; k++)
            rim[k] = shadowmap_kernel_read(shadowmap_kernel_tap(shadowmap_kernel_rim(k), rotation, unit).xy);
        float agreed = shadowmap_rim_agreement(rim);
        if (agreed >= 0.0)
            return agreed;
    }
    float sum = 0.0;
    for (int i = 0; i < shadowmap_kernel_taps(); i++) {
        vec3 tap = shadowmap_kernel_tap(i, rotation, unit);
        sum += tap.z * shadowmap_kernel_read(tap.xy);
    }
    return sum / shadowmap_kernel_norm();
}

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
