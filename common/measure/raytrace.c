/* raytrace: see raytrace.h for what is computed; this file says how.
 *
 * Shadow-ray offset. A hit point is rounded to float twice: Embree finds it
 * on the triangle to within a few ulps of the triangle's coordinates, and
 * interpolating the vertices rounds again. Both errors scale with the
 * magnitude of the coordinates (ulp(x) <= 2^-23 |x| ~ 1.2e-7 |x|), which the
 * diagonal D of the box holding the scene and the world origin bounds. A
 * shadow ray therefore starts eps = RAYTRACE_EPSILON * D (1e-5 D: about 80
 * ulps of the largest coordinate) off the surface along the face normal on
 * the light's side, so it cannot hit its own triangle, and stops eps short
 * of the light, so a light on a surface is not shadowed by it. A fixed
 * epsilon would be too small for a large scene (acne) and too large for a
 * small one (light leaking through thin walls); the offset lies along the
 * normal, not the ray, so it stays eps off the surface at grazing angles.
 * In the standard scenes eps is 2e-4 to 4e-4 world units. */
#include "raytrace.h"

#include <embree3/rtcore.h>
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"

#define RAYTRACE_PI 3.14159265358979323846f

/* What a light needs per shaded point, computed once. */
typedef struct raytrace_light {
    const scene_light *light;
    vec4 position;              /* scene_light_homogeneous: w 0 directional */
    float radiance[3];          /* colour times intensity */
    float cos_outer, cos_inner; /* spot */
    float cap;                  /* directional area light: 1 - cos(angular radius) */
} raytrace_light;

typedef struct raytrace_object {
    const float *vertices; /* world positions, 3 floats each, in Embree's buffer */
    mat3 normal_matrix;    /* scene_object_normal_matrix, as the raster side uses */
} raytrace_object;

typedef struct raytrace_tracer {
    const scene *scene;
    RTCDevice device;
    RTCScene rtc;
    raytrace_object *objects;
    raytrace_light lights[SCENE_MAX_LIGHTS];
    float epsilon;
    int light_samples;
    int light_index;
    int width, height;
    vec3 eye;
    mat4 inverse_view_projection;
    unsigned char background[4];
} raytrace_tracer;

/* The visible surface at a pixel. */
typedef struct raytrace_hit {
    int object;
    float position[3];
    float face_normal[3];    /* unit, towards the eye */
    float shading_normal[3]; /* lit.frag's n */
    float distance;          /* from the eye */
} raytrace_hit;

