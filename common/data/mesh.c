/* mesh: procedural generators, sanitizing and welding (model files:
 * mesh_file.c). The contract is in mesh.h. */
#include "mesh.h"

#include <cglm/cglm.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh_build.h"

#define MESH_DEFAULT_SEGMENTS 32

/* Welding tolerance, as a fraction of the bounding-box diagonal. Seams (normal
 * or UV splits, per-face vertex copies) carry bit-identical or nearly
 * identical positions, far closer than any real feature of the model; being
 * relative, the tolerance welds a 1 mm part and a 1 km terrain alike. */
#define MESH_WELD_TOLERANCE 1e-6

static mesh_error_handler mesh_on_error;
static void *mesh_on_error_user_data;

void mesh_set_error_handler(mesh_error_handler handler, void *user_data) {
    mesh_on_error = handler;
    mesh_on_error_user_data = user_data;
}

bool mesh_fail(mesh *m, const char *name, const char *format, ...) {
    char problem[512];
    va_list args;
    va_start(args, format);
    vsnprintf(problem, sizeof problem, format, args);
    va_end(args);
    /* Importers' messages may span lines; the contract is one line. */
    for (char *c = problem; *c; c++) {
        if (*c == '\n' || *c == '\r')
            *c = ' ';
    }
    if (mesh_on_error) {
        mesh_on_error(name, problem, mesh_on_error_user_data);
    } else {
        fprintf(stderr, "%s: %s\n", name, problem);
    }
    if (m)
        mesh_free(m);
    return false;
}

void mesh_free(mesh *m) {
    free(m->vertices);
    free(m->indices);
    *m = (mesh){0};
}

void mesh_topology_free(mesh_topology *t) {
    free(t->position_of_vertex);
    free(t->positions);
    *t = (mesh_topology){0};
}

bool mesh_alloc(mesh *m, const char *name, size_t vertex_count, size_t index_count) {
    *m = (mesh){0};
    if (vertex_count > UINT32_MAX || index_count > UINT32_MAX) {
        return mesh_fail(m, name, "too large for 32-bit indices (%zu vertices, %zu indices)", vertex_count,
                         index_count);
    }
    m->vertices = malloc(vertex_count * sizeof *m->vertices);
    m->indices = malloc(index_count * sizeof *m->indices);
    if (!m->vertices || !m->indices)
        return mesh_fail(m, name, "out of memory");
    return true;
}

uint32_t mesh_push_vertex(mesh *m, const float position[3], const float normal[3]) {
    mesh_vertex *v = &m->vertices[m->vertex_count];
    memcpy(v->position, position, sizeof v->position);
    memcpy(v->normal, normal, sizeof v->normal);
    v->uv[0] = v->uv[1] = 0;
    return m->vertex_count++;
}

void mesh_push_triangle(mesh *m, uint32_t a, uint32_t b, uint32_t c) {
    m->indices[m->index_count++] = a;
    m->indices[m->index_count++] = b;
    m->indices[m->index_count++] = c;
}

/* a, b, c, d counter-clockwise seen from outside. */
static void mesh_push_quad(mesh *m, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    mesh_push_triangle(m, a, b, c);
    mesh_push_triangle(m, a, c, d);
}

static bool mesh_check_size(mesh *m, const char *name, const char *what, float value) {
    if (isfinite(value) && value > 0)
        return true;
    return mesh_fail(m, name, "%s must be finite and positive (got %g)", what, value);
}

static bool mesh_check_segments(mesh *m, const char *name, int *segments) {
    if (*segments == 0)
        *segments = MESH_DEFAULT_SEGMENTS;
    if (*segments >= MESH_MIN_SEGMENTS && *segments <= MESH_MAX_SEGMENTS)
        return true;
    return mesh_fail(m, name, "segments must be between %d and %d (got %d)", MESH_MIN_SEGMENTS, MESH_MAX_SEGMENTS,
                     *segments);
}

/* Point i of n on the unit circle around Y. It starts at +Z and turns towards
 * +X, which is counter-clockwise seen from +Y: the generators' windings rely
 * on that. */
static void mesh_circle_point(int i, int n, float *x, float *z) {
    double angle = 2.0 * GLM_PI * i / n;
    *x = (float)sin(angle);
    *z = (float)cos(angle);
}

/* Vertex (row, column) of a grid laid out row after row; columns wrap around,
 * which closes rings without duplicating their first vertex. */
