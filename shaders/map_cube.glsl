// The camera pass's cube maps (shaders/map.frag): a point light's
// six 90-degree faces, read by direction with seamless filtering across
// face edges. Light i's map is u_maps_cube[i] and the uniforms of index i.

uniform samplerCubeShadow u_maps_cube[SHADER_PASS_LIGHTS];
uniform samplerCube u_depths_cube[SHADER_PASS_LIGHTS]; // a soft light's map read as depth (compare mode off)
#if MAP_PASS_TRANSMIT_LIGHTS
uniform samplerCube u_transmittances_cube[MAP_PASS_TRANSMIT_SLOTS]; // translucent casters' (map_transmitted)
#else
#define u_transmittances_cube u_depths_cube // no light reads one: no sampler of its own (map.frag)
#endif
uniform float u_near[SHADER_PASS_LIGHTS];
uniform float u_far[SHADER_PASS_LIGHTS];

// A tap ray this close to parallel with the receiver's plane would slide
// far along it onto the plane: such taps keep their own point.
const float MAP_MIN_PLANE_FACING = 0.05;
// The kernel's plane is built across the direction from the up axis, or
// from the x axis when the direction is this close to up (where the cross
// product with up vanishes).
const float MAP_NEAR_UP = 0.9;

// A face's texel at direction d, `size` texels on a side: a 90-degree
// face spans 2 |major axis|.
float map_face_step(vec3 d, float size) { return 2.0 * max(abs(d.x), max(abs(d.y), abs(d.z))) / size; }
// Light i's map's texel at direction d.
float map_cube_step(int i, vec3 d) { return map_face_step(d, u_map_size[i]); }

// The plane across direction d: two unit axes (MAP_NEAR_UP).
void map_cube_across(vec3 d, out vec3 u, out vec3 v) {
    vec3 axis = normalize(d);
    u = normalize(cross(abs(axis.y) < MAP_NEAR_UP ? vec3(0, 1, 0) : vec3(1, 0, 0), axis));
    v = cross(axis, u);
}

// The point's direction from the light, the receiver's normal, the depth
// bias, the plane across the direction (two unit axes), a texel's size
// there and the light's depth range: set by map_visibility for
// map_kernel_read.
vec3 map_direction, map_receiver_normal, map_across_u, map_across_v;
float map_depth_bias, map_step;
vec2 map_cube_depth_range;
bool map_plane_taps; // the taps slide onto the receiver's plane (map_tap_depth)
// For the slide: the direction's dot product with the normal, the plane
// axes' (times a texel), and the direction's squared length.
float map_direction_normal, map_direction_squared;
vec2 map_across_normal;

// The depth a face's projection stores at distance z along its axis: the
// perspective depth.
float map_axis_depth(float z, vec2 range) {
    float near = range.x, far = range.y;
    float ndc = (far + near) / (far - near) - 2.0 * far * near / ((far - near) * z);
    return min(ndc * 0.5 + 0.5, 1.0);
}

// The depth a face's projection stores for a point at this direction.
float map_face_depth(vec3 d, vec2 range) {
    vec3 a = abs(d);
    return map_axis_depth(max(a.x, max(a.y, a.z)), range);
}

// The kernel's taps about direction d (a texel `step` across it), for
// map_kernel_read: the point's normal, depth bias and the light's depth
// range, the taps on the receiver's plane with that bias (and for soft
// lights).
void map_kernel_about(vec3 d, vec3 receiver_normal, float depth_bias, vec2 range, float step, bool soft) {
    map_direction = d;
    map_receiver_normal = receiver_normal;
    map_depth_bias = depth_bias;
    map_cube_depth_range = range;
    map_cube_across(d, map_across_u, map_across_v);
    map_step = step;
    map_plane_taps = map_receiver_plane || soft;
    map_direction_normal = dot(d, receiver_normal);
    map_direction_squared = dot(d, d);
    map_across_normal = vec2(dot(map_across_u, receiver_normal), dot(map_across_v, receiver_normal)) * step;
}

// A tap's direction, offset (in texels) across the point's.
vec3 map_tap_direction(vec2 offset) {
    return map_direction + (map_across_u * offset.x + map_across_v * offset.y) * map_step;
}

// The depth a tap compares, from its direction's distance along its
// face's axis. With the receiver-plane bias (and for soft lights) the tap
// point slides along its light ray onto the receiver's plane, and compares
// that point's own depth (as Isidoro's receiver-plane bias does for 2D
// maps), so a slanted receiver does not shadow its own kernel: the tap
// direction t meets the plane through d of normal n at t (d.n) / (t.n),
// whose distance along the axis is the tap's times |d.n / t.n| (the
// across axes are unit and square to d, so |t|^2 = |d|^2 + |offset|^2
// texels^2).
float map_tap_axis_depth(vec2 offset, float axis) {
    float scale = 1.0;
    if (map_plane_taps) {
        float along_normal = map_direction_normal + dot(map_across_normal, offset);
        float facing = along_normal * inversesqrt(map_direction_squared + map_step * map_step * dot(offset, offset));
        if (abs(facing) > MAP_MIN_PLANE_FACING)
            scale = abs(map_direction_normal / along_normal);
    }
    return map_axis_depth(axis * scale, map_cube_depth_range) - map_depth_bias;
}

