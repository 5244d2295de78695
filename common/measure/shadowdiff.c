#include "shadowdiff.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"

const unsigned char shadowdiff_pixel_colors[SHADOWDIFF_PIXEL_KIND_COUNT][3] = {
    [SHADOWDIFF_PIXEL_NO_SURFACE] = {0, 0, 0},
    [SHADOWDIFF_PIXEL_NOT_COMPARED] = {40, 40, 40},
    [SHADOWDIFF_PIXEL_AGREES] = {SHADOWDIFF_AGREES_GREY_LIT, SHADOWDIFF_AGREES_GREY_LIT, SHADOWDIFF_AGREES_GREY_LIT},
    [SHADOWDIFF_PIXEL_FALSE_SHADOW] = {255, 0, 0},
    [SHADOWDIFF_PIXEL_FALSE_LIT] = {0, 0, 255},
};
const char *const shadowdiff_pixel_names[SHADOWDIFF_PIXEL_KIND_COUNT] = {
    [SHADOWDIFF_PIXEL_NO_SURFACE] = "no surface",
    [SHADOWDIFF_PIXEL_NOT_COMPARED] = "not compared",
    [SHADOWDIFF_PIXEL_AGREES] = "agrees (lighter where lit)",
    [SHADOWDIFF_PIXEL_FALSE_SHADOW] = "false shadow",
    [SHADOWDIFF_PIXEL_FALSE_LIT] = "false lit",
};
const char *const shadowdiff_class_names[SHADOWDIFF_CLASS_COUNT] = {
    [SHADOWDIFF_CLASS_UMBRA] = "umbra",
    [SHADOWDIFF_CLASS_PENUMBRA] = "penumbra",
    [SHADOWDIFF_CLASS_LIT] = "lit",
};
const shadowdiff_pixel shadowdiff_legend_kinds[SHADOWDIFF_PIXEL_KIND_COUNT] = {
    SHADOWDIFF_PIXEL_FALSE_SHADOW, SHADOWDIFF_PIXEL_FALSE_LIT,  SHADOWDIFF_PIXEL_AGREES,
    SHADOWDIFF_PIXEL_NOT_COMPARED, SHADOWDIFF_PIXEL_NO_SURFACE,
};

static double shadowdiff_length3(const float v[3]) {
    return sqrt((double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2]);
}

/* Whether a and b differ by at most `tolerance` in each of n components. */
static bool shadowdiff_close(const float *a, const float *b, int n, double tolerance) {
    for (int i = 0; i < n; i++)
        if (fabs((double)a[i] - b[i]) > tolerance)
            return false;
    return true;
}

/* Relative to the light's length, not per component: a component near 0
 * (a light straight above) would otherwise have to match exactly. */
static bool shadowdiff_same_light(const float a[4], const float b[4]) {
    return a[3] == b[3] &&
           shadowdiff_close(a, b, 3, SHADOWDIFF_LIGHT_TOLERANCE * fmax(shadowdiff_length3(a), shadowdiff_length3(b)));
}

/* Eye and target relative to their distance, as the light is to its
 * length; reversed_depth is a raster program's choice, not the view. */
static bool shadowdiff_same_camera(const scene_camera *a, const scene_camera *b) {
    const float view[3] = {a->target[0] - a->position[0], a->target[1] - a->position[1],
                           a->target[2] - a->position[2]};
    const double t = SHADOWDIFF_CAMERA_TOLERANCE;
    double place = t * shadowdiff_length3(view);
    return shadowdiff_close(a->position, b->position, 3, place) && shadowdiff_close(a->target, b->target, 3, place) &&
           shadowdiff_close(a->up, b->up, 3, t * shadowdiff_length3(a->up)) &&
           shadowdiff_close(&a->fov_deg, &b->fov_deg, 1, t * a->fov_deg) &&
           shadowdiff_close(&a->near_plane, &b->near_plane, 1, t * a->near_plane) &&
           shadowdiff_close(&a->far_plane, &b->far_plane, 1, t * a->far_plane);
}

