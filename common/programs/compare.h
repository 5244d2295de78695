/* compare: compare mode (`--compare`, key A), the technique beside the
 * ray-traced truth of the same view. The picture is a caption strip
 * across the top, COMPARE_STRIP_LINES of the HUD's lines tall (the app's
 * HUD goes there, over no cell), and four cells below it, each half the
 * picture's width and half the rest of its height:
 *   top left      the technique's frame (the app renders it at the cell's
 *                 size);
 *   top right     the truth (truth.h: Embree in a background thread,
 *                 progressive; or baked, where the build cannot trace),
 *                 as far as it is traced: a row not traced yet repeats
 *                 the nearest traced row above it;
 *   bottom left   shadowdiff's heat map of the technique's decisions
 *                 against the truth traced so far (shadowdiff.h; rows not
 *                 traced yet are black, "no surface", and not compared),
 *                 each error grown to a disc (shadowdiff_heatmap_magnify)
 *                 so that a few wrong pixels show in a hall;
 *   bottom right  the heat map's legend (shadowdiff_pixel_colors and
 *                 names), the figures (misclassified %, false shadow and
 *                 false lit, mean absolute error, compared pixels, and
 *                 the MAE and pixels of each of shadowdiff's classes that
 *                 has pixels) and how far the truth is; its first line
 *                 says how wide the error discs are.
 *
 *   compare c;
 *   compare_create(&c, width, height, &settings, NULL);  the picture's size;
 *                                 a folder of baked truths instead of NULL
 *                                 where the build cannot trace
 *   each frame:
 *     compare_update(&c, &scene, light, capture, wait)   before the frame
 *     ... the technique's frame into a target of c.cell_width x c.cell_height ...
 *     compare_draw(&c, &cell_target)                     into c.picture
 *   compare_decisions_changed(&c)   after anything that changes the
 *                                   technique's decisions but not the view
 *   compare_forget(&c)              before the scene changes or goes
 *   compare_destroy(&c)
 *
 * compare_update asks the truth for the frame's view (a new view restarts
 * it) and takes what is traced; once the truth is of the current view and
 * has rows, the technique's decisions for that view are captured (capture
 * is the app's: capture.h's dump of the cell-sized frame, which renders
 * into the cell's target, hence before the frame) once per view and after
 * compare_decisions_changed, and measured whenever either side changes.
 * With `wait` (headless) it first waits for the whole truth, so the
 * picture is the finished one and the same command gives the same bytes.
 */
#ifndef COMPARE_H
#define COMPARE_H

#include <stdbool.h>

#include "dump.h"
#include "raytrace.h"
#include "shadowdiff.h"
#include "target.h"
#include "truth.h"

/* The technique's decisions for light `light` of the current frame, at
 * the cell's size (capture_dump); false after saying why. */
typedef bool (*compare_capture)(int light, dump_frame *out);

/* The caption strip's height in the HUD's lines (hud.h, at
 * hud_scale_for(the picture's height)). */
#define COMPARE_STRIP_LINES 4

typedef struct compare {
    int strip_height; /* pixels, at the picture's top */
    int cell_width, cell_height;
    target picture; /* the four cells */
    truth truth;
    truth_frame shown;
    unsigned textures[2], framebuffers[2]; /* the truth's and the heat map's cells */
    unsigned char *truth_rgba, *heat_rgba; /* cell-sized, top row first */
    bool *traced;                          /* per row of the truth */
    dump_frame decisions;                  /* the technique's, of request decisions_of */
    long decisions_of;
    bool decisions_stale;
    bool measured; /* result holds figures of decisions against shown */
    shadowdiff_result result;
    bool show_seconds;     /* the truth's time in the legend (the window; not in pictures) */
    const char *bake_into; /* each complete truth also baked there (truth_bake.h); NULL: not */
    long baked_of;         /* the request last baked */
} compare;

/* The caption strip's height for a picture `height` pixels tall. */
int compare_strip_height(int height);
/* False after one line on stderr (nothing to destroy). */
bool compare_create(compare *c, int width, int height, const raytrace_settings *settings, const char *baked_dir);
bool compare_update(compare *c, const scene *s, int light, compare_capture capture, bool wait);
bool compare_draw(compare *c, const target *cell);
void compare_decisions_changed(compare *c);
void compare_forget(compare *c);
void compare_destroy(compare *c);
/* The figures line, "misclassified X % (false shadow A %, false lit B %),
 * mean absolute error E, N pixels compared, umbra MAE U (N px), penumbra
 * MAE P (N px), lit MAE L (N px), truth R/H rows" (a class's MAE "none"
 * where the truth has no pixel of it): what the legend shows and a
 * headless run prints. */
void compare_figures_text(const compare *c, char *text, size_t size);

#endif
