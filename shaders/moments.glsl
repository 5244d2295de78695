// Moment shadow maps: what a texel stores for a depth and what a filtered
// texel says of a point's visibility, for MAP_PASS_MOMENTS (a
// map_moments from C). Shared by the blur's first pass
// (shadow_moments.frag, which writes moments_of) and the camera pass
// (map.frag, which reads moments_visibility). Depths are the map's
// as stored, 0..1 (a perspective map's too: its range is spent near the
// light, where the casters are).
//   vsm    Donnelly & Lauritzen, "Variance shadow maps", I3D 2006: the mean
//          and mean square of the depth, and Chebyshev's one-sided bound
//          on the share nearer than the point; light bleeding reduced by
//          Lauritzen's linstep (GPU Gems 3, ch. 8).
//   evsm2  Lauritzen & McCool, "Layered variance shadow maps", GI 2008
//   evsm4  (exponential variance): the bound on e^(c d) (evsm2), and on
//          -e^(-c d) too (evsm4, the smaller of the two), d in [-1, 1].
//   msm    Peters & Klein, "Moment shadow mapping", I3D 2015: d, d^2, d^3,
//          d^4 (d in [-1, 1]) and the Hamburger 4MSM bound, from moments
//          biased towards a fixed distribution first (the paper's bias;
//          32-bit float storage, so without its 16-bit quantization).

// VSM: the bound's share below this counts as shadow, the rest rescaled
// to 0..1 (Lauritzen's light-bleeding reduction: a receiver behind two
// casters gets at most this much light through the nearer one's edge).
const float MOMENTS_VSM_BLEEDING = 0.3;
// VSM: the least variance (depth units squared): a lit receiver's own
// depths, blurred over a slope, vary a little about the mean.
const float MOMENTS_VSM_MIN_VARIANCE = 2e-6;
// EVSM: the warp's exponents for 32-bit floats. The second moment is
// e^(2 c) at d = 1: below FLT_MAX (about e^88.7) for c up to 44; 42
// leaves room for rounding. The negative warp shares the bound.
const float MOMENTS_EVSM_POSITIVE = 42.0;
const float MOMENTS_EVSM_NEGATIVE = 42.0;
// EVSM: the least standard deviation of the depth (in -1..1) before the
// warp, carried through its slope (c e^(c d)) into the warped variance.
const float MOMENTS_EVSM_MIN_DEVIATION = 1e-4;
// MSM: the bias's weight (the paper's alpha) and the moments it mixes in.
const float MOMENTS_MSM_ALPHA = 3e-5;
const vec4 MOMENTS_MSM_BIAS_TARGET = vec4(0.0, 0.63, 0.0, 0.63);

// The stored depth 0..1 on -1..1, where EVSM's exponents and MSM's
// moments are taken.
float moments_signed_depth(float depth) { return depth * 2.0 - 1.0; }

vec2 moments_evsm_warp(float depth) {
    float d = moments_signed_depth(depth);
    return vec2(exp(MOMENTS_EVSM_POSITIVE * d), -exp(-MOMENTS_EVSM_NEGATIVE * d));
}

// What a texel of this depth stores (its unused channels 0).
vec4 moments_of(float depth) {
    if (MAP_PASS_MOMENTS == MAP_MOMENTS_VSM)
        return vec4(depth, depth * depth, 0.0, 0.0);
    if (MAP_PASS_MOMENTS == MAP_MOMENTS_MSM) {
        float d = moments_signed_depth(depth), d2 = d * d;
        return vec4(d, d2, d2 * d, d2 * d2);
    }
    vec2 w = moments_evsm_warp(depth);
    return vec4(w.x, w.x * w.x, w.y, w.y * w.y);
}

// Chebyshev's one-sided bound: of a distribution of this mean and mean
// square (the variance at least min_variance), at most this share lies
// beyond t; 1 where t is not past the mean.
float moments_chebyshev(vec2 m, float t, float min_variance) {
    float variance = max(m.y - m.x * m.x, min_variance);
    float d = t - m.x;
    return d <= 0.0 ? 1.0 : variance / (variance + d * d);
}

// The warped variance's floor at warped value w (positive warp: slope c w).
float moments_evsm_min_variance(float w, float c) {
    float deviation = MOMENTS_EVSM_MIN_DEVIATION * c * w;
    return deviation * deviation;
}

// Hamburger 4MSM (the paper's algorithm 3): the moments b, biased, are
// the first four of a distribution of depths; of all distributions with
// them, the least share in front of z is G, found from the two other
// support points of the canonical one through z: the roots of the
// quadratic whose coefficients c solve B c = (1, z, z^2), B the 3x3 Hankel
// matrix of (1, b), here by its LDL^T factorisation.
float moments_msm_visibility(vec4 b, float z) {
    b = mix(b, MOMENTS_MSM_BIAS_TARGET, MOMENTS_MSM_ALPHA);
    // B = L D L^T, L unit lower triangular: column 1 is (1, b1, b2).
    float d2 = b.y - b.x * b.x;
    float l32 = (b.z - b.x * b.y) / d2;
    float d3 = b.w - b.y * b.y - l32 * l32 * d2;
    // L y = (1, z, z^2), then D, then L^T c = y.
    float y2 = z - b.x;
    float y3 = z * z - b.y - l32 * y2;
    float c3 = y3 / d3;
    float c2 = y2 / d2 - l32 * c3;
    float c1 = 1.0 - b.x * c2 - b.y * c3;
    // The roots z2 <= z3 of c1 + c2 x + c3 x^2.
    float half_p = 0.5 * c2 / c3, q = c1 / c3;
    float root = sqrt(max(half_p * half_p - q, 0.0));
    float z2 = -half_p - root, z3 = -half_p + root;
    float g;
    if (z <= z2)
        g = 0.0;
    else if (z <= z3)
        g = (z * z3 - b.x * (z + z3) + b.y) / ((z3 - z2) * (z - z2));
    else
        g = 1.0 - (z2 * z3 - b.x * (z2 + z3) + b.y) / ((z - z2) * (z - z3));
    return 1.0 - clamp(g, 0.0, 1.0);
}

// The visibility at the stored depth `depth` of a point, from its
// filtered moments m.
float moments_visibility(vec4 m, float depth) {
    if (MAP_PASS_MOMENTS == MAP_MOMENTS_VSM) {
        float p = moments_chebyshev(m.xy, depth, MOMENTS_VSM_MIN_VARIANCE);
        return clamp((p - MOMENTS_VSM_BLEEDING) / (1.0 - MOMENTS_VSM_BLEEDING), 0.0, 1.0);
    }
    if (MAP_PASS_MOMENTS == MAP_MOMENTS_MSM)
        return moments_msm_visibility(m, moments_signed_depth(depth));
    vec2 w = moments_evsm_warp(depth);
    float positive = moments_chebyshev(m.xy, w.x, moments_evsm_min_variance(w.x, MOMENTS_EVSM_POSITIVE));
    if (MAP_PASS_MOMENTS == MAP_MOMENTS_EVSM2)
        return positive;
    return min(positive, moments_chebyshev(m.zw, w.y, moments_evsm_min_variance(-w.y, MOMENTS_EVSM_NEGATIVE)));
}
