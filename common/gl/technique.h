/* technique: the one interface every shadow technique implements, so that
 * the same code runs in its own demo, in the multi-technique window, in the
 * gallery and the benchmark.
 *
 * A technique keeps its state in one static struct in its own file under
 * demos/ and exports one `const technique NAME_technique`. The app calls:
 *   init(gpu)     after a scene is on the GPU: load programs, buffers;
 *   render(frame) each frame, into the bound target (see render.h for the
 *                 state it finds), with the camera and lights of that frame;
 *   destroy()     before another scene or technique takes its place.
 * init returns false after printing why; the app then exits non-zero.
 * GL errors are the caller's to find: technique_init and
 * technique_render_frame check after init and after each frame, and a
 * technique never calls context_gl_ok (which clears what it reports), so
 * no error raised inside a technique goes unseen.
 *
 * Parameters are the technique's settings, a flags_param table (flags.h)
 * whose fields point into its settings struct, where zero means the
 * default; a technique uses the kinds
 *   FLAGS_TOGGLE  a feature, on by default (the field is `disabled`):
 *                 flag --no-NAME, its key flips it;
 *   FLAGS_CHOICE  an index into `choices` (the default first): flag
 *                 --NAME CHOICE, its key steps through them;
 *   FLAGS_NUMBER  a value in [min, max], 0 meaning `fallback`: flag
 *                 --NAME X (no key).
 * The app turns each into a flag, a key in the window and a HUD entry;
 * the benchmark sweeps them through the same parser.
 *
 * bench_configs is the technique's parameter sweep for the benchmark: each
 * entry is a set of the technique's own flags ("" = its defaults), applied
 * with technique_apply_config, the same parser the command line uses; an
 * entry "LABEL: flags" is shown by its label.
 * destroy() is also called after a failed init.
 *
 * Time comes in as frame->time, never from a clock: frames are
 * deterministic.
 */
#ifndef TECHNIQUE_H
#define TECHNIQUE_H

#include <stdbool.h>
#include "camera.h"
#include "flags.h"
#include "render.h"
#include "target.h"

typedef struct technique_frame {
    const render_scene *gpu; /* gpu->scene holds this frame's lights */
    const camera_view *view;
    /* Object i meets this frame's view (render_cull_view; all true with
     * culling off; NULL: all): a technique culls its camera passes with
     * it (render_draw_objects), never a pass that sees from elsewhere. */
    const bool *in_view;
    int width, height;
    double time; /* seconds */
} technique_frame;

typedef struct technique {
    const char *name;  /* "planar": its binary, its registry key */
    const char *title; /* one line for --help and the HUD */
    const flags_param *params;
    int param_count;
    const char *const *bench_configs;
    int bench_config_count;
    bool (*init)(const render_scene *gpu);
    void (*render)(const technique_frame *frame);
    void (*destroy)(void);
    /* Optional: one line of state for the HUD (e.g. a fitted range). */
    void (*describe)(char *out, size_t size);
    /* Optional: the technique's own flags for a second gallery picture,
     * NAME-lecture_SCENE.png (an overlay for lectures), taken from its
     * defaults plus these. */
    const char *gallery_config;
    /* The benchmark's cost floor (demos/unshadowed.c): every ratio is to
     * this technique's frame. One technique in the registry has it. */
    bool cost_floor;
} technique;

/* Back to defaults, then the flags of `config` ("--filter pcf5
 * --no-offset"), through the command line's parser; prints and returns
 * false on a flag that is not the technique's or a bad value. */
bool technique_apply_config(const technique *t, const char *config);
/* What a configuration is called in reports: its label, its flags, or
 * "defaults". */
void technique_config_label(const char *config, char *out, size_t size);
/* "on", "OFF", the choice's name or the number, for the HUD. */
void technique_param_text(const flags_param *p, char *out, size_t size);
/* The window's key press: flips a toggle or steps a choice; false if no
 * parameter has the key. */
bool technique_press_key(const technique *t, int key);

/* t->init, then any GL error it raised reported: the caller owns the
 * check, techniques never test for GL errors themselves. */
bool technique_init(const technique *t, const render_scene *gpu);

/* One frame of `t` into `target`, as the app, the gallery and the benchmark
 * all render it: the lights (visibility mode for light visibility_of, or
 * -1) into the uniform block, the target bound and cleared to the
 * background, default state, the technique, then any GL error reported.
 * The caller has set f->gpu->scene's lights for this frame. */
bool technique_render_frame(const technique *t, const technique_frame *f, const target *target,
                            int visibility_of);

#endif
