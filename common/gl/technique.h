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
 * Skips: see technique_frame.
 */
#ifndef TECHNIQUE_H
#define TECHNIQUE_H

#include <stdbool.h>
#include "camera.h"
#include "flags.h"
#include "frustum.h"
#include "light_mask.h"
#include "render.h"
#include "target.h"
#include "visible.h"

/* What changed since the technique's last frame (technique_host_frame
 * compares): a cache keeps what did not. All set on a technique's first
 * frame and, with --no-cache, on every frame. */
typedef struct technique_changes {
    bool scene;      /* first frame: nothing is cached yet */
    bool camera;     /* the view moved (camera, zoom, frame size) */
    unsigned lights; /* RENDER_LIGHT_BIT(l): light l moved, turned or changed reach */
    bool settings;   /* a setting of the technique changed (technique_host_settings_changed) */
} technique_changes;

/* What the skips saved this frame, for the HUD and --verbose: the host
 * fills lights_skipped, techniques the rest (casters per light: those
 * that cast into the light's map or volume, and those culled). */
typedef struct technique_counts {
    int lights_skipped;
    int casters_drawn[SCENE_MAX_LIGHTS], casters_culled[SCENE_MAX_LIGHTS];
    /* Of the culled: those only the masks of what is seen culled; of the
     * drawn: those the masks kept to a smaller part of the frame
     * (technique_caster_seen). */
    int casters_hidden[SCENE_MAX_LIGHTS], casters_narrowed[SCENE_MAX_LIGHTS];
    int objects_hidden; /* in view, behind what the pre-pass shows (technique_see) */
    /* RENDER_LIGHT_BIT(l): a pass of light l drew in its rectangle as
     * technique_see narrowed it to SHADING_NARROW_LIGHT_SHARE of the
     * frame or less (shading_light_pass). */
    unsigned lights_narrowed;
    int layers_rendered, layers_reused; /* map layers: a cube map has six */
} technique_counts;

/* The receivers the camera sees: the corners of the part of each visible
 * receiver's box inside the view frustum. Enough for a few hundred boxes. */
#define TECHNIQUE_MAX_RECEIVER_POINTS 16384
/* The most corners of one box's part inside a frustum: its 8 and the
 * frustum's 8, and where each one's 12 edges cross the other's 6 faces. */
#define TECHNIQUE_MAX_PART_POINTS (8 + 8 + 2 * 12 * 6)

/* What the camera's depth pre-pass shows (technique_see): the visible
 * pixels' slabs and, made on a light's first technique_light_hull, the
 * masks of where they lie as that light sees them. The host's; a frame
 * points at it. */
typedef struct technique_seen {
    bool read; /* this frame's pixels are read */
    visible pixels;
    /* The host's in_view and lit_by of this frame, which technique_see
     * clears of the objects hidden behind what it read. */
    bool *in_view, *lit_by[SCENE_MAX_LIGHTS];
    /* Light l's pixels: its frame rectangle narrowed to the tiles whose
     * slabs it reaches (technique_light_rect). */
    int light_rect[SCENE_MAX_LIGHTS][4];
    unsigned masks_made; /* RENDER_LIGHT_BIT(l): light l's masks */
    int mask_count[SCENE_MAX_LIGHTS];
    light_mask masks[SCENE_MAX_LIGHTS][LIGHT_MASK_MAX_LAYERS];
} technique_seen;

/* Skips. The frame's owner (technique_host.h: the app and the
 * benchmark) works out per frame what a technique need not do, and hands
 * it over in the frame; none may change a pixel. in_view: the objects the
 * camera passes draw (view culling); lights, lit_by and light_rect: the
 * lights that reach anything visible, and per light the objects and
 * pixels its lighting pass needs (light reach; technique_light_on,
 * shading_light_pass); receivers: the visible receivers' points, for
 * fitting and for caster culling (technique_light_hull,
 * technique_caster_needed, when cull_casters), and what the depth
 * pre-pass shows (technique_see: hidden casters and objects); changed:
 * what moved since the technique's last frame, which its caches obey (all
 * of it on a first frame and with --no-cache). A technique fills counts
 * for the HUD. */
