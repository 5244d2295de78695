/* Tests of demos/lib/wedge_area.c, the penumbra wedges' per-pixel area
 * (the C twin of shaders/wedge_area.glsl): no GL context. The edge terms
 * plus the centre's hard visibility must give the unoccluded share of the
 * light's disk, here counted by Monte Carlo: a half-plane's edge through
 * the centre, a polygon covering the disk, squares of known overlap on
 * the plane, and occluders in 3D under a point light and the sun (which
 * fixes the edges' orientation). And the wedges of demos/lib/volume_wedges.c
 * are conservative: every point where an edge's term is not 0 lies inside
 * its wedge, at infinity or cut off past a box. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <cmocka.h>

#include "area_light.h"
#include "volume_wedges.h"
#include "wedge_area.h"

/* Monte Carlo points over the disk, and the error allowed against them
 * (several standard deviations of a share at that count). */
#define SAMPLES 200000
#define MC_TOLERANCE 0.01
/* Exact cases. */
#define EXACT_TOLERANCE 1e-5
/* An edge far beyond the unit disk, standing for an infinite line. */
#define FAR_AWAY 100.0f

/* The point k of SAMPLES on the unit disk (area_light's stratified map). */
static void disk_point(int k, float out[2]) {
    uint32_t h = area_light_hash((uint32_t)k);
    area_light_disk_sample(k, SAMPLES, area_light_unit(h), area_light_unit(area_light_hash(h)), out);
}

/* Whether q is inside the counter-clockwise convex polygon. */
static bool inside(const float (*polygon)[2], int n, const float q[2]) {
    for (int i = 0; i < n; i++) {
        const float *a = polygon[i], *b = polygon[(i + 1) % n];
        if ((b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0]) < 0)
            return false;
    }
    return true;
}

/* The visibility of the unit disk behind the polygon: the centre's, plus
 * every edge's term. */
static double wedge_visibility(const float (*polygon)[2], int n) {
    double v = inside(polygon, n, (float[2]){0, 0}) ? 0 : 1;
    for (int i = 0; i < n; i++)
        v += wedge_area_beyond(polygon[i], polygon[(i + 1) % n]);
    return v;
}

static double counted_visibility(const float (*polygon)[2], int n) {
    int lit = 0;
    for (int k = 0; k < SAMPLES; k++) {
        float q[2];
        disk_point(k, q);
        lit += !inside(polygon, n, q);
    }
    return (double)lit / SAMPLES;
}

static void test_half_plane_through_centre(void **state) {
    (void)state;
    /* Running towards -x, the occluder (to its left) is the lower half:
     * the upper half lies beyond the edge. */
    assert_float_equal(wedge_area_beyond((float[2]){FAR_AWAY, 0}, (float[2]){-FAR_AWAY, 0}), 0.5, EXACT_TOLERANCE);
    /* Reversed, the same half with the other sign. */
    assert_float_equal(wedge_area_beyond((float[2]){-FAR_AWAY, 0}, (float[2]){FAR_AWAY, 0}), -0.5, EXACT_TOLERANCE);
    /* A line that misses the disk, and an edge that stops short of it. */
    assert_float_equal(wedge_area_beyond((float[2]){FAR_AWAY, 2}, (float[2]){-FAR_AWAY, 2}), 0, EXACT_TOLERANCE);
    assert_float_equal(wedge_area_beyond((float[2]){FAR_AWAY, 0}, (float[2]){2, 0}), 0, EXACT_TOLERANCE);
}

static void test_polygon_covering_disk(void **state) {
    (void)state;
    const float square[4][2] = {{-2, -2}, {2, -2}, {2, 2}, {-2, 2}};
    assert_float_equal(wedge_visibility(square, 4), 0, EXACT_TOLERANCE);
    const float away[4][2] = {{3, -2}, {5, -2}, {5, 2}, {3, 2}};
    assert_float_equal(wedge_visibility(away, 4), 1, EXACT_TOLERANCE);
}

