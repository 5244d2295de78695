/* map: the overlays drawn after the camera pass, for lectures (see
 * map.h). The texel and texel-size overlays are the camera pass's
 * own (shaders/map.glsl); the texel-size legend is drawn here, and
 * the frusta, the map inset (its reduction, its insets and their labels)
 * and the cascades' key, whose labels are common/gl/legend.h's. */
#include <glad/gl.h>
/* stb_easy_font is all static functions; not every one is used. */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-braces"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "context.h"
#include "depth.h"
#include "frustum.h"
#include "hud.h"
#include "legend.h"
#include "map_internal.h"

/* Frustum edges: a warm yellow that reads on the lit scene and the dark
 * background alike. */
static const float map_frustum_color[3] = {1.0f, 0.85f, 0.2f};
/* Insets sit this many pixels in from the picture's corner. */
#define MAP_INSET_MARGIN_PX 8
/* The map inset is a third of the picture's height; the warp view half;
 * an array map's row of layers at most half the picture's width. */
#define MAP_INSET_HEIGHT_DIVISOR 3
#define MAP_ARRAY_INSET_WIDTH_DIVISOR 2
#define MAP_WARP_VIEW_HEIGHT_DIVISOR 2
/* The warp view's background, darker than the scene's so the view stands out. */
static const float map_warp_view_background[4] = {0.08f, 0.08f, 0.1f, 1};
/* The observer of the warp view: where it stands and how wide it sees,
 * chosen so the clip cube (-1..1) fills the view seen from above one side. */
static const float map_warp_view_eye[3] = {3.2f, 2.4f, -4.2f};
#define MAP_WARP_VIEW_FOV_DEG 40.0f
#define MAP_WARP_VIEW_NEAR 0.5f
#define MAP_WARP_VIEW_FAR 20.0f
/* post_perspective.vert clips to the six planes of the clip cube. */
#define MAP_CLIP_PLANES 6

/* `count` (<= MAP_LEGEND_VERTICES) vertices of lines or triangles
 * (mode) in world space, in one colour. */
static void map_draw_solid(map_renderer *r, GLenum mode, const float (*points)[3], int count,
                           const mat4 view_projection, const float color[3]) {
    glUseProgram(r->lines.program.id);
    glUniformMatrix4fv(r->lines.program.view_projection, 1, GL_FALSE, (const float *)view_projection);
    glUniform3fv(r->lines.color, 1, color);
    glBindVertexArray(r->overlay_vao);
    glBindBuffer(GL_ARRAY_BUFFER, r->overlay_buffer);
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(sizeof *points * (size_t)count), points);
    glDrawArrays(mode, 0, count);
}

void map_draw_frustum(map_renderer *r, const mat4 frustum, const mat4 view_projection) {
    float corners[8][3], lines[MAP_OVERLAY_VERTICES][3];
    frustum_corners(frustum, corners);
    int n = 0;
    for (int a = 0; a < 8; a++) {
        for (int bit = 1; bit < 8; bit <<= 1) {
            if (a & bit)
                continue;
            glm_vec3_copy(corners[a], lines[n++]);
            glm_vec3_copy(corners[a | bit], lines[n++]);
        }
    }
    map_draw_solid(r, GL_LINES, (const float(*)[3])lines, n, view_projection, map_frustum_color);
}

/* ---- the map inset ---- */

const float map_cascade_colors[MAP_MAX_ARRAY_LAYERS][3] = {
    {1.0f, 0.25f, 0.25f}, {0.25f, 1.0f, 0.25f}, {0.3f, 0.45f, 1.0f}, {1.0f, 0.9f, 0.2f},
    {1.0f, 0.3f, 1.0f},   {0.2f, 1.0f, 1.0f},   {1.0f, 0.6f, 0.2f},  {0.65f, 0.4f, 1.0f}};
