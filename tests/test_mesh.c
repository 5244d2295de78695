/* Tests of common/data/mesh.c: generators, model loading, sanitizing, welding.
 * Run from the repository root (the paths are relative to it). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cmocka.h>

#include "support.h"

#include "mesh.h"
#include "mesh_pack.h"

#define TESTMODELS_DIR "/usr/share/assimp/models"
#define PI 3.14159265358979323846

/* ASan reserves terabytes of address space for its shadow memory, and its
 * operator new aborts instead of throwing std::bad_alloc, whatever
 * ASAN_OPTIONS say: under ASan the address space is never capped. */
#if defined(__SANITIZE_ADDRESS__)
#define UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define UNDER_ASAN 1
#endif
#endif
#ifndef UNDER_ASAN
#define UNDER_ASAN 0
#endif

/* The text is one line holding every one of the (NULL-terminated) parts. */
static void assert_one_line_with(const char *text, ...) {
    const char *newline = strchr(text, '\n');
    if (!newline || newline[1] != '\0')
        fail_msg("expected exactly one line, got \"%s\"", text);
    va_list parts;
    va_start(parts, text);
    for (const char *part = va_arg(parts, const char *); part; part = va_arg(parts, const char *)) {
        if (!strstr(text, part))
            fail_msg("expected \"%s\" in \"%s\"", part, text);
    }
    va_end(parts);
}

static void assert_empty_mesh(const mesh *m) {
    assert_null(m->vertices);
    assert_null(m->indices);
    assert_int_equal(m->vertex_count, 0);
    assert_int_equal(m->index_count, 0);
}

static mesh_edge_counts count_edges(const mesh *m) {
    mesh_topology topology;
    assert_true(mesh_weld(m, &topology));
    mesh_edge_counts counts = mesh_topology_count_edges(m, &topology);
    mesh_topology_free(&topology);
    return counts;
}

static void cross_of(const mesh *m, uint32_t first_index, double cross[3]) {
    const float *a = m->vertices[m->indices[first_index]].position;
    const float *b = m->vertices[m->indices[first_index + 1]].position;
    const float *c = m->vertices[m->indices[first_index + 2]].position;
    double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    cross[0] = ab[1] * ac[2] - ab[2] * ac[1];
    cross[1] = ab[2] * ac[0] - ab[0] * ac[2];
    cross[2] = ab[0] * ac[1] - ab[1] * ac[0];
}

/* Divergence theorem: positive when the triangles face outwards. */
static double signed_volume(const mesh *m) {
    double volume = 0;
    for (uint32_t i = 0; i < m->index_count; i += 3) {
        const float *a = m->vertices[m->indices[i]].position;
        double cross[3];
        cross_of(m, i, cross);
        volume += (a[0] * cross[0] + a[1] * cross[1] + a[2] * cross[2]) / 6;
    }
    return volume;
}

/* What every mesh handed out must be: valid indices, finite positions inside
 * the bounds, unit normals, no zero-area triangle. */
static void assert_sane_mesh(const mesh *m) {
    assert_true(m->index_count > 0);
    assert_int_equal(m->index_count % 3, 0);
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const mesh_vertex *vertex = &m->vertices[v];
        double length = 0;
        for (int k = 0; k < 3; k++) {
            assert_true(isfinite(vertex->position[k]));
            assert_true(vertex->position[k] >= m->bounds_min[k] && vertex->position[k] <= m->bounds_max[k]);
            length += vertex->normal[k] * vertex->normal[k];
        }
        assert_float_equal(sqrt(length), 1.0, 1e-3);
    }
    double diagonal = 0;
    for (int k = 0; k < 3; k++)
        diagonal += pow(m->bounds_max[k] - m->bounds_min[k], 2);
    for (uint32_t i = 0; i < m->index_count; i += 3) {
        double cross[3];
        for (int k = 0; k < 3; k++)
            assert_true(m->indices[i + k] < m->vertex_count);
        cross_of(m, i, cross);
        assert_true(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2] > 1e-20 * diagonal * diagonal);
    }
}

/* The generators' normals lean the way the winding faces. (Not so for every
 * model: the smooth normals of a tetrahedron's corners lean away from the
 * opposite face.) */
static void assert_normals_follow_winding(const mesh *m) {
    for (uint32_t i = 0; i < m->index_count; i += 3) {
        double cross[3], normal_sum[3] = {0, 0, 0};
        cross_of(m, i, cross);
        for (int k = 0; k < 3; k++) {
            for (int j = 0; j < 3; j++)
                normal_sum[j] += m->vertices[m->indices[i + k]].normal[j];
        }
        assert_true(cross[0] * normal_sum[0] + cross[1] * normal_sum[1] + cross[2] * normal_sum[2] > 0);
    }
}

/* What the generators promise beyond sanity. */
static void assert_good_generated_mesh(const mesh *m) {
    assert_sane_mesh(m);
    assert_normals_follow_winding(m);
}

static void assert_bounds(const mesh *m, const float min[3], const float max[3]) {
    for (int k = 0; k < 3; k++) {
        assert_float_equal(m->bounds_min[k], min[k], 1e-5);
        assert_float_equal(m->bounds_max[k], max[k], 1e-5);
    }
}

