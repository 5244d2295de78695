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
    if (p->kind == FLAGS_TOGGLE && p->available && !*p->available)
        snprintf(out, size, "%s", "not on this GL");
    else if (p->kind == FLAGS_TOGGLE)
        snprintf(out, size, "%s", *p->disabled ? "OFF" : "on");
    else if (p->kind == FLAGS_CHOICE)
        snprintf(out, size, "%s", p->choices[*p->index]);
    else if (p->kind == FLAGS_INT)
        snprintf(out, size, "%d", *p->integer);
    else
        snprintf(out, size, "%g", flags_number(p));
}

/* A setting as a number, 0 its default: a toggle's disabled, a choice's
 * index, a number as set (0: its fallback). */
static double technique_param_value(const flags_param *p) {
    switch (p->kind) {
    case FLAGS_TOGGLE: return *p->disabled;
    case FLAGS_CHOICE: return *p->index;
    case FLAGS_NUMBER: return *p->number;
    case FLAGS_INT: return *p->integer;
    case FLAGS_SWITCH: return *p->on;
    default: return 0;
    }
}

bool technique_param_changed(const flags_param *p) { return technique_param_value(p) != 0; }

void technique_settings_save(const technique *t, technique_settings *out) {
    *out = (technique_settings){.technique = t};
    for (int k = 0; k < t->param_count; k++)
        out->values[k] = technique_param_value(&t->params[k]);
}

bool technique_settings_changes(const technique_settings *saved, const technique *t, char *out, size_t size) {
    if (saved->technique != t)
        return snprintf(out, size, "technique %s", t->name) > 0;
    int n = 0;
    out[0] = '\0';
    for (int k = 0; k < t->param_count && n < (int)size; k++) {
        const flags_param *p = &t->params[k];
        bool lacking = p->kind == FLAGS_TOGGLE && p->available && !*p->available;
        if (technique_param_value(p) == saved->values[k] || lacking)
            continue;
        char value[32];
        technique_param_text(p, value, sizeof value);
        n += snprintf(out + n, size - (size_t)n, "%s%s %s", n ? ", " : "", p->name, value);
    }
    return n > 0;
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

/* ---- what the pre-pass shows ---- */

/* Clears from the frame's in_view and lit_by the objects wholly behind
 * what was seen; none in a frame with a huge object in view. */
static void technique_hide_objects(const technique_frame *f, skips_seen *seen) {
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
        f->skips->counts->objects_hidden++;
    }
}

/* The bound framebuffer's depth into v's slabs; false where the GL reads
 * no depth (context.h's depth_readback) or after printing why: the frame
 * then hides nothing, the same picture at the full cost. */
static bool technique_read_visible(visible *v, const camera_view *view, int width, int height) {
    float *depth = context_current_features()->depth_readback ? visible_depth_buffer(v, width, height) : NULL;
    if (!depth)
        return false;
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    /* A failed read raises a GL error, which the frame's owner reports. */
    glReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
    visible_build(v, view, depth_far(view));
    return true;
}

void technique_see(const technique_frame *f) {
    skips_seen *seen = f->skips->seen;
    if (!seen)
        return;
    seen->masks_made = 0;
    seen->read = technique_read_visible(&seen->pixels, f->view, f->width, f->height);
    if (!seen->read)
        return;
    technique_hide_objects(f, seen);
    skips_narrow_light_rects(f->skips);
}

const char *technique_area_light_text(const technique *t, const scene_light *light, int l) {
    return t->area_light ? t->area_light(light, l) : "hard, from its centre: this technique draws no soft shadows";
}
