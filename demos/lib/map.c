/* map: storage, the depth pass, the camera pass and the frame (see
 * map.h). */
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "context.h"
#include "depth.h"
#include "area_light.h"
#include "map_internal.h"
#include "mesh_point.h"
#include "shading.h"

const char *const map_sizes[] = {"auto", "256", "512", "1024", "2048", "4096", NULL};
const char *const map_filters[] = {[MAP_FILTER_AUTO] = "auto",   [MAP_FILTER_POISSON] = "poisson",
                                   [MAP_FILTER_NONE] = "none",   [MAP_FILTER_HW] = "hw",
                                   [MAP_FILTER_PCF3] = "pcf3",   [MAP_FILTER_PCF5] = "pcf5",
                                   [MAP_FILTER_PCF7] = "pcf7",   [MAP_FILTER_TENT3] = "tent3",
                                   [MAP_FILTER_TENT5] = "tent5", [MAP_FILTER_VSM] = "vsm",
                                   [MAP_FILTER_EVSM2] = "evsm2", [MAP_FILTER_EVSM4] = "evsm4",
                                   [MAP_FILTER_MSM] = "msm",     NULL};
const char *const map_depths[] = {[MAP_DEPTH_24] = "24", [MAP_DEPTH_32F] = "32f", NULL};
const char *const map_kernel_depths[] = {
    [MAP_KERNEL_DEPTH_RECEIVER_PLANE] = "receiver-plane", [MAP_KERNEL_DEPTH_CENTRE] = "centre", NULL};
const char *const map_softs[] = {[MAP_SOFT_PCSS] = "pcss", [MAP_SOFT_OFF] = "off", NULL};

/* What each filter reads: the kernel's shape and its size (N, or the
 * Poisson disc's scale in texels); a moment filter reads its moments once
 * (the single tap's code is the least the program holds). Auto reads as
 * the filter it stands for (map_filter_in_use). */
static const struct {
    map_kernel shape;
    int size;
} map_kernels[] = {
    [MAP_FILTER_POISSON] = {MAP_KERNEL_POISSON, MAP_POISSON_SCALE_TEXELS},
    [MAP_FILTER_NONE] = {MAP_KERNEL_SINGLE, 0},
    [MAP_FILTER_HW] = {MAP_KERNEL_SINGLE, 0},
    [MAP_FILTER_PCF3] = {MAP_KERNEL_GRID, 3},
    [MAP_FILTER_PCF5] = {MAP_KERNEL_GRID, 5},
    [MAP_FILTER_PCF7] = {MAP_KERNEL_GRID, 7},
    [MAP_FILTER_TENT3] = {MAP_KERNEL_TENT, 3},
    [MAP_FILTER_TENT5] = {MAP_KERNEL_TENT, 5},
    [MAP_FILTER_VSM] = {MAP_KERNEL_SINGLE, 0},
    [MAP_FILTER_EVSM2] = {MAP_KERNEL_SINGLE, 0},
    [MAP_FILTER_EVSM4] = {MAP_KERNEL_SINGLE, 0},
    [MAP_FILTER_MSM] = {MAP_KERNEL_SINGLE, 0},
};

/* The C constants the camera pass compares with (and the legend's
 * colours, the heat map's ends). */
static const shader_define map_defines[] = {SHADER_DEFINE(MAP_KERNEL_SINGLE),
                                            SHADER_DEFINE(MAP_KERNEL_GRID),
                                            SHADER_DEFINE(MAP_KERNEL_POISSON),
                                            SHADER_DEFINE(MAP_TEXEL_ORTHOGRAPHIC),
                                            SHADER_DEFINE(MAP_TEXEL_PERSPECTIVE),
                                            SHADER_DEFINE(MAP_TEXEL_PROJECTIVE),
                                            SHADER_DEFINE(MAP_KERNEL_TENT),
                                            SHADER_DEFINE(MAP_HEAT_LOG2_MIN),
                                            SHADER_DEFINE(MAP_HEAT_LOG2_MAX),
                                            SHADER_DEFINE(MAP_MAX_ARRAY_LAYERS),
                                            SHADER_DEFINE(MAP_SOFT_SEARCH_TAPS),
                                            SHADER_DEFINE(MAP_SOFT_FILTER_TAPS),
                                            SHADER_DEFINE(MAP_SOFT_MAX_TEXELS),
                                            SHADER_DEFINE(MAP_POISSON_SCALE_TEXELS),
                                            SHADER_DEFINE(MAP_PENUMBRA_LOG2_MIN),
                                            SHADER_DEFINE(MAP_MOMENTS_VSM),
                                            SHADER_DEFINE(MAP_MOMENTS_EVSM2),
                                            SHADER_DEFINE(MAP_MOMENTS_EVSM4),
                                            SHADER_DEFINE(MAP_MOMENTS_MSM),
                                            SHADER_DEFINE(MAP_RAYS_OFF),
                                            SHADER_DEFINE(MAP_RAYS_UNSURE),
                                            SHADER_DEFINE(MAP_RAYS_ALL),
                                            SHADER_DEFINE(MAP_RAY_FIRST_SAMPLES),
                                            SHADER_DEFINE(MAP_RAY_BLOCKED_SAMPLES),
                                            SHADER_DEFINE(MAP_BOUNDS_CELL_TEXELS),
                                            BVH_GPU_DEFINES,
                                            {NULL, 0}};

/* The camera pass's sampler arrays, by the kind of map they read: its
 * comparisons', a soft light's depths' and the transmittance maps' (the
 * 2D maps' first). */
#define MAP_SAMPLER_2D 0
static const struct {
    const char *name, *depths, *transmittances;
    map_light_kind kind;
} map_samplers[MAP_SAMPLER_TYPES] = {
    {"u_maps_2d", "u_depths_2d", "u_transmittances_2d", MAP_LIGHT_2D},
    {"u_maps_cube", "u_depths_cube", "u_transmittances_cube", MAP_LIGHT_CUBE},
    {"u_maps_array", "u_depths_array", "u_transmittances_array", MAP_LIGHT_ARRAY},
};

static float map_setting(float value, float fallback) { return value != 0 ? value : fallback; }

int map_settings_size(const map_settings *settings) { return atoi(map_sizes[settings->map_size]); }

int map_auto_finer(const map_settings *settings, const scene *s, const scene_light *light) {
    return !map_light_soft(settings, light) && scene_light_reaches_cut_out(s, light) ? MAP_AUTO_CUT_OUT_FINER : 1;
}

int map_side_within_gl(const map_renderer *r, int side, int least) {
    while (side > least && side > r->max_texture_size)
        side /= 2;
    return side;
}

map_auto_rule map_auto_rule_for(const map_renderer *r, const map_settings *settings, const scene *s,
                                const scene_light *light) {
    int finer = map_auto_finer(settings, s, light);
    int largest = finer > 1 && light->type == SCENE_LIGHT_DIRECTIONAL ? MAP_AUTO_CUT_OUT_MAX_SIZE : MAP_AUTO_MAX_SIZE;
    return (map_auto_rule){MAP_AUTO_TEXEL_PIXELS / (float)finer, map_side_within_gl(r, largest, MAP_AUTO_MIN_SIZE)};
}

int map_auto_size(const map_light *m, const scene_light *light, map_samples samples, map_auto_rule rule) {
    if (samples.grazing > samples.count)
        return rule.largest;
    return map_auto_size_or(m, light, samples.samples, samples.count,
                            samples.reach_sampled ? MAP_AUTO_MIN_SIZE : MAP_AUTO_FALLBACK_SIZE, rule);
}

int map_auto_size_or(const map_light *m, const scene_light *light, const warp_sample *samples, int n, int unmeasured,
                     map_auto_rule rule) {
    double sum = 0;
    int measured = 0;
    for (int i = 0; i < n; i++) {
        float texel =
            warp_sample_texel_pixels(m->layer_view_projection, m->layer_count, m->size, light->position, &samples[i]);
        if (isfinite(texel)) {
            sum += texel;
            measured++;
        }
    }
    if (measured == 0)
        return unmeasured;
    double needed = m->size * (sum / measured) / rule.texel_pixels;
    int size = MAP_AUTO_MIN_SIZE;
    while (size < rule.largest && size < needed)
        size *= 2;
    return size;
}

/* Where on screen (NDC x0, y0, x1, y1, within the picture) light l may
 * light a receiver: the bounds of the receivers' boxes clipped to the
 * cube around its range, of those it reaches (a spot's cone). False
 * without a range, where none is left, or where one reaches behind the
 * eye. */
static bool map_reach_ndc(const map_renderer *r, const scene_light *light, const camera_view *view, float ndc[4]) {
    if (light->type == SCENE_LIGHT_DIRECTIONAL || !(light->range > 0))
        return false;
    ndc[0] = ndc[1] = INFINITY;
    ndc[2] = ndc[3] = -INFINITY;
    for (int i = 0; i < r->picture_box_count; i++) {
        vec3 lo, hi;
        vec2 box_lo, box_hi;
        glm_vec3_copy(r->picture_boxes[i][0], lo);
        glm_vec3_copy(r->picture_boxes[i][1], hi);
        if (!scene_light_clip_to_range(light, lo, hi) || !scene_light_reaches_box(light, lo, hi))
            continue;
        if (!frustum_box_ndc_bounds(view->view_projection, lo, hi, box_lo, box_hi))
            return false;
        for (int k = 0; k < 2; k++) {
            ndc[k] = fminf(ndc[k], box_lo[k]);
            ndc[k + 2] = fmaxf(ndc[k + 2], box_hi[k]);
        }
    }
    for (int k = 0; k < 2; k++) {
        ndc[k] = fmaxf(ndc[k], -1);
        ndc[k + 2] = fminf(ndc[k + 2], 1);
    }
    return ndc[0] < ndc[2] && ndc[1] < ndc[3];
}

map_samples map_light_samples(map_renderer *r, const technique_frame *f, int l) {
    const scene *s = f->gpu->scene;
    const scene_light *light = &s->lights[l];
    if (r->hit_count < 0) {
        r->picture_box_count = warp_receiver_boxes(s, r->picture_boxes);
        r->hit_count = warp_samples((const float(*)[2][3])r->picture_boxes, r->picture_box_count, f->view, f->width,
                                    f->height, NULL, r->hits);
    }
    if (r->sample_light != l) {
        r->sample_count = warp_samples_lit(r->hits, r->hit_count, light, r->samples, &r->grazing_count);
        /* No sample of the picture's grid the light's map is measured at
         * (a far lamp's pool, between its rows; at most a wall edge-on to
         * it): a grid again, over where on screen it may light a receiver
         * alone, whose samples decide the grazing rule too. */
        float ndc[4];
        r->reach_sampled = r->sample_count == 0 && map_reach_ndc(r, light, f->view, ndc);
        if (r->reach_sampled) {
            int boxes = warp_boxes_seen_in((const float(*)[2][3])r->picture_boxes, r->picture_box_count, f->view, ndc,
                                           r->reach_boxes);
            int n = warp_samples((const float(*)[2][3])r->reach_boxes, boxes, f->view, f->width, f->height, ndc,
                                 r->reach_hits);
            r->sample_count = warp_samples_lit(r->reach_hits, n, light, r->samples, &r->grazing_count);
        }
        r->sample_light = l;
    }
    return (map_samples){r->samples, r->sample_count, r->grazing_count, r->reach_sampled};
}

