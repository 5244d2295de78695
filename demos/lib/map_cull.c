/* map: which casters a layer needs (see map.h, "Caster
 * culling"). Pure math on the scene: no GL. */
#include <math.h>
#include <string.h>

#include "map_internal.h"

/* The farthest Poisson tap, in units of the disc's scale (map.glsl). */
#define MAP_POISSON_RADIUS 1.234f
/* Bilinear taps read the 2x2 texels whose centres lie within a texel of
 * the tap; a nearest tap reads the one within half a texel. */
#define MAP_BILINEAR_TEXELS 1.0f
#define MAP_NEAREST_TEXELS 0.5f
/* Rounding between C's projection and the GPU's, in texels. */
#define MAP_SAFETY_TEXELS 1.0f
/* A cube map's tap offsets lie across the point's direction, not in its
 * face: on a face they stretch by up to sqrt(2) (and a tap across an edge
 * is measured on the next face), so they count twice. */
#define MAP_CUBE_TAP_STRETCH 2.0f
/* A caster this far in NDC depth beyond the deepest receiver still counts
 * (24-bit storage and rasterization round the stored depth). */
#define MAP_DEPTH_TOLERANCE 1e-4f
/* Clip w at or below this fraction of a point's clip coordinates: the
 * point is at the map's centre of projection, where it sees everything. */
#define MAP_MIN_W FRUSTUM_FLOAT_TOLERANCE

bool map_auto_unfiltered(const map_settings *settings) {
    return settings->filter == MAP_FILTER_AUTO && (settings->no_constant_bias || settings->no_slope_bias);
}

bool map_shows_acne(const map_settings *settings) { return map_auto_unfiltered(settings) && settings->no_slope_bias; }

map_filter map_filter_in_use(const map_settings *settings) {
    if (settings->filter != MAP_FILTER_AUTO)
        return (map_filter)settings->filter;
    if (map_auto_unfiltered(settings))
        return MAP_FILTER_NONE;
    return settings->many_lights && settings->rays != MAP_RAYS_UNSURE ? MAP_FILTER_HW : MAP_FILTER_POISSON;
}

bool map_light_soft(const map_settings *settings, const scene_light *light) {
    return light->radius > 0 && settings->soft == MAP_SOFT_PCSS && !map_auto_unfiltered(settings) &&
           map_filter_moments(map_filter_in_use(settings)) == MAP_MOMENTS_NONE;
}

const char *map_area_light_text(const map_settings *settings, const scene_light *light) {
    if (map_filter_moments(map_filter_in_use(settings)) != MAP_MOMENTS_NONE)
        return "soft by its moment filter, whatever --soft says: the moment map blurred to its casters' mean "
               "penumbra, one width (no contact hardening)";
    if (map_light_soft(settings, light))
        return "soft: pcss, a blocker search then a filter of the penumbra's width";
    if (map_shows_acne(settings))
        return "hard, from its centre: the slope bias is off, and --filter auto shows acne";
    return map_auto_unfiltered(settings) ? "hard, from its centre: a bias is off, and --filter auto is none"
                                         : "hard, from its centre: --soft off";
}

