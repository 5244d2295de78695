/* raytrace: the ray-traced ground truth every shadow technique is measured
 * against (Embree 3 on the CPU), filling the same per-pixel dump (dump.h)
 * the raster programs write.
 *
 *   raytrace_settings settings = {.light_samples = 256};
 *   dump_frame frame;
 *   if (raytrace_render(&scene, 1280, 720, 0, &settings, &frame)) {
 *       ... frame.visibility, frame.color ...
 *       dump_frame_free(&frame);
 *   }
 *
 * raytrace_render says what it computes, pixel by pixel, and how it
 * fails.
 */
#ifndef RAYTRACE_H
#define RAYTRACE_H

#include <stdbool.h>
#include "dump.h"
#include "scene.h"

#define RAYTRACE_DEFAULT_LIGHT_SAMPLES 256
#define RAYTRACE_MAX_LIGHT_SAMPLES 65536
/* How near a plane must pass to a shadow ray's start to be the surface it
 * leaves, in float ulps of the start's coordinates from the eye (see
 * raytrace.c). */
#define RAYTRACE_SURFACE_ULPS 8.0

typedef struct raytrace_settings {
    int light_samples; /* per pixel and area light; 0 means RAYTRACE_DEFAULT_LIGHT_SAMPLES */
    /* An area light's samples traced at every pixel, even where no caster
     * can block them (raytrace.c, raytrace_cone_clear): the same dumps,
     * slower; the tests' proof that the skip changes nothing. */
    bool trace_every_sample;
    bool verbose;
    const char *scene_name; /* for messages (the scene file); NULL: "the scene" */
    /* NULL, or called with the rows done so far after each of
     * RAYTRACE_PROGRESS_BANDS bands (at most one a row; raytrace_render,
     * and truth_wait while it waits, truth.h): the picture is the same. */
    void (*progress)(int rows_done, int rows);
} raytrace_settings;
#define RAYTRACE_PROGRESS_BANDS 50

/* What raytrace_render computes, pixel by pixel:
 *   camera    one primary ray through the centre of each pixel of the
 *             raster camera (the view and projection camera_view_compute
 *             makes with aspect W/H), between its near and far planes, so
 *             it sees what the rasterizer sees; built in double from the
 *             camera's position, target, up and fov, so any near/far ratio
 *             works and the framing does not depend on how far the scene
 *             is from the origin. The scene is traced relative to the eye
 *             (see raytrace.c); the dump is in world units as everywhere.
 *   surface   the dump's normal is the triangle's own (face) normal turned
 *             towards the eye; the shading normal is lit.frag's: the
 *             vertex normals interpolated, through the inverse transpose of
 *             the model matrix, negated on a back face.
 *   colour    shaders/lighting.glsl exactly: albedo * (ambient + sum over
 *             lights of visibility * colour * intensity * max(N.L, 0) *
 *             spot * window), spot = smoothstep(cos outer, cos inner, cos
 *             of the angle off the axis), window = the light's range window
 *             (scene_light_range_window); clamped, rounded to 8 bits as GL
 *             does.
 *             Every light's visibility is used; the background is
 *             SCENE_BACKGROUND.
 *   visibility of light `light_index` (the others only shade):
 *             radius 0: one shadow ray, 0 or 1. radius > 0, an area light:
 *             the fraction of `light_samples` shadow rays that get through
 *             (stratified, with jitter hashed from the pixel: the same call
 *             gives the same frame). A point or spot light is then a sphere
 *             of that radius, sampled as the disk of that radius facing the
 *             shaded point; a directional light's radius is the angular
 *             radius (degrees) of the cone of directions it comes from.
 *             A spot light reaches nothing outside its outer cone, a light
 *             with a range nothing beyond it (visibility 0 there, as in
 *             the raster capture). Objects with
 *             "casts": false block no light; those with "receives": false
 *             are never in shadow.
 *
 * Shadow rays start at the visible point itself, with no offset, so that
 * the shadow's edge is exact at any angle of the light; a plane within
 * RAYTRACE_SURFACE_ULPS float ulps of the point's coordinates (from the
 * eye) is the surface the ray leaves, never an occluder. A ray stops as
 * many ulps of the light's short of it; every hit Embree finds on it is
 * confirmed in double. Nothing depends on the scene's size (a huge ground
 * or sky sphere): see raytrace.c.
 *
 * Rows are traced in parallel with OpenMP. raytrace_render creates the
 * dump (dump_frame_create) and returns true; on failure (an invalid camera,
 * Embree, memory) it prints one line "raytrace: problem" (naming
 * settings->scene_name for the camera) and returns false with nothing to
 * free. No ray it hands Embree is invalid, whatever the scene. With
 * `verbose`, it prints the Embree version, the thread count and where the
 * time went on stderr. */
bool raytrace_render(const scene *s, int width, int height, int light_index, const raytrace_settings *settings,
                     dump_frame *out);

/* The same frame in parts, for a caller that shows it as it comes
 * (compare mode's truth, truth.h). raytrace_begin checks the arguments,
 * prepares the camera and lights, builds the BVH and creates the dump
 * (every pixel "no surface"), or prints one line and returns NULL with
 * nothing to free; `s` must stay as it is until raytrace_end.
 * raytrace_rows traces the rows listed (in parallel), in any order and
 * over any number of calls: a pixel's values depend on that pixel alone,
 * so the finished dump is raytrace_render's, byte for byte. raytrace_end
 * releases the tracer (not the dump) and returns false after printing
 * Embree's error, if it reported one. */
typedef struct raytrace_tracer raytrace_tracer;
/* Whether this build traces: false in the web build, whose raytrace_*
 * functions each fail with one line (Embree is native only). */
bool raytrace_available(void);
raytrace_tracer *raytrace_begin(const scene *s, int width, int height, int light_index,
                                const raytrace_settings *settings, dump_frame *out);
void raytrace_rows(raytrace_tracer *t, const int *rows, int count, dump_frame *out);
bool raytrace_end(raytrace_tracer *t);

#endif
