#include "technique.h"

#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "context.h"

/* A configuration is at most this long: the few flags of one sweep entry. */
#define TECHNIQUE_CONFIG_MAX 512

bool technique_apply_config(const technique *t, const char *config) {
    flags_reset(t->params, t->param_count);
    const char *label_end = strstr(config, ": ");
    char copy[TECHNIQUE_CONFIG_MAX], program[TECHNIQUE_CONFIG_MAX + 64];
    char *words[TECHNIQUE_CONFIG_MAX / 2]; /* words are at least one character and a space */
    int count = 0;
    snprintf(copy, sizeof copy, "%s", label_end ? label_end + 2 : config);
    for (char *rest = copy, *word; (word = strtok_r(rest, " ", &rest));)
        words[count++] = word;
    /* Errors name the configuration, as the command line's name the program. */
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

bool technique_press_key(const technique *t, int key) { return flags_press_key(t->params, t->param_count, key); }

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
