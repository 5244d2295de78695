/* map: moment shadow maps (see map.h, "Moment shadow maps"):
 * the blur's width, the moment textures and the blur's two passes.
 *
 * The blur's width. A hard light's box is MAP_MOMENTS_HARD_BLUR_TEXELS
 * wide past the centre texel: with the bilinear read, a filter a few
 * texels across, as the kernels are. An area light's is the mean
 * penumbra its casters cast, each caster's weighed by the area of its box
 * seen along the light's ray (how much shadow it casts): the ray through
 * a caster's centre, at distance d from a light of radius R (a sun's
 * rays, of angular radius a), meets the first receiver box h farther on;
 * a blocker there casts a penumbra of radius R h / d (a sun's: tan(a) h)
 * by similar triangles, measured in the layer's texels where the ray
 * meets the receiver. One width for the whole
 * layer (a cube's six faces share one, so that their edges meet): the
 * penumbra is as wide at contact as far from it (no contact hardening,
 * which PCSS's blocker search gives). */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>

#include "map_internal.h"

/* The least derivative of map coordinates along a world axis: a matrix
 * degenerate there gives an infinite texel, left out of the mean. */
#define MAP_MOMENTS_MIN_DERIVATIVE 1e-20f

map_moments map_filter_moments(int filter) {
    switch (filter) {
    case MAP_FILTER_VSM: return MAP_MOMENTS_VSM;
    case MAP_FILTER_EVSM2: return MAP_MOMENTS_EVSM2;
    case MAP_FILTER_EVSM4: return MAP_MOMENTS_EVSM4;
    case MAP_FILTER_MSM: return MAP_MOMENTS_MSM;
    default: return MAP_MOMENTS_NONE;
    }
}

/* A texel's world size at p in a layer of a size x size map: how far p
 * moves across the light's ray for its map coordinates to change by one
 * texel, from the matrix's derivatives (as the camera pass measures a
 * warp's texel, shaders/map_2d.glsl); infinite behind the layer. */
static float map_moments_texel(const mat4 layer, const float p[3], int size) {
    vec4 clip;
    glm_mat4_mulv((vec4 *)layer, (vec4){p[0], p[1], p[2], 1}, clip);
    if (clip[3] <= 0)
        return INFINITY;
    vec3 du, dv;
    for (int k = 0; k < 3; k++) {
        du[k] = (layer[k][0] - clip[0] / clip[3] * layer[k][3]) / clip[3];
        dv[k] = (layer[k][1] - clip[1] / clip[3] * layer[k][3]) / clip[3];
    }
    float derivative = fmaxf(fminf(glm_vec3_norm(du), glm_vec3_norm(dv)), MAP_MOMENTS_MIN_DERIVATIVE);
    return 2.0f / ((float)size * derivative);
}

/* The cube face a direction from the light falls on (GL's major axis). */
static int map_moments_face(const float d[3]) {
    int axis = 0;
    for (int k = 1; k < 3; k++)
        if (fabsf(d[k]) > fabsf(d[axis]))
            axis = k;
    return 2 * axis + (d[axis] < 0);
}

/* Where a ray from `from` along unit `ray` first enters the box lo..hi
 * (the slab test; a flat box too), or INFINITY where it misses; 0 from
 * inside. */
static float map_moments_ray_box(const vec3 from, const vec3 ray, const vec3 lo, const vec3 hi) {
    float enter = 0, leave = INFINITY;
    for (int k = 0; k < 3; k++) {
        if (ray[k] == 0) {
            if (from[k] < lo[k] || from[k] > hi[k])
                return INFINITY;
            continue;
        }
        float a = (lo[k] - from[k]) / ray[k], b = (hi[k] - from[k]) / ray[k];
        enter = fmaxf(enter, fminf(a, b));
        leave = fminf(leave, fmaxf(a, b));
    }
    return enter <= leave ? enter : INFINITY;
}

/* How far along the ray from a caster's centre the first receiver (not
 * the caster itself) lies: INFINITY where the ray meets none. */
static float map_moments_drop(const scene *s, int caster, const vec3 centre, const vec3 ray) {
    float nearest = INFINITY;
    for (int j = 0; j < s->object_count; j++) {
        if (j == caster || !s->objects[j].receives)
            continue;
        vec3 lo, hi;
        scene_object_world_bounds(&s->objects[j], lo, hi);
        nearest = fminf(nearest, map_moments_ray_box(centre, ray, lo, hi));
    }
    return nearest;
}

