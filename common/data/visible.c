#include "visible.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "frustum.h"

/* The 24-bit buffer's step; a float buffer's at depth d is at most d
 * times the float one. */
#define VISIBLE_FIXED_STEP 0x1.0p-24
#define VISIBLE_FLOAT_STEP 0x1.0p-23

static bool visible_reserve(visible *v, int width, int height) {
    if (v->width == width && v->height == height)
        return true;
    visible_destroy(v);
    int tiles_x = (width + VISIBLE_TILE_PIXELS - 1) / VISIBLE_TILE_PIXELS;
    int tiles_y = (height + VISIBLE_TILE_PIXELS - 1) / VISIBLE_TILE_PIXELS, tiles = tiles_x * tiles_y;
    v->depth = malloc((size_t)width * (size_t)height * sizeof *v->depth);
    v->slabs = malloc((size_t)tiles * VISIBLE_DEPTH_BINS * sizeof *v->slabs);
    v->seen = malloc((size_t)tiles * VISIBLE_DEPTH_BINS * sizeof *v->seen);
    v->lights = malloc((size_t)tiles * VISIBLE_DEPTH_BINS * sizeof *v->lights);
    v->farthest = malloc((size_t)tiles * sizeof *v->farthest);
    if (!v->depth || !v->slabs || !v->seen || !v->lights || !v->farthest) {
        fprintf(stderr, "visible: out of memory for a %dx%d frame\n", width, height);
        visible_destroy(v);
        return false;
    }
    v->width = width;
    v->height = height;
    v->tiles_x = tiles_x;
    v->tiles_y = tiles_y;
    return true;
}

void visible_destroy(visible *v) {
    free(v->depth);
    free(v->slabs);
    free(v->seen);
    free(v->lights);
    free(v->farthest);
    *v = (visible){0};
}

/* The view's distance along its axis at window depth `d`, from the depth
 * row the camera rasterized with: clip z = a z_eye + b against
 * w = -z_eye, so NDC z = -a - b / z_eye (standard depth's NDC is
 * 2d - 1, reversed depth's d). */
static double visible_view_distance(const camera_view *view, double d) {
    double a = view->raster_projection[2][2], b = view->raster_projection[3][2];
    double ndc = view->reversed_depth ? d : 2 * d - 1;
    return b / (ndc + a);
}

/* The world point at NDC (x, y) and view distance `distance`, in double
 * from the view's rows (an orthonormal basis and the eye). */
static void visible_unproject(const camera_view *view, double x, double y, double distance, float out[3]) {
    double eye_x = x * distance / view->projection[0][0], eye_y = y * distance / view->projection[1][1];
    for (int k = 0; k < 3; k++)
        out[k] =
            (float)(view->eye[k] + eye_x * view->view[k][0] + eye_y * view->view[k][1] - distance * view->view[k][2]);
}

/* One tile's slab from its depths lo..hi (window depth), each end pushed
 * outwards by VISIBLE_DEPTH_STEPS of the buffer's steps there, kept
 * inside the depths that unproject to a finite distance. */
static void visible_slab(visible *v, const camera_view *view, int x0, int y0, int x1, int y1, double lo, double hi) {
    double ends[2];
    if (view->reversed_depth) { /* float, nearer is larger: relative steps */
        ends[0] = lo * (1 - VISIBLE_DEPTH_STEPS * VISIBLE_FLOAT_STEP);
        ends[1] = fmin(hi * (1 + VISIBLE_DEPTH_STEPS * VISIBLE_FLOAT_STEP), 1);
    } else { /* 24-bit fixed point, nearer is smaller */
        ends[0] = fmax(lo - VISIBLE_DEPTH_STEPS * VISIBLE_FIXED_STEP, 0);
        ends[1] = fmin(hi + VISIBLE_DEPTH_STEPS * VISIBLE_FIXED_STEP, 1 - VISIBLE_FIXED_STEP);
    }
    for (int c = 0; c < 8; c++) {
        double x = 2.0 * (c & 1 ? x1 : x0) / v->width - 1, y = 2.0 * (c & 2 ? y1 : y0) / v->height - 1;
        visible_unproject(view, x, y, visible_view_distance(view, ends[c >> 2]), v->slabs[v->count][c]);
    }
    v->seen[v->count] =
        (light_mask_seen){{(float)x0, (float)y0, (float)ends[0]}, {(float)x1, (float)y1, (float)ends[1]}};
    v->count++;
}