static bool shadowdiff_check_size(const dump_frame *r, const dump_frame *t, const char *r_name, const char *t_name) {
    if (r->width == t->width && r->height == t->height)
        return true;
    fprintf(stderr, "shadowdiff: %s and %s differ in size: %dx%d and %dx%d\n", r_name, t_name, r->width, r->height,
            t->width, t->height);
    return false;
}

/* Ids only name the same objects where the names agree, index by index. */
static bool shadowdiff_check_objects(const dump_frame *r, const dump_frame *t, const char *r_name,
                                     const char *t_name) {
    if (r->object_count != t->object_count) {
        fprintf(stderr, "shadowdiff: %s and %s have different objects: %d and %d\n", r_name, t_name, r->object_count,
                t->object_count);
        return false;
    }
    for (int i = 0; i < r->object_count; i++) {
        if (strcmp(r->object_names[i], t->object_names[i]) != 0) {
            fprintf(stderr, "shadowdiff: %s and %s have different objects: %d is '%s' and '%s'\n", r_name, t_name, i,
                    r->object_names[i], t->object_names[i]);
            return false;
        }
    }
    return true;
}

/* Ids, depths and visibilities only mean the same when the dumps come from
 * the same frame of the same scene; anything else would be compared
 * silently and give plausible, meaningless numbers. */
static bool shadowdiff_check_consistent(const dump_frame *r, const dump_frame *t, const char *r_name,
                                        const char *t_name) {
    if (!shadowdiff_check_size(r, t, r_name, t_name))
        return false;
    if (r->light_index != t->light_index || !shadowdiff_same_light(r->light, t->light)) {
        fprintf(stderr,
                "shadowdiff: %s and %s are lit differently: light %d at (%g, %g, %g, %g) and light %d at "
                "(%g, %g, %g, %g)\n",
                r_name, t_name, r->light_index, r->light[0], r->light[1], r->light[2], r->light[3], t->light_index,
                t->light[0], t->light[1], t->light[2], t->light[3]);
        return false;
    }
    return shadowdiff_check_objects(r, t, r_name, t_name);
}

static int shadowdiff_find_object(const dump_frame *d, const char *name) {
    for (int i = 0; i < d->object_count; i++)
        if (strcmp(d->object_names[i], name) == 0)
            return i;
    return -1;
}

static void shadowdiff_print_unknown_receiver(const dump_frame *d, const char *d_name, const char *receiver) {
    fprintf(stderr, "shadowdiff: %s: unknown receiver '%s' (objects:", d_name, receiver);
    for (int i = 0; i < d->object_count; i++)
        fprintf(stderr, "%s %s", i > 0 ? "," : "", d->object_names[i]);
    fprintf(stderr, ")\n");
}

/* light.xyz - w * position is the direction towards the light for both a
 * point (w = 1) and a directional light (w = 0). The cosine must pass
 * FLT_EPSILON too: the normal is a float, so no smaller cosine tells a
 * surface facing the light from one exactly edge-on to it (the stress
 * case light_on_ground_point's ground, the light in its plane, has cosines
 * of the order of 1e-17 either way, row by row, from hit points a rounding
 * off the plane). */
static bool shadowdiff_faces_light(const dump_frame *d, size_t i, double min_cosine) {
    const float *n = d->normal + 3 * i, *p = d->position + 3 * i;
    double n_dot_l = 0, n_length = 0, l_length = 0;
    for (int k = 0; k < 3; k++) {
        double l = (double)d->light[k] - (double)d->light[3] * p[k];
        n_dot_l += (double)n[k] * l;
        n_length += (double)n[k] * n[k];
        l_length += l * l;
    }
    return n_dot_l > fmax(min_cosine, FLT_EPSILON) * sqrt(n_length * l_length);
}