/* The fitted map m at another size: only the texel's world size follows
 * (as 1 / size); the matrices and the depth range do not depend on it. */
static void map_resize(map_light *m, int size) {
    m->texel_scale *= (float)m->size / (float)size;
    m->size = size;
}

const char *map_kind_name(map_kind kind) {
    static const char *const names[] = {[MAP_2D] = "2D", [MAP_CUBE] = "cube", [MAP_ARRAY] = "array"};
    return names[kind];
}

void map_size_text(const map_settings *settings, const map_light *m, char *out, size_t size) {
    snprintf(out, size, "%s map %s%s%d", map_kind_name(m->kind), m->tiled ? "in atlas tiles " : "",
             settings->map_size == 0 ? "auto: " : "", m->size);
}

unsigned map_target(map_kind kind) {
    static const GLenum targets[] = {
        [MAP_2D] = GL_TEXTURE_2D, [MAP_CUBE] = GL_TEXTURE_CUBE_MAP, [MAP_ARRAY] = GL_TEXTURE_2D_ARRAY};
    return targets[kind];
}

/* The texture image a 2D or cube map's layer is stored in. */
unsigned map_layer_image(map_kind kind, int layer) {
    return kind == MAP_CUBE ? GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)layer : GL_TEXTURE_2D;
}