/* The slabs of the tile x0..x1, y0..y1 (pixels), appended to v's. */
static void visible_tile_slabs(visible *v, const camera_view *view, float clear, int x0, int y0, int x1, int y1) {
    double lo = INFINITY, hi = -INFINITY;
    bool sky = false;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++) {
            float d = v->depth[(size_t)y * (size_t)v->width + (size_t)x];
            sky = sky || d == clear;
            if (d != clear) {
                lo = fmin(lo, d);
                hi = fmax(hi, d);
            }
        }
    /* The tile's farthest depth: the clear value where any pixel is sky. */
    v->farthest[(y0 / VISIBLE_TILE_PIXELS) * v->tiles_x + x0 / VISIBLE_TILE_PIXELS] =
        sky ? clear : (float)(view->reversed_depth ? lo : hi);
    if (!(lo <= hi))
        return; /* sky only */
    double near_distance = visible_view_distance(view, view->reversed_depth ? hi : lo);
    double far_distance = visible_view_distance(view, view->reversed_depth ? lo : hi);
    if (!(far_distance > VISIBLE_SPLIT_RATIO * near_distance)) {
        visible_slab(v, view, x0, y0, x1, y1, lo, hi);
        return;
    }
    /* Deep: the depths binned by distance, evenly in its logarithm, one
     * slab a bin that holds a pixel. */
    double bin_lo[VISIBLE_DEPTH_BINS], bin_hi[VISIBLE_DEPTH_BINS];
    for (int b = 0; b < VISIBLE_DEPTH_BINS; b++) {
        bin_lo[b] = INFINITY;
        bin_hi[b] = -INFINITY;
    }
    double scale = VISIBLE_DEPTH_BINS / log(far_distance / near_distance);
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++) {
            float d = v->depth[(size_t)y * (size_t)v->width + (size_t)x];
            if (d == clear)
                continue;
            int b = (int)(scale * log(visible_view_distance(view, d) / near_distance));
            b = b < 0 ? 0 : b >= VISIBLE_DEPTH_BINS ? VISIBLE_DEPTH_BINS - 1 : b;
            bin_lo[b] = fmin(bin_lo[b], d);
            bin_hi[b] = fmax(bin_hi[b], d);
        }
    for (int b = 0; b < VISIBLE_DEPTH_BINS; b++)
        if (bin_lo[b] <= bin_hi[b])
            visible_slab(v, view, x0, y0, x1, y1, bin_lo[b], bin_hi[b]);
}

float *visible_depth_buffer(visible *v, int width, int height) {
    return visible_reserve(v, width, height) ? v->depth : NULL;
}

void visible_build(visible *v, const camera_view *view, float clear) {
    v->count = 0;
    for (int y0 = 0; y0 < v->height; y0 += VISIBLE_TILE_PIXELS)
        for (int x0 = 0; x0 < v->width; x0 += VISIBLE_TILE_PIXELS)
            visible_tile_slabs(v, view, clear, x0, y0,
                               x0 + VISIBLE_TILE_PIXELS < v->width ? x0 + VISIBLE_TILE_PIXELS : v->width,
                               y0 + VISIBLE_TILE_PIXELS < v->height ? y0 + VISIBLE_TILE_PIXELS : v->height);
}

bool visible_box_hidden(const visible *v, const camera_view *view, const vec3 lo, const vec3 hi) {
    vec3 corners[8];
    frustum_box_corners(lo, hi, corners);
    float x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY, nearest = INFINITY;
    for (int c = 0; c < 8; c++) {
        vec4 clip;
        glm_mat4_mulv((vec4 *)view->raster_view_projection, (vec4){corners[c][0], corners[c][1], corners[c][2], 1},
                      clip);
        /* A corner before the near plane: the box's nearest depth is not
         * its corners'. */
        float ndc_z = clip[2] / clip[3];
        if (!(clip[3] > 0) || ndc_z < (view->reversed_depth ? 0.0f : -1.0f) || ndc_z > 1)
            return false;
        float window = view->reversed_depth ? ndc_z : 0.5f * ndc_z + 0.5f;
        /* Nearness as a depth that grows away from the eye. */
        nearest = fminf(nearest, view->reversed_depth ? 1 - window : window);
        x0 = fminf(x0, clip[0] / clip[3]);
        x1 = fmaxf(x1, clip[0] / clip[3]);
        y0 = fminf(y0, clip[1] / clip[3]);
        y1 = fmaxf(y1, clip[1] / clip[3]);
    }
    double step =
        view->reversed_depth ? fmax(VISIBLE_FIXED_STEP, (1 - nearest) * VISIBLE_FLOAT_STEP) : VISIBLE_FIXED_STEP;
    double margin = VISIBLE_DEPTH_STEPS * step;
    /* The tiles the box's rectangle covers, a pixel wider each side. */
    int tx0 = (int)floorf(((glm_clamp(x0, -1, 1) * 0.5f + 0.5f) * (float)v->width - 1) / VISIBLE_TILE_PIXELS);
    int tx1 = (int)floorf(((glm_clamp(x1, -1, 1) * 0.5f + 0.5f) * (float)v->width + 1) / VISIBLE_TILE_PIXELS);
    int ty0 = (int)floorf(((glm_clamp(y0, -1, 1) * 0.5f + 0.5f) * (float)v->height - 1) / VISIBLE_TILE_PIXELS);
    int ty1 = (int)floorf(((glm_clamp(y1, -1, 1) * 0.5f + 0.5f) * (float)v->height + 1) / VISIBLE_TILE_PIXELS);
    tx0 = glm_max(tx0, 0);
    ty0 = glm_max(ty0, 0);
    tx1 = glm_min(tx1, v->tiles_x - 1);
    ty1 = glm_min(ty1, v->tiles_y - 1);
    for (int ty = ty0; ty <= ty1; ty++)
        for (int tx = tx0; tx <= tx1; tx++) {
            float farthest = v->farthest[ty * v->tiles_x + tx];
            double far_as_depth = view->reversed_depth ? 1.0 - farthest : farthest;
            if (nearest - margin <= far_as_depth)
                return false;
        }
    return true;
}
