/* raytrace: see raytrace.h for what is computed; this file says how.
 *
 * Precision far from the origin. Embree 3 takes float geometry, whose
 * spacing grows with the coordinates (ulp(x) <= FLT_EPSILON |x|: 0.06 at
 * 1e6). The BVH is therefore built about a local origin, the eye: each
 * world vertex is transformed and has the eye subtracted in double before
 * it is stored as a float, and every ray is relative to the eye too, so the
 * geometry the camera sees keeps float's relative precision wherever the
 * scene stands. Dumps are turned back to world units (position = eye +
 * local, in double).
 *
 * Camera rays are built in double from the camera's own basis (position,
 * target, up, fov, the image's aspect), not by unprojecting through a float
 * inverse view-projection: with a near/far ratio of 3e7 or more
 * -(f+n)/(f-n) rounds to -1 in float, the far plane unprojects to w = 0 and
 * the directions become NaN. Near and far only bound the ray: its component
 * along the view axis is 1, so t is the eye-space depth GL clips. The
 * visible point is where the pixel's double ray meets the plane of the
 * triangle Embree found, in double (the barycentric point where the ray
 * runs almost in that plane, which leaves the intersection ill-conditioned).
 *
 * Shadow rays. Each starts at the visible point itself, exact in double,
 * and goes along the line from it to the light: no offset moves the line,
 * which at grazing light would move the shadow's edge by the offset over
 * the tangent of the light's elevation. Embree's float test places the
 * crossing of a ray with a triangle's plane to within a few ulps of the
 * triangle's coordinates relative to the ray's start: on a large triangle
 * (a 1e5 ground, 7e4 from the point it holds) that is far more than the
 * distances of contact shadows. Each hit Embree reports on a shadow ray is
 * therefore confirmed by an occlusion filter in double, on the exact line:
 * the line must cross the plane of the triangle (its float vertices, exact
 * in double) after its start and before its end, and the start must lie
 * off that plane by more than RAYTRACE_SURFACE_ULPS times (FLT_EPSILON
 * times the largest coordinate of the point from the eye, plus DBL_EPSILON
 * times the hit triangle's extent about it). A ray never crosses a plane
 * through its own start after it, so a plane within that rounding of the
 * start is the surface the ray leaves (its own triangle, and a neighbour
 * that the vertices' rounding tilts by an ulp), never an occluder, at any
 * angle to the light. Embree's robust, watertight test still decides the
 * edges, so no ray slips between two triangles. A ray to a point light
 * ends as many float ulps of the light's coordinates and of the ray's
 * length short of it, so that a light on a surface is not shadowed by it
 * (the direction's rounding moves the ray's end by about an ulp of its
 * length). Nothing depends on the scene's size: a huge ground or a sky
 * sphere elsewhere changes no tolerance. */
#include "raytrace.h"

#include <cglm/cglm.h>
#include <embree3/rtcore.h>
#include <float.h>
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "area_light.h"
#include "bvh.h"

/* Below this cosine between a camera ray and the hit triangle's normal the
 * visible point is the barycentric one (see the top): the plane's
 * intersection then loses up to 1e-16 / cosine of the ray's length. */
#define RAYTRACE_MIN_PLANE_COSINE 1e-6
/* The most translucent triangles a shadow ray filters its light through;
 * one that crosses more is blocked (a light that far filtered is all but
 * gone). */
#define RAYTRACE_MAX_CROSSED 64
/* Embree's limit on a ray's coordinates (FLT_LARGE in its sources): past it
 * its ray.valid() check fails, an assertion in some builds. */
#define RAYTRACE_MAX_COORDINATE 1.844e18f

/* What a light needs per shaded point, computed once. */
typedef struct raytrace_light {
    const scene_light *light;
    vec4 position;              /* scene_light_homogeneous, from the eye: w 0 directional */
    float radiance[3];          /* colour times intensity */
    float cos_outer, cos_inner; /* spot */
} raytrace_light;

typedef struct raytrace_object {
    const float *vertices;   /* from the eye (see the top), 3 floats each, in Embree's buffer */
    const uint32_t *indices; /* the mesh's, 3 a triangle */
    mat3 normal_matrix;      /* scene_object_normal_matrix, as the raster side uses */
    bool casts;
    const scene_object *translucent; /* the scene's object where it is a translucent caster, else NULL */
    const scene_object *cut_out;     /* the scene's object where it is cut out, else NULL */
    bool single_sided;               /* scene_object's: camera rays pass through its back faces */
} raytrace_object;

struct raytrace_tracer {
    const scene *scene;
    RTCDevice device;
    RTCScene rtc;
    raytrace_object *objects;
    raytrace_light lights[SCENE_MAX_LIGHTS];
    int light_samples;
    int light_index;
    int width, height;
    double eye[3]; /* world: the local origin */
    /* The ray of normalized device coordinates (x, y) is forward + x right
     * + y up, forward the unit view axis. */
    double forward[3], right[3], up[3];
    float near_plane, far_plane;
    unsigned char background[4];
    bool verbose;
    double build_ms, trace_ms; /* for verbose */
    /* Where the scene has an area light: its casters' hierarchy in world
     * units (bvh.h), whose cone test spares an area light's samples where
     * none can be blocked (raytrace_cone_clear). */
    bvh casters;
    float casters_reach;     /* bvh_reach */
    bool trace_every_sample; /* raytrace_settings' */
};

