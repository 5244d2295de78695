/* tour: loads the tour files described in tour.h. */
#include "tour.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <cglm/cglm.h>

#include "json.h"
#include "path.h"

/* A tour is a page of text: anything larger is the wrong file. */
#define TOUR_MAX_FILE_SIZE (1u << 20)
/* Within this many frames of a whole frame the time is that frame's. */
#define TOUR_FRAME_SNAP 1e-6

static const char *const tour_keys[] = {"title", "steps", NULL};
static const char *const tour_step_keys[] = {"scene", "technique", "flags", "caption", "seconds", "motion",
                                             "frame", "camera",    "path",  "compare", "subject", NULL};
static const char *const tour_view_keys[] = {"position", "target", NULL};
static const char *const tour_box_keys[] = {"min", "max", NULL};

/* An optional or required string into a fixed buffer, which it must fit. */
static bool tour_read_text(const char *file, const cJSON *object, const char *where, const char *key, bool required,
                           char *out, size_t size) {
    const char *text = NULL;
    if (!json_read_string(file, object, where, key, required, &text))
        return false;
    if (text && snprintf(out, size, "%s", text) >= (int)size) {
        out[0] = '\0'; /* no cut text for the caller to check again */
        return json_fail(file, where, key, "longer than %zu characters", size - 1);
    }
    return true;
}

/* "scene", relative to the tour file's folder unless absolute. */
static bool tour_read_scene(const char *file, const cJSON *json, const char *where, tour_step *s) {
    char relative[PATH_MAX];
    if (!tour_read_text(file, json, where, "scene", true, relative, sizeof relative))
        return false;
    if (!path_beside(file, relative, s->scene, sizeof s->scene))
        return json_fail(file, where, "scene", "the path is too long");
    return true;
}

static bool tour_read_motion(const char *file, const cJSON *json, const char *where, tour_step *s) {
    const char *name = NULL;
    if (!json_read_string(file, json, where, "motion", false, &name))
        return false;
    if (!name)
        return true;
    for (int k = 0; motion_names[k]; k++) {
        if (strcmp(motion_names[k], name) == 0) {
            s->motion = (motion_kind)k;
            return true;
        }
    }
    char expected[128];
    json_join_names((const char *const *)motion_names, expected, sizeof expected);
    return json_fail(file, where, "motion", "unknown motion \"%s\" (expected %s)", name, expected);
}

static bool tour_read_seconds(const char *file, const cJSON *json, const char *where, tour_step *s) {
    const cJSON *item;
    s->seconds = TOUR_DEFAULT_SECONDS;
    if (!json_lookup(file, json, where, "seconds", false, &item))
        return false;
    if (item && !cJSON_IsNumber(item))
        return json_fail(file, where, "seconds", "expected a number, got %s", json_kind(item));
    if (item && !(item->valuedouble > 0 && item->valuedouble <= TOUR_MAX_SECONDS))
        return json_fail(file, where, "seconds", "must be above 0 and at most %g (got %g)", TOUR_MAX_SECONDS,
                         item->valuedouble);
    if (item)
        s->seconds = item->valuedouble;
    s->frame_count = (int)fmax(1, round(s->seconds * TOUR_FPS));
    return true;
}

/* One {"position", "target"} at where (steps[i].camera, steps[i].path[k]). */
static bool tour_read_view(const char *file, const cJSON *json, const char *where, tour_view *v) {
    if (!cJSON_IsObject(json))
        return json_fail(file, where, NULL, "expected an object, got %s", json_kind(json));
    if (!json_check_keys(file, json, where, tour_view_keys) ||
        !json_read_numbers(file, json, where, "position", v->position, 3) ||
        !json_read_numbers(file, json, where, "target", v->target, 3))
        return false;
    if (v->position[0] == v->target[0] && v->position[1] == v->target[1] && v->position[2] == v->target[2])
        return json_fail(file, where, "target", "must differ from position");
    return true;
}