static float raytrace_dot(const float a[3], const float b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Scales v to unit length and returns its length; 0 (v untouched) when v
 * has no direction, where cglm's normalize would zero v below FLT_EPSILON,
 * a length small triangles of a finely tessellated model reach. */
static float raytrace_normalize(float v[3]) {
    float length = sqrtf(raytrace_dot(v, v));
    if (!(length > 0) || !isfinite(length))
        return 0;
    for (int k = 0; k < 3; k++)
        v[k] /= length;
    return length;
}

/* GLSL's smoothstep; GLSL leaves edge0 >= edge1 undefined, and a spot with
 * inner == outer angle gets a hard edge. */
static float raytrace_smoothstep(float edge0, float edge1, float x) {
    if (edge0 >= edge1)
        return x > edge0 ? 1.0f : 0.0f;
    float t = fminf(fmaxf((x - edge0) / (edge1 - edge0), 0.0f), 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

/* GL's float to 8-bit unsigned normalized conversion: clamp, round. */
static unsigned char raytrace_unorm8(float c) { return (unsigned char)(fminf(fmaxf(c, 0.0f), 1.0f) * 255.0f + 0.5f); }

/* PCG hash: Jarzynski and Olano, "Hash Functions for GPU Rendering",
 * JCGT 9(3), 2020; good avalanche at the cost of a few multiplies. */
static uint32_t raytrace_hash(uint32_t v) {
    uint32_t state = v * 747796405u + 2891336453u;
    uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

/* [0, 1) from the top 24 bits, exact in float. */
static float raytrace_unit(uint32_t h) { return (float)(h >> 8) * (1.0f / 16777216.0f); }

/* Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 6(1),
 * 2017: t and b complete the unit vector n without a branch on its axis. */
static void raytrace_basis(const float n[3], float t[3], float b[3]) {
    float sign = copysignf(1.0f, n[2]);
    float a = -1.0f / (sign + n[2]);
    float c = n[0] * n[1] * a;
    t[0] = 1.0f + sign * n[0] * n[0] * a;
    t[1] = sign * c;
    t[2] = -sign * n[0];
    b[0] = c;
    b[1] = sign + n[1] * n[1] * a;
    b[2] = -n[1];
}

/* Sample k of n on the unit disk. The unit square is cut into n cells of
 * equal area: floor(sqrt n) rows whose counts differ by at most one, each
 * row as tall as its share of the samples (n a square: the usual
 * sqrt(n) x sqrt(n) grid), so every n stratifies without weighting. The
 * jittered point of cell k goes to the disk by Shirley and Chiu's
 * concentric map ("A Low Distortion Map Between Disk and Square", JGT
 * 2(3), 1997), which keeps equal areas and compact strata. */
static void raytrace_disk_sample(int k, int n, float jitter_u, float jitter_v, float disk[2]) {
    int rows = (int)sqrt((double)n);
    int base = n / rows, extra = n % rows; /* the first `extra` rows hold base + 1 */
    int long_cells = extra * (base + 1);
    int row = k < long_cells ? k / (base + 1) : extra + (k - long_cells) / base;
    int count = row < extra ? base + 1 : base;
    int first = row < extra ? row * (base + 1) : long_cells + (row - extra) * base;
    float a = 2.0f * ((float)(k - first) + jitter_u) / (float)count - 1.0f;
    float b = 2.0f * ((float)first + jitter_v * (float)count) / (float)n - 1.0f;
    float r, phi;
    if (a == 0 && b == 0) {
        r = phi = 0;
    } else if (fabsf(a) > fabsf(b)) {
        r = a;
        phi = RAYTRACE_PI / 4 * (b / a);
    } else {
        r = b;
        phi = RAYTRACE_PI / 2 - RAYTRACE_PI / 4 * (a / b);
    }
    disk[0] = r * cosf(phi);
    disk[1] = r * sinf(phi);
}

/* ---- building ---- */

static void raytrace_on_embree_error(void *user, enum RTCError code, const char *message) {
    (void)user;
    fprintf(stderr, "raytrace: Embree error %d: %s\n", (int)code, message ? message : "(no message)");
}

/* Objects with "casts": false stay visible to primary rays but are
 * transparent to shadow rays: their occlusion filter rejects every hit. */
static void raytrace_pass_shadow_rays(const struct RTCFilterFunctionNArguments *args) {
    for (unsigned i = 0; i < args->N; i++)
        args->valid[i] = 0;
}

static bool raytrace_add_object(raytrace_tracer *t, int index) {
    const scene_object *o = &t->scene->objects[index];
    const mesh *m = &o->mesh;
    if (!o->casts && !rtcGetDeviceProperty(t->device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED)) {
        fprintf(stderr, "raytrace: %s: \"casts\": false needs Embree's filter functions, not in this build\n",
                o->name);
        return false;
    }
    scene_object_normal_matrix(o, t->objects[index].normal_matrix);
    RTCGeometry geometry = rtcNewGeometry(t->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!geometry)
        return false;
    rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
    /* Embree's own buffers, padded as its SIMD loads need. */
    float *vertices = rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                              3 * sizeof(float), m->vertex_count);
    uint32_t *indices = rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                3 * sizeof(uint32_t), m->index_count / 3);
    bool ok = vertices && indices;
    for (uint32_t v = 0; ok && v < m->vertex_count; v++)
        glm_mat4_mulv3((vec4 *)o->model, (float *)m->vertices[v].position, 1.0f, vertices + 3 * v);
    for (uint32_t i = 0; ok && i < m->index_count; i++)
        indices[i] = m->indices[i];
    if (ok && !o->casts)
        rtcSetGeometryOccludedFilterFunction(geometry, raytrace_pass_shadow_rays);
    if (ok) {
        rtcCommitGeometry(geometry);
        rtcAttachGeometryByID(t->rtc, geometry, (unsigned)index);
    }
    rtcReleaseGeometry(geometry); /* the scene holds it now */
    t->objects[index].vertices = vertices;
    return ok && rtcGetDeviceError(t->device) == RTC_ERROR_NONE;
}

static bool raytrace_build_scene(raytrace_tracer *t) {
    t->rtc = rtcNewScene(t->device);
    if (!t->rtc)
        return false;
    /* Robust: watertight triangle tests, so primary rays do not slip
     * between the two triangles of a ground quad. */
    rtcSetSceneFlags(t->rtc, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(t->rtc, RTC_BUILD_QUALITY_HIGH);
    for (int i = 0; i < t->scene->object_count; i++)
        if (!raytrace_add_object(t, i))
            return false;
    rtcCommitScene(t->rtc);
    return rtcGetDeviceError(t->device) == RTC_ERROR_NONE;
}

static void raytrace_prepare_lights(raytrace_tracer *t) {
    for (int i = 0; i < t->scene->light_count; i++) {
        const scene_light *l = &t->scene->lights[i];
        raytrace_light *r = &t->lights[i];
        r->light = l;
        scene_light_homogeneous(l, r->position);
        glm_vec3_scale((float *)l->color, l->intensity, r->radiance);
        r->cos_outer = cosf(glm_rad(l->outer_angle_deg));
        r->cos_inner = cosf(glm_rad(l->inner_angle_deg));
        /* 2 sin^2(a/2), not 1 - cos a, which cancels to 0 for a sun-sized
         * radius; a radius past 180 degrees would wrap around. */
        float half_angle = glm_rad(fminf(l->radius, 180.0f)) / 2;
        r->cap = 2.0f * sinf(half_angle) * sinf(half_angle);
    }
}

/* The diagonal of the box holding every object and the origin: it bounds
 * both the scene's size and its coordinates' magnitude (see the top). */
static float raytrace_scene_scale(const scene *s) {
    vec3 lo = {0, 0, 0}, hi = {0, 0, 0};
    for (int i = 0; i < s->object_count; i++) {
        vec3 min, max;
        scene_object_world_bounds(&s->objects[i], min, max);
        glm_vec3_minv(lo, min, lo);
        glm_vec3_maxv(hi, max, hi);
    }
    return glm_vec3_distance(lo, hi);
}

/* ---- tracing ---- */

/* Through the centre of pixel (x, y), y = 0 the top row, from the eye
 * between the near and far planes: what the rasterizer samples. */
static void raytrace_primary_ray(const raytrace_tracer *t, int x, int y, struct RTCRayHit *ray) {
    float ndc_x = ((float)x + 0.5f) / (float)t->width * 2.0f - 1.0f;
    float ndc_y = 1.0f - ((float)y + 0.5f) / (float)t->height * 2.0f;
    vec4 clip_near = {ndc_x, ndc_y, -1.0f, 1.0f}, clip_far = {ndc_x, ndc_y, 1.0f, 1.0f};
    vec4 near, far;
    glm_mat4_mulv((vec4 *)t->inverse_view_projection, clip_near, near);
    glm_mat4_mulv((vec4 *)t->inverse_view_projection, clip_far, far);
    glm_vec3_scale(near, 1.0f / near[3], near);
    glm_vec3_scale(far, 1.0f / far[3], far);
    vec3 direction;
    glm_vec3_sub(far, near, direction);
    raytrace_normalize(direction);
    *ray = (struct RTCRayHit){
        .ray = {.org_x = t->eye[0], .org_y = t->eye[1], .org_z = t->eye[2],
                .tnear = glm_vec3_distance((float *)t->eye, near),
                .dir_x = direction[0], .dir_y = direction[1], .dir_z = direction[2],
                .tfar = glm_vec3_distance((float *)t->eye, far), .mask = UINT32_MAX},
        .hit = {.geomID = RTC_INVALID_GEOMETRY_ID, .instID = {RTC_INVALID_GEOMETRY_ID}},
    };
}

/* The hit as lit.frag sees it. The face normal comes from the world
 * triangle (Embree's Ng has the opposite sign convention) and decides
 * front facing as GL does for counter-clockwise triangles. */
static void raytrace_surface(const raytrace_tracer *t, const struct RTCRayHit *ray, raytrace_hit *h) {
    int object = (int)ray->hit.geomID;
    const mesh *m = &t->scene->objects[object].mesh;
    const uint32_t *corner = m->indices + 3 * (size_t)ray->hit.primID;
    const float weight[3] = {1.0f - ray->hit.u - ray->hit.v, ray->hit.u, ray->hit.v};
    const float *p[3];
    for (int c = 0; c < 3; c++)
        p[c] = t->objects[object].vertices + 3 * (size_t)corner[c];
    vec3 object_normal = {0, 0, 0}, edge1, edge2, to_eye;
    h->object = object;
    for (int k = 0; k < 3; k++)
        h->position[k] = weight[0] * p[0][k] + weight[1] * p[1][k] + weight[2] * p[2][k];
    for (int c = 0; c < 3; c++)
        glm_vec3_muladds((float *)m->vertices[corner[c]].normal, weight[c], object_normal);
    glm_vec3_sub((float *)p[1], (float *)p[0], edge1);
    glm_vec3_sub((float *)p[2], (float *)p[0], edge2);
    glm_vec3_cross(edge1, edge2, h->face_normal);
    glm_vec3_sub((float *)t->eye, h->position, to_eye);
    h->distance = raytrace_normalize(to_eye);
    /* A triangle too thin for a normal in float is seen edge-on: let it
     * face the eye. */
    if (raytrace_normalize(h->face_normal) == 0)
        glm_vec3_copy(to_eye, h->face_normal);
    bool front_facing = raytrace_dot(h->face_normal, to_eye) > 0;
    if (!front_facing)
        glm_vec3_negate(h->face_normal);
    glm_mat3_mulv((vec3 *)t->objects[object].normal_matrix, object_normal, h->shading_normal);
    if (raytrace_normalize(h->shading_normal) == 0)
        glm_vec3_copy(h->face_normal, h->shading_normal);
    else if (!front_facing)
        glm_vec3_negate(h->shading_normal);
}

/* Whether nothing that casts lies between the hit and `target`, a point
 * (w 1) or a direction to infinity (w 0). */
static bool raytrace_unoccluded(const raytrace_tracer *t, struct RTCIntersectContext *context, const raytrace_hit *h,
                                const float target[4]) {
    vec3 towards, origin, direction;
    if (target[3] == 0)
        glm_vec3_copy((float *)target, towards);
    else
        glm_vec3_sub((float *)target, (float *)h->position, towards);
    float side = raytrace_dot(h->face_normal, towards) >= 0 ? t->epsilon : -t->epsilon;
    glm_vec3_copy((float *)h->position, origin);
    glm_vec3_muladds((float *)h->face_normal, side, origin);
    float distance = INFINITY;
    if (target[3] == 0) {
        glm_vec3_copy((float *)target, direction);
    } else {
        glm_vec3_sub((float *)target, origin, direction);
        distance = raytrace_normalize(direction) - t->epsilon;
    }
    struct RTCRay ray = {.org_x = origin[0], .org_y = origin[1], .org_z = origin[2], .tnear = 0,
                         .dir_x = direction[0], .dir_y = direction[1], .dir_z = direction[2],
                         .tfar = distance, .mask = UINT32_MAX};
    rtcOccluded1(t->rtc, context, &ray);
    return ray.tfar >= 0; /* Embree sets -inf on a hit */
}

/* Fraction of light `index` reaching the hit: one ray for a hard light,
 * light_samples for an area light (see raytrace_disk_sample) spread about
 * `to_light`, the unit vector to its centre (0 at the centre itself). */
static float raytrace_visibility(const raytrace_tracer *t, struct RTCIntersectContext *context, const raytrace_hit *h,
                                 int index, const float to_light[3], uint32_t pixel) {
    const raytrace_light *l = &t->lights[index];
    if (!t->scene->objects[h->object].receives)
        return 1;
    if (l->light->radius == 0)
        return raytrace_unoccluded(t, context, h, l->position) ? 1.0f : 0.0f;
    bool directional = l->position[3] == 0;
    vec3 axis, tangent, bitangent;
    glm_vec3_copy((float *)to_light, axis);
    if (raytrace_normalize(axis) == 0) /* at the centre every axis is as good */
        glm_vec3_copy((float *)h->face_normal, axis);
    raytrace_basis(axis, tangent, bitangent);
    uint32_t seed = raytrace_hash(pixel ^ raytrace_hash((uint32_t)index));
    int unoccluded = 0;
    for (int k = 0; k < t->light_samples; k++) {
        uint32_t jitter = raytrace_hash(seed + (uint32_t)k);
        float disk[2];
        raytrace_disk_sample(k, t->light_samples, raytrace_unit(jitter), raytrace_unit(raytrace_hash(jitter)), disk);
        vec4 target;
        if (directional) {
            /* The disk onto the cap of directions within the angular
             * radius, keeping equal areas (Lambert's azimuthal map): a
             * uniform sun disk. */
            float r2 = disk[0] * disk[0] + disk[1] * disk[1];
            float one_minus_cos = r2 * l->cap;
            float sin_over_r = r2 > 0 ? sqrtf(one_minus_cos * (2.0f - one_minus_cos) / r2) : 0.0f;
            glm_vec3_scale(axis, 1.0f - one_minus_cos, target);
            glm_vec3_muladds(tangent, disk[0] * sin_over_r, target);
            glm_vec3_muladds(bitangent, disk[1] * sin_over_r, target);
            target[3] = 0;
        } else {
            glm_vec4_copy((float *)l->position, target);
            glm_vec3_muladds(tangent, disk[0] * l->light->radius, target);
            glm_vec3_muladds(bitangent, disk[1] * l->light->radius, target);
        }
        unoccluded += raytrace_unoccluded(t, context, h, target);
    }
    return (float)unoccluded / (float)t->light_samples;
}

static void raytrace_pixel(const raytrace_tracer *t, struct RTCIntersectContext *context, int x, int y,
                           dump_frame *out) {
    size_t i = (size_t)y * (size_t)t->width + (size_t)x;
    struct RTCRayHit ray;
    raytrace_primary_ray(t, x, y, &ray);
    rtcIntersect1(t->rtc, context, &ray);
    if (ray.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
        memcpy(out->color + 4 * i, t->background, 4);
        return;
    }
    raytrace_hit h;
    raytrace_surface(t, &ray, &h);
    const float *albedo = t->scene->objects[h.object].color;
    vec3 color;
    glm_vec3_mul((float *)albedo, (float *)t->scene->ambient, color);
    for (int l = 0; l < t->scene->light_count; l++) {
        const raytrace_light *light = &t->lights[l];
        vec3 to_light;
        glm_vec3_copy((float *)light->position, to_light);
        if (light->position[3] != 0) {
            glm_vec3_sub(to_light, h.position, to_light);
            raytrace_normalize(to_light);
        }
        bool spot = light->light->type == SCENE_LIGHT_SPOT;
        float cos_axis = -raytrace_dot(to_light, light->light->direction);
        float window = light->position[3] != 0
                           ? scene_light_range_window(light->light, glm_vec3_distance((float *)light->position,
                                                                                     h.position))
                           : 1.0f;
        float unshadowed = fmaxf(raytrace_dot(h.shading_normal, to_light), 0.0f) *
                           (spot ? raytrace_smoothstep(light->cos_outer, light->cos_inner, cos_axis) : 1.0f) *
                           window;
        bool reaches = (!spot || cos_axis > light->cos_outer) && window > 0;
        /* Light K's visibility is dumped wherever it reaches; the others
         * are traced only where they would add light. */
        float visibility = 0;
        if (reaches && (l == t->light_index || unshadowed > 0))
            visibility = raytrace_visibility(t, context, &h, l, to_light, (uint32_t)i);
        if (l == t->light_index)
            out->visibility[i] = visibility;
        for (int k = 0; k < 3; k++)
            color[k] += albedo[k] * light->radiance[k] * unshadowed * visibility;
    }
    out->depth[i] = h.distance;
    out->ids[i] = (float)h.object;
    memcpy(out->normal + 3 * i, h.face_normal, sizeof h.face_normal);
    memcpy(out->position + 3 * i, h.position, sizeof h.position);
    for (int k = 0; k < 3; k++)
        out->color[4 * i + (size_t)k] = raytrace_unorm8(color[k]);
    out->color[4 * i + 3] = 255;
}

static bool raytrace_check_arguments(const scene *s, int width, int height, int light_index, int light_samples) {
    if (width < 1 || height < 1) {
        fprintf(stderr, "raytrace: image size %dx%d is empty\n", width, height);
        return false;
    }
    if (light_index < 0 || light_index >= s->light_count) {
        fprintf(stderr, "raytrace: no light %d (the scene has %d, counted from 0)\n", light_index, s->light_count);
        return false;
    }
    if (light_samples < 0 || light_samples > RAYTRACE_MAX_LIGHT_SAMPLES) {
        fprintf(stderr, "raytrace: light samples must be 1..%d (0: %d), got %d\n", RAYTRACE_MAX_LIGHT_SAMPLES,
                RAYTRACE_DEFAULT_LIGHT_SAMPLES, light_samples);
        return false;
    }
    return true;
}

static void raytrace_release(raytrace_tracer *t) {
    if (t->rtc)
        rtcReleaseScene(t->rtc);
    if (t->device)
        rtcReleaseDevice(t->device);
    free(t->objects);
}

bool raytrace_render(const scene *s, int width, int height, int light_index, const raytrace_settings *settings,
                     dump_frame *out) {
    int light_samples = settings->light_samples ? settings->light_samples : RAYTRACE_DEFAULT_LIGHT_SAMPLES;
    if (!raytrace_check_arguments(s, width, height, light_index, settings->light_samples))
        return false;
    raytrace_tracer t = {
        .scene = s,
        .epsilon = RAYTRACE_EPSILON * raytrace_scene_scale(s),
        .light_samples = light_samples,
        .light_index = light_index,
        .width = width,
        .height = height,
        .background = {raytrace_unorm8(SCENE_BACKGROUND_R), raytrace_unorm8(SCENE_BACKGROUND_G),
                       raytrace_unorm8(SCENE_BACKGROUND_B), 255},
    };
    camera_view view;
    camera_view_compute(&s->camera, (float)width / (float)height, &view);
    glm_mat4_inv(view.view_projection, t.inverse_view_projection);
    glm_vec3_copy(view.eye, t.eye);
    raytrace_prepare_lights(&t);

    double start = omp_get_wtime();
    t.device = rtcNewDevice(NULL);
    if (!t.device) {
        fprintf(stderr, "raytrace: cannot create an Embree device (error %d)\n", (int)rtcGetDeviceError(NULL));
        return false;
    }
    /* From here on Embree reports its own errors, one line each. */
    rtcSetDeviceErrorFunction(t.device, raytrace_on_embree_error, NULL);
    t.objects = calloc((size_t)s->object_count, sizeof *t.objects);
    if (!t.objects)
        fprintf(stderr, "raytrace: out of memory for %d objects\n", s->object_count);
    if (!t.objects || !raytrace_build_scene(&t) || !dump_frame_create(out, width, height, s, light_index)) {
        raytrace_release(&t);
        return false;
    }
    double built = omp_get_wtime();

#pragma omp parallel for schedule(dynamic)
    for (int y = 0; y < height; y++) {
        struct RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (int x = 0; x < width; x++)
            raytrace_pixel(&t, &context, x, y, out);
    }

    bool ok = rtcGetDeviceError(t.device) == RTC_ERROR_NONE;
    if (ok && settings->verbose)
        fprintf(stderr,
                "raytrace: Embree %zd.%zd.%zd, %d threads, epsilon %g; BVH built in %.1f ms, %dx%d traced in "
                "%.1f ms\n",
                rtcGetDeviceProperty(t.device, RTC_DEVICE_PROPERTY_VERSION_MAJOR),
                rtcGetDeviceProperty(t.device, RTC_DEVICE_PROPERTY_VERSION_MINOR),
                rtcGetDeviceProperty(t.device, RTC_DEVICE_PROPERTY_VERSION_PATCH), omp_get_max_threads(),
                (double)t.epsilon, (built - start) * 1e3, width, height, (omp_get_wtime() - built) * 1e3);
    raytrace_release(&t);
    if (!ok)
        dump_frame_free(out);
    return ok;
}