/* The visible surface at a pixel. */
typedef struct raytrace_hit {
    int object;
    double position[3];       /* from the eye */
    float face_normal[3];     /* unit, towards the eye */
    float shading_normal[3];  /* lit.frag's n */
    double distance;          /* from the eye */
    double surface_tolerance; /* a plane nearer the point than this holds it (see the top) */
} raytrace_hit;

/* A shadow ray's intersect context, handed to the occlusion filter: the
 * exact line, of which Embree traces the floats. */
typedef struct raytrace_shadow_context {
    struct RTCIntersectContext embree; /* first: the filter gets its address */
    const raytrace_tracer *tracer;
    double origin[3];         /* the visible point, from the eye */
    double direction[3];      /* towards the light; unit for a point light */
    double end;               /* the ray's length along `direction` (infinite to a direction) */
    double surface_tolerance; /* the hit's (raytrace_hit) */
    /* What the translucent triangles crossed so far let through, per
     * channel, and which they are: Embree may report one triangle more
     * than once (a high-quality build's spatial splits), and each filters
     * the light once. Past RAYTRACE_MAX_CROSSED the ray is taken as
     * blocked. */
    float transmittance[3];
    int crossed_count;
    struct {
        unsigned object, triangle;
    } crossed[RAYTRACE_MAX_CROSSED];
} raytrace_shadow_context;

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

static double raytrace_dot_d(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void raytrace_cross_d(const double a[3], const double b[3], double out[3]) {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Scales v to unit length and returns its length; 0 (v untouched) when v
 * has no direction. */
static double raytrace_normalize_d(double v[3]) {
    double length = sqrt(raytrace_dot_d(v, v));
    if (!(length > 0) || !isfinite(length))
        return 0;
    for (int k = 0; k < 3; k++)
        v[k] /= length;
    return length;
}

static double raytrace_max_abs(const double v[3]) { return fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2]))); }

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

/* ---- building ---- */

static void raytrace_on_embree_error(void *user, enum RTCError code, const char *message) {
    (void)user;
    fprintf(stderr, "raytrace: Embree error %d: %s\n", (int)code, message ? message : "(no message)");
}

/* The corners of triangle `triangle` of an object, from the eye. */
static void raytrace_corners(const raytrace_object *o, unsigned triangle, double v[3][3]) {
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < 3; k++)
            v[c][k] = o->vertices[3 * (size_t)o->indices[3 * (size_t)triangle + (size_t)c] + (size_t)k];
}

/* The plane normal of corners v, counter-clockwise front, not unit. */
static void raytrace_plane_normal(const double v[3][3], double normal[3]) {
    double edge1[3], edge2[3];
    for (int k = 0; k < 3; k++) {
        edge1[k] = v[1][k] - v[0][k];
        edge2[k] = v[2][k] - v[0][k];
    }
    raytrace_cross_d(edge1, edge2, normal);
}

/* Whether the shadow ray of `c` crosses the plane of the triangle after its
 * start and no later than its end, in double, from a start off that plane
 * by more than the surface tolerance (see the top); a ray parallel to the
 * plane does not cross it. */
static bool raytrace_crosses_plane(const raytrace_shadow_context *c, const raytrace_object *o, unsigned triangle) {
    double v[3][3], normal[3], to_plane[3];
    raytrace_corners(o, triangle, v);
    raytrace_plane_normal(v, normal);
    double area = raytrace_normalize_d(normal);
    for (int k = 0; k < 3; k++)
        to_plane[k] = v[0][k] - c->origin[k];
    double height = raytrace_dot_d(to_plane, normal);
    double approach = raytrace_dot_d(c->direction, normal);
    if (area == 0 || approach == 0 || !(fabs(height) > c->surface_tolerance))
        return false;
    double t = height / approach;
    return t > 0 && t <= c->end;
}

/* A translucent triangle the ray crosses: its light filtered by the
 * triangle's transmittance at the crossing, once; false where the ray has
 * crossed too many to follow (it is then blocked). */
static bool raytrace_filter_through(raytrace_shadow_context *c, const struct RTCHit *hit, const scene_object *o) {
    for (int k = 0; k < c->crossed_count; k++)
        if (c->crossed[k].object == hit->geomID && c->crossed[k].triangle == hit->primID)
            return true;
    if (c->crossed_count == RAYTRACE_MAX_CROSSED)
        return false;
    c->crossed[c->crossed_count].object = hit->geomID;
    c->crossed[c->crossed_count++].triangle = hit->primID;
    const float weight[3] = {1.0f - hit->u - hit->v, hit->u, hit->v};
    float through[3];
    scene_object_transmittance(o, hit->primID, weight, through);
    glm_vec3_mul(c->transmittance, through, c->transmittance);
    return true;
}

/* The occlusion filter of every shadow ray: objects with "casts": false
 * block nothing, and every other hit is confirmed in double (see the top);
 * a translucent caster's confirmed hit filters the light and lets the ray
 * go on. Shadow rays go through rtcOccluded1, so N is 1 and the hit is a
 * plain RTCHit. */
