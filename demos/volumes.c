/* volumes: stencil shadow volumes, z-pass, z-fail and the choice between
 * them, for any mesh: closed, open or non-manifold.
 *
 * Crow, "Shadow algorithms for computer graphics", SIGGRAPH 1977: the space
 * a caster shadows is bounded by polygons (its silhouette swept away from
 * the light, and caps); a point is in shadow when the eye ray to it enters
 * more of those volumes than it leaves. Heidmann (1991) counts in the
 * stencil buffer the volume faces in front of the visible surface, +1 for
 * front faces, -1 for back faces (z-pass): wrong when the eye is inside a
 * volume. Carmack's reverse (Bilodeau & Songy, Carmack 2000; Everitt &
 * Kilgard, "Practical and robust stenciled shadow volumes", 2002) counts
 * the faces behind the surface instead (z-fail), which needs caps; the far
 * ones lie at infinity (w = 0), kept from the far plane by depth clamp.
 * The volumes are built by demos/lib/volume_mesh.h, whose comments are
 * their manual (every triangle its own occluder, Aldridge & Woods 2004).
 * Counts wrap at 256: wrong only behind an exact multiple of 256 triangles
 * (closed meshes: casters).
 *
 * After a depth pre-pass, per light (up to 8): clear the stencil in the
 * screen rectangle of the receivers; draw every caster's volume with colour
 * and depth writes off, both faces counted in one pass (glStencilOpSeparate,
 * wrapping); shade the light where the stencil is 0 (everywhere on objects
 * that receive no shadows), the first light's pass with the ambient term
 * (technique_shade_light), so that one light costs one shading pass.
 * --mode auto (default) takes z-pass, without caps, where
 * volume_mesh_zpass_safe says the volume cannot reach the near-plane
 * rectangle, z-fail with caps elsewhere; --mode zpass with the camera
 * inside a shadow visibly fails (shadows inverted).
 *
 * Options (each also a key): --silhouette gpu finds the sides in a
 * geometry shader (demos/lib/volume_silhouette.h); --extrude reach trims
 * the CPU volumes past the light's reach (volumes_trim); --no-depth-bounds
 * and --no-exact-depth turn off the depth bounds (volumes_depth_bounds)
 * and the exact depth of receivers huge seen from the eye
 * (demos/lib/volume_receivers.h); --overlay, for lectures, shows light 0's
 * volumes, silhouette edges or stencil count as colour. How each caster's
 * volume is drawn, kept or streamed, is demos/lib/volume_draw.h's; the
 * skips that leave volumes out (README, "Skips") are volumes_render's.
 */
#include <GLFW/glfw3.h>
#include <glad/gl.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "depth.h"
#include "technique.h"
#include "volume_draw.h"
#include "volume_overlay.h"
#include "volume_receivers.h"

typedef struct volumes_settings {
    int mode;       /* choice */
    int silhouette; /* choice */
    int overlay;    /* choice */
    int extrude;    /* choice */
    bool no_depth_bounds; /* toggle */
    bool no_exact_depth;  /* toggle */
} volumes_settings;

static const char *const volumes_modes[] = {"auto", "zpass", "zfail", NULL};
static const char *const volumes_silhouettes[] = {"cpu", "gpu", NULL};
static const char *const volumes_overlays[] = {"none", "volumes", "silhouettes", "counts", NULL};
static const char *const volumes_extrusions[] = {"infinity", "reach", NULL};
enum { VOLUMES_AUTO, VOLUMES_ZPASS, VOLUMES_ZFAIL };
enum { VOLUMES_CPU, VOLUMES_GPU };
enum { VOLUMES_EXTRUDE_INFINITY, VOLUMES_EXTRUDE_REACH };
enum { VOLUMES_OVERLAY_NONE, VOLUMES_OVERLAY_VOLUMES, VOLUMES_OVERLAY_SILHOUETTES, VOLUMES_OVERLAY_COUNTS };

/* Every bit of the 8-bit stencil: counts wrap at 256 (see top). */
#define VOLUMES_STENCIL_MASK 0xff

static struct {
    volumes_settings settings;
    volume_draw draw;
    volume_receivers receivers;
    bool *needed;  /* per object: it casts a volume for the light at hand */
    int trim_kept; /* whether the kept volumes are trimmed; -1: none kept yet */
    bool has_depth_bounds; /* GL_EXT_depth_bounds_test */
    /* Light 0, last frame: */
    int zpass_count, zfail_count, built_count, reused_count;
    int huge_count; /* objects counted against their exact depth (volume_receivers.h) */
} volumes;