float map_read_reach(const map_settings *settings, map_kind kind, bool area) {
    float offset = 0, footprint = MAP_BILINEAR_TEXELS; /* how far taps lie from the point; what each reads */
    scene_light light = {.radius = area ? 1.0f : 0.0f};
    bool soft = map_light_soft(settings, &light);
    /* A soft light's discs (the search's and the filter's) reach at most
     * this far, whatever the filter. */
    map_filter filter = map_filter_in_use(settings);
    switch (soft ? MAP_FILTER_HW : filter) {
    case MAP_FILTER_NONE: footprint = MAP_NEAREST_TEXELS; break;
    case MAP_FILTER_HW: break;
    case MAP_FILTER_PCF3:
    case MAP_FILTER_PCF5:
    case MAP_FILTER_PCF7:
        offset = (float)((filter - MAP_FILTER_PCF3) + 1); /* N / 2 for N = 3, 5, 7 */
        break;
    /* A tent N reads the texels whose squares its radius N / 2 overlaps:
     * their centres lie within (N + 1) / 2 texels of the point, as pcfN's
     * (N / 2 to its farthest tap, a texel more to the centres it reads). Its
     * taps lie nearer than pcfN's, each between a pair of those centres. On
     * a cube they are a point's on a texel corner, nearer still. */
    case MAP_FILTER_TENT3: offset = 1; break;
    case MAP_FILTER_TENT5: offset = 2; break;
    /* Auto is never in use (it stands for poisson or none): the wider. */
    case MAP_FILTER_AUTO:
    case MAP_FILTER_POISSON: offset = MAP_POISSON_RADIUS * MAP_POISSON_SCALE_TEXELS / 2; break;
    /* A moment map's texel holds its box's depths: one bilinear read
     * reaches the box's radius beyond its footprint (a cube's box stays in
     * its face; the stretch is a bound all the same). */
    case MAP_FILTER_VSM:
    case MAP_FILTER_EVSM2:
    case MAP_FILTER_EVSM4:
    case MAP_FILTER_MSM: offset = area ? MAP_MOMENTS_MAX_BLUR_TEXELS : MAP_MOMENTS_HARD_BLUR_TEXELS; break;
    }
    if (soft)
        offset = MAP_SOFT_MAX_TEXELS;
    if (kind == MAP_CUBE)
        offset *= MAP_CUBE_TAP_STRETCH;
    return offset + footprint + MAP_SAFETY_TEXELS;
}

/* The reach in NDC. */
static float map_read_margin(const map_read_setup *s) { return s->reach * 2 / (float)s->size; }

static void map_clip_point(const mat4 layer, const float p[3], vec4 out) {
    glm_mat4_mulv((vec4 *)layer, (vec4){p[0], p[1], p[2], 1}, out);
}

/* Adds one point a receiver may read the layer from; false where it sees
 * the whole layer (at the centre of projection or behind it). */
static bool map_reads_add(map_reads *r, const mat4 layer, const map_read_setup *s, const float p[3]) {
    vec4 c;
    map_clip_point(layer, p, c);
    if (c[3] <= MAP_MIN_W * (fabsf(c[0]) + fabsf(c[1]) + fabsf(c[2])))
        return false;
    for (int k = 0; k < 2; k++) {
        r->lo[k] = fminf(r->lo[k], c[k] / c[3]);
        r->hi[k] = fmaxf(r->hi[k], c[k] / c[3]);
    }
    r->max_depth = fmaxf(r->max_depth, c[2] / c[3]);
    if (s->cube) {
        /* A cube tap compares the depth of its own direction, which runs
         * past the point's by up to the tap's offset: the point pushed
         * away from the light by that much bounds it. */
        float far_point[3], stretch = 1 + map_read_margin(s);
        for (int k = 0; k < 3; k++)
            far_point[k] = s->center[k] + stretch * (p[k] - s->center[k]);
        map_clip_point(layer, far_point, c);
        r->max_depth = fmaxf(r->max_depth, c[2] / c[3]);
    }
    return true;
}

/* A cube's read body pushed away from the light, as map_reads_add
 * pushes a point: the same directions, the depth a tap compares. */
static void map_push_body(const map_read_setup *s, float corners[8][3]) {
    float stretch = 1 + map_read_margin(s);
    for (int c = 0; s->cube && c < 8; c++)
        for (int k = 0; k < 3; k++)
            corners[c][k] = s->center[k] + stretch * (corners[c][k] - s->center[k]);
}

/* Adds the box's part inside the layer's sides widened by `widen`
 * (light_mask_body_part), each of its points as a receiver would read it. */
static bool map_reads_add_box(map_reads *r, const mat4 layer, const map_read_setup *s, float widen, const float lo[3],
                              const float hi[3]) {
    float corners[8][3];
    frustum_box_corners(lo, hi, corners);
    map_push_body(s, corners);
    light_mask_part part = light_mask_body_part(layer, widen, (const float(*)[3])corners);
    if (part.kind == LIGHT_MASK_PART_WHOLE)
        return false;
    if (part.kind == LIGHT_MASK_PART_SOME) {
        for (int k = 0; k < 2; k++) {
            r->lo[k] = fminf(r->lo[k], part.lo[k]);
            r->hi[k] = fmaxf(r->hi[k], part.hi[k]);
        }
        r->max_depth = fmaxf(r->max_depth, part.deepest);
    }
    return true;
}

