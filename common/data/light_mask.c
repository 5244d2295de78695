#include "light_mask.h"

#include <math.h>
#include <string.h>

#include "frustum.h"

/* Clip w at or below this fraction of a point's clip coordinates: the
 * point is at the layer's centre of projection, where it sees everything. */
#define LIGHT_MASK_MIN_W FRUSTUM_FLOAT_TOLERANCE
/* The clip planes of a layer: its four sides and w >= 0. */
#define LIGHT_MASK_CLIP_PLANES 5
/* A box face clipped by the five planes has at most 4 + 5 corners. */
#define LIGHT_MASK_POLYGON_MAX (4 + LIGHT_MASK_CLIP_PLANES)

/* The six faces of a body by their corners' numbers (bit k: the high end
 * of axis k), in order around each. */
static const int light_mask_faces[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                           {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};

static void light_mask_clip(const mat4 layer, const float p[3], vec4 out) {
    glm_mat4_mulv((vec4 *)layer, (vec4){p[0], p[1], p[2], 1}, out);
}

static bool light_mask_at_centre(const vec4 c) {
    return c[3] <= LIGHT_MASK_MIN_W * (fabsf(c[0]) + fabsf(c[1]) + fabsf(c[2]));
}

/* Grows the part by one point in front of the centre. */
static void light_mask_part_add(light_mask_part *part, const vec4 c) {
    for (int k = 0; k < 2; k++) {
        part->lo[k] = fminf(part->lo[k], c[k] / c[3]);
        part->hi[k] = fmaxf(part->hi[k], c[k] / c[3]);
    }
    part->nearest = fminf(part->nearest, c[2] / c[3]);
    part->deepest = fmaxf(part->deepest, c[2] / c[3]);
}

/* The layer's sides at `side` (1: the NDC square) and w >= 0, as
 * world-homogeneous planes (plane . (p, 1) >= 0 inside). */
static void light_mask_planes(const mat4 layer, float side, vec4 planes[LIGHT_MASK_CLIP_PLANES]) {
    for (int j = 0; j < 4; j++) {
        float w = layer[j][3], x = layer[j][0], y = layer[j][1];
        planes[0][j] = side * w - x;
        planes[1][j] = side * w + x;
        planes[2][j] = side * w - y;
        planes[3][j] = side * w + y;
        planes[4][j] = w;
    }
}

/* Sutherland-Hodgman: the polygon's part inside one plane. */
static int light_mask_clip_polygon(const float (*in)[3], int n, const vec4 plane, float (*out)[3]) {
    int m = 0;
    for (int i = 0; i < n; i++) {
        const float *a = in[i], *b = in[(i + 1) % n];
        float da = glm_vec3_dot((float *)plane, (float *)a) + plane[3];
        float db = glm_vec3_dot((float *)plane, (float *)b) + plane[3];
        if (da >= 0)
            glm_vec3_copy((float *)a, out[m++]);
        if ((da >= 0) != (db >= 0))
            glm_vec3_lerp((float *)a, (float *)b, da / (da - db), out[m++]);
    }
    return m;
}

light_mask_part light_mask_body_part(const mat4 layer, float widen, const float corners[8][3]) {
    light_mask_part part = {.kind = LIGHT_MASK_PART_SOME,
                            .lo = {INFINITY, INFINITY},
                            .hi = {-INFINITY, -INFINITY},
                            .nearest = INFINITY,
                            .deepest = -INFINITY};
    vec4 clip[8];
    bool in_front = true;
    float side = 1 + widen + FRUSTUM_CLIP_TOLERANCE;
    int outside[LIGHT_MASK_CLIP_PLANES] = {0};
    for (int c = 0; c < 8; c++) {
        float *q = clip[c];
        light_mask_clip(layer, corners[c], q);
        in_front = in_front && !light_mask_at_centre(q);
        outside[0] += side * q[3] - q[0] < 0;
        outside[1] += side * q[3] + q[0] < 0;
        outside[2] += side * q[3] - q[1] < 0;
        outside[3] += side * q[3] + q[1] < 0;
        outside[4] += q[3] < 0;
    }
    /* Every corner beyond one plane: so is the body. */
    for (int p = 0; p < LIGHT_MASK_CLIP_PLANES; p++)
        if (outside[p] == 8) {
            part.kind = LIGHT_MASK_PART_NONE;
            return part;
        }
    if (in_front) {
        /* A convex body in front of the centre projects into the
         * rectangle of its corners, its depths between theirs. */
        for (int c = 0; c < 8; c++)
            light_mask_part_add(&part, clip[c]);
    } else {
        vec4 planes[LIGHT_MASK_CLIP_PLANES];
        light_mask_planes(layer, side, planes);
        for (int f = 0; f < 6; f++) {
            float a[LIGHT_MASK_POLYGON_MAX][3], b[LIGHT_MASK_POLYGON_MAX][3];
            int n = 4;
            for (int i = 0; i < 4; i++)
                glm_vec3_copy((float *)corners[light_mask_faces[f][i]], a[i]);
            for (int p = 0; p < LIGHT_MASK_CLIP_PLANES && n > 0; p++) {
                n = light_mask_clip_polygon((const float(*)[3])a, n, planes[p], b);
                memcpy(a, b, (size_t)n * sizeof *a);
            }
            for (int i = 0; i < n; i++) {
                vec4 c;
                light_mask_clip(layer, a[i], c);
                if (light_mask_at_centre(c)) {
                    part.kind = LIGHT_MASK_PART_WHOLE;
                    return part;
                }
                light_mask_part_add(&part, c);
            }
        }
    }
    if (!(part.lo[0] <= side && part.hi[0] >= -side && part.lo[1] <= side && part.hi[1] >= -side))
        part.kind = LIGHT_MASK_PART_NONE;
    return part;
}

static const light_mask_seen light_mask_nothing = LIGHT_MASK_SEEN_NOTHING;

static void light_mask_seen_grow(light_mask_seen *into, const light_mask_seen *by) {
    glm_vec3_minv(into->lo, (float *)by->lo, into->lo);
    glm_vec3_maxv(into->hi, (float *)by->hi, into->hi);
}

void light_mask_start(light_mask *m, const mat4 layer, float grow, bool any_depth, bool keeps_seen) {
    glm_mat4_copy((vec4 *)layer, m->layer);
    m->grow = grow;
    m->any_depth = any_depth;
    m->whole = false;
    m->empty = true;
    m->keeps_seen = keeps_seen;
    for (int i = 0; i < LIGHT_MASK_CELLS * LIGHT_MASK_CELLS; i++) {
        m->deepest[i] = -INFINITY;
        if (keeps_seen)
            m->seen[i] = light_mask_nothing;
    }
}

/* The cells from NDC lo to hi on one axis, clamped to the grid; false
 * when none. */
static bool light_mask_cells(float lo, float hi, int *first, int *last) {
    float scale = 0.5f * LIGHT_MASK_CELLS;
    float a = floorf((lo + 1) * scale), b = floorf((hi + 1) * scale);
    if (b < 0 || a > LIGHT_MASK_CELLS - 1 || !(a <= b))
        return false;
    *first = a < 0 ? 0 : (int)a;
    *last = b > LIGHT_MASK_CELLS - 1 ? LIGHT_MASK_CELLS - 1 : (int)b;
    return true;
}

void light_mask_add(light_mask *m, const float corners[8][3], const light_mask_seen *seen) {
    if (m->whole)
        return;
    light_mask_part part = light_mask_body_part(m->layer, m->grow, corners);
    if (part.kind == LIGHT_MASK_PART_WHOLE)
        m->whole = true;
    if (part.kind != LIGHT_MASK_PART_SOME)
        return;
    int x0, x1, y0, y1;
    if (!light_mask_cells(part.lo[0] - m->grow, part.hi[0] + m->grow, &x0, &x1) ||
        !light_mask_cells(part.lo[1] - m->grow, part.hi[1] + m->grow, &y0, &y1))
        return;
    float depth = m->any_depth ? INFINITY : part.deepest;
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) {
            int cell = y * LIGHT_MASK_CELLS + x;
            m->deepest[cell] = fmaxf(m->deepest[cell], depth);
            if (m->keeps_seen)
                light_mask_seen_grow(&m->seen[cell], seen);
        }
    m->empty = false;
}