/* Bounds of a mesh centred on the origin. */
static void assert_centred_bounds(const mesh *m, float x, float y, float z) {
    assert_bounds(m, (const float[3]){-x, -y, -z}, (const float[3]){x, y, z});
}

static void assert_closed(const mesh *m) {
    mesh_edge_counts edges = count_edges(m);
    assert_int_equal(edges.boundary, 0);
    assert_int_equal(edges.non_manifold, 0);
    assert_true(edges.manifold > 0);
    assert_true(signed_volume(m) > 0);
}

static void test_plane(void **state) {
    (void)state;
    mesh m;
    assert_true(mesh_make_plane(&m, 4, 2));
    assert_good_generated_mesh(&m);
    assert_int_equal(m.vertex_count, 4);
    assert_int_equal(m.index_count, 6);
    assert_centred_bounds(&m, 2, 0, 1);
    for (uint32_t i = 0; i < m.index_count; i += 3) {
        double cross[3];
        cross_of(&m, i, cross);
        assert_true(cross[1] > 0 && cross[0] == 0 && cross[2] == 0); /* facing +Y */
    }
    mesh_edge_counts edges = count_edges(&m);
    assert_int_equal(edges.boundary, 4);
    assert_int_equal(edges.manifold, 1);
    assert_int_equal(edges.non_manifold, 0);
    mesh_free(&m);
    assert_empty_mesh(&m);
}

static void test_box(void **state) {
    (void)state;
    mesh m;
    assert_true(mesh_make_box(&m, 2, 4, 6));
    assert_good_generated_mesh(&m);
    assert_int_equal(m.vertex_count, 24);
    assert_int_equal(m.index_count, 36);
    assert_centred_bounds(&m, 1, 2, 3);
    assert_closed(&m);
    assert_float_equal(signed_volume(&m), 48, 1e-4);
    /* Flat: every triangle's normals are its face normal. */
    for (uint32_t i = 0; i < m.index_count; i += 3) {
        double cross[3];
        cross_of(&m, i, cross);
        double length = sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
        for (int k = 0; k < 3; k++) {
            for (int j = 0; j < 3; j++) {
                assert_float_equal(m.vertices[m.indices[i + k]].normal[j], cross[j] / length, 1e-6);
            }
        }
    }
    mesh_free(&m);
}

static void test_sphere(void **state) {
    (void)state;
    const int segment_counts[] = {0, 3, 4, 7, 64};
    for (size_t i = 0; i < sizeof segment_counts / sizeof *segment_counts; i++) {
        mesh m;
        assert_true(mesh_make_sphere(&m, 2, segment_counts[i]));
        assert_good_generated_mesh(&m);
        assert_closed(&m);
        assert_float_equal(m.bounds_max[1], 2, 1e-6); /* the poles */
        assert_float_equal(m.bounds_min[1], -2, 1e-6);
        mesh_free(&m);
    }
    mesh m;
    assert_true(mesh_make_sphere(&m, 2, 0)); /* default: 32 slices, 16 stacks */
    assert_int_equal(m.vertex_count, 2 + 15 * 32);
    assert_int_equal(m.index_count, 3 * 2 * 32 * 15);
    assert_centred_bounds(&m, 2, 2, 2);
    assert_float_equal(signed_volume(&m), 4.0 / 3.0 * PI * 8, 0.02 * 4.0 / 3.0 * PI * 8);
    for (uint32_t v = 0; v < m.vertex_count; v++) {
        const float *p = m.vertices[v].position;
        assert_float_equal(sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), 2, 1e-5);
    }
    mesh_free(&m);
}

static void test_torus(void **state) {
    (void)state;
    const int segment_counts[] = {0, 3, 5, 48};
    for (size_t i = 0; i < sizeof segment_counts / sizeof *segment_counts; i++) {
        mesh m;
        assert_true(mesh_make_torus(&m, 3, 1, segment_counts[i]));
        assert_good_generated_mesh(&m);
        assert_closed(&m);
        mesh_free(&m);
    }
    mesh m;
    assert_true(mesh_make_torus(&m, 3, 1, 0));
    assert_centred_bounds(&m, 4, 1, 4);
    /* 2 pi^2 R r^2, less what the polygons cut off: 32 rings of 16 sides
     * keep all but about three hundredths of it. */
    assert_float_equal(signed_volume(&m), 2 * PI * PI * 3, 0.05 * 2 * PI * PI * 3);
    mesh_free(&m);
}

static void test_cylinder(void **state) {
    (void)state;
    const int segment_counts[] = {0, 3, 5, 100};
    for (size_t i = 0; i < sizeof segment_counts / sizeof *segment_counts; i++) {
        mesh m;
        assert_true(mesh_make_cylinder(&m, 1, 3, segment_counts[i]));
        assert_good_generated_mesh(&m);
        assert_closed(&m);
        mesh_free(&m);
    }
    mesh m;
    assert_true(mesh_make_cylinder(&m, 1, 3, 0));
    assert_centred_bounds(&m, 1, 1.5f, 1);
    assert_float_equal(signed_volume(&m), PI * 3, 0.01 * PI * 3);
    mesh_free(&m);
}

static void expect_generator_error(bool made, mesh *m, const char *text, const char *generator, const char *what) {
    assert_false(made);
    assert_empty_mesh(m);
    assert_one_line_with(text, generator, what, NULL);
}