static void map_reads_start(map_reads *r) {
    *r = (map_reads){.lo = {INFINITY, INFINITY}, .hi = {-INFINITY, -INFINITY}, .max_depth = -INFINITY};
}

static void map_reads_whole(map_reads *r) { *r = (map_reads){.lo = {-1, -1}, .hi = {1, 1}, .max_depth = INFINITY}; }

void map_layer_reads(const mat4 layer, const map_read_setup *s, const float (*points)[3], int point_count,
                     const float (*boxes)[2][3], int box_count, map_reads *out) {
    float margin = map_read_margin(s);
    /* Two bounds of where receivers read, each whole: the visible
     * receivers' points (the view's part of their boxes) and the surfaces
     * of their boxes within the light's reach and the layer. The reads lie
     * in both. */
    map_reads by_points, by_boxes;
    map_reads_start(&by_points);
    if (!points)
        map_reads_whole(&by_points);
    for (int i = 0; points && i < point_count; i++)
        if (!map_reads_add(&by_points, layer, s, points[i])) {
            map_reads_whole(&by_points);
            break;
        }
    /* A cube's taps read on across its edges: a point beside the face reads it. */
    float widen = s->cube ? margin : 0;
    map_reads_start(&by_boxes);
    for (int i = 0; i < box_count; i++)
        if (!map_reads_add_box(&by_boxes, layer, s, widen, boxes[i][0], boxes[i][1])) {
            map_reads_whole(&by_boxes);
            break;
        }
    map_reads_start(out);
    for (int k = 0; k < 2; k++) {
        out->lo[k] = fmaxf(fmaxf(by_points.lo[k], by_boxes.lo[k]) - margin, -1);
        out->hi[k] = fminf(fminf(by_points.hi[k], by_boxes.hi[k]) + margin, 1);
    }
    out->max_depth = s->any_depth ? INFINITY : fminf(by_points.max_depth, by_boxes.max_depth);
    out->empty = !(out->lo[0] <= out->hi[0] && out->lo[1] <= out->hi[1]);
    out->near_drawn = s->cube;
}

bool map_caster_read(const map_reads *reads, const mat4 layer, const vec3 lo, const vec3 hi) {
    if (reads->empty ||
        (reads->near_drawn ? frustum_box_outside_sides_far(layer, lo, hi) : frustum_box_outside(layer, lo, hi)))
        return false;
    float corners[8][3];
    frustum_box_corners(lo, hi, corners);
    light_mask_part part = light_mask_body_part(layer, 0, (const float(*)[3])corners);
    if (part.kind != LIGHT_MASK_PART_SOME)
        return part.kind == LIGHT_MASK_PART_WHOLE; /* around or behind the centre of projection */
    return part.lo[0] <= reads->hi[0] && part.hi[0] >= reads->lo[0] && part.lo[1] <= reads->hi[1] &&
           part.hi[1] >= reads->lo[1] && part.nearest <= reads->max_depth + MAP_DEPTH_TOLERANCE;
}

int map_light_receivers(const technique_frame *f, int light, float (*boxes)[2][3]) {
    const scene *s = f->gpu->scene;
    const scene_light *l = &s->lights[light];
    int n = 0;
    for (int i = 0; i < s->object_count; i++) {
        vec3 lo, hi;
        if (!s->objects[i].receives || !f->gpu->in_frustum[i]) /* the view's test, whatever the skips */
            continue;
        scene_object_world_bounds(&s->objects[i], lo, hi);
        /* Beyond its range a light adds exactly 0 (lighting.glsl): what is there reads no map. */
        if (!scene_light_clip_to_range(l, lo, hi))
            continue;
        glm_vec3_copy(lo, boxes[n][0]);
        glm_vec3_copy(hi, boxes[n][1]);
        n++;
    }
    return n;
}

/* ---- the plan of a light's depth pass ---- */

/* The mask of where the visible pixels read the layer of light l
 * (light_mask.h): each slab the light reaches (seen->lights; a slab it
 * cannot reach holds no pixel that reads its map: the filter is skipped
 * where the light adds exactly 0) grown by the kernel's reach, a cube's
 * pushed away from the light as map_reads_add pushes a point. */
