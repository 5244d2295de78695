/* shadowdiff: how far a technique's shadows are from the ray-traced
 * reference, pixel by pixel, from two dumps (dump.h) of the same scene,
 * camera, size and light.
 *
 * The two dumps must agree on width and height, light_index, the light
 * (w exactly, x, y, z within 1e-4 of the light vector's length), and the
 * objects (count and names); otherwise shadowdiff_compare prints one line
 * naming both dumps and the difference, and returns false.
 *
 * A pixel is compared when all of these hold (the same rules for every
 * technique, so that none can look better by comparing fewer pixels):
 *   - both dumps see a surface there (ids >= 0 in both);
 *   - their depths agree within a thousandth: |d_test - d_ref| <= 0.001 * d_ref
 *     (otherwise they see different surfaces, e.g. at a silhouette);
 *   - the reference's surface faces the light: N . L > sin(grazing), N the
 *     reference normal, L towards the light from the reference position
 *     (light.xyz - position for a point or spot light, w = 1; light.xyz
 *     for a directional one, w = 0), both unit; grazing is 0 unless the
 *     settings say otherwise, and at least FLT_EPSILON (the float
 *     normal's own precision). A surface turned away is dark by shading
 *     alone, whatever a technique decides there, and so is one exactly
 *     edge-on (a ground in the plane of a point light on it), whose
 *     N . L the rounding of the reference's hit points makes a few ulps
 *     either way, pixel by pixel. A surface within a few
 *     degrees of edge-on takes almost no light and is a silhouette seen from
 *     the light, where a shadow decision is ill-conditioned for every
 *     technique; sweeps of light directions, which meet such surfaces by
 *     the dozen, may leave them out with `grazing`;
 *   - with a receiver: both ids are that object's index.
 *
 * A compared pixel is lit where its visibility is >= 0.5. It is a
 *   false shadow  where the reference is lit and the test is not (acne,
 *                 overgrown shadows), and
 *   false lit     where the reference is shadowed and the test is lit
 *                 (light leaks, peter-panning);
 * misclassified counts both. The percentages are of the compared pixels;
 * mean_abs_error is the mean of |v_ref - v_test| over them.
 *
 * Below: the classes of compared pixels (shadowdiff_class), the cases
 * without a figure (shadowdiff_compare), shimmer (shadowdiff_shimmer) and
 * the heat map (shadowdiff_pixel).
 */
#ifndef SHADOWDIFF_H
#define SHADOWDIFF_H

#include <stdbool.h>
#include <stddef.h>

#include "dump.h"

#define SHADOWDIFF_LIT_THRESHOLD 0.5f
/* The classes' bounds on the reference visibility (shadowdiff_class): at or
 * below the first the umbra, at or above the second the lit class. The
 * 1/32 at either end keeps a pixel where a few of the reference's light
 * samples (256 by default) are hidden, at the rim of a penumbra, in the
 * class it all but belongs to. */
#define SHADOWDIFF_UMBRA_MAX_VISIBILITY (1.0f / 32)
#define SHADOWDIFF_LIT_MIN_VISIBILITY (31.0f / 32)
/* What the reports print for the MAE of a class with no pixel. */
#define SHADOWDIFF_NO_FIGURE "none"
/* The heat map's grey for agreeing pixels, from the reference's shadow to
 * its light: from 96, so that agreeing shadow stays apart from "not
 * compared". */
#define SHADOWDIFF_AGREES_GREY_SHADOWED 96
#define SHADOWDIFF_AGREES_GREY_LIT 255
#define SHADOWDIFF_DEPTH_TOLERANCE 0.001
#define SHADOWDIFF_LIGHT_TOLERANCE 1e-4
#define SHADOWDIFF_CAMERA_TOLERANCE 1e-4
/* How far a followed point's frame-0 position may lie from its frame-1
 * one, as a fraction of its distance from the eye: half a pixel's
 * footprint on a surface seen within about 80 degrees of head-on at
 * 640x360 (a pixel is about 1/400 of the distance there), far less than
 * the jump to another surface that a disocclusion makes. */