void map_moments_blur_texels(const scene *s, int l, const map_light *m, float blur[MAP_MAX_LAYERS]) {
    const scene_light *light = &s->lights[l];
    bool directional = light->type == SCENE_LIGHT_DIRECTIONAL;
    /* A cube's faces share one width (each shadow measured on the face it
     * lands on): one sum for all six. */
    int sums = m->kind == MAP_CUBE ? 1 : m->layer_count;
    double sum[MAP_MAX_LAYERS] = {0}, weights[MAP_MAX_LAYERS] = {0};
    for (int i = 0; light->radius > 0 && i < s->object_count; i++) {
        if (!s->objects[i].casts || (m->casters && !m->casters[i]))
            continue;
        vec3 lo, hi, centre, ray, foot;
        scene_object_world_bounds(&s->objects[i], lo, hi);
        glm_vec3_center(lo, hi, centre);
        float distance = 1;
        if (directional) {
            glm_vec3_normalize_to((float *)light->direction, ray);
        } else {
            glm_vec3_sub(centre, (float *)light->position, ray);
            distance = glm_vec3_norm(ray);
            if (distance <= 0)
                continue;
            glm_vec3_scale(ray, 1 / distance, ray);
        }
        float drop = map_moments_drop(s, i, centre, ray);
        if (!isfinite(drop))
            continue;
        float penumbra = directional ? tanf(glm_rad(light->radius)) * drop : light->radius * drop / distance;
        glm_vec3_copy(centre, foot);
        glm_vec3_muladds(ray, drop, foot);
        int face = 0;
        if (m->kind == MAP_CUBE) {
            vec3 d;
            glm_vec3_sub(foot, (float *)light->position, d);
            face = map_moments_face(d);
        }
        /* The box's shadow's size: its area seen along the ray. */
        vec3 e;
        glm_vec3_sub(hi, lo, e);
        double area = fabsf(ray[0]) * e[1] * e[2] + fabsf(ray[1]) * e[0] * e[2] + fabsf(ray[2]) * e[0] * e[1];
        for (int layer = 0; layer < sums; layer++) {
            int at = m->kind == MAP_CUBE ? face : layer;
            float texel = map_moments_texel(m->layer_view_projection[at], foot, m->size);
            if (!isfinite(texel) || area <= 0)
                continue;
            sum[layer] += area * penumbra / texel;
            weights[layer] += area;
        }
    }
    for (int layer = 0; layer < m->layer_count; layer++) {
        int k = layer < sums ? layer : 0;
        blur[layer] = weights[k] > 0 ? (float)(sum[k] / weights[k]) : MAP_MOMENTS_HARD_BLUR_TEXELS;
    }
}

/* ---- the textures ---- */

/* format: GL_RG32F or GL_RGBA32F; the pixel format named with it is the
 * one ES (WebGL 2) accepts for it, as desktop GL does. */
static void map_moments_image(GLenum target, map_kind kind, int size, int layers, GLenum format, GLint filter) {
    GLenum pixels = format == GL_RG32F ? GL_RG : GL_RGBA;
    if (kind == MAP_ARRAY)
        glTexImage3D(target, 0, (GLint)format, size, size, layers, 0, pixels, GL_FLOAT, NULL);
    else
        for (int layer = 0; layer < layers; layer++)
            glTexImage2D(map_layer_image(kind, layer), 0, (GLint)format, size, size, 0, pixels, GL_FLOAT, NULL);
    map_texture_filter(target, filter);
}

void map_moments_prepare(map_light *m, map_moments moments) {
    map_texture *t = &m->texture;
    glDeleteTextures(1, &t->moments);
    glDeleteTextures(2, t->blur);
    t->moments = t->blur[0] = t->blur[1] = 0;
    if (moments == MAP_MOMENTS_NONE)
        return;
    /* 32-bit floats: EVSM's warp reaches e^84 (16-bit floats end at 65504). */
    bool two = moments == MAP_MOMENTS_VSM || moments == MAP_MOMENTS_EVSM2;
    GLenum format = two ? GL_RG32F : GL_RGBA32F;
    GLenum target = map_target(m->kind);
    glGenTextures(1, &t->moments);
    glBindTexture(target, t->moments);
    /* Read bilinear by the camera pass: a filtered map's point of it all. */
    map_moments_image(target, m->kind, m->size, m->layer_count, format, GL_LINEAR);
    /* Read by the box's pairs, bilinear too. */
    glGenTextures(2, t->blur);
    for (int k = 0; k < 2; k++) {
        glBindTexture(GL_TEXTURE_2D, t->blur[k]);
        map_moments_image(GL_TEXTURE_2D, MAP_2D, m->size, 1, format, GL_LINEAR);
    }
}