/* Ids stay floats here: a damaged dump may hold values no int can. */
static bool shadowdiff_is_compared(const dump_frame *r, const dump_frame *t, size_t i, int receiver,
                                   double min_cosine) {
    double r_depth = r->depth[i], t_depth = t->depth[i];
    return r->ids[i] >= 0 && t->ids[i] >= 0 && fabs(t_depth - r_depth) <= SHADOWDIFF_DEPTH_TOLERANCE * r_depth &&
           shadowdiff_faces_light(r, i, min_cosine) &&
           (receiver < 0 || (r->ids[i] == receiver && t->ids[i] == receiver));
}

static bool shadowdiff_lit(const dump_frame *d, size_t i) { return d->visibility[i] >= SHADOWDIFF_LIT_THRESHOLD; }

shadowdiff_class shadowdiff_class_of(float reference_visibility) {
    if (reference_visibility <= SHADOWDIFF_UMBRA_MAX_VISIBILITY)
        return SHADOWDIFF_CLASS_UMBRA;
    return reference_visibility >= SHADOWDIFF_LIT_MIN_VISIBILITY ? SHADOWDIFF_CLASS_LIT : SHADOWDIFF_CLASS_PENUMBRA;
}

static shadowdiff_pixel shadowdiff_classify(const dump_frame *r, const dump_frame *t, size_t i, int receiver,
                                            double min_cosine) {
    if (!shadowdiff_is_compared(r, t, i, receiver, min_cosine))
        return r->ids[i] < 0 ? SHADOWDIFF_PIXEL_NO_SURFACE : SHADOWDIFF_PIXEL_NOT_COMPARED;
    bool r_lit = shadowdiff_lit(r, i), t_lit = shadowdiff_lit(t, i);
    if (r_lit && !t_lit)
        return SHADOWDIFF_PIXEL_FALSE_SHADOW;
    if (!r_lit && t_lit)
        return SHADOWDIFF_PIXEL_FALSE_LIT;
    return SHADOWDIFF_PIXEL_AGREES;
}

static void shadowdiff_paint(unsigned char *rgba, shadowdiff_pixel pixel, float reference_visibility) {
    if (pixel == SHADOWDIFF_PIXEL_AGREES) {
        float v = fminf(fmaxf(reference_visibility, 0), 1);
        unsigned char grey = (unsigned char)lroundf(
            SHADOWDIFF_AGREES_GREY_SHADOWED + (SHADOWDIFF_AGREES_GREY_LIT - SHADOWDIFF_AGREES_GREY_SHADOWED) * v);
        memset(rgba, grey, 3);
    } else {
        memcpy(rgba, shadowdiff_pixel_colors[pixel], 3);
    }
    rgba[3] = 255;
}

/* Only of compared pixels: `of` > 0. */
static double shadowdiff_percent(long count, long of) { return 100.0 * (double)count / (double)of; }

/* One array of a dump that the rules read, as its file is named in the
 * dump directory (dump.h), so that the message points at the file. */
typedef struct shadowdiff_array {
    const char *file;
    const float *values;
    int components;
    bool everywhere;     /* read at every pixel, not only where a surface is seen */
    bool reference_only; /* read in the reference only (whether it faces the light) */
} shadowdiff_array;

/* Counts the non-finite values of `a` that the rules read; the first one's
 * pixel goes to *first_pixel and its value to *first_value. */
static long shadowdiff_count_non_finite(const dump_frame *d, const shadowdiff_array *a, size_t *first_pixel,
                                        float *first_value) {
    long count = 0;
    size_t n = (size_t)d->width * (size_t)d->height;
    for (size_t i = 0; i < n; i++) {
        if (!a->everywhere && !(d->ids[i] >= 0))
            continue;
        for (int k = 0; k < a->components; k++) {
            float v = a->values[(size_t)a->components * i + (size_t)k];
            if (!isfinite(v) && count++ == 0) {
                *first_pixel = i;
                *first_value = v;
            }
        }
    }
    return count;
}

