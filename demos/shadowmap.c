/* shadowmap: shadow maps with bias and percentage-closer filtering, for
 * spot, directional and point lights.
 *
 * Williams, "Casting curved shadows on curved surfaces", SIGGRAPH 1978:
 * render depth from the light, then test each camera fragment's depth in
 * the light against the map. Reeves, Salesin & Cook, "Rendering antialiased
 * shadows with depth maps", SIGGRAPH 1987: filter the results of the tests
 * (never the depths) over a kernel: percentage-closer filtering.
 *
 *   spot         a perspective map around the cone (outside it the spot
 *                lights nothing: the cone decides there, not the map)
 *   directional  an orthographic map
 *   point        a cube map of six 90-degree faces, read with seamless
 *                filtering so that kernels cross face edges
 *
 * Fitting: each frame the map's frustum is fitted to the receivers the
 * camera can see (the part of their boxes inside the camera's frustum) and
 * to the casters whose shadow can reach them, even casters outside the
 * view; the
 * tighter the depth range, the more of the depth buffer's precision is
 * spent where shadows are decided. The HUD shows the range.
 *
 * Bias, with its size as a number: constant (a toggle; the point is moved
 * towards the light by N map texels of world distance), slope-scaled (a
 * toggle; glPolygonOffset factor in the depth pass, which grows with the
 * caster's depth slope) and normal offset (N texels along the normal,
 * times the sine of the light's angle, where one texel spans most depth;
 * 0 by default). Texel-sized biases hold at every map size, distance and
 * scene scale. Receiver-plane depth bias (--kernel-depth receiver-plane;
 * Isidoro, GDC 2006) makes each tap of a wide kernel compare the
 * receiver's own depth there: it cuts the partial acne of slanted
 * receivers (mean error about a third on the standard scenes) but not the
 * misclassified count. The defaults (poisson, 2048, constant 1 texel,
 * slope factor 1.5, no normal offset, centre depth) come from `make
 * bench`: of the 2048 settings on the technique's own Pareto front on every
 * standard scene, the one that misclassifies least while beating both
 * textbook configurations of the sweep on error and time (pcf5 is more
 * accurate but costs 1.4 times the textbook's pcf3), with no acne anywhere
 * in the elevation sweep (tests/test_shadowmap.c).
 *
 * For lectures, --overlay (key V): the map's texel boundaries drawn on the
 * receivers (aliasing made visible), the light frustum in wireframe (six
 * for a cube map), light 0's map as an inset of linear depth (a cube map's
 * six faces in two rows), or "texel-size": a heat map of a texel's size in
 * pixels. Overlays draw into the picture, so a dump taken with one shows
 * it.
 *
 * Filters: none (one nearest test), hw (one bilinear test: 2x2 in
 * hardware), pcf3/5/7 (an N x N grid of bilinear tests), poisson (16
 * bilinear tests on a Poisson disc three texels wide, rotated per pixel by
 * a hash of the pixel, so frames stay deterministic; three texels
 * misclassified least of 2 to 6 on the standard scenes).
 */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shadowmap.h"

#define SHADOWMAP_POISSON_TEXELS 3
#define SHADOWMAP_NEAR_RATIO 1e-3f /* nearest near plane, as a fraction of far */

const char *const shadowmap_sizes[] = {"2048", "256", "512", "1024", "4096", NULL};
const char *const shadowmap_filters[] = {"poisson", "none", "hw", "pcf3", "pcf5", "pcf7", NULL};
const char *const shadowmap_depths[] = {"24", "32f", NULL};
const char *const shadowmap_kernel_depths[] = {"centre", "receiver-plane", NULL};
static const char *const shadowmap_overlays[] = {SHADOWMAP_OVERLAY_NAMES, NULL};
enum { SHADOWMAP_FILTER_POISSON, SHADOWMAP_FILTER_NONE, SHADOWMAP_FILTER_HW, SHADOWMAP_FILTER_PCF3,
       SHADOWMAP_FILTER_PCF5, SHADOWMAP_FILTER_PCF7 };

static struct {
    shadowmap_settings settings;
    shadowmap_maps maps;
} shadowmap;