static const flags_param volumes_params[] = {
    {"mode", "z-pass (no caps) where safe, else z-fail (caps); or force one", GLFW_KEY_Z, FLAGS_CHOICE,
     .index = &volumes.settings.mode, .choices = volumes_modes},
    {"silhouette", "where silhouettes are found: the CPU edge table or a geometry shader", GLFW_KEY_G,
     FLAGS_CHOICE, .index = &volumes.settings.silhouette, .choices = volumes_silhouettes},
    {"overlay", "for lectures: the volumes, the silhouette edges, or the stencil count as colour", GLFW_KEY_V,
     FLAGS_CHOICE, .index = &volumes.settings.overlay, .choices = volumes_overlays},
    {"extrude", "CPU volumes swept to infinity, or trimmed past the light's reach (less fill; shadow edges may "
                "move by rounding)",
     GLFW_KEY_T, FLAGS_CHOICE, .index = &volumes.settings.extrude, .choices = volumes_extrusions},
    {"depth-bounds", "volumes also count where no receiver in the light's reach is (no decision changes)", GLFW_KEY_B,
     FLAGS_TOGGLE, .disabled = &volumes.settings.no_depth_bounds},
    {"exact-depth", "volumes counted against the exact depth of receivers huge seen from the eye (else their "
                    "shadow edges move)",
     GLFW_KEY_E, FLAGS_TOGGLE, .disabled = &volumes.settings.no_exact_depth},
};

/* ---- set-up ---- */

static bool volumes_init(const render_scene *gpu) {
    if (!volume_draw_init(&volumes.draw, gpu) || !volume_receivers_init(&volumes.receivers, gpu))
        return false;
    volumes.needed = calloc((size_t)gpu->scene->object_count, sizeof *volumes.needed);
    if (!volumes.needed) {
        fprintf(stderr, "volumes: out of memory\n");
        return false;
    }
    volumes.trim_kept = -1;
    volumes.has_depth_bounds = GLAD_GL_EXT_depth_bounds_test;
    return true;
}

static void volumes_destroy(void) {
    volume_draw_destroy(&volumes.draw);
    volume_receivers_destroy(&volumes.receivers);
    free(volumes.needed);
    volumes.needed = NULL;
}

/* ---- counting ---- */

/* Counting ops for both faces in one pass, wrapping so that more than 255
 * overlapping volumes still sum right. */
static void volumes_stencil_ops(bool zfail) {
    if (zfail) {
        glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_DECR_WRAP, GL_KEEP);
        glStencilOpSeparate(GL_BACK, GL_KEEP, GL_INCR_WRAP, GL_KEEP);
    } else {
        glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_KEEP, GL_INCR_WRAP);
        glStencilOpSeparate(GL_BACK, GL_KEEP, GL_KEEP, GL_DECR_WRAP);
    }
}

/* Whether volumes end past their light's reach (--extrude reach, key T;
 * volume_mesh_trim_for): the CPU volumes are trimmed past every receiver
 * clipped to the light's range, closed there by far caps, so that they
 * fill less. Off by default: a shadow edge's pixel may flip by the
 * rounding of the shorter sides' depth (test_volumes'
 * test_trimmed_within_bound keeps the trimmed pictures within the bound).
 * Not for forced z-pass, whose count from an eye inside a volume (wrong,
 * for lectures) a trim could change. */
static bool volumes_trim(void) {
    return volumes.settings.extrude == VOLUMES_EXTRUDE_REACH && volumes.settings.mode != VOLUMES_ZPASS;
}

/* Whether the caster with world box [lo, hi] takes z-fail, with caps, for
 * the light (see top). */
static bool volumes_use_zfail(const float lo[3], const float hi[3], const float light[4],
                              const vec3 near_rectangle[4]) {
    if (volumes.settings.mode != VOLUMES_AUTO)
        return volumes.settings.mode == VOLUMES_ZFAIL;
    return !volume_mesh_zpass_safe(lo, hi, light, near_rectangle);
}

/* Whether caster i draws a volume for the hull's light; counted once,
 * drawn or culled. Leaving one out is exact when its count is 0 on every
 * visible receiver. A volume that misses the view has no fragment. A
 * point inside a caster's volume lies beyond the caster on a segment from
 * the light, so outside the hull of the light and the visible receivers'
 * bounds (convex) it contains no visible receiver point: z-fail counts
 * there exactly that, 0, and so does z-pass where it starts from 0, which
 * auto takes z-pass only where volume_mesh_zpass_safe says; forced z-pass
 * keeps casters that may shadow the eye (they count there). */
