/* compare: see compare.h. The cells are drawn with framebuffer blits (the
 * truth and the heat map uploaded into textures when they change) and the
 * legend with legend.h (the HUD's text, scissored clears as swatches), so
 * nothing here needs a program of its own. */
#include "compare.h"

#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "context.h"
#include "hud.h"
#include "legend.h"
#include "scene.h"
#include "truth_bake.h"

enum { COMPARE_TRUTH, COMPARE_HEAT };
/* Before the truth has a row, and the heat map before it has figures. */
static const unsigned char compare_empty_grey = 24;

/* The legend's lines at most: one on the cells (and how wide an error is
 * drawn), the kinds, three of figures (misclassified, MAE, the truth) and
 * one a class. */
#define COMPARE_LEGEND_MAX_LINES (1 + SHADOWDIFF_PIXEL_KIND_COUNT + 3 + SHADOWDIFF_CLASS_COUNT)
/* Decimals of the mean absolute errors, the whole one's and each class's. */
#define COMPARE_MAE_DECIMALS 5

int compare_strip_height(int height) {
    return (COMPARE_STRIP_LINES * HUD_LINE_UNITS + 2 * HUD_MARGIN) * hud_scale_for(height);
}

bool compare_create(compare *c, int width, int height, const raytrace_settings *settings, const char *baked_dir) {
    int strip = compare_strip_height(height);
    *c = (compare){.strip_height = strip, .cell_width = width / 2, .cell_height = (height - strip) / 2};
    if (c->cell_width < 1 || c->cell_height < 1) {
        fprintf(stderr, "compare: a %dx%d picture has no room for a caption and four cells\n", width, height);
        return false;
    }
    size_t pixels = (size_t)c->cell_width * (size_t)c->cell_height;
    c->truth_rgba = malloc(4 * pixels);
    c->heat_rgba = malloc(4 * pixels);
    c->traced = malloc((size_t)c->cell_height * sizeof *c->traced);
    if (!c->truth_rgba || !c->heat_rgba || !c->traced) {
        fprintf(stderr, "compare: out of memory for %dx%d cells\n", c->cell_width, c->cell_height);
        free(c->truth_rgba), free(c->heat_rgba), free(c->traced);
        return false;
    }
    if (!target_create(&c->picture, width, height)) {
        free(c->truth_rgba), free(c->heat_rgba), free(c->traced);
        return false;
    }
    glGenTextures(2, c->textures);
    glGenFramebuffers(2, c->framebuffers);
    for (int k = 0; k < 2; k++) {
        glBindTexture(GL_TEXTURE_2D, c->textures[k]);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, c->cell_width, c->cell_height, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glBindFramebuffer(GL_FRAMEBUFFER, c->framebuffers[k]);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, c->textures[k], 0);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            fprintf(stderr, "compare: a %dx%d cell's framebuffer is incomplete\n", c->cell_width, c->cell_height);
            compare_destroy(c);
            return false;
        }
    }
    memset(c->truth_rgba, compare_empty_grey, 4 * pixels);
    memset(c->heat_rgba, compare_empty_grey, 4 * pixels);
    if (!context_gl_ok("compare_create") ||
        !truth_start(&c->truth, c->cell_width, c->cell_height, settings, baked_dir)) {
        compare_destroy(c);
        return false;
    }
    return true;
}

/* The truth's colour for the cell: traced rows as they are, the others a
 * copy of the nearest traced row above (row 0 is the first traced). */
static void compare_fill_truth(compare *c) {
    const truth_frame *f = &c->shown;
    size_t row = (size_t)c->cell_width * 4;
    if (!f->dump.width || f->rows == 0) {
        memset(c->truth_rgba, compare_empty_grey, row * (size_t)c->cell_height);
        return;
    }
    memset(c->traced, 0, (size_t)c->cell_height * sizeof *c->traced);
    for (int k = 0; k < f->rows; k++)
        c->traced[c->truth.row_order[k]] = true;
    int source = 0;
    for (int y = 0; y < c->cell_height; y++) {
        source = c->traced[y] ? y : source;
        memcpy(c->truth_rgba + (size_t)y * row, f->dump.color + (size_t)source * row, row);
    }
}

