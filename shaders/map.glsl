// The camera pass's kernels (shaders/map.frag), for both kinds of
// map: which taps a filter reads, where and with what weights. The kernel
// is fixed per program (C defines MAP_PASS_*, below, and the
// MAP_KERNEL_* of its enum map_kernel before this file): a
// uniform would cost every pixel every kernel's code on llvmpipe, which
// runs both sides of a branch. How a tap reads a map is the map kind's (map_2d.glsl,
// map_cube.glsl); the filter over the taps is map_light.glsl's.

// The pixel hash: two primes, so that neighbouring pixels start far apart,
// then MurmurHash2's multiplier between two xor-shifts to mix the bits.
const uint MAP_HASH_PRIME_X = 1973u;
const uint MAP_HASH_PRIME_Y = 9277u;
const uint MAP_HASH_MULTIPLIER = 0x5bd1e995u;
const int MAP_HASH_SHIFT_BEFORE = 13;
const int MAP_HASH_SHIFT_AFTER = 15;
// The hash's 2^32 values onto one turn (2 pi radians), and onto 0..1.
const float MAP_HASH_TO_ANGLE = 6.2831853 / 4294967296.0;
const float MAP_HASH_TO_FRACTION = 1.0 / 4294967296.0;

// A hash of the pixel, so the same frame gives the same picture (no noise
// texture, no clock).
uint map_pixel_hash() {
    uvec2 q = uvec2(gl_FragCoord.xy);
    uint h = q.x * MAP_HASH_PRIME_X + q.y * MAP_HASH_PRIME_Y;
    h = (h ^ (h >> MAP_HASH_SHIFT_BEFORE)) * MAP_HASH_MULTIPLIER;
    return h ^ (h >> MAP_HASH_SHIFT_AFTER);
}

// Per-pixel rotation of the Poisson disc.
float map_pixel_angle() { return float(map_pixel_hash()) * MAP_HASH_TO_ANGLE; }

// 16 points of a Poisson disc (minimum distance 0.35), scaled by half of
// map_kernel_size texels (MAP_POISSON_SCALE_TEXELS: 3). They
// are not all in the unit circle: eight lie outside it, the farthest at radius 1.234, so
// the taps span 3.7 texels across, not 3. The points are kept as they are:
// the defaults (the biases, the kernel's size) were chosen with them, on
// the bench's sweeps and test_shadowmap's bounds.
const int MAP_POISSON_TAPS = 16;
const vec2 map_poisson[MAP_POISSON_TAPS] = vec2[](
    vec2(-0.94201624, -0.39906216), vec2(0.94558609, -0.76890725), vec2(-0.09418410, -0.92938870),
    vec2(0.34495938, 0.29387760), vec2(-0.91588581, 0.45771432), vec2(-0.81544232, -0.87912464),
    vec2(-0.38277543, 0.27676845), vec2(0.97484398, 0.75648379), vec2(0.44323325, -0.97511554),
    vec2(0.53742981, -0.47373420), vec2(-0.26496911, -0.41893023), vec2(0.79197514, 0.19090188),
    vec2(-0.24188840, 0.99706507), vec2(-0.81409955, 0.91437590), vec2(0.19984126, 0.78641367),
    vec2(0.14383161, -0.14100790));
// The farthest point's radius (of (0.9748, 0.7565)), rounded up.
const float MAP_POISSON_REACH = 1.234;
// The early-out's rim: four of the outermost points, about a quarter turn
// apart (at 203, 321, 38 and 132 degrees before the rotation).
const int MAP_POISSON_RIM[4] = int[](0, 1, 7, 13);