/* "camera" or "path" (after "motion", which a path excludes). */
static bool tour_read_views(const char *file, const cJSON *json, const char *where, tour_step *s) {
    const cJSON *camera, *path;
    char inner[64];
    if (!json_lookup(file, json, where, "camera", false, &camera) ||
        !json_lookup(file, json, where, "path", false, &path))
        return false;
    if (path && camera)
        return json_fail(file, where, "path", "not with \"camera\": the path places the camera");
    if (path && motion_moves_camera(s->motion))
        return json_fail(file, where, "path", "not with \"motion\": \"%s\": the path moves the camera",
                         motion_names[s->motion]);
    if (camera) {
        snprintf(inner, sizeof inner, "%s.camera", where);
        s->view_count = 1;
        return tour_read_view(file, camera, inner, &s->views[0]);
    }
    if (!path)
        return true;
    if (!cJSON_IsArray(path))
        return json_fail(file, where, "path", "expected an array, got %s", json_kind(path));
    int count = cJSON_GetArraySize(path);
    if (count < TOUR_MIN_PATH_VIEWS || count > TOUR_MAX_PATH_VIEWS)
        return json_fail(file, where, "path", "expected %d to %d views, got %d", TOUR_MIN_PATH_VIEWS,
                         TOUR_MAX_PATH_VIEWS, count);
    const cJSON *entry;
    cJSON_ArrayForEach(entry, path) {
        snprintf(inner, sizeof inner, "%s.path[%d]", where, s->view_count);
        if (!tour_read_view(file, entry, inner, &s->views[s->view_count]))
            return false;
        s->view_count++;
    }
    return true;
}

/* "subject", if the step has one: a box whose max is nowhere below its
 * min. */
static bool tour_read_subject(const char *file, const cJSON *json, const char *where, tour_step *s) {
    const cJSON *subject;
    if (!json_lookup(file, json, where, "subject", false, &subject))
        return false;
    if (!subject)
        return true;
    char inner[64];
    snprintf(inner, sizeof inner, "%s.subject", where);
    if (!cJSON_IsObject(subject))
        return json_fail(file, where, "subject", "expected an object, got %s", json_kind(subject));
    tour_box *box = &s->subject;
    if (!json_check_keys(file, subject, inner, tour_box_keys) ||
        !json_read_numbers(file, subject, inner, "min", box->min, 3) ||
        !json_read_numbers(file, subject, inner, "max", box->max, 3))
        return false;
    for (int k = 0; k < 3; k++)
        if (box->max[k] < box->min[k])
            return json_fail(file, inner, "max", "below min (axis %d: %g < %g)", k, box->max[k], box->min[k]);
    s->has_subject = true;
    return true;
}

/* Every key of the step is read, each problem said in its line: a
 * file's problems all at once. The frame is checked against the seconds
 * where they were read (a motion that failed stays static, which refuses
 * no path). */
static bool tour_read_step(const char *file, const cJSON *json, const char *where, tour_step *s) {
    if (!cJSON_IsObject(json))
        return json_fail(file, where, NULL, "expected an object, got %s", json_kind(json));
    int frame = -1; /* absent: the last */
    bool ok = json_check_keys(file, json, where, tour_step_keys);
    ok = tour_read_scene(file, json, where, s) && ok;
    ok = tour_read_text(file, json, where, "technique", true, s->technique, sizeof s->technique) && ok;
    ok = tour_read_text(file, json, where, "flags", false, s->flags, sizeof s->flags) && ok;
    ok = tour_read_text(file, json, where, "caption", false, s->caption, sizeof s->caption) && ok;
    bool timed = tour_read_seconds(file, json, where, s);
    ok = tour_read_motion(file, json, where, s) && ok;
    bool framed = json_read_int(file, json, where, "frame", &frame);
    ok = tour_read_views(file, json, where, s) && ok;
    ok = json_read_bool(file, json, where, "compare", &s->compare) && ok;
    ok = tour_read_subject(file, json, where, s) && ok;
    if (timed && framed && cJSON_GetObjectItemCaseSensitive(json, "frame") && (frame < 0 || frame >= s->frame_count))
        framed = json_fail(file, where, "frame", "must be a frame of the step, 0 to %d (got %d)", s->frame_count - 1,
                           frame);
    s->shown_frame = frame >= 0 ? frame : s->frame_count - 1;
    return ok && timed && framed;
}

