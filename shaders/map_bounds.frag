#version 330 core
// A 2D map's depth bounds (demos/lib/map_bounds.c): each texel the least
// (r) and greatest (g) depth of its cell, MAP_BOUNDS_CELL_TEXELS texels on
// a side (a cell past the map's edge repeats the edge's texels, as the
// map's clamped reads do).
uniform sampler2D u_depths; // the map's depths as stored (compare mode off)

out vec4 out_bounds;

void main() {
    ivec2 first = ivec2(gl_FragCoord.xy) * MAP_BOUNDS_CELL_TEXELS;
    ivec2 last = textureSize(u_depths, 0) - 1;
    float least = 1.0, greatest = 0.0;
    for (int y = 0; y < MAP_BOUNDS_CELL_TEXELS; y++)
        for (int x = 0; x < MAP_BOUNDS_CELL_TEXELS; x++) {
            float depth = texelFetch(u_depths, min(first + ivec2(x, y), last), 0).r;
            least = min(least, depth);
            greatest = max(greatest, depth);
        }
    out_bounds = vec4(least, greatest, 0.0, 0.0);
}