static void raytrace_confirm_occlusion(const struct RTCFilterFunctionNArguments *args) {
    raytrace_shadow_context *c = (raytrace_shadow_context *)args->context;
    const struct RTCHit *hit = (const struct RTCHit *)args->hit;
    const raytrace_object *o = &c->tracer->objects[hit->geomID];
    if (!o->casts || !raytrace_crosses_plane(c, o, hit->primID) ||
        (o->translucent && raytrace_filter_through(c, hit, o->translucent)))
        args->valid[0] = 0;
}

/* Whether the hit is on a cut-out object where it has no surface
 * (scene_object_cut_out: the rule of the raster's cut-out programs). */
static bool raytrace_cut_away(const raytrace_object *o, const struct RTCHit *hit) {
    const float weight[3] = {1.0f - hit->u - hit->v, hit->u, hit->v};
    return o->cut_out && scene_object_cut_out(o->cut_out, hit->primID, weight);
}

/* Whether the eye (the local origin) sees the triangle from behind: not in
 * front of its counter-clockwise face, as GL culls a back face (an
 * edge-on triangle, which GL draws no pixel of, too). */
static bool raytrace_seen_from_behind(const raytrace_object *o, unsigned triangle) {
    double v[3][3], normal[3];
    raytrace_corners(o, triangle, v);
    raytrace_plane_normal(v, normal);
    return raytrace_dot_d(v[0], normal) >= 0;
}

/* Camera rays' hits (rtcIntersect1: N is 1) that are no surface: a
 * cut-out's holes, and a single-sided object's back faces. */
static void raytrace_camera_filter(const struct RTCFilterFunctionNArguments *args) {
    const raytrace_object *o = (const raytrace_object *)args->geometryUserPtr;
    const struct RTCHit *hit = (const struct RTCHit *)args->hit;
    if (raytrace_cut_away(o, hit) || (o->single_sided && raytrace_seen_from_behind(o, hit->primID)))
        args->valid[0] = 0;
}

/* Shadow rays' hits (rtcOccluded1: N is 1) on a cut-out's holes; every
 * object casts from both sides. */
static void raytrace_shadow_filter(const struct RTCFilterFunctionNArguments *args) {
    if (raytrace_cut_away((const raytrace_object *)args->geometryUserPtr, (const struct RTCHit *)args->hit))
        args->valid[0] = 0;
}

/* The object's world vertices less the eye, in double, then stored as
 * floats (see the top). False, after one line, where one is beyond what
 * Embree accepts. */
static bool raytrace_store_vertices(const raytrace_tracer *t, const scene_object *o, float *vertices) {
    const mesh *m = &o->mesh;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        const float *p = m->vertices[v].position;
        for (int k = 0; k < 3; k++) {
            double world = (double)o->model[3][k] + (double)o->model[0][k] * p[0] + (double)o->model[1][k] * p[1] +
                           (double)o->model[2][k] * p[2];
            float local = (float)(world - t->eye[k]);
            if (!(fabsf(local) <= RAYTRACE_MAX_COORDINATE)) {
                fprintf(stderr, "raytrace: %s: vertex %u is %g from the eye, beyond Embree's range (%g)\n", o->name,
                        v, world - t->eye[k], (double)RAYTRACE_MAX_COORDINATE);
                return false;
            }
            vertices[3 * v + (uint32_t)k] = local;
        }
    }
    return true;
}

static bool raytrace_add_object(raytrace_tracer *t, int index) {
    const scene_object *o = &t->scene->objects[index];
    const mesh *m = &o->mesh;
    raytrace_object *r = &t->objects[index];
    scene_object_normal_matrix(o, r->normal_matrix);
    r->indices = m->indices;
    r->casts = o->casts;
    r->translucent = o->translucent ? o : NULL;
    r->cut_out = o->alpha_cutoff > 0 ? o : NULL;
    r->single_sided = o->single_sided;
    RTCGeometry geometry = rtcNewGeometry(t->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!geometry)
        return false;
    rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
    rtcSetGeometryUserData(geometry, r);
    if (r->cut_out || r->single_sided)
        rtcSetGeometryIntersectFilterFunction(geometry, raytrace_camera_filter);
    if (r->cut_out)
        rtcSetGeometryOccludedFilterFunction(geometry, raytrace_shadow_filter);
    /* Embree's own buffers, padded as its SIMD loads need. */
    float *vertices = rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                              3 * sizeof(float), m->vertex_count);
    uint32_t *indices = rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                3 * sizeof(uint32_t), m->index_count / 3);
    bool ok = vertices && indices && raytrace_store_vertices(t, o, vertices);
    for (uint32_t i = 0; ok && i < m->index_count; i++)
        indices[i] = m->indices[i];
    if (ok) {
        rtcCommitGeometry(geometry);
        rtcAttachGeometryByID(t->rtc, geometry, (unsigned)index);
    }
    rtcReleaseGeometry(geometry); /* the scene holds it now */
    r->vertices = vertices;
    return ok && rtcGetDeviceError(t->device) == RTC_ERROR_NONE;
}