typedef struct technique_frame {
    const render_scene *gpu; /* gpu->scene holds this frame's lights */
    const camera_view *view;
    /* Object i meets this frame's view (render_cull_view; all true with
     * culling off; NULL: all): a technique culls its camera passes with
     * it (render_draw_objects), never a pass that sees from elsewhere. */
    const bool *in_view;
    /* The lights that reach a visible object (scene_light_reaches_box);
     * every light with --no-light-reach. A technique renders neither a
     * shadow pass nor a lighting pass for the others: they add exactly 0
     * to every visible pixel (technique_light_on). */
    unsigned lights;
    /* Per light on: the objects in view that it reaches (in_view without
     * the skip), and the pixel rectangle (x, y, width, height) outside of
     * which it adds 0 (its range's screen bounds; the whole frame without
     * a range or the skip). Its lighting pass needs no more
     * (shading_light_pass). */
    const bool *lit_by[SCENE_MAX_LIGHTS];
    int light_rect[SCENE_MAX_LIGHTS][4];
    const float (*receivers)[3];
    int receiver_count;
    float receivers_lo[3], receivers_hi[3]; /* their bounds; empty (lo > hi) when none */
    bool cull_casters;                      /* technique_caster_needed culls (--no-caster-cull: never) */
    /* Without --no-hidden-cull, unless the skip sleeps
     * (technique_host.h): where technique_see keeps what the
     * pre-pass shows (its masks cull casters only with cull_casters);
     * else NULL. */
    technique_seen *seen;
    technique_changes changed;
    technique_counts *counts;
    int width, height;
    double time; /* seconds */
    /* An area light's points a technique that samples it adds this frame
     * to the sum the frames before left (progressive, the window's;
     * shading_sample_area_light); 0: every point, from none, so that
     * the same command gives the same picture (headless, the benchmark). */
    int light_points;
    /* The frame the shadow maps are fitted to: NULL, this one. Else the
     * same scene and lights seen from another camera, whose view and
     * receivers (and nothing else) a fit takes, while everything is still
     * drawn from this frame's (technique_host_frame's fit_view): a map
     * held as the frame before fitted it, so that two pictures of one
     * view differ only by how the fit moved (the benchmark's shimmer). */
    const struct technique_frame *fit;
} technique_frame;

/* Light l reaches the view this frame. */
bool technique_light_on(const technique_frame *f, int l);
/* Light l's pixel rectangle (x, y, width, height), outside of which it
 * adds exactly 0: f->light_rect[l], narrowed after technique_see to the
 * tiles whose slabs the light reaches (its range, a spot's cone): every
 * visible point lies in a slab of its own tile. */
const int *technique_light_rect(const technique_frame *f, int l);

/* Hidden casters and objects. A technique calls this after its depth
 * pre-pass (the framebuffer bound, the camera's depth written): the
 * visible pixels are read (visible.h) for the caster culling that
 * follows, which then also culls a caster whose shadow reaches none of
 * them, however near its box lies to the receivers'
 * (technique_caster_needed; a shadow map's own layers,
 * technique_seen_pixels); and the objects wholly behind them
 * (visible_box_hidden) leave f->in_view and f->lit_by, so that the
 * shading passes, which test GL_EQUAL against that depth and would draw
 * none of their pixels, skip them (not in a frame with an object huge
 * seen from the eye, whose rasterized depth may stray). Nothing without
 * f->seen. */
void technique_see(const technique_frame *f);
/* The slabs technique_see read this frame; NULL when it read none. */
const visible *technique_seen_pixels(const technique_frame *f);

/* Caster culling for one light: the hull of the light and the visible
 * receivers it can reach (their bounds, clipped to its range), outside
 * which a caster shadows nothing the camera sees (frustum_light_hull);
 * after technique_see, also the light's masks of the visible pixels
 * within those bounds (light_mask.h: the layers of light_mask_layers),
 * which a caster's box must reach as well. */
typedef struct technique_hull {
    int light;
    bool empty;  /* no visible receiver in reach: no caster is needed */
    vec3 lo, hi; /* the visible receivers' bounds clipped to the light's range (unless empty) */
    vec4 planes[FRUSTUM_HULL_MAX_PLANES];
    int plane_count;
    float margin;            /* world units: FRUSTUM_BOX_TOLERANCE of the hull's size */
    const light_mask *masks; /* NULL: none (no technique_see this frame) */
    int mask_count;
} technique_hull;
void technique_light_hull(const technique_frame *f, int light, technique_hull *out);
/* The hull of one point of light l's area (homogeneous, world) and the
 * visible receivers the light reaches; without masks (those are of what
 * the centre sees). */
void technique_point_hull(const technique_frame *f, int light, const float point[4], technique_hull *out);
/* Object i casts and its shadow may reach a visible receiver for the
 * hull's light (always, when f->cull_casters is off); counts it, drawn or
 * culled (and hidden, where only the masks culled it), in f->counts. */
bool technique_caster_needed(const technique_frame *f, const technique_hull *hull, int object);

/* Where object's shadow for the hull's light may fall on what is seen:
 * the union of the pixels (x, y) and window depths (z) of the visible
 * slabs in the mask cells its box reads, into *out (empty: nowhere).
 * False without masks (no technique_see this frame): anywhere. Exact as
 * light_mask_box_read: every visible point in its shadow lies there. */
bool technique_caster_seen(const technique_frame *f, const technique_hull *hull, int object, light_mask_seen *out);

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
    /* Optional: how the technique, as set now, draws an area light (a
     * scene light with radius > 0): a few words for the HUD ("soft: pcss").
     * NULL: it cannot draw soft shadows and draws every light hard from its
     * centre, which technique_host_start says once on stderr and the HUD
     * says for each area light (technique_area_light_text); l is the
     * light's index in the scene. */
    const char *(*area_light)(const scene_light *light, int l);
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
/* "on", "OFF", the choice's name or the number, for the HUD. */
void technique_param_text(const flags_param *p, char *out, size_t size);
/* Whether a setting differs from its default (zero). */
bool technique_param_changed(const flags_param *p);
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