/* A quad over the whole viewport, in clip space. */
static const float map_overlay_quad[6][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
/* The unit the inset reads the reduction on (the reduction reads a map of
 * kind k on unit k: map_texel_units). */
#define MAP_INSET_UNIT 0
/* A reduced block that holds nothing: (nearest, farthest) = (1, 0). */
#define MAP_INSET_NOTHING 1.0f
/* The room for a depth in a label: "-1e+38" written whole, and more. */
#define MAP_DEPTH_TEXT 48
/* Significant figures of a depth: the key's, and the insets' labels' (an
 * inset may be narrow). */
#define MAP_KEY_FIGURES 3
#define MAP_LABEL_FIGURES 2

int map_inset_count(map_kind kind, int layer_count) { return kind == MAP_ARRAY ? layer_count : 1; }

/* Along the bottom, flush right: a 2D map a square a third of the
 * picture's height, a cube map three faces wide and two high in that
 * height, an array map's layers in a row of squares, nearest cascade
 * first, over at most half the picture's width. */
void map_inset_rect(map_kind kind, int layer_count, int inset, int width, int height, int rect[4]) {
    int insets = map_inset_count(kind, layer_count);
    int h = height / MAP_INSET_HEIGHT_DIVISOR, w = kind == MAP_CUBE ? h * 3 / 2 : h;
    if (kind == MAP_ARRAY)
        w = h = glm_min(h, width / MAP_ARRAY_INSET_WIDTH_DIVISOR / insets);
    rect[0] = width - (insets - inset) * (w + MAP_INSET_MARGIN_PX);
    rect[1] = MAP_INSET_MARGIN_PX;
    rect[2] = w;
    rect[3] = h;
}

/* The program that reduces a map of `kind`, loaded now if it was not. */
static const map_reduce_program *map_reduce_program_for(map_renderer *r, map_kind kind) {
    map_reduce_program *p = &r->reduce[kind];
    if (p->program.id)
        return p;
    static const char *const files[] = {"overlay.vert", "overlay_reduce.frag"};
    const shader_define defines[] = {{"MAP_REDUCE_KIND", (int)kind}, MAP_TEXEL_DEFINES, {NULL, 0}};
    if (!render_program_load(&p->program, files, 2, defines))
        return NULL;
    unsigned id = p->program.id;
    p->factor = shader_uniform(id, "u_factor");
    p->layer = shader_uniform(id, "u_layer");
    glUseProgram(id);
    map_texel_units(id);
    mat4 identity = GLM_MAT4_IDENTITY_INIT;
    glUniformMatrix4fv(p->program.view_projection, 1, GL_FALSE, (const float *)identity);
    return p;
}

/* The reduction's texture, blocks x blocks x layers, made anew when that
 * changes (on the inset's unit). */
static void map_inset_texture(map_renderer *r, int blocks, int layers) {
    if (r->inset_texture && r->inset_blocks == blocks && r->inset_layers == layers)
        return;
    glDeleteTextures(1, &r->inset_texture);
    glGenTextures(1, &r->inset_texture);
    glActiveTexture(GL_TEXTURE0 + MAP_INSET_UNIT);
    glBindTexture(GL_TEXTURE_2D_ARRAY, r->inset_texture);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RG32F, blocks, blocks, layers, 0, GL_RG, GL_FLOAT, NULL);
    map_texture_filter(GL_TEXTURE_2D_ARRAY, GL_NEAREST);
    r->inset_blocks = blocks;
    r->inset_layers = layers;
}

/* Map m reduced to blocks of `factor` texels on a side, every layer, into
 * r->inset_texture, and read back: each layer's nearest and farthest held
 * depth into r->inset_held[layer] (MAP_INSET_NOTHING, 0 where it
 * holds none). False (said once, r->inset_failed) where it cannot be.
 * Leaves the target framebuffer bound, and the viewport at r->viewport. */
