/* unshadowed: the scene lit by every light with no shadows at all.
 *
 * Not a shadow technique but the floor every one of them is measured from:
 * the benchmark's cost baseline ("ratio to the unshadowed frame") and, in
 * a lecture, the picture that shows what shadows add (a number key in the
 * window, after the shadow techniques).
 */
#include <glad/gl.h>

#include "shading.h"
#include "technique.h"

static bool unshadowed_init(const render_scene *gpu) {
    (void)gpu;
    return true;
}

/* The shading every technique shares, with visibility 1: the same depth
 * pre-pass and skips (view culling, light reach, light rectangles), the
 * lighting code with each light compiled in (render_use_lit), and the
 * shadow maps' split of the shading (shading_split_lights), whose pixels
 * are bit for bit those of one pass, so that no skip changes the floor's
 * picture (additive passes would round each light's share apart). No
 * technique pays less than the floor for what it shares with it, and a
 * ratio to it measures shadows alone. */
static void unshadowed_render(const technique_frame *f) {
    /* 1. The depth pre-pass; what it shows (technique_see). */
    render_depth_prepass(f->gpu, f->view, f->skips->in_view);
    technique_see(f);

    /* 2. One shading pass of every object in view, with the ambient term
     *    and the lights not split from it. */
    scene_light_set split = shading_split_lights(f);
    const bool *objects = shading_all_begin(f);
    render_unshadowed(f->gpu, f->view, objects, f->skips->lights & ~split);

    /* 3. Each split light's own pass: what it reaches in its rectangle,
     *    shaded again with every light, or past one light group its own
     *    light added (shading_split_lights). */
    for (int l = 0; l < f->gpu->scene->light_count; l++) {
        if (!(split & SCENE_LIGHT_BIT(l)))
            continue;
        scene_light_set lights;
        bool ambient;
        objects = shading_split_pass(f, l, &lights, &ambient);
        render_draw_objects(f->gpu, render_use_lit(f->gpu, f->view, lights, ambient), objects);
    }
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
}

static void unshadowed_destroy(void) {}

static const char *const unshadowed_bench_configs[] = {""};

const technique unshadowed_technique = {
    .name = "unshadowed",
    .title = "no shadows: the cost floor and the picture without them",
    .bench_configs = unshadowed_bench_configs,
    .bench_config_count = 1,
    .init = unshadowed_init,
    .render = unshadowed_render,
    .destroy = unshadowed_destroy,
    .cost_floor = true,
};