// The kernel, the same for both kinds of map.
// MAP_KERNEL_*: one tap, N x N grid, Poisson disc, N x N tent.
const int map_shape = MAP_PASS_SHAPE;
const int map_kernel_size = MAP_PASS_KERNEL; // N, or the disc's scale in texels
// Wide kernels: four rim taps first, the rest only where they disagree.
const bool map_early_out = MAP_PASS_EARLY_OUT != 0;
// Each tap compares the receiver plane's depth there, not the centre's.
const bool map_receiver_plane = MAP_PASS_RECEIVER_PLANE != 0;
uniform float u_map_size[SHADER_PASS_LIGHTS]; // light i's map: texels on a side
uniform sampler2D u_bounds[SHADER_PASS_LIGHTS]; // light i's depth bounds, in a marking pass (below)

// A flat map's (2D, or an array's layer) point the kernel reads about (map
// coordinates and depth) and its depth gradient: set by
// map_flat_filter (map_flat.glsl) for map_kernel_read.
vec3 map_point;
vec2 map_gradient;

// Below this the screen -> map Jacobian is singular (the receiver seen
// edge-on, or no change across the pixel): no plane to follow, so every
// tap compares the centre's depth.
const float MAP_MIN_SCREEN_TO_MAP_DETERMINANT = 1e-14;

// Receiver-plane depth bias (Isidoro, "Shadow mapping: GPU-based tips and
// techniques", GDC 2006): how the receiver's map depth changes per unit of
// map (u, v), from the screen derivatives dx, dy of its (u, v, depth), so
// that each tap of a wide kernel compares the receiver's own depth there,
// not the centre's, which would shadow a slanted receiver with partial acne.
// A soft light's taps always follow the plane: its kernels are wide.
vec2 map_depth_gradient(vec3 dx, vec3 dy, bool soft) {
    mat2 screen_to_map = mat2(dx.xy, dy.xy);
    if (!(map_receiver_plane || soft) ||
        abs(determinant(screen_to_map)) < MAP_MIN_SCREEN_TO_MAP_DETERMINANT)
        return vec2(0.0);
    return inverse(transpose(screen_to_map)) * vec2(dx.z, dy.z);
}

// The kernels as lists of taps, for both kinds of map: tap i's offset from
// the point, in texels (a 2D map's grid; the plane across the direction of
// a cube map) divided by `unit` (the map's size, for offsets in map
// coordinates; 1 for texels), and its weight. The weighted sum over every
// tap divided by map_kernel_norm() is the visibility. `fraction` is
// the point's place from its nearest texel corner, -0.5..0.5 texels on
// each axis, which the tent places its taps by.
//
// The tent (MAP_KERNEL_TENT, map_kernel_size N = 3 or 5) is
// percentage-closer filtering weighted by a tent of radius N / 2 texels centred on
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
vec2 map_tent_below(vec2 x, float radius) {
    vec2 outside = max(radius - abs(x), 0.0);
    vec2 tail = outside * outside / (2.0 * radius * radius);
    return mix(1.0 - tail, tail, lessThan(x, vec2(0.0)));
}

// The tent's taps on each axis (x and y at once), for the pixel's point:
// pair p's offset and weight, the tent's area over its two squares.
const int MAP_TENT_MAX_PAIRS = 3; /* tent5's */
vec2 map_tent_offset[MAP_TENT_MAX_PAIRS], map_tent_weight[MAP_TENT_MAX_PAIRS];

int map_tent_pairs() { return (map_kernel_size + 1) / 2; }

// Pair p's squares run from corner to corner + 2 (texels from the point):
// the first pair's corner lies (N + 1)/2 texels before the point's
// nearest corner, each next one 2 on; a pair's upper area is the next
// one's lower.
void map_tent_place(vec2 fraction) {
    float radius = 0.5 * float(map_kernel_size);
    vec2 corner = -fraction - float(map_tent_pairs());
    vec2 below = map_tent_below(corner, radius);
    for (int p = 0; p < map_tent_pairs(); p++) {
        vec2 middle = map_tent_below(corner + 1.0, radius);
        vec2 above = map_tent_below(corner + 2.0, radius);
        // Never 0: every pair overlaps the tent by half a texel or more.
        map_tent_weight[p] = above - below;
        // From the first texel's centre (corner + 0.5) towards the second's.
        map_tent_offset[p] = corner + 0.5 + (above - middle) / map_tent_weight[p];
        below = above;
        corner += 2.0;
    }
}

