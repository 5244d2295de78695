#include "volume_overlay.h"

#include <glad/gl.h>
#include <stdio.h>
#include <string.h>

#include "context.h"
#include "depth.h"
#include "legend.h"
#include "shading.h"

#define VOLUME_OVERLAY_COUNT_ALPHA 0.45f
const float volume_overlay_count_ramp[VOLUME_OVERLAY_COUNT_STEPS][3] = {
    {0.2f, 0.4f, 1}, {0.2f, 1, 0.3f}, {1, 0.9f, 0.1f}, {1, 0.2f, 0.1f}};
static const float volume_overlay_faces[4] = {1.0f, 0.85f, 0.2f, 0.12f};
static const float volume_overlay_edges[4] = {1.0f, 0.85f, 0.2f, 0.6f};
static const float volume_overlay_silhouette[4] = {1.0f, 0.3f, 0.2f, 1.0f};
/* The counts' legend: a title line, then a line per step. */
static const char *const volume_overlay_count_names[VOLUME_OVERLAY_COUNT_STEPS] = {"1", "2", "3", "4+"};
#define VOLUME_OVERLAY_LEGEND_LINES (1 + VOLUME_OVERLAY_COUNT_STEPS)
/* The wide count's class past the stencil's reach, and the legend's
 * names of the two classes that differ from the stencil's. */
static const float volume_overlay_count_beyond[3] = {0.9f, 0.2f, 0.9f};
static const char *const volume_overlay_wide_many = "4 to 255";
#define VOLUME_OVERLAY_WIDE_BEYOND_TEXT "%d and more"
#define VOLUME_OVERLAY_WIDE_TITLE "count, largest %d"
#define VOLUME_OVERLAY_WIDE_LEGEND_LINES (1 + VOLUME_WIDE_OVERLAY_STEPS)
_Static_assert(VOLUME_WIDE_OVERLAY_STEPS == VOLUME_OVERLAY_COUNT_STEPS + 1, "the wide ramp adds one class");
/* The whole screen in clip space (two triangles), for the counts. */
static const float volume_overlay_screen[6][4] = {{-1, -1, 0, 1}, {1, -1, 0, 1}, {1, 1, 0, 1},
                                                  {-1, -1, 0, 1}, {1, 1, 0, 1},  {-1, 1, 0, 1}};

void volume_overlay_counts(volume_draw *d, unsigned stencil_mask) {
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    camera_view identity = {0};
    glm_mat4_identity(identity.view_projection);
    glm_mat4_identity(identity.raster_view_projection);
    render_program_use(&d->cpu, &identity);
    glUniformMatrix4fv(d->cpu.model, 1, GL_FALSE, (const float *)identity.view_projection);
    for (int k = 1; k <= VOLUME_OVERLAY_COUNT_STEPS; k++) {
        glStencilFunc(k < VOLUME_OVERLAY_COUNT_STEPS ? GL_EQUAL : GL_LEQUAL, k, stencil_mask);
        glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
        const float *c = volume_overlay_count_ramp[k - 1];
        glUniform4f(d->cpu_color, c[0], c[1], c[2], VOLUME_OVERLAY_COUNT_ALPHA);
        volume_draw_stream(d, volume_overlay_screen, sizeof volume_overlay_screen / sizeof *volume_overlay_screen,
                           GL_TRIANGLES);
    }
    glDisable(GL_BLEND);
    glDisable(GL_STENCIL_TEST);
    legend_line legend[VOLUME_OVERLAY_LEGEND_LINES] = {{.text = "stencil count"}};
    for (int k = 0; k < VOLUME_OVERLAY_COUNT_STEPS; k++) {
        legend_line *line = &legend[1 + k];
        snprintf(line->text, sizeof line->text, "%s", volume_overlay_count_names[k]);
        line->swatches = 1;
        memcpy(line->rgb[0], volume_overlay_count_ramp[k], sizeof line->rgb[0]);
    }
    legend_draw_corner(legend, VOLUME_OVERLAY_LEGEND_LINES);
    glEnable(GL_DEPTH_TEST);
}