static bool volumes_caster_needed(const technique_frame *f, const technique_hull *hull, int i, const float light[4],
                                  const vec3 near_rectangle[4]) {
    const scene_object *o = &f->gpu->scene->objects[i];
    if (!o->casts)
        return false;
    float lo[3], hi[3];
    scene_object_world_bounds(o, lo, hi);
    if (f->cull_casters && volume_mesh_misses_view(lo, hi, light, f->view->view_projection)) {
        f->counts->casters_culled[hull->light]++;
        return false;
    }
    if (volumes.settings.mode == VOLUMES_ZPASS && !volume_mesh_zpass_safe(lo, hi, light, near_rectangle)) {
        f->counts->casters_drawn[hull->light]++;
        return true;
    }
    return technique_caster_needed(f, hull, i);
}

/* Where the light's volumes may count (the scissor's rectangle x, y,
 * width, height; the depth bounds, where on) and where caster i's may:
 * the part of that where what its shadow may fall on was seen
 * (technique_caster_seen), an empty rectangle where nowhere. False: the
 * light's own, unchanged (no masks this frame). */
typedef struct volumes_bounds {
    int rect[4];
    bool bounded;
    float depth[2];
} volumes_bounds;

static bool volumes_caster_bounds(const technique_frame *f, const technique_hull *hull, int i,
                                  const volumes_bounds *light, volumes_bounds *out) {
    light_mask_seen seen;
    if (!hull || !technique_caster_seen(f, hull, i, &seen))
        return false;
    *out = *light;
    /* Clamped to the light's rectangle before they become pixels: "seen
     * everywhere" is infinite. */
    for (int k = 0; k < 2; k++) {
        float first = (float)light->rect[k], last = (float)(light->rect[k] + light->rect[2 + k]);
        int lo = (int)floorf(glm_clamp(seen.lo[k], first, last)), hi = (int)ceilf(glm_clamp(seen.hi[k], first, last));
        out->rect[k] = lo;
        out->rect[2 + k] = glm_max(hi - lo, 0);
    }
    out->depth[0] = fmaxf(light->depth[0], seen.lo[2]);
    out->depth[1] = fminf(light->depth[1], seen.hi[2]);
    f->counts->casters_narrowed[hull->light] +=
        (int64_t)out->rect[2] * out->rect[3] < (int64_t)light->rect[2] * light->rect[3];
    return true;
}

static void volumes_use_bounds(const volumes_bounds *b) {
    glScissor(b->rect[0], b->rect[1], b->rect[2], b->rect[3]);
    if (b->bounded)
        glDepthBoundsEXT(b->depth[0], glm_max(b->depth[0], b->depth[1]));
}

/* Stencil = number of volumes of light l around each visible pixel, of
 * the casters `needed` (NULL: every caster), each within its own bounds
 * (volumes_caster_bounds) where hull is given, else the light's. */
static void volumes_count(const technique_frame *f, int l, const float light[4], const bool *needed,
                          const technique_hull *hull, const volumes_bounds *bounds) {
    const scene *s = f->gpu->scene;
    vec3 near_rectangle[4];
    volume_mesh_near_rectangle(f->view->view_projection, near_rectangle);
    int zpass = 0, zfail = 0;
    volumes.draw.built = volumes.draw.reused = 0;
    glEnable(GL_DEPTH_CLAMP); /* far caps at infinity stay in */
    glDisable(GL_CULL_FACE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);
    glDepthFunc(depth_func(f->view, GL_LESS)); /* a surface's own cap, at its depth, counts as behind it */
    glStencilFunc(GL_ALWAYS, 0, VOLUMES_STENCIL_MASK);
    /* Not only casters in view: one outside may cast a volume across it. */
    for (int i = 0; i < s->object_count; i++) {
        if (!s->objects[i].casts || (needed && !needed[i]))
            continue;
        float lo[3], hi[3];
        scene_object_world_bounds(&s->objects[i], lo, hi);
        bool use_zfail = volumes_use_zfail(lo, hi, light, near_rectangle);
        zfail += use_zfail;
        zpass += !use_zfail;
        volumes_stencil_ops(use_zfail);
        /* Forced z-pass from inside a volume counts it on pixels outside
         * it too: that volume keeps the light's bounds (auto takes z-pass
         * only where it is safe). */
        bool counts_inside =
            volumes.settings.mode != VOLUMES_ZPASS || volume_mesh_zpass_safe(lo, hi, light, near_rectangle);
        volumes_bounds own;
        bool narrowed = counts_inside && volumes_caster_bounds(f, hull, i, bounds, &own);
        if (narrowed)
            volumes_use_bounds(&own);
        if (!narrowed || (own.rect[2] > 0 && own.rect[3] > 0))
            volume_draw_caster(&volumes.draw, f, l, i, light, volumes.settings.silhouette == VOLUMES_GPU, use_zfail);
        if (narrowed)
            volumes_use_bounds(bounds);
    }
    glDisable(GL_DEPTH_CLAMP);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (l == 0 && needed) {
        volumes.zpass_count = zpass;
        volumes.zfail_count = zfail;
        volumes.built_count = volumes.draw.built;
        volumes.reused_count = volumes.draw.reused;
    }
}