void map_texture_filter(unsigned target, int filter) {
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(target, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(target, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(target, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
}

/* Makes a layer of a map the depth pass's depth attachment: an array's
 * layer by its index, a 2D map's or a cube face's by its image. */
static void map_attach_layer(const map_light *m, int layer) {
    if (m->kind == MAP_ARRAY)
        glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, m->texture.id, 0, layer);
    else
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, map_layer_image(m->kind, layer), m->texture.id,
                               0);
}

/* ---- storage ---- */

/* Storage of a map's kind, size and layers for the bound texture of
 * `target`: depth of that format and type, or RGBA16F colour. */
static void map_texture_storage(const map_light *m, GLenum target, GLenum format, GLenum pixels, GLenum type) {
    if (m->kind == MAP_ARRAY)
        glTexImage3D(target, 0, (GLint)format, m->size, m->size, m->layer_count, 0, pixels, type, NULL);
    else
        for (int layer = 0; layer < m->layer_count; layer++)
            glTexImage2D(map_layer_image(m->kind, layer), 0, (GLint)format, m->size, m->size, 0, pixels, type, NULL);
}

void map_depth_format(int depth, unsigned *format, unsigned *type) {
    *format = depth == MAP_DEPTH_24 ? GL_DEPTH_COMPONENT24 : GL_DEPTH_COMPONENT32F;
    *type = depth == MAP_DEPTH_24 ? GL_UNSIGNED_INT : GL_FLOAT;
}

void map_depth_sampling(unsigned target, int filter) {
    map_texture_filter(target, filter == MAP_FILTER_NONE ? GL_NEAREST : GL_LINEAR);
    glTexParameteri(target, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTexParameteri(target, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
}

/* m's texture is the one its fit and the settings ask for. */
static bool map_texture_fits(const map_light *m, const map_settings *settings, bool transmits) {
    const map_texture *t = &m->texture;
    return t->id && t->kind == m->kind && t->size == m->size && t->layer_count == m->layer_count &&
           t->depth == settings->depth && t->filter == (int)map_filter_in_use(settings) &&
           (t->transmittance != 0) == transmits;
}

/* (Re)creates a map's depth texture when its kind, size, layer count,
 * format or filter changed, or whether it `transmits` (a transmittance
 * map beside it: map.h, "Translucent casters"): compare mode on, so that
 * every read is a depth test; outside the map reads are clamped (the
 * shader calls them lit). A moment filter's textures and the
 * transmittance map are made with it. What the layers held is gone:
 * a cache checks map_texture_fits before (map_cache_current). */
static void map_prepare_texture(map_light *m, const map_settings *settings, bool transmits) {
    map_texture *t = &m->texture;
    int depth = settings->depth, filter = map_filter_in_use(settings);
    if (map_texture_fits(m, settings, transmits))
        return;
    glDeleteTextures(1, &t->id);
    glDeleteTextures(1, &t->bounds);
    glDeleteTextures(1, &t->transmittance);
    t->bounds = t->transmittance = 0;
    t->bounds_current = false;
    GLenum target = map_target(m->kind), format, type;
    map_depth_format(depth, &format, &type);
    glGenTextures(1, &t->id);
    glBindTexture(target, t->id);
    map_texture_storage(m, target, format, GL_DEPTH_COMPONENT, type);
    map_depth_sampling(target, filter);
    if (transmits) {
        glGenTextures(1, &t->transmittance);
        glBindTexture(target, t->transmittance);
        map_texture_storage(m, target, GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT);
        map_texture_filter(target, GL_NEAREST);
    }
    t->kind = m->kind;
    t->size = m->size;
    t->layer_count = m->layer_count;
    t->depth = depth;
    t->filter = filter;
    map_moments_prepare(m, map_filter_moments(filter));
}

/* ---- the depth pass ---- */

/* m's depth pass clamps the depth itself: a cube's, where the GL has no
 * depth clamp (r->depth_clamped, r->transmit[1]). */
static bool map_clamp_emulated(const map_renderer *r, const map_light *m) {
    return m->kind == MAP_CUBE && r->depth_clamped.solid.id;
}

/* The depth pass's programs for m. */
static const render_programs *map_depth_programs(const map_renderer *r, const map_light *m) {
    return map_clamp_emulated(r, m) ? &r->depth_clamped : &r->depth;
}

/* The polygon offset's uniforms of program `id`: the slope's alone but
 * where it clamps the depth itself (MAP_DEPTH_CLAMP_EMULATED). */
static map_offset_uniforms map_offset_uniforms_of(unsigned id, bool emulated) {
    map_offset_uniforms u = {shader_uniform(id, "u_slope_factor"), -1, -1};
    if (emulated) {
        u.offset_units = shader_uniform(id, "u_offset_units");
        u.depth_float = shader_uniform(id, "u_depth_float");
    }
    return u;
}

/* Sets program `id`'s polygon offset: glPolygonOffset's factor and units,
 * in a depth of `settings`' format. */
static void map_offset_set(unsigned id, const map_offset_uniforms *u, float factor, float units,
                           const map_settings *settings) {
    glUseProgram(id);
    glUniform1f(u->slope_factor, factor);
    glUniform1f(u->offset_units, units);
    glUniform1i(u->depth_float, settings->depth == MAP_DEPTH_32F);
}

/* The depth pass's state: its framebuffer, viewport, slope bias, program. */
static void map_depth_begin(map_renderer *r, const map_settings *settings, const map_light *m) {
    glBindFramebuffer(GL_FRAMEBUFFER, r->framebuffer);
    glViewport(0, 0, m->size, m->size);
    glDepthFunc(GL_LESS); /* after the camera's pre-pass */
    glDepthMask(GL_TRUE);
    /* The slope-scaled bias (glPolygonOffset's factor and units; both 0
     * with it off), for the GL's offset and the programs that redo it. */
    float factor = settings->no_slope_bias ? 0 : map_setting(settings->slope_factor, MAP_SLOPE_FACTOR);
    float units = settings->no_slope_bias ? 0 : map_setting(settings->slope_units, MAP_SLOPE_UNITS);
    if (settings->no_slope_bias) {
        glDisable(GL_POLYGON_OFFSET_FILL);
    } else {
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(factor, units);
    }
    bool emulated = map_clamp_emulated(r, m);
    for (int pass = 0; emulated && pass < render_programs_passes(&r->depth_clamped); pass++)
        map_offset_set(render_programs_pass(&r->depth_clamped, pass)->id, &r->clamped_offset[pass], factor, units,
                       settings);
    if (m->texture.transmittance)
        map_offset_set(r->transmit[emulated].id, &r->transmit_offset[emulated], factor, units, settings);
    /* A cube's near plane keeps the depth's precision (MAP_NEAR_RATIO of
     * its far plane), and a caster nearer the light than that (a lamp
     * inside a wall's box) lies before every receiver of its face: it is
     * drawn at the near depth, not clipped: by depth clamp, or where the
     * GL has none by r->depth_clamped. */
    depth_clamp(m->kind == MAP_CUBE);
}

/* After a map's layers: the state map_depth_begin set, off. */
static void map_depth_end(void) {
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_SCISSOR_TEST);
    depth_clamp(false);
}

/* Layer `layer`'s transmittance map (map.h, "Translucent casters"), after
 * its depths: the translucent casters of `casters` (NULL: every one) over
 * a clear of 1, tested against those depths without writing them;
 * r->transmit_failed where the GL cannot draw into it (said once). Leaves
 * r->framebuffer bound, depth writes on and blending off. */
static void map_transmit_layer(map_renderer *r, const render_scene *gpu, const map_light *m, int layer,
                               const bool *casters) {
    const scene *s = gpu->scene;
    GLenum image = m->kind == MAP_ARRAY ? GL_TEXTURE_2D_ARRAY : map_layer_image(m->kind, layer);
    glBindFramebuffer(GL_FRAMEBUFFER, r->transmit_framebuffer);
    map_attach_layer(m, layer);
    bool ok = map_color_target(&r->transmit_framebuffer, m->texture.transmittance, image, layer,
                               "translucent casters cast their whole shadow");
    if (ok) {
        static const float clear[4] = {1, 1, 1, 1};
        glClearBufferfv(GL_COLOR, 0, clear);
        glDepthMask(GL_FALSE);
        glEnable(GL_BLEND);
        glBlendFuncSeparate(GL_ZERO, GL_SRC_COLOR, GL_ONE, GL_ONE);
        glBlendEquationSeparate(GL_FUNC_ADD, GL_MIN);
        const render_program *p = &r->transmit[map_clamp_emulated(r, m)];
        glUseProgram(p->id);
        glUniformMatrix4fv(p->view_projection, 1, GL_FALSE, (const float *)m->layer_view_projection[layer]);
        for (int i = 0; i < s->object_count; i++)
            if (s->objects[i].translucent && s->objects[i].casts && (!casters || casters[i]))
                render_draw_object(gpu, p, i);
        glDisable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glDepthMask(GL_TRUE);
    }
    r->transmit_failed = !ok;
    glBindFramebuffer(GL_FRAMEBUFFER, r->framebuffer);
}

/* One layer from its matrix, with the casters of `casters` (NULL: every
 * caster), and with `receivers` the receivers that cast nothing too: a
 * moment map's texel must hold the receiver's own depth among those of
 * its box (where it holds the empty far plane instead, the bounds read
 * the receiver as nearer than most of it: lit). Not the frame's in_view:
 * the light sees casters the camera does not. */
static void map_depth_layer(map_renderer *r, const render_scene *gpu, const map_light *m, int layer,
                            const bool *casters, bool receivers) {
    const scene *s = gpu->scene;
    bool transmits = m->texture.transmittance != 0;
    if (m->tiled) { /* its tile of the atlas alone: viewport, and the clear's scissor */
        const map_tile *t = &m->tiles[layer];
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, r->atlas_texture, 0);
        glViewport(t->x, t->y, t->size, t->size);
        glScissor(t->x, t->y, t->size, t->size);
        glEnable(GL_SCISSOR_TEST);
    } else {
        map_attach_layer(m, layer);
    }
    glClear(GL_DEPTH_BUFFER_BIT);
    /* The solid objects, then the cut-out ones through their program
     * (render_programs); translucent casters into the transmittance map
     * instead, where the map has one. */
    const render_programs *programs = map_depth_programs(r, m);
    for (int pass = 0; pass < render_programs_passes(programs); pass++) {
        const render_program *p = render_programs_pass(programs, pass);
        glUseProgram(p->id);
        glUniformMatrix4fv(p->view_projection, 1, GL_FALSE, (const float *)m->layer_view_projection[layer]);
        for (int i = 0; i < s->object_count; i++) {
            const scene_object *o = &s->objects[i];
            if (render_programs_draws(programs, pass, o) && !(transmits && o->translucent && o->casts) &&
                (o->casts ? !casters || casters[i] : receivers && o->receives))
                render_draw_object(gpu, p, i);
        }
    }
    if (transmits)
        map_transmit_layer(r, gpu, m, layer, casters);
}

/* The frame's maps take transmittance maps (map.h, "Translucent
 * casters"): the scene has translucent casters and the GL draws into
 * them. */
static bool map_scene_transmits(const map_renderer *r) { return r->transmit[0].id && !r->transmit_failed; }

/* Light l's texture unit `unit` is one this GL has; else said once per
 * light (bit l of *said): it lacks the unit for the light's `what`, and
 * does `instead`. */
static bool map_light_unit(const map_renderer *r, int unit, int l, scene_light_set *said, const char *what,
                           const char *instead) {
    if (unit < r->texture_units)
        return true;
    if (!(*said & SCENE_LIGHT_BIT(l)))
        fprintf(stderr, "shadow maps: light %d: this GL has too few texture units for its %s: %s\n", l, what,
                instead);
    *said |= SCENE_LIGHT_BIT(l);
    return false;
}

/* Light l's map takes one: the frame's do and the GL has its unit. */
static bool map_light_transmits(map_renderer *r, int l) {
    return map_scene_transmits(r) &&
           map_light_unit(r, MAP_TRANSMIT_UNITS + RENDER_LIGHT_SLOT(l), l, &r->transmit_warned, "transmittance map",
                          "translucent casters cast their whole shadow");
}

void map_render_depth(map_renderer *r, const map_settings *settings, const render_scene *gpu, map_light *m) {
    map_prepare_texture(m, settings, map_scene_transmits(r));
    map_depth_begin(r, settings, m);
    map_moments moments = map_filter_moments(map_filter_in_use(settings));
    for (int layer = 0; layer < m->layer_count; layer++)
        map_depth_layer(r, gpu, m, layer, m->casters, moments != MAP_MOMENTS_NONE);
    map_depth_end();
    for (int layer = 0; moments != MAP_MOMENTS_NONE && layer < m->layer_count; layer++)
        map_moments_blur(r, m, moments, layer);
}

/* ---- caster culling and the cache ---- */

static void map_forget(map_cache *c) { memset(c->valid, 0, sizeof c->valid); }

/* The layer holds what it would be rendered with now. */
static bool map_layer_cached(const map_renderer *r, const map_cache *c, const map_light *m, int layer) {
    if (!c->valid[layer] || c->blur_texels[layer] != m->blur_texels[layer] ||
        memcmp(c->layer_view_projection[layer], m->layer_view_projection[layer], sizeof(mat4)) != 0)
        return false;
    for (int i = 0; i < r->object_count; i++)
        if (r->needed[layer][i] && !c->drawn[layer][i])
            return false;
    return true;
}

/* What light l's map would be drawn with now, but its casters (a tiled
 * map's faces' tiles: map_tile_place). */
static map_depth_key map_depth_key_of(const map_renderer *r, const map_light *m, const map_settings *st) {
    return (map_depth_key){.texture = m->tiled ? r->atlas_texture : m->texture.id,
                           .size = m->tiled ? 0 : m->size,
                           .depth = st->depth,
                           .filter = map_filter_in_use(st),
                           .no_slope_bias = st->no_slope_bias,
                           .slope_factor = st->slope_factor,
                           .slope_units = st->slope_units};
}

/* What light l's cache holds is still worth reading: neither the scene
 * nor the light changed, and its texture and depth key are those it
 * would be drawn with now. */
static bool map_cache_current(map_renderer *r, const map_settings *st, const technique_frame *f, int l) {
    const map_light *m = &r->maps[l];
    map_depth_key key = map_depth_key_of(r, m, st);
    bool storage = m->tiled ? r->atlas_texture != 0 : map_texture_fits(m, st, map_light_transmits(r, l));
    return !f->changed.scene && !(f->changed.lights & SCENE_LIGHT_BIT(l)) && storage &&
           memcmp(&key, &r->caches[l].key, sizeof key) == 0;
}

/* Light l's whole map is in its cache as it would be drawn now (its
 * casters planned): nothing to draw. */
static bool map_whole_in_cache(map_renderer *r, const map_settings *st, const technique_frame *f, int l) {
    if (!map_cache_current(r, st, f, l))
        return false;
    const map_light *m = &r->maps[l];
    for (int layer = 0; layer < m->layer_count; layer++)
        if ((m->tiled && !map_tile_held(r, m, l, layer)) ||
            (!r->unread[l][layer] && !map_layer_cached(r, &r->caches[l], m, layer)))
            return false;
    return true;
}

/* A tiled map m of light l's faces in their tiles (map_atlas_plan placed
 * them where it made the atlas this frame): a face in a new tile holds
 * nothing cached. Where the atlas has no room for a face, or no memory
 * for its tiles, the map is a cube of its own this frame (its largest
 * face's size), counted in r->tiles_refused. */
static void map_place_tiles(map_renderer *r, map_light *m, int l) {
    bool ready = !m->tiled || r->atlas_texture;
    for (int face = 0; m->tiled && face < MAP_CUBE_FACES; face++) {
        map_tile_placed placed = ready ? map_tile_place(r, m, l, face) : MAP_TILE_NO_ROOM;
        r->caches[l].valid[face] = r->caches[l].valid[face] && placed == MAP_TILE_KEPT;
        if (placed == MAP_TILE_NO_ROOM) {
            map_tiles_release(r, l);
            map_forget(&r->caches[l]);
            m->tiled = false;
            r->tiles_refused++;
        }
    }
}

/* Light l's layers its cache cannot give, with the casters planned in
 * r->needed; its map is then whole, drawn with its fit. */
static void map_draw_layers(map_renderer *r, const map_settings *st, const technique_frame *f, int l) {
    map_light *m = &r->maps[l];
    map_cache *c = &r->caches[l];
    if (!map_cache_current(r, st, f, l))
        map_forget(c);
    map_place_tiles(r, m, l);
    if (!m->tiled)
        map_prepare_texture(m, st, map_light_transmits(r, l));
    c->key = map_depth_key_of(r, m, st);
    map_moments moments = map_filter_moments(map_filter_in_use(st));
    bool begun = false, rendered[MAP_MAX_LAYERS] = {false};
    for (int layer = 0; layer < m->layer_count; layer++) {
        if (map_layer_cached(r, c, m, layer)) {
            f->skips->counts->layers_reused++;
            continue;
        }
        if (r->unread[l][layer]) {
            f->skips->counts->layers_unread++;
            continue;
        }
        if (!begun)
            map_depth_begin(r, st, m);
        begun = true;
        map_depth_layer(r, f->gpu, m, layer, r->needed[layer], moments != MAP_MOMENTS_NONE);
        f->skips->counts->layers_rendered++;
        rendered[layer] = c->valid[layer] = true;
        m->texture.bounds_current = false;
        c->blur_texels[layer] = m->blur_texels[layer];
        glm_mat4_copy(m->layer_view_projection[layer], c->layer_view_projection[layer]);
        memcpy(c->drawn[layer], r->needed[layer], (size_t)r->object_count * sizeof(bool));
    }
    map_depth_end();
    if ((l == 0 || m->tiled) && begun) /* the map inset's reduction is of the layers before */
        r->inset_current = false;
    for (int layer = 0; moments != MAP_MOMENTS_NONE && layer < m->layer_count; layer++)
        if (rendered[layer])
            map_moments_blur(r, m, moments, layer);
    r->drawn_fit[l] = *m;
    r->drawn_light[l] = f->gpu->scene->lights[l];
    r->drawn[l] = true;
    r->waited[l] = 0;
}

/* Light l's planned casters of each layer in r->waiting_needed. */
static bool *map_waiting_needed(const map_renderer *r, int l, int layer) {
    return r->waiting_needed + ((size_t)l * MAP_MAX_LAYERS + (size_t)layer) * (size_t)r->object_count;
}

/* The fitted lights' own maps within the GL's largest texture and,
 * together, MAP_MEMORY_TEXELS (map.h, "Memory"): the largest above
 * MAP_AUTO_MIN_SIZE (the first of equals), which is also the widest,
 * halved until they fit. */
static void map_bound_memory(map_renderer *r, int light_count) {
    for (;;) {
        double texels = 0;
        int largest = -1;
        for (int l = 0; l < light_count; l++) {
            const map_light *m = &r->maps[l];
            if (!r->fitted[l] || m->tiled)
                continue;
            texels += (double)m->layer_count * m->size * m->size;
            if (m->size > MAP_AUTO_MIN_SIZE && (largest < 0 || m->size > r->maps[largest].size))
                largest = l;
        }
        if (largest < 0 || (texels <= MAP_MEMORY_TEXELS && r->maps[largest].size <= r->max_texture_size))
            return;
        map_resize(&r->maps[largest], r->maps[largest].size / 2);
        r->maps_halved++;
    }
}

void map_draw_depth(map_renderer *r, const map_settings *st, const technique_frame *f, int l) {
    if (!r->fitted[l])
        return;
    if (!r->atlas_planned)
        map_bound_memory(r, f->gpu->scene->light_count);
    /* Every light fitted: the atlas sized for all their tiles, before any
     * is drawn. One made again holds nothing: its lights' caches are
     * gone, and each is drawn this frame as a light's first is, whatever
     * the budget. */
    if (!r->atlas_planned && map_atlas_plan(r, st, f->gpu->scene->light_count))
        for (int k = 0; k < f->gpu->scene->light_count; k++)
            if (r->fitted[k] && r->maps[k].tiled) {
                map_forget(&r->caches[k]);
                r->drawn[k] = false;
            }
    r->atlas_planned = true;
    map_plan_casters(r, st, f, l);
    if (st->shadow_budget && r->drawn[l] && !map_whole_in_cache(r, st, f, l)) {
        /* Its turn is map_shade's to give (map_budget_draw). */
        for (int layer = 0; layer < r->maps[l].layer_count; layer++)
            memcpy(map_waiting_needed(r, l, layer), r->needed[layer], (size_t)r->object_count * sizeof(bool));
        r->waiting |= SCENE_LIGHT_BIT(l);
        return;
    }
    map_draw_layers(r, st, f, l);
}

/* The waiting lights' maps, within the budget (map.h, "Budget"): those
 * that waited the most frames drawn, the others back to their maps as
 * drawn. */
static void map_budget_draw(map_renderer *r, const map_settings *st, const technique_frame *f) {
    for (int drawn = 0; r->waiting; drawn++) {
        int next = -1;
        for (int l = 0; l < f->gpu->scene->light_count; l++)
            if ((r->waiting & SCENE_LIGHT_BIT(l)) && (next < 0 || r->waited[l] > r->waited[next]))
                next = l;
        r->waiting &= ~SCENE_LIGHT_BIT(next);
        map_light *m = &r->maps[next];
        if (drawn < st->shadow_budget) {
            for (int layer = 0; layer < m->layer_count; layer++)
                memcpy(r->needed[layer], map_waiting_needed(r, next, layer), (size_t)r->object_count * sizeof(bool));
            map_draw_layers(r, st, f, next);
            continue;
        }
        map_texture texture = m->texture;
        *m = r->drawn_fit[next];
        m->texture = texture;
        render_scene_light_as(f->gpu, next, &r->drawn_light[next]);
        r->waited[next]++;
        f->skips->counts->maps_kept++;
    }
}

/* ---- programs ---- */

/* A uniform of a program: its name, and where its location is kept. */
typedef struct map_uniform {
    int *location;
    const char *name;
} map_uniform;

static void map_find_uniforms(unsigned program, const map_uniform *uniforms, size_t count) {
    for (size_t i = 0; i < count; i++)
        *uniforms[i].location = shader_uniform(program, uniforms[i].name);
}

bool map_color_target(unsigned *framebuffer, unsigned texture, unsigned image, int layer, const char *instead) {
    if (!*framebuffer)
        glGenFramebuffers(1, framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, *framebuffer);
    if (image == GL_TEXTURE_2D_ARRAY)
        glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, texture, 0, layer);
    else
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, image, texture, 0);
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status == GL_FRAMEBUFFER_COMPLETE)
        return true;
    fprintf(stderr, "shadow maps: this GL cannot draw into a float colour texture (framebuffer status 0x%x): %s\n",
            status, instead);
    return false;
}

