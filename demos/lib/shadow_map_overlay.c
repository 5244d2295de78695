/* shadow_map: the overlays drawn after the camera pass, for lectures (see
 * shadow_map.h). The texel and texel-size overlays are the camera pass's
 * own (shaders/shadowmap.glsl). */
#include <glad/gl.h>

#include "depth.h"
#include "frustum.h"
#include "shadow_map.h"

/* Frustum edges: a warm yellow that reads on the lit scene and the dark
 * background alike. */
static const float shadow_map_frustum_color[3] = {1.0f, 0.85f, 0.2f};
/* Insets sit this many pixels in from the picture's corner. */
#define SHADOW_MAP_INSET_MARGIN_PX 8
/* The map inset is a third of the picture's height; the warp view half. */
#define SHADOW_MAP_INSET_HEIGHT_DIVISOR 3
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

/* `count` (<= SHADOW_MAP_OVERLAY_VERTICES) line ends in world space, in one
 * colour. */
static void shadow_map_draw_lines(shadow_map_renderer *r, const float (*points)[3], int count,
                                  const mat4 view_projection, const float color[3]) {
    glUseProgram(r->lines.program.id);
    glUniformMatrix4fv(r->lines.program.view_projection, 1, GL_FALSE, (const float *)view_projection);
    glUniform3fv(r->lines.color, 1, color);
    glBindVertexArray(r->overlay_vao);
    glBindBuffer(GL_ARRAY_BUFFER, r->overlay_buffer);
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(sizeof *points * (size_t)count), points);
    glDrawArrays(GL_LINES, 0, count);
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
    shadow_map_draw_lines(r, (const float(*)[3])lines, n, view_projection, shadow_map_frustum_color);
}

/* Light 0's map in the bottom-right third of the picture: a 2D map as it
 * is, a cube map as its six faces in two rows of three. */
static void shadow_map_draw_inset(shadow_map_renderer *r, const shadow_map *m, const int viewport[4]) {
    static const float quad[6][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    bool cube = m->kind == SHADOW_MAP_CUBE;
    int height = viewport[3] / SHADOW_MAP_INSET_HEIGHT_DIVISOR, width = cube ? height * 3 / 2 : height;
    glViewport(viewport[0] + viewport[2] - width - SHADOW_MAP_INSET_MARGIN_PX, viewport[1] + SHADOW_MAP_INSET_MARGIN_PX,
               width, height);
    glDisable(GL_DEPTH_TEST);
    const shadow_map_inset_program *p = &r->inset;
    glUseProgram(p->program.id);
    mat4 identity = GLM_MAT4_IDENTITY_INIT;
    glUniformMatrix4fv(p->program.view_projection, 1, GL_FALSE, (const float *)identity);
    /* Two units: a 2D and a cube sampler may not share one. */
    GLenum texture_target = cube ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D;
    glUniform1i(p->map, 0);
    glUniform1i(p->cube_map, 1);
    glUniform1i(p->cube, cube);
    glUniform1i(p->orthographic, m->orthographic);
    glUniform1f(p->near_plane, m->near_plane);
    glUniform1f(p->far_plane, m->far_plane);
    glActiveTexture(cube ? GL_TEXTURE1 : GL_TEXTURE0);
    glBindTexture(texture_target, m->texture.id);
    glTexParameteri(texture_target, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glBindVertexArray(r->overlay_vao);
    glBindBuffer(GL_ARRAY_BUFFER, r->overlay_buffer);
    glBufferSubData(GL_ARRAY_BUFFER, 0, sizeof quad, quad);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glTexParameteri(texture_target, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glActiveTexture(GL_TEXTURE0);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
}

void shadow_map_draw_overlays(shadow_map_renderer *r, int overlay, const technique_frame *f, const bool *fitted,
                              const int viewport[4]) {
    glDisable(GL_BLEND);
    glDepthFunc(depth_func(f->view, GL_LEQUAL));
    bool frustum = overlay == SHADOW_MAP_OVERLAY_ALL || overlay == SHADOW_MAP_OVERLAY_FRUSTUM;
    for (int l = 0; frustum && l < f->gpu->scene->light_count; l++)
        for (int layer = 0; fitted[l] && layer < r->maps[l].layer_count; layer++)
            shadow_map_draw_frustum(r, r->maps[l].layer_view_projection[layer], f->view->raster_view_projection);
    if (fitted[0] && (overlay == SHADOW_MAP_OVERLAY_ALL || overlay == SHADOW_MAP_OVERLAY_MAP))
        shadow_map_draw_inset(r, &r->maps[0], viewport);
}

/* ---- a warp's space ---- */

bool shadow_map_warp_view_init(shadow_map_warp_view *w) {
    static const char *const files[] = {"post_perspective.vert", "post_perspective.frag"};
    if (!render_program_load(&w->program, files, 2, NULL))
        return false;
    w->space = glGetUniformLocation(w->program.id, "u_warp_space");
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
