#include "hud.h"

#include <glad/gl.h>
#include <stdio.h>
#include <string.h>
/* stb_easy_font is all static functions; not every one is used. */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-braces"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

#include "shader.h"

#define HUD_MAX_QUADS 8000 /* about 32 lines of 80 characters */
#define HUD_MAX_TEXT 8192
#define HUD_VERTEX_BYTES 16 /* stb_easy_font: x, y, z floats and RGBA bytes */
/* Font units of panel below the text's last line (HUD_LINE_UNITS tall;
 * the text starts HUD_MARGIN below the panel's top). */
#define HUD_PANEL_BOTTOM_UNITS 2

static struct {
    unsigned program, vao, vertex_buffer, index_buffer;
    int viewport, scale;
    unsigned char vertices[HUD_MAX_QUADS * 4 * HUD_VERTEX_BYTES];
} hud;

bool hud_init(void) {
    static const char *const files[] = {"hud.vert", "hud.frag"};
    hud.program = shader_load_program(files, 2, NULL);
    if (!hud.program)
        return false;
    hud.viewport = shader_uniform(hud.program, "u_viewport");
    hud.scale = shader_uniform(hud.program, "u_scale");
    /* stb_easy_font emits quads; GL 3.3 core draws triangles. */
    static unsigned indices[HUD_MAX_QUADS * 6];
    for (unsigned q = 0; q < HUD_MAX_QUADS; q++) {
        static const unsigned corner[6] = {0, 1, 2, 0, 2, 3};
        for (int k = 0; k < 6; k++)
            indices[q * 6 + k] = q * 4 + corner[k];
    }
    glGenVertexArrays(1, &hud.vao);
    glBindVertexArray(hud.vao);
    glGenBuffers(1, &hud.vertex_buffer);
    glBindBuffer(GL_ARRAY_BUFFER, hud.vertex_buffer);
    glBufferData(GL_ARRAY_BUFFER, sizeof hud.vertices, NULL, GL_STREAM_DRAW);
    glGenBuffers(1, &hud.index_buffer);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, hud.index_buffer);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, sizeof indices, indices, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, HUD_VERTEX_BYTES, (void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 4, GL_UNSIGNED_BYTE, GL_TRUE, HUD_VERTEX_BYTES, (void *)12);
    glBindVertexArray(0);
    return true;
}

int hud_scale_for(int height) {
    int scale = (height + HUD_LINES_PER_SCALE / 2) / HUD_LINES_PER_SCALE;
    return scale < 1 ? 1 : scale > HUD_MAX_SCALE ? HUD_MAX_SCALE : scale;
}

int hud_text_width(const char *text) {
    char copy[HUD_MAX_TEXT];
    snprintf(copy, sizeof copy, "%s", text);
    return stb_easy_font_width(copy);
}

/* Whether `length` characters of `line` and then `count` of `piece` fit
 * in `room` font units. */
static bool hud_fits(const char *line, size_t length, const char *piece, size_t count, int room) {
    char joined[HUD_MAX_TEXT];
    snprintf(joined, sizeof joined, "%.*s%.*s", (int)length, line, (int)count, piece);
    return hud_text_width(joined) <= room;
}

/* Appends `count` characters of `text` to out at *n, truncating. */
static void hud_append(char *out, size_t size, size_t *n, const char *text, size_t count) {
    size_t room = size - 1 - *n;
    count = count < room ? count : room;
    memcpy(out + *n, text, count);
    *n += count;
    out[*n] = '\0';
}

int hud_wrap(const char *text, int width, int scale, char *out, size_t size) {
    int room = width / (scale > 0 ? scale : 1) - 2 * HUD_MARGIN; /* font units a line may take */
    char line[HUD_MAX_TEXT];                                     /* the output line being filled */
    size_t length = 0, n = 0;
    bool empty = true; /* nothing on the line yet but a continuation's indent */
    int lines = 1;
    out[0] = '\0';
    for (const char *p = text;;) {
        if (*p == '\n' || !*p) {
            hud_append(out, size, &n, line, length);
            if (!*p)
                return lines;
            hud_append(out, size, &n, "\n", 1);
            lines++;
            length = 0;
            empty = true;
            p++;
            continue;
        }
        size_t piece = strspn(p, " ");
        piece += strcspn(p + piece, " \n");
        if (piece >= sizeof line - length)
            piece = sizeof line - length - 1;
        bool fits = hud_fits(line, length, p, piece, room);
        if (!fits && !empty) {
            /* A break: the spaces before the word go with it. */
            hud_append(out, size, &n, line, length);
            hud_append(out, size, &n, "\n", 1);
            lines++;
            length = strlen(HUD_INDENT);
            memcpy(line, HUD_INDENT, length);
            empty = true;
            p += strspn(p, " ");
            continue;
        }
        /* Alone, and wider than a whole line: as much of it as fits (at
         * least one character), the rest on the next. */
        while (!fits && piece > 1 && !hud_fits(line, length, p, piece, room))
            piece--;
        memcpy(line + length, p, piece);
        length += piece;
        p += piece;
        empty = false;
    }
}

