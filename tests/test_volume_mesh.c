/* Tests of demos/lib/volume_mesh.c, the shadow volumes' CPU geometry (and
 * of volume_silhouette.c's adjacency for the geometry shader), on
 * procedural meshes and a camera of our own: no GL context.
 *
 * A volume's faces must all face out of it (front faces count +1 on the
 * way in): a face (v0, v1, v2) faces away from a point q when
 * det[v0; v1; v2; q] > 0, homogeneous rows; with w >= 0 throughout this
 * holds for faces at infinity too, as in clip space. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "support.h"

#include "volume_mesh.h"
#include "volume_silhouette.h"

/* A side of an edge swept to infinity from a point light: two triangles. */
#define SIDE_VERTICES 6
/* The camera of the z-pass tests: at the origin looking down -z. */
#define CAMERA_FOV_DEG 45.0f
#define CAMERA_ASPECT (16.0f / 9.0f)
#define CAMERA_NEAR 0.1f
#define CAMERA_FAR 100.0f
/* The scissor tests' viewport. */
#define TEST_WIDTH 640
#define TEST_HEIGHT 360
/* NDC of a near corner mapped back and forth, in float. */
#define NDC_TOLERANCE 1e-4f

static double det3(double a0, double a1, double a2, double b0, double b1, double b2, double c0, double c1,
                   double c2) {
    return a0 * (b1 * c2 - b2 * c1) - a1 * (b0 * c2 - b2 * c0) + a2 * (b0 * c1 - b1 * c0);
}

/* det[r0; r1; r2; r3] of homogeneous rows, along the last column. */
static double det4(const float r[4][4]) {
    double sum = 0;
    for (int row = 0; row < 4; row++) {
        const float *m[3];
        for (int k = 0, n = 0; k < 4; k++)
            if (k != row)
                m[n++] = r[k];
        double minor = det3(m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2]);
        sum += ((row + 3) % 2 ? -1 : 1) * r[row][3] * minor;
    }
    return sum;
}

/* Bit for bit: volumes repeat the mesh's own positions. */
static bool same_point(const float *a, const float *b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }

/* Every triangle of v faces away from the point q (w = 1). */
static void assert_faces_out(const volume_mesh *v, const float q[3]) {
    assert_int_equal(v->count % 3, 0);
    for (size_t t = 0; t < v->count; t += 3) {
        float rows[4][4] = {{0}, {0}, {0}, {q[0], q[1], q[2], 1}};
        memcpy(rows, v->vertices[t], 3 * sizeof rows[0]);
        if (det4(rows) <= 0)
            fail_msg("triangle %zu of %zu faces into the volume", t / 3, v->count / 3);
    }
}

/* Caps built (VOLUME_MESH_CAPS) from a point light: each triangle's
 * near and far caps, one after the other, face out of its own prism,
 * which holds the point twice as far from the light as the near cap's
 * centre. */
static void assert_caps_face_out_of_prisms(const volume_mesh *v, const float light[4]) {
    enum { CAP_VERTICES = 3, PAIR = 2 * CAP_VERTICES };
    assert_int_equal(v->count % PAIR, 0);
    for (size_t t = 0; t < v->count; t += PAIR) {
        float inside[3] = {0, 0, 0};
        for (int k = 0; k < CAP_VERTICES; k++)
            for (int j = 0; j < 3; j++)
                inside[j] += v->vertices[t + k][j] * (2.0f / CAP_VERTICES);
        for (int j = 0; j < 3; j++)
            inside[j] -= light[j];
        volume_mesh pair = {.vertices = (float(*)[4])v->vertices[t], .count = PAIR};
        assert_faces_out(&pair, inside);
    }
}

static void build(volume_mesh *v, const mesh *m, const float light[4], volume_mesh_parts parts) {
    mesh_edges e;
    assert_true(mesh_edges_build_welded(m, &e));
    assert_true(volume_mesh_build(v, m, &e, light, NULL, parts));
    mesh_edges_free(&e);
}

/* A unit box lit from (10, 10, 10) shows the light three faces (+x, +y,
 * +z); its silhouette is the hexagon of the six edges between a lit face
 * and an unlit one, where one coordinate is +1/2 and another -1/2. Each
 * has a side, once (multiplicity 1); no other edge has one. */
