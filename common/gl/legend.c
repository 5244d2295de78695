#include "legend.h"

#include <glad/gl.h>
#include <stdio.h>

#include "hud.h"

const float legend_panel_color[3] = {0.08f, 0.08f, 0.09f};
static const float legend_swatch_frame[3] = {0.6f, 0.6f, 0.6f};
/* Room for every line's text, '\n' between them. */
#define LEGEND_MAX_JOINED 4096

static void legend_join(const legend_line *lines, int count, char *text, size_t size) {
    size_t n = 0;
    text[0] = '\0';
    for (int k = 0; k < count && n < size; k++)
        n += (size_t)snprintf(text + n, size - n, "%s%s", k ? "\n" : "", lines[k].text);
}

int legend_width_units(const legend_line *lines, int count) {
    char text[LEGEND_MAX_JOINED];
    legend_join(lines, count, text, sizeof text);
    return LEGEND_SWATCH_UNITS + LEGEND_SWATCH_GAP_UNITS + hud_text_width(text) + 2 * HUD_MARGIN;
}

int legend_height_units(int count) { return count * HUD_LINE_UNITS + 2 * HUD_MARGIN; }

int legend_scale_to_fit(const legend_line *lines, int count, int width, int height, int framebuffer_height) {
    int width_units = legend_width_units(lines, count), height_units = legend_height_units(count);
    for (int scale = hud_scale_for(framebuffer_height); scale >= 1; scale--)
        if (width_units * scale <= width && height_units * scale <= height)
            return scale;
    return 0;
}

/* A solid rectangle, pixels from the viewport's top-left. */
static void legend_rect(const int viewport[4], int x, int y, int width, int height, const float rgb[3]) {
    glScissor(viewport[0] + x, viewport[1] + viewport[3] - y - height, width, height);
    glClearColor(rgb[0], rgb[1], rgb[2], 1);
    glClear(GL_COLOR_BUFFER_BIT);
}

void legend_draw(const legend_line *lines, int count, int x, int y, int scale) {
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    char text[LEGEND_MAX_JOINED];
    legend_join(lines, count, text, sizeof text);
    int column = (LEGEND_SWATCH_UNITS + LEGEND_SWATCH_GAP_UNITS) * scale;
    int text_width = (hud_text_width(text) + 2 * HUD_MARGIN) * scale;
    int height = legend_height_units(count) * scale;

    glEnable(GL_SCISSOR_TEST);
    legend_rect(viewport, x, y, column + text_width, height, legend_panel_color);
    glDisable(GL_SCISSOR_TEST);
    glViewport(viewport[0] + x + column, viewport[1] + viewport[3] - y - height, text_width, height);
    hud_draw(text, text_width, height, scale, 0);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    glEnable(GL_SCISSOR_TEST);
    int size = HUD_LETTER_UNITS * scale, half = size / 2;
    for (int k = 0; k < count; k++) {
        const legend_line *line = &lines[k];
        int left = x + HUD_MARGIN * scale, top = y + (HUD_MARGIN + k * HUD_LINE_UNITS) * scale;
        if (line->swatches < 1)
            continue;
        legend_rect(viewport, left - 1, top - 1, size + 2, size + 2, legend_swatch_frame);
        legend_rect(viewport, left, top, size, size, line->rgb[0]);
        if (line->swatches > 1)
            legend_rect(viewport, left + half, top, size - half, size, line->rgb[1]);
    }
    glDisable(GL_SCISSOR_TEST);
}

void legend_draw_corner(const legend_line *lines, int count) {
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    int scale = hud_scale_for(viewport[3]), margin = HUD_MARGIN * scale;
    int fitted = legend_scale_to_fit(lines, count, viewport[2] - 2 * margin, viewport[3] - 2 * margin, viewport[3]);
    scale = fitted ? fitted : 1;
    int width = legend_width_units(lines, count) * scale, height = legend_height_units(count) * scale;
    legend_draw(lines, count, viewport[2] - margin - width, viewport[3] - margin - height, scale);
}