int map_kernel_taps() {
    if (map_shape == MAP_KERNEL_POISSON)
        return MAP_POISSON_TAPS;
    if (map_shape == MAP_KERNEL_TENT)
        return map_tent_pairs() * map_tent_pairs();
    return map_kernel_size * map_kernel_size;
}

// The grid and the disc weigh every tap 1 and divide by the count (their
// sums are the ones before the tents, bit for bit); the tent's weights
// already sum to 1.
float map_kernel_norm() {
    return map_shape == MAP_KERNEL_TENT ? 1.0 : float(map_kernel_taps());
}

// The disc's rotation for this pixel; the identity for the other kernels.
mat2 map_kernel_rotation() {
    if (map_shape != MAP_KERNEL_POISSON)
        return mat2(1.0);
    float a = map_pixel_angle();
    return mat2(cos(a), sin(a), -sin(a), cos(a));
}

// Tap i of the kernel (the tent's placed by map_tent_place).
vec3 map_kernel_tap(int i, mat2 rotation, float unit) {
    if (map_shape == MAP_KERNEL_POISSON)
        return vec3(rotation * map_poisson[i] * (0.5 * float(map_kernel_size) / unit), 1.0);
    if (map_shape == MAP_KERNEL_TENT) {
        int x = i % map_tent_pairs(), y = i / map_tent_pairs();
        return vec3(vec2(map_tent_offset[x].x, map_tent_offset[y].y) / unit,
                    map_tent_weight[x].x * map_tent_weight[y].y);
    }
    int half_kernel = map_kernel_size / 2;
    return vec3(vec2(i % map_kernel_size - half_kernel, i / map_kernel_size - half_kernel) / unit, 1.0);
}

// How far (texels, on either axis) any tap of the kernel lies from the
// point: the disc's farthest point; pcfN's N / 2 (integer offsets); the
// tent's (N + 1) / 2 pairs, whose offsets lie within
// map_tent_pairs() texels of the point wherever it is in its texel.
float map_kernel_reach() {
    if (map_shape == MAP_KERNEL_POISSON)
        return 0.5 * float(map_kernel_size) * MAP_POISSON_REACH;
    if (map_shape == MAP_KERNEL_TENT)
        return float(map_tent_pairs());
    return float(map_kernel_size / 2);
}

// Depth bounds (demos/lib/map_bounds.c): a marking pass's answer for a
// hard light of MAP_PASS_BOUNDS_LIGHTS, instead of its kernel: what the
// kernel would say where that is sure, without reading the map. A map's
// bounds hold per cell of MAP_BOUNDS_CELL_TEXELS texels on a side (a
// cube's six faces side by side) a plane between two of whose heights
// every texel's depth lies: its slope per texel on x and y, and its least
// and greatest height at the cell's centre (map_bounds.frag fits it). A
// sloped surface lies close to its cell's plane, where a cell's least
// and greatest depth would be far apart.
// The answer is 1 where no texel a tap reads can lie before that tap's
// depth, 0 where every one must lie past it, and MAP_BOUNDS_UNSURE
// (strictly between: the pixel is marked for the kernel and the rays)
// elsewhere, and where the reads span more than MAP_BOUNDS_SPAN_CELLS
// cells on an axis (a cell of 8 texels holds the default kernel's reads
// in 2). Lit is asked at the depth lit_shift deeper (map_share's sure-lit
// point), shadowed at the taps' own. MAP_BOUNDS_DEPTH_MARGIN keeps a tap
// whose depth rounds to a texel's out of both. A sampler places a read within
// MAP_BOUNDS_SUBTEXEL of a texel (GPUs resolve 1/256 of one), which
// may pick the texel beyond: the cells are read a texel wider
// (MAP_BOUNDS_ROUNDING_TEXELS), and a texel read lies within 1 +
// MAP_BOUNDS_SUBTEXEL of the tap.
const float MAP_BOUNDS_UNSURE = 0.5;
const float MAP_BOUNDS_DEPTH_MARGIN = 1e-6;
const int MAP_BOUNDS_ROUNDING_TEXELS = 1;
const float MAP_BOUNDS_SUBTEXEL = 1.0 / 16.0;
const int MAP_BOUNDS_SPAN_CELLS = 2;