float map_tap_depth(vec2 offset) {
    vec3 a = abs(map_tap_direction(offset));
    return map_tap_axis_depth(offset, max(a.x, max(a.y, a.z)));
}

float map_kernel_read(samplerCubeShadow map, vec2 offset) {
    return texture(map, vec4(map_tap_direction(offset), map_tap_depth(offset)));
}

// A soft light's reads (map_soft.glsl).
float map_reference_depth(samplerCube raw, vec2 offset) { return map_tap_depth(offset); }

// The raw map's texel an offset away: a depth (.r), or moments.
vec4 map_raw_read(samplerCube raw, vec2 offset) { return texture(raw, map_tap_direction(offset)); }

// A stored depth back to its distance along the face's axis.
float map_soft_distance(samplerCube raw, int i, float depth) {
    float near = u_near[i], far = u_far[i], ndc = depth * 2.0 - 1.0;
    return 2.0 * far * near / ((far + near) - ndc * (far - near));
}

// Direction d in the frame of face `face` (+X -X +Y -Y +Z -Z): the
// specification's table of sc, tc and ma, its (s, t) times its distance
// along the face's axis, and that distance. Linear in d.
vec3 map_cube_on_face(int face, vec3 d) {
    return face == 0   ? vec3(-d.z, -d.y, d.x)
           : face == 1 ? vec3(d.z, -d.y, -d.x)
           : face == 2 ? vec3(d.x, d.z, d.y)
           : face == 3 ? vec3(d.x, -d.z, -d.y)
           : face == 4 ? vec3(d.x, -d.y, d.z)
                       : vec3(-d.x, -d.y, -d.z);
}

// GL's face of direction d (its index) and d's (s, t) on it, 0..1.
int map_cube_face(vec3 d, out vec2 st) {
    vec3 a = abs(d);
    int face = a.x >= a.y && a.x >= a.z ? (d.x >= 0.0 ? 0 : 1)
               : a.y >= a.z             ? (d.y >= 0.0 ? 2 : 3)
                                        : (d.z >= 0.0 ? 4 : 5);
    vec3 on_face = map_cube_on_face(face, d);
    st = (on_face.xy / on_face.z + 1.0) * 0.5;
    return face;
}

// A direction in a face's frame (map_cube_on_face) as texels from the
// first centre of a face `size` texels wide.
vec2 map_cube_texel(vec3 on_face, float size) { return (on_face.xy / on_face.z + 1.0) * 0.5 * size - 0.5; }

// Below this the face's texels hardly move with the kernel's offsets:
// no plane through the taps is fitted.
const float MAP_CUBE_MIN_DETERMINANT = 1e-12;

// The depth bounds' answer (map.glsl) for the kernel's own taps, about
// the point map_visibility set up: where every tap reads the point's face
// away from its edges (seamless reads cross them), from the cells that
// hold the texels their directions read. A tap's direction in the face's
// frame is linear in its offset, so each tap's texel is one projection
// of the point's frame and the two across it. A face is a perspective
// view, in which a plane's stored depth is linear: the taps' depths (on
// the receiver's plane, or on the plane across the direction) lie on the
// line through the point's and two neighbours', within the slack that the
// depth's clamp and the taps kept off a grazing plane leave, measured
// (lit: lit_shift deeper). A tap on the face's far side of the light, or
// off its edges, leaves the pixel unsure.
float map_cube_bounds_visibility(sampler2D bounds, int i, float lit_shift) {
    float size = u_map_size[i];
    vec2 st;
    int face = map_cube_face(map_direction, st);
    vec3 frame = map_cube_on_face(face, map_direction);
    vec3 frame_x = map_cube_on_face(face, map_across_u * map_step);
    vec3 frame_y = map_cube_on_face(face, map_across_v * map_step);
    vec3 at_x = frame + frame_x, at_y = frame + frame_y;
    vec2 point = map_cube_texel(frame, size);
    vec2 along_x = map_cube_texel(at_x, size), along_y = map_cube_texel(at_y, size);
    float depth = map_tap_axis_depth(vec2(0.0), frame.z);
    mat2 steps = mat2(along_x - point, along_y - point); // columns: texels per unit of offset
    vec2 gradient = vec2(0.0);
    if (abs(determinant(steps)) > MAP_CUBE_MIN_DETERMINANT)
        gradient = inverse(transpose(steps)) * vec2(map_tap_axis_depth(vec2(1.0, 0.0), at_x.z) - depth,
                                                    map_tap_axis_depth(vec2(0.0, 1.0), at_y.z) - depth);
    vec2 low = vec2(size), high = vec2(-1.0);
    float slack = 0.0, nearest = min(frame.z, min(at_x.z, at_y.z));
    mat2 rotation = map_kernel_rotation();
    if (map_shape == MAP_KERNEL_TENT)
        map_tent_place(vec2(0.0));
    for (int k = 0; k < map_kernel_taps(); k++) {
        vec2 offset = map_kernel_tap(k, rotation, 1.0).xy;
        vec3 tap = frame + frame_x * offset.x + frame_y * offset.y;
        vec2 texel = map_cube_texel(tap, size);
        low = min(low, texel);
        high = max(high, texel);
        nearest = min(nearest, tap.z);
        slack = max(slack, abs(map_tap_axis_depth(offset, tap.z) - depth - dot(gradient, texel - point)));
    }
    int edge = MAP_BOUNDS_ROUNDING_TEXELS + 1;
    if (!(nearest > 0.0) || any(lessThan(floor(low), vec2(edge))) ||
        any(greaterThan(floor(high), vec2(size - 1.0 - float(edge)))))
        return MAP_BOUNDS_UNSURE;
    int cells = (int(size) + MAP_BOUNDS_CELL_TEXELS - 1) / MAP_BOUNDS_CELL_TEXELS;
    return map_bounds_answer(bounds, ivec2(face * cells, 0), int(size), low, high, point, depth, gradient, slack,
                             lit_shift);
}