static uint32_t mesh_grid_vertex(uint32_t first, int row, int column, int columns) {
    return first + (uint32_t)row * (uint32_t)columns + (uint32_t)(column % columns);
}

bool mesh_make_plane(mesh *m, float size_x, float size_z) {
    *m = (mesh){0};
    if (!mesh_check_size(m, "plane", "size_x", size_x) || !mesh_check_size(m, "plane", "size_z", size_z) ||
        !mesh_alloc(m, "plane", 4, 6)) {
        return false;
    }
    float x = size_x / 2, z = size_z / 2;
    const float up[3] = {0, 1, 0};
    uint32_t a = mesh_push_vertex(m, (const float[3]){-x, 0, -z}, up);
    uint32_t b = mesh_push_vertex(m, (const float[3]){-x, 0, z}, up);
    uint32_t c = mesh_push_vertex(m, (const float[3]){x, 0, z}, up);
    uint32_t d = mesh_push_vertex(m, (const float[3]){x, 0, -z}, up);
    mesh_push_quad(m, a, b, c, d);
    return mesh_sanitize(m, "plane");
}

bool mesh_make_box(mesh *m, float size_x, float size_y, float size_z) {
    *m = (mesh){0};
    if (!mesh_check_size(m, "box", "size_x", size_x) || !mesh_check_size(m, "box", "size_y", size_y) ||
        !mesh_check_size(m, "box", "size_z", size_z) || !mesh_alloc(m, "box", 24, 36)) {
        return false;
    }
    const float half[3] = {size_x / 2, size_y / 2, size_z / 2};
    static const float corner_signs[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int axis = 0; axis < 3; axis++) {
        for (int side = -1; side <= 1; side += 2) {
            /* Corners go counter-clockwise in the (u, v) plane, so the face
             * points along u x v: the axis' cyclic successors (u, v) give
             * +axis; swapped, they give -axis. */
            int u = (axis + (side > 0 ? 1 : 2)) % 3;
            int v = (axis + (side > 0 ? 2 : 1)) % 3;
            float normal[3] = {0, 0, 0};
            normal[axis] = (float)side;
            uint32_t first = m->vertex_count;
            for (int i = 0; i < 4; i++) {
                float position[3];
                position[axis] = side * half[axis];
                position[u] = corner_signs[i][0] * half[u];
                position[v] = corner_signs[i][1] * half[v];
                mesh_push_vertex(m, position, normal);
            }
            mesh_push_quad(m, first, first + 1, first + 2, first + 3);
        }
    }
    return mesh_sanitize(m, "box");
}

bool mesh_make_sphere(mesh *m, float radius, int segments) {
    *m = (mesh){0};
    if (!mesh_check_size(m, "sphere", "radius", radius) || !mesh_check_segments(m, "sphere", &segments)) {
        return false;
    }
    /* Rings of latitude between two single pole vertices: the caps are fans
     * of real triangles, not quads collapsed onto the pole. */
    int slices = segments;
    int stacks = segments / 2 < 2 ? 2 : segments / 2;
    int rings = stacks - 1;
    if (!mesh_alloc(m, "sphere", 2 + (size_t)rings * slices, 6 * (size_t)slices * rings)) {
        return false;
    }
    uint32_t north = mesh_push_vertex(m, (const float[3]){0, radius, 0}, (const float[3]){0, 1, 0});
    uint32_t first_ring = m->vertex_count;
    for (int ring = 0; ring < rings; ring++) {
        double latitude = GLM_PI * (ring + 1) / stacks;
        for (int slice = 0; slice < slices; slice++) {
            float x, z;
            mesh_circle_point(slice, slices, &x, &z);
            float normal[3] = {(float)sin(latitude) * x, (float)cos(latitude), (float)sin(latitude) * z};
            float position[3];
            glm_vec3_scale(normal, radius, position);
            mesh_push_vertex(m, position, normal);
        }
    }
    uint32_t south = mesh_push_vertex(m, (const float[3]){0, -radius, 0}, (const float[3]){0, -1, 0});
    for (int slice = 0; slice < slices; slice++) {
        mesh_push_triangle(m, north, mesh_grid_vertex(first_ring, 0, slice, slices),
                           mesh_grid_vertex(first_ring, 0, slice + 1, slices));
        for (int ring = 0; ring + 1 < rings; ring++) {
            mesh_push_quad(m, mesh_grid_vertex(first_ring, ring + 1, slice, slices),
                           mesh_grid_vertex(first_ring, ring + 1, slice + 1, slices),
                           mesh_grid_vertex(first_ring, ring, slice + 1, slices),
                           mesh_grid_vertex(first_ring, ring, slice, slices));
        }
        mesh_push_triangle(m, south, mesh_grid_vertex(first_ring, rings - 1, slice + 1, slices),
                           mesh_grid_vertex(first_ring, rings - 1, slice, slices));
    }
    return mesh_sanitize(m, "sphere");
}