static void test_generators_reject_bad_sizes(void **state) {
    (void)state;
    const float bad[] = {0, -1, NAN, INFINITY, -INFINITY};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        mesh m;
        bool made;
        support_capture_stderr();
        made = mesh_make_plane(&m, 1, bad[i]);
        expect_generator_error(made, &m, support_release_stderr(), "plane: ", "size_z");
        support_capture_stderr();
        made = mesh_make_box(&m, 1, bad[i], 1);
        expect_generator_error(made, &m, support_release_stderr(), "box: ", "size_y");
        support_capture_stderr();
        made = mesh_make_sphere(&m, bad[i], 8);
        expect_generator_error(made, &m, support_release_stderr(), "sphere: ", "radius");
        support_capture_stderr();
        made = mesh_make_torus(&m, 2, bad[i], 8);
        expect_generator_error(made, &m, support_release_stderr(), "torus: ", "minor_radius");
        support_capture_stderr();
        made = mesh_make_cylinder(&m, 1, bad[i], 8);
        expect_generator_error(made, &m, support_release_stderr(), "cylinder: ", "height");
    }
    mesh m;
    bool made;
    support_capture_stderr();
    made = mesh_make_sphere(&m, 1, 2);
    expect_generator_error(made, &m, support_release_stderr(),
                           "sphere: ", "segments must be between 3 and 1024 (got 2)");
    support_capture_stderr();
    made = mesh_make_cylinder(&m, 1, 1, MESH_MAX_SEGMENTS + 1);
    expect_generator_error(made, &m, support_release_stderr(), "cylinder: ", "segments");
    support_capture_stderr(); /* only 0 is the default */
    made = mesh_make_sphere(&m, 1, -1);
    expect_generator_error(made, &m, support_release_stderr(),
                           "sphere: ", "segments must be between 3 and 1024 (got -1)");
    support_capture_stderr();
    made = mesh_make_torus(&m, 1, 1, 8);
    expect_generator_error(made, &m, support_release_stderr(), "torus: ", "must be smaller than major_radius");
}

static void test_generators_at_extreme_scales(void **state) {
    (void)state;
    const float scales[] = {1e-30f, 1e30f};
    for (size_t i = 0; i < sizeof scales / sizeof *scales; i++) {
        mesh m;
        assert_true(mesh_make_sphere(&m, scales[i], 16));
        assert_good_generated_mesh(&m);
        assert_closed(&m);
        mesh_free(&m);
        assert_true(mesh_make_box(&m, scales[i], scales[i], scales[i]));
        assert_closed(&m);
        mesh_free(&m);
    }
}

static void test_weld_joins_copies_within_tolerance(void **state) {
    (void)state;
    /* Two triangles sharing the edge (1,0,0)-(0,1,0), through copies: one
     * bit-identical, one off by far less than the tolerance (1e-6 of the
     * diagonal). The last vertex is near (1,0,0) but well outside it. */
    mesh_vertex vertices[] = {
        {{0, 0, 0}, {0, 0, 1}, {0, 0}},      {{1, 0, 0}, {0, 0, 1}, {0, 0}},
        {{0, 1, 0}, {0, 0, 1}, {0, 0}},      {{1, 0, 0}, {0, 0, 1}, {0, 0}},
        {{1, 1, 0}, {0, 0, 1}, {0, 0}},      {{0, 1.0f + 1e-9f, 0}, {0, 0, 1}, {0, 0}},
        {{1.001f, 0, 0}, {0, 0, 1}, {0, 0}},
    };
    uint32_t indices[] = {0, 1, 2, 3, 4, 5};
    mesh m = {vertices, indices, 7, 6, {0, 0, 0}, {1, 1, 0}};
    mesh_topology t;
    assert_true(mesh_weld(&m, &t));
    assert_int_equal(t.position_count, 5);
    assert_int_equal(t.position_of_vertex[1], t.position_of_vertex[3]);
    assert_int_equal(t.position_of_vertex[2], t.position_of_vertex[5]);
    assert_int_not_equal(t.position_of_vertex[1], t.position_of_vertex[6]);
    mesh_edge_counts edges = mesh_topology_count_edges(&m, &t);
    assert_int_equal(edges.boundary, 4);
    assert_int_equal(edges.manifold, 1);
    assert_int_equal(edges.non_manifold, 0);
    mesh_topology_free(&t);
}

static void test_edge_counts_see_non_manifold_edges(void **state) {
    (void)state;
    /* Three triangles on one edge, like pages of a book. */
    mesh_vertex vertices[] = {
        {{0, 0, 0}, {0, 0, 1}, {0, 0}},  {{0, 1, 0}, {0, 0, 1}, {0, 0}}, {{1, 0, 0}, {0, 0, 1}, {0, 0}},
        {{-1, 0, 0}, {0, 0, 1}, {0, 0}}, {{0, 0, 1}, {1, 0, 0}, {0, 0}},
    };
    uint32_t indices[] = {0, 1, 2, 0, 3, 1, 0, 1, 4};
    mesh m = {vertices, indices, 5, 9, {-1, 0, 0}, {1, 1, 1}};
    mesh_edge_counts edges = count_edges(&m);
    assert_int_equal(edges.non_manifold, 1);
    assert_int_equal(edges.boundary, 6);
    assert_int_equal(edges.manifold, 0);
}