static void map_layer_mask(light_mask *mask, const mat4 layer, const map_read_setup *s, const visible *seen, int l) {
    light_mask_start(mask, layer, map_read_margin(s), s->any_depth, false);
    for (int i = 0; i < seen->count; i++) {
        if (!(seen->lights[i] & SCENE_LIGHT_BIT(l)))
            continue;
        float slab[8][3];
        memcpy(slab, seen->slabs[i], sizeof slab);
        map_push_body(s, slab);
        light_mask_add(mask, (const float(*)[3])slab, NULL);
    }
}

/* Light l's map culls its casters (see map.h, "Caster culling"). */
static bool map_culls(const map_settings *st, const technique_frame *f, int l) {
    bool inset =
        l == 0 && (st->overlay == MAP_OVERLAY_ALL || st->overlay == MAP_OVERLAY_MAP || MAP_SHOWS_CASCADES(st));
    return f->skips->cull_casters && !inset && st->normal_texels == 0;
}

void map_plan_casters(map_renderer *r, const map_settings *st, const technique_frame *f, int l) {
    const scene *s = f->gpu->scene;
    const map_light *m = &r->maps[l];
    bool cull = map_culls(st, f, l);
    /* A soft light's taps follow the receiver's plane, as receiver-plane
     * taps do; a moment map's texel holds every depth of its box, a
     * caster's behind the receivers too. */
    bool soft = map_light_soft(st, &s->lights[l]);
    bool moments = map_filter_moments(map_filter_in_use(st)) != MAP_MOMENTS_NONE;
    map_read_setup setup = {.reach = map_read_reach(st, m->kind, s->lights[l].radius > 0),
                            .size = m->size,
                            .cube = m->kind == MAP_CUBE,
                            .any_depth = soft || moments || st->kernel_depth == MAP_KERNEL_DEPTH_RECEIVER_PLANE};
    glm_vec3_copy((float *)s->lights[l].position, setup.center);
    map_reads reads[MAP_MAX_LAYERS];
    int box_count = cull ? map_light_receivers(f, l, r->receiver_boxes) : 0;
    /* A full list may have left receivers out: then only the boxes bound the reads. */
    const float(*points)[3] = f->skips->receiver_count < SKIPS_MAX_RECEIVER_POINTS ? f->skips->receivers : NULL;
    for (int layer = 0; cull && layer < m->layer_count; layer++)
        map_layer_reads(m->layer_view_projection[layer], &setup, points, f->skips->receiver_count,
                        (const float(*)[2][3])r->receiver_boxes, box_count, &reads[layer]);
    const visible *seen = cull ? skips_seen_pixels(f->skips) : NULL;
    /* A layer no receiver reads needs no caster: no mask either. Nor is
     * it drawn, nor one whose mask no visible pixel reaches (the mask's
     * bodies cross its sides by the kernel's reach, as taps do), but
     * under a budget: a map kept past it is read whole, wherever the
     * camera has turned since it was drawn. */
    for (int layer = 0; layer < m->layer_count; layer++) {
        bool masked = seen && !reads[layer].empty;
        if (masked)
            map_layer_mask(&r->masks[layer], m->layer_view_projection[layer], &setup, seen, l);
        r->unread[l][layer] = cull && !st->shadow_budget && (reads[layer].empty || (masked && r->masks[layer].empty));
    }
    for (int i = 0; i < s->object_count; i++) {
        bool candidate = s->objects[i].casts && (!m->casters || m->casters[i]), drawn = false;
        vec3 lo = GLM_VEC3_ZERO_INIT, hi = GLM_VEC3_ZERO_INIT;
        if (cull && candidate)
            scene_object_world_bounds(&s->objects[i], lo, hi);
        bool read = false; /* by the receivers' bounds, seen or not */
        for (int layer = 0; layer < m->layer_count; layer++) {
            bool layer_read =
                candidate && (!cull || map_caster_read(&reads[layer], m->layer_view_projection[layer], lo, hi));
            read = read || layer_read;
            r->needed[layer][i] = layer_read && (!seen || light_mask_box_read(&r->masks[layer], lo, hi));
            drawn = drawn || r->needed[layer][i];
        }
        if (candidate && drawn)
            f->skips->counts->casters_drawn[l]++;
        else if (candidate)
            f->skips->counts->casters_culled[l]++;
        f->skips->counts->casters_hidden[l] += read && !drawn;
    }
}