static bool map_inset_reduce(map_renderer *r, const map_light *m, int factor) {
    float(*held)[2] = r->inset_held;
    int blocks = (m->size + factor - 1) / factor;
    const map_reduce_program *p = map_reduce_program_for(r, m->kind);
    size_t per_layer = (size_t)blocks * (size_t)blocks, count = per_layer * (size_t)m->layer_count;
    float(*ranges)[4] = malloc(count * sizeof *ranges); /* read as RGBA: (nearest, farthest, 0, 1) */
    bool ok = p && ranges;
    if (!ranges)
        fprintf(stderr, "shadow maps: out of memory for the map inset's %zu blocks\n", count);
    if (ok) {
        map_inset_texture(r, blocks, m->layer_count);
        glUseProgram(p->program.id);
        glUniform1i(p->factor, factor);
        glActiveTexture(GL_TEXTURE0 + (GLenum)m->kind);
        glBindTexture(map_target(m->kind), m->texture.id);
        glBindSampler((GLuint)m->kind, r->depth_sampler); /* the depths as stored */
        glBindVertexArray(r->overlay_vao);
        glBindBuffer(GL_ARRAY_BUFFER, r->overlay_buffer);
        glBufferSubData(GL_ARRAY_BUFFER, 0, sizeof map_overlay_quad, map_overlay_quad);
        glViewport(0, 0, blocks, blocks);
    }
    for (int layer = 0; ok && layer < m->layer_count; layer++) {
        ok = map_color_target(&r->inset_framebuffer, r->inset_texture, GL_TEXTURE_2D_ARRAY, layer,
                              "the map inset is not drawn");
        if (!ok)
            break;
        glUseProgram(p->program.id);
        glUniform1i(p->layer, layer);
        glDrawArrays(GL_TRIANGLES, 0, 6);
        /* Through the framebuffer, in the one format every GL reads a
         * float colour buffer in (ES has no glGetTexImage). */
        glReadPixels(0, 0, blocks, blocks, GL_RGBA, GL_FLOAT, ranges + per_layer * (size_t)layer);
    }
    if (ok) {
        glActiveTexture(GL_TEXTURE0 + MAP_INSET_UNIT);
        glBindTexture(GL_TEXTURE_2D_ARRAY, r->inset_texture);
        for (int layer = 0; layer < m->layer_count; layer++) {
            held[layer][0] = MAP_INSET_NOTHING;
            held[layer][1] = 0;
            for (size_t i = per_layer * (size_t)layer; i < per_layer * (size_t)(layer + 1); i++) {
                held[layer][0] = fminf(held[layer][0], ranges[i][0]);
                held[layer][1] = fmaxf(held[layer][1], ranges[i][1]);
            }
        }
    }
    free(ranges);
    if (p)
        glBindSampler((GLuint)m->kind, 0);
    r->inset_failed = !ok;
    r->inset_current = ok;
    r->inset_factor = factor;
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)r->target_framebuffer);
    glViewport(r->viewport[0], r->viewport[1], r->viewport[2], r->viewport[3]);
    return ok;
}

/* The depth d stored in layer `layer` in the units of the light's view:
 * a perspective map's distance from the light along its axis, an
 * orthographic one's from its near plane (its view's origin is arbitrary:
 * the fit's). */
static float map_inset_distance(const map_light *m, int layer, float d) {
    float n = m->near_plane, f = m->far_plane;
    if (m->kind == MAP_ARRAY) /* glm_ortho's depth scale: -2 / (far - near) */
        return d * -2 / m->cascade_scale[layer][2];
    if (m->orthographic)
        return d * (f - n);
    return 2 * n * f / (f + n - (2 * d - 1) * (f - n));
}

/* "A..B", the range a..b, each to `figures` significant figures (whole
 * units from 10^figures on, where %g would write an exponent), into out. */
static void map_format_range(char *out, size_t size, float a, float b, int figures) {
    const float ends[2] = {a, b};
    char text[2][MAP_DEPTH_TEXT];
    for (int k = 0; k < 2; k++) {
        if (fabsf(ends[k]) < powf(10, (float)figures))
            snprintf(text[k], sizeof text[k], "%.*g", figures, (double)ends[k]);
        else
            snprintf(text[k], sizeof text[k], "%.0f", (double)ends[k]);
    }
    snprintf(out, size, "%s..%s", text[0], text[1]);
}

/* One line of text just above rect (pixels from the viewport's
 * bottom-left), as large as fits its width (at least the smallest
 * scale). */
static void map_label(const legend_line *line, const int rect[4], const int viewport[4]) {
    int scale = legend_scale_to_fit(line, 1, rect[2], rect[3], viewport[3]);
    scale = scale ? scale : 1;
    legend_draw(line, 1, rect[0], viewport[3] - rect[1] - rect[3] - legend_height_units(1) * scale, scale);
}

/* Light 0's map m as its insets (map_inset_rect), each fitted to
 * what its layer holds and labelled (see "The map inset" in
 * map.h). */
