/* The web build's reference: the page cannot trace (Embree is native
 * only), so every trace fails with one line and the gallery says so;
 * compare mode shows truths baked natively instead (truth_bake.h). */
#include <stdio.h>

#include "raytrace.h"

bool raytrace_available(void) { return false; }

static void raytrace_web_refuse(const raytrace_settings *settings) {
    fprintf(stderr, "raytrace: %s: the page has no ray tracer (Embree is native only)\n",
            settings && settings->scene_name ? settings->scene_name : "scene");
}

bool raytrace_render(const scene *s, int width, int height, int light_index, const raytrace_settings *settings,
                     dump_frame *out) {
    (void)s, (void)width, (void)height, (void)light_index, (void)out;
    raytrace_web_refuse(settings);
    return false;
}

raytrace_tracer *raytrace_begin(const scene *s, int width, int height, int light_index,
                                const raytrace_settings *settings, dump_frame *out) {
    (void)s, (void)width, (void)height, (void)light_index, (void)out;
    raytrace_web_refuse(settings);
    return NULL;
}

void raytrace_rows(raytrace_tracer *t, const int *rows, int count, dump_frame *out) {
    (void)t, (void)rows, (void)count, (void)out;
}

bool raytrace_end(raytrace_tracer *t) {
    (void)t;
    return true;
}