void volume_overlay_wide_counts(volume_wide *w) {
    float ramp[VOLUME_WIDE_OVERLAY_STEPS][3];
    memcpy(ramp, volume_overlay_count_ramp, sizeof volume_overlay_count_ramp);
    memcpy(ramp[VOLUME_OVERLAY_COUNT_STEPS], volume_overlay_count_beyond, sizeof ramp[0]);
    int largest = 0;
    volume_wide_overlay(w, (const float(*)[3])ramp, VOLUME_OVERLAY_COUNT_ALPHA, &largest);
    legend_line legend[VOLUME_OVERLAY_WIDE_LEGEND_LINES] = {{.swatches = 0}};
    snprintf(legend[0].text, sizeof legend[0].text, VOLUME_OVERLAY_WIDE_TITLE, largest);
    for (int k = 0; k < VOLUME_WIDE_OVERLAY_STEPS; k++) {
        legend_line *line = &legend[1 + k];
        if (k < VOLUME_OVERLAY_COUNT_STEPS - 1)
            snprintf(line->text, sizeof line->text, "%s", volume_overlay_count_names[k]);
        else if (k == VOLUME_OVERLAY_COUNT_STEPS - 1)
            snprintf(line->text, sizeof line->text, "%s", volume_overlay_wide_many);
        else
            snprintf(line->text, sizeof line->text, VOLUME_OVERLAY_WIDE_BEYOND_TEXT,
                     VOLUME_COUNT_BOUND_STENCIL_MAX + 1);
        line->swatches = 1;
        memcpy(line->rgb[0], ramp[k], sizeof line->rgb[0]);
    }
    legend_draw_corner(legend, VOLUME_OVERLAY_WIDE_LEGEND_LINES);
}

/* Whether the volumes' faces get their wire edges: they need
 * glPolygonMode, which is said once where the context lacks it. */
static bool volume_overlay_wires(void) {
    static bool said;
    bool wires = context_current_features()->polygon_mode;
    if (!wires && !said)
        fprintf(stderr, "volumes: --overlay volumes: no wire edges, the context has no glPolygonMode\n");
    said = said || !wires;
    return wires;
}

void volume_overlay_shapes(volume_draw *d, const technique_frame *f, const float light[4], bool faces) {
    const scene *s = f->gpu->scene;
    glDisable(GL_STENCIL_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    glDepthFunc(depth_func(f->view, GL_LEQUAL));
    depth_clamp(true);
    for (int i = 0; i < s->object_count; i++) {
        if (!s->objects[i].casts ||
            !volume_draw_build(d, f, i, light, faces ? VOLUME_MESH_SIDES : VOLUME_MESH_SILHOUETTE_LINES))
            continue;
        const volume_mesh *v = &d->geometry;
        if (faces) {
            glUniform4fv(d->cpu_color, 1, volume_overlay_faces);
            volume_draw_stream(d, v->vertices, v->count, GL_TRIANGLES);
            if (volume_overlay_wires()) {
                glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
                glUniform4fv(d->cpu_color, 1, volume_overlay_edges);
                volume_draw_stream(d, v->vertices, v->count, GL_TRIANGLES);
                glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
            }
        } else {
            glUniform4fv(d->cpu_color, 1, volume_overlay_silhouette);
            glDepthFunc(GL_ALWAYS);
            volume_draw_stream(d, v->vertices, v->count, GL_LINES);
            glDepthFunc(depth_func(f->view, GL_LEQUAL));
        }
    }
    depth_clamp(false);
    glDisable(GL_BLEND);
}

void volume_overlay_draw(volume_overlay_kind kind, const technique_frame *f, volume_counter *c,
                         volume_plan_caster *casters, bool trim) {
    const scene *s = f->gpu->scene;
    if (kind == VOLUME_OVERLAY_NONE || s->light_count == 0)
        return;
    volume_draw_reach(c->draw, &s->lights[0], trim);
    volume_plan plan;
    float centre[4];
    scene_light_homogeneous(&s->lights[0], centre);
    volume_plan_every_caster(f, 0, centre, c->settings.mode, casters, &plan);
    plan.cache = volume_draw_cache(0, SHADING_LIGHT_CENTRE);
    if (kind != VOLUME_OVERLAY_COUNTS) {
        volume_overlay_shapes(c->draw, f, plan.position, kind == VOLUME_OVERLAY_VOLUMES);
        return;
    }
    plan.bounds.rect[2] = f->width;
    plan.bounds.rect[3] = f->height;
    volume_counter_clear(c, f, &plan);
    glDisable(GL_SCISSOR_TEST);
    volume_counter_begin(c, f, &plan);
    bool wide = c->counting_wide;
    volume_counter_draw(c, f, &plan);
    if (wide) {
        volume_counter_end(c, f);
        volume_overlay_wide_counts(&c->wide);
    } else {
        volume_overlay_counts(c->draw, VOLUME_COUNTER_STENCIL_MASK);
    }
}
