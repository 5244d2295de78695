#include "technique_host.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A light's pixel rectangle is grown by this many pixels each side: the
 * rasterizer's pixel centres and float rounding at its edge. */
#define TECHNIQUE_HOST_RECT_MARGIN_PIXELS 1

bool technique_host_start(technique_host *h, const technique *t, render_scene *gpu, const render_skips *skips) {
    const scene *s = gpu->scene;
    for (int l = 0; l < s->light_count && !t->area_light && !t->cost_floor; l++)
        if (s->lights[l].radius > 0)
            fprintf(stderr,
                    "%s: light %d is an area light (radius %g%s): drawn hard, from its centre: %s draws no soft "
                    "shadows\n",
                    t->name, l, s->lights[l].radius, scene_light_radius_unit(&s->lights[l]), t->name);
    int translucent = scene_translucent_casters(s);
    if (translucent && !t->cost_floor && !t->coloured_shadows)
        fprintf(stderr,
                "%s: %d translucent objects (alphaMode BLEND) cast the shadow of their whole surface: %s draws no "
                "coloured shadows\n",
                t->name, translucent, t->name);
    /* Each light's masks: a scene's, not every light a scene may have. */
    h->seen.masks = calloc((size_t)(s->light_count > 0 ? s->light_count : 1), sizeof *h->seen.masks);
    if (!h->seen.masks) {
        fprintf(stderr, "%s: out of memory for the lights' masks\n", t->name);
        return false;
    }
    h->technique = t;
    h->gpu = gpu;
    h->skips = skips;
    h->started = false;
    h->hidden_idle = 0;
    h->settings_changed = false;
    if (technique_init(t, gpu))
        return true;
    free(h->seen.masks);
    h->seen.masks = NULL;
    return false;
}

void technique_host_settings_changed(technique_host *h) { h->settings_changed = true; }

void technique_host_stop(technique_host *h) {
    h->technique->destroy();
    visible_destroy(&h->seen.pixels);
    free(h->seen.masks);
    h->seen.masks = NULL;
}

/* Whether a light moved in any way a shadow depends on (not its colour). */
static bool technique_host_light_moved(const scene_light *a, const scene_light *b) {
    return a->type != b->type || !glm_vec3_eqv((float *)a->position, (float *)b->position) ||
           !glm_vec3_eqv((float *)a->direction, (float *)b->direction) || a->outer_angle_deg != b->outer_angle_deg ||
           a->inner_angle_deg != b->inner_angle_deg || a->range != b->range;
}

static technique_changes technique_host_changes(technique_host *h, const camera_view *view) {
    const scene *s = h->gpu->scene;
    bool everything = !h->started || !render_skip_on(h->skips, h->skips->no_cache);
    technique_changes c = {.scene = everything, .camera = everything, .settings = everything || h->settings_changed};
    h->settings_changed = false;
    if (everything)
        c.lights = SCENE_ALL_LIGHTS(s->light_count);
    if (!everything && memcmp(h->last_view_projection, view->view_projection, sizeof(mat4)) != 0)
        c.camera = true;
    for (int l = 0; !everything && l < s->light_count; l++)
        if (technique_host_light_moved(&h->last_lights[l], &s->lights[l]))
            c.lights |= SCENE_LIGHT_BIT(l);
    h->started = true;
    memcpy(h->last_view_projection, view->view_projection, sizeof(mat4));
    memcpy(h->last_lights, s->lights, sizeof h->last_lights);
    return c;
}

/* The part of o's box inside the view's frustum (by the view's corners,
 * camera.h): its corners at out, at most SKIPS_MAX_PART_POINTS. The
 * caller skips boxes outside the frustum first, by the test view culling
 * uses, applied whatever the skips, so that what follows never depends on
 * them. */
static int technique_host_visible_part(const scene_object *o, const camera_view *view, float (*out)[3]) {
    vec3 lo, hi;
    scene_object_world_bounds(o, lo, hi);
    return frustum_box_part(view->view_projection, (const vec3 *)view->corners, lo, hi, out, SKIPS_MAX_PART_POINTS);
}

/* Appends a part's points to points[*n], as far as max_points allows. */
static void technique_host_append_points(float (*points)[3], int *n, int max_points, const float (*part)[3],
                                         int count) {
    if (count > max_points - *n) {
        fprintf(stderr, "technique host: more than %d receiver points: the frame's receivers are cut short\n",
                max_points);
        count = max_points - *n;
    }
    memcpy(points + *n, part, (size_t)count * sizeof *part);
    *n += count;
}

