/* unshadowed: the scene lit by every light with no shadows at all.
 *
 * Not a shadow technique but the floor every one of them is measured from:
 * the benchmark's cost baseline ("ratio to the unshadowed frame") and, in
 * a lecture, the picture that shows what shadows add (a number key in the
 * window, after the shadow techniques).
 */
#include "technique.h"

static bool unshadowed_init(const render_scene *gpu) {
    (void)gpu;
    return true;
}

/* As the techniques' camera passes draw: a depth pre-pass, then one lit
 * pass tested GL_EQUAL against it (where two objects tie for a pixel the
 * later one drawn shows, as in every technique's picture), of the objects
 * the pre-pass does not show hidden (technique_see). */
static void unshadowed_render(const technique_frame *f) {
    render_depth_prepass(f->gpu, f->view, f->in_view);
    technique_see(f);
    render_unshadowed(f->gpu, f->view, f->in_view, f->lights);
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
