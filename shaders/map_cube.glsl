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

// A face's texel at direction d from light i: a 90-degree face spans
// 2 |major axis| over the map's size.
float map_cube_step(int i, vec3 d) { return 2.0 * max(abs(d.x), max(abs(d.y), abs(d.z))) / u_map_size[i]; }

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

// The depth a face's projection stores for a point at this direction:
// the perspective depth of its distance along the face's axis.
float map_face_depth(vec3 d, vec2 range) {
    float near = range.x, far = range.y;
    vec3 a = abs(d);
    float z = max(a.x, max(a.y, a.z));
    float ndc = (far + near) / (far - near) - 2.0 * far * near / ((far - near) * z);
    return min(ndc * 0.5 + 0.5, 1.0);
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
}

// A tap's direction, offset (in texels) across the point's.
vec3 map_tap_direction(vec2 offset) {
    return map_direction + (map_across_u * offset.x + map_across_v * offset.y) * map_step;
}

// The depth a tap compares. With the receiver-plane bias (and for soft
// lights) the tap point slides along its light ray onto the receiver's
// plane, and compares that point's own depth (as Isidoro's receiver-plane
// bias does for 2D maps), so a slanted receiver does not shadow its own
// kernel.
float map_tap_depth(vec2 offset) {
    vec3 t = map_tap_direction(offset), w = t - map_direction;
    float facing = dot(normalize(t), map_receiver_normal);
    if (map_plane_taps && abs(facing) > MAP_MIN_PLANE_FACING)
        t -= normalize(t) * (dot(w, map_receiver_normal) / facing);
    return map_face_depth(t, map_cube_depth_range) - map_depth_bias;
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

// GL's face of direction d (its index: +X -X +Y -Y +Z -Z) and d's (s, t)
// on it, 0..1: the specification's table of sc, tc over |ma|.
int map_cube_face(vec3 d, out vec2 st) {
    vec3 a = abs(d);
    int face;
    vec2 across;
    float major;
    if (a.x >= a.y && a.x >= a.z) {
        face = d.x >= 0.0 ? 0 : 1;
        major = a.x;
        across = d.x >= 0.0 ? vec2(-d.z, -d.y) : vec2(d.z, -d.y);
    } else if (a.y >= a.z) {
        face = d.y >= 0.0 ? 2 : 3;
        major = a.y;
        across = d.y >= 0.0 ? vec2(d.x, d.z) : vec2(d.x, -d.z);
    } else {
        face = d.z >= 0.0 ? 4 : 5;
        major = a.z;
        across = d.z >= 0.0 ? vec2(d.x, -d.y) : vec2(-d.x, -d.y);
    }
    st = (across / major + 1.0) * 0.5;
    return face;
}

// Where the direction `offset` (texels across the point's) falls on
// `face`, in texels from its first centre (false: on another face).
bool map_cube_place(int face, float size, vec2 offset, out vec2 texel) {
    vec2 st;
    bool same = map_cube_face(map_tap_direction(offset), st) == face;
    texel = st * size - 0.5;
    return same;
}

// Below this the face's texels hardly move with the kernel's offsets:
// no plane through the taps is fitted.
const float MAP_CUBE_MIN_DETERMINANT = 1e-12;

// The depth bounds' answer (map.glsl) for the kernel's own taps, about
// the point map_visibility set up: where every tap reads the point's face
// away from its edges (seamless reads cross them), from the cells that
// hold the texels their directions read. A face is a perspective view,
// in which a plane's stored depth is linear: the taps' depths (on the
// receiver's plane, or on the plane across the direction) lie on the line
// through the point's and two neighbours', within the slack that the
// depth's clamp and the taps kept off a grazing plane leave, measured
// (lit: lit_shift deeper).
float map_cube_bounds_visibility(sampler2D bounds, int i, float lit_shift) {
    float size = u_map_size[i];
    vec2 st;
    int face = map_cube_face(map_direction, st);
    vec2 point, along_x, along_y;
    if (!map_cube_place(face, size, vec2(0.0), point) || !map_cube_place(face, size, vec2(1.0, 0.0), along_x) ||
        !map_cube_place(face, size, vec2(0.0, 1.0), along_y))
        return MAP_BOUNDS_UNSURE;
    float depth = map_tap_depth(vec2(0.0));
    mat2 steps = mat2(along_x - point, along_y - point); // columns: texels per unit of offset
    vec2 gradient = vec2(0.0);
    if (abs(determinant(steps)) > MAP_CUBE_MIN_DETERMINANT)
        gradient = inverse(transpose(steps)) *
                   vec2(map_tap_depth(vec2(1.0, 0.0)) - depth, map_tap_depth(vec2(0.0, 1.0)) - depth);
    vec2 low = vec2(size), high = vec2(-1.0);
    float slack = 0.0;
    mat2 rotation = map_kernel_rotation();
    if (map_shape == MAP_KERNEL_TENT)
        map_tent_place(vec2(0.0));
    for (int k = 0; k < map_kernel_taps(); k++) {
        vec2 offset = map_kernel_tap(k, rotation, 1.0).xy, texel;
        if (!map_cube_place(face, size, offset, texel))
            return MAP_BOUNDS_UNSURE;
        low = min(low, texel);
        high = max(high, texel);
        slack = max(slack, abs(map_tap_depth(offset) - depth - dot(gradient, texel - point)));
    }
    int edge = MAP_BOUNDS_ROUNDING_TEXELS + 1;
    if (any(lessThan(floor(low), vec2(edge))) || any(greaterThan(floor(high), vec2(size - 1.0 - float(edge)))))
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