#define SHADOWDIFF_SHIMMER_POSITION_TOLERANCE 0.01

typedef struct shadowdiff_settings {
    const char *receiver;       /* object name; NULL: every object */
    const char *reference_name; /* for messages (the dump directory); NULL: "reference" */
    const char *test_name;      /* NULL: "test" */
    /* shadowdiff_shimmer's previous frame, for messages; NULL: "previous
     * reference", "previous test" */
    const char *previous_reference_name, *previous_test_name;
    double grazing_degrees; /* also skip surfaces within this of edge-on to the light */
} shadowdiff_settings;

typedef enum shadowdiff_problem {
    SHADOWDIFF_PROBLEM_NONE,
    SHADOWDIFF_PROBLEM_MISMATCH,
    SHADOWDIFF_PROBLEM_NOT_FINITE,
    SHADOWDIFF_PROBLEM_NOTHING_COMPARED,
} shadowdiff_problem;

/* The heat map (RGBA, top row first, opaque) shows
 *   red  (255, 0, 0)    false shadow
 *   blue (0, 0, 255)    false lit
 *   grey 96..255        compared and agreeing, by the reference visibility
 *                       (lighter where lit)
 *   dark grey (40)      not compared
 *   black               no surface in the reference
 * Each pixel's kind; compared pixels are AGREES and after. */
typedef enum shadowdiff_pixel {
    SHADOWDIFF_PIXEL_NO_SURFACE,
    SHADOWDIFF_PIXEL_NOT_COMPARED,
    SHADOWDIFF_PIXEL_AGREES,
    SHADOWDIFF_PIXEL_FALSE_SHADOW,
    SHADOWDIFF_PIXEL_FALSE_LIT,
    SHADOWDIFF_PIXEL_KIND_COUNT
} shadowdiff_pixel;

/* The heat map's colour of each kind (AGREES: its lit end; shadowed
 * agreeing pixels are darker, down to SHADOWDIFF_AGREES_GREY_SHADOWED)
 * and its name, for legends: the one definition the map and every
 * legend of it use. */
extern const unsigned char shadowdiff_pixel_colors[SHADOWDIFF_PIXEL_KIND_COUNT][3];
extern const char *const shadowdiff_pixel_names[SHADOWDIFF_PIXEL_KIND_COUNT];
/* The kinds in the order a legend lists them: the errors first. */
extern const shadowdiff_pixel shadowdiff_legend_kinds[SHADOWDIFF_PIXEL_KIND_COUNT];

/* Misclassified % cannot see a soft shadow drawn hard or a hard one drawn
 * soft: only the side of 0.5 counts. So the compared pixels are also
 * split into classes by the REFERENCE's visibility v alone (whatever the
 * test says there):
 *   umbra     v <= SHADOWDIFF_UMBRA_MAX_VISIBILITY (1/32): no light, or
 *             almost none, reaches the point (outside a spot light's
 *             cone too);
 *   lit       v >= SHADOWDIFF_LIT_MIN_VISIBILITY (31/32): all of it, or
 *             almost all;
 *   penumbra  in between: part of an area light is hidden.
 * Each class has its pixel count and its MAE, the mean of |v_ref - v_test|
 * over that class's pixels (class_pixels, class_mae; the classes
 * partition the compared pixels, so the counts sum to `compared` and the
 * three MAEs weighed by their counts to mean_abs_error):
 *   the umbra's MAE is light leaking or bleeding into full shadow
 *             (peter-panning, a shadow filtered too wide);
 *   the lit class's MAE is acne and over-darkening of fully lit surfaces
 *             (bias too small, a shadow grown or blurred outwards);
 *   the penumbra's MAE is how well a soft shadow is drawn: a hard edge
 *             through a penumbra whose visibility ramps evenly from 0 to 1
 *             is off by 1/4 on average there, even where it sits on the
 *             0.5 line and misclassifies nothing.
 * A class with no pixel has no MAE: class_mae is 0 there and the reports
 * print "none" (JSON null), since a 0 would read as perfect. A hard
 * reference (point, spot or directional light without a radius) has
 * visibilities of exactly 0 and 1, so its penumbra is always empty. */
