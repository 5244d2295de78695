#include "technique.h"

#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "context.h"

static const technique_param *technique_find(const technique *t, const char *name, bool toggle) {
    const char *prefix = toggle ? "--no-" : "--";
    size_t n = strlen(prefix);
    if (strncmp(name, prefix, n) != 0)
        return NULL;
    for (int k = 0; k < t->param_count; k++)
        if ((t->params[k].kind == TECHNIQUE_TOGGLE) == toggle && strcmp(name + n, t->params[k].name) == 0)
            return &t->params[k];
    return NULL;
}

bool technique_flag_takes_value(const technique *t, const char *name) {
    return technique_find(t, name, false) != NULL;
}

static bool technique_set(const technique *t, const technique_param *p, const char *value) {
    if (p->kind == TECHNIQUE_CHOICE) {
        for (int c = 0; p->choices[c]; c++) {
            if (strcmp(value, p->choices[c]) == 0) {
                *p->index = c;
                return true;
            }
        }
        char list[256] = "";
        for (int c = 0; p->choices[c]; c++)
            snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", c ? ", " : "", p->choices[c]);
        fprintf(stderr, "%s: --%s: expected one of %s, got '%s'\n", t->name, p->name, list, value);
        return false;
    }
    char *end;
    float v = strtof(value, &end);
    if (end == value || *end != '\0' || !(v >= p->min && v <= p->max)) {
        fprintf(stderr, "%s: --%s: expected a number in %g..%g, got '%s'\n", t->name, p->name, p->min, p->max,
                value);
        return false;
    }
    *p->number = v;
    return true;
}

bool technique_apply_flag(const technique *t, const char *name, const char *value, bool *bad_value) {
    *bad_value = false;
    const technique_param *p = technique_find(t, name, true);
    if (p) {
        *p->disabled = true;
        return true;
    }
    p = technique_find(t, name, false);
    if (!p)
        return false;
    *bad_value = !technique_set(t, p, value);
    return !*bad_value;
}

bool technique_apply_config(const technique *t, const char *config) {
    for (int k = 0; k < t->param_count; k++) {
        const technique_param *p = &t->params[k];
        if (p->kind == TECHNIQUE_TOGGLE)
            *p->disabled = false;
        else if (p->kind == TECHNIQUE_CHOICE)
            *p->index = 0;
        else
            *p->number = 0;
    }
    const char *label_end = strstr(config, ": ");
    char copy[512];
    snprintf(copy, sizeof copy, "%s", label_end ? label_end + 2 : config);
    char *rest = copy;
    for (char *flag; (flag = strtok_r(rest, " ", &rest));) {
        bool takes_value = technique_flag_takes_value(t, flag);
        const char *value = takes_value ? strtok_r(rest, " ", &rest) : NULL;
        bool bad_value;
        if (takes_value && !value) {
            fprintf(stderr, "%s: missing value after %s in configuration \"%s\"\n", t->name, flag, config);
            return false;
        }
        if (!technique_apply_flag(t, flag, value, &bad_value)) {
            if (!bad_value)
                fprintf(stderr, "%s: unknown flag '%s' in configuration \"%s\"\n", t->name, flag, config);
            return false;
        }
    }
    return true;
}

void technique_config_label(const char *config, char *out, size_t size) {
    const char *label_end = strstr(config, ": ");
    if (label_end)
        snprintf(out, size, "%.*s", (int)(label_end - config), config);
    else
        snprintf(out, size, "%s", config[0] ? config : "defaults");
}

float technique_number(const technique_param *p) { return *p->number != 0 ? *p->number : p->fallback; }

void technique_param_text(const technique_param *p, char *out, size_t size) {
    if (p->kind == TECHNIQUE_TOGGLE)
        snprintf(out, size, "%s", *p->disabled ? "OFF" : "on");
    else if (p->kind == TECHNIQUE_CHOICE)
        snprintf(out, size, "%s", p->choices[*p->index]);
    else
        snprintf(out, size, "%g", technique_number(p));
}

bool technique_press_key(const technique *t, int key) {
    bool found = false;
    for (int k = 0; k < t->param_count; k++) {
        const technique_param *p = &t->params[k];
        if (p->key != key || key == 0)
            continue;
        found = true;
        if (p->kind == TECHNIQUE_TOGGLE)
            *p->disabled ^= true;
        else if (p->kind == TECHNIQUE_CHOICE)
            *p->index = p->choices[*p->index + 1] ? *p->index + 1 : 0;
    }
    return found;
}

bool technique_init(const technique *t, const render_scene *gpu) {
    bool ok = t->init(gpu);
    return context_gl_ok(t->name) && ok;
}

bool technique_render_frame(const technique *t, const technique_frame *f, const target *target,
                            int visibility_of) {
    render_scene_update_lights(f->gpu, visibility_of);
    target_bind(target);
    glClearColor(SCENE_BACKGROUND_R, SCENE_BACKGROUND_G, SCENE_BACKGROUND_B, 1);
    glClearDepth(1);
    glClearStencil(0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    render_reset_state();
    t->render(f);
    render_reset_state();
    return context_gl_ok(t->name);
}
