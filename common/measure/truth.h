/* truth: the ray-traced reference (raytrace.h) of a view that changes,
 * traced in a background thread, progressively, for compare mode: the
 * frame loop hands it each frame's view and takes what is traced so far,
 * and never waits for it.
 *
 *   truth t;
 *   truth_start(&t, width, height, &settings);
 *   each frame:  truth_request(&t, &scene, light);   the frame's view
 *                if (truth_take(&t, &shown)) ... shown.dump, shown.rows ...
 *   headless:    truth_wait(&t), then truth_take: the whole frame
 *   before the scene goes: truth_forget(&t); at the end truth_stop(&t).
 *
 * A request whose camera or lights differ from the last one (or another
 * light index) restarts the trace: the thread drops its frame between two
 * bands of rows and begins the new one; an equal request changes nothing.
 * The scene is copied at each new request (camera and lights); its objects
 * and meshes are shared, so they must not change until truth_forget.
 *
 * Rows come in TRUTH_PASSES interleaved passes (truth_row_order): every
 * 16th row first, then the rows halfway between those, and so on, so the
 * whole picture is there, coarse, after a 16th of the work and sharpens as
 * rows fill in. Each pixel's values are raytrace_render's exactly (the
 * trace is raytrace_begin / raytrace_rows / raytrace_end), so the finished
 * frame is the reference `build/raytrace` writes for that view; rows not
 * yet traced are "no surface" in the dump (dump.h), so shadowdiff compares
 * only what is traced.
 *
 * The thread traces with OpenMP like raytrace_render, so it shares the CPU
 * with the frame loop; on a failure (Embree, memory) raytrace prints its
 * line and the frame is `failed` until the next new request.
 *
 * Baked (a build that cannot trace: the web page): started with a folder
 * of baked truths (truth_bake.h), there is no thread; each new request is
 * answered at once with the truth baked for its view, complete, or with a
 * failed frame where none is (said once per truth_start).
 */
#ifndef TRUTH_H
#define TRUTH_H

#include <stdbool.h>
#include <threads.h>

#include "dump.h"
#include "raytrace.h"
#include "scene.h"

/* Rows in bands of height / TRUTH_BANDS: the thread looks for a newer
 * request between two bands, so a restart waits at most for one. */
#define TRUTH_BANDS 16
/* log2 of the first pass's row stride: 16. */
#define TRUTH_PASSES 5

/* What has been traced of one request, the caller's copy. */
typedef struct truth_frame {
    dump_frame dump; /* every array; rows not traced are "no surface" */
    int rows;        /* traced, of dump.height, in truth_row_order */
    long request;    /* the request it is of, counted from 1; 0: none yet */
    bool current;    /* of the latest request (the view asked for last) */
    bool complete;   /* current, and every row traced */
    bool failed;     /* the trace of that request failed (said on stderr) */
    double seconds;  /* from the request to the last row, when complete */
} truth_frame;

typedef struct truth {
    int width, height;
    raytrace_settings settings;
    int *row_order; /* truth_row_order's, height of them */
    thrd_t thread;
    mtx_t lock;
    cnd_t changed; /* a request or quit, for the thread; rows, for truth_wait */
    bool running;
    const char *baked_dir; /* baked: the truths' folder; NULL: traced */
    bool said_unbaked;     /* a view without a baked truth was said */
    /* under lock */
    bool quit;
    bool has_request; /* false at first and after truth_forget */
    bool busy;        /* the thread is tracing, its frame in use */
    scene requested;  /* camera and lights of the latest request */
    int requested_light;
    long request_count; /* requests that restarted the trace */
    long tracing;       /* the request the thread's frame is of; 0: none */
    dump_frame traced;  /* the thread's frame: rows [0, traced_rows) of the order are done */
    int traced_rows;
    bool trace_failed;
    double trace_seconds;
    /* the thread's own */
    scene job;
} truth;

/* The order rows are traced in: y = 0, 16, 32, ..., then 8, 24, ...,
 * then 4, 12, ..., 2, ..., 1, 3, ...: each row exactly once. */
void truth_row_order(int height, int *order);

/* Starts the thread for frames of width x height (settings as
 * raytrace_render's; scene_name is kept as a pointer), or with
 * `baked_dir` (kept as a pointer) no thread: the truths baked there.
 * False after one line on stderr. */
bool truth_start(truth *t, int width, int height, const raytrace_settings *settings, const char *baked_dir);
void truth_request(truth *t, const scene *s, int light_index);
/* Copies into `shown` (zero it before the first call; truth_frame_free
 * at the end) what is new since its last take: returns whether anything
 * changed. */
bool truth_take(truth *t, truth_frame *shown);
/* Until the latest request is traced (or failed); meanwhile the
 * settings' progress, where given, hears the rows traced of it as they
 * grow, the last count always (from this thread, not the tracing one). */
void truth_wait(truth *t);
/* Drops the request and waits until the thread holds nothing of the scene
 * (before it changes or is freed); the next request starts afresh. */
void truth_forget(truth *t);
void truth_stop(truth *t);
void truth_frame_free(truth_frame *f);

#endif