/* Checks every value the rules read in dump `d`; false after one line
 * naming the first bad value's file and pixel. */
static bool shadowdiff_check_finite(const dump_frame *d, const char *name, bool is_reference) {
    const shadowdiff_array arrays[] = {
        {"visibility_rgb.pfm", d->visibility_rgb, 3, false, false},
        {"ids.pfm", d->ids, 1, true, false},
        {"depth.pfm", d->depth, 1, false, false},
        {"visibility.pfm", d->visibility, 1, false, false},
        {"normal.pfm", d->normal, 3, false, true},
        {"position.pfm", d->position, 3, false, true},
    };
    for (size_t a = 0; a < sizeof arrays / sizeof *arrays; a++) {
        if ((arrays[a].reference_only && !is_reference) || !arrays[a].values)
            continue;
        size_t pixel = 0;
        float value = 0;
        long count = shadowdiff_count_non_finite(d, &arrays[a], &pixel, &value);
        if (count > 0) {
            fprintf(stderr,
                    "shadowdiff: %s/%s: %g at pixel (%zu, %zu)%s, and %ld non-finite value%s in all: a broken "
                    "dump, no figure is given\n",
                    name, arrays[a].file, value, pixel % (size_t)d->width, pixel / (size_t)d->width,
                    arrays[a].everywhere ? "" : " where a surface is seen", count, count == 1 ? "" : "s");
            return false;
        }
    }
    return true;
}

/* The percentages and the mean absolute errors of r's counts (r->compared
 * > 0) and of the sums of its compared pixels' errors, all of them and by
 * class. */
static void shadowdiff_result_figures(shadowdiff_result *r, double error_sum,
                                      const double class_error_sum[SHADOWDIFF_CLASS_COUNT]) {
    r->false_shadow_percent = shadowdiff_percent(r->false_shadow, r->compared);
    r->false_lit_percent = shadowdiff_percent(r->false_lit, r->compared);
    r->misclassified_percent = shadowdiff_percent(r->false_shadow + r->false_lit, r->compared);
    r->mean_abs_error = error_sum / (double)r->compared;
    for (int c = 0; c < SHADOWDIFF_CLASS_COUNT; c++)
        r->class_mae[c] = r->class_pixels[c] > 0 ? class_error_sum[c] / (double)r->class_pixels[c] : 0;
}

static double shadowdiff_min_cosine(const shadowdiff_settings *s) {
    return sin(s->grazing_degrees * (3.14159265358979 / 180));
}