static void map_draw_inset(map_renderer *r, const map_light *m, const int viewport[4]) {
    bool cube = m->kind == MAP_CUBE, array = m->kind == MAP_ARRAY;
    int insets = map_inset_count(m->kind, m->layer_count), rect[4];
    map_inset_rect(m->kind, m->layer_count, 0, viewport[2], viewport[3], rect);
    /* A block to at most a pixel of the inset (of a cube's face). */
    int pixels = glm_max(1, cube ? rect[3] / 2 : rect[3]);
    int factor = glm_max(1, (m->size + pixels - 1) / pixels);
    bool current = r->inset_current && r->inset_factor == factor && r->inset_layers == m->layer_count;
    if (r->inset_failed || (!current && !map_inset_reduce(r, m, factor)))
        return;
    float held[MAP_MAX_LAYERS][2];
    memcpy(held, r->inset_held, sizeof held);
    if (cube) /* one inset: the six faces' range */
        for (int face = 1; face < MAP_CUBE_FACES; face++) {
            held[0][0] = fminf(held[0][0], held[face][0]);
            held[0][1] = fmaxf(held[0][1], held[face][1]);
        }
    glDisable(GL_DEPTH_TEST);
    const map_inset_program *p = &r->inset;
    const float far_grey = MAP_INSET_FAR_GREY_PERCENT / 100.0f;
    for (int inset = 0; inset < insets; inset++) {
        map_inset_rect(m->kind, m->layer_count, inset, viewport[2], viewport[3], rect);
        /* An array layer's colour; else the ramp's ends. */
        legend_line label = {.swatches = array ? 1 : 2, .rgb = {{0, 0, 0}, {far_grey, far_grey, far_grey}}};
        if (array)
            memcpy(label.rgb[0], map_cascade_colors[inset], sizeof label.rgb[0]);
        bool empty = held[inset][0] > held[inset][1];
        if (empty) {
            glEnable(GL_SCISSOR_TEST);
            glScissor(viewport[0] + rect[0], viewport[1] + rect[1], rect[2], rect[3]);
            glClearColor(legend_panel_color[0], legend_panel_color[1], legend_panel_color[2], 1);
            glClear(GL_COLOR_BUFFER_BIT);
            glDisable(GL_SCISSOR_TEST);
            snprintf(label.text, sizeof label.text, "empty");
            label.swatches = array;
        } else {
            glUseProgram(p->program.id);
            mat4 identity = GLM_MAT4_IDENTITY_INIT;
            glUniformMatrix4fv(p->program.view_projection, 1, GL_FALSE, (const float *)identity);
            glUniform1i(p->reduced, MAP_INSET_UNIT);
            glUniform1i(p->kind, m->kind);
            glUniform1i(p->layer, inset);
            glUniform1i(p->size, m->size);
            glUniform1i(p->factor, factor);
            glUniform1i(p->orthographic, m->orthographic);
            glUniform1f(p->near_plane, m->near_plane);
            glUniform1f(p->far_plane, m->far_plane);
            glUniform2f(p->held, held[inset][0], held[inset][1]);
            glActiveTexture(GL_TEXTURE0 + MAP_INSET_UNIT);
            glBindTexture(GL_TEXTURE_2D_ARRAY, r->inset_texture);
            glBindVertexArray(r->overlay_vao);
            glBindBuffer(GL_ARRAY_BUFFER, r->overlay_buffer);
            glBufferSubData(GL_ARRAY_BUFFER, 0, sizeof map_overlay_quad, map_overlay_quad);
            glViewport(viewport[0] + rect[0], viewport[1] + rect[1], rect[2], rect[3]);
            glDrawArrays(GL_TRIANGLES, 0, 6);
            glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
            map_format_range(label.text, sizeof label.text, map_inset_distance(m, inset, held[inset][0]),
                             map_inset_distance(m, inset, held[inset][1]), MAP_LABEL_FIGURES);
        }
        map_label(&label, rect, viewport);
    }
    glActiveTexture(GL_TEXTURE0);
}

/* The cascades overlay's key, in the bottom-left corner: a title, then
 * each layer of light 0's array map m with its colour, its number and its
 * slice of view depth, then what the insets' labels say. */