static void test_closed_box_sides_on_silhouette_once(void **state) {
    (void)state;
    mesh m;
    assert_true(mesh_make_box(&m, 1, 1, 1));
    const float light[4] = {10, 10, 10, 1}, inside[3] = {-1, -1, -1}, half = 0.5f;
    volume_mesh v = {0};
    build(&v, &m, light, VOLUME_MESH_SIDES);
    enum { SILHOUETTE_EDGES = 6 };
    assert_int_equal(v.count, SILHOUETTE_EDGES * SIDE_VERTICES);
    for (int i = 0; i < SILHOUETTE_EDGES; i++) {
        const float *a = v.vertices[i * SIDE_VERTICES], *b = v.vertices[i * SIDE_VERTICES + 1];
        assert_true(a[3] == 1 && b[3] == 1 && v.vertices[i * SIDE_VERTICES + 2][3] == 0);
        int along = 0, plus = 0, minus = 0;
        for (int k = 0; k < 3; k++) {
            along += a[k] != b[k];
            plus += a[k] == b[k] && a[k] == half;
            minus += a[k] == b[k] && a[k] == -half;
        }
        assert_true(along == 1 && plus == 1 && minus == 1);
        for (int j = 0; j < i; j++) {
            const float *c = v.vertices[j * SIDE_VERTICES], *d = v.vertices[j * SIDE_VERTICES + 1];
            bool same = (same_point(c, a) && same_point(d, b)) || (same_point(c, b) && same_point(d, a));
            assert_false(same);
        }
    }
    assert_faces_out(&v, inside);
    /* z-fail adds the caps: the lit faces' triangles and their images at
     * infinity, on their own (sides and caps are kept apart). */
    enum { LIT_TRIANGLES = 6 };
    build(&v, &m, light, VOLUME_MESH_CAPS);
    assert_int_equal(v.count, LIT_TRIANGLES * 2 * 3);
    assert_faces_out(&v, inside);
    build(&v, &m, light, VOLUME_MESH_SILHOUETTE_LINES);
    assert_int_equal(v.count, SILHOUETTE_EDGES * 2);
    volume_mesh_free(&v);
    mesh_free(&m);
}

/* A point light inside a closed box, or in its top face (volume_mesh.h:
 * the closed rule would cast nothing, every triangle facing away or
 * edge-on): the box is weighed as an open mesh. Inside, all 12 triangles
 * are caps (near, reversed, and far) and no edge has a side; in the top
 * face, its 2 triangles are edge-on and weigh 0, the other 10 are caps,
 * and the top face's 4 border edges have sides, in the face's plane.
 * Each triangle's caps face out of its own prism (the prisms together
 * are the volume). Just above the face, or beside the box, the light is
 * outside and the closed rule holds. */
static void test_light_inside_closed_box(void **state) {
    (void)state;
    mesh m;
    assert_true(mesh_make_box(&m, 2, 2, 2));
    mesh_edges e;
    assert_true(mesh_edges_build_welded(&m, &e));
    assert_true(e.closed);
    const float centre[4] = {0.1f, 0.2f, -0.3f, 1}, on_top[4] = {0.3f, 1, -0.2f, 1};
    const float above[4] = {0.3f, 1.001f, -0.2f, 1}, beside[4] = {3, 1, 0, 1}, sun[4] = {0.1f, 1, 0.2f, 0};
    assert_true(mesh_point_inside(&m, centre) && mesh_point_inside(&m, on_top));
    assert_false(mesh_point_inside(&m, above) || mesh_point_inside(&m, beside) || mesh_point_inside(&m, sun));
    assert_false(volume_mesh_closed_rule(&m, &e, centre) || volume_mesh_closed_rule(&m, &e, on_top));
    assert_true(volume_mesh_closed_rule(&m, &e, above) && volume_mesh_closed_rule(&m, &e, beside));
    enum { TRIANGLES = 12, TOP_TRIANGLES = 2, TOP_EDGES = 4 };
    volume_mesh v = {0};
    assert_true(volume_mesh_build(&v, &m, &e, centre, NULL, VOLUME_MESH_SIDES));
    assert_int_equal(v.count, 0);
    assert_true(volume_mesh_build(&v, &m, &e, centre, NULL, VOLUME_MESH_CAPS));
    assert_int_equal(v.count, TRIANGLES * 2 * 3);
    assert_caps_face_out_of_prisms(&v, centre);
    assert_true(volume_mesh_build(&v, &m, &e, on_top, NULL, VOLUME_MESH_SIDES));
    assert_int_equal(v.count, TOP_EDGES * SIDE_VERTICES);
    assert_true(volume_mesh_build(&v, &m, &e, on_top, NULL, VOLUME_MESH_CAPS));
    assert_int_equal(v.count, (TRIANGLES - TOP_TRIANGLES) * 2 * 3);
    assert_caps_face_out_of_prisms(&v, on_top);
    volume_mesh_free(&v);
    mesh_edges_free(&e);
    mesh_free(&m);
}