bool shadowdiff_compare(const dump_frame *reference, const dump_frame *test, const shadowdiff_settings *settings,
                        shadowdiff_result *out, unsigned char *heatmap_rgba) {
    const shadowdiff_settings s = settings ? *settings : (shadowdiff_settings){0};
    const char *r_name = s.reference_name ? s.reference_name : "reference";
    const char *t_name = s.test_name ? s.test_name : "test";
    *out = (shadowdiff_result){.problem = SHADOWDIFF_PROBLEM_MISMATCH};
    if (!shadowdiff_check_consistent(reference, test, r_name, t_name))
        return false;
    int receiver = -1;
    if (s.receiver && (receiver = shadowdiff_find_object(reference, s.receiver)) < 0) {
        shadowdiff_print_unknown_receiver(reference, r_name, s.receiver);
        return false;
    }
    out->problem = SHADOWDIFF_PROBLEM_NOT_FINITE;
    if (!shadowdiff_check_finite(reference, r_name, true) || !shadowdiff_check_finite(test, t_name, false))
        return false;
    out->problem = SHADOWDIFF_PROBLEM_NONE;
    double error_sum = 0, class_error_sum[SHADOWDIFF_CLASS_COUNT] = {0}, min_cosine = shadowdiff_min_cosine(&s);
    double channel_error_sum[3] = {0, 0, 0};
    out->coloured = reference->visibility_rgb && test->visibility_rgb;
    size_t n = (size_t)reference->width * (size_t)reference->height;
    for (size_t i = 0; i < n; i++) {
        shadowdiff_pixel pixel = shadowdiff_classify(reference, test, i, receiver, min_cosine);
        if (pixel >= SHADOWDIFF_PIXEL_AGREES) {
            double error = fabs((double)reference->visibility[i] - (double)test->visibility[i]);
            shadowdiff_class c = shadowdiff_class_of(reference->visibility[i]);
            out->compared++;
            out->false_shadow += pixel == SHADOWDIFF_PIXEL_FALSE_SHADOW;
            out->false_lit += pixel == SHADOWDIFF_PIXEL_FALSE_LIT;
            out->class_pixels[c]++;
            error_sum += error;
            class_error_sum[c] += error;
            for (int k = 0; out->coloured && k < 3; k++)
                channel_error_sum[k] += fabs((double)reference->visibility_rgb[3 * i + (size_t)k] -
                                             test->visibility_rgb[3 * i + (size_t)k]);
        }
        if (heatmap_rgba)
            shadowdiff_paint(heatmap_rgba + 4 * i, pixel, reference->visibility[i]);
    }
    if (out->compared == 0) {
        fprintf(stderr,
                "shadowdiff: %s and %s: nothing compared (no pixel is seen by both at the same depth, facing the "
                "light%s%s): no figure is given\n",
                r_name, t_name, s.receiver ? ", on " : "", s.receiver ? s.receiver : "");
        out->problem = SHADOWDIFF_PROBLEM_NOTHING_COMPARED;
        return false;
    }
    shadowdiff_result_figures(out, error_sum, class_error_sum);
    for (int k = 0; out->coloured && k < 3; k++)
        out->channel_mae[k] = channel_error_sum[k] / (double)out->compared;
    return true;
}

void shadowdiff_result_add(shadowdiff_result *total, const shadowdiff_result *frame) {
    double error_sum =
        total->mean_abs_error * (double)total->compared + frame->mean_abs_error * (double)frame->compared;
    double class_error_sum[SHADOWDIFF_CLASS_COUNT];
    for (int c = 0; c < SHADOWDIFF_CLASS_COUNT; c++) {
        class_error_sum[c] = total->class_mae[c] * (double)total->class_pixels[c] +
                             frame->class_mae[c] * (double)frame->class_pixels[c];
        total->class_pixels[c] += frame->class_pixels[c];
    }
    /* Coloured where every frame added is. */
    bool coloured = frame->coloured && (total->coloured || total->compared == 0);
    for (int k = 0; k < 3; k++)
        total->channel_mae[k] = coloured && total->compared + frame->compared > 0
                                    ? (total->channel_mae[k] * (double)total->compared +
                                       frame->channel_mae[k] * (double)frame->compared) /
                                          (double)(total->compared + frame->compared)
                                    : 0;
    total->coloured = coloured;
    total->compared += frame->compared;
    total->false_shadow += frame->false_shadow;
    total->false_lit += frame->false_lit;
    if (total->compared > 0)
        shadowdiff_result_figures(total, error_sum, class_error_sum);
}

const char *shadowdiff_class_mae_text(const shadowdiff_result *r, shadowdiff_class c, int decimals, char *text,
                                      size_t size) {
    if (r->class_pixels[c] > 0)
        snprintf(text, size, "%.*f", decimals, r->class_mae[c]);
    else
        snprintf(text, size, "%s", SHADOWDIFF_NO_FIGURE);
    return text;
}

const char *shadowdiff_class_figures_text(const shadowdiff_result *r, shadowdiff_class c, int decimals, char *text,
                                          size_t size) {
    char mae[SHADOWDIFF_FIGURE_TEXT_MAX];
    snprintf(text, size, "%s MAE %s (%ld px)", shadowdiff_class_names[c],
             shadowdiff_class_mae_text(r, c, decimals, mae, sizeof mae), r->class_pixels[c]);
    return text;
}