int technique_host_receiver_points(const scene *s, const camera_view *view, float (*points)[3], int max_points) {
    float part[SKIPS_MAX_PART_POINTS][3];
    int n = 0;
    for (int i = 0; i < s->object_count; i++) {
        vec3 lo, hi;
        scene_object_world_bounds(&s->objects[i], lo, hi);
        if (s->objects[i].receives && !frustum_box_outside(view->view_projection, lo, hi))
            technique_host_append_points(points, &n, max_points, (const float(*)[3])part,
                                         technique_host_visible_part(&s->objects[i], view, part));
    }
    return n;
}

/* The lights worth testing against the visible objects: all but those
 * whose range sphere lies outside the view's frustum. */
static scene_light_set technique_host_lights_near_view(const scene *s, const camera_view *view) {
    scene_light_set lights = 0;
    for (int l = 0; l < s->light_count; l++) {
        const scene_light *light = &s->lights[l];
        bool bounded = light->type != SCENE_LIGHT_DIRECTIONAL && light->range > 0;
        if (!bounded || !frustum_sphere_outside(view->view_projection, light->position,
                                                light->range * (1 + SCENE_REACH_RANGE_MARGIN)))
            lights |= SCENE_LIGHT_BIT(l);
    }
    return lights;
}

/* The frame's receiver points and their bounds. */
static void technique_host_set_receivers(skips *k, const float (*points)[3], int count) {
    k->receivers = points;
    k->receiver_count = count;
    glm_vec3_fill(k->receivers_lo, INFINITY);
    glm_vec3_fill(k->receivers_hi, -INFINITY);
    for (int i = 0; i < count; i++) {
        glm_vec3_minv(k->receivers_lo, (float *)points[i], k->receivers_lo);
        glm_vec3_maxv(k->receivers_hi, (float *)points[i], k->receivers_hi);
    }
}

/* One pass over what the view sees: each object's part inside the frustum
 * gives the receivers' points (for fitting maps and culling casters) and
 * the lights that reach something visible (scene_light_reaches_box on the
 * part's bounds: a light reaching the ground's box somewhere out of view
 * reaches nothing on screen). */
static void technique_host_visible(technique_host *h, const camera_view *view, skips *k) {
    const scene *s = h->gpu->scene;
    scene_light_set all = SCENE_ALL_LIGHTS(s->light_count);
    bool reach_skip = render_skip_on(h->skips, h->skips->no_light_reach);
    scene_light_set candidates = reach_skip ? technique_host_lights_near_view(s, view) : 0, reached = 0;
    float part[SKIPS_MAX_PART_POINTS][3];
    int n = 0;
    for (int i = 0; i < s->object_count; i++) {
        int count = h->gpu->in_frustum[i] ? technique_host_visible_part(&s->objects[i], view, part) : 0;
        if (count == 0)
            continue;
        if (candidates & ~reached) {
            vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
            for (int k = 0; k < count; k++) {
                glm_vec3_minv(lo, part[k], lo);
                glm_vec3_maxv(hi, part[k], hi);
            }
            for (int l = 0; l < s->light_count; l++)
                if ((candidates & ~reached & SCENE_LIGHT_BIT(l)) && scene_light_reaches_box(&s->lights[l], lo, hi))
                    reached |= SCENE_LIGHT_BIT(l);
        }
        if (s->objects[i].receives)
            technique_host_append_points(h->receivers, &n, SKIPS_MAX_RECEIVER_POINTS, (const float(*)[3])part, count);
    }
    k->lights = reach_skip ? reached : all;
    technique_host_set_receivers(k, (const float(*)[3])h->receivers, n);
}

/* NDC -> the pixel at or beyond it, on an axis of `size` pixels. */
static int technique_host_pixel(float ndc, int size, bool up) {
    float x = (glm_clamp(ndc, -1, 1) * 0.5f + 0.5f) * (float)size;
    return up ? (int)ceilf(x) + TECHNIQUE_HOST_RECT_MARGIN_PIXELS
              : (int)floorf(x) - TECHNIQUE_HOST_RECT_MARGIN_PIXELS;
}

/* The pixels light l may reach: the screen bounds of the cube around its
 * range (the range window is 0 beyond it); the whole frame without a
 * range, when the cube reaches behind the eye, or without the skip
 * (`bounded` false). */