/* Turns on the depth bounds of the hull's light (volume_mesh_depth_bounds:
 * the visible receivers within its range, hull->lo..hi) where the
 * extension is and the frame's receivers are all there (not cut short),
 * into b; b->bounded false: left off. While counting a light, only pixels
 * whose depth lies within those receivers take stencil updates; no
 * decision changes, as the others keep the cleared count where the light
 * adds 0. */
static void volumes_depth_bounds(const technique_frame *f, const technique_hull *hull, volumes_bounds *b) {
    /* The bounds are window depths of GL's standard convention; with
     * reversed depth they are left off (they only save fill). */
    b->bounded = volumes.has_depth_bounds && !volumes.settings.no_depth_bounds && !f->view->reversed_depth &&
                 f->receiver_count < TECHNIQUE_MAX_RECEIVER_POINTS && !hull->empty &&
                 volume_mesh_depth_bounds(f->view->view_projection, f->receivers, f->receiver_count, hull->lo,
                                          hull->hi, b->depth);
    if (!b->bounded)
        return;
    glEnable(GL_DEPTH_BOUNDS_TEST_EXT);
    glDepthBoundsEXT(b->depth[0], b->depth[1]);
}

/* ---- lighting ---- */

/* Light l is blocked on receivers where a volume counts; the rest take no
 * shadows and are lit everywhere. */
static const technique_stencil_lit volumes_lit = {
    .lit = GL_EQUAL, .blocked = GL_NOTEQUAL, .ref = 0, .mask = VOLUMES_STENCIL_MASK, .receivers_only = true};

/* ---- overlays ---- */

/* The stencil still holds the last light's counts: recount light 0 with
 * every volume (the overlay colours every pixel), then colour them. */
static void volumes_draw_counts(const technique_frame *f, const float light[4]) {
    glEnable(GL_STENCIL_TEST);
    glClear(GL_STENCIL_BUFFER_BIT);
    volumes_count(f, 0, light, NULL, NULL, NULL);
    volume_overlay_counts(&volumes.draw, VOLUMES_STENCIL_MASK);
}

/* ---- the frame ---- */

/* The frame. Receivers huge seen from the eye (a ground 1e5 across) are
 * counted against their exact depth, not the rasterizer's interpolation
 * across them, which moves shadow edges (demos/lib/volume_receivers.h);
 * their shading passes against the pre-pass's depth, drawn again.
 * Skips (README, "Skips"), none of which changes a count on a visible
 * receiver, the only pixels the stencil decides:
 * - casters whose shadow cannot reach a visible receiver draw no volume
 *   (technique_caster_needed: outside the hull of the light and the
 *   visible receivers' bounds; see volumes_caster_needed for why exact);
 * - volumes that miss the view draw none (volume_mesh_misses_view: no
 *   fragment of them would be drawn), counted as culled;
 * - after technique_see, a volume counts only in the pixels and depths
 *   where what its shadow may fall on was seen (technique_caster_seen;
 *   scissor and depth bounds): elsewhere its count is 0 on every visible
 *   pixel;
 * - the CPU volumes are kept per light, built when a caster is first
 *   needed after the light moved and drawn from there until it moves
 *   again (objects never move; volume_draw.h). */