void map_texel_units(unsigned program) {
    /* A unit per sampler type: two types may not share one. */
    glUniform1i(shader_uniform(program, "u_source_2d"), MAP_2D);
    glUniform1i(shader_uniform(program, "u_source_cube"), MAP_CUBE);
    glUniform1i(shader_uniform(program, "u_source_array"), MAP_ARRAY);
}

/* The names of the per-light defines: light i's kind, its map's texel
 * kind, its transmittance map's slot. */
static char map_kind_names[SHADER_PASS_LIGHTS][sizeof "MAP_LIGHT_KIND_" + 3];
static char map_texel_kind_names[SHADER_PASS_LIGHTS][sizeof "MAP_TEXEL_KIND_" + 3];
static char map_transmit_slot_names[SHADER_PASS_LIGHTS][sizeof "MAP_TRANSMIT_SLOT_" + 3];

/* Light l's element of the transmittance samplers: the transmitting
 * lights' in their order, so that each kind's array holds only as many
 * as light (a WebGL program counts every element against its units);
 * a light that reads none names the first, unread. */
static int map_transmit_slot(unsigned transmit_lights, int l) {
    return transmit_lights >> l & 1u ? __builtin_popcount(transmit_lights & ((1u << l) - 1)) : 0;
}

/* Light `light`'s field of a key's kinds or texel_kinds. */
static unsigned map_light_bits(int light, unsigned value) { return value << (MAP_LIGHT_KIND_BITS * light); }

static unsigned map_light_field(unsigned bits, int light) {
    return (bits >> (MAP_LIGHT_KIND_BITS * light)) & ((1u << MAP_LIGHT_KIND_BITS) - 1);
}

/* Light i's uniform `name`[i], or -1 where its kind has none. */
static int map_light_uniform(unsigned program, const char *name, int light) {
    char element[64];
    snprintf(element, sizeof element, "%s[%d]", name, light);
    return shader_uniform(program, element);
}

/* The camera program of key k. */
static bool map_camera_program_load(map_camera_program *p, const map_camera_key *k) {
    const shader_define pass[] = {
        SHADER_DEFINE(MAP_LIGHT_OFF),
        SHADER_DEFINE(MAP_LIGHT_UNSHADOWED),
        SHADER_DEFINE(MAP_LIGHT_2D),
        SHADER_DEFINE(MAP_LIGHT_CUBE),
        SHADER_DEFINE(MAP_LIGHT_ARRAY),
        SHADER_DEFINE(MAP_LIGHT_TILES),
        SHADER_DEFINE(MAP_CUBE_FACES),
        {"MAP_PASS_SHAPE", (int)k->shape},
        {"MAP_PASS_KERNEL", (int)k->kernel},
        {"MAP_PASS_EARLY_OUT", (int)k->early_out},
        {"MAP_PASS_RECEIVER_PLANE", (int)k->receiver_plane},
        {"MAP_PASS_SHOW_TEXELS", (int)k->show_texels},
        {"MAP_PASS_SHOW_TEXEL_SIZE", (int)k->show_texel_size},
        {"MAP_PASS_SHOW_CASCADES", (int)k->show_cascades},
        {"MAP_PASS_SHOW_PENUMBRA", (int)k->show_penumbra},
        {"MAP_PASS_RAYS", (int)k->rays},
        {"MAP_PASS_SHOW_UNSURE", (int)k->show_unsure},
        {"MAP_PASS_RAY_COUNTS", (int)k->ray_counts},
        {"MAP_PASS_MARK_RAYS", (int)k->mark_rays},
        {"MAP_PASS_BOUNDS_LIGHTS", (int)k->bounds_lights},
        {"MAP_PASS_SOFT_LIGHTS", (int)k->soft_lights},
        {"MAP_PASS_MOMENTS", (int)k->moments},
        {"MAP_PASS_MOMENT_LIGHTS", (int)k->moment_lights},
        {"MAP_PASS_TRANSMIT_LIGHTS", (int)k->transmit_lights},
        {"MAP_PASS_TRANSMIT_SLOTS", k->transmit_lights ? __builtin_popcount(k->transmit_lights) : 1},
        {"BVH_RECORDS", (int)k->ray_records},
        {"BVH_TEXTURE_BUFFER", (int)k->ray_buffer},
    };
    /* This key's defines, then the enums every camera program compares
     * with, then each light's three, then the list's end ({NULL}, zeroed). */
    enum { PASS = sizeof pass / sizeof *pass, COMMON = sizeof map_defines / sizeof *map_defines - 1 };
    shader_define defines[PASS + COMMON + 3 * SHADER_PASS_LIGHTS + 1] = {{NULL, 0}};
    memcpy(defines, pass, sizeof pass);
    memcpy(defines + PASS, map_defines, COMMON * sizeof *defines);
    shader_define *light_defines = defines + PASS + COMMON;
    for (int l = 0; l < SHADER_PASS_LIGHTS; l++) {
        snprintf(map_kind_names[l], sizeof map_kind_names[l], "MAP_LIGHT_KIND_%d", l);
        snprintf(map_texel_kind_names[l], sizeof map_texel_kind_names[l], "MAP_TEXEL_KIND_%d", l);
        snprintf(map_transmit_slot_names[l], sizeof map_transmit_slot_names[l], "MAP_TRANSMIT_SLOT_%d", l);
        light_defines[3 * l] = (shader_define){map_kind_names[l], (int)map_light_field(k->kinds, l)};
        light_defines[3 * l + 1] = (shader_define){map_texel_kind_names[l], (int)map_light_field(k->texel_kinds, l)};
        light_defines[3 * l + 2] =
            (shader_define){map_transmit_slot_names[l], map_transmit_slot(k->transmit_lights, l)};
    }
    static const char *const files[] = {"lit.vert", "map.frag"};
    if (!render_program_load(&p->program, files, 2, defines))
        return false;
    unsigned id = p->program.id;
    const map_uniform uniforms[] = {
        {&p->constant_bias, "u_constant_bias"},
        {&p->normal_offset, "u_normal_offset"},
        {&p->depth_bias, "u_depth_bias"},
        {&p->closed_outside, "u_closed_outside"},
        {&p->view_depth, "u_view_depth"},
        {&p->cascade_blend, "u_cascade_blend"},
        {&p->ray_samples, "u_ray_samples"},
        {&p->frame, "u_frame"},
        {&p->eye, "u_eye"},
        {&p->exact_surface, "u_exact_surface"},
        {&p->translucent, "u_translucent"},
        {&p->ambient, "u_ambient"},
    };
    map_find_uniforms(id, uniforms, sizeof uniforms / sizeof *uniforms);
    /* Each sampler on a unit, those of lights without a map too: an
     * array's elements below the last one used stay active, and two types
     * on one unit (unit 0, the default) would fail every draw. Light l's
     * own on unit l (a soft light's depths, a moment light's moments, on
     * MAP_DEPTH_UNITS + l),
     * the others idle (MAP_IDLE_UNITS, the comparisons' types, then
     * the depths'). */
    glUseProgram(id);
    for (int l = 0; l < SHADER_PASS_LIGHTS; l++) {
        for (int t = 0; t < MAP_SAMPLER_TYPES; t++) {
            bool own = map_light_field(k->kinds, l) == (unsigned)map_samplers[t].kind;
            bool soft = own && ((k->soft_lights | k->moment_lights) >> l & 1u);
            glUniform1i(map_light_uniform(id, map_samplers[t].name, l), own ? l : MAP_IDLE_UNITS + t);
            glUniform1i(map_light_uniform(id, map_samplers[t].depths, l),
                        soft ? MAP_DEPTH_UNITS + l : MAP_IDLE_UNITS + MAP_SAMPLER_TYPES + t);
            if (k->transmit_lights >> l & 1u)
                glUniform1i(
                    map_light_uniform(id, map_samplers[t].transmittances, map_transmit_slot(k->transmit_lights, l)),
                    own ? MAP_TRANSMIT_UNITS + l : MAP_IDLE_UNITS + MAP_SAMPLER_TYPES + t);
        }
        /* Its depth bounds (a 2D sampler for every kind), idle with the 2D
         * maps' depths. */
        glUniform1i(map_light_uniform(id, "u_bounds", l), k->bounds_lights >> l & 1u
                                                              ? MAP_DEPTH_UNITS + l
                                                              : MAP_IDLE_UNITS + MAP_SAMPLER_TYPES + MAP_SAMPLER_2D);
        p->lights[l].cascade_count = map_light_uniform(id, "u_cascade_count", l);
        p->lights[l].cascade_scale = map_light_uniform(id, "u_cascade_scale", l * MAP_MAX_ARRAY_LAYERS);
        p->lights[l].cascade_offset = map_light_uniform(id, "u_cascade_offset", l * MAP_MAX_ARRAY_LAYERS);
        p->lights[l].map_size = map_light_uniform(id, "u_map_size", l);
        p->lights[l].light_matrix = map_light_uniform(id, "u_light_matrix", l);
        p->lights[l].light_inverse = map_light_uniform(id, "u_light_inverse", l);
        p->lights[l].light_size = map_light_uniform(id, "u_light_size", l);
        p->lights[l].light_area = map_light_uniform(id, "u_light_area", l);
        p->lights[l].texel_scale = map_light_uniform(id, "u_texel_scale", l);
        p->lights[l].near_plane = map_light_uniform(id, "u_near", l);
        p->lights[l].far_plane = map_light_uniform(id, "u_far", l);
        p->lights[l].tiles = map_light_uniform(id, "u_tiles", l * MAP_CUBE_FACES);
    }
    /* The atlas on the first tiled light's own unit (its map's, which it
     * has not). */
    for (int l = 0; l < SHADER_PASS_LIGHTS; l++)
        if (map_light_field(k->kinds, l) == MAP_LIGHT_TILES) {
            glUniform1i(shader_uniform_optional(id, "u_atlas.depths"), l);
            break;
        }
    p->atlas_size = shader_uniform_optional(id, "u_atlas_size");
    glUniform3fv(shader_uniform(id, "u_cascade_colors"), MAP_MAX_ARRAY_LAYERS, map_cascade_colors[0]);
    glUniform1i(shader_uniform_optional(id, "u_bvh"), MAP_RAY_UNIT);
    return true;
}