/* mesh_point_facing: +1 and -1 either side of a triangle's plane, 0
 * within the edge-on tolerance of it, for point and directional lights,
 * whichever corner the triangle starts from. */
static void test_facing_edge_on(void **state) {
    (void)state;
    const float a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 0, -1}; /* faces +y */
    const float over = 1e-3f, within = 1e-6f;
    const float lights[][4] = {
        {0.2f, over, -0.2f, 1}, {0.2f, -over, -0.2f, 1}, {0.2f, within, -0.2f, 1}, {5, 0, 3, 1},
        {0, 1, 0, 0},           {1, within, 0, 0}};
    const int expected[] = {1, -1, 0, 0, 1, 0};
    for (size_t i = 0; i < sizeof expected / sizeof *expected; i++) {
        assert_int_equal(mesh_point_facing(a, b, c, lights[i]), expected[i]);
        assert_int_equal(mesh_point_facing(b, c, a, lights[i]), expected[i]);
        assert_int_equal(mesh_point_facing(a, c, b, lights[i]), -expected[i]);
    }
}

/* Trimmed volumes (see "Trimmed to the light's reach" in volume_mesh.h):
 * a unit box's sides and caps together are closed (every directed edge
 * met by its reverse), face out, and every swept vertex, every far edge's
 * midpoint and every far cap's centre lies beyond the reach: farther from
 * a point light than the reach's farthest corner, past the reach's last
 * plane across a directional light's travel. */
#define REACH_HALF 6.0f
static void assert_trimmed_closed_beyond_reach(const float light[4], const float inside[3]) {
    mesh m;
    assert_true(mesh_make_box(&m, 1, 1, 1));
    mesh_edges e;
    assert_true(mesh_edges_build_welded(&m, &e));
    mat4 identity = GLM_MAT4_IDENTITY_INIT;
    const float reach_lo[3] = {-REACH_HALF, -REACH_HALF, -REACH_HALF};
    const float reach_hi[3] = {REACH_HALF, REACH_HALF, REACH_HALF};
    volume_mesh_trim trim;
    volume_mesh_trim_for(identity, light, &m, reach_lo, reach_hi, &trim);
    assert_true(trim.on);
    volume_mesh sides = {0}, caps = {0};
    assert_true(volume_mesh_build(&sides, &m, &e, light, &trim, VOLUME_MESH_SIDES));
    assert_true(volume_mesh_build(&caps, &m, &e, light, &trim, VOLUME_MESH_CAPS));
    assert_faces_out(&sides, inside);
    assert_faces_out(&caps, inside);
    /* The reach's farthest corner from the light, or its last plane. */
    float beyond = -INFINITY, travel[3] = {-light[0], -light[1], -light[2]};
    for (int c = 0; c < 8; c++) {
        float corner[3] = {c & 1 ? REACH_HALF : -REACH_HALF, c & 2 ? REACH_HALF : -REACH_HALF,
                           c & 4 ? REACH_HALF : -REACH_HALF};
        beyond =
            fmaxf(beyond, light[3] != 0 ? glm_vec3_distance(corner, (float *)light) : glm_vec3_dot(corner, travel));
    }
    const volume_mesh *parts[2] = {&sides, &caps};
    int unmatched = 0;
    for (int p = 0; p < 2; p++) {
        for (size_t t = 0; t < parts[p]->count; t += 3) {
            const float(*tri)[4] = (const float(*)[4])parts[p]->vertices[t];
            int swept = 0;
            vec3 centre = {0, 0, 0};
            for (int k = 0; k < 3; k++) {
                assert_true(tri[k][3] == 1);
                bool on_mesh = fabsf(tri[k][0]) <= 0.5f && fabsf(tri[k][1]) <= 0.5f && fabsf(tri[k][2]) <= 0.5f;
                swept += !on_mesh;
                glm_vec3_muladds((float *)tri[k], 1.0f / 3, centre);
                /* Each directed edge against its reverse, in both parts. */
                const float *a = tri[k], *b = tri[(k + 1) % 3];
                int balance = 0;
                for (int q = 0; q < 2; q++)
                    for (size_t u = 0; u < parts[q]->count; u += 3)
                        for (int j = 0; j < 3; j++) {
                            const float *c = parts[q]->vertices[u + j], *d = parts[q]->vertices[u + (j + 1) % 3];
                            balance += same_point(c, a) && same_point(d, b);
                            balance -= same_point(c, b) && same_point(d, a);
                        }
                unmatched += balance != 0;
            }
            for (int k = 0; k < 3 && swept == 3; k++) {
                vec3 midpoint;
                glm_vec3_center((float *)tri[k], (float *)tri[(k + 1) % 3], midpoint);
                float *points[2] = {midpoint, centre};
                for (int n = 0; n < 2; n++) {
                    float at = light[3] != 0 ? glm_vec3_distance(points[n], (float *)light)
                                             : glm_vec3_dot(points[n], travel);
                    if (!(at > beyond))
                        fail_msg("a far cap comes to %g, within the reach (%g)", (double)at, (double)beyond);
                }
            }
        }
    }
    assert_int_equal(unmatched, 0);
    volume_mesh_free(&sides);
    volume_mesh_free(&caps);
    mesh_edges_free(&e);
    mesh_free(&m);
}