static void test_squares_of_known_overlap(void **state) {
    (void)state;
    static const float offsets[][2] = {{0.3f, 0.2f}, {0.9f, -0.4f}, {-1.2f, 0.5f}, {0.0f, 1.1f}, {0.5f, 0.5f}};
    static const float halves[] = {0.6f, 0.5f, 0.8f, 0.4f, 0.2f};
    for (size_t c = 0; c < sizeof halves / sizeof *halves; c++) {
        float o0 = offsets[c][0], o1 = offsets[c][1], h = halves[c];
        const float square[4][2] = {{o0 - h, o1 - h}, {o0 + h, o1 - h}, {o0 + h, o1 + h}, {o0 - h, o1 + h}};
        double wedge = wedge_visibility(square, 4), counted = counted_visibility(square, 4);
        printf("    square %zu: wedges %.4f, counted %.4f\n", c, wedge, counted);
        assert_float_equal(wedge, counted, MC_TOLERANCE);
    }
}

/* A square occluder at height y, light-facing (counter-clockwise seen from
 * above), its corners (x, z) in the plane. */
static void occluder(float lo, float hi, float y, float out[4][3]) {
    const float corners[4][2] = {{lo, lo}, {lo, hi}, {hi, hi}, {hi, lo}};
    for (int i = 0; i < 4; i++)
        out[i][0] = corners[i][0], out[i][1] = y, out[i][2] = corners[i][1];
}

/* Whether the ray from p along d meets the square (an axis-aligned one in
 * the plane y = corner's). */
static bool blocked(const float p[3], const float d[3], const float (*square)[3]) {
    float t = (square[0][1] - p[1]) / d[1];
    if (t <= 0)
        return false;
    float x = p[0] + t * d[0], z = p[2] + t * d[2];
    return x >= square[0][0] && x <= square[2][0] && z >= square[0][2] && z <= square[2][2];
}

static double edges_visibility(const float p[3], const float light[4], float size, const float (*square)[3]) {
    float axis[3];
    for (int c = 0; c < 3; c++)
        axis[c] = light[3] != 0 ? light[c] - p[c] : light[c];
    double v = blocked(p, axis, square) ? 0 : 1;
    for (int i = 0; i < 4; i++)
        v += wedge_area_edge(p, light, size, square[i], square[(i + 1) % 4]);
    return v;
}

/* The share of the disk (turned towards p; a directional light's on its
 * plane one unit along) p sees past the square. */
static double traced_visibility(const float p[3], const float light[4], float size, const float (*square)[3]) {
    float axis[3], t[3], b[3];
    float length = 0;
    for (int c = 0; c < 3; c++) {
        axis[c] = light[3] != 0 ? light[c] - p[c] : light[c];
        length += axis[c] * axis[c];
    }
    length = sqrtf(length);
    for (int c = 0; c < 3; c++)
        axis[c] /= length;
    area_light_basis(axis, t, b);
    float reach = light[3] != 0 ? length : 1;
    int lit = 0;
    for (int k = 0; k < SAMPLES; k++) {
        float q[2], d[3];
        disk_point(k, q);
        for (int c = 0; c < 3; c++)
            d[c] = axis[c] * reach + (t[c] * q[0] + b[c] * q[1]) * size;
        lit += !blocked(p, d, square);
    }
    return (double)lit / SAMPLES;
}

static void test_occluders_in_space(void **state) {
    (void)state;
    float square[4][3];
    occluder(-1, 1, 2, square);
    const float point[4] = {0, 6, 0, 1}, sun[4] = {0.1f, 1, 0.05f, 0};
    const float points[][3] = {{1.2f, 0, 0.3f},   {1.3f, 0, -1.2f}, {-1.1f, 0, 1.25f},
                               {1.45f, 0, 1.35f}, {0, 0, 0},        {2.5f, 0, 0}};
    for (size_t k = 0; k < sizeof points / sizeof *points; k++) {
        double wedge = edges_visibility(points[k], point, 1.0f, square);
        double traced = traced_visibility(points[k], point, 1.0f, square);
        printf("    point light, p %zu: wedges %.4f, traced %.4f\n", k, wedge, traced);
        assert_float_equal(wedge, traced, MC_TOLERANCE);
        wedge = edges_visibility(points[k], sun, 0.3f, square);
        traced = traced_visibility(points[k], sun, 0.3f, square);
        printf("    sun, p %zu: wedges %.4f, traced %.4f\n", k, wedge, traced);
        assert_float_equal(wedge, traced, MC_TOLERANCE);
    }
}

/* Points of the cube [-CUBE, CUBE]^3 tried against each wedge, along
 * each axis, and the term below which an edge counts as missing. */