#define MAP_SAMPLER samplerCubeShadow
#define MAP_RAW_SAMPLER samplerCube
#include "map_light.glsl"
#include "map_soft.glsl"
#undef MAP_RAW_SAMPLER
#undef MAP_SAMPLER

float map_texel_world(samplerCubeShadow map, int i, int texel_kind, vec3 p) {
    return map_cube_step(i, p - lights_position[i].xyz);
}

// The kernels' offsets lie in the plane across the direction, a texel
// apart there: a face's texel grid is not at hand in direction space. The
// tents take the taps and weights of a point on a texel corner (fraction
// 0): symmetric about the point, the same tap count and footprint as on a
// 2D map, but not following where the point lies in its texel.
float map_visibility(samplerCubeShadow map, samplerCube raw, sampler2D bounds, int i, vec3 p, vec3 lit_p,
                     float depth_bias, bool soft, bool moments, float texel, bool needed) {
    vec3 d = p - lights_position[i].xyz;
    vec3 receiver_normal = normalize(cross(dFdx(p), dFdy(p))); /* before any branch */
    if (!needed)
        return 1.0;
    vec2 range = vec2(u_near[i], u_far[i]);
    if (moments)
        return moments_visibility(texture(raw, d), map_face_depth(d, range) - depth_bias);
    if (map_shape == MAP_KERNEL_SINGLE && !soft)
        return texture(map, vec4(d, map_face_depth(d, range) - depth_bias));
    map_kernel_about(d, receiver_normal, depth_bias, range, map_cube_step(i, d), soft);
    if (map_bounds_light(i))
        return map_cube_bounds_visibility(
            bounds, i, map_face_depth(lit_p - lights_position[i].xyz, range) - map_face_depth(d, range));
    if (soft)
        return map_soft_filter(map, raw, i, map_step, 1.0);
    return map_kernel_filter(map, vec2(0.0), 1.0);
}

// On the face the direction falls on: the two other components over the
// major one span -1..1 across the face.
vec2 map_texel_coord(samplerCubeShadow map, int i, vec3 p) {
    vec3 d = p - lights_position[i].xyz, a = abs(d);
    vec2 face = a.x >= a.y && a.x >= a.z ? d.yz / a.x : a.y >= a.z ? d.xz / a.y : d.xy / a.z;
    return (face * 0.5 + 0.5) * u_map_size[i];
}

// The directions a texel apart about p's, 3 x 3 across it (a face's
// texel at the major axis' length), each read nearest.
bool map_translucent_near(samplerCube transmittance, int i, vec3 p, float depth_bias) {
    vec3 d = p - lights_position[i].xyz, u, v;
    map_cube_across(d, u, v);
    float step = map_cube_step(i, d);
    float depth = map_face_depth(d, vec2(u_near[i], u_far[i])) - depth_bias;
    bool near = false;
    for (int y = -1; y <= 1; y++)
        for (int x = -1; x <= 1; x++)
            near = near || map_translucent_before(
                               textureLod(transmittance, d + step * (float(x) * u + float(y) * v), 0.0), depth);
    return near;
}

// The face the direction falls on, at the depth that face stores.
vec3 map_transmittance(samplerCube transmittance, int i, vec3 p, float depth_bias) {
    vec3 d = p - lights_position[i].xyz;
    return map_transmitted(textureLod(transmittance, d, 0.0), map_face_depth(d, vec2(u_near[i], u_far[i])) - depth_bias);
}
