#include "shading.h"

#include <glad/gl.h>
#include <string.h>

/* Light l's rectangle covers at most SHADING_NARROW_LIGHT_SHARE of the frame. */
static bool shading_light_narrow(const technique_frame *f, int l) {
    const int *rect = skips_light_rect(f->skips, l);
    return (double)rect[2] * (double)rect[3] <= SHADING_NARROW_LIGHT_SHARE * (double)f->width * (double)f->height;
}

const bool *shading_light_pass(const technique_frame *f, int l) {
    const int *rect = skips_light_rect(f->skips, l);
    if (shading_light_narrow(f, l) && memcmp(rect, f->skips->light_rect[l], sizeof f->skips->light_rect[l]) != 0)
        f->skips->counts->lights_narrowed |= SCENE_LIGHT_BIT(l);
    glEnable(GL_SCISSOR_TEST);
    glScissor(rect[0], rect[1], rect[2], rect[3]);
    return f->skips->lit_by[l];
}

int shading_ambient_light(const technique_frame *f) {
    for (int l = 0; l < f->gpu->scene->light_count; l++)
        if (skips_light_on(f->skips, l))
            return l;
    return -1;
}

/* The shading passes' depth state: each visible pixel once, nothing
 * written but colour. */
static void shading_depth(void) {
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
}

/* Light l's shading pass state: for the ambient light no blending and no
 * scissor, for the others additive blending in the light's rectangle.
 * Returns the objects the pass draws (every one in view, or what the light
 * reaches); *ambient: whether it also draws the ambient term. */
static const bool *shading_begin(const technique_frame *f, int l, bool *ambient) {
    shading_depth();
    *ambient = l == shading_ambient_light(f);
    if (*ambient) {
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_BLEND);
        return f->skips->in_view;
    }
    render_blend_add();
    return shading_light_pass(f, l);
}

const bool *shading_all_begin(const technique_frame *f) {
    shading_depth();
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    return f->skips->in_view;
}

/* Past one light group, every light on is split and its pass adds its
 * own light alone (shading_split_lights). */
static bool shading_split_adds(const technique_frame *f) { return render_light_groups(f->gpu) > 1; }

scene_light_set shading_split_lights(const technique_frame *f) {
    scene_light_set split = 0;
    bool adds = shading_split_adds(f);
    for (int l = 0; l < f->gpu->scene->light_count; l++)
        if (skips_light_on(f->skips, l) && (adds || shading_light_narrow(f, l)))
            split |= SCENE_LIGHT_BIT(l);
    return split;
}

const bool *shading_split_pass(const technique_frame *f, int l, scene_light_set *lights, bool *ambient) {
    const bool *objects = shading_light_pass(f, l);
    bool adds = shading_split_adds(f);
    *lights = adds ? SCENE_LIGHT_BIT(l) : f->skips->lights;
    *ambient = !adds;
    if (adds)
        render_blend_add();
    return objects;
}

void shading_ambient(const technique_frame *f) {
    shading_depth();
    render_draw_objects(f->gpu, render_use_lit(f->gpu, f->view, 0, true), f->skips->in_view);
}

/* Light l's share on the objects of `objects` the stencil tests (or on
 * the others, `tested` false), through stencil test `func`; with the
 * ambient term when `ambient`. */
static void shading_objects(const technique_frame *f, const bool *objects, scene_light_set lights, bool ambient,
                            const shading_stencil *stencil, unsigned func, bool tested) {
    const scene *s = f->gpu->scene;
    const render_program *p = render_use_lit(f->gpu, f->view, lights, ambient);
    glStencilFunc(tested ? func : GL_ALWAYS, stencil->ref, stencil->mask);
    for (int i = 0; i < s->object_count; i++)
        if (render_in_mask(objects, i) && (!stencil->receivers_only || s->objects[i].receives) == tested)
            render_draw_object(f->gpu, p, i);
}

