/* compare: see compare.h. The cells are drawn with framebuffer blits (the
 * truth and the heat map uploaded into textures when they change) and the
 * legend with the HUD's text and scissored clears as swatches, so nothing
 * here needs a program of its own. */
#include "compare.h"

#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "context.h"
#include "hud.h"
#include "scene.h"

enum { COMPARE_TRUTH, COMPARE_HEAT };
/* Before the truth has a row, and the heat map before it has figures. */
static const unsigned char compare_empty_grey = 24;
/* The legend's cell (the HUD's panel draws over it). */
static const float compare_legend_background[3] = {0.08f, 0.08f, 0.09f};
static const float compare_agrees_shadowed[3] = {
    SHADOWDIFF_AGREES_GREY_SHADOWED / 255.0f, SHADOWDIFF_AGREES_GREY_SHADOWED / 255.0f,
    SHADOWDIFF_AGREES_GREY_SHADOWED / 255.0f};
static const float compare_swatch_frame[3] = {0.6f, 0.6f, 0.6f};
/* Font units of the swatch column left of the legend's text. */
#define COMPARE_SWATCH_UNITS 10
#define COMPARE_SWATCH_GAP_UNITS 2

/* The legend's lines: the heat map's kinds in the order drawn, each with
 * a swatch (two for AGREES: its lit and its shadowed end). */
static const shadowdiff_pixel compare_legend_kinds[] = {
    SHADOWDIFF_PIXEL_FALSE_SHADOW, SHADOWDIFF_PIXEL_FALSE_LIT, SHADOWDIFF_PIXEL_AGREES,
    SHADOWDIFF_PIXEL_NOT_COMPARED, SHADOWDIFF_PIXEL_NO_SURFACE,
};
enum { compare_legend_count = sizeof compare_legend_kinds / sizeof *compare_legend_kinds };
/* The legend's lines before the kinds': what the cells are. */
#define COMPARE_LEGEND_INTRO_LINES 2

