/* shadow_map: the overlays drawn after the camera pass, for lectures (see
 * shadow_map.h). The texel and texel-size overlays are the camera pass's
 * own (shaders/shadowmap.glsl); the texel-size legend is drawn here. */
#include <glad/gl.h>
/* stb_easy_font is all static functions; not every one is used. */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-braces"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

#include "depth.h"
#include "frustum.h"
#include "hud.h"
#include "shadow_map.h"

/* Frustum edges: a warm yellow that reads on the lit scene and the dark
 * background alike. */
static const float shadow_map_frustum_color[3] = {1.0f, 0.85f, 0.2f};
/* Insets sit this many pixels in from the picture's corner. */
#define SHADOW_MAP_INSET_MARGIN_PX 8
/* The map inset is a third of the picture's height; the warp view half;
 * an array map's row of layers at most half the picture's width. */
#define SHADOW_MAP_INSET_HEIGHT_DIVISOR 3
#define SHADOW_MAP_ARRAY_INSET_WIDTH_DIVISOR 2
#define SHADOW_MAP_WARP_VIEW_HEIGHT_DIVISOR 2
/* The warp view's background, darker than the scene's so the view stands out. */
static const float shadow_map_warp_view_background[4] = {0.08f, 0.08f, 0.1f, 1};
/* The observer of the warp view: where it stands and how wide it sees,
 * chosen so the clip cube (-1..1) fills the view seen from above one side. */
static const float shadow_map_warp_view_eye[3] = {3.2f, 2.4f, -4.2f};
#define SHADOW_MAP_WARP_VIEW_FOV_DEG 40.0f
#define SHADOW_MAP_WARP_VIEW_NEAR 0.5f
#define SHADOW_MAP_WARP_VIEW_FAR 20.0f
/* post_perspective.vert clips to the six planes of the clip cube. */
#define SHADOW_MAP_CLIP_PLANES 6

/* `count` (<= SHADOW_MAP_LEGEND_VERTICES) vertices of lines or triangles
 * (mode) in world space, in one colour. */
static void shadow_map_draw_solid(shadow_map_renderer *r, GLenum mode, const float (*points)[3], int count,
                                  const mat4 view_projection, const float color[3]) {
    glUseProgram(r->lines.program.id);
    glUniformMatrix4fv(r->lines.program.view_projection, 1, GL_FALSE, (const float *)view_projection);
    glUniform3fv(r->lines.color, 1, color);
    glBindVertexArray(r->overlay_vao);
    glBindBuffer(GL_ARRAY_BUFFER, r->overlay_buffer);
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(sizeof *points * (size_t)count), points);
    glDrawArrays(mode, 0, count);
}

void shadow_map_draw_frustum(shadow_map_renderer *r, const mat4 frustum, const mat4 view_projection) {
    float corners[8][3], lines[SHADOW_MAP_OVERLAY_VERTICES][3];
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
    shadow_map_draw_solid(r, GL_LINES, (const float(*)[3])lines, n, view_projection, shadow_map_frustum_color);
}

/* Light 0's map in the bottom-right third of the picture: a 2D map as it
 * is, a cube map as its six faces in two rows of three, an array map's
 * layers in a row along the bottom, nearest cascade first, over at most
 * half the picture's width. */
