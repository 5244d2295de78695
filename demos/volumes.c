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
 * Counts wrap at 256: wrong behind a non-zero multiple of 256 volumes, so
 * where a light's volumes could stack that deep over a pixel (the bound
 * of demos/lib/volume_count_bound.h) they count in a float target instead
 * (demos/lib/volume_wide.h); --counter stencil shows the wrap, --counter
 * float counts there everywhere (demos/lib/volume_counter.h counts).
 *
 * After a depth pre-pass, per light (up to 8): plan which casters count
 * where (volumes_plan_light); clear the stencil in the plan's rectangle;
 * draw their volumes with colour and depth writes off, both faces counted
 * in one pass (glStencilOpSeparate, wrapping); shade the light where the
 * stencil is 0 (everywhere on objects that receive no shadows), the first
 * light's pass with the ambient term (shading_light), so that one
 * light costs one shading pass.
 * --mode auto (default) takes z-pass where volume_mesh_zpass_safe says a
 * volume cannot reach the near-plane rectangle, z-fail elsewhere;
 * eye-count starts z-pass from the volumes that hold the eye
 * (volume_mesh_count_at), exact only under depth clamp; zp-plus (ZP+,
 * Hornus et al. 2005) from each pixel's count on the near plane, the
 * casters drawn onto it from the light (demos/lib/volume_near.h), exact
 * with the volumes clipped there.
 *
 * The options, each a flag and a key, are volumes_params. How each
 * caster's volume is drawn, kept or streamed, is demos/lib/volume_draw.h's;
 * the skips that leave volumes out (README, "Skips") are
 * demos/lib/volume_plan.h's.
 * An area light (--light-samples N) is N hard lights at its points
 * (Brotman & Badler, "Generating soft shadows with a depth buffer
 * algorithm", 1984): each counts with its own plan and kept volumes and
 * adds one to the light's sum where its count is 0; the light is shaded
 * once with the sum over N (soft_visibility.h), in the window over
 * frames (shading_sample_area_light). Or (--soft wedges) the centre's
 * hard shadow, softened by penumbra wedges round every silhouette edge
 * (Assarsson & Akenine-Moller 2003; demos/lib/volume_wedges.h).
 */
#include <GLFW/glfw3.h>
#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "context.h"
#include "depth.h"
#include "shading.h"
#include "technique.h"
#include "volume_draw.h"
#include "volume_overlay.h"
#include "volume_plan.h"
#include "volume_receivers.h"
#include "volume_wedges.h"
#include "volume_counter.h"

typedef struct volumes_settings {
    int mode;             /* choice */
    int silhouette;       /* choice */
    int overlay;          /* choice */
    int extrude;          /* choice */
    bool no_depth_bounds; /* toggle */
    bool no_exact_depth;  /* toggle */
    bool no_depth_clamp;  /* toggle */
    int light_samples;    /* choice: soft_visibility_sample_counts; the first (1) draws an area light hard */
    int soft;             /* choice: volumes_softs */
    int counter;          /* choice: volumes_counters */
} volumes_settings;

/* volume_plan_mode's */
static const char *const volumes_modes[] = {"auto", "zpass", "zfail", "eye-count", "zp-plus", NULL};
static const char *const volumes_silhouettes[] = {"cpu", "gpu", NULL};
static const char *const volumes_overlays[] = {"none", "volumes", "silhouettes", "counts",
                                               NULL}; /* volume_overlay_kind's */
static const char *const volumes_extrusions[] = {"infinity", "reach", NULL};
static const char *const volumes_softs[] = {"samples", "wedges", NULL};
static const char *const volumes_counters[] = {"auto", "stencil", "float", NULL}; /* volume_counter_kind's */
enum { VOLUMES_SOFT_SAMPLES, VOLUMES_SOFT_WEDGES };
enum { VOLUMES_CPU, VOLUMES_GPU };
enum { VOLUMES_EXTRUDE_INFINITY, VOLUMES_EXTRUDE_REACH };

static struct {
    volumes_settings settings;
    volume_draw draw;
    volume_receivers receivers;
    volume_plan_caster *casters; /* per object: the plan of the light at hand */
    volume_plan_caster *group;   /* per object: the wedges' casters of one rule (volume_wedges.h) */
    int trim_kept;               /* whether the kept volumes are trimmed; -1: none kept yet */
    bool has_depth_bounds;       /* GL_EXT_depth_bounds_test */
    bool has_exact_depth;        /* gl_PrimitiveID, which the exact depth's program reads */
    bool has_depth_clamp;        /* GL_DEPTH_CLAMP */
    /* Light 0, last frame: */
    int built_count, reused_count;
    int huge_count;        /* objects counted against their exact depth (volume_receivers.h) */
    int receivers_rect[4]; /* this frame's: every receiver's box on screen, for every light */
    soft_visibility soft;  /* an area light's visibility, sampled or from wedges */
    volume_wedges wedges;
    volume_counter counter;        /* the stencil's counts (volume_counter.h) */
    scene_light_set soft_warned;   /* bit l: light l's area said drawn hard */
    int samples[SCENE_MAX_LIGHTS]; /* this frame's points of light l: 1 drawn hard */
    bool point_reported;           /* the HUD's counts are of this frame's first point */
} volumes;

static const flags_param volumes_params[] = {
    {"mode",
     "z-pass (no caps) where safe, else z-fail (caps); or force one; or z-pass from the count of the volumes that "
     "hold the eye, found on the CPU; or ZP+: z-pass from each pixel's count on the near plane, drawn from the "
     "light (depth clamp off)",
     GLFW_KEY_Z, FLAGS_CHOICE, .index = &volumes.settings.mode, .choices = volumes_modes},
    {"silhouette", "where silhouettes are found: the CPU edge table or a geometry shader", GLFW_KEY_G, FLAGS_CHOICE,
     .index = &volumes.settings.silhouette, .choices = volumes_silhouettes},
    {"overlay", "for lectures: the volumes, the silhouette edges, or the stencil count as colour", GLFW_KEY_V,
     FLAGS_CHOICE, .index = &volumes.settings.overlay, .choices = volumes_overlays},
    {"extrude",
     "CPU volumes swept to infinity, or trimmed past the light's reach (less fill; shadow edges may "
     "move by rounding)",
     GLFW_KEY_T, FLAGS_CHOICE, .index = &volumes.settings.extrude, .choices = volumes_extrusions},
    {"depth-bounds", "volumes also count where no receiver in the light's reach is (no decision changes)", GLFW_KEY_B,
     FLAGS_TOGGLE, .disabled = &volumes.settings.no_depth_bounds, .available = &volumes.has_depth_bounds},
    {"exact-depth",
     "volumes counted against the exact depth of receivers huge seen from the eye (else their "
     "shadow edges move)",
     GLFW_KEY_E, FLAGS_TOGGLE, .disabled = &volumes.settings.no_exact_depth, .available = &volumes.has_exact_depth},
    {"depth-clamp",
     "volumes clamped to the depth range while they count; off: clipped by the near and far planes, as without "
     "depth clamp (the near plane cuts volumes before the eye, z-fail's caps at infinity are lost)",
     GLFW_KEY_C, FLAGS_TOGGLE, .disabled = &volumes.settings.no_depth_clamp, .available = &volumes.has_depth_clamp},
    {"light-samples",
     "points of each area light, each a hard shadow, averaged (Brotman & Badler 1984); 1: hard, from its centre",
     GLFW_KEY_L, FLAGS_CHOICE, .index = &volumes.settings.light_samples, .choices = soft_visibility_sample_counts},
    {"soft",
     "area lights: sampled at --light-samples points; or wedges, the centre's hard shadow softened by penumbra "
     "wedges round its silhouette (Assarsson & Akenine-Moller 2003)",
     GLFW_KEY_W, FLAGS_CHOICE, .index = &volumes.settings.soft, .choices = volumes_softs},
    {"counter",
     "what volumes count in: the 8-bit stencil where a bound says no pixel's count reaches 256, else a float target "
     "(auto); the stencil always (it wraps: a pixel behind 256 volumes reads lit); or the float target always",
     GLFW_KEY_N, FLAGS_CHOICE, .index = &volumes.settings.counter, .choices = volumes_counters},
};

/* ---- set-up ---- */

/* What GPU silhouettes say where the context has no geometry shaders. */
#define VOLUMES_NO_GEOMETRY_SHADERS                                                                                  \
    "volumes: --silhouette gpu needs a geometry shader, which this context lacks (GLSL ES 3.00 and WebGL 2 have "    \
    "none): use --silhouette cpu"

static bool volumes_init(const render_scene *gpu) {
    if (volumes.settings.silhouette == VOLUMES_GPU && !context_current_features()->geometry_shaders) {
        fprintf(stderr, "%s\n", VOLUMES_NO_GEOMETRY_SHADERS);
        return false;
    }
    if (!volume_draw_init(&volumes.draw, gpu) || !volume_receivers_init(&volumes.receivers, gpu))
        return false;
    /* A volume is bounded by a caster's silhouette: it has no holes. */
    if (scene_has_cut_outs(gpu->scene))
        fprintf(stderr, "volumes: cut-out objects (alphaMode MASK) cast the shadow of their whole surface: a "
                        "shadow volume has no holes (the shadow maps cut them out)\n");
    volumes.casters = calloc((size_t)gpu->scene->object_count, sizeof *volumes.casters);
    volumes.group = calloc((size_t)gpu->scene->object_count, sizeof *volumes.group);
    if (!volumes.casters || !volumes.group) {
        fprintf(stderr, "volumes: out of memory\n");
        return false;
    }
    volumes.trim_kept = -1;
    volumes.has_depth_bounds = context_current_features()->depth_bounds;
    volumes.has_exact_depth = context_current_features()->primitive_id;
    volumes.has_depth_clamp = context_current_features()->depth_clamp;
    volumes.soft_warned = 0;
    memset(volumes.samples, 0, sizeof volumes.samples);
    return soft_visibility_init(&volumes.soft) && volume_wedges_init(&volumes.wedges) &&
           volume_counter_init(&volumes.counter, &volumes.draw, gpu->scene->object_count);
}

static void volumes_destroy(void) {
    soft_visibility_destroy(&volumes.soft);
    volume_wedges_destroy(&volumes.wedges);
    volume_counter_destroy(&volumes.counter);
    volume_draw_destroy(&volumes.draw);
    volume_receivers_destroy(&volumes.receivers);
    free(volumes.casters);
    free(volumes.group);
    volumes.casters = volumes.group = NULL;
}

/* ---- the plan: every skip (volume_plan.h) ---- */

/* Whether volumes end past their light's reach (--extrude reach, key T;
 * volume_mesh_trim_for): the CPU volumes are trimmed past every receiver
 * clipped to the light's range, closed there by far caps, so that they
 * fill less. Off by default: a shadow edge's pixel may flip by the
 * rounding of the shorter sides' depth (test_volumes'
 * test_trimmed_within_bound keeps the trimmed pictures within the bound).
 * Not for forced z-pass, whose count from an eye inside a volume (wrong,
 * for lectures) a trim could change. */
static bool volumes_trim(void) {
    return volumes.settings.extrude == VOLUMES_EXTRUDE_REACH &&
           !volume_plan_forced_zpass((volume_plan_mode)volumes.settings.mode);
}

/* Light l's plan (volume_plan.h), for its centre (point NULL), or for
 * point k of its area, whose volumes are kept apart. */
static void volumes_plan_light(const technique_frame *f, int l, int k, const float point[4], volume_plan *plan) {
    volume_plan_light(f, l, point, (volume_plan_mode)volumes.settings.mode, volumes.receivers_rect,
                      volumes.has_depth_bounds && !volumes.settings.no_depth_bounds, volumes.casters, plan);
    plan->cache = volume_draw_cache(l, k);
    plan->reported = l == 0;
}

/* The HUD's figures of the volumes light 0 drew, from the light's first
 * count (volumes_count_begin) to its last (volumes_count_end). */
static void volumes_count_begin(void) { volumes.draw.built = volumes.draw.reused = 0; }
static void volumes_count_end(int l) {
    if (l != 0)
        return;
    volumes.built_count = volumes.draw.built;
    volumes.reused_count = volumes.draw.reused;
}

/* ---- the depth counted against ---- */

/* Receivers huge seen from the eye (a ground 1e5 across) are counted
 * against their exact depth, not the rasterizer's interpolation across
 * them, which moves shadow edges (demos/lib/volume_receivers.h). Where
 * none is, nothing is drawn. */
static void volumes_exact_depth(const technique_frame *f) {
    if (volumes.huge_count > 0)
        volume_receivers_depth(&volumes.receivers, f, true);
}

/* After an exact count the pre-pass's depth again, which the shading
 * passes are equal to; stencil test off while it is drawn. */
static void volumes_prepass_depth(const technique_frame *f) {
    if (volumes.huge_count == 0)
        return;
    glDisable(GL_STENCIL_TEST);
    volume_receivers_depth(&volumes.receivers, f, false);
}

/* ---- lighting ---- */

/* Light l is blocked on receivers where a volume counts; the rest take no
 * shadows and are lit everywhere. */
static const shading_stencil volumes_lit = {
    .lit = GL_EQUAL, .blocked = GL_NOTEQUAL, .ref = 0, .mask = VOLUME_COUNTER_STENCIL_MASK, .receivers_only = true};

/* ---- area lights ---- */

/* Whether a light is drawn by wedges (--soft wedges, an area light). */
static bool volumes_by_wedges(const scene_light *light) {
    return volumes.settings.soft == VOLUMES_SOFT_WEDGES && light->radius > 0;
}

/* Steps 3 and 4 for a plan, against the exact depth where it counts. */
static void volumes_count_plan(const technique_frame *f, const volume_plan *plan) {
    volumes_exact_depth(f);
    volume_counter_clear(&volumes.counter, f, plan);
    volume_counter_begin(&volumes.counter, f, plan);
    volume_counter_draw(&volumes.counter, f, plan);
    volume_counter_end(&volumes.counter, f);
    volumes_prepass_depth(f);
}

/* Point k of light l's area counted as a hard light there (steps 2 to 4
 * with the point's own plan and kept volumes). The casters' counts for
 * the HUD are the first point's. */
static void volumes_count_point(const technique_frame *f, int l, int k, const float point[4]) {
    skips_counts counts = *f->skips->counts;
    volume_plan plan;
    volumes_plan_light(f, l, k, point, &plan);
    plan.reported = plan.reported && !volumes.point_reported;
    volumes_count_plan(f, &plan);
    if (volumes.point_reported)
        *f->skips->counts = counts;
    volumes.point_reported = true;
}

/* ---- the kept volumes ---- */

/* The CPU volumes are kept per light and per point of its area, built
 * when a caster is first needed after the light moved and drawn from
 * there until it moves again (objects never move; volume_draw.h):
 * forgets those of the lights that moved, or all where the trim changed,
 * and frees a light's points' where it is sampled at other points. */
static void volumes_forget_moved(const technique_frame *f) {
    const scene *s = f->gpu->scene;
    bool trim_changed = volumes.trim_kept != (int)volumes_trim();
    volumes.trim_kept = volumes_trim();
    for (int l = 0; l < s->light_count; l++) {
        if (f->changed.scene || trim_changed || (f->changed.lights & SCENE_LIGHT_BIT(l)))
            volume_draw_forget(&volumes.draw, l);
        int samples = volumes_by_wedges(&s->lights[l])
                          ? 1
                          : soft_visibility_samples("volumes", volumes.settings.light_samples, &s->lights[l], l,
                                                    &volumes.soft_warned);
        if (samples != volumes.samples[l])
            volume_draw_free_points(&volumes.draw, l);
        volumes.samples[l] = samples;
    }
}

/* ---- the frame ---- */

static void volumes_render(const technique_frame *f) {
    volumes_forget_moved(f);
    /* Key G in the window: the CPU's silhouettes stay. */
    if (volumes.settings.silhouette == VOLUMES_GPU && !context_current_features()->geometry_shaders) {
        fprintf(stderr, "%s\n", VOLUMES_NO_GEOMETRY_SHADERS);
        volumes.settings.silhouette = VOLUMES_CPU;
    }
    volumes.counter.settings = (volume_counter_settings){
        .mode = (volume_plan_mode)volumes.settings.mode,
        .kind = (volume_counter_kind)volumes.settings.counter,
        .gpu_silhouettes = volumes.settings.silhouette == VOLUMES_GPU,
        .no_depth_clamp = volumes.settings.no_depth_clamp,
    };
    /* 1. Depth pre-pass: the depth every pass tests against; what it
     *    shows (technique_see) is read from the depth the volumes are
     *    counted against. */
    render_depth_prepass(f->gpu, f->view, f->skips->in_view);
    volume_mesh_receivers_scissor(f->gpu->scene, f->view->view_projection, f->width, f->height,
                                  volumes.receivers_rect);
    volumes.huge_count = volumes.settings.no_exact_depth ? 0 : volume_receivers_update(&volumes.receivers, f);
    if (f->skips->seen)
        volumes_exact_depth(f);
    technique_see(f);
    for (int l = 0; l < f->gpu->scene->light_count; l++) {
        if (!skips_light_on(f->skips, l))
            continue;
        /* The CPU volumes built for this light, or its points, reach as
         * far as volumes_trim says. */
        volume_draw_reach(&volumes.draw, &f->gpu->scene->lights[l], volumes_trim());
        volumes_count_begin();
        if (volumes.samples[l] > 1) {
            /* An area light: steps 2 to 4 for each of its points not yet
             * in its sum, each adding one where its count is 0; then step
             * 5 with the sum. */
            shading_light_pass(f, l);
            volumes.point_reported = false;
            bool summed =
                shading_sample_area_light(f, l, volumes.samples[l], &volumes.soft, &volumes_lit, volumes_count_point);
            volumes_count_end(l);
            if (summed)
                shading_light_soft(f, l, &volumes.soft, volumes_lit.receivers_only);
            continue;
        }
        /* 2. Plan: which casters, each z-pass or z-fail, and where their
         *    volumes may count (the skips). */
        volume_plan plan;
        volumes_plan_light(f, l, SHADING_LIGHT_CENTRE, NULL, &plan);
        /* 2b. An area light by wedges: steps 3 and 4 for the plan's
         *     casters of each rule apart, the visibility from their counts
         *     (1 - count), each silhouette edge's wedge adding the share
         *     of the light's disk it uncovers; then step 5 with that. */
        if (volumes_by_wedges(&f->gpu->scene->lights[l])) {
            if (volume_wedges_light(&volumes.wedges, f, l, &plan, volumes.group, volumes.draw.edges, &volumes.soft,
                                    VOLUME_COUNTER_STENCIL_MASK, volumes_count_plan))
                shading_light_soft(f, l, &volumes.soft, volumes_lit.receivers_only);
            volumes_count_end(l);
            continue;
        }
        volumes_exact_depth(f); /* huge receivers' exact depth, counted against */
        /* 3. Clear the stencil in the plan's rectangle (--mode eye-count:
         *    to the number of volumes that hold the eye). */
        volume_counter_clear(&volumes.counter, f, &plan);
        /* 4. Count the volumes into the stencil, per caster the faces in
         *    front of the surface (z-pass) or behind it (z-fail), +1 or -1
         *    by their facing; where they could stack 256 deep (the
         *    bound), into a float target, written back into the stencil
         *    after. */
        volume_counter_begin(&volumes.counter, f, &plan);
        volume_counter_draw(&volumes.counter, f, &plan);
        volume_counter_end(&volumes.counter, f);
        volumes_count_end(l);
        volumes_prepass_depth(f); /* back to the depth the shading is equal to */
        /* 5. Shade the light where the count is 0, in its own scissor
         *    (objects that take no shadows may lie outside the plan's);
         *    the first light's pass adds the ambient term. */
        shading_light(f, l, &volumes_lit);
        glDisable(GL_STENCIL_TEST);
    }
    /* 6. Ambient alone where no light is on. */
    if (shading_ambient_light(f) < 0)
        shading_ambient(f);
    /* 7. For lectures, the overlays. */
    volume_overlay_draw((volume_overlay_kind)volumes.settings.overlay, f, &volumes.counter, volumes.casters,
                        volumes_trim());
}

static void volumes_describe(char *out, size_t size) {
    const volume_counter *c = &volumes.counter;
    int n = snprintf(out, size, "light 0: %d casters z-pass, %d z-fail", c->zpass, c->zfail);
    if (n > 0 && (size_t)n < size && volumes.settings.mode == VOLUME_PLAN_EYE_COUNT)
        n += snprintf(out + n, size - (size_t)n, ", from the eye inside %d", c->eye);
    if (n > 0 && (size_t)n < size && volumes.settings.mode == VOLUME_PLAN_ZP_PLUS)
        n += snprintf(out + n, size - (size_t)n, ", %d from the near plane's count", c->near_counted);
    if (n > 0 && (size_t)n < size)
        n += snprintf(out + n, size - (size_t)n, "; volumes built %d, kept %d; all lights' kept %.1f MiB",
                      volumes.built_count, volumes.reused_count, (double)volumes.draw.cache_bytes / VOLUME_DRAW_MIB);
    if (n > 0 && (size_t)n < size)
        n += snprintf(out + n, size - (size_t)n, "; depth bounds %s",
                      !volumes.has_depth_bounds          ? "off (no GL_EXT_depth_bounds_test)"
                      : volumes.settings.no_depth_bounds ? "OFF"
                                                         : "on");
    if (n > 0 && (size_t)n < size) {
        if (!volumes.has_exact_depth)
            n += snprintf(out + n, size - (size_t)n, "; exact depth off (no gl_PrimitiveID)");
        else if (volumes.settings.no_exact_depth)
            n += snprintf(out + n, size - (size_t)n, "; exact depth OFF");
        else
            n += snprintf(out + n, size - (size_t)n, "; exact depth of %d huge objects", volumes.huge_count);
    }
    if (n > 0 && (size_t)n < size)
        n += volume_counter_describe(c, out + n, size - (size_t)n);
    if (n > 0 && (size_t)n < size && volumes.settings.soft == VOLUMES_SOFT_WEDGES)
        snprintf(out + n, size - (size_t)n, "; wedges %d, %d edges left out", volumes.wedges.wedge_count,
                 volumes.wedges.skipped_count);
}

/* The sweep: mode x silhouette path, the trim, and an area light's points
 * (on a hard light the defaults' picture; on the soft scenes the
 * convergence to the truth). */
static const char *const volumes_bench_configs[] = {
    "",
    "--mode zpass",
    "--mode zfail",
    "--mode zp-plus",
    "--silhouette gpu",
    "--mode zfail --silhouette gpu",
    "--extrude reach",
    "--light-samples 4",
    "--light-samples 16",
    "--light-samples 64",
    "--light-samples 256",
    "--soft wedges",
    "--counter stencil",
    "--counter float",
};

static const char *volumes_area_light(const scene_light *light, int l) {
    (void)light;
    if (volumes.settings.soft == VOLUMES_SOFT_WEDGES)
        return "penumbra wedges round the centre's silhouette";
    return soft_visibility_area_light_text(&volumes.soft, volumes.settings.light_samples, l);
}

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
    .area_light = volumes_area_light,
    .describe = volumes_describe,
};