bool map_bounds_light(int i) { return ((MAP_PASS_BOUNDS_LIGHTS >> i) & 1) != 0; }

// The answer for taps at texel positions within `low` .. `high` (texels
// from the first centre, on a face `size` texels wide whose first cell is
// `origin`), each comparing a depth within `slack` of the linear one
// through `depth` at `point` with `gradient` per texel (for lit, through
// depth + lit_shift). A bilinear read
// takes the texels whose centres lie within a texel of the tap (and
// MAP_BOUNDS_SUBTEXEL): such a texel's own linear depth is within the
// gradient's reach of the tap's. Per cell the
// test is linear over the texels it holds, so their box's corners decide.
float map_bounds_answer(sampler2D bounds, ivec2 origin, int size, vec2 low, vec2 high, vec2 point, float depth,
                        vec2 gradient, float slack, float lit_shift) {
    ivec2 last = ivec2(size - 1);
    ivec2 first_texel = clamp(ivec2(floor(low)) - MAP_BOUNDS_ROUNDING_TEXELS, ivec2(0), last);
    ivec2 last_texel = clamp(ivec2(floor(high)) + 1 + MAP_BOUNDS_ROUNDING_TEXELS, ivec2(0), last);
    ivec2 first_cell = first_texel / MAP_BOUNDS_CELL_TEXELS, last_cell = last_texel / MAP_BOUNDS_CELL_TEXELS;
    if (any(greaterThanEqual(last_cell - first_cell, ivec2(MAP_BOUNDS_SPAN_CELLS))))
        return MAP_BOUNDS_UNSURE;
    float reach = (abs(gradient.x) + abs(gradient.y)) * (1.0 + MAP_BOUNDS_SUBTEXEL) + slack + MAP_BOUNDS_DEPTH_MARGIN;
    bool lit = true, shadowed = true;
    for (int y = 0; y < MAP_BOUNDS_SPAN_CELLS; y++)
        for (int x = 0; x < MAP_BOUNDS_SPAN_CELLS; x++) {
            ivec2 cell = min(first_cell + ivec2(x, y), last_cell);
            vec4 plane = texelFetch(bounds, origin + cell, 0); // slope x, y; least, greatest at the centre
            vec2 centre = vec2(cell * MAP_BOUNDS_CELL_TEXELS) + 0.5 * float(MAP_BOUNDS_CELL_TEXELS - 1);
            vec2 box_low = vec2(max(first_texel, cell * MAP_BOUNDS_CELL_TEXELS));
            vec2 box_high = vec2(min(last_texel, cell * MAP_BOUNDS_CELL_TEXELS + MAP_BOUNDS_CELL_TEXELS - 1));
            // The texels' depth over the taps' linear depth: plane - line.
            vec2 slope = plane.xy - gradient;
            float at_centre = dot(plane.xy, -centre) - depth + dot(gradient, point);
            vec2 lowest = mix(box_high, box_low, greaterThan(slope, vec2(0.0)));
            vec2 highest = mix(box_low, box_high, greaterThan(slope, vec2(0.0)));
            lit = lit && plane.z + at_centre - lit_shift + dot(slope, lowest) >= reach;
            shadowed = shadowed && plane.w + at_centre + dot(slope, highest) <= -reach &&
                       plane.w + dot(plane.xy, mix(box_low, box_high, greaterThan(plane.xy, vec2(0.0))) - centre) <
                           1.0 - MAP_BOUNDS_DEPTH_MARGIN;
        }
    return lit ? 1.0 : shadowed ? 0.0 : MAP_BOUNDS_UNSURE;
}

