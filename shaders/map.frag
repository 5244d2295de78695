#version 330 core
// The camera pass of the shadow maps (demos/lib/map.c, for
// demos/shadowmap.c, demos/psm.c and demos/cascades.c): every light in one
// pass over the visible receivers, after a depth pre-pass, so that each
// visible pixel is shaded once and filtered once per light that reaches
// it. main, at the end, is the whole pass: the ambient term, then each
// light's share by its kind (map_share, map_light.glsl).
//
// C compiles one program per combination of the defines below
// (map_camera_program_load), in which each light's code is there
// only for its kind and the kernel's only for its shape: read from
// uniforms, every pixel would run every kind's code (llvmpipe runs both
// sides of a branch, masked). Samplers can be indexed only by constant
// expressions in GLSL 3.30, so the lights are listed one by one: light i
// is slot i of the light group the pass draws (common/gl/render.h,
// "Light groups"). The permutation's axes, and where each is read:
//   MAP_LIGHT_KIND_<i>   light i: off, on without a map (nothing it
//       reaches receives: added unshadowed), or with a 2D, cube or array
//       map or a cube's tiles in the atlas (a map_light_kind): here,
//       MAP_LIGHT;
//   MAP_TEXEL_KIND_<i>   how light i's 2D map's texel is measured
//       (a map_texel_kind): map_2d.glsl, map_texel_world;
//   MAP_TRANSMIT_SLOT_<i>   light i's element of its kind's
//       transmittance samplers: here, MAP_LIGHT;
//   MAP_PASS_SHAPE, MAP_PASS_KERNEL   the kernel's shape and
//       size: map.glsl (map_shape, map_kernel_size);
//   MAP_PASS_EARLY_OUT   the rim's taps first: map.glsl
//       (map_early_out), for map_light.glsl's kernel filter;
//   MAP_PASS_RECEIVER_PLANE   taps at the receiver plane's depth:
//       map.glsl (map_receiver_plane), and map_cube.glsl;
//   MAP_PASS_SOFT_LIGHTS, MAP_PASS_MOMENT_LIGHTS   bit i:
//       light i is soft (map_soft.glsl's filter), or reads its
//       moment map: here, MAP_SOFT and MAP_MOMENTS;
//   MAP_PASS_MOMENTS   which moments: moments.glsl;
//   MAP_PASS_TRANSMIT_LIGHTS   bit i: light i reads its transmittance
//       map (translucent casters' colour): here, MAP_TRANSMITS;
//   MAP_PASS_SHOW_*   the lecture's overlays: here (map_show_*),
//       for map_light.glsl's map_share, map_soft.glsl
//       (the penumbra) and main (the cascades' tint);
//   MAP_PASS_RAYS   shadow rays where the map is unsure, everywhere or
//       nowhere (a map_rays): map_light.glsl's map_share, with
//       map_ray_visibility here;
//   MAP_PASS_RAY_COUNTS   the rays counted: each pixel's rays and
//       traced lights into a second target (out_ray_counts);
//   MAP_PASS_MARK_RAYS   the pixels that rays would decide are marked in
//       a second target (out_rays_marked) and not traced: the pass
//       before the one that traces them alone (map.h, "Rays");
//   MAP_PASS_BOUNDS_LIGHTS   bit i: light i's 2D map is read by its depth
//       bounds, not its kernel (a marking pass's): map_2d.glsl.
// The other MAP_* names are the C constants these are compared with
// (map.c, map_defines).
#include "lighting.glsl"
#include "surface.glsl"

in vec3 v_position;
in vec3 v_normal;

uniform float u_constant_bias;   // texels of world distance, towards the light
uniform float u_normal_offset;   // texels, along the normal, times the slope
uniform vec2 u_depth_bias;       // max(x (1 - N.L), y) in map depth (0..1): the tutorials' bias
uniform int u_closed_outside;    // bit i: a closed caster with the eye inside it and light i outside
uniform float u_ambient;         // 1: the pass draws the ambient term too; 0: it adds its lights alone

// The triangle's own (flat) normal, on the side the eye sees: set first in
// main, where derivatives are defined, for map_share.
vec3 map_face_normal;

