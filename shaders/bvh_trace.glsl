// Shadow rays against the casters' hierarchy (common/data/bvh.h: its
// layout, and the same tests in the same order as bvh_transmittance), read from
// one RGBA32F texture (common/gl/bvh_gpu.h): a texture buffer where
// BVH_TEXTURE_BUFFER is 1, else 2D, BVH_GPU_TEXTURE_WIDTH texels wide. The
// nodes, two texels each, then the triangles, three each.
// u_bvh_node_count 0: no casters, every ray gets through.
// u_bvh_reach: the farthest corner of the casters' box from the origin.
uniform int u_bvh_node_count;
uniform float u_bvh_reach;

// A direction's zero component is taken as this, of its sign.
const float BVH_TINY_DIRECTION = 1e-30;
// A float's ulp at 1 (C's FLT_EPSILON, 2^-23), and Ize's gamma(3) from
// the unit roundoff, half of it: a box's far distance is widened by it.
const float BVH_FLOAT_EPSILON = 1.1920929e-7;
const float BVH_FAR_WIDENING = 1.0 + 3.0 * BVH_FLOAT_EPSILON / (1.0 - 1.5 * BVH_FLOAT_EPSILON);

#if BVH_TEXTURE_BUFFER
uniform samplerBuffer u_bvh;
vec4 bvh_texel(int k) { return texelFetch(u_bvh, k); }
#else
uniform sampler2D u_bvh;
vec4 bvh_texel(int k) { return texelFetch(u_bvh, ivec2(k % BVH_GPU_TEXTURE_WIDTH, k / BVH_GPU_TEXTURE_WIDTH), 0); }
#endif

#if BVH_RECORDS
// Casters whose surface the rays read (common/data/bvh.h: cut-out or
// translucent): a triangle whose first vertex's w is r > 0 has record
// r - 1 at u_bvh_records_first, four texels, and its texture's texels at
// u_bvh_texels_first, linear colour and alpha (common/gl/bvh_gpu.h). A ray
// passes a cut-out where scene_object_cut_out (common/data/scene.c) says
// it has no surface, and a translucent one filtered by
// scene_object_transmittance: the same bilinear read of level 0, the same
// wrap (common/data/texture.c).
uniform int u_bvh_records_first;
uniform int u_bvh_texels_first;

// texture.h's texture_wrap and bvh_gpu.h's packing of two of them.
const int BVH_WRAP_MIRRORED_REPEAT = 1;
const int BVH_WRAP_CLAMP_TO_EDGE = 2;
const int BVH_WRAP_BASE = 4;
// Beyond this a texel coordinate says nothing of where it lands
// (texture.c's guard).
const float BVH_TEXEL_RANGE = 1073741823.0;

// Texel index i of n by the wrap mode.
int bvh_wrap(int mode, int i, int n) {
    if (mode == BVH_WRAP_CLAMP_TO_EDGE)
        return clamp(i, 0, n - 1);
    int period = mode == BVH_WRAP_MIRRORED_REPEAT ? 2 * n : n;
    int r = i - period * int(floor(float(i) / float(period)));
    if (mode != BVH_WRAP_MIRRORED_REPEAT)
        return r;
    int a = r - n;
    return (n - 1) - (a >= 0 ? a : -(1 + a));
}