static bool raytrace_build_scene(raytrace_tracer *t) {
    if (!rtcGetDeviceProperty(t->device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED)) {
        fprintf(stderr, "raytrace: this Embree build has no filter functions, which confirm shadow-ray hits\n");
        return false;
    }
    t->rtc = rtcNewScene(t->device);
    if (!t->rtc)
        return false;
    /* Robust: watertight triangle tests, so primary rays do not slip
     * between the two triangles of a ground quad. The context filter
     * confirms shadow-ray hits (see the top). */
    rtcSetSceneFlags(t->rtc, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
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
        for (int k = 0; k < 3 && r->position[3] != 0; k++)
            r->position[k] = (float)((double)l->position[k] - t->eye[k]);
        glm_vec3_scale((float *)l->color, l->intensity, r->radiance);
        r->cos_outer = cosf(glm_rad(l->outer_angle_deg));
        r->cos_inner = cosf(glm_rad(l->inner_angle_deg));
    }
}

/* What is wrong with the camera, written to `problem`, or false when
 * nothing is: scene_load refuses all of these in a file, but a scene made
 * or changed in memory may hold any of them. */
static bool raytrace_camera_problem(const scene_camera *c, char *problem, size_t capacity) {
    const float *numbers[] = {c->position, c->target, c->up, &c->fov_deg, &c->near_plane, &c->far_plane};
    const int counts[] = {3, 3, 3, 1, 1, 1};
    bool finite = true;
    for (size_t n = 0; n < sizeof counts / sizeof *counts; n++)
        for (int k = 0; k < counts[n]; k++)
            finite = finite && isfinite(numbers[n][k]);
    double view[3], side[3], up[3] = {c->up[0], c->up[1], c->up[2]};
    for (int k = 0; k < 3; k++)
        view[k] = (double)c->target[k] - c->position[k];
    raytrace_cross_d(view, up, side);
    if (!finite)
        snprintf(problem, capacity, "a number is not finite");
    else if (!(c->fov_deg > 0 && c->fov_deg < 180))
        snprintf(problem, capacity, "fov %g is not between 0 and 180 degrees", (double)c->fov_deg);
    else if (!(c->near_plane > 0 && c->near_plane < c->far_plane))
        snprintf(problem, capacity, "near %g and far %g: need 0 < near < far", (double)c->near_plane,
                 (double)c->far_plane);
    else if (raytrace_normalize_d(view) == 0)
        snprintf(problem, capacity, "target is the position");
    else if (raytrace_normalize_d(side) == 0)
        snprintf(problem, capacity, "up is zero or parallel to the view direction");
    else
        return false;
    return true;
}

/* The camera's basis in double, as glm_lookat and glm_perspective make it
 * (see raytrace_tracer), or false after one line naming the scene. */
static bool raytrace_prepare_camera(raytrace_tracer *t, const char *scene_name) {
    const scene_camera *c = &t->scene->camera;
    char problem[128];
    if (raytrace_camera_problem(c, problem, sizeof problem)) {
        fprintf(stderr, "raytrace: %s: camera: %s\n", scene_name ? scene_name : "the scene", problem);
        return false;
    }
    double side[3], up[3] = {c->up[0], c->up[1], c->up[2]};
    for (int k = 0; k < 3; k++) {
        t->eye[k] = c->position[k];
        t->forward[k] = (double)c->target[k] - c->position[k];
    }
    raytrace_normalize_d(t->forward);
    raytrace_cross_d(t->forward, up, side);
    raytrace_normalize_d(side);
    raytrace_cross_d(side, t->forward, t->up);
    double half_height = tan((double)c->fov_deg * (M_PI / 360.0));
    double half_width = half_height * (double)t->width / (double)t->height;
    for (int k = 0; k < 3; k++) {
        t->right[k] = side[k] * half_width;
        t->up[k] *= half_height;
    }
    t->near_plane = c->near_plane;
    t->far_plane = c->far_plane;
    return true;
}

/* ---- tracing ---- */

/* Whether Embree accepts the ray: finite coordinates within its range, and
 * 0 <= tnear <= tfar. */
static bool raytrace_ray_valid(const struct RTCRay *r) {
    const float coordinates[6] = {r->org_x, r->org_y, r->org_z, r->dir_x, r->dir_y, r->dir_z};
    for (int k = 0; k < 6; k++)
        if (!(fabsf(coordinates[k]) <= RAYTRACE_MAX_COORDINATE))
            return false;
    return r->tnear >= 0 && r->tnear <= r->tfar;
}

/* Through the centre of pixel (x, y), y = 0 the top row: what the
 * rasterizer samples. Its component along the view axis is 1. */
static void raytrace_pixel_direction(const raytrace_tracer *t, int x, int y, double direction[3]) {
    double ndc_x = ((double)x + 0.5) / (double)t->width * 2.0 - 1.0;
    double ndc_y = 1.0 - ((double)y + 0.5) / (double)t->height * 2.0;
    for (int k = 0; k < 3; k++)
        direction[k] = t->forward[k] + ndc_x * t->right[k] + ndc_y * t->up[k];
}