bool mesh_make_torus(mesh *m, float major_radius, float minor_radius, int segments) {
    *m = (mesh){0};
    if (!mesh_check_size(m, "torus", "major_radius", major_radius) ||
        !mesh_check_size(m, "torus", "minor_radius", minor_radius) || !mesh_check_segments(m, "torus", &segments)) {
        return false;
    }
    if (minor_radius >= major_radius) {
        /* The tube would cross the Y axis and intersect itself. */
        return mesh_fail(m, "torus", "minor_radius (%g) must be smaller than major_radius (%g)", minor_radius,
                         major_radius);
    }
    int rings = segments;
    int sides = segments / 2 < 3 ? 3 : segments / 2;
    if (!mesh_alloc(m, "torus", (size_t)rings * sides, 6 * (size_t)rings * sides))
        return false;
    for (int ring = 0; ring < rings; ring++) {
        float ring_x, ring_z;
        mesh_circle_point(ring, rings, &ring_x, &ring_z);
        for (int side = 0; side < sides; side++) {
            /* Around the tube: outwards from the Y axis at side 0, then up. */
            float out, up;
            mesh_circle_point(side, sides, &up, &out);
            float normal[3] = {out * ring_x, up, out * ring_z};
            float position[3] = {major_radius * ring_x + minor_radius * normal[0], minor_radius * normal[1],
                                 major_radius * ring_z + minor_radius * normal[2]};
            mesh_push_vertex(m, position, normal);
        }
    }
    for (int ring = 0; ring < rings; ring++) {
        int next_ring = (ring + 1) % rings;
        for (int side = 0; side < sides; side++) {
            mesh_push_quad(m, mesh_grid_vertex(0, ring, side, sides), mesh_grid_vertex(0, next_ring, side, sides),
                           mesh_grid_vertex(0, next_ring, side + 1, sides),
                           mesh_grid_vertex(0, ring, side + 1, sides));
        }
    }
    return mesh_sanitize(m, "torus");
}

/* A flat disc at height y facing away from the cylinder's centre: a fan
 * around its own centre vertex, with its own normals so the rim stays sharp. */
static void mesh_push_cap(mesh *m, float radius, float y, int segments) {
    const float normal[3] = {0, y > 0 ? 1.0f : -1.0f, 0};
    uint32_t centre = mesh_push_vertex(m, (const float[3]){0, y, 0}, normal);
    uint32_t first = m->vertex_count;
    for (int i = 0; i < segments; i++) {
        float x, z;
        mesh_circle_point(i, segments, &x, &z);
        mesh_push_vertex(m, (const float[3]){radius * x, y, radius * z}, normal);
    }
    for (int i = 0; i < segments; i++) {
        uint32_t a = mesh_grid_vertex(first, 0, i, segments);
        uint32_t b = mesh_grid_vertex(first, 0, i + 1, segments);
        if (y > 0) {
            mesh_push_triangle(m, centre, a, b);
        } else {
            mesh_push_triangle(m, centre, b, a);
        }
    }
}

bool mesh_make_cylinder(mesh *m, float radius, float height, int segments) {
    *m = (mesh){0};
    if (!mesh_check_size(m, "cylinder", "radius", radius) || !mesh_check_size(m, "cylinder", "height", height) ||
        !mesh_check_segments(m, "cylinder", &segments)) {
        return false;
    }
    if (!mesh_alloc(m, "cylinder", 4 * (size_t)segments + 2, 12 * (size_t)segments))
        return false;
    float top = height / 2;
    /* The side: one row of (top, bottom) pairs with horizontal normals. */
    for (int i = 0; i < segments; i++) {
        float normal[3] = {0, 0, 0};
        mesh_circle_point(i, segments, &normal[0], &normal[2]);
        mesh_push_vertex(m, (const float[3]){radius * normal[0], top, radius * normal[2]}, normal);
        mesh_push_vertex(m, (const float[3]){radius * normal[0], -top, radius * normal[2]}, normal);
    }
    for (int i = 0; i < segments; i++) {
        uint32_t top_here = 2 * (uint32_t)i, top_next = 2 * (uint32_t)((i + 1) % segments);
        mesh_push_quad(m, top_here + 1, top_next + 1, top_next, top_here);
    }
    mesh_push_cap(m, radius, top, segments);
    mesh_push_cap(m, radius, -top, segments);
    return mesh_sanitize(m, "cylinder");
}

