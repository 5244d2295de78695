#include "bvh.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* 1 + 2 gamma(3), gamma(n) = n u / (1 - n u) with u = FLT_EPSILON / 2
 * (Ize): a box's far distance widened by the error of three rounded
 * operations. */
#define BVH_FAR_WIDENING (1.0f + 3.0f * FLT_EPSILON / (1.0f - 1.5f * FLT_EPSILON))
/* A direction's zero component is taken as this, of its sign, so that its
 * reciprocal is finite and a box's slab test never multiplies 0 by it. */
#define BVH_TINY_DIRECTION 1e-30f

/* The build's view of one triangle. */
typedef struct bvh_triangle {
    float vertices[3][3];
    float lo[3], hi[3], centroid[3];
    bvh_record source; /* its object and index there */
} bvh_triangle;

/* A triangle's centroid along the median split's axis. */
typedef struct bvh_key {
    float centroid;
    int triangle;
} bvh_key;

typedef struct bvh_builder {
    bvh_triangle *triangles;
    int *order;    /* triangle indices, partitioned in place */
    bvh_key *keys; /* the median split's sort */
    bvh *out;
} bvh_builder;

typedef struct bvh_box {
    float lo[3], hi[3];
} bvh_box;

static bvh_box bvh_box_empty(void) {
    return (bvh_box){{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
}

static void bvh_box_grow(bvh_box *b, const float lo[3], const float hi[3]) {
    for (int k = 0; k < 3; k++) {
        b->lo[k] = fminf(b->lo[k], lo[k]);
        b->hi[k] = fmaxf(b->hi[k], hi[k]);
    }
}

/* Half the surface area (the heuristic compares, so the factor 2 goes). */
static float bvh_box_area(const bvh_box *b) {
    float d[3];
    for (int k = 0; k < 3; k++)
        d[k] = fmaxf(b->hi[k] - b->lo[k], 0.0f);
    return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
}

/* The split of order[begin..end) with the least SAH cost over BVH_BINS
 * bins of the centroids along each axis: its axis, and the bin its right
 * side starts at; false where every centroid is in one bin on every axis. */
static bool bvh_best_split(const bvh_builder *b, int begin, int end, const bvh_box *centroids, int *axis_out,
                           int *bin_out) {
    float best = INFINITY;
    for (int axis = 0; axis < 3; axis++) {
        float lo = centroids->lo[axis], extent = centroids->hi[axis] - lo;
        if (!(extent > 0))
            continue;
        bvh_box bins[BVH_BINS];
        int counts[BVH_BINS] = {0};
        for (int i = 0; i < BVH_BINS; i++)
            bins[i] = bvh_box_empty();
        for (int i = begin; i < end; i++) {
            const bvh_triangle *t = &b->triangles[b->order[i]];
            int bin = (int)((t->centroid[axis] - lo) * (BVH_BINS / extent));
            bin = bin < BVH_BINS ? bin : BVH_BINS - 1;
            counts[bin]++;
            bvh_box_grow(&bins[bin], t->lo, t->hi);
        }
        float right_area[BVH_BINS];
        int right_count[BVH_BINS];
        bvh_box right = bvh_box_empty();
        int count = 0;
        for (int i = BVH_BINS - 1; i > 0; i--) {
            bvh_box_grow(&right, bins[i].lo, bins[i].hi);
            count += counts[i];
            right_area[i] = bvh_box_area(&right);
            right_count[i] = count;
        }
        bvh_box left = bvh_box_empty();
        count = 0;
        for (int i = 1; i < BVH_BINS; i++) {
            bvh_box_grow(&left, bins[i - 1].lo, bins[i - 1].hi);
            count += counts[i - 1];
            if (count == 0 || right_count[i] == 0)
                continue;
            float cost = bvh_box_area(&left) * (float)count + right_area[i] * (float)right_count[i];
            if (cost < best) {
                best = cost;
                *axis_out = axis;
                *bin_out = i;
            }
        }
    }
    return best < INFINITY;
}

/* By centroid, ties by index, so that the build is the same on every run. */
static int bvh_compare_keys(const void *a, const void *b) {
    const bvh_key *i = a, *j = b;
    return i->centroid < j->centroid   ? -1
           : i->centroid > j->centroid ? 1
                                       : (i->triangle > j->triangle) - (i->triangle < j->triangle);
}

/* order[begin..end) sorted by centroid along `axis`. */
static void bvh_sort(bvh_builder *b, int begin, int end, int axis) {
    for (int i = begin; i < end; i++)
        b->keys[i - begin] = (bvh_key){b->triangles[b->order[i]].centroid[axis], b->order[i]};
    qsort(b->keys, (size_t)(end - begin), sizeof *b->keys, bvh_compare_keys);
    for (int i = begin; i < end; i++)
        b->order[i] = b->keys[i - begin].triangle;
}

/* Node `node` over order[begin..end) and its subtree after it; returns
 * the index after the subtree. */
static int bvh_build_node(bvh_builder *b, int node, int begin, int end, int depth) {
    bvh_box box = bvh_box_empty(), centroids = bvh_box_empty();
    for (int i = begin; i < end; i++) {
        const bvh_triangle *t = &b->triangles[b->order[i]];
        bvh_box_grow(&box, t->lo, t->hi);
        bvh_box_grow(&centroids, t->centroid, t->centroid);
    }
    float(*n)[4] = b->out->nodes[node];
    memcpy(n[0], box.lo, sizeof box.lo);
    memcpy(n[1], box.hi, sizeof box.hi);
    b->out->depth = depth > b->out->depth ? depth : b->out->depth;
    if (end - begin <= BVH_LEAF_TRIANGLES) {
        n[0][3] = (float)begin;
        n[1][3] = (float)(end - begin);
        return node + 1;
    }
    int axis = 0, bin = 0, middle = begin;
    if (depth < BVH_SAH_DEPTH && bvh_best_split(b, begin, end, &centroids, &axis, &bin)) {
        float lo = centroids.lo[axis], extent = centroids.hi[axis] - lo;
        for (int i = begin; i < end; i++) {
            int t = b->order[i];
            int in = (int)((b->triangles[t].centroid[axis] - lo) * (BVH_BINS / extent));
            if ((in < BVH_BINS ? in : BVH_BINS - 1) < bin) {
                b->order[i] = b->order[middle];
                b->order[middle++] = t;
            }
        }
    } else {
        for (int k = 1; k < 3; k++)
            if (centroids.hi[k] - centroids.lo[k] > centroids.hi[axis] - centroids.lo[axis])
                axis = k;
        bvh_sort(b, begin, end, axis);
        middle = begin + (end - begin) / 2;
    }
    int right = bvh_build_node(b, node + 1, begin, middle, depth + 1);
    n[0][3] = (float)right;
    n[1][3] = 0;
    return bvh_build_node(b, right, middle, end, depth + 1);
}

static void bvh_builder_free(bvh_builder *b) {
    free(b->triangles);
    free(b->order);
    free(b->keys);
}

/* Whether o's triangles go into the hierarchy (bvh_build). */
/* Whether the rays read o's surface (bvh_record). */
static bool bvh_reads_surface(const scene_object *o) { return o->alpha_cutoff > 0 || o->translucent; }

bool bvh_build(const scene *s, const char *who, bvh *out) {
    *out = (bvh){0};
    long long count = 0, records = 0;
    for (int i = 0; i < s->object_count; i++) {
        long long triangles = s->objects[i].casts ? s->objects[i].mesh.index_count / 3 : 0;
        count += triangles;
        records += bvh_reads_surface(&s->objects[i]) ? triangles : 0;
    }
    if (count == 0)
        return true;
    if (count >= BVH_MAX_INDEX / 2) {
        fprintf(stderr, "%s: %lld casting triangles, more than the ray hierarchy holds (%d)\n", who, count,
                BVH_MAX_INDEX / 2 - 1);
        return false;
    }
    int n = (int)count;
    bvh_builder b = {malloc((size_t)n * sizeof *b.triangles), malloc((size_t)n * sizeof *b.order),
                     malloc((size_t)n * sizeof *b.keys), out};
    out->nodes = malloc((size_t)(2 * n) * sizeof *out->nodes);
    out->triangles = malloc((size_t)n * sizeof *out->triangles);
    out->records = malloc((size_t)(records + 1) * sizeof *out->records);
    if (!b.triangles || !b.order || !b.keys || !out->nodes || !out->triangles || !out->records) {
        fprintf(stderr, "%s: out of memory for the ray hierarchy of %d triangles\n", who, n);
        bvh_builder_free(&b);
        bvh_free(out);
        return false;
    }
    int t = 0;
    for (int i = 0; i < s->object_count; i++) {
        const scene_object *o = &s->objects[i];
        for (uint32_t k = 0; o->casts && k < o->mesh.index_count / 3; k++, t++) {
            bvh_triangle *tri = &b.triangles[t];
            tri->source = (bvh_record){o, k};
            for (int v = 0; v < 3; v++) {
                double corner[3];
                scene_object_world_corner(o, k, v, corner);
                for (int row = 0; row < 3; row++)
                    tri->vertices[v][row] = (float)corner[row];
            }
            for (int row = 0; row < 3; row++) {
                tri->lo[row] = fminf(fminf(tri->vertices[0][row], tri->vertices[1][row]), tri->vertices[2][row]);
                tri->hi[row] = fmaxf(fmaxf(tri->vertices[0][row], tri->vertices[1][row]), tri->vertices[2][row]);
                tri->centroid[row] = 0.5f * (tri->lo[row] + tri->hi[row]);
            }
            b.order[t] = t;
        }
    }
    out->triangle_count = n;
    out->node_count = bvh_build_node(&b, 0, 0, n, 1);
    for (int i = 0; i < n; i++) {
        const bvh_triangle *tri = &b.triangles[b.order[i]];
        for (int v = 0; v < 3; v++) {
            memcpy(out->triangles[i][v], tri->vertices[v], 3 * sizeof(float));
            out->triangles[i][v][3] = 0;
        }
        if (bvh_reads_surface(tri->source.object)) {
            out->records[out->record_count++] = tri->source;
            out->triangles[i][0][3] = (float)out->record_count;
        }
    }
    bvh_builder_free(&b);
    return true;
}

void bvh_free(bvh *b) {
    free(b->nodes);
    free(b->triangles);
    free(b->records);
    *b = (bvh){0};
}

/* The ray's shear into the frame where it runs along +z (Woop et al.):
 * kz its largest axis, kx and ky the others, swapped to keep the winding. */
typedef struct bvh_ray {
    float origin[3], inverse[3], t_max;
    float surface; /* a plane this near the origin is the surface it leaves */
    int kx, ky, kz;
    float shear[3];
} bvh_ray;

static bvh_ray bvh_ray_make(const float origin[3], const float dir[3], float t_max) {
    bvh_ray r = {.t_max = t_max};
    for (int k = 0; k < 3; k++) {
        r.origin[k] = origin[k];
        r.surface = fmaxf(r.surface, (float)BVH_SURFACE_ULPS * FLT_EPSILON * fabsf(origin[k]));
        float d = fabsf(dir[k]) < BVH_TINY_DIRECTION ? copysignf(BVH_TINY_DIRECTION, dir[k]) : dir[k];
        r.inverse[k] = 1.0f / d;
    }
    r.kz = fabsf(dir[0]) > fabsf(dir[1]) ? (fabsf(dir[0]) > fabsf(dir[2]) ? 0 : 2)
                                         : (fabsf(dir[1]) > fabsf(dir[2]) ? 1 : 2);
    r.kx = (r.kz + 1) % 3;
    r.ky = (r.kx + 1) % 3;
    if (dir[r.kz] < 0) {
        int swap = r.kx;
        r.kx = r.ky;
        r.ky = swap;
    }
    r.shear[0] = dir[r.kx] / dir[r.kz];
    r.shear[1] = dir[r.ky] / dir[r.kz];
    r.shear[2] = 1.0f / dir[r.kz];
    return r;
}

static bool bvh_ray_box(const bvh_ray *r, const float lo[4], const float hi[4]) {
    float near = 0, far = r->t_max;
    for (int k = 0; k < 3; k++) {
        float t0 = (lo[k] - r->origin[k]) * r->inverse[k], t1 = (hi[k] - r->origin[k]) * r->inverse[k];
        near = fmaxf(near, fminf(t0, t1));
        far = fminf(far, fmaxf(t0, t1) * BVH_FAR_WIDENING);
    }
    return near <= far;
}

/* Whether the ray meets triangle v; its barycentric weights there (of
 * its vertices, in order) into weight where it does. */
static bool bvh_ray_triangle(const bvh_ray *r, const float (*v)[4], float weight[3]) {
    float a[3], b[3], c[3];
    for (int k = 0; k < 3; k++) {
        a[k] = v[0][k] - r->origin[k];
        b[k] = v[1][k] - r->origin[k];
        c[k] = v[2][k] - r->origin[k];
    }
    float ax = a[r->kx] - r->shear[0] * a[r->kz], ay = a[r->ky] - r->shear[1] * a[r->kz];
    float bx = b[r->kx] - r->shear[0] * b[r->kz], by = b[r->ky] - r->shear[1] * b[r->kz];
    float cx = c[r->kx] - r->shear[0] * c[r->kz], cy = c[r->ky] - r->shear[1] * c[r->kz];
    float u = cx * by - cy * bx, v_ = ax * cy - ay * cx, w = bx * ay - by * ax;
    if ((u < 0 || v_ < 0 || w < 0) && (u > 0 || v_ > 0 || w > 0))
        return false;
    float det = u + v_ + w;
    if (det == 0)
        return false;
    float normal[3] = {(b[1] - a[1]) * (c[2] - a[2]) - (b[2] - a[2]) * (c[1] - a[1]),
                       (b[2] - a[2]) * (c[0] - a[0]) - (b[0] - a[0]) * (c[2] - a[2]),
                       (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])};
    float length = sqrtf(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    if (fabsf(normal[0] * a[0] + normal[1] * a[1] + normal[2] * a[2]) <= r->surface * length)
        return false;
    float t = r->shear[2] * (u * a[r->kz] + v_ * b[r->kz] + w * c[r->kz]);
    weight[0] = u / det;
    weight[1] = v_ / det;
    weight[2] = w / det;
    /* t / det in (0, t_max), without the division: the signs agree. */
    return det > 0 ? t > 0 && t < r->t_max * det : t < 0 && t > r->t_max * det;
}

/* What triangle i (in leaf order) lets through where the ray meets it at
 * weight, into out: nothing (an opaque surface), everything (a cut-out's
 * hole) or a translucent surface's transmittance. */
static void bvh_surface_at(const bvh *b, int i, const float weight[3], float out[3]) {
    int record = (int)b->triangles[i][0][3] - 1;
    const bvh_record *r = record >= 0 ? &b->records[record] : NULL;
    bool hole = r && scene_object_cut_out(r->object, r->triangle, weight);
    for (int k = 0; k < 3; k++)
        out[k] = hole ? 1.0f : 0.0f;
    if (r && !hole && r->object->translucent)
        scene_object_transmittance(r->object, r->triangle, weight, out);
}

/* Whether the segment meets the box lo..hi grown by the cone's radius
 * where the segment crosses it: first grown by its widest, end_radius,
 * which bounds where it may cross; then by the radius at the far end of
 * that crossing, which bounds the cone's over it. */
static bool bvh_cone_box(const bvh_ray *r, const float lo[4], const float hi[4], float end_radius) {
    float near = 0, far = r->t_max;
    for (int pass = 0; pass < 2 && near <= far; pass++) {
        float grow = pass == 0 ? end_radius : end_radius * fminf(far / r->t_max, 1.0f);
        near = 0;
        far = r->t_max;
        for (int k = 0; k < 3; k++) {
            float t0 = (lo[k] - grow - r->origin[k]) * r->inverse[k],
                  t1 = (hi[k] + grow - r->origin[k]) * r->inverse[k];
            near = fmaxf(near, fminf(t0, t1));
            far = fminf(far, fmaxf(t0, t1) * BVH_FAR_WIDENING);
        }
    }
    return near <= far;
}

float bvh_reach(const bvh *b) {
    float reach = 0;
    for (int k = 0; k < 3 && b->node_count > 0; k++)
        reach += fmaxf(b->nodes[0][0][k] * b->nodes[0][0][k], b->nodes[0][1][k] * b->nodes[0][1][k]);
    return sqrtf(reach);
}

bool bvh_cone_clear(const bvh *b, const float origin[3], const float dir[3], float t_max, float end_radius) {
    if (b->node_count == 0)
        return true;
    bvh_ray r = bvh_ray_make(origin, dir, t_max);
    int stack[BVH_MAX_DEPTH], top = 0, node = 0;
    for (;;) {
        const float(*n)[4] = b->nodes[node];
        if (bvh_cone_box(&r, n[0], n[1], end_radius)) {
            if (n[1][3] > 0)
                return false;
            stack[top++] = (int)n[0][3];
            node++;
            continue;
        }
        if (top == 0)
            return true;
        node = stack[--top];
    }
}

void bvh_transmittance(const bvh *b, const float origin[3], const float dir[3], float t_max, float out[3]) {
    out[0] = out[1] = out[2] = 1.0f;
    if (b->node_count == 0)
        return;
    bvh_ray r = bvh_ray_make(origin, dir, t_max);
    int stack[BVH_MAX_DEPTH], top = 0, node = 0;
    for (;;) {
        const float(*n)[4] = b->nodes[node];
        if (bvh_ray_box(&r, n[0], n[1])) {
            if (n[1][3] > 0) {
                for (int i = (int)n[0][3], end = i + (int)n[1][3]; i < end; i++) {
                    float weight[3], through[3];
                    if (!bvh_ray_triangle(&r, (const float(*)[4])b->triangles[i], weight))
                        continue;
                    bvh_surface_at(b, i, weight, through);
                    for (int k = 0; k < 3; k++)
                        out[k] *= through[k];
                    if (out[0] == 0 && out[1] == 0 && out[2] == 0)
                        return;
                }
            } else {
                stack[top++] = (int)n[0][3];
                node++;
                continue;
            }
        }
        if (top == 0)
            return;
        node = stack[--top];
    }
}

bool bvh_occluded(const bvh *b, const float origin[3], const float dir[3], float t_max) {
    float through[3];
    bvh_transmittance(b, origin, dir, t_max, through);
    return through[0] == 0 && through[1] == 0 && through[2] == 0;
}