static void test_trimmed_volume_closed_beyond_reach(void **state) {
    (void)state;
    const float point[4] = {3, 4, 5, 1}, directional[4] = {1, 2, 3, 0}, inside[3] = {-1, -1.5f, -2};
    assert_trimmed_closed_beyond_reach(point, inside);
    assert_trimmed_closed_beyond_reach(directional, inside);
}

/* A caster that spans too much of a point light's view is not trimmed. */
static void test_trim_off_near_the_light(void **state) {
    (void)state;
    mesh m;
    assert_true(mesh_make_box(&m, 1, 1, 1));
    mat4 identity = GLM_MAT4_IDENTITY_INIT;
    const float near_light[4] = {0.9f, 0, 0, 1}, lo[3] = {-5, -5, -5}, hi[3] = {5, 5, 5};
    volume_mesh_trim trim;
    volume_mesh_trim_for(identity, near_light, &m, lo, hi, &trim);
    assert_false(trim.on);
    mesh_free(&m);
}

/* An open plane (two triangles, facing +y) lit from above has its prism
 * below, lit from below (both triangles weigh -1) above: the same four
 * border sides, reversed, and none on the diagonal inside. */
static void test_plane_lit_from_behind_reverses_sides(void **state) {
    (void)state;
    mesh m;
    assert_true(mesh_make_plane(&m, 2, 2));
    const float above[4] = {0.3f, 5, 0.2f, 1}, below[4] = {0.3f, -5, 0.2f, 1};
    const float under[3] = {0, -1, 0}, over[3] = {0, 1, 0};
    enum { BORDER_EDGES = 4 };
    volume_mesh front = {0}, back = {0};
    build(&front, &m, above, VOLUME_MESH_SIDES);
    build(&back, &m, below, VOLUME_MESH_SIDES);
    assert_int_equal(front.count, BORDER_EDGES * SIDE_VERTICES);
    assert_int_equal(back.count, BORDER_EDGES * SIDE_VERTICES);
    for (int i = 0; i < BORDER_EDGES; i++) {
        assert_true(same_point(front.vertices[i * SIDE_VERTICES], back.vertices[i * SIDE_VERTICES + 1]));
        assert_true(same_point(front.vertices[i * SIDE_VERTICES + 1], back.vertices[i * SIDE_VERTICES]));
    }
    assert_faces_out(&front, under);
    assert_faces_out(&back, over);
    /* The caps, wound the other way round for the triangles lit from
     * behind, face out of the prisms too. */
    build(&front, &m, above, VOLUME_MESH_CAPS);
    build(&back, &m, below, VOLUME_MESH_CAPS);
    assert_faces_out(&front, under);
    assert_faces_out(&back, over);
    volume_mesh_free(&front);
    volume_mesh_free(&back);
    mesh_free(&m);
}

static void camera(mat4 view_projection) {
    mat4 view, projection;
    glm_lookat((vec3){0, 0, 0}, (vec3){0, 0, -1}, (vec3){0, 1, 0}, view);
    glm_perspective(glm_rad(CAMERA_FOV_DEG), CAMERA_ASPECT, CAMERA_NEAR, CAMERA_FAR, projection);
    glm_mat4_mul(projection, view, view_projection);
}