void shading_light(const technique_frame *f, int l, const shading_stencil *stencil) {
    bool ambient;
    const bool *objects = shading_begin(f, l, &ambient);
    glEnable(GL_STENCIL_TEST);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    shading_objects(f, objects, SCENE_LIGHT_BIT(l), ambient, stencil, stencil->lit, true);
    if (stencil->receivers_only)
        shading_objects(f, objects, SCENE_LIGHT_BIT(l), ambient, stencil, stencil->lit, false);
    if (ambient)
        shading_objects(f, objects, 0, true, stencil, stencil->blocked, true);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
}

void shading_area_light_frame(const technique_frame *f, int l, area_light_frame *frame) {
    const scene *s = f->gpu->scene;
    const scene_light *light = &s->lights[l];
    float centre[4];
    vec3 axis, lo, hi, middle = {0, 0, 0};
    scene_receivers_bounds(s, lo, hi);
    if (lo[0] <= hi[0])
        glm_vec3_center(lo, hi, middle);
    scene_light_homogeneous(light, centre);
    glm_vec3_copy(centre, axis);
    if (centre[3] != 0)
        glm_vec3_sub(centre, middle, axis);
    if (glm_vec3_norm(axis) == 0) /* the light in the middle: any axis is as good */
        glm_vec3_copy((vec3){0, 1, 0}, axis);
    glm_vec3_normalize(axis);
    area_light_frame_for(light, centre, axis, frame);
}

bool shading_sample_area_light(const technique_frame *f, int l, int samples, soft_visibility *v,
                               const shading_stencil *lit, shading_count_point count) {
    bool moved =
        f->changed.scene || f->changed.camera || f->changed.settings || (f->changed.lights & SCENE_LIGHT_BIT(l));
    /* A window's frame in which anything moved: the centre alone. */
    bool centre = f->light_points > 0 && moved;
    if (!soft_visibility_begin(v, l, centre ? 1 : samples, f->light_points == 0 || moved))
        return false;
    soft_visibility_light *sum = &v->lights[l];
    glDisable(GL_STENCIL_TEST);
    if (sum->points == sum->samples) /* the frames before added every point */
        return true;
    area_light_frame frame;
    shading_area_light_frame(f, l, &frame);
    uint32_t seed = area_light_hash((uint32_t)l);
    for (int budget = f->light_points > 0 ? f->light_points : samples; budget > 0 && sum->points < sum->samples;
         budget--) {
        int k = centre ? SHADING_LIGHT_CENTRE : area_light_progressive_index(sum->points, samples);
        float point[4];
        if (centre)
            glm_vec4_copy(frame.centre, point);
        else
            area_light_sample_ball(&frame, k, samples, area_light_hash(seed + (uint32_t)k), point);
        count(f, l, k, point);
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(lit->lit, lit->ref, lit->mask);
        soft_visibility_add(v, l, 1.0f);
        sum->points++;
    }
    glDisable(GL_STENCIL_TEST);
    return true;
}

void shading_light_soft(const technique_frame *f, int l, const soft_visibility *v, bool receivers_only) {
    bool ambient;
    const bool *objects = shading_begin(f, l, &ambient);
    const scene *s = f->gpu->scene;
    glDisable(GL_STENCIL_TEST);
    const render_program *p = soft_visibility_use_lit(v, f->gpu, f->view, l, SCENE_LIGHT_BIT(l), ambient);
    for (int i = 0; i < s->object_count; i++)
        if (render_in_mask(objects, i) && (!receivers_only || s->objects[i].receives))
            render_draw_object(f->gpu, p, i);
    if (receivers_only) {
        p = render_use_lit(f->gpu, f->view, SCENE_LIGHT_BIT(l), ambient);
        for (int i = 0; i < s->object_count; i++)
            if (render_in_mask(objects, i) && !s->objects[i].receives)
                render_draw_object(f->gpu, p, i);
    }
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
}