/* The heat map's error discs' radius. */
static int compare_error_radius(const compare *c) { return shadowdiff_magnify_radius(c->cell_height); }

/* The heat map and figures of the decisions against the truth so far;
 * false when out of memory. */
static bool compare_measure(compare *c) {
    /* Grey until measured, and after a mismatch, which shadowdiff does
     * not paint. */
    memset(c->heat_rgba, compare_empty_grey, (size_t)c->cell_width * (size_t)c->cell_height * 4);
    c->measured = false;
    if (c->decisions_of != c->shown.request || !c->shown.dump.width || !c->decisions.width)
        return true;
    const shadowdiff_settings settings = {.reference_name = "the truth", .test_name = "the technique"};
    c->measured = shadowdiff_compare(&c->shown.dump, &c->decisions, &settings, &c->result, c->heat_rgba);
    return !c->measured ||
           shadowdiff_heatmap_magnify(c->heat_rgba, c->cell_width, c->cell_height, compare_error_radius(c));
}

static void compare_upload(const compare *c, int cell, const unsigned char *rgba) {
    glBindTexture(GL_TEXTURE_2D, c->textures[cell]);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, c->cell_width, c->cell_height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
}

bool compare_update(compare *c, const scene *s, int light, compare_capture capture, bool wait) {
    truth_request(&c->truth, s, light);
    if (wait)
        truth_wait(&c->truth);
    bool changed = truth_take(&c->truth, &c->shown);
    if (c->bake_into && c->shown.complete && c->baked_of != c->shown.request) {
        if (!truth_bake_write(c->bake_into, &c->shown.dump, s, &c->truth.settings))
            return false;
        c->baked_of = c->shown.request;
    }
    /* The decisions are captured for the view the truth is of, so only
     * once the truth is of the current one. */
    if (c->shown.current && c->shown.rows > 0 && (c->decisions_of != c->shown.request || c->decisions_stale)) {
        dump_frame_free(&c->decisions);
        if (!capture(light, &c->decisions))
            return false;
        c->decisions_of = c->shown.request;
        c->decisions_stale = false;
        changed = true;
    }
    if (!changed)
        return true;
    compare_fill_truth(c);
    if (!compare_measure(c))
        return false;
    compare_upload(c, COMPARE_TRUTH, c->truth_rgba);
    compare_upload(c, COMPARE_HEAT, c->heat_rgba);
    return context_gl_ok("compare_update");
}

void compare_figures_text(const compare *c, char *text, size_t size) {
    char truth[64];
    snprintf(truth, sizeof truth, "truth %d/%d rows", c->shown.rows, c->cell_height);
    if (!c->measured) {
        snprintf(text, size, "no figures yet, %s", truth);
        return;
    }
    const shadowdiff_result *r = &c->result;
    char classes[SHADOWDIFF_CLASS_COUNT * SHADOWDIFF_CLASS_FIGURES_TEXT_MAX] = "";
    for (int k = 0; k < SHADOWDIFF_CLASS_COUNT; k++) {
        char one[SHADOWDIFF_CLASS_FIGURES_TEXT_MAX];
        shadowdiff_class_figures_text(r, (shadowdiff_class)k, COMPARE_MAE_DECIMALS, one, sizeof one);
        size_t used = strlen(classes);
        snprintf(classes + used, sizeof classes - used, "%s, ", one);
    }
    snprintf(text, size,
             "misclassified %.4f %% (false shadow %.4f %%, false lit %.4f %%), mean absolute error %.*f, %ld pixels "
             "compared, %s%s",
             r->misclassified_percent, r->false_shadow_percent, r->false_lit_percent, COMPARE_MAE_DECIMALS,
             r->mean_abs_error, r->compared, classes, truth);
}