// What record `record`'s triangle lets through at the barycentric
// weights `weight` of its corners: everything where a cut-out has no
// surface, nothing where it has, a translucent one's transmittance
// (1 - a) + a C.
vec3 bvh_surface(int record, vec3 weight) {
    int k = u_bvh_records_first + 4 * record;
    vec4 r0 = bvh_texel(k), r1 = bvh_texel(k + 1), r2 = bvh_texel(k + 2), r3 = bvh_texel(k + 3);
    vec2 uv = weight.x * r0.xy + weight.y * r0.zw + weight.z * r1.xy;
    vec4 texel = vec4(1.0);
    int width = int(r2.y), height = int(r2.z);
    if (width > 0) {
        int first = u_bvh_texels_first + int(r2.x), wraps = int(r2.w);
        int wrap_u = wraps / BVH_WRAP_BASE, wrap_v = wraps - BVH_WRAP_BASE * wrap_u;
        float x = uv.x * float(width) - 0.5, y = uv.y * float(height) - 0.5;
        float fx = floor(x), fy = floor(y), ax = x - fx, ay = y - fy;
        if (!(abs(fx) < BVH_TEXEL_RANGE && abs(fy) < BVH_TEXEL_RANGE)) {
            fx = fy = ax = ay = 0.0;
        }
        int x0 = bvh_wrap(wrap_u, int(fx), width), x1 = bvh_wrap(wrap_u, int(fx) + 1, width);
        int y0 = bvh_wrap(wrap_v, int(fy), height), y1 = bvh_wrap(wrap_v, int(fy) + 1, height);
        texel = (1.0 - ax) * (1.0 - ay) * bvh_texel(first + y0 * width + x0);
        texel += ax * (1.0 - ay) * bvh_texel(first + y0 * width + x1);
        texel += (1.0 - ax) * ay * bvh_texel(first + y1 * width + x0);
        texel += ax * ay * bvh_texel(first + y1 * width + x1);
    }
    float alpha = r1.z * texel.a;
    if (alpha < r1.w)
        return vec3(1.0);
    return r3.w > 0.0 ? 1.0 - alpha + alpha * r3.rgb * texel.rgb : vec3(0.0);
}
#endif

// One component of v by index (GLSL ES indexes vectors by constants only
// in some drivers' eyes; a select is safe everywhere).
float bvh_component(vec3 v, int k) { return k == 0 ? v.x : (k == 1 ? v.y : v.z); }

// 1 / dir, a zero component taken as BVH_TINY_DIRECTION of its sign.
vec3 bvh_inverse(vec3 dir) {
    vec3 tiny = BVH_TINY_DIRECTION * mix(vec3(1.0), sign(dir), notEqual(dir, vec3(0.0)));
    return 1.0 / mix(dir, tiny, lessThan(abs(dir), vec3(BVH_TINY_DIRECTION)));
}

// Whether the segment meets the box lo..hi grown by the cone's radius
// where the segment crosses it (common/data/bvh.c's bvh_cone_box).
bool bvh_cone_box(vec3 origin, vec3 inverse, float t_max, vec3 lo, vec3 hi, float end_radius) {
    float near = 0.0, far = t_max;
    for (int pass = 0; pass < 2 && near <= far; pass++) {
        float grow = pass == 0 ? end_radius : end_radius * min(far / t_max, 1.0);
        vec3 t0 = (lo - vec3(grow) - origin) * inverse, t1 = (hi + vec3(grow) - origin) * inverse;
        vec3 near3 = min(t0, t1), far3 = max(t0, t1) * BVH_FAR_WIDENING;
        near = max(max(near3.x, near3.y), max(near3.z, 0.0));
        far = min(min(far3.x, far3.y), min(far3.z, t_max));
    }
    return near <= far;
}

// Whether no caster can meet the cone along origin + t dir, 0 < t < t_max,
// of radius growing from 0 to end_radius at t_max (bvh.h's
// bvh_cone_clear): conservative, false where a leaf's grown box is near.
bool bvh_cone_clear(vec3 origin, vec3 dir, float t_max, float end_radius) {
    if (u_bvh_node_count == 0)
        return true;
    vec3 inverse = bvh_inverse(dir);
    int stack[BVH_MAX_DEPTH];
    int top = 0, node = 0;
    for (;;) {
        vec4 lo = bvh_texel(2 * node), hi = bvh_texel(2 * node + 1);
        if (bvh_cone_box(origin, inverse, t_max, lo.xyz, hi.xyz, end_radius)) {
            if (hi.w > 0.0)
                return false;
            stack[top++] = int(lo.w);
            node++;
            continue;
        }
        if (top == 0)
            return true;
        node = stack[--top];
    }
    return true;
}