// Light i reaches this fragment's face from the inside of a closed caster
// (the eye is inside the mesh and sees the triangle's back, the light is
// outside the mesh and on the eye's side of the face): it can only have
// come through the mesh, which shadows it, as the reference's ray says.
// The map cannot tell where such a face meets one that faces the light:
// the depth between the two goes to zero at their edge and the
// slope-scaled bias of the steeper is thicker than the mesh there (seen
// from inside a box, a column of false light along the corner: the stress
// suite's camera_inside cases). With the eye outside, every fragment is
// as it was.
bool map_through_closed(int i, vec3 to_light) {
    return !gl_FrontFacing && (u_closed_outside & (1 << i)) != 0 && dot(map_face_normal, to_light) > 0.0;
}

layout(location = 0) out vec4 out_color; // explicit: GLSL ES asks it of every output where there are two
#if MAP_PASS_RAY_COUNTS && MAP_PASS_MARK_RAYS
#error "the rays' counts and marks are each the camera pass's second target"
#elif MAP_PASS_RAY_COUNTS
layout(location = 1) out vec4 out_ray_counts; // the pixel's rays, its lights traced
#elif MAP_PASS_MARK_RAYS
layout(location = 1) out vec4 out_rays_marked; // 1 where a light would be traced
#endif
// This fragment's shadow rays and the lights they were cast to; with
// MAP_PASS_MARK_RAYS, whether any light would have been traced.
int map_rays_cast = 0, map_lights_traced = 0;
bool map_rays_marked = false;

// The lecture's overlays, fixed per program like the kernel.
const bool map_show_texels = MAP_PASS_SHOW_TEXELS != 0;         // darken the map's texel boundaries
const bool map_show_texel_size = MAP_PASS_SHOW_TEXEL_SIZE != 0; // colour by a texel's size on screen
const bool map_show_cascades = MAP_PASS_SHOW_CASCADES != 0;     // tint by light 0's cascade
const bool map_show_penumbra = MAP_PASS_SHOW_PENUMBRA != 0;     // colour by PCSS's penumbra estimate
const bool map_show_unsure = MAP_PASS_SHOW_UNSURE != 0;         // tint where the map is unsure
const int map_rays = MAP_PASS_RAYS;
const bool map_mark_rays = MAP_PASS_MARK_RAYS != 0;
// With the penumbra overlay: the penumbra radius (world units) that the
// last soft filter estimated, or MAP_NO_PENUMBRA where its blocker
// search found no blocker (or no filter ran).
const float MAP_NO_PENUMBRA = -1.0;
float map_penumbra_estimate = MAP_NO_PENUMBRA;
// Whether the last soft filter's blocker search leaves the pixel unsure
// even where the filter's narrower disc is wholly in shadow: some of its
// taps unblocked (the light's cone partly occluded), or its region
// clamped short of the cone (MAP_SOFT_MAX_TEXELS: not conservative).
bool map_soft_search_unsure = false;

#include "bvh_trace.glsl"
#include "area_light.glsl"
#include "eye_ray.glsl"

// Where this fragment's shadow rays start, set first in main: its
// interpolated position, or where the pixel's eye ray meets its
// triangle's plane (u_exact_surface: an object huge seen from the eye, or
// any object where the GL's interpolation is not known to be close;
// common/gl/render.h, "Huge receivers"), the point the reference traces
// from. The plane is the one the interpolated positions lie in, which
// their rounding leaves within the triangle's plane where it moves them
// along it.
uniform vec3 u_eye;
uniform bool u_exact_surface;
vec3 map_ray_origin;

void map_set_ray_origin() {
    map_ray_origin = v_position;
    if (!u_exact_surface)
        return;
    vec3 ray = eye_ray_world(), n = map_face_normal;
    float t = dot(n, v_position - u_eye) / dot(n, ray);
    if (t > 0.0 && !isinf(t)) // else edge-on: the interpolated one
        map_ray_origin = u_eye + t * ray;
}

// Rays (map.h, "Rays"): an area light's samples per pixel (the reference's
// count: every sample is the reference's), the frame's rectangle in the
// target (x, y, width, height: the reference numbers pixels from the top
// row), and per light its disk's radius and a sun's cap (1 - cos of its
// angular radius).
uniform int u_ray_samples;
uniform ivec4 u_frame;
uniform vec2 u_light_area[SHADER_PASS_LIGHTS];

