#include "technique.h"

#include <glad/gl.h>
#include <stdio.h>
#include <string.h>

#include "context.h"

bool technique_apply_flag(const technique *t, const char *flag) {
    if (strncmp(flag, "--no-", 5) != 0)
        return false;
    for (int k = 0; k < t->toggle_count; k++) {
        if (strcmp(flag + 5, t->toggles[k].name) == 0) {
            *t->toggles[k].disabled = true;
            return true;
        }
    }
    return false;
}

bool technique_apply_config(const technique *t, const char *config) {
    for (int k = 0; k < t->toggle_count; k++)
        *t->toggles[k].disabled = false;
    char copy[512];
    snprintf(copy, sizeof copy, "%s", config);
    char *rest = copy;
    for (char *flag; (flag = strtok_r(rest, " ", &rest));) {
        if (!technique_apply_flag(t, flag)) {
            fprintf(stderr, "%s: unknown flag '%s' in configuration \"%s\"\n", t->name, flag, config);
            return false;
        }
    }
    return true;
}

bool technique_render_frame(const technique *t, const technique_frame *f, const target *target,
                            int visibility_of) {
    render_scene_update_lights(f->gpu, visibility_of);
    target_bind(target);
    glClearColor(RENDER_BACKGROUND_R, RENDER_BACKGROUND_G, RENDER_BACKGROUND_B, 1);
    glClearDepth(1);
    glClearStencil(0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    render_reset_state();
    t->render(f);
    render_reset_state();
    return context_gl_ok(t->name);
}
