/* psm: perspective shadow maps, with light space perspective shadow maps
 * and the uniform map for comparison.
 *
 * A uniform map spends its texels evenly over what the light sees, so near
 * the viewer one texel covers many pixels (perspective aliasing). Warping
 * the map puts texels where the viewer looks:
 *
 *   psm     Stamminger & Drettakis, "Perspective shadow maps", SIGGRAPH
 *           2002: the map is rendered in the camera's post-perspective
 *           space (PPS), where the near part of the view is large. A
 *           directional light becomes a point there, a point light on the
 *           camera's plane a direction. The hard cases follow Kozlov,
 *           "Perspective shadow maps: care and feeding" (GPU Gems, ch. 14):
 *           casters behind the camera are brought in by sliding a virtual
 *           camera back; a light behind the viewer lands beyond infinity,
 *           its rays reach the scene from the far side of its PPS image,
 *           so the map looks from there with its depth order reversed (the
 *           depth row negated: the test flipped without a special state).
 *   lispsm  Wimmer, Scherzer & Purgathofer, "Light space perspective shadow
 *           maps", EGSR 2004: a perspective warp along the view direction
 *           as seen from the light, its strength set by n_opt = (z_n +
 *           sqrt(z_n z_f)) / sin(gamma); as the view turns parallel to the
 *           light, n_opt grows without bound and the map turns uniform.
 *           Spot and point lights get the same warp in the light's own
 *           post-perspective space, where they are directional.
 *   uniform shadowmap.c's fitted map (a cube map for point lights).
 *
 * The same virtual near plane sets both warps' strength: z_n + sqrt(z_n
 * z_f), the optimum both papers derive for a light overhead. A warp can
 * lose to the uniform map, so each frame both are measured where the
 * camera looks and the warp is kept only where it pays (psm_fit); the HUD
 * says which won and why. Bias and filtering are shadowmap.c's, the biases
 * in texels of the warped map found from its matrix's derivatives.
 *
 * The warps' math is demos/lib/warp.h (no GL, unit-tested in
 * tests/test_warp.c); the maps, passes and overlays are
 * demos/lib/map.h. This file chooses between them each frame.
 *
 * For lectures (--overlay): shadowmap.c's overlays, among them
 * "texel-size" (the dp/ds heat map: compare the warps on long_view), and
 * "post-perspective": a second viewport with light 0's warp space (PPS for
 * psm: its clip cube is the view frustum), the scene warped into it and the
 * map's frustum there.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "map.h"
#include "warp.h"

/* Room for the receivers' corners, then 256 casters' box corners. */
#define PSM_MAX_POINTS (SKIPS_MAX_RECEIVER_POINTS + 8 * 256)
/* A warp is kept where it shrinks the mean texel by at least a fifth: the
 * measure is taken on the receivers' boxes, not their surfaces, so near
 * ties go to the map whose texels do not depend on the warp's aim. */
#define PSM_WARP_GAIN 0.8f

static const char *const psm_warps[] = {"psm", "uniform", "lispsm", NULL};
enum { PSM_WARP_PSM, PSM_WARP_UNIFORM, PSM_WARP_LISPSM };
static const char *const psm_overlays[] = {MAP_OVERLAY_NAMES, "post-perspective", NULL};
enum { PSM_OVERLAY_POST_PERSPECTIVE = MAP_OVERLAY_COUNT };

/* What a frame chose for one light, for the HUD, the tests and the
 * post-perspective view. */
typedef struct psm_choice {
    const char *warp;      /* the map in use: "psm", "lispsm" or "uniform" */
    float texel_pixels[2]; /* mean texel size on screen: the warp's, uniform's, at measured_size */
    int measured_size;     /* the size the fit had (--map-size auto sizes the map after it) */
    warp_result result;    /* why, and the warp's space */
} psm_choice;

static struct {
    map_settings settings;
    int warp;
    map_renderer *maps;
    map_warp_view warp_view;         /* the post-perspective overlay */
    bool *casters[SCENE_MAX_LIGHTS]; /* per light: the casters that can shadow what is seen */
    psm_choice choice[SCENE_MAX_LIGHTS];
    /* Scratch space of a fit: */
    float points[PSM_MAX_POINTS][3]; /* the receivers, then the relevant casters' corners */
    float warped[PSM_MAX_POINTS][3]; /* the same points in the warp's space */
} psm;

static const flags_param psm_params[] = {
    {"warp", "how the map is placed: post-perspective, light-space perspective, or uniform", GLFW_KEY_W, FLAGS_CHOICE,
     .index = &psm.warp, .choices = psm_warps},
    MAP_PARAMS(psm.settings),
    {"overlay", "for lectures: shadowmap's overlays, texel size on screen, the post-perspective view", GLFW_KEY_V,
     FLAGS_CHOICE, .index = &psm.settings.overlay, .choices = psm_overlays},
};