/* Whether the camera of dump `r` and of its test `t` agree; says so if
 * not. */
static bool shadowdiff_check_camera(const dump_frame *r, const dump_frame *t, const char *r_name,
                                    const char *t_name) {
    if (shadowdiff_same_camera(&r->camera, &t->camera))
        return true;
    fprintf(stderr, "shadowdiff: %s and %s are seen from different cameras: eyes (%g, %g, %g) and (%g, %g, %g)\n",
            r_name, t_name, r->camera.position[0], r->camera.position[1], r->camera.position[2],
            t->camera.position[0], t->camera.position[1], t->camera.position[2]);
    return false;
}

/* The pixel of `previous` (its camera, dump.h) that world point p falls
 * in, as the rasterizer samples pixel centres, top row 0; -1 where p is
 * behind its eye or outside its picture. */
static long shadowdiff_reproject(const camera_view *previous, int width, int height, const float p[3]) {
    double clip[4];
    for (int row = 0; row < 4; row++) {
        clip[row] = previous->view_projection[3][row];
        for (int k = 0; k < 3; k++)
            clip[row] += (double)previous->view_projection[k][row] * p[k];
    }
    if (!(clip[3] > 0))
        return -1;
    double x = (clip[0] / clip[3] + 1) * 0.5 * width, y = (1 - clip[1] / clip[3]) * 0.5 * height;
    if (!(x >= 0 && x < width && y >= 0 && y < height))
        return -1;
    return (long)floor(y) * width + (long)floor(x);
}

/* Follows every compared pixel of the current frame to the previous one
 * and counts (see shadowdiff.h). */
