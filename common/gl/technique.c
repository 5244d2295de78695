#include "technique.h"

#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "context.h"
#include "depth.h"

/* A configuration is at most this long: the few flags of one sweep entry. */
#define TECHNIQUE_CONFIG_MAX 512

bool technique_apply_config(const technique *t, const char *config) {
    return technique_apply_config_as(t, config, NULL);
}

bool technique_apply_config_as(const technique *t, const char *config, const char *who) {
    flags_reset(t->params, t->param_count);
    const char *label_end = strstr(config, ": ");
    char copy[TECHNIQUE_CONFIG_MAX], program[TECHNIQUE_CONFIG_MAX + 64];
    char *words[TECHNIQUE_CONFIG_MAX / 2]; /* words are at least one character and a space */
    int count = 0;
    snprintf(copy, sizeof copy, "%s", label_end ? label_end + 2 : config);
    for (char *rest = copy, *word; (word = strtok_r(rest, " ", &rest));)
        words[count++] = word;
    /* Errors name the configuration, as the command line's name the program. */
    if (who)
        snprintf(program, sizeof program, "%s", who);
    else
        snprintf(program, sizeof program, "%s (configuration \"%s\")", t->name, config);
    return flags_parse(program, t->params, t->param_count, count, words) == 0;
}

void technique_config_label(const char *config, char *out, size_t size) {
    const char *label_end = strstr(config, ": ");
    if (label_end)
        snprintf(out, size, "%.*s", (int)(label_end - config), config);
    else
        snprintf(out, size, "%s", config[0] ? config : "defaults");
}

void technique_param_text(const flags_param *p, char *out, size_t size) {
    if (p->kind == FLAGS_TOGGLE)
        snprintf(out, size, "%s", *p->disabled ? "OFF" : "on");
    else if (p->kind == FLAGS_CHOICE)
        snprintf(out, size, "%s", p->choices[*p->index]);
    else
        snprintf(out, size, "%g", flags_number(p));
}

bool technique_param_changed(const flags_param *p) {
    switch (p->kind) {
    case FLAGS_TOGGLE: return *p->disabled;
    case FLAGS_CHOICE: return *p->index != 0;
    case FLAGS_NUMBER: return *p->number != 0;
    case FLAGS_INT: return *p->integer != 0;
    case FLAGS_SWITCH: return *p->on;
    default: return false;
    }
}

bool technique_press_key(const technique *t, int key) { return flags_press_key(t->params, t->param_count, key); }

bool technique_init(const technique *t, const render_scene *gpu) {
    bool ok = t->init(gpu);
    return context_gl_ok(t->name) && ok;
}

