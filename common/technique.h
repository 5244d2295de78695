/* technique: the one interface every shadow technique implements, so that
 * the same code runs in its own demo, in the multi-technique window, in the
 * gallery and (later) in comparisons and the benchmark.
 *
 * A technique keeps its state in one static struct in its own file under
 * demos/ and exports one `const technique NAME_technique`. The app calls:
 *   init(gpu)     after a scene is on the GPU: load programs, buffers;
 *   render(frame) each frame, into the bound target (see render.h for the
 *                 state it finds), with the camera and lights of that frame;
 *   destroy()     before another scene or technique takes its place.
 * init returns false after printing why; the app then exits non-zero.
 *
 * Toggles are the technique's on/off features (each on by default: the
 * setting is a `disabled` flag, so a zeroed settings struct is the default).
 * The app turns each into a command-line flag --no-NAME, a key in the
 * window, and a line on the HUD.
 *
 * bench_configs is the technique's parameter sweep for the benchmark: each
 * entry is a set of the technique's own flags ("" = its defaults), applied
 * with technique_apply_config, the same parser the command line uses.
 * destroy() is also called after a failed init.
 *
 * Time comes in as frame->time, never from a clock: frames are
 * deterministic.
 */
#ifndef TECHNIQUE_H
#define TECHNIQUE_H

#include <stdbool.h>
#include "camera.h"
#include "render.h"
#include "target.h"

typedef struct technique_toggle {
    const char *name;  /* flag --no-NAME, and the HUD label */
    const char *help;  /* what turning it off shows */
    int key;           /* GLFW_KEY_* in the window */
    bool *disabled;    /* in the technique's settings */
} technique_toggle;

typedef struct technique_frame {
    const render_scene *gpu; /* gpu->scene holds this frame's lights */
    const camera_view *view;
    int width, height;
    double time; /* seconds */
} technique_frame;

typedef struct technique {
    const char *name;  /* "planar": its binary, its registry key */
    const char *title; /* one line for --help and the HUD */
    const technique_toggle *toggles;
    int toggle_count;
    const char *const *bench_configs;
    int bench_config_count;
    bool (*init)(const render_scene *gpu);
    void (*render)(const technique_frame *frame);
    void (*destroy)(void);
} technique;

/* Applies one of the technique's own flags ("--no-NAME"); false if the
 * flag is not one of its. */
bool technique_apply_flag(const technique *t, const char *flag);
/* Back to defaults, then the space-separated flags of `config`; prints
 * "TECHNIQUE: unknown flag in configuration" and returns false on a flag
 * that is not the technique's. */
bool technique_apply_config(const technique *t, const char *config);

/* One frame of `t` into `target`, as the app, the gallery and the benchmark
 * all render it: the lights (visibility mode for light visibility_of, or
 * -1) into the uniform block, the target bound and cleared to the
 * background, default state, the technique, then any GL error reported.
 * The caller has set f->gpu->scene's lights for this frame. */
bool technique_render_frame(const technique *t, const technique_frame *f, const target *target,
                            int visibility_of);

#endif