void mesh_reflect_x(mesh *m) {
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        m->vertices[v].position[0] = -m->vertices[v].position[0];
        m->vertices[v].normal[0] = -m->vertices[v].normal[0];
    }
    for (uint32_t i = 0; i + 2 < m->index_count; i += 3) {
        uint32_t second = m->indices[i + 1];
        m->indices[i + 1] = m->indices[i + 2];
        m->indices[i + 2] = second;
    }
    float min_x = m->bounds_min[0];
    m->bounds_min[0] = -m->bounds_max[0];
    m->bounds_max[0] = -min_x;
}

/* Bounds over the finite positions only (zero when there is none). */
static void mesh_measure_bounds(const mesh *m, float min[3], float max[3]) {
    bool any = false;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *p = m->vertices[v].position;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
            continue;
        for (int k = 0; k < 3; k++) {
            min[k] = any ? fminf(min[k], p[k]) : p[k];
            max[k] = any ? fmaxf(max[k], p[k]) : p[k];
        }
        any = true;
    }
    if (!any) {
        glm_vec3_zero(min);
        glm_vec3_zero(max);
    }
}

/* In double: float extents can overflow when squared. */
static double mesh_diagonal(const float min[3], const float max[3]) {
    double sum = 0;
    for (int k = 0; k < 3; k++)
        sum += ((double)max[k] - min[k]) * ((double)max[k] - min[k]);
    return sqrt(sum);
}

/* (b - a) x (c - a) in double: the differences of floats are exact there, so
 * a collinear triangle really gives zero, and twice the area is its length. */
static void mesh_triangle_cross(const mesh *m, const uint32_t corner[3], double cross[3]) {
    const float *a = m->vertices[corner[0]].position;
    const float *b = m->vertices[corner[1]].position;
    const float *c = m->vertices[corner[2]].position;
    double ab[3], ac[3];
    for (int k = 0; k < 3; k++) {
        ab[k] = (double)b[k] - a[k];
        ac[k] = (double)c[k] - a[k];
    }
    cross[0] = ab[1] * ac[2] - ab[2] * ac[1];
    cross[1] = ab[2] * ac[0] - ab[0] * ac[2];
    cross[2] = ab[0] * ac[1] - ab[1] * ac[0];
}

typedef struct mesh_weld_key {
    int64_t cell[3];
    uint32_t vertex;
} mesh_weld_key;

static int mesh_compare_weld_keys(const void *a, const void *b) {
    const mesh_weld_key *x = a, *y = b;
    for (int k = 0; k < 3; k++) {
        if (x->cell[k] != y->cell[k])
            return x->cell[k] < y->cell[k] ? -1 : 1;
    }
    /* Ties by vertex index: each welded position is its lowest vertex's. */
    return (x->vertex > y->vertex) - (x->vertex < y->vertex);
}

/* mesh_weld without the report, for callers that name the mesh themselves. */
static bool mesh_build_topology(const mesh *m, mesh_topology *t) {
    *t = (mesh_topology){0};
    if (m->vertex_count == 0)
        return true;
    float min[3], max[3];
    mesh_measure_bounds(m, min, max);
    double diagonal = mesh_diagonal(min, max);
    double cell = diagonal > 0 ? diagonal * MESH_WELD_TOLERANCE : 1.0;

    mesh_weld_key *keys = malloc(m->vertex_count * sizeof *keys);
    t->position_of_vertex = malloc(m->vertex_count * sizeof *t->position_of_vertex);
    t->positions = malloc(m->vertex_count * sizeof *t->positions);
    if (!keys || !t->position_of_vertex || !t->positions) {
        free(keys);
        mesh_topology_free(t);
        return false;
    }
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *p = m->vertices[v].position;
        keys[v].vertex = v;
        if (isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2])) {
            /* Within the bounds, so at most 1/MESH_WELD_TOLERANCE cells. */
            for (int k = 0; k < 3; k++)
                keys[v].cell[k] = llround(((double)p[k] - min[k]) / cell);
        } else {
            /* A cell of its own, past every real one: it never welds. */
            keys[v].cell[0] = INT64_MAX;
            keys[v].cell[1] = v;
            keys[v].cell[2] = 0;
        }
    }
    qsort(keys, m->vertex_count, sizeof *keys, mesh_compare_weld_keys);
    for (uint32_t i = 0; i < m->vertex_count; i++) {
        bool same_cell = i > 0 && memcmp(keys[i].cell, keys[i - 1].cell, sizeof keys[i].cell) == 0;
        if (!same_cell) {
            memcpy(t->positions[t->position_count], m->vertices[keys[i].vertex].position, sizeof t->positions[0]);
            t->position_count++;
        }
        t->position_of_vertex[keys[i].vertex] = t->position_count - 1;
    }
    free(keys);
    return true;
}