// The share of each channel of light that gets through origin + t dir,
// 0 < t < t_max, past every caster's triangle other than the surface the
// ray leaves (BVH_SURFACE_ULPS): 0 where an opaque one meets it, else the
// product of the translucent ones' transmittances (bvh.h's
// bvh_transmittance).
vec3 bvh_transmittance(vec3 origin, vec3 dir, float t_max) {
    vec3 through = vec3(1.0);
    if (u_bvh_node_count == 0)
        return through;
    vec3 inverse = bvh_inverse(dir);
    // Woop et al.'s shear: kz the largest axis, kx and ky the others,
    // swapped where dir[kz] < 0 to keep the winding.
    vec3 a = abs(dir);
    int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    float dz = bvh_component(dir, kz);
    if (dz < 0.0) {
        int swap = kx;
        kx = ky;
        ky = swap;
    }
    vec3 o = abs(origin);
    float surface = float(BVH_SURFACE_ULPS) * BVH_FLOAT_EPSILON * max(max(o.x, o.y), o.z);
    vec3 shear = vec3(bvh_component(dir, kx) / dz, bvh_component(dir, ky) / dz, 1.0 / dz);
    int stack[BVH_MAX_DEPTH];
    int top = 0, node = 0;
    for (;;) {
        vec4 lo = bvh_texel(2 * node), hi = bvh_texel(2 * node + 1);
        vec3 t0 = (lo.xyz - origin) * inverse, t1 = (hi.xyz - origin) * inverse;
        vec3 near3 = min(t0, t1), far3 = max(t0, t1) * BVH_FAR_WIDENING;
        float near = max(max(near3.x, near3.y), max(near3.z, 0.0));
        float far = min(min(far3.x, far3.y), min(far3.z, t_max));
        if (near <= far) {
            if (hi.w > 0.0) {
                int first = 2 * u_bvh_node_count + 3 * int(lo.w), end = first + 3 * int(hi.w);
                for (int k = first; k < end; k += 3) {
                    vec3 pa = bvh_texel(k).xyz - origin;
                    vec3 pb = bvh_texel(k + 1).xyz - origin;
                    vec3 pc = bvh_texel(k + 2).xyz - origin;
                    float az = bvh_component(pa, kz), bz = bvh_component(pb, kz), cz = bvh_component(pc, kz);
                    float ax = bvh_component(pa, kx) - shear.x * az, ay = bvh_component(pa, ky) - shear.y * az;
                    float bx = bvh_component(pb, kx) - shear.x * bz, by = bvh_component(pb, ky) - shear.y * bz;
                    float cx = bvh_component(pc, kx) - shear.x * cz, cy = bvh_component(pc, ky) - shear.y * cz;
                    float u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax;
                    if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0))
                        continue;
                    float det = u + v + w;
                    if (det == 0.0)
                        continue;
                    vec3 normal = cross(pb - pa, pc - pa);
                    if (abs(dot(normal, pa)) <= surface * length(normal))
                        continue;
                    float t = shear.z * (u * az + v * bz + w * cz);
                    if (det > 0.0 ? (t > 0.0 && t < t_max * det) : (t < 0.0 && t > t_max * det)) {
#if BVH_RECORDS
                        float record = bvh_texel(k).w;
                        through *= record > 0.0 ? bvh_surface(int(record) - 1, vec3(u, v, w) / det) : vec3(0.0);
#else
                        through = vec3(0.0);
#endif
                        if (through == vec3(0.0))
                            return through;
                    }
                }
            } else {
                stack[top++] = int(lo.w);
                node++;
                continue;
            }
        }
        if (top == 0)
            return through;
        node = stack[--top];
    }
    return through;
}