static void technique_host_range_rect(const scene_light *l, const camera_view *view, int width, int height,
                                      bool bounded, int rect[4]) {
    rect[0] = rect[1] = 0;
    rect[2] = width;
    rect[3] = height;
    vec3 lo, hi;
    vec2 ndc_lo, ndc_hi;
    if (!bounded || !scene_light_range_box(l, lo, hi) ||
        !frustum_box_ndc_bounds(view->view_projection, lo, hi, ndc_lo, ndc_hi))
        return;
    int x0 = glm_max(technique_host_pixel(ndc_lo[0], width, false), 0);
    int y0 = glm_max(technique_host_pixel(ndc_lo[1], height, false), 0);
    int x1 = glm_min(technique_host_pixel(ndc_hi[0], width, true), width);
    int y1 = glm_min(technique_host_pixel(ndc_hi[1], height, true), height);
    rect[0] = x0;
    rect[1] = y0;
    rect[2] = glm_max(x1 - x0, 0);
    rect[3] = glm_max(y1 - y0, 0);
}

/* Each light's objects and pixels (skips.lit_by, light_rect) in a frame
 * of width x height pixels. */
static void technique_host_light_passes(technique_host *h, const camera_view *view, int width, int height, skips *k) {
    const scene *s = h->gpu->scene;
    bool reach_skip = render_skip_on(h->skips, h->skips->no_light_reach);
    for (int l = 0; l < s->light_count; l++) {
        bool *lit = h->gpu->lit_by[l];
        k->lit_by[l] = lit;
        technique_host_range_rect(&s->lights[l], view, width, height, reach_skip, k->light_rect[l]);
        for (int i = 0; i < s->object_count; i++) {
            lit[i] = h->gpu->in_view[i];
            if (lit[i] && reach_skip && skips_light_on(k, l)) {
                vec3 lo, hi;
                scene_object_world_bounds(&s->objects[i], lo, hi);
                lit[i] = scene_light_reaches_box(&s->lights[l], lo, hi);
            }
        }
    }
}

bool technique_host_frame(technique_host *h, const camera_view *view, const camera_view *fit_view, target *target,
                          double time, int visibility_of) {
    const scene *s = h->gpu->scene;
    h->counts = (skips_counts){0};
    h->seen.read = false; /* until the technique's technique_see */
    h->seen.in_view = h->gpu->in_view;
    memcpy(h->seen.lit_by, h->gpu->lit_by, sizeof h->seen.lit_by);
    h->objects_in_view = render_cull_view(h->gpu, view, h->skips);
    skips k = {.scene = s,
               .in_view = h->gpu->in_view,
               .cull_casters = render_skip_on(h->skips, h->skips->no_caster_cull),
               .marked_pass = render_skip_on(h->skips, h->skips->no_marked_pass),
               .seen = render_skip_on(h->skips, h->skips->no_hidden_cull) && h->hidden_idle == 0 ? &h->seen : NULL,
               .counts = &h->counts};
    technique_frame f = {.gpu = h->gpu,
                         .view = view,
                         .width = target->width,
                         .height = target->height,
                         .time = time,
                         .changed = technique_host_changes(h, view),
                         .skips = &k,
                         .light_points = visibility_of < 0 ? h->light_points : 0,
                         .counters = h->counters};
    technique_host_visible(h, view, &k);
    technique_host_light_passes(h, view, f.width, f.height, &k);
    for (int l = 0; l < s->light_count; l++)
        h->counts.lights_skipped += !skips_light_on(&k, l);
    technique_frame fit = f;
    skips fit_skips = k;
    if (fit_view) {
        fit.view = fit_view;
        technique_host_set_receivers(
            &fit_skips, (const float(*)[3])h->fit_receivers,
            technique_host_receiver_points(s, fit_view, h->fit_receivers, SKIPS_MAX_RECEIVER_POINTS));
        fit.skips = &fit_skips;
        f.fit = &fit;
    }
    h->hidden_idle -= h->hidden_idle > 0;
    bool rendered = technique_render_frame(h->technique, &f, target, visibility_of);
    int saved = h->counts.objects_hidden + (h->counts.lights_narrowed != 0);
    for (int l = 0; l < s->light_count; l++)
        saved += h->counts.casters_hidden[l] + h->counts.casters_narrowed[l];
    if (h->seen.read && saved == 0)
        h->hidden_idle = TECHNIQUE_HOST_HIDDEN_RETRY_FRAMES;
    return rendered;
}