static void build_edges(const mesh *m, mesh_edges *e) {
    mesh_topology topology;
    assert_true(mesh_weld(m, &topology));
    assert_true(mesh_edges_build(m, &topology, e));
    mesh_topology_free(&topology);
}

/* Each use names a triangle corner that starts the edge, running a -> b
 * (+1) or b -> a (-1), by welded position. */
static void assert_uses_match_corners(const mesh *m, const mesh_edges *e) {
    uint32_t total = 0;
    for (uint32_t i = 0; i < e->edge_count; i++) {
        const float *a = m->vertices[e->edges[i].a].position, *b = m->vertices[e->edges[i].b].position;
        for (uint32_t k = 0; k < e->edges[i].use_count; k++, total++) {
            const mesh_edge_use *u = &e->uses[e->edges[i].first_use + k];
            uint32_t next = u->corner % 3 == 2 ? u->corner - 2 : u->corner + 1;
            const float *from = m->vertices[m->indices[u->corner]].position;
            const float *to = m->vertices[m->indices[next]].position;
            assert_true(u->direction == 1 || u->direction == -1);
            assert_memory_equal(from, u->direction > 0 ? a : b, sizeof(float[3]));
            assert_memory_equal(to, u->direction > 0 ? b : a, sizeof(float[3]));
        }
    }
    assert_int_equal(total, m->index_count);
}

/* A closed box: 18 welded edges, two uses each, one each way; its
 * adjacency names, across each edge, the other triangle's third vertex. */
static void test_edge_table_of_closed_box(void **state) {
    (void)state;
    mesh m;
    mesh_edges e;
    assert_true(mesh_make_box(&m, 1, 2, 3));
    build_edges(&m, &e);
    assert_true(e.closed);
    assert_int_equal(e.edge_count, 18);
    assert_uses_match_corners(&m, &e);
    uint32_t *adjacency = malloc(m.index_count * 2 * sizeof *adjacency);
    assert_non_null(adjacency);
    assert_true(mesh_adjacency_indices(&m, &e, adjacency));
    for (uint32_t t = 0; t < m.index_count / 3; t++) {
        for (int c = 0; c < 3; c++) {
            assert_int_equal(adjacency[t * 6 + c * 2], m.indices[t * 3 + c]);
            /* The vertex across is off the edge and on neither end. */
            const float *across = m.vertices[adjacency[t * 6 + c * 2 + 1]].position;
            for (int k = 0; k < 3; k++)
                if (k != (c + 2) % 3)
                    assert_memory_not_equal(across, m.vertices[m.indices[t * 3 + k]].position, sizeof(float[3]));
        }
    }
    free(adjacency);
    mesh_edges_free(&e);
    mesh_free(&m);
}

/* Open and non-manifold meshes are not closed and have no adjacency; an
 * edge keeps every triangle that uses it. */
static void test_edge_table_of_open_and_non_manifold_meshes(void **state) {
    (void)state;
    mesh_vertex vertices[] = {
        {{0, 0, 0}, {0, 0, 1}, {0, 0}},  {{0, 1, 0}, {0, 0, 1}, {0, 0}}, {{1, 0, 0}, {0, 0, 1}, {0, 0}},
        {{-1, 0, 0}, {0, 0, 1}, {0, 0}}, {{0, 0, 1}, {1, 0, 0}, {0, 0}},
    };
    uint32_t indices[] = {0, 1, 2, 0, 3, 1, 0, 1, 4};
    mesh book = {vertices, indices, 5, 9, {-1, 0, 0}, {1, 1, 1}};
    mesh_edges e;
    build_edges(&book, &e);
    assert_false(e.closed);
    assert_int_equal(e.edge_count, 7);
    assert_uses_match_corners(&book, &e);
    uint32_t spine_uses = 0;
    for (uint32_t i = 0; i < e.edge_count; i++)
        spine_uses = e.edges[i].use_count > spine_uses ? e.edges[i].use_count : spine_uses;
    assert_int_equal(spine_uses, 3);
    uint32_t adjacency[18] = {0};
    assert_false(mesh_adjacency_indices(&book, &e, adjacency));
    mesh_edges_free(&e);

    mesh teapot;
    assert_true(mesh_load_file(&teapot, "assets/teapot.obj", NULL));
    build_edges(&teapot, &e);
    assert_false(e.closed);
    assert_uses_match_corners(&teapot, &e);
    mesh_edges_free(&e);
    mesh_free(&teapot);
}