/* ---- the blur ---- */

static bool map_moments_program(map_blur_program *p, map_moments moments, bool from_depth, map_kind kind) {
    if (p->id)
        return true;
    static const char *const files[] = {"viewport_triangle.vert", "shadow_moments.frag"};
    const shader_define defines[] = {{"MAP_PASS_MOMENTS", (int)moments},
                                     {"MAP_BLUR_FROM_DEPTH", from_depth},
                                     {"MAP_BLUR_KIND", (int)kind},
                                     SHADER_DEFINE(MAP_MOMENTS_VSM),
                                     SHADER_DEFINE(MAP_MOMENTS_EVSM2),
                                     SHADER_DEFINE(MAP_MOMENTS_EVSM4),
                                     SHADER_DEFINE(MAP_MOMENTS_MSM),
                                     SHADER_DEFINE(MAP_MOMENTS_MAX_BLUR_TEXELS),
                                     MAP_TEXEL_DEFINES,
                                     {NULL, 0}};
    p->id = shader_load_program(files, 2, defines);
    if (!p->id)
        return false;
    p->radius = shader_uniform(p->id, "u_radius");
    p->axis = shader_uniform(p->id, "u_axis");
    p->layer = shader_uniform(p->id, "u_layer");
    glUseProgram(p->id);
    map_texel_units(p->id); /* the second pass reads its 2D sums on the 2D unit */
    return true;
}

/* The moments' framebuffer with `texture`'s image `image` as its colour
 * (map_color_target). */
static bool map_moments_target(map_renderer *r, unsigned texture, GLenum image, int layer) {
    return map_color_target(&r->blur_framebuffer, texture, image, layer,
                            "a moment filter reads one bilinear depth test instead; use a kernel (--filter "
                            "poisson)");
}

/* One box pass along `axis` from the 2D texture `source` into the target
 * bound. */
static void map_moments_box(const map_blur_program *p, unsigned source, float radius, float axis_x) {
    glActiveTexture(GL_TEXTURE0 + MAP_2D);
    glBindTexture(GL_TEXTURE_2D, source);
    glUseProgram(p->id);
    glUniform1f(p->radius, radius);
    glUniform2f(p->axis, axis_x, 1 - axis_x);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

bool map_moments_blur(map_renderer *r, const map_light *m, map_moments moments, int layer) {
    if (r->blur_failed)
        return false;
    map_blur_program *first = &r->blur_depth[moments][m->kind], *box = &r->blur_moments;
    const map_texture *t = &m->texture;
    if (!map_moments_program(first, moments, true, m->kind) || !map_moments_program(box, moments, false, MAP_2D) ||
        !map_moments_target(r, t->blur[0], GL_TEXTURE_2D, 0)) {
        r->blur_failed = true;
        return false;
    }
    GLboolean depth_test = glIsEnabled(GL_DEPTH_TEST);
    glDisable(GL_DEPTH_TEST);
    glViewport(0, 0, m->size, m->size);
    glBindVertexArray(r->screen_vao);
    GLuint unit = (GLuint)m->kind;
    /* The depths as stored: compare mode off, nearest. */
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(map_target(m->kind), t->id);
    glBindSampler(unit, r->depth_sampler);
    glUseProgram(first->id);
    glUniform1i(first->layer, layer);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindSampler(unit, 0);
    GLenum image = m->kind == MAP_ARRAY ? GL_TEXTURE_2D_ARRAY : map_layer_image(m->kind, layer);
    bool ok = map_moments_target(r, t->blur[1], GL_TEXTURE_2D, 0);
    if (ok)
        map_moments_box(box, t->blur[0], m->blur_texels[layer], 1);
    ok = ok && map_moments_target(r, t->moments, image, layer);
    if (ok)
        map_moments_box(box, t->blur[1], m->blur_texels[layer], 0);
    r->blur_failed = !ok;
    glBindVertexArray(0);
    if (depth_test)
        glEnable(GL_DEPTH_TEST);
    return ok;
}

void map_moments_destroy(map_renderer *r) {
    for (int k = 0; k <= MAP_MOMENTS_MSM; k++)
        for (int kind = 0; kind <= MAP_ARRAY; kind++)
            shader_delete_program(r->blur_depth[k][kind].id);
    shader_delete_program(r->blur_moments.id);
    glDeleteFramebuffers(1, &r->blur_framebuffer);
}