bool mesh_weld(const mesh *m, mesh_topology *t) {
    if (mesh_build_topology(m, t))
        return true;
    return mesh_fail(NULL, "mesh_weld", "out of memory");
}

typedef struct mesh_corner_key {
    uint64_t edge;   /* smaller welded id << 32 | larger: both directions match */
    uint32_t corner; /* index into m->indices: the edge runs from it to the next corner */
} mesh_corner_key;

static int mesh_compare_corner_keys(const void *a, const void *b) {
    const mesh_corner_key *x = a, *y = b;
    if (x->edge != y->edge)
        return (x->edge > y->edge) - (x->edge < y->edge);
    return (x->corner > y->corner) - (x->corner < y->corner);
}

static uint32_t mesh_next_corner(uint32_t corner) { return corner % 3 == 2 ? corner - 2 : corner + 1; }

bool mesh_edges_build(const mesh *m, const mesh_topology *t, mesh_edges *e) {
    memset(e, 0, sizeof *e);
    uint32_t corner_count = m->index_count / 3 * 3;
    mesh_corner_key *keys = malloc((corner_count ? corner_count : 1) * sizeof *keys);
    e->uses = malloc((corner_count ? corner_count : 1) * sizeof *e->uses);
    e->edges = malloc((corner_count ? corner_count : 1) * sizeof *e->edges);
    if (!keys || !e->uses || !e->edges) {
        free(keys);
        mesh_edges_free(e);
        return mesh_fail(NULL, "mesh_edges_build", "out of memory");
    }
    for (uint32_t i = 0; i < corner_count; i++) {
        uint64_t a = t->position_of_vertex[m->indices[i]];
        uint64_t b = t->position_of_vertex[m->indices[mesh_next_corner(i)]];
        keys[i] = (mesh_corner_key){a < b ? a << 32 | b : b << 32 | a, i};
    }
    qsort(keys, corner_count, sizeof *keys, mesh_compare_corner_keys);
    e->closed = corner_count > 0;
    for (uint32_t i = 0; i < corner_count;) {
        uint32_t uses = 1;
        while (i + uses < corner_count && keys[i + uses].edge == keys[i].edge)
            uses++;
        mesh_edge *edge = &e->edges[e->edge_count++];
        uint32_t first = keys[i].corner;
        edge->a = m->indices[first];
        edge->b = m->indices[mesh_next_corner(first)];
        edge->first_use = i;
        edge->use_count = uses;
        int direction_sum = 0;
        for (uint32_t k = 0; k < uses; k++) {
            uint32_t corner = keys[i + k].corner;
            bool same = t->position_of_vertex[m->indices[corner]] == t->position_of_vertex[edge->a];
            e->uses[i + k] = (mesh_edge_use){corner, same ? 1 : -1};
            direction_sum += same ? 1 : -1;
        }
        if (uses != 2 || direction_sum != 0)
            e->closed = false;
        i += uses;
    }
    free(keys);
    return true;
}

void mesh_edges_free(mesh_edges *e) {
    free(e->edges);
    free(e->uses);
    memset(e, 0, sizeof *e);
}

mesh_edge_counts mesh_topology_count_edges(const mesh *m, const mesh_topology *t) {
    mesh_edge_counts counts = {0, 0, 0};
    mesh_edges e;
    if (!mesh_edges_build(m, t, &e))
        return counts;
    for (uint32_t i = 0; i < e.edge_count; i++) {
        if (e.edges[i].use_count == 1) {
            counts.boundary++;
        } else if (e.edges[i].use_count == 2) {
            counts.manifold++;
        } else {
            counts.non_manifold++;
        }
    }
    mesh_edges_free(&e);
    return counts;
}