/* The camera program of key k: one compiled before, or compiled now in
 * place of the oldest. NULL where it does not compile (said on stderr,
 * once: the failure is kept). */
static const map_camera_program *map_camera_program_for(map_renderer *r, const map_camera_key *k) {
    for (int i = 0; i < r->camera_count; i++)
        if (memcmp(&r->camera[i].key, k, sizeof *k) == 0)
            return r->camera[i].program.id ? &r->camera[i] : NULL;
    int slot = r->camera_oldest;
    if (r->camera_count < MAP_CAMERA_PROGRAMS)
        slot = r->camera_count++;
    else
        r->camera_oldest = (slot + 1) % MAP_CAMERA_PROGRAMS;
    map_camera_program *p = &r->camera[slot];
    render_program_destroy(&p->program);
    *p = (map_camera_program){.key = *k};
    return map_camera_program_load(p, k) ? p : NULL;
}

/* The key of the settings' kernel and overlays; no light set yet. */
static map_camera_key map_settings_key(const map_settings *st) {
    map_filter filter = map_filter_in_use(st);
    return (map_camera_key){
        .shape = (unsigned)map_kernels[filter].shape,
        .kernel = (unsigned)map_kernels[filter].size,
        .early_out = !st->no_early_out && st->rays == MAP_RAYS_OFF,
        .receiver_plane = st->kernel_depth == MAP_KERNEL_DEPTH_RECEIVER_PLANE,
        .show_texels = st->overlay == MAP_OVERLAY_ALL || st->overlay == MAP_OVERLAY_TEXELS,
        .show_texel_size = st->overlay == MAP_OVERLAY_TEXEL_SIZE,
        .show_cascades = MAP_SHOWS_CASCADES(st),
        .show_penumbra = st->overlay == MAP_OVERLAY_PENUMBRA,
        .moments = map_filter_moments(filter),
        .rays = (unsigned)st->rays,
        .show_unsure = MAP_SHOWS_UNSURE(st),
    };
}

/* The camera pass's kind of light for a map's kind. */
static map_light_kind map_light_kind_of(map_kind kind) {
    static const map_light_kind kinds[] = {
        [MAP_2D] = MAP_LIGHT_2D, [MAP_CUBE] = MAP_LIGHT_CUBE, [MAP_ARRAY] = MAP_LIGHT_ARRAY};
    return kinds[kind];
}

/* A light with a map, of any kind. */
static bool map_light_mapped(unsigned kind) {
    return kind == MAP_LIGHT_2D || kind == MAP_LIGHT_CUBE || kind == MAP_LIGHT_ARRAY || kind == MAP_LIGHT_TILES;
}

/* The light in slot `slot` of key k, of that kind and texel kind. */
static void map_key_light(map_camera_key *k, int slot, map_light_kind kind, map_texel_kind texel) {
    k->kinds |= map_light_bits(slot, kind);
    k->texel_kinds |= map_light_bits(slot, texel);
}

/* Every light of the scene with its uniform map (a cube for a point light,
 * a perspective map for a spot, an orthographic one for the sun), with
 * the settings' kernel: the first frame's program, most often. */
static map_camera_key map_scene_key(const map_renderer *r, const scene *s, const map_settings *st) {
    map_camera_key k = map_settings_key(st);
    for (int l = 0; l < s->light_count && l < SHADER_PASS_LIGHTS; l++) {
        const scene_light *light = &s->lights[l];
        map_kind kind = light->type == SCENE_LIGHT_POINT ? MAP_CUBE : MAP_2D;
        map_key_light(&k, l, map_tiles_wanted(r, st, light, kind) ? MAP_LIGHT_TILES : map_light_kind_of(kind),
                      light->type == SCENE_LIGHT_DIRECTIONAL ? MAP_TEXEL_ORTHOGRAPHIC : MAP_TEXEL_PERSPECTIVE);
        k.moment_lights |= k.moments != MAP_MOMENTS_NONE ? 1u << l : 0;
    }
    return k;
}

static bool map_overlay_programs_load(map_renderer *r) {
    static const char *const lines_files[] = {"overlay.vert", "overlay_lines.frag"};
    static const char *const inset_files[] = {"overlay.vert", "overlay_map.frag"};
    static const char *const legend_files[] = {"overlay.vert", "overlay_heat_legend.frag"};
    static const shader_define inset_defines[] = {
        SHADER_DEFINE(MAP_CUBE), SHADER_DEFINE(MAP_INSET_FAR_GREY_PERCENT), {NULL, 0}};
    if (!render_program_load(&r->lines.program, lines_files, 2, NULL) ||
        !render_program_load(&r->inset.program, inset_files, 2, inset_defines) ||
        !render_program_load(&r->legend.program, legend_files, 2, map_defines))
        return false;
    r->lines.color = shader_uniform(r->lines.program.id, "u_color");
    r->legend.log2_range = shader_uniform(r->legend.program.id, "u_log2_range");
    map_inset_program *p = &r->inset;
    const map_uniform uniforms[] = {
        {&p->reduced, "u_reduced"}, {&p->kind, "u_kind"},     {&p->layer, "u_layer"},
        {&p->size, "u_size"},       {&p->factor, "u_factor"}, {&p->orthographic, "u_orthographic"},
        {&p->near_plane, "u_near"}, {&p->far_plane, "u_far"}, {&p->held, "u_held"},
    };
    map_find_uniforms(p->program.id, uniforms, sizeof uniforms / sizeof *uniforms);
    return true;
}

/* The caster sets: each light's drawn per layer, then one light's needed
 * per layer; and the receivers' boxes. */
static bool map_alloc_sets(map_renderer *r, int object_count) {
    size_t n = (size_t)object_count, layers = MAP_MAX_LAYERS;
    bool *sets = calloc((SCENE_MAX_LIGHTS + 1) * layers * n + 1, sizeof(bool));
    r->receiver_boxes = calloc(n + 1, sizeof *r->receiver_boxes);
    r->picture_boxes = calloc(n + 1, sizeof *r->picture_boxes);
    r->reach_boxes = calloc(n + 1, sizeof *r->reach_boxes);
    r->unmapped = calloc(n + 1, sizeof *r->unmapped);
    r->waiting_needed = calloc(SCENE_MAX_LIGHTS * layers * n + 1, sizeof *r->waiting_needed);
    r->closed = calloc(n + 1, sizeof *r->closed);
    r->masks = malloc(layers * sizeof *r->masks);
    r->object_count = object_count;
    r->needed[0] = sets; /* what destroy frees */
    if (!sets || !r->receiver_boxes || !r->picture_boxes || !r->reach_boxes || !r->unmapped || !r->waiting_needed ||
        !r->closed || !r->masks) {
        fprintf(stderr, "shadow maps: out of memory for %d objects' caster sets\n", object_count);
        return false;
    }
    for (size_t layer = 0; layer < layers; layer++) {
        r->needed[layer] = sets + layer * n;
        for (int l = 0; l < SCENE_MAX_LIGHTS; l++)
            r->caches[l].drawn[layer] = sets + ((size_t)(l + 1) * layers + layer) * n;
    }
    return true;
}

/* r->closed: which casters are closed meshes (their welded edge table,
 * as the volumes weigh them). */