/* The truth's state, the legend's last line. */
static void compare_truth_text(const compare *c, char *text, size_t size) {
    const truth_frame *f = &c->shown;
    if (f->failed && c->truth.baked_dir)
        snprintf(text, size, "truth: none baked for this view (0: the loaded view)");
    else if (f->failed)
        snprintf(text, size, "truth: the trace FAILED (see stderr)");
    else if (f->complete && c->truth.baked_dir)
        snprintf(text, size, "truth: Embree, baked for this view");
    else if (f->complete && c->show_seconds)
        snprintf(text, size, "truth: Embree, traced in %.2f s", f->seconds);
    else if (f->complete)
        snprintf(text, size, "truth: Embree, every row traced");
    else if (!f->current)
        snprintf(text, size, "truth: the view moved, tracing it anew");
    else
        snprintf(text, size, "truth: %d %% of rows traced", (int)(100.0 * f->rows / c->cell_height));
}

/* Appends a line of the legend, with `swatches` of the colours (0..255). */
static void compare_legend_add(legend_line *lines, int *count, int swatches, const unsigned char rgb[2][3],
                               const char *text) {
    legend_line *line = &lines[(*count)++];
    snprintf(line->text, sizeof line->text, "%s", text);
    line->swatches = swatches;
    for (int s = 0; s < swatches; s++)
        for (int k = 0; k < 3; k++)
            line->rgb[s][k] = rgb[s][k] / 255.0f;
}

/* The legend's lines: with `brief`, for a small cell (a thumbnail), the
 * kinds, the misclassified share and, where the truth has a penumbra, its
 * MAE. Returns their count. */
static int compare_legend_lines(const compare *c, bool brief, legend_line lines[COMPARE_LEGEND_MAX_LINES]) {
    const shadowdiff_result *r = &c->result;
    int count = 0;
    char text[LEGEND_TEXT_MAX];
    if (!brief) {
        snprintf(text, sizeof text, "above: technique | truth; left: errors (%d px)",
                 2 * compare_error_radius(c) + 1);
        compare_legend_add(lines, &count, 0, NULL, text);
    }
    for (int k = 0; k < SHADOWDIFF_PIXEL_KIND_COUNT; k++) { /* each with its swatch */
        shadowdiff_pixel kind = shadowdiff_legend_kinds[k];
        int n = snprintf(text, sizeof text, "%s", shadowdiff_pixel_names[kind]);
        if (c->measured && kind == SHADOWDIFF_PIXEL_FALSE_SHADOW)
            snprintf(text + n, sizeof text - (size_t)n, "   %.4f %%", r->false_shadow_percent);
        if (c->measured && kind == SHADOWDIFF_PIXEL_FALSE_LIT)
            snprintf(text + n, sizeof text - (size_t)n, "   %.4f %%", r->false_lit_percent);
        /* AGREES: its lit end, and its shadowed end beside it. */
        const unsigned char swatch[2][3] = {
            {shadowdiff_pixel_colors[kind][0], shadowdiff_pixel_colors[kind][1], shadowdiff_pixel_colors[kind][2]},
            {SHADOWDIFF_AGREES_GREY_SHADOWED, SHADOWDIFF_AGREES_GREY_SHADOWED, SHADOWDIFF_AGREES_GREY_SHADOWED}};
        compare_legend_add(lines, &count, kind == SHADOWDIFF_PIXEL_AGREES ? 2 : 1, swatch, text);
    }
    char truth[96];
    compare_truth_text(c, truth, sizeof truth);
    if (brief && c->measured) {
        snprintf(text, sizeof text, "misclassified %.4f %%", r->misclassified_percent);
        compare_legend_add(lines, &count, 0, NULL, text);
        if (r->class_pixels[SHADOWDIFF_CLASS_PENUMBRA] > 0) { /* a soft shadow's own figure */
            snprintf(text, sizeof text, "%s MAE %.*f", shadowdiff_class_names[SHADOWDIFF_CLASS_PENUMBRA],
                     COMPARE_MAE_DECIMALS, r->class_mae[SHADOWDIFF_CLASS_PENUMBRA]);
            compare_legend_add(lines, &count, 0, NULL, text);
        }
    } else if (c->measured) {
        snprintf(text, sizeof text, "misclassified %.4f %% of %ld pixels", r->misclassified_percent, r->compared);
        compare_legend_add(lines, &count, 0, NULL, text);
        snprintf(text, sizeof text, "mean absolute error %.*f", COMPARE_MAE_DECIMALS, r->mean_abs_error);
        compare_legend_add(lines, &count, 0, NULL, text);
        for (int k = 0; k < SHADOWDIFF_CLASS_COUNT; k++) {
            if (r->class_pixels[k] == 0) /* a class the view does not hold */
                continue;
            shadowdiff_class_figures_text(r, (shadowdiff_class)k, COMPARE_MAE_DECIMALS, text, sizeof text);
            compare_legend_add(lines, &count, 0, NULL, text);
        }
        compare_legend_add(lines, &count, 0, NULL, truth);
    } else {
        compare_legend_add(lines, &count, 0, NULL, "no figures yet");
        if (!brief)
            compare_legend_add(lines, &count, 0, NULL, truth);
    }
    return count;
}

