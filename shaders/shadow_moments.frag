#version 330 core
// The moment maps' passes (demos/lib/shadow_map_moments.c) over one layer
// of a map. SHADOW_MAP_BLUR_FROM_DEPTH: the layer's depths (a map of kind
// SHADOW_MAP_BLUR_KIND) as moments (moments.glsl), a texel each. Else a
// separable box along u_axis over a 2D texture of moments: 2 u_radius + 1
// texels across, its two end texels weighted by the radius's fraction,
// reads past the edge clamped to it. The box's texels are read in pairs,
// one bilinear read between a pair's centres weighted by their sum (the
// texture's linear filter mixes them by their weights), so a box of N
// texels takes about N / 2 reads.
#include "moments.glsl"

uniform float u_radius;                // texels past the centre one
uniform vec2 u_axis;                   // (1, 0) or (0, 1)
uniform int u_layer;                   // the depths' layer (a cube's face)
uniform sampler2D u_source_2d;         // a 2D map's depths, or moments to blur (linear filter)
uniform samplerCube u_source_cube;     // a cube map's depths
uniform sampler2DArray u_source_array; // an array map's depths

out vec4 out_moments;

// The box's most texels past the centre (C clamps the radius below it).
const int MOMENTS_BLUR_MAX_TEXELS = SHADOW_MAP_MOMENTS_MAX_BLUR_TEXELS + 1;

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

// Texel k's weight in the box (k texels from the centre, k >= 1).
float moments_box_weight(int k) {
    float whole = floor(u_radius);
    return float(k) <= whole ? 1.0 : float(k) == whole + 1.0 ? u_radius - whole : 0.0;
}

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
#if SHADOW_MAP_BLUR_FROM_DEPTH && SHADOW_MAP_BLUR_KIND == SHADOW_MAP_CUBE
    int size = textureSize(u_source_cube, 0).x;
    out_moments = moments_of(texture(u_source_cube, moments_cube_direction(texel, u_layer, size)).r);
#elif SHADOW_MAP_BLUR_FROM_DEPTH && SHADOW_MAP_BLUR_KIND == SHADOW_MAP_ARRAY
    out_moments = moments_of(texelFetch(u_source_array, ivec3(texel, u_layer), 0).r);
#elif SHADOW_MAP_BLUR_FROM_DEPTH
    out_moments = moments_of(texelFetch(u_source_2d, texel, 0).r);
#else
    vec2 size = vec2(textureSize(u_source_2d, 0));
    vec2 centre = (vec2(texel) + 0.5) / size, step = u_axis / size;
    vec4 sum = texelFetch(u_source_2d, texel, 0);
    // Pairs (k, k + 1) for k = 1, 3, 5...: both sides at once.
    for (int k = 1; k <= MOMENTS_BLUR_MAX_TEXELS && float(k) <= u_radius + 1.0; k += 2) {
        float a = moments_box_weight(k), b = moments_box_weight(k + 1);
        if (a + b <= 0.0)
            break;
        float offset = float(k) + b / (a + b);
        sum += (a + b) * (texture(u_source_2d, centre + offset * step) + texture(u_source_2d, centre - offset * step));
    }
    out_moments = sum / (2.0 * u_radius + 1.0);
#endif
}