#define CUBE 4.0f
#define CUBE_STEPS 24
#define TERM_EPSILON 1e-5f
/* det[p0; p1; p2; q] of homogeneous rows, relative to the rows' sizes,
 * below which q counts as on the face. */
#define DET_EPSILON 1e-4

static double det4(const float *r0, const float *r1, const float *r2, const float *r3) {
    const float *rows[4] = {r0, r1, r2, r3};
    double det = 0;
    for (int p = 0; p < 24; p++) { /* Leibniz, over the permutations */
        int perm[4] = {0, 1, 2, 3}, k = p, sign = 1;
        for (int i = 0; i < 4; i++) {
            int j = i + k % (4 - i);
            k /= 4 - i;
            if (j != i) {
                int t = perm[i];
                perm[i] = perm[j], perm[j] = t;
                sign = -sign;
            }
        }
        double term = sign;
        for (int i = 0; i < 4; i++)
            term *= rows[i][perm[i]];
        det += term;
    }
    return det;
}

static double row_size(const float *r) { return sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3]); }

/* Every point of the cube's grid with a non-zero term lies inside the
 * wedge: on the inner side of each face (det > 0 faces away). */
static void check_conservative(const float a[3], const float b[3], const float light[4], float reach, float size,
                               const float *lo, const float *hi) {
    float wedge[VOLUME_WEDGES_EDGE_VERTICES][4];
    assert_int_equal(volume_wedges_edge(a, b, light, reach, lo, hi, wedge), VOLUME_WEDGES_EDGE_VERTICES);
    int checked = 0;
    for (int i = 0; i <= CUBE_STEPS; i++)
        for (int j = 0; j <= CUBE_STEPS; j++)
            for (int k = 0; k <= CUBE_STEPS; k++) {
                float step = 2 * CUBE / CUBE_STEPS;
                float p[4] = {-CUBE + i * step, -CUBE + j * step, -CUBE + k * step, 1};
                bool in_box = !lo || (p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1] &&
                                      p[2] >= lo[2] && p[2] <= hi[2]);
                if (!in_box || fabsf(wedge_area_edge(p, light, size, a, b)) <= TERM_EPSILON)
                    continue;
                checked++;
                for (int t = 0; t < VOLUME_WEDGES_EDGE_VERTICES; t += 3) {
                    double scale = row_size(wedge[t]) * row_size(wedge[t + 1]) * row_size(wedge[t + 2]) * row_size(p);
                    assert_true(det4(wedge[t], wedge[t + 1], wedge[t + 2], p) >= -DET_EPSILON * scale);
                }
            }
    printf("    edge (%g %g %g) -> (%g %g %g), light w %g%s: %d points in its penumbra, all inside\n", a[0], a[1],
           a[2], b[0], b[1], b[2], light[3], lo ? ", cut off" : "", checked);
    assert_true(checked > 0);
}

static void test_wedges_conservative(void **state) {
    (void)state;
    const float point[4] = {0.5f, 5, 0.3f, 1}, sun[4] = {0.36f, 0.8f, 0.48f, 0};
    const float sun_angle = 0.15f;
    const float edges[][2][3] = {{{-1, 1.5f, 0}, {1, 1.6f, 0.2f}}, {{0.2f, 2, -1}, {-0.3f, 1.2f, 1}}};
    const float lo[3] = {-CUBE, -CUBE, -CUBE}, hi[3] = {CUBE, 0.5f, CUBE};
    for (size_t e = 0; e < sizeof edges / sizeof *edges; e++) {
        check_conservative(edges[e][0], edges[e][1], point, 1.0f, 1.0f, NULL, NULL);
        check_conservative(edges[e][0], edges[e][1], point, 1.0f, 1.0f, lo, hi);
        check_conservative(edges[e][0], edges[e][1], sun, sinf(sun_angle), tanf(sun_angle), NULL, NULL);
        check_conservative(edges[e][0], edges[e][1], sun, sinf(sun_angle), tanf(sun_angle), lo, hi);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_half_plane_through_centre), cmocka_unit_test(test_polygon_covering_disk),
        cmocka_unit_test(test_squares_of_known_overlap),  cmocka_unit_test(test_occluders_in_space),
        cmocka_unit_test(test_wedges_conservative),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