/* The bottom-right cell: one line per kind of heat-map pixel, each with
 * its swatch at the left, then the figures and the truth's state; briefer
 * where the cell is too small for all of it (smaller still: cut at the
 * cell's edge). */
static void compare_draw_legend(const compare *c) {
    int x0 = c->cell_width, y0 = c->strip_height + c->cell_height; /* the cell's top-left, from the picture's top */
    legend_line lines[COMPARE_LEGEND_MAX_LINES];
    int count = compare_legend_lines(c, false, lines);
    int scale = legend_scale_to_fit(lines, count, c->cell_width, c->cell_height, c->picture.height);
    if (!scale) {
        count = compare_legend_lines(c, true, lines);
        scale = legend_scale_to_fit(lines, count, c->cell_width, c->cell_height, c->picture.height);
    }
    glViewport(0, 0, c->picture.width, c->picture.height);
    glEnable(GL_SCISSOR_TEST);
    glClearColor(legend_panel_color[0], legend_panel_color[1], legend_panel_color[2], 1);
    glScissor(x0, c->picture.height - y0 - c->cell_height, c->cell_width, c->cell_height);
    glClear(GL_COLOR_BUFFER_BIT);
    glScissor(0, c->picture.height - c->strip_height, c->picture.width, c->strip_height); /* the caption's */
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    legend_draw(lines, count, x0, y0, scale ? scale : 1);
}

/* Cell `k` of the uploaded ones to the picture at (x, y) from the
 * picture's top-left: the rows are top first, so the blit turns them. */
static void compare_blit_cell(const compare *c, int k, int x, int y) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, c->framebuffers[k]);
    int top = c->picture.height - y, bottom = top - c->cell_height;
    glBlitFramebuffer(0, 0, c->cell_width, c->cell_height, x, top, x + c->cell_width, bottom, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
}

bool compare_draw(compare *c, const target *cell) {
    target_bind(&c->picture);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, cell->framebuffer);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, c->picture.framebuffer);
    int top = c->picture.height - c->strip_height;
    glBlitFramebuffer(0, 0, c->cell_width, c->cell_height, 0, top - c->cell_height, c->cell_width, top,
                      GL_COLOR_BUFFER_BIT, GL_NEAREST);
    compare_blit_cell(c, COMPARE_TRUTH, c->cell_width, c->strip_height);
    compare_blit_cell(c, COMPARE_HEAT, 0, c->strip_height + c->cell_height);
    target_bind(&c->picture);
    compare_draw_legend(c);
    return context_gl_ok("compare_draw");
}

void compare_decisions_changed(compare *c) { c->decisions_stale = true; }

void compare_forget(compare *c) {
    truth_forget(&c->truth);
    truth_frame_free(&c->shown);
    dump_frame_free(&c->decisions);
    c->decisions_of = 0;
    c->measured = false;
}

void compare_destroy(compare *c) {
    truth_stop(&c->truth);
    truth_frame_free(&c->shown);
    dump_frame_free(&c->decisions);
    glDeleteFramebuffers(2, c->framebuffers);
    glDeleteTextures(2, c->textures);
    target_destroy(&c->picture);
    free(c->truth_rgba), free(c->heat_rgba), free(c->traced);
    *c = (compare){0};
}