bool technique_render_frame(const technique *t, const technique_frame *f, target *target, int visibility_of) {
    render_scene_update_lights(f->gpu, visibility_of);
    if (!target_match_depth(target, f->view->reversed_depth))
        return false;
    target_bind(target);
    glClearColor(SCENE_BACKGROUND_R, SCENE_BACKGROUND_G, SCENE_BACKGROUND_B, 1);
    glClearDepth(depth_far(f->view));
    glClearStencil(0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    render_reset_state();
    depth_use_camera(f->view);
    t->render(f);
    render_reset_state();
    depth_use_standard(f->view); /* what comes between frames expects GL's */
    return context_gl_ok(t->name) && !f->gpu->lit->failed;
}

/* ---- skips ---- */

bool technique_light_on(const technique_frame *f, int l) { return (f->lights & RENDER_LIGHT_BIT(l)) != 0; }

const int *technique_light_rect(const technique_frame *f, int l) {
    return f->seen && f->seen->read ? f->seen->light_rect[l] : f->light_rect[l];
}

/* The bounds of a slab's corners. */
static void technique_slab_bounds(const float slab[8][3], vec3 lo, vec3 hi) {
    glm_vec3_fill(lo, INFINITY);
    glm_vec3_fill(hi, -INFINITY);
    for (int c = 0; c < 8; c++) {
        glm_vec3_minv(lo, (float *)slab[c], lo);
        glm_vec3_maxv(hi, (float *)slab[c], hi);
    }
}

/* Clears from the frame's in_view and lit_by the objects wholly behind
 * what was seen; none in a frame with a huge object in view. */
static void technique_hide_objects(const technique_frame *f, technique_seen *seen) {
    const scene *s = f->gpu->scene;
    for (int i = 0; i < s->object_count; i++)
        if (seen->in_view[i] && render_object_huge(f->gpu, i, f->view->eye))
            return;
    for (int i = 0; i < s->object_count; i++) {
        vec3 lo, hi;
        if (!seen->in_view[i])
            continue;
        scene_object_world_bounds(&s->objects[i], lo, hi);
        if (!visible_box_hidden(&seen->pixels, f->view, lo, hi))
            continue;
        seen->in_view[i] = false;
        for (int l = 0; l < s->light_count; l++)
            seen->lit_by[l][i] = false;
        f->counts->objects_hidden++;
    }
}

/* Each light's rectangle narrowed to the tiles of the slabs it reaches
 * (technique_light_rect); a directional light reaches every one. One pass
 * over the slabs, each slab's bounds made once for every light. */
static void technique_narrow_light_rects(const technique_frame *f, technique_seen *seen) {
    const scene *s = f->gpu->scene;
    unsigned narrowed = 0;
    float lo[SCENE_MAX_LIGHTS][2], hi[SCENE_MAX_LIGHTS][2];
    for (int l = 0; l < s->light_count; l++) {
        memcpy(seen->light_rect[l], f->light_rect[l], sizeof seen->light_rect[l]);
        if (s->lights[l].type != SCENE_LIGHT_DIRECTIONAL && technique_light_on(f, l))
            narrowed |= RENDER_LIGHT_BIT(l);
        lo[l][0] = lo[l][1] = INFINITY;
        hi[l][0] = hi[l][1] = -INFINITY;
    }
    for (int i = 0; i < seen->pixels.count && narrowed; i++) {
        const light_mask_seen *tile = &seen->pixels.seen[i];
        vec3 slab_lo, slab_hi;
        technique_slab_bounds((const float(*)[3])seen->pixels.slabs[i], slab_lo, slab_hi);
        for (int l = 0; l < s->light_count; l++)
            if ((narrowed & RENDER_LIGHT_BIT(l)) && scene_light_reaches_box(&s->lights[l], slab_lo, slab_hi))
                for (int k = 0; k < 2; k++) {
                    lo[l][k] = fminf(lo[l][k], tile->lo[k]);
                    hi[l][k] = fmaxf(hi[l][k], tile->hi[k]);
                }
    }
    for (int l = 0; l < s->light_count; l++) {
        if (!(narrowed & RENDER_LIGHT_BIT(l)))
            continue;
        const int *frame_rect = f->light_rect[l];
        int *rect = seen->light_rect[l];
        if (!(lo[l][0] <= hi[l][0])) { /* no slab: nothing seen is reached */
            rect[2] = rect[3] = 0;
            continue;
        }
        int x0 = glm_max(frame_rect[0], (int)lo[l][0]), y0 = glm_max(frame_rect[1], (int)lo[l][1]);
        int x1 = glm_min(frame_rect[0] + frame_rect[2], (int)hi[l][0]);
        int y1 = glm_min(frame_rect[1] + frame_rect[3], (int)hi[l][1]);
        rect[0] = x0;
        rect[1] = y0;
        rect[2] = glm_max(x1 - x0, 0);
        rect[3] = glm_max(y1 - y0, 0);
    }
}

void technique_see(const technique_frame *f) {
    technique_seen *seen = f->seen;
    if (!seen)
        return;
    seen->masks_made = 0;
    seen->read = visible_read(&seen->pixels, f->view, f->width, f->height);
    if (!seen->read)
        return;
    technique_hide_objects(f, seen);
    technique_narrow_light_rects(f, seen);
}

const visible *technique_seen_pixels(const technique_frame *f) {
    return f->seen && f->seen->read ? &f->seen->pixels : NULL;
}

/* Whether the slab's box meets the box lo..hi and the light reaches it
 * (its range, a spot's cone): else what is seen there takes nothing
 * from the light, and no shadow of it matters. */
static bool technique_slab_reached(const scene_light *light, const float slab[8][3], const vec3 lo, const vec3 hi) {
    vec3 slab_lo, slab_hi;
    technique_slab_bounds(slab, slab_lo, slab_hi);
    for (int k = 0; k < 3; k++)
        if (slab_lo[k] > hi[k] || slab_hi[k] < lo[k])
            return false;
    return scene_light_reaches_box(light, slab_lo, slab_hi);
}

/* Light l's masks of the visible slabs that meet the box lo..hi (the
 * receivers within its range) and that it reaches. The slabs
 * that do are swapped to the front of the frame's list, which stays the
 * same set: a mask is a maximum, the same in any order. */
static void technique_light_masks(technique_seen *seen, const scene_light *light, int l, const vec3 lo,
                                  const vec3 hi) {
    float(*slabs)[8][3] = seen->pixels.slabs;
    int count = 0;
    for (int i = 0; i < seen->pixels.count; i++)
        if (technique_slab_reached(light, (const float(*)[3])slabs[i], lo, hi)) {
            float swap[8][3];
            memcpy(swap, slabs[count], sizeof swap);
            memcpy(slabs[count], slabs[i], sizeof swap);
            memcpy(slabs[i], swap, sizeof swap);
            light_mask_seen seen_swap = seen->pixels.seen[count];
            seen->pixels.seen[count] = seen->pixels.seen[i];
            seen->pixels.seen[i] = seen_swap;
            count++;
        }
    mat4 layers[LIGHT_MASK_MAX_LAYERS];
    seen->mask_count[l] = light_mask_layers(light, (const float(*)[8][3])slabs, count, layers);
    for (int m = 0; m < seen->mask_count[l]; m++) {
        light_mask *mask = &seen->masks[l][m];
        light_mask_start(mask, layers[m], 0, false, true);
        for (int i = 0; i < count; i++)
            light_mask_add(mask, (const float(*)[3])slabs[i], &seen->pixels.seen[i]);
    }
    seen->masks_made |= RENDER_LIGHT_BIT(l);
}

void technique_point_hull(const technique_frame *f, int light, const float position[4], technique_hull *out) {
    const scene_light *l = &f->gpu->scene->lights[light];
    *out = (technique_hull){.light = light};
    float *lo = out->lo, *hi = out->hi;
    glm_vec3_copy((float *)f->receivers_lo, lo);
    glm_vec3_copy((float *)f->receivers_hi, hi);
    /* Receivers beyond the range take nothing from this light. */
    out->empty = !scene_light_clip_to_range(l, lo, hi);
    if (out->empty)
        return;
    float size = fmaxf(fmaxf(hi[0] - lo[0], hi[1] - lo[1]), hi[2] - lo[2]), reach = 0;
    for (int k = 0; k < 3; k++)
        reach = fmaxf(reach, fmaxf(fabsf(lo[k]), fabsf(hi[k])));
    if (position[3] != 0)
        for (int k = 0; k < 3; k++)
            size = fmaxf(size, fabsf(position[k] / position[3] - 0.5f * (lo[k] + hi[k])));
    out->margin = FRUSTUM_BOX_TOLERANCE * size + FRUSTUM_FLOAT_TOLERANCE * reach;
    out->plane_count = frustum_light_hull(position, lo, hi, out->planes);
}

void technique_light_hull(const technique_frame *f, int light, technique_hull *out) {
    const scene_light *l = &f->gpu->scene->lights[light];
    float homogeneous[4];
    scene_light_homogeneous(l, homogeneous);
    technique_point_hull(f, light, homogeneous, out);
    if (out->empty)
        return;
    technique_seen *seen = f->seen;
    if (!f->cull_casters || !seen || !seen->read)
        return;
    if (!(seen->masks_made & RENDER_LIGHT_BIT(light))) {
        /* The slabs' own rounding stays inside the hull's margin. */
        vec3 grown_lo, grown_hi;
        glm_vec3_subs(out->lo, out->margin, grown_lo);
        glm_vec3_adds(out->hi, out->margin, grown_hi);
        technique_light_masks(seen, l, light, grown_lo, grown_hi);
    }
    out->masks = seen->masks[light];
    out->mask_count = seen->mask_count[light];
}

/* Whether the box lo..hi holds the hull's positional light, within the
 * hull's margin: a caster around its light (or with the light in a face)
 * shadows all around it, which its volume counts as an open mesh's; the
 * masks see no part of it apart from the rest, so they leave it whole. */
static bool technique_box_around_light(const technique_frame *f, const technique_hull *hull, const vec3 lo,
                                       const vec3 hi) {
    const scene_light *l = &f->gpu->scene->lights[hull->light];
    if (l->type == SCENE_LIGHT_DIRECTIONAL)
        return false;
    for (int k = 0; k < 3; k++)
        if (l->position[k] < lo[k] - hull->margin || l->position[k] > hi[k] + hull->margin)
            return false;
    return true;
}

bool technique_caster_needed(const technique_frame *f, const technique_hull *hull, int object) {
    const scene_object *o = &f->gpu->scene->objects[object];
    if (!o->casts)
        return false;
    bool needed = !f->cull_casters;
    if (!needed && !hull->empty) {
        vec3 lo, hi;
        scene_object_world_bounds(o, lo, hi);
        needed = !frustum_planes_box_outside((const vec4 *)hull->planes, hull->plane_count, lo, hi, hull->margin);
        if (needed && hull->masks && !technique_box_around_light(f, hull, lo, hi)) {
            needed = false;
            for (int m = 0; m < hull->mask_count && !needed; m++)
                needed = light_mask_box_read(&hull->masks[m], lo, hi);
            f->counts->casters_hidden[hull->light] += !needed;
        }
    }
    if (needed)
        f->counts->casters_drawn[hull->light]++;
    else
        f->counts->casters_culled[hull->light]++;
    return needed;
}

bool technique_caster_seen(const technique_frame *f, const technique_hull *hull, int object, light_mask_seen *out) {
    vec3 lo, hi;
    scene_object_world_bounds(&f->gpu->scene->objects[object], lo, hi);
    if (!hull->masks || technique_box_around_light(f, hull, lo, hi))
        return false;
    *out = (light_mask_seen)LIGHT_MASK_SEEN_NOTHING;
    for (int m = 0; m < hull->mask_count; m++)
        light_mask_box_seen(&hull->masks[m], lo, hi, out);
    return true;
}

const char *technique_area_light_text(const technique *t, const scene_light *light, int l) {
    return t->area_light ? t->area_light(light, l) : "hard, from its centre: this technique draws no soft shadows";
}