static void test_sanitize_repairs_hand_made_mesh(void **state) {
    (void)state;
    /* A good triangle with a NaN normal, one touching a NaN vertex, one with
     * an index past the vertices, one collinear, and an unused vertex far
     * away that must not widen the bounds. */
    mesh m = {0};
    m.vertex_count = 6;
    m.index_count = 12;
    m.vertices = calloc(m.vertex_count, sizeof *m.vertices);
    m.indices = calloc(m.index_count, sizeof *m.indices);
    assert_non_null(m.vertices);
    assert_non_null(m.indices);
    const mesh_vertex vertices[] = {
        {{0, 0, 0}, {NAN, 0, 0}, {0, 0}}, {{2, 0, 0}, {0, 0, 1}, {0, 0}}, {{0, 2, 0}, {0, 0, 0}, {0, 0}},
        {{NAN, 0, 0}, {0, 0, 1}, {0, 0}}, {{1, 0, 0}, {0, 0, 1}, {0, 0}}, {{1000, 1000, 1000}, {0, 0, 1}, {0, 0}},
    };
    const uint32_t indices[] = {0, 1, 2, 0, 3, 1, 0, 1, 99, 0, 4, 1};
    memcpy(m.vertices, vertices, sizeof vertices);
    memcpy(m.indices, indices, sizeof indices);
    support_capture_stderr();
    bool sane = mesh_sanitize(&m, "hand-made");
    const char *text = support_release_stderr();
    assert_true(sane);
    assert_one_line_with(text, "warning: hand-made: removed 1 degenerate and 2 non-finite triangles", NULL);
    assert_int_equal(m.index_count, 3);
    assert_int_equal(m.vertex_count, 3);
    assert_sane_mesh(&m);
    assert_float_equal(m.bounds_max[0], 2, 0);
    assert_float_equal(m.bounds_max[2], 0, 0);
    for (uint32_t v = 0; v < m.vertex_count; v++)
        assert_float_equal(m.vertices[v].normal[2], 1, 1e-6);
    mesh_free(&m);
}

static void test_sanitize_of_nothing_is_an_error(void **state) {
    (void)state;
    mesh m = {0};
    support_capture_stderr();
    bool sane = mesh_sanitize(&m, "nothing");
    const char *text = support_release_stderr();
    assert_false(sane);
    assert_empty_mesh(&m);
    assert_one_line_with(text, "nothing: no triangles", NULL);
}

static mesh_edge_counts report_edges(const char *path, const mesh *m) {
    assert_sane_mesh(m);
    mesh_edge_counts edges = count_edges(m);
    print_message("%s: %u vertices, %u triangles; edges: %u boundary, %u manifold, %u non-manifold\n", path,
                  m->vertex_count, m->index_count / 3, edges.boundary, edges.manifold, edges.non_manifold);
    return edges;
}

static void test_load_bunny(void **state) {
    (void)state;
    mesh m;
    assert_true(mesh_load_file(&m, "assets/bunny.obj", NULL));
    mesh_edge_counts edges = report_edges("assets/bunny.obj", &m);
    assert_int_equal(m.index_count / 3, 3674);
    assert_int_equal(edges.boundary, 0);
    assert_int_equal(edges.non_manifold, 0);
    assert_int_equal(edges.manifold, 3674 * 3 / 2);
    assert_true(signed_volume(&m) > 0);
    mesh_free(&m);
}

static void test_load_teapot(void **state) {
    (void)state;
    mesh m;
    assert_true(mesh_load_file(&m, "assets/teapot.obj", NULL));
    mesh_edge_counts edges = report_edges("assets/teapot.obj", &m);
    assert_int_equal(m.index_count / 3, 992);
    /* The file repeats 540 vertices bit for bit along its patch seams: over
     * its own 792 indices it has 528 boundary edges, welded only the real
     * openings are left (rims of lid and body, ends of spout and handle). */
    assert_int_equal(edges.boundary, 64);
    assert_int_equal(edges.non_manifold, 0);
    mesh_free(&m);
}

/* mirror_node.gltf: the wedge of mirror_wedge.obj under two nodes, one
 * of them scaled by -1 in x, both using the one mesh. Baked as they were,
 * the mirrored copy turned inside out: its volume cancelled the other's.
 * Reversed, each copy faces outwards and the file holds twice the wedge. */
static void test_load_mirrored_node(void **state) {
    (void)state;
    mesh wedge, pair;
    assert_true(mesh_load_file(&wedge, "tests/data/mirror_wedge.obj", NULL));
    assert_true(mesh_load_file(&pair, "tests/data/mirror_node.gltf", NULL));
    assert_closed(&wedge);
    assert_sane_mesh(&pair);
    assert_int_equal(pair.index_count, 2 * wedge.index_count);
    print_message("wedge: volume %g; the wedge and its mirror image: %g\n", signed_volume(&wedge),
                  signed_volume(&pair));
    assert_float_equal(signed_volume(&pair), 2 * signed_volume(&wedge), 1e-6);
    mesh_free(&wedge);
    mesh_free(&pair);
}

static void test_load_testmodels(void **state) {
    (void)state;
    const char *paths[] = {TESTMODELS_DIR "/OBJ/spider.obj", TESTMODELS_DIR "/OBJ/WusonOBJ.obj"};
    for (size_t i = 0; i < sizeof paths / sizeof *paths; i++) {
        if (access(paths[i], R_OK) != 0) {
            print_message("%s missing (Debian package assimp-testmodels): skipped\n", paths[i]);
            continue;
        }
        mesh m;
        /* spider.obj holds zero-area triangles: a warning is expected. */
        support_capture_stderr();
        bool loaded = mesh_load_file(&m, paths[i], NULL);
        print_message("%s", support_release_stderr());
        assert_true(loaded);
        assert_true(m.index_count > 0);
        report_edges(paths[i], &m);
        mesh_free(&m);
    }
}

typedef struct model_case {
    const char *path;
    const char *problem; /* in the one line of the error; NULL: loads */
    uint32_t triangles;  /* when it loads */
} model_case;

/* Loads each model that exists (a missing one is skipped, saying so) and
 * checks the outcome: loaded with its triangle count, or refused with one
 * line naming the file and the problem. Returns how many were tried. */
