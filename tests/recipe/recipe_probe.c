/* recipe_probe: the throwaway technique tests/recipe/follow.sh adds by
 * README's "Adding a technique", the smallest file the recipe's first
 * step describes: the scene lit without shadows in one pass, with one
 * setting. Never in demos/ but in the copy that script makes.
 */
#include <glad/gl.h>

#include "shading.h"
#include "technique.h"

static struct {
    struct {
        bool lights_disabled; /* --no-lights: the ambient term alone */
    } settings;
} recipe_probe;

static const flags_param recipe_probe_params[] = {
    {"lights", "the ambient term alone", 0, FLAGS_TOGGLE, .disabled = &recipe_probe.settings.lights_disabled},
};

static bool recipe_probe_init(const render_scene *gpu) {
    (void)gpu;
    return true;
}

static void recipe_probe_render(const technique_frame *f) {
    /* 1. The depth pre-pass; what it shows. */
    render_depth_prepass(f->gpu, f->view, f->skips->in_view);
    technique_see(f);

    /* 2. One shading pass of every object in view, every light that
     *    reaches it unshadowed. */
    const bool *objects = shading_all_begin(f);
    render_unshadowed(f->gpu, f->view, objects, recipe_probe.settings.lights_disabled ? 0u : f->skips->lights);
}

static void recipe_probe_destroy(void) {}

static const char *const recipe_probe_bench_configs[] = {""};

const technique recipe_probe_technique = {
    .name = "recipe_probe",
    .title = "the recipe's throwaway: no shadows, in one pass",
    .params = recipe_probe_params,
    .param_count = (int)(sizeof recipe_probe_params / sizeof *recipe_probe_params),
    .bench_configs = recipe_probe_bench_configs,
    .bench_config_count = 1,
    .init = recipe_probe_init,
    .render = recipe_probe_render,
    .destroy = recipe_probe_destroy,
};