static void map_draw_cascade_key(const map_light *m, const int viewport[4]) {
    legend_line lines[2 + MAP_MAX_ARRAY_LAYERS] = {{.text = "cascade: view depth"}};
    for (int k = 0; k < m->layer_count; k++) {
        legend_line *line = &lines[1 + k];
        char range[2 * MAP_DEPTH_TEXT];
        map_format_range(range, sizeof range, m->cascade_split[k], m->cascade_split[k + 1], MAP_KEY_FIGURES);
        snprintf(line->text, sizeof line->text, "%d  %s", k, range);
        line->swatches = 1;
        memcpy(line->rgb[0], map_cascade_colors[k], sizeof line->rgb[0]);
    }
    snprintf(lines[1 + m->layer_count].text, sizeof lines[0].text, "insets: light depth held");
    int count = 2 + m->layer_count, insets[4];
    /* Left of the insets. */
    map_inset_rect(m->kind, m->layer_count, 0, viewport[2], viewport[3], insets);
    int margin = MAP_INSET_MARGIN_PX, width = insets[0] - 2 * margin, height = viewport[3] - 2 * margin;
    int scale = legend_scale_to_fit(lines, count, width, height, viewport[3]);
    scale = scale ? scale : 1;
    legend_draw(lines, count, margin, viewport[3] - margin - legend_height_units(count) * scale, scale);
}

/* ---- the heat maps' legends ---- */

/* A heat map's legend: the ramp's ends in log2 of what it measures, and
 * the ticks labelled under the bar: the ends and the ramp's green. */
#define MAP_LEGEND_TICKS 3
typedef struct map_legend_scale {
    float log2_min, log2_max;
    struct {
        float log2_value;
        const char *label;
    } ticks[MAP_LEGEND_TICKS];
} map_legend_scale;
/* A texel's size in pixels, green at one. */
static const map_legend_scale map_texel_size_legend = {
    MAP_HEAT_LOG2_MIN, MAP_HEAT_LOG2_MAX, {{MAP_HEAT_LOG2_MIN, "1/4"}, {0, "1 px"}, {MAP_HEAT_LOG2_MAX, "32+ px"}}};
/* The penumbra's estimated radius in world units: the same ramp moved. */
static const map_legend_scale map_penumbra_legend = {MAP_PENUMBRA_LOG2_MIN,
                                                     MAP_PENUMBRA_LOG2_MAX,
                                                     {{MAP_PENUMBRA_LOG2_MIN, "1/64"},
                                                      {MAP_PENUMBRA_LOG2_MIN - MAP_HEAT_LOG2_MIN, "1/16"},
                                                      {MAP_PENUMBRA_LOG2_MAX, "radius 2+ units"}}};
/* Sizes in font units, so the legend grows with the HUD's text (hud.h):
 * the bar, a tick's length, the panel's margin, stb_easy_font's line. */
#define MAP_LEGEND_BAR_UNITS 160
#define MAP_LEGEND_BAR_HEIGHT_UNITS 8
#define MAP_LEGEND_TICK_UNITS 3
#define MAP_LEGEND_MARGIN_UNITS 4
#define MAP_LEGEND_LINE_UNITS 12
#define MAP_LEGEND_PANEL_UNITS (MAP_LEGEND_BAR_HEIGHT_UNITS + MAP_LEGEND_TICK_UNITS + MAP_LEGEND_LINE_UNITS)
/* stb_easy_font's quads: four vertices of x, y, z floats and RGBA bytes. */
#define MAP_LEGEND_FONT_VERTEX_BYTES 16
#define MAP_LEGEND_FONT_QUADS (MAP_LEGEND_VERTICES / 6)
/* A dark panel, so the labels read over any scene, and white text. */
static const float map_legend_panel_color[3] = {0.05f, 0.05f, 0.06f};
static const float map_legend_text_color[3] = {1, 1, 1};

/* Triangles in the viewport's clip space from rectangles in pixels from
 * its top-left corner (stb_easy_font's way up: y down). */
typedef struct map_legend_mesh {
    float vertices[MAP_LEGEND_VERTICES][3];
    int count;
    float width, height;
} map_legend_mesh;

