#version 330 core
// The moment maps' passes (demos/lib/map_moments.c) over one layer
// of a map. MAP_BLUR_FROM_DEPTH: the layer's depths (a map of kind
// MAP_BLUR_KIND) as moments (moments.glsl), a texel each. Else a
// separable box along u_axis over a 2D texture of moments: 2 u_radius + 1
// texels across, its two end texels weighted by the radius's fraction,
// reads past the edge clamped to it. The box's texels are read in pairs,
// one bilinear read between a pair's centres weighted by their sum (the
// texture's linear filter mixes them by their weights), so a box of N
// texels takes about N / 2 reads.
#include "map_texel.glsl"
#include "moments.glsl"

uniform float u_radius;                // texels past the centre one
uniform vec2 u_axis;                   // (1, 0) or (0, 1)
uniform int u_layer;                   // the depths' layer (a cube's face)

out vec4 out_moments;

// The box's most texels past the centre (C clamps the radius below it).
const int MOMENTS_BLUR_MAX_TEXELS = MAP_MOMENTS_MAX_BLUR_TEXELS + 1;

// Texel k's weight in the box (k texels from the centre, k >= 1).
float moments_box_weight(int k) {
    float whole = floor(u_radius);
    return float(k) <= whole ? 1.0 : float(k) == whole + 1.0 ? u_radius - whole : 0.0;
}

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
#if MAP_BLUR_FROM_DEPTH
    out_moments = moments_of(map_texel_depth(MAP_BLUR_KIND, texel, u_layer));
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