static void shadowdiff_count_shimmer(const dump_frame *r0, const dump_frame *t0, const dump_frame *r1,
                                     const dump_frame *t1, int receiver, double min_cosine,
                                     shadowdiff_shimmer_result *out) {
    camera_view previous;
    camera_view_compute(&r0->camera, (float)r0->width / (float)r0->height, &previous);
    size_t n = (size_t)r1->width * (size_t)r1->height;
    for (size_t i1 = 0; i1 < n; i1++) {
        if (shadowdiff_classify(r1, t1, i1, receiver, min_cosine) < SHADOWDIFF_PIXEL_AGREES)
            continue;
        const float *p1 = r1->position + 3 * i1;
        long found = shadowdiff_reproject(&previous, r0->width, r0->height, p1);
        if (found < 0)
            continue;
        size_t i0 = (size_t)found;
        const float *p0 = r0->position + 3 * i0;
        const float moved[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        if (r0->ids[i0] != r1->ids[i1] || t0->ids[i0] != t1->ids[i1] ||
            shadowdiff_length3(moved) > SHADOWDIFF_SHIMMER_POSITION_TOLERANCE * r1->depth[i1] ||
            shadowdiff_classify(r0, t0, i0, receiver, min_cosine) < SHADOWDIFF_PIXEL_AGREES)
            continue;
        bool truth_changed = shadowdiff_lit(r0, i0) != shadowdiff_lit(r1, i1);
        bool test_changed = shadowdiff_lit(t0, i0) != shadowdiff_lit(t1, i1);
        out->followed++;
        out->truth_changed += truth_changed;
        out->shimmered += test_changed && !truth_changed;
    }
}

bool shadowdiff_shimmer(const dump_frame *previous_reference, const dump_frame *previous_test,
                        const dump_frame *reference, const dump_frame *test, const shadowdiff_settings *settings,
                        shadowdiff_shimmer_result *out) {
    const shadowdiff_settings s = settings ? *settings : (shadowdiff_settings){0};
    const char *r_name = s.reference_name ? s.reference_name : "reference";
    const char *t_name = s.test_name ? s.test_name : "test";
    shadowdiff_settings previous_settings = s;
    previous_settings.reference_name = s.previous_reference_name ? s.previous_reference_name : "previous reference";
    previous_settings.test_name = s.previous_test_name ? s.previous_test_name : "previous test";
    *out = (shadowdiff_shimmer_result){.problem = SHADOWDIFF_PROBLEM_MISMATCH};
    if (!shadowdiff_compare(previous_reference, previous_test, &previous_settings, &out->previous, NULL)) {
        out->problem = out->previous.problem;
        return false;
    }
    if (!shadowdiff_compare(reference, test, &s, &out->current, NULL)) {
        out->problem = out->current.problem;
        return false;
    }
    if (!shadowdiff_check_camera(previous_reference, previous_test, previous_settings.reference_name,
                                 previous_settings.test_name) ||
        !shadowdiff_check_camera(reference, test, r_name, t_name) ||
        !shadowdiff_check_size(previous_reference, reference, previous_settings.reference_name, r_name) ||
        !shadowdiff_check_objects(previous_reference, reference, previous_settings.reference_name, r_name))
        return false;
    int receiver = s.receiver ? shadowdiff_find_object(reference, s.receiver) : -1;
    shadowdiff_count_shimmer(previous_reference, previous_test, reference, test, receiver, shadowdiff_min_cosine(&s),
                             out);
    if (out->followed == 0) {
        fprintf(stderr,
                "shadowdiff: %s and %s: no compared pixel followed to a compared pixel of %s on the same surface: "
                "no shimmer figure is given\n",
                r_name, t_name, previous_settings.reference_name);
        out->problem = SHADOWDIFF_PROBLEM_NOTHING_COMPARED;
        return false;
    }
    out->problem = SHADOWDIFF_PROBLEM_NONE;
    out->shimmer_percent = shadowdiff_percent(out->shimmered, out->followed);
    out->truth_changed_percent = shadowdiff_percent(out->truth_changed, out->followed);
    return true;
}

int shadowdiff_magnify_radius(int height) {
    int radius = height / SHADOWDIFF_MAGNIFY_LINES_PER_PIXEL;
    return radius > 1 ? radius : 1;
}

/* Whether an RGBA pixel has kind k's colour. */
static bool shadowdiff_is_kind(const unsigned char *rgba, shadowdiff_pixel k) {
    return memcmp(rgba, shadowdiff_pixel_colors[k], 3) == 0;
}

bool shadowdiff_heatmap_magnify(unsigned char *rgba, int width, int height, int radius) {
    static const shadowdiff_pixel errors[] = {SHADOWDIFF_PIXEL_FALSE_SHADOW, SHADOWDIFF_PIXEL_FALSE_LIT};
    size_t pixels = (size_t)width * (size_t)height;
    unsigned char *kind = malloc(pixels); /* the error kinds before any disc is drawn */
    if (!kind) {
        fprintf(stderr, "shadowdiff: out of memory for a %dx%d heat map's errors\n", width, height);
        return false;
    }
    for (size_t i = 0; i < pixels; i++) {
        kind[i] = SHADOWDIFF_PIXEL_AGREES;
        for (int e = 0; e < 2; e++)
            if (shadowdiff_is_kind(rgba + 4 * i, errors[e]))
                kind[i] = (unsigned char)errors[e];
    }
    for (int e = 0; e < 2; e++)
        for (int y = 0; y < height; y++)
            for (int x = 0; x < width; x++) {
                if (kind[(size_t)y * width + x] != errors[e])
                    continue;
                for (int dy = -radius; dy <= radius; dy++)
                    for (int dx = -radius; dx <= radius; dx++) {
                        int px = x + dx, py = y + dy;
                        if (dx * dx + dy * dy > radius * radius || px < 0 || py < 0 || px >= width || py >= height)
                            continue;
                        memcpy(rgba + 4 * ((size_t)py * width + px), shadowdiff_pixel_colors[errors[e]], 3);
                    }
            }
    free(kind);
    return true;
}