/* Light l's warp, fitted to the receivers and the casters that can shadow
 * them; false (with the reason in the result) where it cannot be placed. */
static bool psm_place_warp(const technique_frame *f, int light, const float (*receivers)[3], int receiver_count,
                           warp_result *w) {
    const scene *s = f->gpu->scene;
    const scene_light *l = &s->lights[light];
    memcpy(psm.points, receivers, sizeof *psm.points * (size_t)receiver_count);
    int n = warp_relevant_casters(s, l, psm.points, receiver_count, PSM_MAX_POINTS, psm.casters[light]);
    if (n < 0) {
        snprintf(w->why, sizeof w->why, "more casters than the warp's fit holds");
        return false;
    }
    const float(*points)[3] = (const float(*)[3])psm.points;
    warp_view v;
    bool ok = warp_view_of(f->view, receivers, receiver_count, &v) &&
              (psm.warp == PSM_WARP_PSM ? warp_psm(f->view, l, &v, points, n, psm.warped, w)
                                        : warp_lispsm(l, &v, points, receiver_count, n, psm.warped, w));
    if (ok && !warp_finite(w->view_projection)) {
        snprintf(w->why, sizeof w->why, "the warp is not finite here");
        ok = false;
    }
    return ok;
}

/* The uniform map, replaced by the warp where the warp's texels are
 * smaller on screen. A warp can lose to the uniform map (light nearly
 * along the view, a point light among the receivers), so both are
 * measured where the camera looks: rays through a grid of pixels hit the
 * receivers' boxes, and at each hit the map texel's size in pixels on
 * that plane (the dp/ds of the papers) is found from both matrices
 * (warp_texel_pixels). The warp is kept only where its mean is at least a
 * fifth smaller (PSM_WARP_GAIN). Either way the constant and
 * normal-offset biases move the point in world units, one texel of the
 * map in use there (found from the matrix's derivatives,
 * MAP_TEXEL_PROJECTIVE), since the warp distorts depth. */
static bool psm_fit(const technique_frame *f, int light, map_light *m, const float (*receivers)[3],
                    int receiver_count) {
    const scene_light *l = &f->gpu->scene->lights[light];
    psm_choice *choice = &psm.choice[light];
    warp_result *w = &choice->result;
    choice->warp = psm_warps[PSM_WARP_UNIFORM];
    w->has_space = false;
    w->psm_case = WARP_PSM_NONE;
    choice->texel_pixels[0] = choice->texel_pixels[1] = INFINITY;
    snprintf(w->why, sizeof w->why, "as asked");
    if (!map_fit_uniform(f->gpu->scene, light, m, receivers, receiver_count))
        return false;
    if (psm.warp == PSM_WARP_UNIFORM || !psm_place_warp(f, light, receivers, receiver_count, w))
        return true;
    map_light warped = *m;
    warped.kind = MAP_2D;
    warped.layer_count = 1;
    warped.casters = psm.casters[light];
    warped.texel_kind = MAP_TEXEL_PROJECTIVE;
    glm_mat4_copy(w->view_projection, warped.layer_view_projection[0]);
    warped.near_plane = w->near_plane;
    warped.far_plane = w->far_plane;
    warped.orthographic = w->orthographic;
    map_samples measured = map_light_samples(psm.maps, f, light);
    choice->measured_size = m->size;
    choice->texel_pixels[0] = warp_texel_pixels(warped.layer_view_projection, 1, warped.size, l->position,
                                                measured.samples, measured.count);
    choice->texel_pixels[1] = warp_texel_pixels(m->layer_view_projection, m->layer_count, m->size, l->position,
                                                measured.samples, measured.count);
    if (!(choice->texel_pixels[0] < PSM_WARP_GAIN * choice->texel_pixels[1])) {
        snprintf(w->why + strlen(w->why), sizeof w->why - strlen(w->why), "; the warp does not pay here");
        return true;
    }
    choice->warp = psm_warps[psm.warp];
    *m = warped;
    return true;
}

/* ---- the technique ---- */

static bool psm_init(const render_scene *gpu) {
    for (int l = 0; l < SCENE_MAX_LIGHTS; l++) {
        psm.casters[l] = calloc((size_t)gpu->scene->object_count + 1, sizeof(bool));
        if (!psm.casters[l]) {
            fprintf(stderr, "psm: out of memory\n");
            return false;
        }
    }
    psm.maps = map_create(&psm.settings, gpu);
    return psm.maps && map_warp_view_init(&psm.warp_view);
}