/* From the eye (the local origin) between the near and far planes. */
static struct RTCRayHit raytrace_primary_ray(const raytrace_tracer *t, const double direction[3]) {
    return (struct RTCRayHit){
        .ray = {.tnear = t->near_plane,
                .dir_x = (float)direction[0],
                .dir_y = (float)direction[1],
                .dir_z = (float)direction[2],
                .tfar = t->far_plane,
                .mask = UINT32_MAX},
        .hit = {.geomID = RTC_INVALID_GEOMETRY_ID, .instID = {RTC_INVALID_GEOMETRY_ID}},
    };
}

/* The hit as lit.frag sees it, at the point of the triangle's plane on the
 * double ray `direction` (see the top). The face normal comes from the
 * triangle (Embree's Ng has the opposite sign convention) and decides front
 * facing as GL does for counter-clockwise triangles. */
static void raytrace_surface(const raytrace_tracer *t, const struct RTCRayHit *ray, const double direction[3],
                             raytrace_hit *h) {
    int object = (int)ray->hit.geomID;
    const raytrace_object *o = &t->objects[object];
    const mesh *m = &t->scene->objects[object].mesh;
    const uint32_t *corner = m->indices + 3 * (size_t)ray->hit.primID;
    const float weight[3] = {1.0f - ray->hit.u - ray->hit.v, ray->hit.u, ray->hit.v};
    double v[3][3], normal[3], to_eye[3];
    raytrace_corners(o, ray->hit.primID, v);
    raytrace_plane_normal(v, normal);
    double area = raytrace_normalize_d(normal);
    double approach = raytrace_dot_d(direction, normal);
    bool on_plane =
        area > 0 && fabs(approach) >= RAYTRACE_MIN_PLANE_COSINE * sqrt(raytrace_dot_d(direction, direction));
    double along = on_plane ? raytrace_dot_d(v[0], normal) / approach : 0;
    double extent = 0;
    for (int k = 0; k < 3; k++)
        h->position[k] =
            on_plane ? along * direction[k] : weight[0] * v[0][k] + weight[1] * v[1][k] + weight[2] * v[2][k];
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < 3; k++)
            extent = fmax(extent, fabs(v[c][k] - h->position[k]));
    h->surface_tolerance =
        RAYTRACE_SURFACE_ULPS * (FLT_EPSILON * raytrace_max_abs(h->position) + DBL_EPSILON * extent);
    h->object = object;
    for (int k = 0; k < 3; k++)
        to_eye[k] = -h->position[k];
    h->distance = raytrace_normalize_d(to_eye);
    /* A triangle too thin for a normal is seen edge-on: let it face the
     * eye. */
    if (area == 0)
        memcpy(normal, to_eye, sizeof normal);
    bool front_facing = raytrace_dot_d(normal, to_eye) > 0;
    for (int k = 0; k < 3; k++)
        h->face_normal[k] = (float)(front_facing ? normal[k] : -normal[k]);
    vec3 object_normal = {0, 0, 0};
    for (int c = 0; c < 3; c++)
        glm_vec3_muladds((float *)m->vertices[corner[c]].normal, weight[c], object_normal);
    glm_mat3_mulv((vec3 *)o->normal_matrix, object_normal, h->shading_normal);
    if (raytrace_normalize(h->shading_normal) == 0)
        glm_vec3_copy(h->face_normal, h->shading_normal);
    else if (!front_facing)
        glm_vec3_negate(h->shading_normal);
}

/* The share of light, per channel, that reaches the hit from `target`, a
 * point (w 1) or a direction to infinity (w 0), from the eye: 0 where an
 * opaque caster lies between, else what the translucent ones between let
 * through (1 where none is). A ray Embree would refuse (the light nearer
 * the surface than the margin, or beyond Embree's range) is not traced:
 * nothing is taken to block it. */
static void raytrace_transmitted(raytrace_shadow_context *c, const raytrace_hit *h, const float target[4],
                                 float out[3]) {
    bool directional = target[3] == 0;
    for (int k = 0; k < 3; k++) {
        c->origin[k] = h->position[k];
        c->direction[k] = directional ? target[k] : target[k] - h->position[k];
    }
    c->end = INFINITY;
    if (!directional) {
        const double light[3] = {target[0], target[1], target[2]};
        double length = raytrace_normalize_d(c->direction);
        c->end = length - RAYTRACE_SURFACE_ULPS * FLT_EPSILON * (raytrace_max_abs(light) + length);
    }
    c->surface_tolerance = h->surface_tolerance;
    struct RTCRay ray = {.org_x = (float)c->origin[0],
                         .org_y = (float)c->origin[1],
                         .org_z = (float)c->origin[2],
                         .tnear = 0,
                         .dir_x = (float)c->direction[0],
                         .dir_y = (float)c->direction[1],
                         .dir_z = (float)c->direction[2],
                         .tfar = (float)c->end,
                         .mask = UINT32_MAX};
    glm_vec3_one(c->transmittance);
    c->crossed_count = 0;
    if (raytrace_ray_valid(&ray))
        rtcOccluded1(c->tracer->rtc, &c->embree, &ray);
    if (ray.tfar >= 0) /* Embree sets -inf on a hit */
        glm_vec3_copy(c->transmittance, out);
    else
        glm_vec3_zero(out);
}