static int expect_models(const model_case *cases, size_t count) {
    int tried = 0;
    for (size_t i = 0; i < count; i++) {
        if (access(cases[i].path, R_OK) != 0) {
            print_message("%s missing (Debian package assimp-testmodels): skipped\n", cases[i].path);
            continue;
        }
        mesh m;
        support_capture_stderr();
        bool loaded = mesh_load_file(&m, cases[i].path, NULL);
        const char *text = support_release_stderr();
        if (loaded) {
            print_message("%s: loaded, %u triangles\n", cases[i].path, m.index_count / 3);
        } else {
            print_message("%s", text);
        }
        if (cases[i].problem) {
            assert_false(loaded);
            assert_empty_mesh(&m);
            char expected[512];
            snprintf(expected, sizeof expected, "%s: %s", cases[i].path, cases[i].problem);
            assert_one_line_with(text, expected, NULL);
        } else {
            assert_true(loaded);
            assert_sane_mesh(&m);
            assert_int_equal(m.index_count / 3, cases[i].triangles);
        }
        mesh_free(&m);
        tried++;
    }
    return tried;
}

/* Every file of assimp-testmodels' invalid/ directory, which holds no
 * other. OutOfMemory.off claims 353535235358 vertices, which assimp 5.2's
 * reader wraps to 1347917086 and allocates (16 GB): it must be refused
 * before assimp reads it, from the header's claims. The address space is
 * capped all the same, so that a regression fails on the message instead
 * of taking the machine's memory (not under ASan, whose shadow memory
 * needs a large address space: there the pre-check alone keeps it out). */
/* A model's colour: its named materials' base or diffuse colour, the one
 * that covers the most triangles (materials of one colour together); none
 * where the file names no material (assimp's stand-in is not the file's
 * colour). */
static void test_load_material_colour(void **state) {
    (void)state;
    static const struct {
        const char *path;
        bool has_color;
        float color[3];
    } cases[] = {
        /* red covers the most of one material, blue of one colour */
        {"tests/data/mesh_two_colours.obj", true, {0.1f, 0.2f, 0.9f}},
        /* OBJ from assimp-testmodels: the floor's Kd, of 12 materials */
        {TESTMODELS_DIR "/OBJ/regr01.obj", true, {0.9f, 0.9f, 0.7f}},
        /* glTF: baseColorFactor, grey parts most of the engine */
        {TESTMODELS_DIR "/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", true, {0.85f, 0.85f, 0.85f}},
        {"assets/bunny.obj", false, {0}},            /* no .mtl */
        {"tests/data/io_off_cube.off", false, {0}},  /* no materials in OFF */
        {"tests/data/mirror_node.gltf", false, {0}}, /* a primitive without a material */
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        mesh m;
        mesh_material material = {.has_color = !cases[i].has_color};
        support_capture_stderr(); /* the engine's degenerate triangles' warning */
        bool loaded = mesh_load_file(&m, cases[i].path, &material);
        support_release_stderr();
        assert_true(loaded);
        if (material.has_color != cases[i].has_color)
            fail_msg("%s: has_color %d, expected %d", cases[i].path, material.has_color, cases[i].has_color);
        for (int k = 0; cases[i].has_color && k < 3; k++)
            if (material.color[k] != cases[i].color[k])
                fail_msg("%s: channel %d is %g, expected %g", cases[i].path, k, material.color[k], cases[i].color[k]);
        mesh_free(&m);
    }
}

static void test_load_invalid_models(void **state) {
    (void)state;
    static const model_case cases[] = {
        {TESTMODELS_DIR "/invalid/OutOfMemory.off",
         "OFF header claims 353535235358 vertices and 6 faces: at least 707070470728 bytes, but the file holds", 0},
        {TESTMODELS_DIR "/invalid/empty.3ds", "StreamReader: File is empty", 0},
        {TESTMODELS_DIR "/invalid/empty.ase", "File is empty", 0},
        {TESTMODELS_DIR "/invalid/empty.lwo", "LWO: The file is too small", 0},
        {TESTMODELS_DIR "/invalid/empty.md5mesh", "Failed to read valid contents", 0},
        {TESTMODELS_DIR "/invalid/empty.obj", "OBJ-file is too small", 0},
        {TESTMODELS_DIR "/invalid/empty.off", "File is empty", 0},
        {TESTMODELS_DIR "/invalid/empty.ply", "File ", 0}, /* "File PATH is empty." */
        {TESTMODELS_DIR "/invalid/empty.raw", "File is empty", 0},
        {TESTMODELS_DIR "/invalid/empty.smd", "File is empty", 0},
        {TESTMODELS_DIR "/invalid/empty.x", "XFile is too small", 0},
        {TESTMODELS_DIR "/invalid/emptyIrrMesh.xml", "IRRMESH: Unable to read a mesh", 0},
        {TESTMODELS_DIR "/invalid/malformed.obj", "OBJ: Invalid face index", 0},
        /* A whole cube with an unknown material. */
        {TESTMODELS_DIR "/invalid/malformed2.obj", NULL, 10},
        {TESTMODELS_DIR "/invalid/readme.txt", "No suitable reader found", 0},
    };
    struct rlimit saved_limit;
    assert_int_equal(getrlimit(RLIMIT_AS, &saved_limit), 0);
    if (!UNDER_ASAN) {
        struct rlimit capped = saved_limit;
        capped.rlim_cur = (rlim_t)4 << 30;
        if (saved_limit.rlim_cur == RLIM_INFINITY || saved_limit.rlim_cur > capped.rlim_cur) {
            assert_int_equal(setrlimit(RLIMIT_AS, &capped), 0);
        }
    }
    int tried = expect_models(cases, sizeof cases / sizeof *cases);
    assert_int_equal(setrlimit(RLIMIT_AS, &saved_limit), 0);
    print_message("invalid models: %d of %zu tried\n", tried, sizeof cases / sizeof *cases);
}

