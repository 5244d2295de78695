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
 *
 * Skips: see skips.h.
 */
#ifndef TECHNIQUE_H
#define TECHNIQUE_H

#include <stdbool.h>
#include "camera.h"
#include "flags.h"
#include "render.h"
#include "skips.h"
#include "target.h"

/* What changed since the technique's last frame (technique_host_frame
 * compares): a cache keeps what did not. All set on a technique's first
 * frame and, with --no-cache, on every frame. */
typedef struct technique_changes {
    bool scene;             /* first frame: nothing is cached yet */
    bool camera;            /* the view moved (camera, zoom, frame size) */
    scene_light_set lights; /* SCENE_LIGHT_BIT(l): light l moved, turned or changed reach */
    bool settings;          /* a setting of the technique changed (technique_host_settings_changed) */
} technique_changes;

/* One frame as the frame's owner (technique_host.h) hands it to a
 * technique. */
typedef struct technique_frame {
    const render_scene *gpu; /* gpu->scene holds this frame's lights */
    const camera_view *view;
    int width, height;
    double time; /* seconds */
    technique_changes changed;
    /* What the frame need not draw, and the counts of what that saved
     * (skips.h); skips->scene is gpu->scene. */
    const skips *skips;
    /* An area light's points a technique that samples it adds this frame
     * to the sum the frames before left (progressive, the window's;
     * shading_sample_area_light); 0: every point, from none, so that
     * the same command gives the same picture (headless, the benchmark). */
    int light_points;
    /* The HUD shows its counters (--verbose, F3) or the benchmark measures
     * the frame: a technique also counts what costs a read-back, its
     * shadow rays (technique.rays). Never a decision. */
    bool counters;
    /* The frame the shadow maps are fitted to: NULL, this one. Else the
     * same scene and lights seen from another camera, whose view and
     * receivers (its skips' receivers; nothing else) a fit takes, while
     * everything is still drawn from this frame's (technique_host_frame's
     * fit_view): a map held as the frame before fitted it, so that two
     * pictures of one view differ only by how the fit moved (the
     * benchmark's shimmer). */
    const struct technique_frame *fit;
} technique_frame;

/* Hidden casters and objects. A technique calls this after its depth
 * pre-pass (the framebuffer bound, the camera's depth written): the
 * visible pixels are read (visible.h) for the caster culling that
 * follows, which then also culls a caster whose shadow reaches none of
 * them, however near its box lies to the receivers'
 * (skips_caster_needed; a shadow map's own layers, skips_seen_pixels);
 * each light's rectangle narrows to the tiles it reaches
 * (skips_light_rect); and the objects wholly behind them
 * (visible_box_hidden) leave the skips' in_view and lit_by, so that the
 * shading passes, which test GL_EQUAL against that depth and would draw
 * none of their pixels, skip them (not in a frame with an object huge
 * seen from the eye, whose rasterized depth may stray). Nothing without
 * f->skips->seen. */
void technique_see(const technique_frame *f);

/* The shadow rays of one frame, per pixel of its target: pixels, the
 * lights traced at them (a pixel traced to two lights counts two), the
 * rays cast, and the pixels a first pass marked for the pass that traces
 * (skips.h, marked_pass; 0 without one). */
typedef struct technique_rays {
    long pixels, traced, rays, marked;
} technique_rays;

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
    /* Translucent casters (scene_object's translucent) filter its shadows
     * per channel, as the reference's: its visibility is coloured
     * (capture.h). Else they cast their whole surface's shadow, which
     * technique_host_start says once on stderr. */
    bool coloured_shadows;
    /* Optional: how the technique, as set now, draws an area light (a
     * scene light with radius > 0): a few words for the HUD ("soft: pcss").
     * NULL: it cannot draw soft shadows and draws every light hard from its
     * centre, which technique_host_start says once on stderr and the HUD
     * says for each area light (technique_area_light_text); l is the
     * light's index in the scene. */
    const char *(*area_light)(const scene_light *light, int l);
    /* Optional: a technique that casts shadow rays, those of its last
     * frame that counted them (technique_frame.counters); false where none
     * has since init. */
    bool (*rays)(technique_rays *out);
} technique;

/* What the HUD says of area light `light`, the scene's light l, under t:
 * t's own words, or that it is drawn hard. */
const char *technique_area_light_text(const technique *t, const scene_light *light, int l);

/* Back to defaults, then the flags of `config` ("--filter pcf5
 * --no-offset"), through the command line's parser; prints and returns
 * false on a flag that is not the technique's or a bad value. */
bool technique_apply_config(const technique *t, const char *config);
/* The same, its errors beginning with `who` ("FILE: steps[2].flags")
 * instead of the technique's name and the configuration. */
bool technique_apply_config_as(const technique *t, const char *config, const char *who);
/* What a configuration is called in reports: its label, its flags, or
 * "defaults". */
void technique_config_label(const char *config, char *out, size_t size);
/* "on", "OFF" ("not on this GL" for a toggle whose feature the GL
 * lacks), the choice's name or the number, for the HUD. */
void technique_param_text(const flags_param *p, char *out, size_t size);
/* Whether a setting differs from its default (zero). */
bool technique_param_changed(const flags_param *p);

/* A technique's settings as they stood once (a tour step's, as its flags
 * set them), to say later which of them the window's keys have changed. */
#define TECHNIQUE_MAX_PARAMS 32 /* app_main refuses a technique with more */
typedef struct technique_settings {
    const technique *technique;
    double values[TECHNIQUE_MAX_PARAMS]; /* each parameter's: a toggle's disabled, a choice's index */
} technique_settings;
void technique_settings_save(const technique *t, technique_settings *out);
/* What differs between `saved` and technique t as set now, into out: the
 * technique ("technique volumes") where t is another, else each setting
 * that differs as "NAME VALUE" (technique_param_text's), ", " between
 * them ("constant-bias OFF, filter pcf5"); a toggle whose feature this GL
 * lacks changes nothing drawn and is left out. False, out "", where
 * nothing differs. */
bool technique_settings_changes(const technique_settings *saved, const technique *t, char *out, size_t size);
/* The window's key press: flips a toggle or steps a choice; false if no
 * parameter has the key. */
bool technique_press_key(const technique *t, int key);

/* t->init, then any GL error it raised reported: the caller owns the
 * check, techniques never test for GL errors themselves. */
bool technique_init(const technique *t, const render_scene *gpu);

/* One frame of `t` into `target`, as the app, the gallery and the benchmark
 * all render it: the lights (visibility mode for light visibility_of, or
 * -1) into the uniform block, the target's depth matched to the view's
 * (depth.h), bound and cleared to the background, default state in the
 * view's depth convention, the technique, GL's standard depth again, then
 * any GL error reported.
 * The caller has set f->gpu->scene's lights for this frame. */
bool technique_render_frame(const technique *t, const technique_frame *f, target *target, int visibility_of);

#endif