bool mesh_adjacency_indices(const mesh *m, const mesh_edges *e, uint32_t *out) {
    if (!e->closed)
        return false;
    for (uint32_t i = 0; i < e->edge_count; i++) {
        const mesh_edge_use *u = &e->uses[e->edges[i].first_use];
        for (int k = 0; k < 2; k++) {
            /* Triangle t's edge runs from corner c to the next; after the
             * corner c, the vertex of the other triangle off the edge. */
            uint32_t t = u[k].corner / 3, c = u[k].corner % 3, other = u[1 - k].corner;
            out[t * 6 + c * 2] = m->indices[u[k].corner];
            out[t * 6 + c * 2 + 1] = m->indices[mesh_next_corner(mesh_next_corner(other))];
        }
    }
    return true;
}

typedef bool (*mesh_triangle_test)(const mesh *m, const uint32_t corner[3], const void *context);

/* Removes the triangles the test picks, keeping the order of the others;
 * returns how many went. */
static uint32_t mesh_remove_triangles(mesh *m, mesh_triangle_test is_bad, const void *context) {
    uint32_t kept = 0;
    for (uint32_t i = 0; i < m->index_count; i += 3) {
        if (is_bad(m, &m->indices[i], context))
            continue;
        for (int k = 0; k < 3; k++)
            m->indices[kept + k] = m->indices[i + k];
        kept += 3;
    }
    uint32_t removed = (m->index_count - kept) / 3;
    m->index_count = kept;
    return removed;
}

/* Out-of-range indices count as non-finite: there is no position at all. */
static bool mesh_triangle_non_finite(const mesh *m, const uint32_t corner[3], const void *unused) {
    (void)unused;
    for (int k = 0; k < 3; k++) {
        if (corner[k] >= m->vertex_count)
            return true;
        const float *p = m->vertices[corner[k]].position;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
            return true;
    }
    return false;
}

typedef struct mesh_degeneracy {
    const mesh_topology *topology;
    double min_cross_length; /* |(b - a) x (c - a)| at or below it is degenerate */
} mesh_degeneracy;

static bool mesh_triangle_degenerate(const mesh *m, const uint32_t corner[3], const void *context) {
    const mesh_degeneracy *d = context;
    const uint32_t *welded = d->topology->position_of_vertex;
    uint32_t a = welded[corner[0]], b = welded[corner[1]], c = welded[corner[2]];
    if (a == b || b == c || c == a)
        return true;
    double cross[3];
    mesh_triangle_cross(m, corner, cross);
    return sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]) <= d->min_cross_length;
}

static bool mesh_normal_usable(const float n[3]) {
    return isfinite(n[0]) && isfinite(n[1]) && isfinite(n[2]) && n[0] * n[0] + n[1] * n[1] + n[2] * n[2] > 1e-12f;
}

/* Vertices without a usable normal (missing, zero or non-finite) get the
 * area-weighted average of the faces around their welded position: a smooth
 * normal, as assimp would have generated. */
static bool mesh_repair_normals(mesh *m, const mesh_topology *t) {
    bool any_broken = false;
    for (uint32_t v = 0; v < m->vertex_count && !any_broken; v++) {
        any_broken = !mesh_normal_usable(m->vertices[v].normal);
    }
    if (!any_broken)
        return true;
    double(*sums)[3] = calloc(t->position_count, sizeof *sums);
    if (!sums)
        return false;
    for (uint32_t i = 0; i < m->index_count; i += 3) {
        double cross[3];
        mesh_triangle_cross(m, &m->indices[i], cross);
        for (int k = 0; k < 3; k++) {
            double *sum = sums[t->position_of_vertex[m->indices[i + k]]];
            for (int j = 0; j < 3; j++)
                sum[j] += cross[j];
        }
    }
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        float *n = m->vertices[v].normal;
        if (mesh_normal_usable(n))
            continue;
        const double *sum = sums[t->position_of_vertex[v]];
        double length = sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
        /* Faces that cancel out (a two-sided sheet) leave no direction. */
        if (length > 0) {
            for (int j = 0; j < 3; j++)
                n[j] = (float)(sum[j] / length);
        } else {
            glm_vec3_copy((vec3){0, 1, 0}, n);
        }
    }
    free(sums);
    return true;
}