/* Headers whose counts the file cannot hold are refused before assimp
 * reads them (it would allocate for every claimed vertex or face); the
 * same files with true counts load. */
static void test_load_checks_header_claims(void **state) {
    (void)state;
    static const model_case cases[] = {
        {"tests/data/io_off_cube.off", NULL, 12},
        {"tests/data/io_off_claims_too_many.off",
         "OFF header claims 100000000 vertices and 6 faces: at least 200000012 bytes, but the file holds 171 after "
         "the header (refused before assimp allocates for them)",
         0},
        {"tests/data/io_off_no_keyword_claims_too_many.off", "OFF header claims 8 vertices and 100000000 faces", 0},
        {"tests/data/io_ply_triangle.ply", NULL, 1},
        {"tests/data/io_ply_claims_too_many.ply",
         "PLY header claims elements (3 vertex, 100000000 face): at least 200000006 bytes, but the file holds 26", 0},
        {"tests/data/io_ply_binary_triangle.ply", NULL, 1},
        {"tests/data/io_ply_binary_claims_too_many.ply",
         "PLY header claims elements (100000000 vertex, 1 face): at least 300000001 bytes, but the file holds 49", 0},
    };
    assert_int_equal(expect_models(cases, sizeof cases / sizeof *cases), sizeof cases / sizeof *cases);
}

/* Real OFF and PLY files of assimp-testmodels pass the header check. */
static void test_load_testmodels_with_headers(void **state) {
    (void)state;
    static const model_case cases[] = {
        {TESTMODELS_DIR "/OFF/Cube.off", NULL, 12},
        {TESTMODELS_DIR "/PLY/cube.ply", NULL, 12},
        {TESTMODELS_DIR "/PLY/cube_binary.ply", NULL, 12},
    };
    expect_models(cases, sizeof cases / sizeof *cases);
}

static void test_load_removes_non_finite_triangles(void **state) {
    (void)state;
    mesh m;
    support_capture_stderr();
    bool loaded = mesh_load_file(&m, "tests/data/mesh_nan_vertex.obj", NULL);
    const char *text = support_release_stderr();
    assert_true(loaded);
    assert_one_line_with(
        text, "warning: tests/data/mesh_nan_vertex.obj: ", "removed 0 degenerate and 2 non-finite triangles", NULL);
    assert_int_equal(m.index_count, 12);
    assert_sane_mesh(&m);
    assert_bounds(&m, (const float[3]){0, 0, 0}, (const float[3]){1, 1, 1});
    assert_closed(&m);
    mesh_free(&m);
}

static void test_load_removes_degenerate_triangles(void **state) {
    (void)state;
    mesh m;
    support_capture_stderr();
    bool loaded = mesh_load_file(&m, "tests/data/mesh_degenerate_triangles.obj", NULL);
    const char *text = support_release_stderr();
    assert_true(loaded);
    assert_one_line_with(text, "warning: tests/data/mesh_degenerate_triangles.obj: ",
                         "removed 3 degenerate and 0 non-finite triangles", NULL);
    assert_int_equal(m.index_count, 12);
    assert_int_equal(m.vertex_count, 4);
    assert_sane_mesh(&m);
    assert_closed(&m);
    mesh_free(&m);
}

static void test_load_clean_model_is_quiet(void **state) {
    (void)state;
    mesh m;
    support_capture_stderr();
    bool loaded = mesh_load_file(&m, "tests/data/mesh_tetrahedron.obj", NULL);
    const char *text = support_release_stderr();
    assert_true(loaded);
    assert_string_equal(text, "");
    assert_int_equal(m.vertex_count, 4);
    assert_closed(&m);
    mesh_free(&m);
}

static void expect_load_error(const char *path, const char *problem) {
    mesh m;
    support_capture_stderr();
    bool loaded = mesh_load_file(&m, path, NULL);
    const char *text = support_release_stderr();
    assert_false(loaded);
    assert_empty_mesh(&m);
    char expected[512];
    snprintf(expected, sizeof expected, "%s: %s", path, problem);
    assert_one_line_with(text, expected, NULL);
    mesh_free(&m);
}

static void test_load_errors(void **state) {
    (void)state;
    expect_load_error("tests/data/mesh_only_degenerate.obj",
                      "no triangles left after removing 2 degenerate and 0 non-finite");
    expect_load_error("tests/data/mesh_lines_only.obj", "no triangles");
    expect_load_error("tests/data/mesh_bad_index.obj", "OBJ:");
    expect_load_error("tests/data/mesh_single_vertex_line.obj", "line 8: a line statement needs 2 or more vertices");
    expect_load_error("tests/data/no_such_file.obj", "cannot open: No such file or directory");
    expect_load_error("tests/data", "not a regular file");
    expect_load_error("tests/data/scene_good.json", ""); /* assimp has no reader for it */
}