static void shadow_map_draw_inset(shadow_map_renderer *r, const shadow_map *m, const int viewport[4]) {
    static const float quad[6][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    static const GLenum targets[] = {[SHADOW_MAP_2D] = GL_TEXTURE_2D,
                                     [SHADOW_MAP_CUBE] = GL_TEXTURE_CUBE_MAP,
                                     [SHADOW_MAP_ARRAY] = GL_TEXTURE_2D_ARRAY};
    bool cube = m->kind == SHADOW_MAP_CUBE, array = m->kind == SHADOW_MAP_ARRAY;
    int height = viewport[3] / SHADOW_MAP_INSET_HEIGHT_DIVISOR, width = cube ? height * 3 / 2 : height;
    if (array)
        width = height = glm_min(height, viewport[2] / SHADOW_MAP_ARRAY_INSET_WIDTH_DIVISOR / m->layer_count);
    glDisable(GL_DEPTH_TEST);
    const shadow_map_inset_program *p = &r->inset;
    glUseProgram(p->program.id);
    mat4 identity = GLM_MAT4_IDENTITY_INIT;
    glUniformMatrix4fv(p->program.view_projection, 1, GL_FALSE, (const float *)identity);
    /* A unit per sampler type: two types may not share one. */
    GLenum texture_target = targets[m->kind];
    glUniform1i(p->map, SHADOW_MAP_2D);
    glUniform1i(p->cube_map, SHADOW_MAP_CUBE);
    glUniform1i(p->array_map, SHADOW_MAP_ARRAY);
    glUniform1i(p->kind, m->kind);
    glUniform1i(p->orthographic, m->orthographic);
    glUniform1f(p->near_plane, m->near_plane);
    glUniform1f(p->far_plane, m->far_plane);
    glActiveTexture(GL_TEXTURE0 + (GLenum)m->kind);
    glBindTexture(texture_target, m->texture.id);
    glTexParameteri(texture_target, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glBindVertexArray(r->overlay_vao);
    glBindBuffer(GL_ARRAY_BUFFER, r->overlay_buffer);
    glBufferSubData(GL_ARRAY_BUFFER, 0, sizeof quad, quad);
    int insets = array ? m->layer_count : 1;
    for (int layer = 0; layer < insets; layer++) {
        glViewport(viewport[0] + viewport[2] - (insets - layer) * (width + SHADOW_MAP_INSET_MARGIN_PX),
                   viewport[1] + SHADOW_MAP_INSET_MARGIN_PX, width, height);
        glUniform1i(p->layer, layer);
        glDrawArrays(GL_TRIANGLES, 0, 6);
    }
    glTexParameteri(texture_target, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glActiveTexture(GL_TEXTURE0);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
}

/* ---- the heat maps' legends ---- */

/* A heat map's legend: the ramp's ends in log2 of what it measures, and
 * the ticks labelled under the bar: the ends and the ramp's green. */
#define SHADOW_MAP_LEGEND_TICKS 3
typedef struct shadow_map_legend_scale {
    float log2_min, log2_max;
    struct {
        float log2_value;
        const char *label;
    } ticks[SHADOW_MAP_LEGEND_TICKS];
} shadow_map_legend_scale;
/* A texel's size in pixels, green at one. */
static const shadow_map_legend_scale shadow_map_texel_size_legend = {
    SHADOW_MAP_HEAT_LOG2_MIN,
    SHADOW_MAP_HEAT_LOG2_MAX,
    {{SHADOW_MAP_HEAT_LOG2_MIN, "1/4"}, {0, "1 px"}, {SHADOW_MAP_HEAT_LOG2_MAX, "32+ px"}}};
/* The penumbra's estimated radius in world units: the same ramp moved. */
static const shadow_map_legend_scale shadow_map_penumbra_legend = {
    SHADOW_MAP_PENUMBRA_LOG2_MIN,
    SHADOW_MAP_PENUMBRA_LOG2_MAX,
    {{SHADOW_MAP_PENUMBRA_LOG2_MIN, "1/64"},
     {SHADOW_MAP_PENUMBRA_LOG2_MIN - SHADOW_MAP_HEAT_LOG2_MIN, "1/16"},
     {SHADOW_MAP_PENUMBRA_LOG2_MAX, "radius 2+ units"}}};
/* Sizes in font units, so the legend grows with the HUD's text (hud.h):
 * the bar, a tick's length, the panel's margin, stb_easy_font's line. */
#define SHADOW_MAP_LEGEND_BAR_UNITS 160
#define SHADOW_MAP_LEGEND_BAR_HEIGHT_UNITS 8
#define SHADOW_MAP_LEGEND_TICK_UNITS 3
#define SHADOW_MAP_LEGEND_MARGIN_UNITS 4
#define SHADOW_MAP_LEGEND_LINE_UNITS 12
#define SHADOW_MAP_LEGEND_PANEL_UNITS                                                                                \
    (SHADOW_MAP_LEGEND_BAR_HEIGHT_UNITS + SHADOW_MAP_LEGEND_TICK_UNITS + SHADOW_MAP_LEGEND_LINE_UNITS)
/* stb_easy_font's quads: four vertices of x, y, z floats and RGBA bytes. */
#define SHADOW_MAP_LEGEND_FONT_VERTEX_BYTES 16
#define SHADOW_MAP_LEGEND_FONT_QUADS (SHADOW_MAP_LEGEND_VERTICES / 6)
/* A dark panel, so the labels read over any scene, and white text. */
static const float shadow_map_legend_panel_color[3] = {0.05f, 0.05f, 0.06f};
static const float shadow_map_legend_text_color[3] = {1, 1, 1};

/* Triangles in the viewport's clip space from rectangles in pixels from
 * its top-left corner (stb_easy_font's way up: y down). */
typedef struct shadow_map_legend_mesh {
    float vertices[SHADOW_MAP_LEGEND_VERTICES][3];
    int count;
    float width, height;
} shadow_map_legend_mesh;

static void shadow_map_legend_rect(shadow_map_legend_mesh *m, float x0, float y0, float x1, float y1) {
    static const int corner[6][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
    for (int k = 0; k < 6 && m->count < SHADOW_MAP_LEGEND_VERTICES; k++, m->count++) {
        m->vertices[m->count][0] = 2 * (corner[k][0] ? x1 : x0) / m->width - 1;
        m->vertices[m->count][1] = 1 - 2 * (corner[k][1] ? y1 : y0) / m->height;
        m->vertices[m->count][2] = 0;
    }
}

/* A heat map's legend in the bottom-right corner (free of the map inset,
 * which these overlays do not show): its colour bar in the picture's
 * colours, a tick and a label at each of the scale's ticks, on a dark
 * panel. */
static void shadow_map_draw_legend(shadow_map_renderer *r, const shadow_map_legend_scale *scale,
                                   const int viewport[4]) {
    static const float quad[6][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    /* Scratch, static for their size (not state: filled anew each frame). */
    static shadow_map_legend_mesh panel, text;
    static char font[SHADOW_MAP_LEGEND_FONT_QUADS * 4 * SHADOW_MAP_LEGEND_FONT_VERTEX_BYTES];
    float unit = (float)hud_scale_for(viewport[3]), margin = SHADOW_MAP_LEGEND_MARGIN_UNITS * unit;
    float bar_width = SHADOW_MAP_LEGEND_BAR_UNITS * unit, bar_height = SHADOW_MAP_LEGEND_BAR_HEIGHT_UNITS * unit;
    float x = (float)viewport[2] - SHADOW_MAP_INSET_MARGIN_PX - margin - bar_width;
    float y = (float)viewport[3] - SHADOW_MAP_INSET_MARGIN_PX - margin - SHADOW_MAP_LEGEND_PANEL_UNITS * unit;
    panel = (shadow_map_legend_mesh){.width = (float)viewport[2], .height = (float)viewport[3]};
    text = panel;
    shadow_map_legend_rect(&panel, x - margin, y - margin, x + bar_width + margin,
                           y + SHADOW_MAP_LEGEND_PANEL_UNITS * unit + margin);
    for (int t = 0; t < SHADOW_MAP_LEGEND_TICKS; t++) {
        float along = (scale->ticks[t].log2_value - scale->log2_min) / (scale->log2_max - scale->log2_min);
        float tick = x + along * (bar_width - unit);
        shadow_map_legend_rect(&text, tick, y + bar_height, tick + unit,
                               y + bar_height + SHADOW_MAP_LEGEND_TICK_UNITS * unit);
        /* Each label under its tick, shifted left by its share of the bar,
         * so the end labels stay over the panel. */
        char *label = (char *)scale->ticks[t].label;
        float label_x = tick - along * (float)stb_easy_font_width(label) * unit;
        float label_y = y + bar_height + SHADOW_MAP_LEGEND_TICK_UNITS * unit;
        int quads = stb_easy_font_print(0, 0, label, NULL, font, (int)sizeof font);
        for (int q = 0; q < quads; q++) {
            const float *a = (const float *)(font + (size_t)q * 4 * SHADOW_MAP_LEGEND_FONT_VERTEX_BYTES);
            const float *b = (const float *)(font + ((size_t)q * 4 + 2) * SHADOW_MAP_LEGEND_FONT_VERTEX_BYTES);
            shadow_map_legend_rect(&text, label_x + a[0] * unit, label_y + a[1] * unit, label_x + b[0] * unit,
                                   label_y + b[1] * unit);
        }
    }
    glDisable(GL_DEPTH_TEST);
    mat4 identity = GLM_MAT4_IDENTITY_INIT;
    shadow_map_draw_solid(r, GL_TRIANGLES, (const float(*)[3])panel.vertices, panel.count, identity,
                          shadow_map_legend_panel_color);
    shadow_map_draw_solid(r, GL_TRIANGLES, (const float(*)[3])text.vertices, text.count, identity,
                          shadow_map_legend_text_color);
    glViewport(viewport[0] + (int)x, viewport[1] + viewport[3] - (int)(y + bar_height), (int)bar_width,
               (int)bar_height);
    glUseProgram(r->legend.program.id);
    glUniformMatrix4fv(r->legend.program.view_projection, 1, GL_FALSE, (const float *)identity);
    /* The bar is the ramp's, the texel-size scale's. */
    glUniform2f(r->legend.log2_range, SHADOW_MAP_HEAT_LOG2_MIN, SHADOW_MAP_HEAT_LOG2_MAX);
    glBindVertexArray(r->overlay_vao);
    glBindBuffer(GL_ARRAY_BUFFER, r->overlay_buffer);
    glBufferSubData(GL_ARRAY_BUFFER, 0, sizeof quad, quad);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
}

void shadow_map_draw_overlays(shadow_map_renderer *r, const shadow_map_settings *settings, const technique_frame *f) {
    int overlay = settings->overlay;
    glDisable(GL_BLEND);
    glDepthFunc(depth_func(f->view, GL_LEQUAL));
    bool frustum = overlay == SHADOW_MAP_OVERLAY_ALL || overlay == SHADOW_MAP_OVERLAY_FRUSTUM;
    for (int l = 0; frustum && l < f->gpu->scene->light_count; l++)
        for (int layer = 0; r->fitted[l] && layer < r->maps[l].layer_count; layer++)
            shadow_map_draw_frustum(r, r->maps[l].layer_view_projection[layer], f->view->raster_view_projection);
    bool inset =
        overlay == SHADOW_MAP_OVERLAY_ALL || overlay == SHADOW_MAP_OVERLAY_MAP || SHADOW_MAP_SHOWS_CASCADES(settings);
    if (r->fitted[0] && inset)
        shadow_map_draw_inset(r, &r->maps[0], r->viewport);
    if (overlay == SHADOW_MAP_OVERLAY_TEXEL_SIZE)
        shadow_map_draw_legend(r, &shadow_map_texel_size_legend, r->viewport);
    if (overlay == SHADOW_MAP_OVERLAY_PENUMBRA)
        shadow_map_draw_legend(r, &shadow_map_penumbra_legend, r->viewport);
}

/* ---- a warp's space ---- */

bool shadow_map_warp_view_init(shadow_map_warp_view *w) {
    static const char *const files[] = {"post_perspective.vert", "post_perspective.frag"};
    if (!render_program_load(&w->program, files, 2, NULL))
        return false;
    w->space = shader_uniform(w->program.id, "u_warp_space");
    return true;
}

void shadow_map_warp_view_destroy(shadow_map_warp_view *w) { render_program_destroy(&w->program); }

void shadow_map_warp_view_draw(const shadow_map_warp_view *w, shadow_map_renderer *r, const technique_frame *f,
                               const mat4 space, const mat4 map_view_projection) {
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    int height = viewport[3] / SHADOW_MAP_WARP_VIEW_HEIGHT_DIVISOR, width = height;
    int x = viewport[0] + SHADOW_MAP_INSET_MARGIN_PX, y = viewport[1] + SHADOW_MAP_INSET_MARGIN_PX;
    glViewport(x, y, width, height);
    glEnable(GL_SCISSOR_TEST);
    glScissor(x, y, width, height);
    const float *bg = shadow_map_warp_view_background;
    glClearColor(bg[0], bg[1], bg[2], bg[3]);
    depth_use_standard(f->view); /* its own observer's depth, not the camera's */
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    glDepthMask(GL_TRUE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_BLEND);
    mat4 observer, projection, view;
    glm_perspective(glm_rad(SHADOW_MAP_WARP_VIEW_FOV_DEG), 1, SHADOW_MAP_WARP_VIEW_NEAR, SHADOW_MAP_WARP_VIEW_FAR,
                    projection);
    glm_lookat((float *)shadow_map_warp_view_eye, (vec3){0, 0, 0}, (vec3){0, 1, 0}, view);
    glm_mat4_mul(projection, view, observer);
    glUseProgram(w->program.id);
    glUniformMatrix4fv(w->space, 1, GL_FALSE, (const float *)space);
    glUniformMatrix4fv(w->program.view_projection, 1, GL_FALSE, (const float *)observer);
    for (int k = 0; k < SHADOW_MAP_CLIP_PLANES; k++)
        glEnable(GL_CLIP_DISTANCE0 + (unsigned)k);
    for (int i = 0; i < f->gpu->scene->object_count; i++)
        render_draw_object(f->gpu, &w->program, i);
    for (int k = 0; k < SHADOW_MAP_CLIP_PLANES; k++)
        glDisable(GL_CLIP_DISTANCE0 + (unsigned)k);
    mat4 identity = GLM_MAT4_IDENTITY_INIT, map_in_space, space_inverse;
    shadow_map_draw_frustum(r, identity, observer); /* the clip cube of the warp space */
    glm_mat4_inv((vec4 *)space, space_inverse);
    glm_mat4_mul((vec4 *)map_view_projection, space_inverse, map_in_space);
    shadow_map_draw_frustum(r, map_in_space, observer);
    depth_use_camera(f->view);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
}