static void map_legend_rect(map_legend_mesh *m, float x0, float y0, float x1, float y1) {
    static const int corner[6][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
    for (int k = 0; k < 6 && m->count < MAP_LEGEND_VERTICES; k++, m->count++) {
        m->vertices[m->count][0] = 2 * (corner[k][0] ? x1 : x0) / m->width - 1;
        m->vertices[m->count][1] = 1 - 2 * (corner[k][1] ? y1 : y0) / m->height;
        m->vertices[m->count][2] = 0;
    }
}

/* A heat map's legend in the bottom-right corner (free of the map inset,
 * which these overlays do not show): its colour bar in the picture's
 * colours, a tick and a label at each of the scale's ticks, on a dark
 * panel. */
static void map_draw_legend(map_renderer *r, const map_legend_scale *scale, const int viewport[4]) {
    /* Scratch, static for their size (not state: filled anew each frame). */
    static map_legend_mesh panel, text;
    static char font[MAP_LEGEND_FONT_QUADS * 4 * MAP_LEGEND_FONT_VERTEX_BYTES];
    float unit = (float)hud_scale_for(viewport[3]), margin = MAP_LEGEND_MARGIN_UNITS * unit;
    float bar_width = MAP_LEGEND_BAR_UNITS * unit, bar_height = MAP_LEGEND_BAR_HEIGHT_UNITS * unit;
    float x = (float)viewport[2] - MAP_INSET_MARGIN_PX - margin - bar_width;
    float y = (float)viewport[3] - MAP_INSET_MARGIN_PX - margin - MAP_LEGEND_PANEL_UNITS * unit;
    panel = (map_legend_mesh){.width = (float)viewport[2], .height = (float)viewport[3]};
    text = panel;
    map_legend_rect(&panel, x - margin, y - margin, x + bar_width + margin,
                    y + MAP_LEGEND_PANEL_UNITS * unit + margin);
    for (int t = 0; t < MAP_LEGEND_TICKS; t++) {
        float along = (scale->ticks[t].log2_value - scale->log2_min) / (scale->log2_max - scale->log2_min);
        float tick = x + along * (bar_width - unit);
        map_legend_rect(&text, tick, y + bar_height, tick + unit, y + bar_height + MAP_LEGEND_TICK_UNITS * unit);
        /* Each label under its tick, shifted left by its share of the bar,
         * so the end labels stay over the panel. */
        char *label = (char *)scale->ticks[t].label;
        float label_x = tick - along * (float)stb_easy_font_width(label) * unit;
        float label_y = y + bar_height + MAP_LEGEND_TICK_UNITS * unit;
        int quads = stb_easy_font_print(0, 0, label, NULL, font, (int)sizeof font);
        for (int q = 0; q < quads; q++) {
            const float *a = (const float *)(font + (size_t)q * 4 * MAP_LEGEND_FONT_VERTEX_BYTES);
            const float *b = (const float *)(font + ((size_t)q * 4 + 2) * MAP_LEGEND_FONT_VERTEX_BYTES);
            map_legend_rect(&text, label_x + a[0] * unit, label_y + a[1] * unit, label_x + b[0] * unit,
                            label_y + b[1] * unit);
        }
    }
    glDisable(GL_DEPTH_TEST);
    mat4 identity = GLM_MAT4_IDENTITY_INIT;
    map_draw_solid(r, GL_TRIANGLES, (const float(*)[3])panel.vertices, panel.count, identity, map_legend_panel_color);
    map_draw_solid(r, GL_TRIANGLES, (const float(*)[3])text.vertices, text.count, identity, map_legend_text_color);
    glViewport(viewport[0] + (int)x, viewport[1] + viewport[3] - (int)(y + bar_height), (int)bar_width,
               (int)bar_height);
    glUseProgram(r->legend.program.id);
    glUniformMatrix4fv(r->legend.program.view_projection, 1, GL_FALSE, (const float *)identity);
    /* The bar is the ramp's, the texel-size scale's. */
    glUniform2f(r->legend.log2_range, MAP_HEAT_LOG2_MIN, MAP_HEAT_LOG2_MAX);
    glBindVertexArray(r->overlay_vao);
    glBindBuffer(GL_ARRAY_BUFFER, r->overlay_buffer);
    glBufferSubData(GL_ARRAY_BUFFER, 0, sizeof map_overlay_quad, map_overlay_quad);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
}

void map_draw_overlays(map_renderer *r, const map_settings *settings, const technique_frame *f) {
    int overlay = settings->overlay;
    glDisable(GL_BLEND);
    glDepthFunc(depth_func(f->view, GL_LEQUAL));
    bool frustum = overlay == MAP_OVERLAY_ALL || overlay == MAP_OVERLAY_FRUSTUM;
    for (int l = 0; frustum && l < f->gpu->scene->light_count; l++)
        for (int layer = 0; r->fitted[l] && layer < r->maps[l].layer_count; layer++)
            map_draw_frustum(r, r->maps[l].layer_view_projection[layer], f->view->raster_view_projection);
    bool inset = overlay == MAP_OVERLAY_ALL || overlay == MAP_OVERLAY_MAP || MAP_SHOWS_CASCADES(settings);
    bool tiles = false;
    for (int l = 0; l < f->gpu->scene->light_count; l++)
        tiles = tiles || (r->fitted[l] && r->maps[l].tiled);
    map_light atlas = map_atlas_as_map(r);
    if (inset && (tiles || r->fitted[0])) /* the atlas where lights have tiles, else light 0's map */
        map_draw_inset(r, tiles ? &atlas : &r->maps[0], r->viewport);
    if (r->fitted[0] && MAP_SHOWS_CASCADES(settings) && r->maps[0].kind == MAP_ARRAY)
        map_draw_cascade_key(&r->maps[0], r->viewport);
    if (overlay == MAP_OVERLAY_TEXEL_SIZE)
        map_draw_legend(r, &map_texel_size_legend, r->viewport);
    if (overlay == MAP_OVERLAY_PENUMBRA)
        map_draw_legend(r, &map_penumbra_legend, r->viewport);
}

/* ---- a warp's space ---- */

bool map_warp_view_init(map_warp_view *w) {
    static const char *const files[] = {"post_perspective.vert", "post_perspective.frag"};
    if (!render_program_load(&w->program, files, 2, NULL))
        return false;
    w->program.both_sides = true; /* a diagram of the warp's space, which may mirror (render.h) */
    w->space = shader_uniform(w->program.id, "u_warp_space");
    return true;
}

void map_warp_view_destroy(map_warp_view *w) { render_program_destroy(&w->program); }

void map_warp_view_draw(const map_warp_view *w, map_renderer *r, const technique_frame *f, const mat4 space,
                        const mat4 map_view_projection) {
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    int height = viewport[3] / MAP_WARP_VIEW_HEIGHT_DIVISOR, width = height;
    int x = viewport[0] + MAP_INSET_MARGIN_PX, y = viewport[1] + MAP_INSET_MARGIN_PX;
    glViewport(x, y, width, height);
    glEnable(GL_SCISSOR_TEST);
    glScissor(x, y, width, height);
    const float *bg = map_warp_view_background;
    glClearColor(bg[0], bg[1], bg[2], bg[3]);
    depth_use_standard(f->view); /* its own observer's depth, not the camera's */
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    glDepthMask(GL_TRUE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_BLEND);
    mat4 observer, projection, view;
    glm_perspective(glm_rad(MAP_WARP_VIEW_FOV_DEG), 1, MAP_WARP_VIEW_NEAR, MAP_WARP_VIEW_FAR, projection);
    glm_lookat((float *)map_warp_view_eye, (vec3){0, 0, 0}, (vec3){0, 1, 0}, view);
    glm_mat4_mul(projection, view, observer);
    glUseProgram(w->program.id);
    glUniformMatrix4fv(w->space, 1, GL_FALSE, (const float *)space);
    glUniformMatrix4fv(w->program.view_projection, 1, GL_FALSE, (const float *)observer);
    /* Without clip distances the shaders discard instead (shader.h). */
    int planes = context_current_features()->clip_distances ? MAP_CLIP_PLANES : 0;
    for (int k = 0; k < planes; k++)
        glEnable(GL_CLIP_DISTANCE0 + (unsigned)k);
    for (int i = 0; i < f->gpu->scene->object_count; i++)
        render_draw_object(f->gpu, &w->program, i);
    for (int k = 0; k < planes; k++)
        glDisable(GL_CLIP_DISTANCE0 + (unsigned)k);
    mat4 identity = GLM_MAT4_IDENTITY_INIT, map_in_space, space_inverse;
    map_draw_frustum(r, identity, observer); /* the clip cube of the warp space */
    glm_mat4_inv((vec4 *)space, space_inverse);
    glm_mat4_mul((vec4 *)map_view_projection, space_inverse, map_in_space);
    map_draw_frustum(r, map_in_space, observer);
    depth_use_camera(f->view);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
}