bool compare_create(compare *c, int width, int height, const raytrace_settings *settings) {
    *c = (compare){.cell_width = width / 2, .cell_height = height / 2};
    if (c->cell_width < 1 || c->cell_height < 1) {
        fprintf(stderr, "compare: a %dx%d picture has no room for four cells\n", width, height);
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
    if (!context_gl_ok("compare_create") || !truth_start(&c->truth, c->cell_width, c->cell_height, settings)) {
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

/* The heat map and figures of the decisions against the truth so far. */
static void compare_measure(compare *c) {
    /* Grey until measured, and after a mismatch, which shadowdiff does
     * not paint. */
    memset(c->heat_rgba, compare_empty_grey, (size_t)c->cell_width * (size_t)c->cell_height * 4);
    c->measured = false;
    if (c->decisions_of != c->shown.request || !c->shown.dump.width || !c->decisions.width)
        return;
    const shadowdiff_settings settings = {.reference_name = "the truth", .test_name = "the technique"};
    c->measured = shadowdiff_compare(&c->shown.dump, &c->decisions, &settings, &c->result, c->heat_rgba);
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
    compare_measure(c);
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
    snprintf(text, size,
             "misclassified %.4f %% (false shadow %.4f %%, false lit %.4f %%), mean absolute error %.5f, %ld pixels "
             "compared, %s",
             r->misclassified_percent, r->false_shadow_percent, r->false_lit_percent, r->mean_abs_error, r->compared,
             truth);
}

/* The truth's state, the legend's last line. */
static void compare_truth_text(const compare *c, char *text, size_t size) {
    const truth_frame *f = &c->shown;
    if (f->failed)
        snprintf(text, size, "truth: the trace FAILED (see stderr)");
    else if (f->complete && c->show_seconds)
        snprintf(text, size, "truth: Embree, traced in %.2f s", f->seconds);
    else if (f->complete)
        snprintf(text, size, "truth: Embree, every row traced");
    else if (!f->current)
        snprintf(text, size, "truth: the view moved, tracing it anew");
    else
        snprintf(text, size, "truth: %d %% of rows traced", (int)(100.0 * f->rows / c->cell_height));
}

/* A solid rectangle, picture pixels from the top-left. */
static void compare_rect(const compare *c, int x, int y, int width, int height, const float rgb[3]) {
    glScissor(x, c->picture.height - y - height, width, height);
    glClearColor(rgb[0], rgb[1], rgb[2], 1);
    glClear(GL_COLOR_BUFFER_BIT);
}

/* A swatch framed, so that the dark kinds show on the dark cell too. */
static void compare_swatch(const compare *c, int x, int y, int size, const unsigned char rgb[3]) {
    const float color[3] = {rgb[0] / 255.0f, rgb[1] / 255.0f, rgb[2] / 255.0f};
    compare_rect(c, x - 1, y - 1, size + 2, size + 2, compare_swatch_frame);
    compare_rect(c, x, y, size, size, color);
}

/* The legend's text: with `brief`, for a small cell (a thumbnail), the
 * kinds and the misclassified share only. Returns its first kind's line. */
static int compare_legend_text(const compare *c, bool brief, char *text, size_t size) {
    const shadowdiff_result *r = &c->result;
    int n = brief ? 0 : snprintf(text, size, "above: the technique | the ray-traced truth\nleft: the heat map of its errors\n");
    int first_kind_line = brief ? 0 : COMPARE_LEGEND_INTRO_LINES;
    for (int k = 0; k < compare_legend_count; k++) {
        shadowdiff_pixel kind = compare_legend_kinds[k];
        n += snprintf(text + n, size - (size_t)n, "%s", shadowdiff_pixel_names[kind]);
        if (c->measured && kind == SHADOWDIFF_PIXEL_FALSE_SHADOW)
            n += snprintf(text + n, size - (size_t)n, "   %.4f %%", r->false_shadow_percent);
        if (c->measured && kind == SHADOWDIFF_PIXEL_FALSE_LIT)
            n += snprintf(text + n, size - (size_t)n, "   %.4f %%", r->false_lit_percent);
        n += snprintf(text + n, size - (size_t)n, "\n");
    }
    char truth[96];
    compare_truth_text(c, truth, sizeof truth);
    if (brief && c->measured)
        snprintf(text + n, size - (size_t)n, "misclassified %.4f %%", r->misclassified_percent);
    else if (c->measured)
        snprintf(text + n, size - (size_t)n, "misclassified %.4f %% of %ld pixels\nmean absolute error %.5f\n%s",
                 r->misclassified_percent, r->compared, r->mean_abs_error, truth);
    else
        snprintf(text + n, size - (size_t)n, "no figures yet%s%s", brief ? "" : "\n", brief ? "" : truth);
    return first_kind_line;
}

/* The largest scale, at most the window HUD's, at which `text` fits the
 * cell beside the swatches without wrapping (hud_draw would wrap it, and
 * the swatches would no longer face their lines); 0 if none does. */
static int compare_legend_scale(const compare *c, const char *text) {
    int lines = 1;
    for (const char *p = text; *p; p++)
        lines += *p == '\n';
    int room_units = COMPARE_SWATCH_UNITS + COMPARE_SWATCH_GAP_UNITS + hud_text_width(text) + 2 * HUD_MARGIN;
    int height_units = lines * HUD_LINE_UNITS + 2 * HUD_MARGIN;
    for (int scale = hud_scale_for(c->picture.height); scale >= 1; scale--)
        if (room_units * scale <= c->cell_width && height_units * scale <= c->cell_height)
            return scale;
    return 0;
}

/* The bottom-right cell: one line per kind of heat-map pixel, each with
 * its swatch at the left, then the figures and the truth's state; briefer
 * where the cell is too small for all of it. */
static void compare_draw_legend(const compare *c) {
    int x0 = c->cell_width, y0 = c->cell_height; /* the cell's top-left, from the picture's top */
    char text[2048];
    int first_kind_line = compare_legend_text(c, false, text, sizeof text);
    int scale = compare_legend_scale(c, text);
    if (!scale) {
        first_kind_line = compare_legend_text(c, true, text, sizeof text);
        scale = compare_legend_scale(c, text);
    }
    scale = scale ? scale : 1; /* smaller still: cut at the cell's edge */

    glEnable(GL_SCISSOR_TEST);
    compare_rect(c, x0, y0, c->cell_width, c->cell_height, compare_legend_background);
    glDisable(GL_SCISSOR_TEST);
    int column = (COMPARE_SWATCH_UNITS + COMPARE_SWATCH_GAP_UNITS) * scale;
    glViewport(x0 + column, c->picture.height - 2 * c->cell_height, c->cell_width - column, c->cell_height);
    hud_draw(text, c->cell_width - column, c->cell_height, scale);
    glViewport(0, 0, c->picture.width, c->picture.height);
    glEnable(GL_SCISSOR_TEST);
    int size = HUD_LETTER_UNITS * scale, half = size / 2;
    for (int k = 0; k < compare_legend_count; k++) {
        shadowdiff_pixel kind = compare_legend_kinds[k];
        int x = x0 + HUD_MARGIN * scale, y = y0 + (HUD_MARGIN + (k + first_kind_line) * HUD_LINE_UNITS) * scale;
        compare_swatch(c, x, y, size, shadowdiff_pixel_colors[kind]);
        if (kind == SHADOWDIFF_PIXEL_AGREES) /* its shadowed end beside the lit one */
            compare_rect(c, x + half, y, size - half, size, compare_agrees_shadowed);
    }
    glDisable(GL_SCISSOR_TEST);
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
    int top = c->picture.height - c->cell_height;
    glBlitFramebuffer(0, 0, c->cell_width, c->cell_height, 0, top, c->cell_width, c->picture.height,
                      GL_COLOR_BUFFER_BIT, GL_NEAREST);
    compare_blit_cell(c, COMPARE_TRUTH, c->cell_width, 0);
    compare_blit_cell(c, COMPARE_HEAT, 0, c->cell_height);
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