static bool map_find_closed(map_renderer *r, const scene *s) {
    for (int i = 0; i < s->object_count; i++) {
        mesh_edges e;
        if (!s->objects[i].casts)
            continue;
        if (!mesh_edges_build_welded(&s->objects[i].mesh, &e))
            return false;
        r->closed[i] = e.closed;
        mesh_edges_free(&e);
    }
    return true;
}

/* The GL objects of a zeroed r; false after printing why. */
static bool map_init(map_renderer *r, const map_settings *settings, const render_scene *gpu) {
    map_camera_key scene_key = map_scene_key(r, gpu->scene, settings);
    static const char *const depth_files[] = {"shadow_depth.vert", "depth.frag"};
    if (!map_alloc_sets(r, gpu->scene->object_count) || !map_find_closed(r, gpu->scene) ||
        !render_programs_load(&r->depth, gpu->scene, depth_files, 2, NULL) ||
        /* The scene's own combination now, so that a shader that does not
         * compile fails init; the others as frames need them. */
        !map_camera_program_for(r, &scene_key) || !map_overlay_programs_load(r))
        return false;
    /* The light's view: a shadow's shape, cast from both sides (render.h). */
    r->depth.solid.both_sides = r->depth.cut_out.both_sides = true;
    static const shader_define clamp_defines[] = {{"MAP_DEPTH_CLAMP_EMULATED", 1}, {NULL, 0}};
    bool emulate_clamp = !context_current_features()->depth_clamp;
    if (emulate_clamp) {
        if (!render_programs_load(&r->depth_clamped, gpu->scene, depth_files, 2, clamp_defines))
            return false;
        r->depth_clamped.solid.both_sides = r->depth_clamped.cut_out.both_sides = true;
        for (int pass = 0; pass < render_programs_passes(&r->depth_clamped); pass++)
            r->clamped_offset[pass] = map_offset_uniforms_of(render_programs_pass(&r->depth_clamped, pass)->id, true);
    }
    /* The transmittance maps' programs, for a scene that needs them: the
     * plain one, and where the GL lacks depth clamp a cube's. */
    static const char *const transmit_files[] = {"shadow_depth.vert", "transmittance.frag"};
    if (scene_translucent_casters(gpu->scene) > 0) {
        for (int emulated = 0; emulated <= emulate_clamp; emulated++) {
            render_program *p = &r->transmit[emulated];
            if (!render_program_load(p, transmit_files, 2, emulated ? clamp_defines : NULL))
                return false;
            p->both_sides = true;
            r->transmit_offset[emulated] = map_offset_uniforms_of(p->id, emulated);
        }
        glGenFramebuffers(1, &r->transmit_framebuffer);
    }
    glGenVertexArrays(1, &r->screen_vao);
    glGenVertexArrays(1, &r->overlay_vao);
    glBindVertexArray(r->overlay_vao);
    glGenBuffers(1, &r->overlay_buffer);
    glBindBuffer(GL_ARRAY_BUFFER, r->overlay_buffer);
    glBufferData(GL_ARRAY_BUFFER, MAP_LEGEND_VERTICES * 3 * sizeof(float), NULL, GL_STREAM_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), NULL);
    glBindVertexArray(0);
    /* A soft light's blocker search reads its map's depths as they are. */
    glGenSamplers(1, &r->depth_sampler);
    glSamplerParameteri(r->depth_sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(r->depth_sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glSamplerParameteri(r->depth_sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(r->depth_sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(r->depth_sampler, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(r->depth_sampler, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &r->texture_units);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &r->max_texture_size);
    memset(r->tile_nodes, -1, sizeof r->tile_nodes); /* no light holds a tile */
    glGenFramebuffers(1, &r->framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, r->framebuffer);
    static const GLenum none = GL_NONE;
    glDrawBuffers(1, &none);
    glReadBuffer(GL_NONE);
    /* Kernels that cross a cube face read on into the next face: a switch
     * in desktop GL, always so in ES. */
    if (context_current_features()->desktop_gl)
        glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    return true;
}

map_renderer *map_create(map_settings *settings, const render_scene *gpu) {
    settings->many_lights = render_light_groups(gpu) > 1;
    map_renderer *r = calloc(1, sizeof *r);
    if (!r) {
        fprintf(stderr, "shadow maps: out of memory\n");
        return NULL;
    }
    if (map_init(r, settings, gpu))
        return r;
    map_destroy(r);
    return NULL;
}

const map_light *map_of_light(const map_renderer *r, int l) { return &r->maps[l]; }

void map_trace_with(map_renderer *r, const bvh_gpu *casters) { r->casters = casters; }

void map_destroy(map_renderer *r) {
    if (!r)
        return;
    render_programs_destroy(&r->depth);
    render_programs_destroy(&r->depth_clamped);
    for (int i = 0; i < r->camera_count; i++)
        render_program_destroy(&r->camera[i].program);
    render_program_destroy(&r->lines.program);
    render_program_destroy(&r->inset.program);
    render_program_destroy(&r->legend.program);
    for (int kind = 0; kind <= MAP_ARRAY; kind++)
        render_program_destroy(&r->reduce[kind].program);
    glDeleteTextures(1, &r->inset_texture);
    glDeleteFramebuffers(1, &r->inset_framebuffer);
    glDeleteVertexArrays(1, &r->overlay_vao);
    glDeleteVertexArrays(1, &r->screen_vao);
    glDeleteBuffers(1, &r->overlay_buffer);
    glDeleteFramebuffers(1, &r->framebuffer);
    glDeleteSamplers(1, &r->depth_sampler);
    for (size_t i = 0; i < sizeof r->transmit / sizeof *r->transmit; i++)
        render_program_destroy(&r->transmit[i]);
    glDeleteFramebuffers(1, &r->transmit_framebuffer);
    map_moments_destroy(r);
    map_rays_destroy(r);
    map_bounds_destroy(r);
    for (int l = 0; l < SCENE_MAX_LIGHTS; l++) {
        glDeleteTextures(1, &r->maps[l].texture.id);
        glDeleteTextures(1, &r->maps[l].texture.bounds);
        glDeleteTextures(1, &r->maps[l].texture.transmittance);
        map_moments_prepare(&r->maps[l], MAP_MOMENTS_NONE);
    }
    glDeleteTextures(1, &r->atlas_texture);
    map_atlas_destroy(&r->atlas);
    free(r->needed[0]);
    free(r->receiver_boxes);
    free(r->picture_boxes);
    free(r->reach_boxes);
    free(r->unmapped);
    free(r->waiting_needed);
    free(r->closed);
    free(r->masks);
    free(r);
}

/* ---- the camera pass ---- */

/* Where the eye is inside object i, a closed caster, the lights with a
 * map in group g's key k that are outside it (bit i: slot i), for
 * shaders/map.frag's u_closed_outside: a face that such a light
 * reaches on the eye's side is in the mesh's shadow. Only with the eye
 * inside: from outside, a triangle whose back the eye sees wins the
 * depth test at a few silhouette pixels, and the reference may see the
 * lit front there (long_view_behind and test_psm's low point light would
 * read shadowed there). */
static unsigned map_closed_outside(const map_renderer *r, const technique_frame *f, const map_camera_key *k, int g,
                                   int i) {
    const scene *s = f->gpu->scene;
    const float eye[4] = {f->view->eye[0], f->view->eye[1], f->view->eye[2], 1};
    float object_eye[4];
    if (!r->closed[i])
        return 0;
    mesh_point_to_object(s->objects[i].model, eye, object_eye);
    if (!mesh_point_inside(&s->objects[i].mesh, object_eye))
        return 0;
    unsigned slots = 0;
    for (int slot = 0; slot < SHADER_PASS_LIGHTS; slot++) {
        float light[4], object_light[4];
        if (!map_light_mapped(map_light_field(k->kinds, slot)))
            continue;
        scene_light_homogeneous(&s->lights[RENDER_GROUP_LIGHT(g, slot)], light);
        mesh_point_to_object(s->objects[i].model, light, object_light);
        if (!mesh_point_inside(&s->objects[i].mesh, object_light))
            slots |= 1u << slot;
    }
    return slots;
}

/* Soft light l's map on its slot's depth unit too, read through the
 * depth sampler, and its disc: a radius, or a sun's tangent of its
 * angular radius (degrees in the scene); a 2D map's inverse, for its
 * depths' distances. */
static void map_bind_soft(const map_renderer *r, const map_camera_program *p, const scene *s, int l) {
    const map_light *m = &r->maps[l];
    const scene_light *light = &s->lights[l];
    int slot = RENDER_LIGHT_SLOT(l);
    GLuint unit = MAP_DEPTH_UNITS + (GLuint)slot;
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(map_target(m->kind), m->texture.id);
    glBindSampler(unit, r->depth_sampler);
    glUniform1f(p->lights[slot].light_size,
                light->type == SCENE_LIGHT_DIRECTIONAL ? tanf(glm_rad(light->radius)) : light->radius);
    mat4 inverse;
    glm_mat4_inv((vec4 *)m->layer_view_projection[0], inverse);
    glUniformMatrix4fv(p->lights[slot].light_inverse, 1, GL_FALSE, (const float *)inverse);
    /* The rays' disk: area_light.h's radius and a sun's cap. */
    area_light_frame disk;
    area_light_frame_for(light, (const float[4]){0, 0, 0, 1}, (const float[3]){0, 0, 1}, &disk);
    glUniform2f(p->lights[slot].light_area, disk.radius, disk.cap);
}

/* Tiled map m's faces' tiles for slot `slot` of camera program p. */
static void map_tiles_uniforms(const map_renderer *r, const map_camera_program *p, const map_light *m, int slot) {
    float tiles[MAP_CUBE_FACES][4];
    for (int face = 0; face < MAP_CUBE_FACES; face++) {
        const map_tile *t = &m->tiles[face];
        memcpy(tiles[face], (const float[4]){(float)t->x, (float)t->y, (float)t->size, 0}, sizeof tiles[face]);
    }
    glUniform4fv(p->lights[slot].tiles, MAP_CUBE_FACES, tiles[0]);
    glUniform1f(p->atlas_size, (float)r->atlas.size);
}

/* Key k without the lights of `lights` (slot bits). */
static map_camera_key map_key_without(map_camera_key k, unsigned lights) {
    for (int l = 0; l < SHADER_PASS_LIGHTS; l++) {
        unsigned field = map_light_bits(l, (1u << MAP_LIGHT_KIND_BITS) - 1);
        if (lights >> l & 1u) {
            k.kinds &= ~field;
            k.texel_kinds &= ~field;
        }
    }
    k.soft_lights &= ~lights;
    k.moment_lights &= ~lights;
    k.bounds_lights &= ~lights;
    k.transmit_lights &= ~lights;
    return k;
}

/* Camera program p in use for light group g, with every light of its
 * key's map, matrices and settings. */
static void map_camera_use(map_renderer *r, const map_settings *st, const technique_frame *f,
                           const map_camera_program *p, int g) {
    const map_camera_key *k = &p->key;
    render_bind_light_group(f->gpu, g);
    render_program_use(&p->program, f->view);
    if (k->rays != MAP_RAYS_OFF) {
        bvh_gpu_bind(r->casters, p->program.id, MAP_RAY_UNIT);
        glUniform1i(p->ray_samples, st->ray_samples ? st->ray_samples : MAP_RAY_DEFAULT_SAMPLES);
        glUniform4i(p->frame, r->viewport[0], r->viewport[1], r->viewport[2], r->viewport[3]);
        glUniform3fv(p->eye, 1, f->view->eye);
        render_eye_ray_uniforms(p->program.id, f->view, f->width, f->height);
    }
    glUniform1f(p->constant_bias, st->no_constant_bias ? 0 : map_setting(st->constant_texels, MAP_CONSTANT_TEXELS));
    glUniform1f(p->normal_offset, st->normal_texels);
    glUniform2f(p->depth_bias, st->depth_bias_slope, st->depth_bias_min);
    /* The camera's view depth of a world point: minus its view-space
     * z, as the fit measured the cascades' splits. */
    const mat4 *view = &map_fit_frame(f)->view->view;
    glUniform4f(p->view_depth, -(*view)[0][2], -(*view)[1][2], -(*view)[2][2], -(*view)[3][2]);
    for (int slot = 0; slot < SHADER_PASS_LIGHTS; slot++) {
        if (!map_light_mapped(map_light_field(k->kinds, slot)))
            continue;
        int l = RENDER_GROUP_LIGHT(g, slot);
        const map_light *m = &r->maps[l];
        glActiveTexture(GL_TEXTURE0 + (GLenum)slot);
        glBindTexture(m->tiled ? GL_TEXTURE_2D : map_target(m->kind), m->tiled ? r->atlas_texture : m->texture.id);
        if (m->tiled) /* each face's corner and size, in texels of the atlas */
            map_tiles_uniforms(r, p, m, slot);
        glUniform1f(p->lights[slot].map_size, (float)m->size);
        glUniform1f(p->lights[slot].texel_scale, m->texel_scale);
        glUniform1f(p->lights[slot].near_plane, m->near_plane);
        glUniform1f(p->lights[slot].far_plane, m->far_plane);
        if (k->soft_lights >> slot & 1u)
            map_bind_soft(r, p, f->gpu->scene, l);
        if (k->moment_lights >> slot & 1u) {
            /* Its moments, bilinear (the texture's own filter). */
            glActiveTexture(GL_TEXTURE0 + MAP_DEPTH_UNITS + (GLenum)slot);
            glBindTexture(map_target(m->kind), m->texture.moments);
        }
        if (k->bounds_lights >> slot & 1u) {
            glActiveTexture(GL_TEXTURE0 + MAP_DEPTH_UNITS + (GLenum)slot);
            glBindTexture(GL_TEXTURE_2D, m->texture.bounds);
        }
        if (k->transmit_lights >> slot & 1u) {
            glActiveTexture(GL_TEXTURE0 + MAP_TRANSMIT_UNITS + (GLenum)slot);
            glBindTexture(map_target(m->kind), m->texture.transmittance);
        }
        if (m->kind != MAP_ARRAY) {
            glUniformMatrix4fv(p->lights[slot].light_matrix, 1, GL_FALSE, (const float *)m->layer_view_projection[0]);
            continue;
        }
        /* Layer k's scale and offset, w its slice's far and near ends. */
        float scale[MAP_MAX_ARRAY_LAYERS][4], offset[MAP_MAX_ARRAY_LAYERS][4];
        for (int layer = 0; layer < m->layer_count; layer++) {
            memcpy(scale[layer], m->cascade_scale[layer], sizeof m->cascade_scale[layer]);
            memcpy(offset[layer], m->cascade_offset[layer], sizeof m->cascade_offset[layer]);
            scale[layer][3] = m->cascade_split[layer + 1];
            offset[layer][3] = m->cascade_split[layer];
        }
        glUniformMatrix4fv(p->lights[slot].light_matrix, 1, GL_FALSE, (const float *)m->cascade_view);
        glUniform4fv(p->lights[slot].cascade_scale, m->layer_count, (const float *)scale);
        glUniform4fv(p->lights[slot].cascade_offset, m->layer_count, (const float *)offset);
        glUniform1i(p->lights[slot].cascade_count, m->layer_count);
        glUniform1f(p->cascade_blend, m->cascade_blend);
    }
    glActiveTexture(GL_TEXTURE0);
}

/* The receivers of `objects` through camera program p, in use for light
 * group g: every light of its key by its kind (shadowed where its map
 * lets it through, or unshadowed), and the ambient term of group 0's. */
static void map_draw_receivers(const map_renderer *r, const technique_frame *f, const map_camera_program *p, int g,
                               const bool *objects) {
    const map_camera_key *k = &p->key;
    const scene *s = f->gpu->scene;
    for (int i = 0; i < s->object_count; i++) {
        if (!render_in_mask(objects, i) || !s->objects[i].receives)
            continue;
        glUniform1i(p->closed_outside, (GLint)map_closed_outside(r, f, k, g, i));
        if (k->transmit_lights)
            glUniform1i(p->translucent, s->objects[i].translucent && s->objects[i].casts);
        if (k->rays != MAP_RAYS_OFF)
            glUniform1i(p->exact_surface, !context_current_features()->close_interpolation ||
                                              render_object_huge(f->gpu, i, f->view->eye));
        render_draw_object(f->gpu, &p->program, i);
    }
}

/* Every light on, by its kind in its group's key (keys[g]), and the
 * ambient term, on `objects`' receivers: the one shading pass, with the
 * lights shading_split_lights leaves out shaded each in its own
 * rectangle (shading_split_pass: again with every light, or past one
 * group its own light added). Past one group, each group's part of the
 * one pass after the first adds its lights (render_group_pass_begin;
 * the second targets of the rays' marks and counts add too). False where
 * a program failed (said once on stderr). */
static bool map_shade_receivers(map_renderer *r, const map_settings *st, const technique_frame *f,
                                const map_camera_key *keys, const bool *objects) {
    scene_light_set split = shading_split_lights(f);
    bool blending, ok = true;
    for (int g = 0; g < render_light_groups(f->gpu); g++) {
        render_group_pass_begin(g, &blending);
        if (g > 0 && !render_group_slots(f->skips->lights & ~split, g))
            continue;
        map_camera_key key = map_key_without(keys[g], render_group_slots(split, g));
        const map_camera_program *p = map_camera_program_for(r, &key);
        ok = p != NULL;
        if (!ok)
            break;
        map_camera_use(r, st, f, p, g);
        glUniform1f(p->ambient, g == 0 ? 1.0f : 0.0f);
        map_draw_receivers(r, f, p, g, objects);
    }
    const map_camera_program *used = NULL;
    int used_group = 0;
    for (int l = 0; ok && l < f->gpu->scene->light_count; l++) {
        if (!(split & SCENE_LIGHT_BIT(l)))
            continue;
        int g = RENDER_LIGHT_GROUP(l);
        scene_light_set lights;
        bool ambient;
        const bool *lit = shading_split_pass(f, l, &lights, &ambient);
        map_camera_key key = map_key_without(keys[g], ~render_group_slots(lights, g));
        const map_camera_program *p = map_camera_program_for(r, &key);
        ok = p != NULL;
        if (!ok)
            break;
        if (p != used || g != used_group)
            map_camera_use(r, st, f, p, g);
        used = p;
        used_group = g;
        glUniform1f(p->ambient, ambient ? 1.0f : 0.0f);
        map_draw_receivers(r, f, p, g, lit);
    }
    render_group_pass_end(blending);
    glDisable(GL_SCISSOR_TEST);
    return ok;
}

/* The lights of group g's key k whose marking pass reads their depth
 * bounds for their kernel (map_bounds_update), as slot bits: a 2D or cube
 * map's, filtered by a kernel of more than one tap, hard (neither soft
 * nor by its moments), where the GL has its depth unit (the bounds take
 * it). */
static unsigned map_bounds_lights(map_renderer *r, const map_camera_key *k, int g) {
    unsigned slots = 0;
    for (int slot = 0; slot < SHADER_PASS_LIGHTS; slot++) {
        bool hard = !((k->soft_lights | k->moment_lights) >> slot & 1u);
        unsigned kind = map_light_field(k->kinds, slot);
        if ((kind == MAP_LIGHT_2D || kind == MAP_LIGHT_CUBE) && hard && k->shape != MAP_KERNEL_SINGLE &&
            MAP_DEPTH_UNITS + slot < r->texture_units && map_bounds_update(r, &r->maps[RENDER_GROUP_LIGHT(g, slot)]))
            slots |= 1u << slot;
    }
    return slots;
}

/* The camera pass by each group's key: the receivers (where rays decide
 * only the unsure pixels, marked first, then traced alone: map.h,
 * "Rays"), then the objects that take no shadows, every light
 * unshadowed as in the reference. Only receivers read maps (the caster
 * culling is for them too). The marks are the pixel's, not a light's:
 * past one group, where each light is shaded in a pass of its own
 * (shading_split_pass), a pixel one light marked would be shaded again,
 * kernel and all, by every light whose pass reaches it, so the receivers
 * are shaded in one pass there. */
static void map_shade_lights(map_renderer *r, const map_settings *st, const technique_frame *f,
                             map_camera_key *keys) {
    const bool *objects = shading_all_begin(f);
    int groups = render_light_groups(f->gpu);
    bool mapped = true, rays = keys[0].rays != MAP_RAYS_OFF;
    if (keys[0].rays == MAP_RAYS_UNSURE && f->skips->marked_pass && groups == 1 && map_ray_marks_begin(r)) {
        f->skips->counts->marked_passes++;
        map_camera_key marking[RENDER_LIGHT_GROUPS];
        for (int g = 0; g < groups; g++) {
            marking[g] = keys[g];
            marking[g].mark_rays = true;
            marking[g].bounds_lights = map_bounds_lights(r, &keys[g], g);
        }
        mapped = map_shade_receivers(r, st, f, marking, objects);
        map_ray_marks_end(r, f->counters);
    }
    bool counts = f->counters && rays && map_ray_counts_begin(r);
    for (int g = 0; g < groups; g++)
        keys[g].ray_counts = counts;
    mapped = mapped && map_shade_receivers(r, st, f, keys, objects);
    glDisable(GL_STENCIL_TEST);
    if (counts)
        map_ray_counts_end(r);
    unsigned soft = 0;
    for (int g = 0; g < groups; g++)
        soft |= keys[g].soft_lights;
    for (int slot = 0; slot < SHADER_PASS_LIGHTS; slot++)
        if (soft >> slot & 1u)
            glBindSampler(MAP_DEPTH_UNITS + (GLuint)slot, 0);
    /* Without a program (said once on stderr) receivers are lit too. */
    bool *unmapped = r->unmapped;
    for (int i = 0; i < f->gpu->scene->object_count; i++)
        unmapped[i] = render_in_mask(objects, i) && (!mapped || !f->gpu->scene->objects[i].receives);
    render_unshadowed(f->gpu, f->view, unmapped, f->skips->lights);
}

/* ---- the frame ---- */

const technique_frame *map_fit_frame(const technique_frame *f) { return f->fit ? f->fit : f; }

/* Light l is drawn soft: an area light with --soft pcss, whose depth unit
 * the GL has. An area light drawn hard is said once on stderr. */
static bool map_soft_unit(map_renderer *r, const map_settings *settings, const scene_light *light, int l) {
    bool soft = map_light_soft(settings, light);
    if (soft && MAP_DEPTH_UNITS + RENDER_LIGHT_SLOT(l) < r->texture_units)
        return true;
    bool moments = map_filter_moments(map_filter_in_use(settings)) != MAP_MOMENTS_NONE;
    if (light->radius > 0 && !moments && !(r->soft_warned & SCENE_LIGHT_BIT(l)))
        fprintf(stderr, "shadow maps: light %d is an area light (radius %g%s), drawn hard from its centre: %s\n", l,
                light->radius, scene_light_radius_unit(light),
                soft ? "this GL has too few texture units for its soft filter" : "--soft off");
    r->soft_warned |= light->radius > 0 && !moments ? SCENE_LIGHT_BIT(l) : 0;
    return false;
}

/* Light l reads its moment map: a moment filter whose blur runs (else
 * said once by the blur), and its depth unit (the moments' unit) the GL
 * has; else it takes one bilinear test of its depths, said once on
 * stderr. */
static bool map_moment_unit(map_renderer *r, const map_settings *settings, int l) {
    map_filter filter = map_filter_in_use(settings);
    if (map_filter_moments(filter) == MAP_MOMENTS_NONE || r->blur_failed)
        return false;
    char what[64];
    snprintf(what, sizeof what, "moment map (--filter %s)", map_filters[filter]);
    return map_light_unit(r, MAP_DEPTH_UNITS + RENDER_LIGHT_SLOT(l), l, &r->moments_warned, what,
                          "one bilinear depth test instead");
}

/* Light l's moment blur per layer (map_moments_blur_texels), a
 * moment filter's: an auto-sized map (not an array's) halves while an
 * area light's would be wider than MAP_MOMENTS_MAX_BLUR_TEXELS (a
 * texel's width is its share of the penumbra: the blur's cost grows with
 * its width, and a blurred map needs no more texels than its blur shows),
 * then any wider one is clamped to it. */
static void map_moments_fit(const scene *s, int l, map_light *m, bool auto_size) {
    float widest = 0, blur[MAP_MAX_LAYERS];
    map_moments_blur_texels(s, l, m, blur);
    for (int layer = 0; layer < m->layer_count; layer++)
        widest = fmaxf(widest, blur[layer]);
    int size = m->size;
    /* A texel's world size goes as 1 / size: so does the blur in texels. */
    while (auto_size && m->kind != MAP_ARRAY && s->lights[l].radius > 0 && widest > MAP_MOMENTS_MAX_BLUR_TEXELS &&
           size > MAP_AUTO_MIN_SIZE) {
        size /= 2;
        widest /= 2;
    }
    if (size != m->size) {
        map_resize(m, size);
        map_moments_blur_texels(s, l, m, blur);
    }
    for (int layer = 0; layer < m->layer_count; layer++)
        m->blur_texels[layer] = fminf(blur[layer], MAP_MOMENTS_MAX_BLUR_TEXELS);
}

void map_begin(map_renderer *r, const technique_frame *f) {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &r->target_framebuffer);
    glGetIntegerv(GL_VIEWPORT, r->viewport);
    memset(r->fitted, 0, sizeof r->fitted);
    r->atlas_planned = false;
    r->tiles_short = r->tiles_refused = r->tiles_halved = r->maps_halved = 0;
    r->hit_count = r->sample_light = -1; /* nothing measured yet this frame */
    /* The camera's depth first: the shading pass tests against it (each
     * visible pixel filtered once), and the maps cull the casters it
     * shows hidden (technique_see). */
    render_depth_prepass(f->gpu, f->view, f->skips->in_view);
    technique_see(f);
    depth_use_standard(f->view); /* the maps' depth is the lights', never the camera's */
}

void map_describe_filter(const map_settings *settings, char *out, size_t size) {
    size_t n = strlen(out);
    if (map_auto_unfiltered(settings) && n < size)
        snprintf(out + n, size - n, ", filter: %s (%s)", map_filters[MAP_FILTER_NONE],
                 map_shows_acne(settings) ? "shows acne" : "a bias is off");
    else if (settings->filter == MAP_FILTER_AUTO && map_filter_in_use(settings) == MAP_FILTER_HW && n < size)
        snprintf(out + n, size - n, ", filter: %s (many lights)", map_filters[MAP_FILTER_HW]);
}

bool map_described_light(const map_renderer *r, int *l, char *out, size_t size) {
    for (*l = 0; *l < SCENE_MAX_LIGHTS; ++*l)
        if (r->fitted[*l])
            return true;
    snprintf(out, size, "no light has a map this frame");
    return false;
}

void map_describe_storage(const map_renderer *r, int l, char *out, size_t size) {
    size_t n = strlen(out);
    const map_light *m = &r->maps[l];
    if (m->tiled && n < size)
        n += (size_t)snprintf(out + n, size - n, ", atlas %d: %.0f %% held", r->atlas.size,
                              100.0 * (double)map_atlas_used(&r->atlas) / ((double)r->atlas.size * r->atlas.size));
    if (r->tiles_halved && n < size)
        n += (size_t)snprintf(out + n, size - n, ", tiles halved %d times to fit", r->tiles_halved);
    if (r->maps_halved && n < size)
        n += (size_t)snprintf(out + n, size - n, ", maps halved %d times to fit the memory", r->maps_halved);
    if ((r->tiles_short || r->tiles_refused) && n < size)
        n += (size_t)snprintf(out + n, size - n, ", atlas full: %d faces smaller, %d lights in cube maps",
                              r->tiles_short, r->tiles_refused);
    if (m->texture.transmittance && n < size)
        snprintf(out + n, size - n, ", transmittance map: coloured shadows");
}

bool map_fit_light(map_renderer *r, const map_settings *settings, const technique_frame *f, int l,
                   map_fit_function fit) {
    const scene *s = f->gpu->scene;
    const technique_frame *fit_frame = map_fit_frame(f);
    if (fit_frame->skips->receiver_count == 0 || !skips_light_on(f->skips, l))
        return false;
    map_light *m = &r->maps[l];
    int size = map_settings_size(settings);
    m->size = size ? size : MAP_AUTO_MAX_SIZE;
    r->fitted[l] = fit(fit_frame, l, m, fit_frame->skips->receivers, fit_frame->skips->receiver_count);
    if (!r->fitted[l])
        return false;
    m->tiled = map_tiles_wanted(r, settings, &s->lights[l], m->kind);
    if (!m->tiled)
        map_tiles_release(r, l);
    for (int face = 0; m->tiled && face < MAP_CUBE_FACES; face++)
        m->tiles[face] = (map_tile){.size = m->size};
    if (!size && m->kind != MAP_ARRAY) {
        map_samples samples = map_light_samples(r, fit_frame, l);
        map_auto_rule rule = map_auto_rule_for(r, settings, s, &s->lights[l]);
        map_resize(m, m->tiled ? map_tiles_size(r, m, &s->lights[l], samples, rule)
                               : map_auto_size(m, &s->lights[l], samples, rule));
    }
    if (map_filter_moments(map_filter_in_use(settings)) != MAP_MOMENTS_NONE)
        map_moments_fit(s, l, m, !size);
    return true;
}

void map_shade(map_renderer *r, const map_settings *settings, const technique_frame *f) {
    const scene *s = f->gpu->scene;
    map_budget_draw(r, settings, f);
    /* A light without a map this frame may change unseen before the next. */
    for (int l = 0; l < SCENE_MAX_LIGHTS; l++)
        if (!r->fitted[l]) {
            map_tiles_release(r, l);
            map_forget(&r->caches[l]);
            r->drawn[l] = false;
            r->waited[l] = 0;
        }
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)r->target_framebuffer);
    glViewport(r->viewport[0], r->viewport[1], r->viewport[2], r->viewport[3]);
    depth_use_camera(f->view);
    /* Each light group's key, its lights in their slots. */
    map_camera_key keys[RENDER_LIGHT_GROUPS];
    keys[0] = map_settings_key(settings);
    if (!r->casters)
        keys[0].rays = MAP_RAYS_OFF;
    keys[0].ray_records = keys[0].rays != MAP_RAYS_OFF && r->casters->record_count > 0;
    keys[0].ray_buffer = keys[0].rays != MAP_RAYS_OFF && r->casters->buffer != 0;
    for (int g = 1; g < render_light_groups(f->gpu); g++)
        keys[g] = keys[0];
    for (int l = 0; l < s->light_count; l++) {
        map_camera_key *key = &keys[RENDER_LIGHT_GROUP(l)];
        int slot = RENDER_LIGHT_SLOT(l);
        bool fitted = r->fitted[l];
        if (fitted && map_soft_unit(r, settings, &s->lights[l], l))
            key->soft_lights |= 1u << slot;
        if (fitted && map_moment_unit(r, settings, l))
            key->moment_lights |= 1u << slot;
        if (fitted && r->maps[l].texture.transmittance)
            key->transmit_lights |= 1u << slot;
        if (fitted)
            map_key_light(key, slot, r->maps[l].tiled ? MAP_LIGHT_TILES : map_light_kind_of(r->maps[l].kind),
                          r->maps[l].texel_kind);
        else if (skips_light_on(f->skips, l)) /* nothing visible receives: no map needed, nothing shadowed */
            key->kinds |= map_light_bits(slot, MAP_LIGHT_UNSHADOWED);
    }
    if (f->skips->lights)
        map_shade_lights(r, settings, f, keys);
    else
        shading_ambient(f);
}