// What gets through, per channel, between the visible point itself and
// `target`, a point (w 1) or a direction towards a sun (w 0): 0 where an
// opaque caster stands between, the translucent ones' transmittances
// (bvh_transmittance, which leaves the point's surface). A ray to a point
// ends as many ulps of the target's coordinates and of its length short
// of it as the reference's, so that a light on a surface is not shadowed
// by it; a sun's ray runs past every caster.
vec3 map_ray_through(vec4 target) {
    vec3 o = map_ray_origin;
    if (target.w == 0.0)
        return bvh_transmittance(o, target.xyz * (length(o) + u_bvh_reach), 1.0);
    vec3 dir = target.xyz - o, a = abs(target.xyz);
    float len = length(dir);
    float t_max = 1.0 - float(BVH_SURFACE_ULPS) * BVH_FLOAT_EPSILON * (max(max(a.x, a.y), a.z) + len) / len;
    return bvh_transmittance(o, dir, t_max);
}

// Light i at this fragment by shadow rays, per channel: one to a hard
// light's centre; an area light's mean over the reference's samples for
// this pixel (the same points: its seed from the pixel and the light),
// taken in area_light_progressive_index's order and stopped where the
// first ones all agree: after MAP_RAY_FIRST_SAMPLES where they get
// through, after MAP_RAY_BLOCKED_SAMPLES where they are blocked (map.h,
// "Rays").
vec3 map_ray_visibility(int i, bool soft) {
    vec4 centre = lights_position[i];
    vec4 towards = centre.w == 0.0 ? vec4(-lights_direction[i].xyz, 0.0) : centre;
    map_lights_traced++;
    if (!soft) {
        map_rays_cast++;
        return map_ray_through(towards);
    }
    ivec2 q = ivec2(gl_FragCoord.xy) - u_frame.xy;
    uint pixel = uint((u_frame.w - 1 - q.y) * u_frame.z + q.x);
    uint seed = area_light_hash(pixel ^ area_light_hash(uint(i)));
    vec3 axis = lighting_to_light(i, map_ray_origin);
    vec3 sum = vec3(0.0), first = vec3(0.0);
    bool agree = true;
    int traced = 0;
    for (int j = 0; j < u_ray_samples; j++) {
        int k = area_light_progressive_index(j, u_ray_samples);
        vec4 target = area_light_sample(centre.w == 0.0 ? vec4(axis, 0.0) : centre, axis, u_light_area[i].x,
                                        u_light_area[i].y, k, u_ray_samples, area_light_hash(seed + uint(k)));
        vec3 through = map_ray_through(target);
        first = traced == 0 ? through : first;
        agree = agree && through == first;
        sum += through;
        traced++;
        if (agree && traced == (first == vec3(0.0) ? MAP_RAY_BLOCKED_SAMPLES : MAP_RAY_FIRST_SAMPLES))
            break;
    }
    map_rays_cast += traced;
    return sum / float(traced);
}

#include "moments.glsl"
#include "map.glsl"

// Whether no caster can stand between this fragment and area light i's
// disk: the cone from the point to the disk, which holds all of its rays,
// meets no leaf's box of the casters' hierarchy (a sun's disk as seen at
// the ray's end, its tangent of angular radius u_light_size).
bool map_light_cone_clear(int i) {
    vec4 centre = lights_position[i];
    vec3 o = map_ray_origin;
    if (centre.w == 0.0) {
        float reach = length(o) + u_bvh_reach;
        return bvh_cone_clear(o, -lights_direction[i].xyz * reach, 1.0, reach * u_light_size[i]);
    }
    return bvh_cone_clear(o, centre.xyz - o, 1.0, u_light_area[i].x);
}

#include "map_2d.glsl"
#include "map_cube.glsl"
#include "map_array.glsl"
#include "map_tiles.glsl"

