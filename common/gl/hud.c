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

#define HUD_SCALE 2.0f
#define HUD_MAX_QUADS 4000 /* about 16 lines of 80 characters */
#define HUD_VERTEX_BYTES 16 /* stb_easy_font: x, y, z floats and RGBA bytes */

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
    hud.viewport = glGetUniformLocation(hud.program, "u_viewport");
    hud.scale = glGetUniformLocation(hud.program, "u_scale");
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

void hud_draw(const char *text, int width, int height) {
    char copy[4096];
    snprintf(copy, sizeof copy, "%s", text);
    float text_width = (float)stb_easy_font_width(copy), text_height = (float)stb_easy_font_height(copy);
    int quads = hud_add_panel(0, 0, 0, text_width + 8, text_height + 6);
    unsigned char white[4] = {255, 255, 255, 255};
    quads += stb_easy_font_print(4, 4, copy, white, hud.vertices + (size_t)quads * 4 * HUD_VERTEX_BYTES,
                                 (int)sizeof hud.vertices - quads * 4 * HUD_VERTEX_BYTES);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(hud.program);
    glUniform2f(hud.viewport, (float)width, (float)height);
    glUniform1f(hud.scale, HUD_SCALE);
    glBindVertexArray(hud.vao);
    glBindBuffer(GL_ARRAY_BUFFER, hud.vertex_buffer);
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)quads * 4 * HUD_VERTEX_BYTES, hud.vertices);
    glDrawElements(GL_TRIANGLES, quads * 6, GL_UNSIGNED_INT, NULL);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
}

void hud_destroy(void) {
    glDeleteProgram(hud.program);
    glDeleteVertexArrays(1, &hud.vao);
    glDeleteBuffers(1, &hud.vertex_buffer);
    glDeleteBuffers(1, &hud.index_buffer);
    hud.program = hud.vao = hud.vertex_buffer = hud.index_buffer = 0;
}