/* The near rectangle goes round: NDC (-1 -1), (1 -1), (1 1), (-1 1). */
static void test_near_rectangle_goes_round(void **state) {
    (void)state;
    static const float expected[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    mat4 view_projection;
    camera(view_projection);
    vec3 rectangle[4];
    volume_mesh_near_rectangle(view_projection, rectangle);
    for (int k = 0; k < 4; k++) {
        vec4 clip;
        glm_mat4_mulv(view_projection, (vec4){rectangle[k][0], rectangle[k][1], rectangle[k][2], 1}, clip);
        assert_true(fabsf(clip[0] / clip[3] - expected[k][0]) < NDC_TOLERANCE);
        assert_true(fabsf(clip[1] / clip[3] - expected[k][1]) < NDC_TOLERANCE);
        assert_true(fabsf(clip[2] / clip[3] + 1) < NDC_TOLERANCE);
    }
}

/* The box of side 2 round `centre`. */
static void box_of_side_2(const float centre[3], float lo[3], float hi[3]) {
    for (int k = 0; k < 3; k++)
        lo[k] = centre[k] - 1, hi[k] = centre[k] + 1;
}

static bool zpass_safe(const float centre[3], const float light[4]) {
    mat4 view_projection;
    camera(view_projection);
    vec3 rectangle[4];
    volume_mesh_near_rectangle(view_projection, rectangle);
    float lo[3], hi[3];
    box_of_side_2(centre, lo, hi);
    return volume_mesh_zpass_safe(lo, hi, light, rectangle);
}

/* Light 10 in front of the camera. A box of side 2 far beyond it casts its
 * shadow away from the camera, and lies outside the hull's upper face
 * (which beyond the light dips below the box); one between the camera and
 * the light shadows the near rectangle itself. */
static void test_zpass_safe_only_beyond_the_light(void **state) {
    (void)state;
    const float light[4] = {0, 0, -10, 1};
    assert_true(zpass_safe((const float[3]){0, 0, -1000}, light));
    assert_false(zpass_safe((const float[3]){0, 0, -5}, light));
    /* A directional light from behind the camera: every caster in front
     * of the near plane shadows away from it. */
    const float from_behind[4] = {0, 0, 1, 0};
    assert_true(zpass_safe((const float[3]){0, 0, -5}, from_behind));
    const float towards_camera[4] = {0, 0, -1, 0};
    assert_false(zpass_safe((const float[3]){0, 0, -5}, towards_camera));
}

/* The count a unit box's volume holds at a point: beyond it from a point
 * light, one under the closed rule (its near face) and two under the
 * open one (both faces' prisms); before it, none; to the side, none; and
 * under a directional light along the ray towards it. */
static void test_count_at_a_point(void **state) {
    (void)state;
    mesh box;
    assert_true(mesh_make_box(&box, 1, 1, 1));
    const float light[4] = {0, 10, 0, 1}, sun[4] = {0, 1, 0, 0};
    const float below[3] = {0, -3, 0}, above[3] = {0, 3, 0}, aside[3] = {3, -3, 0};
    assert_int_equal(volume_mesh_count_at(&box, true, light, below), 1);
    assert_int_equal(volume_mesh_count_at(&box, false, light, below), 2);
    assert_int_equal(volume_mesh_count_at(&box, true, light, above), 0);
    assert_int_equal(volume_mesh_count_at(&box, true, light, aside), 0);
    assert_int_equal(volume_mesh_count_at(&box, true, sun, below), 1);
    assert_int_equal(volume_mesh_count_at(&box, false, sun, aside), 0);
    mesh_free(&box);
}

static bool misses_view(const float centre[3], const float light[4]) {
    mat4 view_projection;
    camera(view_projection);
    float lo[3], hi[3];
    box_of_side_2(centre, lo, hi);
    return volume_mesh_misses_view(lo, hi, light, view_projection);
}

/* A volume misses the view when the box and its sweep away from the light
 * both stay beyond one side: not when the box is in view, nor when it is
 * out of view but its shadow sweeps into it. */
static void test_misses_view_only_when_the_sweep_does(void **state) {
    (void)state;
    const float in_front[3] = {0, 0, -10}, behind[3] = {0, 0, 10}, right[3] = {50, 0, -10};
    assert_false(misses_view(in_front, (const float[4]){0, 10, -10, 1}));
    /* Behind the eye: lit from further behind, the shadow reaches forward
     * into the view; lit from in front, it stays behind the eye. */
    assert_false(misses_view(behind, (const float[4]){0, 0, 20, 1}));
    assert_true(misses_view(behind, (const float[4]){0, 0, -10, 1}));
    /* Off to the right: lit from the view's side the shadow goes further
     * right; lit from further right it crosses the view. */
    assert_true(misses_view(right, (const float[4]){0, 0, -10, 1}));
    assert_false(misses_view(right, (const float[4]){100, 0, -10, 1}));
    /* The same with a directional light, (towards it, 0). */
    assert_true(misses_view(right, (const float[4]){-1, 0, 0, 0}));
    assert_false(misses_view(right, (const float[4]){1, 0, 0, 0}));
    /* Above the view, lit from below: the shadow goes up. */
    assert_true(misses_view((const float[3]){0, 50, -10}, (const float[4]){0, 0, -10, 1}));
}

/* Deterministic pseudo-random numbers in [lo, hi) (a 32-bit LCG). */
static float random_in(uint32_t *seed, float lo, float hi) {
    *seed = *seed * 1664525u + 1013904223u;
    return lo + (hi - lo) * (float)(*seed >> 8) / (float)(1u << 24);
}

/* Homogeneous world point p (w 1 or 0) inside the view's clip region
 * with depth clamp: |x|, |y| <= w, w > 0. */
static bool clip_inside(const mat4 view_projection, const float p[4]) {
    vec4 clip;
    glm_mat4_mulv((vec4 *)view_projection, (float *)p, clip);
    return clip[3] > 0 && fabsf(clip[0]) <= clip[3] && fabsf(clip[1]) <= clip[3];
}

/* Random boxes and lights: whenever the test says a volume misses the
 * view, no point of it (in the box, swept away from the light, at
 * infinity) is inside; and the test does say so for some, not all. */
enum { RANDOM_VOLUMES = 2000, POINTS_PER_VOLUME = 200 };
static void test_missed_volumes_have_no_point_in_view(void **state) {
    (void)state;
    static const float sweeps[] = {0, 0.5f, 3, 1000}; /* how far beyond the box, in box-light distances */
    mat4 view_projection;
    camera(view_projection);
    uint32_t seed = 1;
    int missed = 0;
    for (int n = 0; n < RANDOM_VOLUMES; n++) {
        float lo[3], hi[3], light[4];
        for (int k = 0; k < 3; k++) {
            lo[k] = random_in(&seed, -60, 60);
            hi[k] = lo[k] + random_in(&seed, 0.1f, 10);
            light[k] = random_in(&seed, -60, 60);
        }
        light[3] = n % 4 == 0 ? 0 : 1; /* a quarter directional */
        if (!volume_mesh_misses_view(lo, hi, light, view_projection))
            continue;
        missed++;
        for (int i = 0; i < POINTS_PER_VOLUME; i++) {
            float p[3], away[3];
            for (int k = 0; k < 3; k++) {
                p[k] = random_in(&seed, lo[k], hi[k]);
                away[k] = p[k] * light[3] - light[k];
            }
            for (size_t t = 0; t < sizeof sweeps / sizeof *sweeps; t++) {
                float q[4] = {p[0] + sweeps[t] * away[0], p[1] + sweeps[t] * away[1], p[2] + sweeps[t] * away[2], 1};
                if (clip_inside(view_projection, q))
                    fail_msg("volume %d: a point swept %g is in view", n, (double)sweeps[t]);
            }
            if (clip_inside(view_projection, (const float[4]){away[0], away[1], away[2], 0}))
                fail_msg("volume %d: its point at infinity is in view", n);
        }
    }
    printf("    %d of %d random volumes miss the view\n", missed, RANDOM_VOLUMES);
    assert_true(missed > 0 && missed < RANDOM_VOLUMES);
}

/* The receivers' rectangle covers a box in front of the camera, is empty
 * without receivers, and gives up on a box reaching behind the eye (the
 * scissor is then the whole viewport). */
static void test_receivers_ndc(void **state) {
    (void)state;
    mat4 view_projection;
    camera(view_projection);
    scene_object o = {.receives = true};
    assert_true(mesh_make_box(&o.mesh, 1, 1, 1));
    glm_translate_make((vec4 *)o.model, (vec3){1, 0, -5});
    scene s = {.objects = &o, .object_count = 1};
    float lo[2], hi[2];
    assert_true(volume_mesh_receivers_ndc(&s, view_projection, lo, hi));
    vec4 centre;
    glm_mat4_mulv(view_projection, (vec4){1, 0, -5, 1}, centre);
    for (int k = 0; k < 2; k++)
        assert_true(lo[k] < centre[k] / centre[3] && centre[k] / centre[3] < hi[k]);
    assert_true(lo[0] > 0); /* the box lies right of the view's centre */
    o.receives = false;
    assert_true(volume_mesh_receivers_ndc(&s, view_projection, lo, hi));
    assert_true(lo[0] > hi[0] && lo[1] > hi[1]);
    int rect[4];
    volume_mesh_receivers_scissor(&s, view_projection, TEST_WIDTH, TEST_HEIGHT, rect);
    assert_true(rect[2] == 0 && rect[3] == 0); /* nothing to clear */
    o.receives = true;
    volume_mesh_receivers_scissor(&s, view_projection, TEST_WIDTH, TEST_HEIGHT, rect);
    assert_true(rect[0] > TEST_WIDTH / 2 && rect[2] > 0 && rect[0] + rect[2] <= TEST_WIDTH);
    glm_translate_make((vec4 *)o.model, (vec3){0, 0, 0});
    assert_false(volume_mesh_receivers_ndc(&s, view_projection, lo, hi));
    volume_mesh_receivers_scissor(&s, view_projection, TEST_WIDTH, TEST_HEIGHT, rect); /* behind the eye: all */
    assert_true(rect[0] == 0 && rect[1] == 0 && rect[2] == TEST_WIDTH && rect[3] == TEST_HEIGHT);
    mesh_free(&o.mesh);
}

/* Depth bounds (volume_mesh_depth_bounds): every point of the hull of
 * the receivers' points that lies in the reach box has its window depth
 * within them; the box narrows them; a box reaching behind the eye bounds
 * nothing; no points, no bounds. */
#define BOUNDS_SAMPLES 2000
static float window_depth(const mat4 view_projection, const float p[3]) {
    vec4 clip = {p[0], p[1], p[2], 1};
    glm_mat4_mulv((vec4 *)view_projection, clip, clip);
    return clip[2] / clip[3] * 0.5f + 0.5f;
}

static void test_depth_bounds(void **state) {
    (void)state;
    mat4 view_projection;
    camera(view_projection);
    const float box_lo[3] = {-1, -1, -30}, box_hi[3] = {1, 1, -4};
    float points[8][3], bounds[2], whole[2];
    for (int c = 0; c < 8; c++)
        for (int k = 0; k < 3; k++)
            points[c][k] = c & (1 << k) ? box_hi[k] : box_lo[k];
    const float reach_lo[3] = {-5, -5, -12}, reach_hi[3] = {5, 5, -8};
    assert_true(volume_mesh_depth_bounds(view_projection, (const float(*)[3])points, 8, reach_lo, reach_hi, bounds));
    assert_true(volume_mesh_depth_bounds(view_projection, (const float(*)[3])points, 8, NULL, NULL, whole));
    assert_true(bounds[0] > whole[0] && bounds[1] < whole[1]);
    printf("    depth bounds %.6f..%.6f, cut by the reach to %.6f..%.6f\n", (double)whole[0], (double)whole[1],
           (double)bounds[0], (double)bounds[1]);
    uint32_t seed = 7;
    int inside = 0;
    for (int i = 0; i < BOUNDS_SAMPLES; i++) {
        float p[3];
        for (int k = 0; k < 3; k++)
            p[k] = random_in(&seed, box_lo[k], box_hi[k]);
        float depth = window_depth(view_projection, p);
        assert_true(depth >= whole[0] && depth <= whole[1]);
        if (p[2] < reach_lo[2] || p[2] > reach_hi[2])
            continue;
        inside++;
        assert_true(depth >= bounds[0] && depth <= bounds[1]);
    }
    assert_true(inside > 0);
    const float behind_lo[3] = {-5, -5, -12}, behind_hi[3] = {5, 5, 3};
    assert_true(
        volume_mesh_depth_bounds(view_projection, (const float(*)[3])points, 8, behind_lo, behind_hi, bounds));
    assert_true(bounds[0] == whole[0] && bounds[1] == whole[1]);
    assert_false(volume_mesh_depth_bounds(view_projection, (const float(*)[3])points, 0, NULL, NULL, bounds));
}

/* Uses in adjacency `indices` (of mesh m) marked as borders: the index
 * across is the triangle's own third vertex. */
static int border_marks(const mesh *m, const uint32_t *indices) {
    int marks = 0;
    for (uint32_t t = 0; t < m->index_count / 3; t++)
        for (int k = 0; k < 3; k++)
            marks +=
                indices[t * VOLUME_SILHOUETTE_INDICES_PER_TRIANGLE + k * 2 + 1] == m->indices[t * 3 + (k + 2) % 3];
    return marks;
}

/* Welded but not at one position (mesh_edges_build_welded): a box (one
 * vertex per face corner) with one face's copy of a corner one ulp off
 * still welds into the closed edge table, but counts as open, and the
 * adjacency pairs nothing across the two box edges from that copy to
 * the neighbouring faces: their 4 uses are marked as borders, no other. */
static void test_welded_apart_is_open(void **state) {
    (void)state;
    mesh box;
    mesh_edges e;
    assert_true(mesh_make_box(&box, 2, 2, 2));
    size_t count = (size_t)box.index_count / 3 * VOLUME_SILHOUETTE_INDICES_PER_TRIANGLE;
    uint32_t *indices = malloc(count * sizeof *indices);
    assert_non_null(indices);
    enum { NUDGED_EDGE_USES = 4 };
    for (int nudged = 0; nudged < 2; nudged++) {
        if (nudged)
            box.vertices[0].position[0] = nextafterf(box.vertices[0].position[0], 0);
        assert_true(mesh_edges_build_welded(&box, &e));
        mesh_topology t;
        assert_true(mesh_weld(&box, &t));
        assert_int_equal(mesh_topology_count_edges(&box, &t).manifold, box.index_count / 2);
        mesh_topology_free(&t);
        assert_int_equal(e.closed, !nudged);
        volume_silhouette_adjacency(&box, &e, indices);
        assert_int_equal(border_marks(&box, indices), nudged ? NUDGED_EDGE_USES : 0);
        mesh_edges_free(&e);
    }
    free(indices);
    mesh_free(&box);
}

/* The geometry shader's adjacency (volume_silhouette.h): on a closed box,
 * mesh_adjacency_indices' indices. On an open, non-manifold mesh, a book
 * of three pages on one spine (0-1) and a fourth triangle across the
 * first page's edge 1-2, each corner first and then across its edge the
 * one other triangle's third vertex (only 1-2 has one: 5 from the first
 * page, 0 from the fourth), everywhere else the mark, the triangle's own
 * third vertex: on the spine (three uses) and the open borders (one). */
static void test_adjacency_marks_borders(void **state) {
    (void)state;
    mesh box;
    mesh_edges e;
    assert_true(mesh_make_box(&box, 1, 2, 3));
    assert_true(mesh_edges_build_welded(&box, &e));
    size_t count = (size_t)box.index_count / 3 * VOLUME_SILHOUETTE_INDICES_PER_TRIANGLE;
    uint32_t *ours = malloc(count * sizeof *ours), *closed = malloc(count * sizeof *closed);
    assert_true(ours && closed);
    volume_silhouette_adjacency(&box, &e, ours);
    assert_true(mesh_adjacency_indices(&box, &e, closed));
    assert_memory_equal(ours, closed, count * sizeof *ours);
    free(ours);
    free(closed);
    mesh_edges_free(&e);
    mesh_free(&box);

    mesh_vertex vertices[] = {
        {{0, 0, 0}, {0, 0, 1}, {0, 0}},  {{0, 1, 0}, {0, 0, 1}, {0, 0}}, {{1, 0, 0}, {0, 0, 1}, {0, 0}},
        {{-1, 0, 0}, {0, 0, 1}, {0, 0}}, {{0, 0, 1}, {1, 0, 0}, {0, 0}}, {{1, 1, 0}, {0, 0, -1}, {0, 0}},
    };
    uint32_t indices[] = {0, 1, 2, 0, 3, 1, 0, 1, 4, 2, 1, 5};
    mesh book = {vertices, indices, 6, 12, {-1, 0, 0}, {1, 1, 1}};
    static const uint32_t expected[] = {0, 2, 1, 5, 2, 1, /* page: spine, across 1-2, border */
                                        0, 1, 3, 0, 1, 3, /* page: border, border, spine */
                                        0, 4, 1, 0, 4, 1, /* page: spine, border, border */
                                        2, 0, 1, 2, 5, 1 /* across 1-2, border, border */};
    uint32_t adjacency[sizeof expected / sizeof *expected];
    assert_true(mesh_edges_build_welded(&book, &e));
    assert_false(e.closed);
    volume_silhouette_adjacency(&book, &e, adjacency);
    assert_memory_equal(adjacency, expected, sizeof expected);
    mesh_edges_free(&e);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_closed_box_sides_on_silhouette_once),
        cmocka_unit_test(test_light_inside_closed_box),
        cmocka_unit_test(test_facing_edge_on),
        cmocka_unit_test(test_plane_lit_from_behind_reverses_sides),
        cmocka_unit_test(test_trimmed_volume_closed_beyond_reach),
        cmocka_unit_test(test_trim_off_near_the_light),
        cmocka_unit_test(test_near_rectangle_goes_round),
        cmocka_unit_test(test_zpass_safe_only_beyond_the_light),
        cmocka_unit_test(test_count_at_a_point),
        cmocka_unit_test(test_misses_view_only_when_the_sweep_does),
        cmocka_unit_test(test_missed_volumes_have_no_point_in_view),
        cmocka_unit_test(test_receivers_ndc),
        cmocka_unit_test(test_depth_bounds),
        cmocka_unit_test(test_adjacency_marks_borders),
        cmocka_unit_test(test_welded_apart_is_open),
    };
    return cmocka_run_group_tests_name("shadow volumes' CPU geometry", tests, NULL, NULL);
}