/* Drops the vertices no triangle uses, keeping the order of the others, and
 * sets the bounds from those left: a stray vertex cannot widen them. */
static bool mesh_remove_unused_vertices(mesh *m, const char *name) {
    if (m->vertex_count > 0) {
        uint32_t *new_index = malloc(m->vertex_count * sizeof *new_index);
        if (!new_index)
            return mesh_fail(m, name, "out of memory");
        for (uint32_t v = 0; v < m->vertex_count; v++)
            new_index[v] = UINT32_MAX;
        for (uint32_t i = 0; i < m->index_count; i++)
            new_index[m->indices[i]] = 0;
        uint32_t kept = 0;
        for (uint32_t v = 0; v < m->vertex_count; v++) {
            if (new_index[v] == UINT32_MAX)
                continue;
            m->vertices[kept] = m->vertices[v];
            new_index[v] = kept++;
        }
        for (uint32_t i = 0; i < m->index_count; i++)
            m->indices[i] = new_index[m->indices[i]];
        m->vertex_count = kept;
        free(new_index);
    }
    mesh_measure_bounds(m, m->bounds_min, m->bounds_max);
    return true;
}

bool mesh_sanitize(mesh *m, const char *name) {
    mesh_removed removed = {0};
    if (!mesh_sanitize_quietly(m, name, &removed))
        return false;
    if (removed.degenerate + removed.non_finite > 0) {
        fprintf(stderr, "warning: %s: removed %u degenerate and %u non-finite triangles\n", name, removed.degenerate,
                removed.non_finite);
    }
    return true;
}

bool mesh_sanitize_quietly(mesh *m, const char *name, mesh_removed *removed) {
    m->index_count -= m->index_count % 3;
    uint32_t non_finite = mesh_remove_triangles(m, mesh_triangle_non_finite, NULL);
    if (!mesh_remove_unused_vertices(m, name))
        return false;

    mesh_topology topology;
    if (!mesh_build_topology(m, &topology))
        return mesh_fail(m, name, "out of memory");
    /* The cross product of two edges as short as the weld tolerance: a face
     * smaller than that has no usable normal. */
    double tolerance = MESH_WELD_TOLERANCE * mesh_diagonal(m->bounds_min, m->bounds_max);
    mesh_degeneracy degeneracy = {&topology, tolerance * tolerance};
    uint32_t degenerate = mesh_remove_triangles(m, mesh_triangle_degenerate, &degeneracy);
    bool repaired = mesh_repair_normals(m, &topology);
    mesh_topology_free(&topology);
    if (!repaired)
        return mesh_fail(m, name, "out of memory");

    if (m->index_count == 0) {
        if (degenerate + non_finite == 0)
            return mesh_fail(m, name, "no triangles");
        return mesh_fail(m, name, "no triangles left after removing %u degenerate and %u non-finite", degenerate,
                         non_finite);
    }
    if (!mesh_remove_unused_vertices(m, name))
        return false;
    removed->degenerate += degenerate;
    removed->non_finite += non_finite;
    return true;
}

static bool mesh_same_position(const mesh *m, uint32_t corner_a, uint32_t corner_b) {
    return memcmp(m->vertices[m->indices[corner_a]].position, m->vertices[m->indices[corner_b]].position,
                  sizeof m->vertices[0].position) == 0;
}

bool mesh_edge_uses_meet(const mesh *m, const mesh_edge_use *u, const mesh_edge_use *v) {
    uint32_t u_end = mesh_next_corner(u->corner), v_end = mesh_next_corner(v->corner);
    if (u->direction == v->direction)
        return mesh_same_position(m, u->corner, v->corner) && mesh_same_position(m, u_end, v_end);
    return mesh_same_position(m, u->corner, v_end) && mesh_same_position(m, u_end, v->corner);
}

bool mesh_edges_build_welded(const mesh *m, mesh_edges *e) {
    mesh_topology t;
    if (!mesh_weld(m, &t))
        return false;
    bool ok = mesh_edges_build(m, &t, e);
    mesh_topology_free(&t);
    /* Closed only where every edge's two triangles meet at one position
     * (see the header). */
    for (uint32_t i = 0; ok && e->closed && i < e->edge_count; i++) {
        const mesh_edge_use *u = &e->uses[e->edges[i].first_use];
        e->closed = mesh_edge_uses_meet(m, &u[0], &u[1]);
    }
    return ok;
}