typedef enum shadowdiff_class {
    SHADOWDIFF_CLASS_UMBRA,
    SHADOWDIFF_CLASS_PENUMBRA,
    SHADOWDIFF_CLASS_LIT,
    SHADOWDIFF_CLASS_COUNT
} shadowdiff_class;
/* The class of a pixel whose reference visibility is v (by the bounds
 * SHADOWDIFF_UMBRA_MAX_VISIBILITY and SHADOWDIFF_LIT_MIN_VISIBILITY). */
shadowdiff_class shadowdiff_class_of(float v);

/* Each class's name ("umbra", "penumbra", "lit"): the one definition the
 * reports' labels and keys use. */
extern const char *const shadowdiff_class_names[SHADOWDIFF_CLASS_COUNT];

typedef struct shadowdiff_result {
    shadowdiff_problem problem; /* NONE exactly when shadowdiff_compare returns true */
    long compared;
    long false_shadow, false_lit;
    double false_shadow_percent, false_lit_percent, misclassified_percent;
    double mean_abs_error;
    long class_pixels[SHADOWDIFF_CLASS_COUNT]; /* of compared, by the reference's visibility */
    double class_mae[SHADOWDIFF_CLASS_COUNT];  /* over the class's pixels; 0 where it has none */
    /* Coloured visibility (dump.h's visibility_rgb: a scene with
     * translucent casters), where both dumps have it: the mean of
     * |v_ref - v_test| of each channel, red, green, blue, over the
     * compared pixels; the classes and decisions above read the one
     * figure. */
    bool coloured;
    double channel_mae[3];
} shadowdiff_result;

/* No figure is given (shadowdiff_compare prints one line naming the dumps
 * and returns false, with `problem` saying why) when
 *   - the dumps disagree as above, or the receiver is unknown (MISMATCH);
 *   - a value the rules read is NaN or infinite (NOT_FINITE): an id
 *     anywhere, or, where that dump sees a surface (id >= 0), its depth or
 *     visibility, or the reference's normal or position. A NaN visibility
 *     would otherwise count as shadow, a NaN depth or normal would leave the
 *     pixel out: a broken technique would get plausible figures;
 *   - no pixel is compared (NOTHING_COMPARED): every percentage would be
 *     0, which reads as a perfect technique. The counts are then 0. */
/* `settings` may be NULL (every object, default names). `heatmap_rgba`
 * may be NULL, else width * height * 4 bytes (not painted after a MISMATCH
 * or NOT_FINITE). Returns whether the figures in `out` mean something; `out`
 * always gets the problem. */
bool shadowdiff_compare(const dump_frame *reference, const dump_frame *test, const shadowdiff_settings *settings,
                        shadowdiff_result *out, unsigned char *heatmap_rgba);

/* A heat map for people, not for counting: each false-shadow and
 * false-lit pixel grown into a disc of `radius` pixels (false lit drawn
 * last), over whatever it covers, so that errors of a few pixels are seen
 * in a lecture hall. shadowdiff_magnify_radius(height) is the disc for a
 * picture `height` pixels tall: one pixel of radius per
 * SHADOWDIFF_MAGNIFY_LINES_PER_PIXEL lines, at least 1. A caller that
 * shows the result says how wide the discs are (2 * radius + 1). False,
 * after one line on stderr, when out of memory. */
#define SHADOWDIFF_MAGNIFY_LINES_PER_PIXEL 100
int shadowdiff_magnify_radius(int height);
bool shadowdiff_heatmap_magnify(unsigned char *rgba, int width, int height, int radius);

/* Adds `frame`'s comparison to `total` as if both were one comparison of
 * all their compared pixels: the counts summed, the percentages and the
 * mean absolute errors (the whole one and each class's) over the sums (the
 * error of several frames, each pixel weighing the same). A zeroed total
 * is the sum of none. */
void shadowdiff_result_add(shadowdiff_result *total, const shadowdiff_result *frame);