// The early-out (map_early_out, for kernels of more than four taps): four
// taps on the kernel's rim first, the middles of the sides of the grid of
// taps (pcfN's, the tent's pairs) or the disc's MAP_POISSON_RIM.
// Where all four are wholly lit or wholly shadowed the point is taken to
// be outside any penumbra (nearly every pixel is) and that is the answer;
// elsewhere the whole kernel decides, rim included, so that its sum is the
// one without the early-out. It differs only where a feature thinner than
// the kernel hides between the rim taps. The middles of the sides, not the
// corners: their gaps are 1/sqrt(2) as wide (the corners let long_view's
// thin shadows slip through tent5; the middles change no decision on any
// standard scene or long_view, with any kernel: test_shadowmap's
// test_early_out_changes_no_decision).
const int MAP_RIM_TAPS = 4;

bool map_kernel_early_out() { return map_early_out && map_kernel_taps() > MAP_RIM_TAPS; }

// The taps' loop after the rim stays a loop: its bound adds u_unroll_guard,
// which is 0 (GL sets every uniform to 0 at link, and C never sets this
// one) but unknown to the compiler, which would unroll a loop of constant
// count. llvmpipe runs an unrolled branch's code for every pixel of a
// block, masked, yet leaves a loop once no pixel of the block is in it: only a
// loop lets the early-out skip the taps it promises (a GPU skips either).
uniform int u_unroll_guard;
int map_kernel_loop_taps() { return map_kernel_taps() + u_unroll_guard; }

// Rim tap k's index, k = 0..3: the middles of the sides of the side x side
// grid of taps (side odd), in the order the taps are listed.
int map_kernel_rim(int k) {
    if (map_shape == MAP_KERNEL_POISSON)
        return MAP_POISSON_RIM[k];
    int side = map_shape == MAP_KERNEL_TENT ? map_tent_pairs() : map_kernel_size;
    int middle = side / 2;
    return k == 0 ? middle : k == 1 ? middle * side : k == 2 ? middle * side + side - 1 : (side - 1) * side + middle;
}

// Which rim tap (0..3) tap i is, or -1.
int map_kernel_rim_index(int i) {
    for (int k = 0; k < MAP_RIM_TAPS; k++)
        if (map_kernel_rim(k) == i)
            return k;
    return -1;
}

// What four rim taps agree on: 0 or 1 where they are all that, else -1.
float map_rim_agreement(vec4 rim) {
    return rim == vec4(0.0) || rim == vec4(1.0) ? rim.x : -1.0;
}

// Soft shadows' pieces that do not depend on the kind of map (the
// filter itself, per kind: map_soft.glsl).

// Light i's disc: its radius (world units) for a point or spot light, the
// tangent of its angular radius for a directional one.
uniform float u_light_size[SHADER_PASS_LIGHTS];

// The radius in world units on the receiver of the penumbra that a
// blocker at distance d_b casts from light i on a receiver at d_r.
// (A blocker at the light itself would cast an unbounded one.)
const float MAP_MIN_BLOCKER_DISTANCE = 1e-6;
float map_penumbra_world(int i, float d_r, float d_b) {
    float depth = max(d_r - d_b, 0.0);
    return lights_position[i].w == 0.0 ? u_light_size[i] * depth
                                       : u_light_size[i] * depth / max(d_b, MAP_MIN_BLOCKER_DISTANCE);
}

float map_soft_texels(float world, float texel_world) {
    return clamp(world / texel_world, 0.5 * float(MAP_POISSON_SCALE_TEXELS), float(MAP_SOFT_MAX_TEXELS));
}