static const technique_param shadowmap_params[] = {
    SHADOWMAP_PARAMS(shadowmap.settings),
    {"overlay", "for lectures: texel boundaries on receivers, the light frustum, the map as an inset, texel size on "
                "screen",
     GLFW_KEY_V, TECHNIQUE_CHOICE, .index = &shadowmap.settings.overlay, .choices = shadowmap_overlays},
};

static float shadowmap_setting(float value, float fallback) { return value != 0 ? value : fallback; }

/* ---- fitting ---- */

int shadowmap_receiver_points(const technique_frame *f, float (*points)[3], int max_points) {
    const scene *s = f->gpu->scene;
    vec3 frustum[8];
    frustum_corners(f->view->view_projection, frustum);
    int n = 0;
    for (int i = 0; i < s->object_count; i++) {
        vec3 lo, hi;
        if (!s->objects[i].receives)
            continue;
        scene_object_world_bounds(&s->objects[i], lo, hi);
        n += frustum_box_part(f->view->view_projection, (const vec3 *)frustum, lo, hi, points + n,
                                    max_points - n);
    }
    return n;
}

/* Directional: an orthographic box around the visible receivers, deepened
 * towards the light to every caster whose box overlaps them seen from the
 * light. Spot: the cone, from the nearest such caster to the farthest
 * receiver. The depth range in view space runs along -z. */
static bool shadowmap_fit_2d(const technique_frame *f, const scene_light *l, shadowmap_light *m,
                             const float (*receivers)[3], int receiver_count) {
    const scene *s = f->gpu->scene;
    bool directional = l->type == SCENE_LIGHT_DIRECTIONAL;
    mat4 view, projection;
    vec3 lo, hi, eye;
    if (directional) {
        vec3 center = GLM_VEC3_ZERO_INIT;
        for (int i = 0; i < receiver_count; i++)
            glm_vec3_add(center, (float *)receivers[i], center);
        glm_vec3_scale(center, 1.0f / (float)receiver_count, center);
        glm_vec3_copy(center, eye); /* any point on the axis: depths are relative */
    } else {
        glm_vec3_copy((float *)l->position, eye);
    }
    frustum_look_along(eye, l->direction, view);
    frustum_view_bounds(view, receivers, receiver_count, lo, hi);
    float nearest = hi[2];
    for (int i = 0; i < s->object_count; i++) {
        vec3 corners[8], clo, chi, blo, bhi;
        if (!s->objects[i].casts)
            continue;
        scene_object_world_bounds(&s->objects[i], blo, bhi);
        frustum_box_corners(blo, bhi, corners);
        frustum_view_bounds(view, (const float(*)[3])corners, 8, clo, chi);
        /* A spot's caster counts if any of it is in front of the light. */
        bool overlaps = directional ? clo[0] <= hi[0] && chi[0] >= lo[0] && clo[1] <= hi[1] && chi[1] >= lo[1]
                                    : clo[2] < 0;
        if (overlaps)
            nearest = fmaxf(nearest, chi[2]);
    }
    float far_plane = -lo[2], near_plane = -nearest;
    float margin = 1e-3f * (far_plane - near_plane) + 1e-6f * fabsf(far_plane);
    m->far_plane = far_plane + margin;
    m->near_plane = near_plane - margin;
    m->orthographic = directional;
    if (directional) {
        glm_ortho(lo[0], hi[0], lo[1], hi[1], m->near_plane, m->far_plane, projection);
        m->texel_kind = SHADOWMAP_TEXEL_ORTHOGRAPHIC;
        m->texel_scale = fmaxf(hi[0] - lo[0], hi[1] - lo[1]) / (float)m->size;
    } else {
        float half_angle = glm_rad(fminf(l->outer_angle_deg + 1.0f, 85.0f));
        m->near_plane = fmaxf(m->near_plane, m->far_plane * SHADOWMAP_NEAR_RATIO);
        glm_perspective(2 * half_angle, 1, m->near_plane, m->far_plane, projection);
        m->texel_kind = SHADOWMAP_TEXEL_PERSPECTIVE;
        m->texel_scale = 2 * tanf(half_angle) / (float)m->size;
    }
    glm_mat4_mul(projection, view, m->view_projection[0]);
    return m->far_plane > m->near_plane;
}

