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
#include "area_light.h"
#include "camera.h"
#include "flags.h"
#include "frustum.h"
#include "light_mask.h"
#include "render.h"
#include "soft_visibility.h"
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
     * technique_see narrowed it to TECHNIQUE_NARROW_LIGHT_SHARE of the
     * frame or less (technique_light_pass). */
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
 * technique_light_pass); receivers: the visible receivers' points, for
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
     * (technique_light_pass). */
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
     * technique_sample_area_light); 0: every point, from none, so that
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
/* A light whose rectangle covers at most this share of the frame is
 * narrowed enough to pay for the read-back of technique_see, and split
 * from the one shading pass (technique_split_lights). */
#define TECHNIQUE_NARROW_LIGHT_SHARE 0.25
/* Light l's pixel rectangle (x, y, width, height), outside of which it
 * adds exactly 0: f->light_rect[l], narrowed after technique_see to the
 * tiles whose slabs the light reaches (its range, a spot's cone): every
 * visible point lies in a slab of its own tile. */
const int *technique_light_rect(const technique_frame *f, int l);
/* Scissors to light l's rectangle (technique_light_rect; scissor test
 * on) and returns the objects its lighting pass draws: what it reaches. */
const bool *technique_light_pass(const technique_frame *f, int l);

/* The shading passes, after render_depth_prepass of f->in_view (depth
 * test GL_EQUAL, depth writes off), two ways. A technique that can shade
 * every light at once (the shadow maps) draws one pass of every object in
 * view, unscissored and unblended (technique_shade_all_begin). The
 * stencil techniques shade one light per pass (technique_shade_light):
 * every visible pixel is shaded once per light that reaches it, and the
 * ambient term rides on the first light's pass (technique_ambient_light)
 * rather than a pass of its own, so a one-light scene is shaded once. That
 * pass draws every object in view, unscissored (a light adds exactly 0
 * beyond its range, outside a spot's cone and outside its rectangle),
 * without blending; the others add their light (GL_ONE, GL_ONE) on what
 * they reach, in their rectangle. Sums are quantized to the target's 8
 * bits once per pass, so a pixel's colour may differ by one step from a
 * single-pass picture of the same lights; decisions do not. */
/* The light whose shading pass also draws the ambient term: the first that
 * is on; -1 when none is (technique_shade_ambient). */
int technique_ambient_light(const technique_frame *f);
/* The one shading pass's state; returns the objects it draws: every one
 * in view. */
const bool *technique_shade_all_begin(const technique_frame *f);
/* The lights on whose rectangle covers at most TECHNIQUE_NARROW_LIGHT_SHARE
 * of the frame, which the one shading pass leaves to passes of their own,
 * for a shader that pays for every light it holds on every pixel (one
 * whose lights are fixed when it is compiled: llvmpipe runs both sides of
 * a branch). The one pass then shades every object in view with the other
 * lights; light l's own pass (technique_light_pass), with every light,
 * shades again what it reaches in its rectangle. A light adds exactly 0
 * outside its rectangle, so each pixel's sum is the one pass's with every
 * light, bit for bit. None with the skips off (every rectangle the whole
 * frame). */
unsigned technique_split_lights(const technique_frame *f);
/* The frame's only shading pass when no light is on: the ambient term on
 * every object in view. */
void technique_shade_ambient(const technique_frame *f);
/* Where a stencil says a light is blocked: a pixel is lit where the test
 * `lit` (GL_EQUAL, GL_NOTEQUAL) of (stencil & mask) against ref passes,
 * blocked where `blocked` (its complement) does. receivers_only: objects
 * that take no shadows ("receives": false) are lit whatever the stencil. */
typedef struct technique_stencil_lit {
    unsigned lit, blocked;
    int ref;
    unsigned mask;
    bool receivers_only;
} technique_stencil_lit;
/* Light l's shading pass through such a stencil (see above); where the
 * ambient light is blocked, the ambient term alone. Leaves the stencil
 * test on, blending and the scissor test off. */
void technique_shade_light(const technique_frame *f, int l, const technique_stencil_lit *stencil);
/* Light l's disk (area_light.h) for the techniques that sample it with
 * one set of points for every pixel: facing the middle of the scene's
 * receivers (the origin where none is), so that the points stay where
 * they are while the light does, whatever the camera. */
void technique_area_light_frame(const technique_frame *f, int l, area_light_frame *frame);
/* Light l's visibility from `samples` of its points (area_light_sample_ball
 * of technique_area_light_frame) into v's sum: for each point k not yet
 * in it, `count` leaves the stencil as for a hard light at that point,
 * and the point is added where `lit` passes. In the order
 * area_light_progressive_index gives; f->light_points of them per frame,
 * the sum kept while neither the camera, the light, the scene nor a
 * setting changes, or with f->light_points 0 every point from none. A
 * frame with f->light_points in which any of those changed counts the
 * light's centre alone (k TECHNIQUE_LIGHT_CENTRE), the hard technique's
 * picture, so that a moving view shows the hard shadow, not one point's;
 * the sum starts from none on the next. False, after one line on stderr,
 * when v cannot be made for the bound target. Leaves the stencil test
 * off. */
typedef void (*technique_count_point)(const technique_frame *f, int l, int k, const float point[4]);
/* The k a technique's count takes for the light's centre (a hard light). */
#define TECHNIQUE_LIGHT_CENTRE (-1)
bool technique_sample_area_light(const technique_frame *f, int l, int samples, soft_visibility *v,
                                 const technique_stencil_lit *lit, technique_count_point count);
/* Light l's shading pass with its visibility accumulated in v
 * (soft_visibility.h) instead of a stencil: its unshadowed light times
 * the fraction, on every object but those that take no shadows where
 * receivers_only. Leaves blending and the scissor test off. */
void technique_shade_light_soft(const technique_frame *f, int l, const soft_visibility *v, bool receivers_only);

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