// The share of light i's disc above the receiver's own horizon (its
// tangent plane, normal n): a disc of angular radius a whose centre stands
// at elevation e cut by the plane, x = sin(e) / sin(a) clamped to -1..1,
// keeps 1 - (acos(x) - x sqrt(1 - x^2)) / pi of its area. Near the
// terminator of a curved receiver the light sets behind the surface
// itself, as the reference's rays see it; a map has no such depth to
// compare. 1 wherever the whole disc is above the plane.
const float MAP_PI = 3.14159265;
float map_horizon_share(int i, vec3 n, vec3 to_light, vec3 p) {
    float sin_a = lights_position[i].w == 0.0 ? u_light_size[i] * inversesqrt(1.0 + u_light_size[i] * u_light_size[i])
                                              : min(u_light_size[i] / distance(lights_position[i].xyz, p), 1.0);
    float x = clamp(dot(n, to_light) / sin_a, -1.0, 1.0);
    return 1.0 - (acos(x) - x * sqrt(1.0 - x * x)) / MAP_PI;
}

// Tap k of n on the unit disc (Vogel 1979): radius sqrt((k + 0.5) / n),
// each a golden angle on from the one before, turned by `rotation`.
const float MAP_GOLDEN_ANGLE = 2.39996323;
vec2 map_vogel_tap(int k, int n, mat2 rotation) {
    float a = float(k) * MAP_GOLDEN_ANGLE;
    return rotation * (vec2(cos(a), sin(a)) * sqrt((float(k) + 0.5) / float(n)));
}

// The texel overlay: a floor on the screen derivative of the map position
// (where it does not change across a pixel there are no edges to find, and
// no division by zero), and how much a texel boundary darkens the picture.
const float MAP_MIN_TEXEL_FWIDTH = 1e-6;
const float MAP_TEXEL_LINE_DARKENING = 0.6;
// The least spacing of the texel overlay's lines, in pixels: well above
// the two pixels a line of Nyquist's limit, so the grid reads as squares.
const float MAP_TEXEL_LINE_MIN_PIXELS = 4.0;
// The penumbra overlay's floor on the radius (a blocker at the receiver's
// own depth casts none), so that its log2 is finite.
const float MAP_MIN_PENUMBRA = 1e-6;
// With rays, the share of the constant bias a hard light's map must say
// lit with too where the full bias says lit, for the pixel to be sure
// (map_light.glsl, map_share): the larger the bias, the surer a shadow,
// the smaller, the surer the light. Acne the smaller bias lets through
// only sends pixels to the rays; a caster nearer to its receiver than
// this share of a texel stays hidden (test_gltf's truck: window frames
// about a texel over the body).
const float MAP_SURE_LIT_BIAS_SHARE = 0.25;

// The unsure overlay: magenta, over half of the pixel's colour, so that
// the shading still shows through.
const vec3 MAP_UNSURE_TINT = vec3(1.0, 0.0, 1.0);
const float MAP_UNSURE_TINT_SHARE = 0.5;
#include "texel_heat.glsl"

// Translucent casters (demos/lib/map.h): a transmittance map's texel (rgb
// the share of each channel its casters let through, alpha the nearest
// one's depth, a half float) filters a point at map depth `depth` where
// the point lies beyond that caster by more than MAP_TRANSMIT_ROUNDING,
// twice a half float's rounding below 1 (2^-12). A translucent receiver
// (u_translucent) lying beyond it is one of the texel's casters: its own
// transmittance is divided out (where a channel of it is 0, so is the
// product's), so that a pane under another is filtered by that one alone.
uniform bool u_translucent;
const float MAP_TRANSMIT_ROUNDING = 2.0 / 4096.0;
const float MAP_MIN_TRANSMITTANCE = 1e-6;
// Whether the texel's translucent casters lie before a point at `depth`.
bool map_translucent_before(vec4 texel, float depth) { return depth > texel.a + MAP_TRANSMIT_ROUNDING; }

vec3 map_transmitted(vec4 texel, float depth) {
    if (!map_translucent_before(texel, depth))
        return vec3(1.0);
    return u_translucent ? min(texel.rgb / max(surface_transmittance(), MAP_MIN_TRANSMITTANCE), 1.0) : texel.rgb;
}