static void psm_destroy(void) {
    map_destroy(psm.maps);
    psm.maps = NULL;
    map_warp_view_destroy(&psm.warp_view);
    for (int l = 0; l < SCENE_MAX_LIGHTS; l++) {
        free(psm.casters[l]);
        psm.casters[l] = NULL;
    }
}

static const char *psm_area_light(const scene_light *light, int l) {
    (void)l;
    return map_area_light_text(&psm.settings, light);
}

/* Light 0's warp space, with the map in use placed in it; where the
 * uniform map is in use (asked for, or the warp did not pay), its own clip
 * space, the map's frustum the unit cube there: how the scene fills a map
 * nothing warps, to set beside the warps'. A cube map has no one space:
 * nothing is drawn. */
static void psm_draw_warp_view(const technique_frame *f) {
    const warp_result *w = &psm.choice[0].result;
    const map_light *m = map_of_light(psm.maps, 0);
    if (w->has_space)
        map_warp_view_draw(&psm.warp_view, psm.maps, f, w->space, m->layer_view_projection[0]);
    else if (m->kind == MAP_2D)
        map_warp_view_draw(&psm.warp_view, psm.maps, f, m->layer_view_projection[0], m->layer_view_projection[0]);
}

/* The frame: shadowmap.c's passes, with each light's map placed by
 * psm_fit, warped where the warp pays. */
static void psm_render(const technique_frame *f) {
    map_renderer *r = psm.maps;
    const map_settings *settings = &psm.settings;
    /* 1. The camera's depth pre-pass: what is seen. */
    map_begin(r, f);
    /* 2. Per light, the warp (or the uniform map where it does not pay),
     * fitted to the visible receivers and the casters that shadow them. */
    for (int l = 0; l < f->gpu->scene->light_count; l++)
        map_fit_light(r, settings, f, l, psm_fit);
    /* 3. Depth from each fitted light through its warp. */
    for (int l = 0; l < f->gpu->scene->light_count; l++)
        map_draw_depth(r, settings, f, l);
    /* 4. Shading: each pixel compared in the map's warped space. */
    map_shade(r, settings, f);
    /* 5. The lecture's overlays, then light 0's warp space. */
    map_draw_overlays(r, settings, f);
    if (settings->overlay == PSM_OVERLAY_POST_PERSPECTIVE)
        psm_draw_warp_view(f);
}

static void psm_describe(char *out, size_t size) {
    int l;
    if (!map_described_light(psm.maps, &l, out, size))
        return;
    const psm_choice *c = &psm.choice[l];
    const map_light *m = map_of_light(psm.maps, l);
    char map[64];
    map_size_text(&psm.settings, m, map, sizeof map);
    int n = snprintf(out, size, "light %d: %s %s (%s)", l, c->warp, map, c->result.why);
    /* A texel's size on screen scales as 1 / size. */
    float scale = (float)c->measured_size / (float)m->size;
    if (n > 0 && (size_t)n < size && isfinite(c->texel_pixels[1]))
        snprintf(out + n, size - (size_t)n, "; texel on screen %.3g px, uniform's %.3g px",
                 c->texel_pixels[0] * scale, c->texel_pixels[1] * scale);
    map_describe_filter(&psm.settings, out, size);
    map_describe_storage(psm.maps, l, out, size);
}

/* The sweep: warp x map size (auto, the default, against fixed sizes); the
 * filters' early-out off, the tents and two moment filters at the
 * defaults (map.h, "The camera pass", "Moment shadow maps"). */
static const char *const psm_bench_configs[] = {
    "",
    "--map-size 1024",
    "--map-size 2048",
    "--warp lispsm",
    "--warp lispsm --map-size 1024",
    "--warp lispsm --map-size 2048",
    "--warp uniform",
    "--warp uniform --map-size 1024",
    "--no-early-out",
    "--filter tent3",
    "--filter tent5",
    "--filter evsm4",
    "--filter msm",
};

const technique psm_technique = {
    .name = "psm",
    .title = "perspective shadow maps (Stamminger & Drettakis 2002), LiSPSM (Wimmer et al. 2004), uniform",
    .params = psm_params,
    .param_count = (int)(sizeof psm_params / sizeof *psm_params),
    .bench_configs = psm_bench_configs,
    .bench_config_count = (int)(sizeof psm_bench_configs / sizeof *psm_bench_configs),
    .init = psm_init,
    .render = psm_render,
    .destroy = psm_destroy,
    .area_light = psm_area_light,
    .describe = psm_describe,
    .coloured_shadows = true, /* the transmittance maps (map.h, "Translucent casters") */
    .gallery_config = "--overlay post-perspective",
};