/* Whether no caster can block any of area light l's samples at the hit
 * (t->casters' bvh_cone_clear): the cone from the point to the light's
 * disk holds every sample's ray (a sun's, as far as the casters reach),
 * and it is widened by RAYTRACE_SURFACE_ULPS of the point's coordinates
 * and the cone's length everywhere along it, from its apex on, for the
 * rounding between the casters' world coordinates and Embree's from the
 * eye: its apex moves back along the axis until its radius at the point
 * is that margin, and its end radius grows by twice it. Every sample then
 * gets through, the mean the samples would give exactly, so they are not
 * traced: a skip that changes no pixel. */
static bool raytrace_cone_clear(const raytrace_tracer *t, const raytrace_hit *h, const raytrace_light *l) {
    if (t->casters.node_count == 0)
        return true;
    float origin[3], axis[3], length, radius;
    for (int k = 0; k < 3; k++)
        origin[k] = (float)(t->eye[k] + h->position[k]);
    if (l->light->type == SCENE_LIGHT_DIRECTIONAL) {
        length = glm_vec3_norm(origin) + t->casters_reach;
        glm_vec3_negate_to((float *)l->light->direction, axis);
        glm_vec3_normalize(axis);
        radius = length * tanf(glm_rad(l->light->radius));
    } else {
        glm_vec3_sub((float *)l->light->position, origin, axis);
        length = glm_vec3_norm(axis);
        glm_vec3_normalize(axis);
        radius = l->light->radius;
    }
    float margin = RAYTRACE_SURFACE_ULPS * FLT_EPSILON *
                   (fmaxf(fmaxf(fabsf(origin[0]), fabsf(origin[1])), fabsf(origin[2])) + length);
    float back = margin * length / (radius + margin), apex[3], dir[3];
    for (int k = 0; k < 3; k++) {
        apex[k] = origin[k] - back * axis[k];
        dir[k] = (length + back) * axis[k];
    }
    return length > margin && isfinite(back) && bvh_cone_clear(&t->casters, apex, dir, 1, radius + 2 * margin);
}

/* Fraction of light `index` reaching the hit, per channel: one ray for a
 * hard light, light_samples for an area light (area_light.h) spread about
 * `to_light`, the unit vector to its centre (0 at the centre itself). */
static void raytrace_visibility(raytrace_shadow_context *c, const raytrace_hit *h, int index, const float to_light[3],
                                uint32_t pixel, float out[3]) {
    const raytrace_tracer *t = c->tracer;
    const raytrace_light *l = &t->lights[index];
    if (!t->scene->objects[h->object].receives) {
        glm_vec3_one(out);
        return;
    }
    if (l->light->radius == 0) {
        raytrace_transmitted(c, h, l->position, out);
        return;
    }
    if (!t->trace_every_sample && raytrace_cone_clear(t, h, l)) {
        glm_vec3_one(out);
        return;
    }
    vec3 axis;
    glm_vec3_copy((float *)to_light, axis);
    if (raytrace_normalize(axis) == 0) /* at the centre every axis is as good */
        glm_vec3_copy((float *)h->face_normal, axis);
    area_light_frame frame;
    area_light_frame_for(l->light, l->position, axis, &frame);
    uint32_t seed = area_light_hash(pixel ^ area_light_hash((uint32_t)index));
    glm_vec3_zero(out);
    for (int k = 0; k < t->light_samples; k++) {
        vec4 target;
        float through[3];
        area_light_sample(&frame, k, t->light_samples, area_light_hash(seed + (uint32_t)k), target);
        raytrace_transmitted(c, h, target, through);
        glm_vec3_add(out, through, out);
    }
    glm_vec3_divs(out, (float)t->light_samples, out);
}

/* The texture coordinates at p (from the eye) in the plane of corners v,
 * of coordinates uv: by p's barycentric coordinates, extrapolated beyond
 * the triangle (a neighbour pixel's point may lie outside it, as the
 * rasterizer's derivatives extrapolate too). */
static void raytrace_uv_at(const double v[3][3], const float uv[3][2], const double p[3], float out[2]) {
    double e1[3], e2[3], d[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = v[1][k] - v[0][k];
        e2[k] = v[2][k] - v[0][k];
        d[k] = p[k] - v[0][k];
    }
    double d11 = raytrace_dot_d(e1, e1), d12 = raytrace_dot_d(e1, e2), d22 = raytrace_dot_d(e2, e2);
    double d1 = raytrace_dot_d(d, e1), d2 = raytrace_dot_d(d, e2);
    double denominator = d11 * d22 - d12 * d12;
    double b1 = denominator != 0 ? (d22 * d1 - d12 * d2) / denominator : 0;
    double b2 = denominator != 0 ? (d11 * d2 - d12 * d1) / denominator : 0;
    for (int k = 0; k < 2; k++)
        out[k] = (float)((1 - b1 - b2) * uv[0][k] + b1 * uv[1][k] + b2 * uv[2][k]);
}

/* The hit's base colour (shaders/surface.glsl): the object's colour, times
 * its texture's (texture.h's rule) at the hit's texture coordinates, the
 * level of detail from where the rays of the pixels to the right and
 * above meet the hit triangle's plane (ray differentials). */
