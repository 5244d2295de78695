#include "visible.h"

#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "depth.h"

/* The 24-bit buffer's step; a float buffer's at depth d is at most d
 * times the float one. */
#define VISIBLE_FIXED_STEP 0x1.0p-24
#define VISIBLE_FLOAT_STEP 0x1.0p-23

static bool visible_reserve(visible *v, int width, int height) {
    if (v->width == width && v->height == height)
        return true;
    visible_destroy(v);
    int tiles = ((width + VISIBLE_TILE_PIXELS - 1) / VISIBLE_TILE_PIXELS) *
                ((height + VISIBLE_TILE_PIXELS - 1) / VISIBLE_TILE_PIXELS);
    v->depth = malloc((size_t)width * (size_t)height * sizeof *v->depth);
    v->slabs = malloc((size_t)tiles * VISIBLE_DEPTH_BINS * sizeof *v->slabs);
    v->seen = malloc((size_t)tiles * VISIBLE_DEPTH_BINS * sizeof *v->seen);
    if (!v->depth || !v->slabs || !v->seen) {
        fprintf(stderr, "visible: out of memory for a %dx%d frame\n", width, height);
        visible_destroy(v);
        return false;
    }
    v->capacity = tiles * VISIBLE_DEPTH_BINS;
    v->width = width;
    v->height = height;
    return true;
}

void visible_destroy(visible *v) {
    free(v->depth);
    free(v->slabs);
    free(v->seen);
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
        out[k] = (float)(view->eye[k] + eye_x * view->view[k][0] + eye_y * view->view[k][1] -
                         distance * view->view[k][2]);
}

/* One tile's slab from its depths lo..hi (window depth), each end pushed
 * outwards by VISIBLE_DEPTH_STEPS of the buffer's steps there, kept
 * inside the depths that unproject to a finite distance. */
static void visible_slab(visible *v, const camera_view *view, int x0, int y0, int x1, int y1, double lo,
                         double hi) {
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
    v->seen[v->count] = (light_mask_seen){{(float)x0, (float)y0, (float)ends[0]}, {(float)x1, (float)y1, (float)ends[1]}};
    v->count++;
}

/* The slabs of the tile x0..x1, y0..y1 (pixels), appended to v's. */
static void visible_tile_slabs(visible *v, const camera_view *view, int x0, int y0, int x1, int y1) {
    float clear = depth_far(view);
    double lo = INFINITY, hi = -INFINITY;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++) {
            float d = v->depth[(size_t)y * (size_t)v->width + (size_t)x];
            if (d != clear) {
                lo = fmin(lo, d);
                hi = fmax(hi, d);
            }
        }
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

bool visible_read(visible *v, const camera_view *view, int width, int height) {
    if (!visible_reserve(v, width, height))
        return false;
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    /* A failed read raises a GL error, which the frame's owner reports. */
    glReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, v->depth);
    v->count = 0;
    for (int y0 = 0; y0 < height; y0 += VISIBLE_TILE_PIXELS)
        for (int x0 = 0; x0 < width; x0 += VISIBLE_TILE_PIXELS)
            visible_tile_slabs(v, view, x0, y0, x0 + VISIBLE_TILE_PIXELS < width ? x0 + VISIBLE_TILE_PIXELS : width,
                               y0 + VISIBLE_TILE_PIXELS < height ? y0 + VISIBLE_TILE_PIXELS : height);
    return true;
}
