/* technique_host: the frame's owner (the app, the benchmark), which runs
 * one technique on one scene under the skips and works out, for each
 * frame, what the technique need not do and what changed since its last
 * frame (technique.h's technique_frame, skips.h's skips).
 */
#ifndef TECHNIQUE_HOST_H
#define TECHNIQUE_HOST_H

#include "technique.h"

/* The frames the hidden-caster skip sleeps after a frame in which it
 * culled, narrowed and hid nothing: the read-back then costs without
 * saving (a scene of a few casters and objects, all in view and in
 * light, under a map). It never changes a decision, so it may sleep and
 * wake as it likes. */
#define TECHNIQUE_HOST_HIDDEN_RETRY_FRAMES 30

/* The corners of the part of every receiver's box of `s` inside the
 * frustum of `view`, at most max_points; returns how many (the frame's
 * receivers). */
int technique_host_receiver_points(const scene *s, const camera_view *view, float (*points)[3], int max_points);

/* The frame's owner (the app, the benchmark): one technique on one scene,
 * the skips it runs under, and what the last frame saw, so that each frame
 * tells the technique what changed. */
typedef struct technique_host {
    const technique *technique;
    render_scene *gpu;
    const render_skips *skips;
    skips_counts counts; /* the last frame's */
    int objects_in_view; /* the last frame's, from render_cull_view */
    bool started;        /* a frame was rendered since technique_host_start */
    mat4 last_view_projection;
    scene_light last_lights[SCENE_MAX_LIGHTS];
    float receivers[SKIPS_MAX_RECEIVER_POINTS][3];
    float fit_receivers[SKIPS_MAX_RECEIVER_POINTS][3]; /* fit_view's */
    skips_seen seen;
    /* Frames left in which technique_see reads nothing: the last read
     * saved nothing (TECHNIQUE_HOST_HIDDEN_RETRY_FRAMES). */
    int hidden_idle;
    /* The frames' light_points (technique_frame): the window's
     * TECHNIQUE_HOST_PROGRESSIVE_POINTS, else 0; a frame of one light's
     * visibility (visibility_of) takes every point. */
    int light_points;
    bool counters;         /* the frames' counters (technique_frame): the caller's */
    bool settings_changed; /* since the last frame (technique_host_settings_changed) */
} technique_host;

/* The area light's points a stencil technique adds per frame in the
 * window: a hard light's cost, so that sampling one never slows a frame
 * below the hard technique's; the picture converges over as many frames
 * as the light has points while nothing moves. */
#define TECHNIQUE_HOST_PROGRESSIVE_POINTS 1

/* technique_init of t on gpu, under skips; the next frame is its first. */
bool technique_host_start(technique_host *h, const technique *t, render_scene *gpu, const render_skips *skips);
/* The technique's destroy; frees what the host kept. */
void technique_host_stop(technique_host *h);
/* One of the technique's settings changed (its key in the window): the
 * next frame says so (technique_changes.settings). */
void technique_host_settings_changed(technique_host *h);
/* One frame: the view culled (render_cull_view), the lights that reach it,
 * the receivers it sees, what changed since the last frame, then
 * technique_render_frame. The caller has set gpu->scene's lights.
 * fit_view: NULL, or the camera the shadow maps are fitted to instead
 * (technique_frame.fit). */
bool technique_host_frame(technique_host *h, const camera_view *view, const camera_view *fit_view, target *target,
                          double time, int visibility_of);

#endif