static void raytrace_albedo(const raytrace_tracer *t, const struct RTCRayHit *ray, const raytrace_hit *h, int x,
                            int y, float albedo[3]) {
    const scene_object *object = &t->scene->objects[h->object];
    glm_vec3_copy((float *)object->color, albedo);
    if (!object->base_color)
        return;
    const raytrace_object *o = &t->objects[h->object];
    const uint32_t *corner = object->mesh.indices + 3 * (size_t)ray->hit.primID;
    double v[3][3], normal[3];
    float uv[3][2];
    raytrace_corners(o, ray->hit.primID, v);
    raytrace_plane_normal(v, normal);
    for (int c = 0; c < 3; c++)
        memcpy(uv[c], object->mesh.vertices[corner[c]].uv, sizeof uv[c]);
    float at[2], beside[2][2], duv[2][2];
    raytrace_uv_at(v, uv, h->position, at);
    const int step[2][2] = {{1, 0}, {0, -1}};
    for (int d = 0; d < 2; d++) {
        double direction[3], p[3];
        raytrace_pixel_direction(t, x + step[d][0], y + step[d][1], direction);
        double approach = raytrace_dot_d(direction, normal);
        double along = approach != 0 ? raytrace_dot_d(v[0], normal) / approach : INFINITY;
        for (int k = 0; k < 3; k++)
            p[k] = along * direction[k];
        raytrace_uv_at(v, uv, p, beside[d]);
        for (int k = 0; k < 2; k++) {
            duv[d][k] = beside[d][k] - at[k];
            /* A plane the neighbour's ray misses (or meets behind the
             * eye): the widest footprint, the last level. */
            if (!(along > 0) || !isfinite(duv[d][k]))
                duv[d][k] = FLT_MAX;
        }
    }
    float texel[4];
    texture_sample(object->base_color, at, texture_lod(object->base_color, duv[0], duv[1]), texel);
    glm_vec3_mul(albedo, texel, albedo);
}

/* Light K's visibility at pixel i: its channels where the frame has
 * them, and one figure, their own where they agree (every pixel of a
 * scene without translucent casters, bit for bit), else their mean. */
static void raytrace_store_visibility(const float visibility[3], size_t i, dump_frame *out) {
    bool grey = visibility[0] == visibility[1] && visibility[1] == visibility[2];
    out->visibility[i] = grey ? visibility[0] : (visibility[0] + visibility[1] + visibility[2]) / 3.0f;
    if (out->visibility_rgb)
        memcpy(out->visibility_rgb + 3 * i, visibility, 3 * sizeof *visibility);
}

static void raytrace_pixel(const raytrace_tracer *t, struct RTCIntersectContext *primary,
                           raytrace_shadow_context *shadow, int x, int y, dump_frame *out) {
    size_t i = (size_t)y * (size_t)t->width + (size_t)x;
    double direction[3];
    raytrace_pixel_direction(t, x, y, direction);
    struct RTCRayHit ray = raytrace_primary_ray(t, direction);
    if (raytrace_ray_valid(&ray.ray))
        rtcIntersect1(t->rtc, primary, &ray);
    if (ray.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
        memcpy(out->color + 4 * i, t->background, 4);
        return;
    }
    raytrace_hit h;
    raytrace_surface(t, &ray, direction, &h);
    vec3 albedo, color;
    raytrace_albedo(t, &ray, &h, x, y, albedo);
    glm_vec3_mul(albedo, (float *)t->scene->ambient, color);
    for (int l = 0; l < t->scene->light_count; l++) {
        const raytrace_light *light = &t->lights[l];
        double towards[3];
        for (int k = 0; k < 3; k++)
            towards[k] = light->position[3] != 0 ? light->position[k] - h.position[k] : light->position[k];
        double distance = light->position[3] != 0 ? raytrace_normalize_d(towards) : 0;
        const float to_light[3] = {(float)towards[0], (float)towards[1], (float)towards[2]};
        bool spot = light->light->type == SCENE_LIGHT_SPOT;
        float cos_axis = -raytrace_dot(to_light, light->light->direction);
        float window = light->position[3] != 0 ? scene_light_range_window(light->light, (float)distance) : 1.0f;
        float unshadowed = fmaxf(raytrace_dot(h.shading_normal, to_light), 0.0f) *
                           (spot ? raytrace_smoothstep(light->cos_outer, light->cos_inner, cos_axis) : 1.0f) * window;
        bool reaches = (!spot || cos_axis > light->cos_outer) && window > 0;
        /* Light K's visibility is dumped wherever it reaches; the others
         * are traced only where they would add light. */
        float visibility[3] = {0, 0, 0};
        if (reaches && (l == t->light_index || unshadowed > 0))
            raytrace_visibility(shadow, &h, l, to_light, (uint32_t)i, visibility);
        if (l == t->light_index)
            raytrace_store_visibility(visibility, i, out);
        for (int k = 0; k < 3; k++)
            color[k] += albedo[k] * light->radiance[k] * unshadowed * visibility[k];
    }
    out->depth[i] = (float)h.distance;
    out->ids[i] = (float)h.object;
    memcpy(out->normal + 3 * i, h.face_normal, sizeof h.face_normal);
    for (int k = 0; k < 3; k++)
        out->position[3 * i + (size_t)k] = (float)(t->eye[k] + h.position[k]);
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
    bvh_free(&t->casters);
    free(t);
}

