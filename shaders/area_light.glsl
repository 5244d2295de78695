// Points on an area light, common/data/area_light.h's: the same hash, the
// same cells and the same concentric map, in the same order of
// operations, so that a shader that takes the reference's sample k of n
// for a pixel traces towards the point the reference traced
// (tests/test_hybrid.c compares the two on the soft scenes).

const float AREA_LIGHT_PI = 3.14159265;
// A unit from the top 24 bits of a hash: exact in float.
const float AREA_LIGHT_UNIT_SCALE = 1.0 / 16777216.0;

// PCG hash (Jarzynski and Olano, JCGT 9(3), 2020).
uint area_light_hash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

float area_light_unit(uint h) { return float(h >> 8u) * AREA_LIGHT_UNIT_SCALE; }

// Duff et al.'s basis (JCGT 6(1), 2017): t and b complete the unit n.
void area_light_basis(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

// Sample k of n on the unit disk, jittered by (u, v) within its cell of
// the unit square (floor(sqrt n) rows), carried to the disk by Shirley and
// Chiu's concentric map.
vec2 area_light_disk_sample(int k, int n, float u, float v) {
    int rows = int(sqrt(float(n)));
    int base = n / rows, extra = n - (n / rows) * rows;
    int long_cells = extra * (base + 1);
    int row = k < long_cells ? k / (base + 1) : extra + (k - long_cells) / base;
    int count = row < extra ? base + 1 : base;
    int first = row < extra ? row * (base + 1) : long_cells + (row - extra) * base;
    float a = 2.0 * (float(k - first) + u) / float(count) - 1.0;
    float b = 2.0 * (float(first) + v * float(count)) / float(n) - 1.0;
    float r = 0.0, phi = 0.0;
    if (a == 0.0 && b == 0.0) {
        r = 0.0;
    } else if (abs(a) > abs(b)) {
        r = a;
        phi = AREA_LIGHT_PI / 4.0 * (b / a);
    } else {
        r = b;
        phi = AREA_LIGHT_PI / 2.0 - AREA_LIGHT_PI / 4.0 * (a / b);
    }
    return vec2(r * cos(phi), r * sin(phi));
}

// Sample k of n of a light seen along the unit `axis` (towards it):
// centre.w 1, a disk of `radius` about centre.xyz facing the point, as a
// point (w 1); centre.w 0, a sun's cap of 1 - cos(angular radius) `cap`
// about axis, as the unit direction towards it (w 0). jitter: the
// caller's hash (area_light_hash), its two units the cell's jitter.
vec4 area_light_sample(vec4 centre, vec3 axis, float radius, float cap, int k, int n, uint jitter) {
    vec2 disk = area_light_disk_sample(k, n, area_light_unit(jitter), area_light_unit(area_light_hash(jitter)));
    vec3 t, b;
    area_light_basis(axis, t, b);
    if (centre.w == 0.0) {
        float r2 = dot(disk, disk);
        float one_minus_cos = r2 * cap;
        float sin_over_r = r2 > 0.0 ? sqrt(one_minus_cos * (2.0 - one_minus_cos) / r2) : 0.0;
        return vec4(axis * (1.0 - one_minus_cos) + t * (disk.x * sin_over_r) + b * (disk.y * sin_over_r), 0.0);
    }
    return vec4(centre.xyz + t * (disk.x * radius) + b * (disk.y * radius), 1.0);
}

// The sample taken j-th of n by a caller that stops early: a permutation
// of 0..n-1 whose every first 4^i fall one in each cell of a 2^i x 2^i
// grid (n a power of 4; any other n: j itself).
int area_light_progressive_index(int j, int n) {
    int bits = 0;
    while ((1 << (2 * bits)) < n)
        bits++;
    if ((1 << (2 * bits)) != n)
        return j;
    int row = 0, column = 0;
    for (int b = 0; b < bits; b++) {
        column |= ((j >> (2 * b)) & 1) << (bits - 1 - b);
        row |= ((j >> (2 * b + 1)) & 1) << (bits - 1 - b);
    }
    return row * (1 << bits) + column;
}
