#version 330 core
// The map inset's reduction (demos/lib/map_overlay.c): layer
// u_layer (a cube's face) of light 0's map, of kind
// MAP_REDUCE_KIND, cut into blocks of u_factor x u_factor texels,
// one block a texel of the target (the blocks of the last row and column
// cut at the map's edge). Each holds the nearest and the farthest depth
// stored in its block, among the texels that hold one: a depth below the
// cleared value, 1. A block that holds none stores (1, 0).
#include "map_texel.glsl"

uniform int u_factor;
uniform int u_layer;

out vec2 out_range;

void main() {
    int size = map_texel_size(MAP_REDUCE_KIND);
    ivec2 first = ivec2(gl_FragCoord.xy) * u_factor, end = min(first + u_factor, ivec2(size));
    vec2 range = vec2(1.0, 0.0);
    for (int y = first.y; y < end.y; y++)
        for (int x = first.x; x < end.x; x++) {
            float d = map_texel_depth(MAP_REDUCE_KIND, ivec2(x, y), u_layer);
            if (d < 1.0)
                range = vec2(min(range.x, d), max(range.y, d));
        }
    out_range = range;
}