/* Class c's MAE of r as text with `decimals` decimals, or
 * SHADOWDIFF_NO_FIGURE where the class has no pixel; returns text. */
const char *shadowdiff_class_mae_text(const shadowdiff_result *r, shadowdiff_class c, int decimals, char *text,
                                      size_t size);

/* Room for one number's text, and for shadowdiff_class_figures_text's. */
#define SHADOWDIFF_FIGURE_TEXT_MAX 32
#define SHADOWDIFF_CLASS_FIGURES_TEXT_MAX 48
/* "CLASS MAE E (N px)", E as shadowdiff_class_mae_text gives it: what
 * compare mode and the gallery show of a class; returns text. */
const char *shadowdiff_class_figures_text(const shadowdiff_result *r, shadowdiff_class c, int decimals, char *text,
                                          size_t size);

typedef struct shadowdiff_shimmer_result {
    shadowdiff_problem problem;                    /* NONE exactly when shadowdiff_shimmer returns true */
    shadowdiff_result previous, current;           /* each frame's own comparison */
    long followed;                                 /* compared pixels of frame 1 followed to frame 0 */
    long shimmered;                                /* of those: the test's decision changed, the truth's did not */
    long truth_changed;                            /* of those: the truth's decision changed */
    double shimmer_percent, truth_changed_percent; /* of followed */
} shadowdiff_shimmer_result;

/* Shimmer (shadowdiff_shimmer): how much a technique's shadows crawl or
 * flicker from one frame to the next where the truth does not, from four
 * dumps: the technique's and the reference's of a previous frame (frame 0)
 * and of the current one (frame 1), the camera (or anything) having moved
 * between them. Each pair is first compared as above (every rule and
 * problem of shadowdiff_compare, each frame's figures kept); the cameras
 * of a pair must agree (eye and target within 1e-4 of their distance, up,
 * fov, near and far within 1e-4 of their size), and the frames must have
 * the same size and objects (MISMATCH otherwise). Then every pixel i1 of
 * frame 1 that the rules compare is followed to frame 0:
 *   - its reference's world position p (position.pfm) is projected by
 *     frame 0's camera (meta.json's "camera", dump.h, with aspect width /
 *     height) to the frame-0 pixel i0 whose square it falls in (pixel
 *     centres as the rasterizer samples them: none rounds by more than
 *     half a pixel); it is not followed where p is behind frame 0's eye or
 *     outside its picture;
 *   - i0 must be compared by the rules too (frame 0's pair, the same
 *     receiver and grazing setting), see the same object as i1 in the
 *     reference and in the test, and its reference position must lie
 *     within SHADOWDIFF_SHIMMER_POSITION_TOLERANCE (a hundredth) of i1's distance
 *     from the eye of p: otherwise the point was hidden (or off the
 *     surface seen) in frame 0, a disocclusion, and is not followed. A
 *     surface seen nearly edge-on from the eye, where half a pixel spans
 *     more than that, is left out the same way.
 * Of the followed pixels, `truth_changed` counts those whose reference
 * decision (lit: visibility >= 0.5) differs between i0 and i1, and
 * `shimmered` those whose test decision differs while the reference's
 * does not:
 *   shimmer % = 100 * shimmered / followed.
 * A pixel whose truth changes counts as not shimmering whatever the test
 * does (a moving light, a shadow edge passing through it). A technique
 * whose decisions are stable in the world, exact or not, scores 0; one
 * whose shadow-map texels slide over the receivers as its fit follows the
 * camera scores the edge pixels that flip. No figure (problem set,
 * false returned) when a pair gives none, as above, or nothing is
 * followed (NOTHING_COMPARED). */
/* Shimmer from frame 0 (previous_*) to frame 1 (above). Returns
 * whether the figures mean something; `out` always gets the problem. */
bool shadowdiff_shimmer(const dump_frame *previous_reference, const dump_frame *previous_test,
                        const dump_frame *reference, const dump_frame *test, const shadowdiff_settings *settings,
                        shadowdiff_shimmer_result *out);

#endif
