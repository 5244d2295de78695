#version 330 core
// A map's depth bounds (demos/lib/map_bounds.c; shaders/map.glsl reads
// them): per cell of MAP_BOUNDS_CELL_TEXELS texels on a side, the least
// squares plane of its depths, its slope per texel on x and y (r, g), and
// the least and greatest height at the cell's centre (b, a) of the planes
// of that slope through its texels: every texel's depth lies between
// those two planes (a cell past the map's edge repeats the edge's texels,
// as the map's clamped reads do, each at its place in the cell). A 2D map's
// cells in one square; with MAP_BOUNDS_CUBE a cube map's, its six faces
// side by side (+X -X +Y -Y +Z -Z), each texel read by the direction
// through its centre (GL's face table, map_cube.glsl's map_cube_face
// the other way).
#if MAP_BOUNDS_CUBE
uniform samplerCube u_depths; // the map's depths as stored (compare mode off, nearest)
#else
uniform sampler2D u_depths;
#endif
uniform int u_size; // the map's texels on a side

out vec4 out_bounds;

#if MAP_BOUNDS_CUBE
// Texel q of face `face`'s depth.
float map_bounds_depth(int face, ivec2 q) {
    vec2 c = (vec2(q) + 0.5) / float(u_size) * 2.0 - 1.0;
    vec3 directions[6] = vec3[](vec3(1.0, -c.y, -c.x), vec3(-1.0, -c.y, c.x), vec3(c.x, 1.0, c.y),
                                vec3(c.x, -1.0, -c.y), vec3(c.x, -c.y, 1.0), vec3(-c.x, -c.y, -1.0));
    return texture(u_depths, directions[face]).r;
}
#else
float map_bounds_depth(int face, ivec2 q) { return texelFetch(u_depths, q, 0).r; }
#endif

void main() {
    int cells = (u_size + MAP_BOUNDS_CELL_TEXELS - 1) / MAP_BOUNDS_CELL_TEXELS;
    ivec2 cell = ivec2(gl_FragCoord.xy);
    int face = cell.x / cells;
    ivec2 first = ivec2(cell.x - face * cells, cell.y) * MAP_BOUNDS_CELL_TEXELS;
    // A texel's place from the cell's centre, and the sum of its squares
    // on one axis over the whole cell: the least squares slope's divisor.
    float middle = 0.5 * float(MAP_BOUNDS_CELL_TEXELS - 1), squares = 0.0;
    float depths[MAP_BOUNDS_CELL_TEXELS * MAP_BOUNDS_CELL_TEXELS];
    vec2 moment = vec2(0.0);
    for (int y = 0; y < MAP_BOUNDS_CELL_TEXELS; y++)
        for (int x = 0; x < MAP_BOUNDS_CELL_TEXELS; x++) {
            vec2 place = vec2(x, y) - middle;
            float depth = map_bounds_depth(face, min(first + ivec2(x, y), ivec2(u_size - 1)));
            depths[y * MAP_BOUNDS_CELL_TEXELS + x] = depth;
            moment += place * depth;
            squares += place.x * place.x;
        }
    vec2 slope = moment / squares;
    float least = 1e30, greatest = -1e30;
    for (int y = 0; y < MAP_BOUNDS_CELL_TEXELS; y++)
        for (int x = 0; x < MAP_BOUNDS_CELL_TEXELS; x++) {
            float height = depths[y * MAP_BOUNDS_CELL_TEXELS + x] - dot(slope, vec2(x, y) - middle);
            least = min(least, height);
            greatest = max(greatest, height);
        }
    out_bounds = vec4(slope, least, greatest);
}