/* light_mask_box_read, and with `out` the union of the seen bounds of
 * every cell that reads the box. */
static bool light_mask_box(const light_mask *m, const vec3 lo, const vec3 hi, light_mask_seen *out) {
    static const light_mask_seen everything = {{-INFINITY, -INFINITY, -INFINITY}, {INFINITY, INFINITY, INFINITY}};
    if (m->whole) {
        if (out)
            *out = everything;
        return true;
    }
    if (m->empty)
        return false;
    float corners[8][3];
    frustum_box_corners(lo, hi, corners);
    light_mask_part part = light_mask_body_part(m->layer, 0, (const float(*)[3])corners);
    if (part.kind != LIGHT_MASK_PART_SOME) {
        if (part.kind == LIGHT_MASK_PART_WHOLE && out)
            *out = everything;
        return part.kind == LIGHT_MASK_PART_WHOLE;
    }
    int x0, x1, y0, y1;
    if (!light_mask_cells(part.lo[0], part.hi[0], &x0, &x1) || !light_mask_cells(part.lo[1], part.hi[1], &y0, &y1))
        return false;
    float nearest = part.nearest - LIGHT_MASK_DEPTH_TOLERANCE;
    bool read = false;
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) {
            int cell = y * LIGHT_MASK_CELLS + x;
            if (m->deepest[cell] < nearest)
                continue;
            if (!out)
                return true;
            read = true;
            light_mask_seen_grow(out, &m->seen[cell]);
        }
    return read;
}

