#include "skips.h"

#include <math.h>
#include <string.h>

bool skips_light_on(const skips *s, int l) { return (s->lights & SCENE_LIGHT_BIT(l)) != 0; }

const int *skips_light_rect(const skips *s, int l) {
    return s->seen && s->seen->read ? s->seen->light_rect[l] : s->light_rect[l];
}

/* The bounds of a slab's corners. */
static void skips_slab_bounds(const float slab[8][3], vec3 lo, vec3 hi) {
    glm_vec3_fill(lo, INFINITY);
    glm_vec3_fill(hi, -INFINITY);
    for (int c = 0; c < 8; c++) {
        glm_vec3_minv(lo, (float *)slab[c], lo);
        glm_vec3_maxv(hi, (float *)slab[c], hi);
    }
}

/* One pass over the slabs, each slab's bounds made once for every light:
 * the lights on that reach it, and the narrowed lights' rectangles. */
void skips_narrow_light_rects(const skips *s) {
    const scene *sc = s->scene;
    skips_seen *seen = s->seen;
    scene_light_set narrowed = 0;
    float lo[SCENE_MAX_LIGHTS][2], hi[SCENE_MAX_LIGHTS][2];
    for (int l = 0; l < sc->light_count; l++) {
        memcpy(seen->light_rect[l], s->light_rect[l], sizeof seen->light_rect[l]);
        if (sc->lights[l].type != SCENE_LIGHT_DIRECTIONAL && skips_light_on(s, l))
            narrowed |= SCENE_LIGHT_BIT(l);
        lo[l][0] = lo[l][1] = INFINITY;
        hi[l][0] = hi[l][1] = -INFINITY;
    }
    for (int i = 0; i < seen->pixels.count; i++) {
        const light_mask_seen *tile = &seen->pixels.seen[i];
        vec3 slab_lo, slab_hi;
        skips_slab_bounds((const float(*)[3])seen->pixels.slabs[i], slab_lo, slab_hi);
        scene_light_set *reached = &seen->pixels.lights[i];
        *reached = 0;
        for (int l = 0; l < sc->light_count; l++)
            if (skips_light_on(s, l) && scene_light_reaches_box(&sc->lights[l], slab_lo, slab_hi))
                *reached |= SCENE_LIGHT_BIT(l);
        for (int l = 0; l < sc->light_count; l++)
            if (narrowed & *reached & SCENE_LIGHT_BIT(l))
                for (int k = 0; k < 2; k++) {
                    lo[l][k] = fminf(lo[l][k], tile->lo[k]);
                    hi[l][k] = fmaxf(hi[l][k], tile->hi[k]);
                }
    }
    for (int l = 0; l < sc->light_count; l++) {
        if (!(narrowed & SCENE_LIGHT_BIT(l)))
            continue;
        const int *frame_rect = s->light_rect[l];
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

const visible *skips_seen_pixels(const skips *s) { return s->seen && s->seen->read ? &s->seen->pixels : NULL; }

/* Whether the slab's box meets the box lo..hi and the light reaches it
 * (its range, a spot's cone): else what is seen there takes nothing
 * from the light, and no shadow of it matters. */
static bool skips_slab_reached(const scene_light *light, const float slab[8][3], const vec3 lo, const vec3 hi) {
    vec3 slab_lo, slab_hi;
    skips_slab_bounds(slab, slab_lo, slab_hi);
    for (int k = 0; k < 3; k++)
        if (slab_lo[k] > hi[k] || slab_hi[k] < lo[k])
            return false;
    return scene_light_reaches_box(light, slab_lo, slab_hi);
}

/* Light l's masks of the visible slabs that meet the box lo..hi (the
 * receivers within its range) and that it reaches. The slabs
 * that do are swapped to the front of the frame's list, which stays the
 * same set: a mask is a maximum, the same in any order. */
static void skips_light_masks(skips_seen *seen, const scene_light *light, int l, const vec3 lo, const vec3 hi) {
    float(*slabs)[8][3] = seen->pixels.slabs;
    int count = 0;
    for (int i = 0; i < seen->pixels.count; i++)
        if (skips_slab_reached(light, (const float(*)[3])slabs[i], lo, hi)) {
            float swap[8][3];
            memcpy(swap, slabs[count], sizeof swap);
            memcpy(slabs[count], slabs[i], sizeof swap);
            memcpy(slabs[i], swap, sizeof swap);
            light_mask_seen seen_swap = seen->pixels.seen[count];
            seen->pixels.seen[count] = seen->pixels.seen[i];
            seen->pixels.seen[i] = seen_swap;
            scene_light_set lights_swap = seen->pixels.lights[count];
            seen->pixels.lights[count] = seen->pixels.lights[i];
            seen->pixels.lights[i] = lights_swap;
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
    seen->masks_made |= SCENE_LIGHT_BIT(l);
}

void skips_point_hull(const skips *s, int light, const float position[4], skips_hull *out) {
    const scene_light *l = &s->scene->lights[light];
    *out = (skips_hull){.light = light};
    float *lo = out->lo, *hi = out->hi;
    glm_vec3_copy((float *)s->receivers_lo, lo);
    glm_vec3_copy((float *)s->receivers_hi, hi);
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

void skips_light_hull(const skips *s, int light, skips_hull *out) {
    const scene_light *l = &s->scene->lights[light];
    float homogeneous[4];
    scene_light_homogeneous(l, homogeneous);
    skips_point_hull(s, light, homogeneous, out);
    if (out->empty)
        return;
    skips_seen *seen = s->seen;
    if (!s->cull_casters || !seen || !seen->read)
        return;
    if (!(seen->masks_made & SCENE_LIGHT_BIT(light))) {
        /* The slabs' own rounding stays inside the hull's margin. */
        vec3 grown_lo, grown_hi;
        glm_vec3_subs(out->lo, out->margin, grown_lo);
        glm_vec3_adds(out->hi, out->margin, grown_hi);
        skips_light_masks(seen, l, light, grown_lo, grown_hi);
    }
    out->masks = seen->masks[light];
    out->mask_count = seen->mask_count[light];
}

/* Whether the box lo..hi holds the hull's positional light, within the
 * hull's margin: a caster around its light (or with the light in a face)
 * shadows all around it, which its volume counts as an open mesh's; the
 * masks see no part of it apart from the rest, so they leave it whole. */
static bool skips_box_around_light(const skips *s, const skips_hull *hull, const vec3 lo, const vec3 hi) {
    const scene_light *l = &s->scene->lights[hull->light];
    if (l->type == SCENE_LIGHT_DIRECTIONAL)
        return false;
    for (int k = 0; k < 3; k++)
        if (l->position[k] < lo[k] - hull->margin || l->position[k] > hi[k] + hull->margin)
            return false;
    return true;
}

bool skips_caster_needed(const skips *s, const skips_hull *hull, int object) {
    const scene_object *o = &s->scene->objects[object];
    if (!o->casts)
        return false;
    bool needed = !s->cull_casters;
    if (!needed && !hull->empty) {
        vec3 lo, hi;
        scene_object_world_bounds(o, lo, hi);
        needed = !frustum_planes_box_outside((const vec4 *)hull->planes, hull->plane_count, lo, hi, hull->margin);
        if (needed && hull->masks && !skips_box_around_light(s, hull, lo, hi)) {
            needed = false;
            for (int m = 0; m < hull->mask_count && !needed; m++)
                needed = light_mask_box_read(&hull->masks[m], lo, hi);
            s->counts->casters_hidden[hull->light] += !needed;
        }
    }
    if (needed)
        s->counts->casters_drawn[hull->light]++;
    else
        s->counts->casters_culled[hull->light]++;
    return needed;
}

bool skips_caster_seen(const skips *s, const skips_hull *hull, int object, light_mask_seen *out) {
    vec3 lo, hi;
    scene_object_world_bounds(&s->scene->objects[object], lo, hi);
    if (!hull->masks || skips_box_around_light(s, hull, lo, hi))
        return false;
    *out = (light_mask_seen)LIGHT_MASK_SEEN_NOTHING;
    for (int m = 0; m < hull->mask_count; m++)
        light_mask_box_seen(&hull->masks[m], lo, hi, out);
    return true;
}
