#include "soft_visibility.h"

#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>

#include "context.h"
#include "shader.h"

const char *const soft_visibility_sample_counts[] = {"1", "4", "16", "64", "256", NULL};

int soft_visibility_samples(const char *technique, int choice, const scene_light *light, int l,
                            scene_light_set *warned) {
    int samples = atoi(soft_visibility_sample_counts[choice]);
    if (light->radius > 0 && samples == 1 && !(*warned & SCENE_LIGHT_BIT(l)))
        fprintf(stderr, "%s: light %d is an area light (radius %g%s), drawn hard from its centre: --light-samples\n",
                technique, l, light->radius, scene_light_radius_unit(light));
    *warned |= light->radius > 0 && samples == 1 ? SCENE_LIGHT_BIT(l) : 0;
    return light->radius > 0 ? samples : 1;
}

const char *soft_visibility_area_light_text(const soft_visibility *v, int choice, int l) {
    static char text[96];
    int samples = atoi(soft_visibility_sample_counts[choice]);
    const soft_visibility_light *sum = &v->lights[l];
    if (samples == 1)
        return "hard, from its centre: --light-samples N samples it";
    int n = snprintf(text, sizeof text, "sampled at %d points", samples);
    if (sum->samples == 1)
        snprintf(text + n, sizeof text - (size_t)n, ", while nothing moves (now hard, from its centre)");
    else if (sum->samples == samples && sum->points < samples)
        snprintf(text + n, sizeof text - (size_t)n, ", %d so far", sum->points);
    return text;
}

bool soft_visibility_init(soft_visibility *v) {
    *v = (soft_visibility){0};
    static const char *const accumulate_files[] = {"viewport_triangle.vert", "soft_visibility.frag"};
    v->accumulate = shader_load_program(accumulate_files, 2, NULL);
    if (!v->accumulate) {
        soft_visibility_destroy(v);
        return false;
    }
    v->weight = shader_uniform(v->accumulate, "u_weight");
    glGenVertexArrays(1, &v->vao);
    return context_gl_ok("soft_visibility_init");
}

/* Light l's texture at the size of v's target, with the target's depth
 * and stencil; false after one line on stderr. */
static bool soft_visibility_make(soft_visibility *v, soft_visibility_light *light) {
    if (!light->texture) {
        glGenFramebuffers(1, &light->framebuffer);
        glGenTextures(1, &light->texture);
    }
    glBindTexture(GL_TEXTURE_2D, light->texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, v->width, v->height, 0, GL_RED, GL_FLOAT, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, light->framebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, light->texture, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, v->depth_stencil);
    bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glBindFramebuffer(GL_FRAMEBUFFER, v->target_framebuffer);
    if (!complete)
        fprintf(stderr, "soft_visibility: a %dx%d visibility target is incomplete\n", v->width, v->height);
    return complete;
}

/* Whether v is for the bound target (its size and stencil); if not, it
 * is now, every light's sum forgotten. */
static bool soft_visibility_match(soft_visibility *v) {
    GLint framebuffer, depth_stencil, viewport[4];
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT,
                                          GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &depth_stencil);
    glGetIntegerv(GL_VIEWPORT, viewport);
    if ((unsigned)framebuffer == v->target_framebuffer && (unsigned)depth_stencil == v->depth_stencil &&
        viewport[2] == v->width && viewport[3] == v->height)
        return true;
    v->target_framebuffer = (unsigned)framebuffer;
    v->depth_stencil = (unsigned)depth_stencil;
    v->width = viewport[2];
    v->height = viewport[3];
    for (int l = 0; l < SCENE_MAX_LIGHTS; l++)
        v->lights[l].samples = 0; /* remade on its next begin */
    return false;
}

bool soft_visibility_begin(soft_visibility *v, int l, int samples, bool restart) {
    soft_visibility_light *light = &v->lights[l];
    if (!soft_visibility_match(v) || light->samples == 0) {
        if (!soft_visibility_make(v, light)) {
            light->samples = 0;
            return false;
        }
        restart = true;
    }
    if (!restart && light->samples == samples)
        return true;
    light->samples = samples;
    light->points = 0;
    GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, light->framebuffer);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    if (scissor)
        glEnable(GL_SCISSOR_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, v->target_framebuffer);
    return true;
}

void soft_visibility_add(soft_visibility *v, int l, float weight) {
    soft_visibility_light *light = &v->lights[l];
    glBindFramebuffer(GL_FRAMEBUFFER, light->framebuffer);
    GLboolean depth_test = glIsEnabled(GL_DEPTH_TEST), blend = glIsEnabled(GL_BLEND);
    GLboolean color_mask[4];
    glGetBooleanv(GL_COLOR_WRITEMASK, color_mask);
    glDisable(GL_DEPTH_TEST);
    render_blend_add();
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glUseProgram(v->accumulate);
    glUniform1f(v->weight, weight);
    glBindVertexArray(v->vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glColorMask(color_mask[0], color_mask[1], color_mask[2], color_mask[3]);
    if (depth_test)
        glEnable(GL_DEPTH_TEST);
    if (!blend)
        glDisable(GL_BLEND);
    glBindFramebuffer(GL_FRAMEBUFFER, v->target_framebuffer);
}

const render_program *soft_visibility_use_lit(const soft_visibility *v, const render_scene *r,
                                              const camera_view *view, int light, scene_light_set lights,
                                              bool ambient) {
    const render_lit_program *p = render_use_lit_variant(r, RENDER_LIT_SOFT_VISIBILITY, view, lights, ambient);
    if (!p)
        return NULL;
    const soft_visibility_light *sum = &v->lights[light];
    glUniform1i(p->soft_light, RENDER_LIGHT_SLOT(light));
    glUniform1i(p->soft_visibility, SOFT_VISIBILITY_UNIT);
    glUniform1f(p->soft_scale, 1.0f / (float)(sum->points > 0 ? sum->points : 1));
    glActiveTexture(GL_TEXTURE0 + SOFT_VISIBILITY_UNIT);
    glBindTexture(GL_TEXTURE_2D, sum->texture);
    glActiveTexture(GL_TEXTURE0);
    return &p->program;
}

void soft_visibility_destroy(soft_visibility *v) {
    shader_delete_program(v->accumulate);
    glDeleteVertexArrays(1, &v->vao);
    for (int l = 0; l < SCENE_MAX_LIGHTS; l++) {
        glDeleteFramebuffers(1, &v->lights[l].framebuffer);
        glDeleteTextures(1, &v->lights[l].texture);
    }
    *v = (soft_visibility){0};
}