static float shadowmap_box_distance(const scene_object *o, const float p[3]) {
    vec3 lo, hi, d;
    scene_object_world_bounds(o, lo, hi);
    for (int k = 0; k < 3; k++)
        d[k] = fmaxf(fmaxf(lo[k] - p[k], 0), p[k] - hi[k]);
    return glm_vec3_norm(d);
}

/* Point: six faces from the nearest caster to the farthest receiver. */
static bool shadowmap_fit_cube(const technique_frame *f, const scene_light *l, shadowmap_light *m,
                               const float (*receivers)[3], int receiver_count) {
    const scene *s = f->gpu->scene;
    static const float axes[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    /* GL's cube faces look along each axis with these "up" vectors. */
    static const float ups[6][3] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    float far_plane = 0, nearest = INFINITY;
    for (int i = 0; i < receiver_count; i++)
        far_plane = fmaxf(far_plane, glm_vec3_distance((float *)l->position, (float *)receivers[i]));
    for (int i = 0; i < s->object_count; i++)
        if (s->objects[i].casts)
            nearest = fminf(nearest, shadowmap_box_distance(&s->objects[i], l->position));
    m->far_plane = far_plane * 1.001f;
    /* A face's near plane cuts along its axis, and a point's distance along
     * the axis of its face is at least its distance over sqrt(3). */
    m->near_plane = fmaxf(fminf(nearest, far_plane) * 0.999f / sqrtf(3), m->far_plane * SHADOWMAP_NEAR_RATIO);
    m->orthographic = false;
    mat4 projection;
    glm_perspective(glm_rad(90), 1, m->near_plane, m->far_plane, projection);
    for (int face = 0; face < 6; face++) {
        vec3 target;
        mat4 view;
        glm_vec3_add((float *)l->position, (float *)axes[face], target);
        glm_lookat((float *)l->position, target, (float *)ups[face], view);
        glm_mat4_mul(projection, view, m->view_projection[face]);
    }
    return m->far_plane > m->near_plane;
}

bool shadowmap_fit_uniform(const technique_frame *f, int light, shadowmap_light *m, const float (*receivers)[3],
                           int receiver_count) {
    const scene_light *l = &f->gpu->scene->lights[light];
    m->cube = l->type == SCENE_LIGHT_POINT;
    m->casters = NULL;
    return m->cube ? shadowmap_fit_cube(f, l, m, receivers, receiver_count)
                   : shadowmap_fit_2d(f, l, m, receivers, receiver_count);
}

/* ---- maps ---- */

int shadowmap_settings_size(const shadowmap_settings *settings) {
    return atoi(shadowmap_sizes[settings->map_size]);
}

/* (Re)creates a light's depth texture when its kind, size, format or
 * filter changed: compare mode on, so that every read is a depth test;
 * outside the map reads are clamped (the shader calls them lit). */
static void shadowmap_prepare_texture(shadowmap_light *m, const shadowmap_settings *settings) {
    int depth = settings->depth, filter = settings->filter;
    if (m->texture && m->texture_cube == m->cube && m->texture_size == m->size && m->texture_depth == depth &&
        m->texture_filter == filter)
        return;
    glDeleteTextures(1, &m->texture);
    GLenum target = m->cube ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D;
    GLenum format = depth == 0 ? GL_DEPTH_COMPONENT24 : GL_DEPTH_COMPONENT32F;
    GLenum type = depth == 0 ? GL_UNSIGNED_INT : GL_FLOAT;
    GLint texel_filter = filter == SHADOWMAP_FILTER_NONE ? GL_NEAREST : GL_LINEAR;
    glGenTextures(1, &m->texture);
    glBindTexture(target, m->texture);
    for (int face = 0; face < (m->cube ? 6 : 1); face++)
        glTexImage2D(m->cube ? GL_TEXTURE_CUBE_MAP_POSITIVE_X + face : GL_TEXTURE_2D, 0, (GLint)format, m->size,
                     m->size, 0, GL_DEPTH_COMPONENT, type, NULL);
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, texel_filter);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, texel_filter);
    glTexParameteri(target, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(target, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(target, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    glTexParameteri(target, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTexParameteri(target, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    m->texture_cube = m->cube;
    m->texture_size = m->size;
    m->texture_depth = depth;
    m->texture_filter = filter;
}

static void shadowmap_render_depth(shadowmap_maps *k, const shadowmap_settings *settings, const technique_frame *f,
                                   shadowmap_light *m) {
    const scene *s = f->gpu->scene;
    glBindFramebuffer(GL_FRAMEBUFFER, k->framebuffer);
    glViewport(0, 0, m->size, m->size);
    if (settings->no_slope_bias) {
        glDisable(GL_POLYGON_OFFSET_FILL);
    } else {
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(shadowmap_setting(settings->slope_factor, SHADOWMAP_SLOPE_FACTOR),
                        shadowmap_setting(settings->slope_units, SHADOWMAP_SLOPE_UNITS));
    }
    glUseProgram(k->depth.id);
    for (int face = 0; face < (m->cube ? 6 : 1); face++) {
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT,
                               m->cube ? GL_TEXTURE_CUBE_MAP_POSITIVE_X + face : GL_TEXTURE_2D, m->texture, 0);
        glClear(GL_DEPTH_BUFFER_BIT);
        glUniformMatrix4fv(k->depth.view_projection, 1, GL_FALSE, (const float *)m->view_projection[face]);
        for (int i = 0; i < s->object_count; i++)
            if (s->objects[i].casts && (!m->casters || m->casters[i]))
                render_draw_object(f->gpu, &k->depth, i);
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
}

/* ---- programs ---- */

static bool shadowmap_program_load(shadowmap_program *p, const char *const files[2]) {
    if (!render_program_load(&p->program, files, 2, NULL))
        return false;
    unsigned id = p->program.id;
    p->map = glGetUniformLocation(id, "u_map");
    p->light = glGetUniformLocation(id, "u_light");
    p->filter = glGetUniformLocation(id, "u_filter");
    p->receiver_plane = glGetUniformLocation(id, "u_receiver_plane");
    p->show_texels = glGetUniformLocation(id, "u_show_texels");
    p->show_texel_size = glGetUniformLocation(id, "u_show_texel_size");
    p->kernel = glGetUniformLocation(id, "u_kernel");
    p->map_size = glGetUniformLocation(id, "u_map_size");
    p->constant_bias = glGetUniformLocation(id, "u_constant_bias");
    p->normal_offset = glGetUniformLocation(id, "u_normal_offset");
    p->depth_bias = glGetUniformLocation(id, "u_depth_bias");
    p->light_origin = glGetUniformLocation(id, "u_light_origin");
    p->near_plane = glGetUniformLocation(id, "u_near");
    p->far_plane = glGetUniformLocation(id, "u_far");
    p->light_matrix = glGetUniformLocation(id, "u_light_matrix");
    p->texel_kind = glGetUniformLocation(id, "u_texel_kind");
    p->orthographic = glGetUniformLocation(id, "u_orthographic");
    p->texel_scale = glGetUniformLocation(id, "u_texel_scale");
    p->light_axis = glGetUniformLocation(id, "u_light_axis");
    p->color = glGetUniformLocation(id, "u_color");
    p->cube_map = glGetUniformLocation(id, "u_cube_map");
    p->cube = glGetUniformLocation(id, "u_cube");
    return true;
}

bool shadowmap_maps_init(shadowmap_maps *k) {
    static const char *const depth_files[] = {"shadow_depth.vert", "shadow_depth.frag"};
    static const char *const files_2d[] = {"lit.vert", "shadowmap_2d.frag"};
    static const char *const files_cube[] = {"lit.vert", "shadowmap_cube.frag"};
    static const char *const lines_files[] = {"overlay.vert", "overlay_lines.frag"};
    static const char *const inset_files[] = {"overlay.vert", "overlay_map.frag"};
    if (!render_program_load(&k->depth, depth_files, 2, NULL) || !shadowmap_program_load(&k->camera_2d, files_2d) ||
        !shadowmap_program_load(&k->camera_cube, files_cube) || !shadowmap_program_load(&k->lines, lines_files) ||
        !shadowmap_program_load(&k->inset, inset_files))
        return false;
    glGenVertexArrays(1, &k->overlay_vao);
    glBindVertexArray(k->overlay_vao);
    glGenBuffers(1, &k->overlay_buffer);
    glBindBuffer(GL_ARRAY_BUFFER, k->overlay_buffer);
    glBufferData(GL_ARRAY_BUFFER, 24 * 3 * sizeof(float), NULL, GL_STREAM_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), NULL);
    glBindVertexArray(0);
    glGenFramebuffers(1, &k->framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, k->framebuffer);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    /* Kernels that cross a cube face read on into the next face. */
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    return true;
}

void shadowmap_maps_destroy(shadowmap_maps *k) {
    render_program_destroy(&k->depth);
    render_program_destroy(&k->camera_2d.program);
    render_program_destroy(&k->camera_cube.program);
    render_program_destroy(&k->lines.program);
    render_program_destroy(&k->inset.program);
    glDeleteVertexArrays(1, &k->overlay_vao);
    glDeleteBuffers(1, &k->overlay_buffer);
    glDeleteFramebuffers(1, &k->framebuffer);
    for (int l = 0; l < SCENE_MAX_LIGHTS; l++)
        glDeleteTextures(1, &k->lights[l].texture);
    memset(k, 0, sizeof *k);
}

/* ---- the camera pass ---- */

/* Light l's share, added where its map lets it through. */
static void shadowmap_add_light(shadowmap_maps *k, const shadowmap_settings *st, const technique_frame *f, int l,
                                const shadowmap_light *m) {
    const scene_light *light = &f->gpu->scene->lights[l];
    const shadowmap_program *p = m->cube ? &k->camera_cube : &k->camera_2d;
    static const int kernels[] = {[SHADOWMAP_FILTER_PCF3] = 3, [SHADOWMAP_FILTER_PCF5] = 5,
                                  [SHADOWMAP_FILTER_PCF7] = 7, [SHADOWMAP_FILTER_POISSON] = SHADOWMAP_POISSON_TEXELS};
    int mode = st->filter == SHADOWMAP_FILTER_NONE || st->filter == SHADOWMAP_FILTER_HW ? 0
               : st->filter == SHADOWMAP_FILTER_POISSON                                 ? 2
                                                                                        : 1;
    render_program_use(&p->program, f->view);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(m->cube ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D, m->texture);
    glUniform1i(p->map, 0);
    glUniform1i(p->light, l);
    glUniform1i(p->filter, mode);
    glUniform1i(p->receiver_plane, st->kernel_depth == 1);
    glUniform1i(p->show_texels, st->overlay == SHADOWMAP_OVERLAY_ALL || st->overlay == SHADOWMAP_OVERLAY_TEXELS);
    glUniform1i(p->show_texel_size, st->overlay == SHADOWMAP_OVERLAY_TEXEL_SIZE);
    glUniform1i(p->kernel, kernels[st->filter]);
    glUniform1f(p->map_size, (float)m->size);
    glUniform1f(p->constant_bias,
                st->no_constant_bias ? 0 : shadowmap_setting(st->constant_texels, SHADOWMAP_CONSTANT_TEXELS));
    glUniform1f(p->normal_offset, st->normal_texels);
    glUniform2f(p->depth_bias, st->depth_bias_slope, st->depth_bias_min);
    glUniform3fv(p->light_origin, 1, light->position);
    glUniform1f(p->near_plane, m->near_plane);
    glUniform1f(p->far_plane, m->far_plane);
    glUniformMatrix4fv(p->light_matrix, 1, GL_FALSE, (const float *)m->view_projection[0]);
    glUniform1i(p->texel_kind, (int)m->texel_kind);
    glUniform1f(p->texel_scale, m->texel_scale);
    glUniform3fv(p->light_axis, 1, light->direction);
    for (int i = 0; i < f->gpu->scene->object_count; i++)
        render_draw_object(f->gpu, &p->program, i);
}

/* ---- overlays ---- */

/* `count` (<= 24) line ends in world space, in one colour. */
static void shadowmap_draw_lines(shadowmap_maps *k, const float (*points)[3], int count, const mat4 view_projection,
                                 const float color[3]) {
    glUseProgram(k->lines.program.id);
    glUniformMatrix4fv(k->lines.program.view_projection, 1, GL_FALSE, (const float *)view_projection);
    glUniform3fv(k->lines.color, 1, color);
    glBindVertexArray(k->overlay_vao);
    glBindBuffer(GL_ARRAY_BUFFER, k->overlay_buffer);
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(sizeof *points * (size_t)count), points);
    glDrawArrays(GL_LINES, 0, count);
}

void shadowmap_draw_frustum(shadowmap_maps *k, const mat4 frustum, const mat4 view_projection) {
    float corners[8][3], lines[24][3];
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
    shadowmap_draw_lines(k, (const float(*)[3])lines, 24, view_projection, (const float[3]){1.0f, 0.85f, 0.2f});
}

/* Light 0's map in the bottom-right third of the picture: a 2D map as it
 * is, a cube map as its six faces in two rows (+X -X +Y, -Y +Z -Z). */
static void shadowmap_draw_inset(shadowmap_maps *k, const shadowmap_light *m, const int viewport[4]) {
    static const float quad[6][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    int height = viewport[3] / 3, width = m->cube ? height * 3 / 2 : height;
    glViewport(viewport[0] + viewport[2] - width - 8, viewport[1] + 8, width, height);
    glDisable(GL_DEPTH_TEST);
    const shadowmap_program *p = &k->inset;
    glUseProgram(p->program.id);
    mat4 identity = GLM_MAT4_IDENTITY_INIT;
    glUniformMatrix4fv(p->program.view_projection, 1, GL_FALSE, (const float *)identity);
    /* Two units: a 2D and a cube sampler may not share one. */
    GLenum texture_target = m->cube ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_2D;
    glUniform1i(p->map, 0);
    glUniform1i(p->cube_map, 1);
    glUniform1i(p->cube, m->cube);
    glUniform1i(p->orthographic, m->orthographic);
    glUniform1f(p->near_plane, m->near_plane);
    glUniform1f(p->far_plane, m->far_plane);
    glActiveTexture(m->cube ? GL_TEXTURE1 : GL_TEXTURE0);
    glBindTexture(texture_target, m->texture);
    glTexParameteri(texture_target, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glBindVertexArray(k->overlay_vao);
    glBindBuffer(GL_ARRAY_BUFFER, k->overlay_buffer);
    glBufferSubData(GL_ARRAY_BUFFER, 0, sizeof quad, quad);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glTexParameteri(texture_target, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glActiveTexture(GL_TEXTURE0);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
}

static void shadowmap_draw_overlays(shadowmap_maps *k, int overlay, const technique_frame *f, const bool *fitted,
                                    const int viewport[4]) {
    glDisable(GL_BLEND);
    glDepthFunc(GL_LEQUAL);
    bool frustum = overlay == SHADOWMAP_OVERLAY_ALL || overlay == SHADOWMAP_OVERLAY_FRUSTUM;
    for (int l = 0; frustum && l < f->gpu->scene->light_count; l++)
        for (int face = 0; fitted[l] && face < (k->lights[l].cube ? 6 : 1); face++)
            shadowmap_draw_frustum(k, k->lights[l].view_projection[face], f->view->view_projection);
    if (fitted[0] && (overlay == SHADOWMAP_OVERLAY_ALL || overlay == SHADOWMAP_OVERLAY_MAP))
        shadowmap_draw_inset(k, &k->lights[0], viewport);
}

void shadowmap_maps_render(shadowmap_maps *k, const shadowmap_settings *settings, const technique_frame *f,
                           shadowmap_fit_function fit) {
    const scene *s = f->gpu->scene;
    GLint target_framebuffer, viewport[4];
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target_framebuffer);
    glGetIntegerv(GL_VIEWPORT, viewport);
    static float receivers[SHADOWMAP_MAX_RECEIVER_POINTS][3];
    int receiver_count = shadowmap_receiver_points(f, receivers, SHADOWMAP_MAX_RECEIVER_POINTS);
    bool fitted[SCENE_MAX_LIGHTS] = {false};
    for (int l = 0; l < s->light_count && receiver_count > 0; l++) {
        shadowmap_light *m = &k->lights[l];
        m->size = shadowmap_settings_size(settings);
        fitted[l] = fit(f, l, m, (const float(*)[3])receivers, receiver_count);
        if (fitted[l]) {
            shadowmap_prepare_texture(m, settings);
            shadowmap_render_depth(k, settings, f, m);
        }
    }
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)target_framebuffer);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    /* Ambient, then each light added where its map lets it through. */
    render_use_lit(f->gpu, f->view, 0, 0, true);
    for (int i = 0; i < s->object_count; i++)
        render_draw_object(f->gpu, &f->gpu->lit, i);
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    for (int l = 0; l < s->light_count; l++) {
        if (fitted[l]) {
            shadowmap_add_light(k, settings, f, l, &k->lights[l]);
        } else { /* nothing visible receives: no map needed, nothing shadowed */
            render_use_lit(f->gpu, f->view, l, l + 1, false);
            for (int i = 0; i < s->object_count; i++)
                render_draw_object(f->gpu, &f->gpu->lit, i);
        }
    }
    shadowmap_draw_overlays(k, settings->overlay, f, fitted, viewport);
}

/* ---- the technique ---- */

static bool shadowmap_init(const render_scene *gpu) {
    (void)gpu;
    return shadowmap_maps_init(&shadowmap.maps);
}

static void shadowmap_destroy(void) { shadowmap_maps_destroy(&shadowmap.maps); }

static void shadowmap_render(const technique_frame *f) {
    shadowmap_maps_render(&shadowmap.maps, &shadowmap.settings, f, shadowmap_fit_uniform);
}

static void shadowmap_describe(char *out, size_t size) {
    const shadowmap_light *m = &shadowmap.maps.lights[0];
    snprintf(out, size, "light 0: %s map %dx%d, depth range %.3g .. %.3g", m->cube ? "cube" : "2D", m->size, m->size,
             m->near_plane, m->far_plane);
}

/* The sweep: map size x filter x bias, and two configurations popular
 * tutorials use ("label: flags"), so the report shows where our biases
 * stand at the same cost: LearnOpenGL's bias max(0.05 (1 - N.L), 0.005)
 * with 3x3 PCF at 1024 (against --map-size 1024 --filter pcf3), and
 * polygon offset (1.25, 1.75) with 3x3 PCF at 2048 (against --filter
 * pcf3). */
static const char *const shadowmap_bench_configs[] = {
    "",
    "--map-size 1024",
    "--map-size 1024 --filter pcf3",
    "--map-size 4096",
    "--filter none",
    "--filter hw",
    "--filter pcf3",
    "--filter pcf5",
    "--kernel-depth receiver-plane",
    "--filter pcf7 --kernel-depth receiver-plane",
    "--normal-texels 1",
    "--no-slope-bias",
    "--no-constant-bias --no-slope-bias",
    "textbook depth bias: --map-size 1024 --filter pcf3 --no-constant-bias --no-slope-bias --depth-bias-slope 0.05 "
    "--depth-bias-min 0.005",
    "textbook polygon offset: --filter pcf3 --no-constant-bias --slope-factor 1.25 --slope-units 1.75",
};

const technique shadowmap_technique = {
    .name = "shadowmap",
    .title = "shadow maps (Williams 1978) with bias and PCF (Reeves et al. 1987)",
    .params = shadowmap_params,
    .param_count = (int)(sizeof shadowmap_params / sizeof *shadowmap_params),
    .bench_configs = shadowmap_bench_configs,
    .bench_config_count = (int)(sizeof shadowmap_bench_configs / sizeof *shadowmap_bench_configs),
    .init = shadowmap_init,
    .render = shadowmap_render,
    .destroy = shadowmap_destroy,
    .describe = shadowmap_describe,
};