/* Appends one quad of solid colour in stb_easy_font's vertex layout. */
static int hud_add_panel(int quads, float x0, float y0, float x1, float y1) {
    const float corners[4][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    for (int k = 0; k < 4; k++) {
        unsigned char *v = hud.vertices + ((size_t)quads * 4 + k) * HUD_VERTEX_BYTES;
        const float xyz[3] = {corners[k][0], corners[k][1], 0};
        const unsigned char rgba[4] = {0, 0, 0, 160};
        memcpy(v, xyz, sizeof xyz);
        memcpy(v + 12, rgba, sizeof rgba);
    }
    return quads + 1;
}

/* Appends `text`'s quads from font unit `top` down, in the grey `grey`
 * (HUD_WHITE, HUD_DIMMED_GREY); returns the quads then. */
static int hud_add_text(int quads, int top, char *text, unsigned char grey) {
    unsigned char rgba[4] = {grey, grey, grey, 255}; /* opaque */
    return quads + stb_easy_font_print(HUD_MARGIN, (float)top, text, rgba,
                                       hud.vertices + (size_t)quads * 4 * HUD_VERTEX_BYTES,
                                       (int)sizeof hud.vertices - quads * 4 * HUD_VERTEX_BYTES);
}

int hud_scale_to_fit(const char *text, int width, int height, int scale, int framebuffer_height) {
    char wrapped[HUD_MAX_TEXT];
    scale = scale > 0 ? scale : hud_scale_for(framebuffer_height);
    while (scale > 1 &&
           (hud_wrap(text, width, scale, wrapped, sizeof wrapped) * HUD_LINE_UNITS + 2 * HUD_MARGIN) * scale > height)
        scale--;
    return scale;
}

/* hud_draw's layout of `text`: its scale (0: fitted), its first
 * `dimmed_lines` lines and the rest wrapped apart (each line wraps alone)
 * into `dimmed` (its rows in *dimmed_rows) and `rest`, and the panel's
 * size in font units. */
static int hud_layout(const char *text, int width, int height, int scale, int dimmed_lines, char dimmed[HUD_MAX_TEXT],
                      char rest[HUD_MAX_TEXT], int *dimmed_rows, int panel_units[2]) {
    char joined[2 * HUD_MAX_TEXT];
    scale = scale > 0 ? scale : hud_scale_to_fit(text, width, height, 0, height);
    const char *split = text;
    for (int k = 0; k < dimmed_lines && *split; k++) {
        split += strcspn(split, "\n");
        split += *split == '\n';
    }
    dimmed[0] = '\0';
    *dimmed_rows = 0;
    if (split > text) {
        snprintf(joined, sizeof joined, "%.*s", (int)(split - text) - (split[-1] == '\n'), text);
        *dimmed_rows = hud_wrap(joined, width, scale, dimmed, HUD_MAX_TEXT);
    }
    hud_wrap(split, width, scale, rest, HUD_MAX_TEXT);
    snprintf(joined, sizeof joined, "%s%s%s", dimmed, *dimmed_rows ? "\n" : "", rest);
    panel_units[0] = hud_text_width(joined) + 2 * HUD_MARGIN;
    panel_units[1] = stb_easy_font_height(joined) + HUD_MARGIN + HUD_PANEL_BOTTOM_UNITS;
    return scale;
}

void hud_panel_size(const char *text, int width, int height, int scale, int dimmed_lines, int *panel_width,
                    int *panel_height) {
    char dimmed[HUD_MAX_TEXT], rest[HUD_MAX_TEXT];
    int panel_units[2], dimmed_rows;
    scale = hud_layout(text, width, height, scale, dimmed_lines, dimmed, rest, &dimmed_rows, panel_units);
    *panel_width = panel_units[0] * scale;
    *panel_height = panel_units[1] * scale;
}

void hud_draw(const char *text, int width, int height, int scale, int dimmed_lines) {
    char dimmed[HUD_MAX_TEXT], rest[HUD_MAX_TEXT];
    int panel_units[2], dimmed_rows;
    scale = hud_layout(text, width, height, scale, dimmed_lines, dimmed, rest, &dimmed_rows, panel_units);
    int quads = hud_add_panel(0, 0, 0, (float)panel_units[0], (float)panel_units[1]);
    quads = hud_add_text(quads, HUD_MARGIN, dimmed, HUD_DIMMED_GREY);
    quads = hud_add_text(quads, HUD_MARGIN + dimmed_rows * HUD_LINE_UNITS, rest, HUD_WHITE);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(hud.program);
    glUniform2f(hud.viewport, (float)width, (float)height);
    glUniform1f(hud.scale, (float)scale);
    glBindVertexArray(hud.vao);
    glBindBuffer(GL_ARRAY_BUFFER, hud.vertex_buffer);
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)quads * 4 * HUD_VERTEX_BYTES, hud.vertices);
    glDrawElements(GL_TRIANGLES, quads * 6, GL_UNSIGNED_INT, NULL);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
}

void hud_destroy(void) {
    shader_delete_program(hud.program);
    glDeleteVertexArrays(1, &hud.vao);
    glDeleteBuffers(1, &hud.vertex_buffer);
    glDeleteBuffers(1, &hud.index_buffer);
    hud.program = hud.vao = hud.vertex_buffer = hud.index_buffer = 0;
}