static void volumes_render(const technique_frame *f) {
    const scene *s = f->gpu->scene;
    render_depth_prepass(f->gpu, f->view, f->in_view); /* the depth every pass tests against */
    bool trim_changed = volumes.trim_kept != (int)volumes_trim();
    volumes.trim_kept = volumes_trim();
    for (int l = 0; l < s->light_count; l++)
        if (f->changed.scene || trim_changed || (f->changed.lights & RENDER_LIGHT_BIT(l)))
            volume_draw_forget(&volumes.draw, l);
    vec3 near_rectangle[4];
    volume_mesh_near_rectangle(f->view->view_projection, near_rectangle);
    /* The screen rectangle of every receiver's box, the same for every
     * light: no shadow is counted outside it. */
    int receivers_rect[4];
    volume_mesh_receivers_scissor(s, f->view->view_projection, f->width, f->height, receivers_rect);
    volumes.huge_count = volumes.settings.no_exact_depth ? 0 : volume_receivers_update(&volumes.receivers, f);
    bool exact = volumes.huge_count > 0;
    if (exact && f->seen) /* what is seen, as the volumes are counted against it */
        volume_receivers_depth(&volumes.receivers, f, true);
    technique_see(f);
    for (int l = 0; l < s->light_count; l++) {
        if (!technique_light_on(f, l))
            continue;
        float light[4];
        scene_light_homogeneous(&s->lights[l], light);
        technique_hull hull;
        technique_light_hull(f, l, &hull);
        volume_draw_reach(&volumes.draw, &s->lights[l], volumes_trim());
        for (int i = 0; i < s->object_count; i++)
            volumes.needed[i] = volumes_caster_needed(f, &hull, i, light, (const vec3 *)near_rectangle);
        if (exact)
            volume_receivers_depth(&volumes.receivers, f, true);
        volumes_bounds bounds = {.rect = {receivers_rect[0], receivers_rect[1], receivers_rect[2], receivers_rect[3]}};
        glEnable(GL_SCISSOR_TEST);
        glScissor(receivers_rect[0], receivers_rect[1], receivers_rect[2], receivers_rect[3]);
        glClear(GL_STENCIL_BUFFER_BIT);
        glEnable(GL_STENCIL_TEST);
        volumes_depth_bounds(f, &hull, &bounds);
        volumes_count(f, l, light, volumes.needed, &hull, &bounds);
        if (bounds.bounded)
            glDisable(GL_DEPTH_BOUNDS_TEST_EXT);
        if (exact) { /* the depth the shading passes are equal to */
            glDisable(GL_STENCIL_TEST);
            volume_receivers_depth(&volumes.receivers, f, false);
        }
        /* Its own scissor: objects that take no shadows may lie outside the receivers'. */
        technique_shade_light(f, l, &volumes_lit);
        glDisable(GL_STENCIL_TEST);
    }
    if (technique_ambient_light(f) < 0)
        technique_shade_ambient(f);
    if (volumes.settings.overlay == VOLUMES_OVERLAY_NONE || s->light_count == 0)
        return;
    float light[4]; /* for lectures, over the finished picture: light 0's */
    scene_light_homogeneous(&s->lights[0], light);
    volume_draw_reach(&volumes.draw, &s->lights[0], volumes_trim());
    if (volumes.settings.overlay == VOLUMES_OVERLAY_COUNTS)
        volumes_draw_counts(f, light);
    else
        volume_overlay_shapes(&volumes.draw, f, light, volumes.settings.overlay == VOLUMES_OVERLAY_VOLUMES);
}

static void volumes_describe(char *out, size_t size) {
    int n = snprintf(out, size, "light 0: %d casters z-pass, %d z-fail", volumes.zpass_count, volumes.zfail_count);
    if (n > 0 && (size_t)n < size)
        n += snprintf(out + n, size - (size_t)n, "; volumes built %d, kept %d; all lights' kept %.1f MiB",
                      volumes.built_count, volumes.reused_count, (double)volumes.draw.cache_bytes / VOLUME_DRAW_MIB);
    if (n > 0 && (size_t)n < size)
        n += snprintf(out + n, size - (size_t)n, "; depth bounds %s",
                      !volumes.has_depth_bounds           ? "off (no GL_EXT_depth_bounds_test)"
                      : volumes.settings.no_depth_bounds ? "OFF"
                                                         : "on");
    if (n > 0 && (size_t)n < size) {
        if (volumes.settings.no_exact_depth)
            snprintf(out + n, size - (size_t)n, "; exact depth OFF");
        else
            snprintf(out + n, size - (size_t)n, "; exact depth of %d huge objects", volumes.huge_count);
    }
}

/* The sweep: mode x silhouette path, and the trim. */
static const char *const volumes_bench_configs[] = {
    "", "--mode zpass", "--mode zfail", "--silhouette gpu", "--mode zfail --silhouette gpu", "--extrude reach",
};

const technique volumes_technique = {
    .name = "volumes",
    .title = "stencil shadow volumes (Crow 1977), z-pass and z-fail, any mesh (Aldridge & Woods 2004)",
    .params = volumes_params,
    .param_count = (int)(sizeof volumes_params / sizeof *volumes_params),
    .bench_configs = volumes_bench_configs,
    .bench_config_count = (int)(sizeof volumes_bench_configs / sizeof *volumes_bench_configs),
    .init = volumes_init,
    .render = volumes_render,
    .destroy = volumes_destroy,
    .describe = volumes_describe,
};