bool light_mask_box_read(const light_mask *m, const vec3 lo, const vec3 hi) {
    return light_mask_box(m, lo, hi, NULL);
}

bool light_mask_box_seen(const light_mask *m, const vec3 lo, const vec3 hi, light_mask_seen *out) {
    return light_mask_box(m, lo, hi, out);
}

/* The light-view bounds of every corner of the bodies. */
static void light_mask_view_bounds(const mat4 view, const float (*bodies)[8][3], int count, vec3 lo, vec3 hi) {
    glm_vec3_fill(lo, INFINITY);
    glm_vec3_fill(hi, -INFINITY);
    for (int b = 0; b < count; b++)
        for (int c = 0; c < 8; c++) {
            vec3 p;
            glm_mat4_mulv3((vec4 *)view, (float *)bodies[b][c], 1, p);
            glm_vec3_minv(lo, p, lo);
            glm_vec3_maxv(hi, p, hi);
        }
}

int light_mask_layers(const scene_light *light, const float (*bodies)[8][3], int count,
                      mat4 layers[LIGHT_MASK_MAX_LAYERS]) {
    if (count == 0)
        return 0;
    if (light->type == SCENE_LIGHT_DIRECTIONAL) {
        mat4 view, projection;
        vec3 lo, hi;
        frustum_look_along(GLM_VEC3_ZERO, (float *)light->direction, view);
        light_mask_view_bounds(view, bodies, count, lo, hi);
        /* A flat extent keeps a width: the projection stays invertible. */
        float size = fmaxf(fmaxf(hi[0] - lo[0], hi[1] - lo[1]), hi[2] - lo[2]), pad = FRUSTUM_BOX_TOLERANCE * size;
        pad = pad > 0 ? pad : 1;
        glm_ortho(lo[0] - pad, hi[0] + pad, lo[1] - pad, hi[1] + pad, -hi[2] - pad, -lo[2] + pad, projection);
        glm_mat4_mul(projection, view, layers[0]);
        return 1;
    }
    float farthest = 0;
    for (int b = 0; b < count; b++)
        for (int c = 0; c < 8; c++)
            farthest = fmaxf(farthest, glm_vec3_distance((float *)light->position, (float *)bodies[b][c]));
    float near_plane = fmaxf(LIGHT_MASK_NEAR_SHARE * farthest, FRUSTUM_FLOAT_TOLERANCE);
    mat4 projection;
    glm_perspective(GLM_PI_2f, 1, near_plane, fmaxf(farthest, 2 * near_plane), projection);
    for (int face = 0; face < LIGHT_MASK_MAX_LAYERS; face++) {
        vec3 axis = GLM_VEC3_ZERO_INIT;
        axis[face / 2] = face & 1 ? 1.0f : -1.0f;
        mat4 view;
        frustum_look_along(light->position, axis, view);
        glm_mat4_mul(projection, view, layers[face]);
    }
    return LIGHT_MASK_MAX_LAYERS;
}