/* A mesh pack (mesh_pack.h, the web build's models) reads back the mesh
 * and colour mesh_load_file made, bit for bit; a file that is no pack, or
 * a truncated one, is one line naming it. */
#define PACK_DIR "out/test/mesh_pack"
static void test_pack_round_trip(void **state) {
    (void)state;
    static const char *const models[] = {"assets/bunny.obj", "tests/data/mesh_two_colours.obj"};
    assert_int_equal(system("mkdir -p " PACK_DIR), 0);
    for (size_t i = 0; i < sizeof models / sizeof *models; i++) {
        mesh loaded, read;
        mesh_material loaded_material, read_material;
        assert_true(mesh_load_file(&loaded, models[i], &loaded_material));
        assert_true(mesh_pack_write(PACK_DIR "/model.pack", &loaded, &loaded_material));
        assert_true(mesh_pack_read(&read, PACK_DIR "/model.pack", &read_material));
        assert_int_equal(read.vertex_count, loaded.vertex_count);
        assert_int_equal(read.index_count, loaded.index_count);
        assert_memory_equal(read.vertices, loaded.vertices, loaded.vertex_count * sizeof *loaded.vertices);
        assert_memory_equal(read.indices, loaded.indices, loaded.index_count * sizeof *loaded.indices);
        assert_memory_equal(read.bounds_min, loaded.bounds_min, sizeof loaded.bounds_min);
        assert_memory_equal(read.bounds_max, loaded.bounds_max, sizeof loaded.bounds_max);
        assert_int_equal(read_material.has_color, loaded_material.has_color);
        assert_memory_equal(read_material.color, loaded_material.color, sizeof loaded_material.color);
        mesh_free(&loaded);
        mesh_free(&read);
    }
    /* The pack cut short, then a file that is no pack. */
    assert_int_equal(system("head -c 100 " PACK_DIR "/model.pack > " PACK_DIR "/short.pack"), 0);
    static const struct {
        const char *path, *problem;
    } bad[] = {
        {PACK_DIR "/short.pack", "truncated"},
        {"assets/bunny.obj", "not a mesh pack"},
        {PACK_DIR "/none.pack", "cannot open"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        mesh m;
        support_capture_stderr();
        bool read = mesh_pack_read(&m, bad[i].path, NULL);
        const char *text = support_release_stderr();
        assert_false(read);
        assert_empty_mesh(&m);
        char expected[256];
        snprintf(expected, sizeof expected, "%s: %s", bad[i].path, bad[i].problem);
        assert_one_line_with(text, expected, NULL);
    }
}

typedef struct reported_error {
    char name[256];
    char problem[256];
    int count;
} reported_error;

static void record_error(const char *name, const char *problem, void *user_data) {
    reported_error *error = user_data;
    snprintf(error->name, sizeof error->name, "%s", name);
    snprintf(error->problem, sizeof error->problem, "%s", problem);
    error->count++;
}

static void test_error_handler_replaces_stderr(void **state) {
    (void)state;
    reported_error error = {.count = 0};
    mesh m;
    mesh_set_error_handler(record_error, &error);
    support_capture_stderr();
    bool made = mesh_make_sphere(&m, -1, 0);
    const char *text = support_release_stderr();
    mesh_set_error_handler(NULL, NULL);
    assert_false(made);
    assert_string_equal(text, "");
    assert_int_equal(error.count, 1);
    assert_string_equal(error.name, "sphere");
    assert_non_null(strstr(error.problem, "radius"));
    assert_null(strchr(error.problem, '\n'));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_plane),
        cmocka_unit_test(test_box),
        cmocka_unit_test(test_sphere),
        cmocka_unit_test(test_torus),
        cmocka_unit_test(test_cylinder),
        cmocka_unit_test(test_generators_reject_bad_sizes),
        cmocka_unit_test(test_generators_at_extreme_scales),
        cmocka_unit_test(test_weld_joins_copies_within_tolerance),
        cmocka_unit_test(test_edge_counts_see_non_manifold_edges),
        cmocka_unit_test(test_edge_table_of_closed_box),
        cmocka_unit_test(test_edge_table_of_open_and_non_manifold_meshes),
        cmocka_unit_test(test_sanitize_repairs_hand_made_mesh),
        cmocka_unit_test(test_sanitize_of_nothing_is_an_error),
        cmocka_unit_test(test_load_bunny),
        cmocka_unit_test(test_load_teapot),
        cmocka_unit_test(test_load_mirrored_node),
        cmocka_unit_test(test_load_testmodels),
        cmocka_unit_test(test_load_material_colour),
        cmocka_unit_test(test_load_invalid_models),
        cmocka_unit_test(test_load_checks_header_claims),
        cmocka_unit_test(test_load_testmodels_with_headers),
        cmocka_unit_test(test_load_removes_non_finite_triangles),
        cmocka_unit_test(test_load_removes_degenerate_triangles),
        cmocka_unit_test(test_load_clean_model_is_quiet),
        cmocka_unit_test(test_load_errors),
        cmocka_unit_test(test_error_handler_replaces_stderr),
        cmocka_unit_test(test_pack_round_trip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
