/* app: main, command-line flags, the frame loop and the gallery, shared by
 * every program (common/main_single.c hosts one technique, main_registry.c
 * all of them).
 *
 * Common flags: --backend auto|glfw|egl|osmesa, --size WxH (1280x720),
 * --scene PATH (assets/scenes/simple.json), --frames N, --screenshot PATH.png,
 * --shader-dir DIR, --technique NAME, --motion static|light|camera,
 * --animate, the skips (--no-skip, --no-view-cull, --no-light-reach,
 * --no-caster-cull, --no-cache: technique.h), the HUD (--hud: in headless
 * pictures too; --hud-scale N, --hud-compact: hud.h), --verbose, --help,
 * --flags-markdown (every flag and key as the README's tables), and
 * --gallery DIR SCENE... (every technique on every scene, to
 * DIR/TECHNIQUE_SCENE.png), --tour FILE (a tour file, tour.h: its steps
 * one by one, stepped by keys in the window, every one headless). Each technique parameter adds its flag
 * (--no-NAME for a toggle); all are one flags_param table (flags.h). An
 * unknown flag's error names the programs of `elsewhere` that have it.
 *
 * A run with --frames, --screenshot or --gallery is headless (auto picks
 * EGL, then OSMesa); otherwise auto opens a window when a display is there.
 * Headless frame i is rendered at time i/60 s.
 *
 * Exit status: 0 success, 1 a run-time error (scene, model, shader, GL,
 * file), 2 a bad command line. Every error is one line on stderr.
 */
#ifndef APP_H
#define APP_H

#include "technique.h"

/* The window's HUD ends its last line with this while the keys' help is
 * hidden (H); a headless picture's HUD has none. */
#define APP_HELP_HINT "   H: help"

int app_main(int argc, char **argv, const technique *const *techniques, int technique_count,
             const flags_elsewhere *elsewhere, int elsewhere_count);

#endif