raytrace_tracer *raytrace_begin(const scene *s, int width, int height, int light_index,
                                const raytrace_settings *settings, dump_frame *out) {
    int light_samples = settings->light_samples ? settings->light_samples : RAYTRACE_DEFAULT_LIGHT_SAMPLES;
    if (!raytrace_check_arguments(s, width, height, light_index, settings->light_samples))
        return NULL;
    raytrace_tracer *t = calloc(1, sizeof *t);
    if (!t) {
        fprintf(stderr, "raytrace: out of memory for a tracer\n");
        return NULL;
    }
    *t = (raytrace_tracer){
        .scene = s,
        .light_samples = light_samples,
        .light_index = light_index,
        .width = width,
        .height = height,
        .verbose = settings->verbose,
        .trace_every_sample = settings->trace_every_sample,
        .background = {raytrace_unorm8(SCENE_BACKGROUND_R), raytrace_unorm8(SCENE_BACKGROUND_G),
                       raytrace_unorm8(SCENE_BACKGROUND_B), 255},
    };
    if (!raytrace_prepare_camera(t, settings->scene_name)) {
        free(t);
        return NULL;
    }
    raytrace_prepare_lights(t);

    double start = omp_get_wtime();
    t->device = rtcNewDevice(NULL);
    if (!t->device) {
        fprintf(stderr, "raytrace: cannot create an Embree device (error %d)\n", (int)rtcGetDeviceError(NULL));
        free(t);
        return NULL;
    }
    /* From here on Embree reports its own errors, one line each. */
    rtcSetDeviceErrorFunction(t->device, raytrace_on_embree_error, NULL);
    t->objects = calloc((size_t)s->object_count, sizeof *t->objects);
    if (!t->objects)
        fprintf(stderr, "raytrace: out of memory for %d objects\n", s->object_count);
    bool area_light = false;
    for (int l = 0; l < s->light_count; l++)
        area_light = area_light || s->lights[l].radius > 0;
    bool cone_test = area_light && !t->trace_every_sample;
    if (!t->objects || !raytrace_build_scene(t) || (cone_test && !bvh_build(s, "raytrace", &t->casters)) ||
        !dump_frame_create(out, width, height, s, light_index)) {
        raytrace_release(t);
        return NULL;
    }
    t->casters_reach = bvh_reach(&t->casters);
    t->build_ms = (omp_get_wtime() - start) * 1e3;
    return t;
}

void raytrace_rows(raytrace_tracer *t, const int *rows, int count, dump_frame *out) {
    double start = omp_get_wtime();
#pragma omp parallel for schedule(dynamic)
    for (int r = 0; r < count; r++) {
        struct RTCIntersectContext primary;
        raytrace_shadow_context shadow = {.tracer = t};
        rtcInitIntersectContext(&primary);
        rtcInitIntersectContext(&shadow.embree);
        shadow.embree.filter = raytrace_confirm_occlusion;
        for (int x = 0; x < t->width; x++)
            raytrace_pixel(t, &primary, &shadow, x, rows[r], out);
    }
    t->trace_ms += (omp_get_wtime() - start) * 1e3;
}

bool raytrace_end(raytrace_tracer *t) {
    bool ok = rtcGetDeviceError(t->device) == RTC_ERROR_NONE;
    if (ok && t->verbose)
        fprintf(stderr, "raytrace: Embree %zd.%zd.%zd, %d threads; BVH built in %.1f ms, %dx%d traced in %.1f ms\n",
                rtcGetDeviceProperty(t->device, RTC_DEVICE_PROPERTY_VERSION_MAJOR),
                rtcGetDeviceProperty(t->device, RTC_DEVICE_PROPERTY_VERSION_MINOR),
                rtcGetDeviceProperty(t->device, RTC_DEVICE_PROPERTY_VERSION_PATCH), omp_get_max_threads(),
                t->build_ms, t->width, t->height, t->trace_ms);
    raytrace_release(t);
    return ok;
}

bool raytrace_render(const scene *s, int width, int height, int light_index, const raytrace_settings *settings,
                     dump_frame *out) {
    raytrace_tracer *t = raytrace_begin(s, width, height, light_index, settings, out);
    if (!t)
        return false;
    int *rows = malloc((size_t)height * sizeof *rows);
    if (!rows) {
        fprintf(stderr, "raytrace: out of memory for %d rows\n", height);
        raytrace_release(t);
        dump_frame_free(out);
        return false;
    }
    for (int y = 0; y < height; y++)
        rows[y] = y;
    int bands = !settings->progress ? 1 : height < RAYTRACE_PROGRESS_BANDS ? height : RAYTRACE_PROGRESS_BANDS;
    for (int b = 0, done = 0; b < bands; b++) {
        int end = (int)((long long)height * (b + 1) / bands);
        raytrace_rows(t, rows + done, end - done, out);
        done = end;
        if (settings->progress)
            settings->progress(done, height);
    }
    free(rows);
    bool ok = raytrace_end(t);
    if (!ok)
        dump_frame_free(out);
    return ok;
}

bool raytrace_available(void) { return true; }