#if SHADER_PASS_LIGHTS != 8
#error "map.frag lists SHADER_PASS_LIGHTS lights one by one: one MAP_LIGHT line each"
#endif
// Light i's share by its kind (a constant: the other kinds' code is dropped).
// Light i is soft (an area light, filtered by map_soft.glsl) where
// its bit of MAP_PASS_SOFT_LIGHTS is set.
// Light i reads its moment map (moments.glsl; in its depths' sampler)
// where its bit of MAP_PASS_MOMENT_LIGHTS is set.
#define MAP_SOFT(i) (((MAP_PASS_SOFT_LIGHTS >> i) & 1) != 0)
#define MAP_MOMENTS(i) (((MAP_PASS_MOMENT_LIGHTS >> i) & 1) != 0)
// Light i reads its transmittance map where its bit of
// MAP_PASS_TRANSMIT_LIGHTS is set, in element MAP_TRANSMIT_SLOT_<i> of
// its kind's samplers (MAP_PASS_TRANSMIT_SLOTS of them: one a light
// that reads one). Without any, their names stand for the depths'
// (map_2d.glsl...). A WebGL program counts every sampler its code names
// against its units, read or not.
#define MAP_TRANSMITS(i) (((MAP_PASS_TRANSMIT_LIGHTS >> i) & 1) != 0)
#define MAP_LIGHT(i, kind, texel_kind, slot) \
    if (kind == MAP_LIGHT_UNSHADOWED) \
        c += lighting_unshadowed(i, v_position, n, surface_albedo); \
    else if (kind == MAP_LIGHT_2D) \
        c += map_share(u_maps_2d[i], u_depths_2d[i], u_transmittances_2d[slot], u_bounds[i], i, texel_kind, \
                       MAP_SOFT(i), MAP_MOMENTS(i), MAP_TRANSMITS(i), n); \
    else if (kind == MAP_LIGHT_CUBE) \
        c += map_share(u_maps_cube[i], u_depths_cube[i], u_transmittances_cube[slot], u_bounds[i], i, texel_kind, \
                       MAP_SOFT(i), MAP_MOMENTS(i), MAP_TRANSMITS(i), n); \
    else if (kind == MAP_LIGHT_ARRAY) \
        c += map_share(u_maps_array[i], u_depths_array[i], u_transmittances_array[slot], u_bounds[i], i, \
                       texel_kind, MAP_SOFT(i), MAP_MOMENTS(i), MAP_TRANSMITS(i), n); \
    else if (kind == MAP_LIGHT_TILES) \
        c += map_share(u_atlas, u_atlas, u_atlas, u_bounds[i], i, texel_kind, false, false, false, n)

void main() {
    // Two-sided: open meshes (the teapot) show their inside.
    vec3 n = normalize(gl_FrontFacing ? v_normal : -v_normal);
    surface_begin();
    map_face_normal = cross(dFdx(v_position), dFdy(v_position));
    if (dot(map_face_normal, n) < 0.0)
        map_face_normal = -map_face_normal;
    if (map_rays != MAP_RAYS_OFF)
        map_set_ray_origin();
    vec3 c = u_ambient * lighting_ambient(surface_albedo);
    MAP_LIGHT(0, MAP_LIGHT_KIND_0, MAP_TEXEL_KIND_0, MAP_TRANSMIT_SLOT_0);
    MAP_LIGHT(1, MAP_LIGHT_KIND_1, MAP_TEXEL_KIND_1, MAP_TRANSMIT_SLOT_1);
    MAP_LIGHT(2, MAP_LIGHT_KIND_2, MAP_TEXEL_KIND_2, MAP_TRANSMIT_SLOT_2);
    MAP_LIGHT(3, MAP_LIGHT_KIND_3, MAP_TEXEL_KIND_3, MAP_TRANSMIT_SLOT_3);
    MAP_LIGHT(4, MAP_LIGHT_KIND_4, MAP_TEXEL_KIND_4, MAP_TRANSMIT_SLOT_4);
    MAP_LIGHT(5, MAP_LIGHT_KIND_5, MAP_TEXEL_KIND_5, MAP_TRANSMIT_SLOT_5);
    MAP_LIGHT(6, MAP_LIGHT_KIND_6, MAP_TEXEL_KIND_6, MAP_TRANSMIT_SLOT_6);
    MAP_LIGHT(7, MAP_LIGHT_KIND_7, MAP_TEXEL_KIND_7, MAP_TRANSMIT_SLOT_7);
    if (map_show_cascades && MAP_LIGHT_KIND_0 == MAP_LIGHT_ARRAY)
        c = map_cascade_tint(0, c);
    out_color = vec4(c, 1.0);
#if MAP_PASS_RAY_COUNTS
    out_ray_counts = vec4(float(map_rays_cast), float(map_lights_traced), 0.0, 0.0);
#elif MAP_PASS_MARK_RAYS
    out_rays_marked = vec4(map_rays_marked ? 1.0 : 0.0);
#endif
}