/* Every step is read, a step's problems not hiding the next one's. */
static bool tour_read_root(const char *file, const cJSON *root, tour *t) {
    if (!cJSON_IsObject(root))
        return json_fail(file, "", NULL, "expected an object, got %s", json_kind(root));
    const cJSON *steps;
    bool ok = json_check_keys(file, root, "", tour_keys);
    ok = tour_read_text(file, root, "", "title", true, t->title, sizeof t->title) && ok;
    if (!json_lookup(file, root, "", "steps", true, &steps))
        return false;
    if (!cJSON_IsArray(steps))
        return json_fail(file, "", "steps", "expected an array, got %s", json_kind(steps));
    int count = cJSON_GetArraySize(steps);
    if (count < 1 || count > TOUR_MAX_STEPS)
        return json_fail(file, "", "steps", "expected 1 to %d steps, got %d", TOUR_MAX_STEPS, count);
    const cJSON *entry;
    cJSON_ArrayForEach(entry, steps) {
        char where[32];
        snprintf(where, sizeof where, "steps[%d]", t->step_count);
        ok = tour_read_step(file, entry, where, &t->steps[t->step_count]) && ok;
        t->step_count++;
    }
    return ok;
}

bool tour_load(tour *t, const char *path) {
    *t = (tour){0};
    cJSON *root = json_load(path, TOUR_MAX_FILE_SIZE);
    bool loaded = root && tour_read_root(path, root, t);
    cJSON_Delete(root);
    return loaded;
}

tour_view tour_path_view(const tour_view *views, int count, double u) {
    double along = fmin(fmax(u, 0), 1) * (count - 1); /* fmax: a NaN u is the start */
    int segment = (int)fmin(floor(along), count - 2);
    double w = along - segment;
    w = w * w * (3 - 2 * w);
    const tour_view *a = &views[segment], *b = &views[segment + 1];
    tour_view out;
    /* (1 - w) a + w b rather than a + w (b - a): exact at both ends. */
    for (int k = 0; k < 3; k++) {
        out.position[k] = (1 - w) * a->position[k] + w * b->position[k];
        out.target[k] = (1 - w) * a->target[k] + w * b->target[k];
    }
    return out;
}

tour_view tour_step_view(const tour_step *s, double time) {
    if (!tour_step_has_path(s))
        return s->views[0];
    /* Frame i's time, i / TOUR_FPS, times TOUR_FPS lands an ulp off i for
     * some i (31, 62, ...): snapped back, frame i is exactly where the
     * path puts it, its last frame exactly the last view. */
    double frame = time * TOUR_FPS;
    if (fabs(frame - round(frame)) < TOUR_FRAME_SNAP)
        frame = round(frame);
    double u = s->frame_count > 1 ? frame / (s->frame_count - 1) : 1;
    return tour_path_view(s->views, s->view_count, u);
}

/* The view less the origin, as floats; false where a coordinate would
 * not fit one (a view far beyond a far-away origin). */
static bool tour_view_relative(const tour_view *v, const double origin[3], float position[3], float target[3]) {
    for (int k = 0; k < 3; k++) {
        double p = v->position[k] - origin[k], t = v->target[k] - origin[k];
        if (!(fabs(p) <= FLT_MAX && fabs(t) <= FLT_MAX))
            return false;
        position[k] = (float)p;
        target[k] = (float)t;
    }
    return true;
}

void tour_step_camera(const tour_step *s, double time, const double origin[3], scene_camera *camera) {
    if (s->view_count == 0)
        return;
    tour_view v = tour_step_view(s, time);
    /* It fits: tour_step_check_views passed every frame at the start. */
    tour_view_relative(&v, origin, camera->position, camera->target);
}

bool tour_step_check_views(const char *file, int k, const tour_step *s, const double origin[3],
                           const scene_camera *camera) {
    if (s->view_count == 0)
        return true;
    char where[32];
    snprintf(where, sizeof where, "steps[%d]", k);
    const char *key = tour_step_has_path(s) ? "path" : "camera";
    /* Every frame a headless run can render; the same arithmetic as
     * tour_step_camera, in float as the view matrix sees it. */
    int frames = tour_step_has_path(s) ? s->frame_count : 1;
    for (int i = 0; i < frames; i++) {
        tour_view v = tour_step_view(s, (double)i / TOUR_FPS);
        float position[3], target[3];
        if (!tour_view_relative(&v, origin, position, target))
            return json_fail(file, where, key, "frame %d lies too far from the scene's origin", i);
        vec3 view, side;
        glm_vec3_sub(target, position, view);
        if (!(glm_vec3_norm2(view) > 0))
            return json_fail(file, where, key, "at frame %d the position meets the target", i);
        glm_vec3_cross(view, (float *)camera->up, side);
        if (!(glm_vec3_norm2(side) > 0))
            return json_fail(file, where, key, "at frame %d the view looks along the scene's up", i);
    }
    return true;
}
