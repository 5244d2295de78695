#version 330 core
// The moment maps' blur (demos/lib/shadow_map_moments.c), a separable box
// over one layer of a map, in two passes: the first reads the layer's
// depths (SHADOW_MAP_BLUR_FROM_DEPTH, from a map of kind
// SHADOW_MAP_BLUR_KIND) and sums their moments (moments.glsl) along x into
// a 2D texture; the second sums that along y into the moment map's layer.
// The box is 2 u_radius + 1 texels across, its two end texels weighted by
// the radius's fraction; reads past the layer's edge clamp to it.
#include "moments.glsl"

uniform float u_radius;             // texels past the centre one
uniform int u_layer;                // the first pass's layer (a cube's face)
uniform sampler2D u_source_2d;      // a 2D map's depths, or the first pass's sums
uniform samplerCube u_source_cube;  // a cube map's depths
uniform sampler2DArray u_source_array; // an array map's depths

out vec4 out_moments;

// The box's most texels past the centre (C clamps the radius below it).
const int MOMENTS_BLUR_MAX_TAPS = SHADOW_MAP_MOMENTS_MAX_BLUR_TEXELS + 1;

// The direction from a cube's centre through texel `texel` of face
// `face` (GL's table of faces, inverted; a texel's centre).
vec3 moments_cube_direction(ivec2 texel, int face, int size) {
    vec2 st = (vec2(texel) + 0.5) * 2.0 / float(size) - 1.0;
    if (face == SHADOW_MAP_FACE_POSITIVE_X) return vec3(1.0, -st.y, -st.x);
    if (face == SHADOW_MAP_FACE_NEGATIVE_X) return vec3(-1.0, -st.y, st.x);
    if (face == SHADOW_MAP_FACE_POSITIVE_Y) return vec3(st.x, 1.0, st.y);
    if (face == SHADOW_MAP_FACE_NEGATIVE_Y) return vec3(st.x, -1.0, -st.y);
    if (face == SHADOW_MAP_FACE_POSITIVE_Z) return vec3(st.x, -st.y, 1.0);
    return vec3(-st.x, -st.y, -1.0);
}

// The sampler the pass reads (only it is active: C puts each type on a
// unit of its own all the same).
#if SHADOW_MAP_BLUR_FROM_DEPTH && SHADOW_MAP_BLUR_KIND == SHADOW_MAP_CUBE
#define MOMENTS_SOURCE u_source_cube
#elif SHADOW_MAP_BLUR_FROM_DEPTH && SHADOW_MAP_BLUR_KIND == SHADOW_MAP_ARRAY
#define MOMENTS_SOURCE u_source_array
#else
#define MOMENTS_SOURCE u_source_2d
#endif

// What the pass sums at a texel of the layer: the moments of its depth,
// or the first pass's sums.
vec4 moments_source(ivec2 texel) {
#if SHADOW_MAP_BLUR_FROM_DEPTH
#if SHADOW_MAP_BLUR_KIND == SHADOW_MAP_CUBE
    int size = textureSize(MOMENTS_SOURCE, 0).x;
    return moments_of(texture(MOMENTS_SOURCE, moments_cube_direction(texel, u_layer, size)).r);
#elif SHADOW_MAP_BLUR_KIND == SHADOW_MAP_ARRAY
    return moments_of(texelFetch(MOMENTS_SOURCE, ivec3(texel, u_layer), 0).r);
#else
    return moments_of(texelFetch(MOMENTS_SOURCE, texel, 0).r);
#endif
#else
    return texelFetch(MOMENTS_SOURCE, texel, 0);
#endif
}

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    ivec2 axis = SHADOW_MAP_BLUR_FROM_DEPTH != 0 ? ivec2(1, 0) : ivec2(0, 1);
    int last = textureSize(MOMENTS_SOURCE, 0).x - 1;
    int whole = int(floor(u_radius));
    float end = u_radius - float(whole);
    vec4 sum = moments_source(texel);
    for (int k = 1; k <= MOMENTS_BLUR_MAX_TAPS && k <= whole + 1; k++) {
        float weight = k <= whole ? 1.0 : end;
        sum += weight * (moments_source(clamp(texel + k * axis, 0, last)) +
                         moments_source(clamp(texel - k * axis, 0, last)));
    }
    out_moments = sum / (2.0 * u_radius + 1.0);
}
