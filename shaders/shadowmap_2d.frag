#version 330 core
// Camera pass of a 2D shadow map: a spot or directional light's
// (demos/shadowmap.c), or any light's warped map (demos/psm.c).
#include "lighting.glsl"
#include "shadowmap.glsl"

uniform sampler2DShadow u_map;   // compare mode on: every read is a test
uniform mat4 u_light_matrix;     // world -> the light's clip space
uniform int u_texel_kind;        // SHADOW_MAP_TEXEL_*: orthographic, perspective, any projective map (a warp)
uniform float u_texel_scale;     // world texel: this (orthographic) or this x depth along the axis (perspective)
uniform vec3 u_light_axis;       // where a perspective map looks
uniform vec3 u_light_origin;
uniform bool u_receiver_plane;

// A matrix whose map coordinates hardly change with p (degenerate there)
// gives a huge texel rather than a division by zero.
const float SHADOWMAP_MIN_MAP_DERIVATIVE = 1e-20;
// Below this the screen -> map Jacobian is singular (the receiver seen
// edge-on, or no change across the pixel): no plane to follow, so every
// tap compares the centre's depth.
const float SHADOWMAP_MIN_SCREEN_TO_MAP_DETERMINANT = 1e-14;

// A warped map's texel size changes across the map, and its depth is not
// distance: the texel is how far p moves for its map coordinates to
// change by one texel, from the matrix's derivatives at p. (Along the light
// ray through p they do not change at all, so this measures across it.)
float shadowmap_projective_texel(vec3 p) {
    vec4 clip = u_light_matrix * vec4(p, 1.0);
    mat4 m = u_light_matrix;
    vec3 w_row = vec3(m[0][3], m[1][3], m[2][3]);
    vec3 du = (vec3(m[0][0], m[1][0], m[2][0]) - clip.x / clip.w * w_row) / clip.w;
    vec3 dv = (vec3(m[0][1], m[1][1], m[2][1]) - clip.y / clip.w * w_row) / clip.w;
    return 2.0 / (u_map_size * max(min(length(du), length(dv)), SHADOWMAP_MIN_MAP_DERIVATIVE));
}

float shadowmap_texel_world(vec3 p) {
    if (u_texel_kind == SHADOW_MAP_TEXEL_ORTHOGRAPHIC)
        return u_texel_scale;
    if (u_texel_kind == SHADOW_MAP_TEXEL_PERSPECTIVE)
        return u_texel_scale * max(dot(p - u_light_origin, u_light_axis), 0.0);
    return shadowmap_projective_texel(p);
}

// Receiver-plane depth bias (Isidoro, "Shadow mapping: GPU-based tips and
// techniques", GDC 2006): how the receiver's map depth changes per unit of
// map (u, v), from the screen derivatives of its (u, v, depth), so that each
// tap of a wide kernel compares the receiver's own depth there, not the
// centre's, which would shadow a slanted receiver with partial acne.
vec2 shadowmap_depth_gradient(vec3 uvz) {
    vec3 dx = dFdx(uvz), dy = dFdy(uvz);
    mat2 screen_to_map = mat2(dx.xy, dy.xy);
    if (!u_receiver_plane || abs(determinant(screen_to_map)) < SHADOWMAP_MIN_SCREEN_TO_MAP_DETERMINANT)
        return vec2(0.0);
    return inverse(transpose(screen_to_map)) * vec2(dx.z, dy.z);
}

// The point the kernel reads about (map coordinates and depth) and its
// depth gradient: set by shadowmap_visibility for shadowmap_kernel_read.
vec3 shadowmap_point;
vec2 shadowmap_gradient;

// offset: in map coordinates.
float shadowmap_kernel_read(vec2 offset) {
    return texture(u_map, vec3(shadowmap_point.xy + offset, shadowmap_point.z + dot(shadowmap_gradient, offset)));
}

float shadowmap_visibility(vec3 p, float depth_bias) {
    vec4 clip = u_light_matrix * vec4(p, 1.0);
    vec3 uvz = clip.xyz / clip.w * 0.5 + 0.5;
    vec2 gradient = shadowmap_depth_gradient(uvz); /* derivatives: before any branch */
    // Outside the map nothing was rendered: lit, never a wrapped read.
    if (clip.w <= 0.0 || any(lessThan(uvz.xy, vec2(0.0))) || any(greaterThan(uvz.xy, vec2(1.0))))
        return 1.0;
    uvz.z = min(uvz.z - depth_bias, 1.0);
    if (u_filter == SHADOW_MAP_KERNEL_SINGLE)
        return texture(u_map, uvz);
    shadowmap_point = uvz;
    shadowmap_gradient = gradient;
    vec2 texel = uvz.xy * u_map_size;
    return shadowmap_kernel_filter(texel - floor(texel + 0.5), u_map_size);
}

vec2 shadowmap_texel_coord(vec3 p) {
    vec4 clip = u_light_matrix * vec4(p, 1.0);
    return (clip.xy / clip.w * 0.5 + 0.5) * u_map_size;
}
