/* truth: see truth.h. The thread and the frame loop share one lock: the
 * thread writes rows of its frame outside it, but only rows it has not
 * published yet (traced_rows counts the published), and the frame loop
 * reads only published rows, under the lock; everything else changes
 * under the lock. */
#include "truth.h"

#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "truth_bake.h"

void truth_row_order(int height, int *order) {
    int n = 0;
    for (int pass = 0; pass < TRUTH_PASSES; pass++) {
        int stride = 1 << (TRUTH_PASSES - 1 - pass);
        /* The first pass takes rows 0, 16, ...; each later one the rows
         * halfway between the earlier passes' rows. */
        int first = pass == 0 ? 0 : stride;
        int step = pass == 0 ? stride : 2 * stride;
        for (int y = first; y < height; y += step)
            order[n++] = y;
    }
}

static double truth_now(void) {
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* Whether the camera and lights of a and b are the same (the camera's
 * padding left out). */
static bool truth_same_view(const scene *a, const scene *b) {
    return a->objects == b->objects && a->light_count == b->light_count &&
           memcmp(&a->camera, &b->camera, offsetof(scene_camera, reversed_depth)) == 0 &&
           a->camera.reversed_depth == b->camera.reversed_depth &&
           memcmp(a->lights, b->lights, (size_t)a->light_count * sizeof *a->lights) == 0;
}

static int truth_band_rows(const truth *t) { return (t->height + TRUTH_BANDS - 1) / TRUTH_BANDS; }

/* One request's trace; called and returning with the lock held. */
static void truth_trace(truth *t, long request) {
    t->job = t->requested;
    int light = t->requested_light;
    t->busy = true;
    mtx_unlock(&t->lock);
    double start = truth_now();
    dump_frame frame;
    raytrace_tracer *tracer = raytrace_begin(&t->job, t->width, t->height, light, &t->settings, &frame);
    mtx_lock(&t->lock);
    if (!tracer) {
        t->trace_failed = true;
        t->busy = false;
        return;
    }
    t->traced = frame;
    bool dropped = false;
    for (int done = 0; done < t->height;) {
        if ((dropped = t->quit || t->request_count != request))
            break;
        int band = t->height - done < truth_band_rows(t) ? t->height - done : truth_band_rows(t);
        mtx_unlock(&t->lock);
        raytrace_rows(tracer, t->row_order + done, band, &t->traced);
        mtx_lock(&t->lock);
        t->traced_rows = done += band;
        cnd_broadcast(&t->changed);
    }
    mtx_unlock(&t->lock);
    bool ok = raytrace_end(tracer);
    mtx_lock(&t->lock);
    t->trace_failed = !ok;
    if (ok && !dropped)
        t->trace_seconds = truth_now() - start;
    t->busy = false;
}

static int truth_thread(void *argument) {
    truth *t = argument;
    mtx_lock(&t->lock);
    for (;;) {
        while (!t->quit && t->tracing == t->request_count)
            cnd_wait(&t->changed, &t->lock);
        if (t->quit)
            break;
        long request = t->tracing = t->request_count;
        dump_frame_free(&t->traced);
        t->traced_rows = 0;
        t->trace_failed = false;
        t->trace_seconds = 0;
        if (t->has_request)
            truth_trace(t, request);
        cnd_broadcast(&t->changed);
    }
    mtx_unlock(&t->lock);
    return 0;
}

/* The baked truth of the latest request as the thread's finished frame,
 * or a failed one; called with the lock held. */
static void truth_find_baked(truth *t) {
    dump_frame_free(&t->traced);
    t->tracing = t->request_count;
    t->job = t->requested;
    truth_bake_found found =
        truth_bake_find(t->baked_dir, &t->job, t->width, t->height, t->requested_light, &t->settings, &t->traced);
    t->traced_rows = found == TRUTH_BAKE_FOUND ? t->height : 0;
    t->trace_failed = found != TRUTH_BAKE_FOUND;
    if (found == TRUTH_BAKE_NONE && !t->said_unbaked)
        fprintf(stderr,
                "truth: %s: no truth is baked in %s for this view (light %d, %dx%d): only loaded views are "
                "baked\n",
                t->settings.scene_name ? t->settings.scene_name : "the scene", t->baked_dir, t->requested_light,
                t->width, t->height);
    t->said_unbaked = t->said_unbaked || found == TRUTH_BAKE_NONE;
}

bool truth_start(truth *t, int width, int height, const raytrace_settings *settings, const char *baked_dir) {
    *t = (truth){.width = width, .height = height, .settings = *settings, .baked_dir = baked_dir};
    t->row_order = malloc((size_t)height * sizeof *t->row_order);
    if (!t->row_order) {
        fprintf(stderr, "truth: out of memory for %d rows\n", height);
        return false;
    }
    truth_row_order(height, t->row_order);
    if (mtx_init(&t->lock, mtx_plain) != thrd_success || cnd_init(&t->changed) != thrd_success ||
        (!baked_dir && thrd_create(&t->thread, truth_thread, t) != thrd_success)) {
        fprintf(stderr, "truth: cannot start the reference's thread\n");
        free(t->row_order);
        return false;
    }
    t->running = true;
    return true;
}

void truth_request(truth *t, const scene *s, int light_index) {
    mtx_lock(&t->lock);
    if (!t->has_request || t->requested_light != light_index || !truth_same_view(&t->requested, s)) {
        t->requested = *s;
        t->requested_light = light_index;
        t->has_request = true;
        t->request_count++;
        if (t->baked_dir)
            truth_find_baked(t);
        cnd_broadcast(&t->changed);
    }
    mtx_unlock(&t->lock);
}

/* Row y of every array of `from` into `to` (the same size). */
static void truth_copy_row(const dump_frame *from, dump_frame *to, int y) {
    size_t first = (size_t)y * (size_t)from->width, n = (size_t)from->width;
    memcpy(to->visibility + first, from->visibility + first, n * sizeof *to->visibility);
    memcpy(to->depth + first, from->depth + first, n * sizeof *to->depth);
    memcpy(to->ids + first, from->ids + first, n * sizeof *to->ids);
    memcpy(to->normal + 3 * first, from->normal + 3 * first, 3 * n * sizeof *to->normal);
    memcpy(to->position + 3 * first, from->position + 3 * first, 3 * n * sizeof *to->position);
    memcpy(to->color + 4 * first, from->color + 4 * first, 4 * n);
}

bool truth_take(truth *t, truth_frame *shown) {
    mtx_lock(&t->lock);
    bool changed = false;
    if (shown->request != t->tracing) {
        /* Another request's frame: begin the copy afresh. */
        truth_frame_free(shown);
        shown->request = t->tracing;
        changed = true;
    }
    /* The thread's frame exists once its BVH is built, maybe after the
     * request was taken up. */
    if (!shown->dump.width && !shown->failed && t->traced.width &&
        !dump_frame_create(&shown->dump, t->width, t->height, &t->job, t->traced.light_index))
        shown->failed = true;
    if (shown->dump.width) {
        for (int k = shown->rows; k < t->traced_rows; k++)
            truth_copy_row(&t->traced, &shown->dump, t->row_order[k]);
        changed = changed || shown->rows != t->traced_rows;
        shown->rows = t->traced_rows;
    }
    bool current = t->has_request && shown->request == t->request_count;
    bool complete = current && !t->busy && !t->trace_failed && shown->rows == t->height;
    bool failed = shown->failed || t->trace_failed;
    changed = changed || current != shown->current || complete != shown->complete || failed != shown->failed;
    shown->current = current;
    shown->complete = complete;
    shown->failed = failed;
    shown->seconds = t->trace_seconds;
    mtx_unlock(&t->lock);
    return changed;
}

void truth_wait(truth *t) {
    mtx_lock(&t->lock);
    int shown = -1; /* the rows last handed to the settings' progress */
    for (;;) {
        if (t->settings.progress && t->has_request && t->tracing == t->request_count && t->traced_rows != shown) {
            shown = t->traced_rows;
            t->settings.progress(shown, t->height);
        }
        if (!t->has_request || (!t->busy && t->tracing == t->request_count))
            break;
        cnd_wait(&t->changed, &t->lock);
    }
    mtx_unlock(&t->lock);
}

void truth_forget(truth *t) {
    mtx_lock(&t->lock);
    t->has_request = false;
    t->request_count++;
    if (t->baked_dir) {
        dump_frame_free(&t->traced);
        t->traced_rows = 0;
        t->tracing = t->request_count;
    }
    cnd_broadcast(&t->changed);
    while (t->busy || t->tracing != t->request_count)
        cnd_wait(&t->changed, &t->lock);
    mtx_unlock(&t->lock);
}

void truth_stop(truth *t) {
    if (!t->running)
        return;
    mtx_lock(&t->lock);
    t->quit = true;
    cnd_broadcast(&t->changed);
    mtx_unlock(&t->lock);
    if (!t->baked_dir)
        thrd_join(t->thread, NULL);
    cnd_destroy(&t->changed);
    mtx_destroy(&t->lock);
    dump_frame_free(&t->traced);
    free(t->row_order);
    *t = (truth){0};
}

void truth_frame_free(truth_frame *f) {
    dump_frame_free(&f->dump);
    *f = (truth_frame){0};
}
