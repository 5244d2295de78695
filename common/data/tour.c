/* tour: loads the tour files described in tour.h. */
#include "tour.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "json.h"
#include "path.h"

/* A tour is a page of text: anything larger is the wrong file. */
#define TOUR_MAX_FILE_SIZE (1u << 20)

static const char *const tour_keys[] = {"title", "steps", NULL};
static const char *const tour_step_keys[] = {"scene", "technique", "flags", "caption", "seconds",
                                             "motion", "frame", NULL};

/* An optional or required string into a fixed buffer, which it must fit. */
static bool tour_read_text(const char *file, const cJSON *object, const char *where, const char *key, bool required,
                           char *out, size_t size) {
    const char *text = NULL;
    if (!json_read_string(file, object, where, key, required, &text))
        return false;
    if (text && snprintf(out, size, "%s", text) >= (int)size)
        return json_fail(file, where, key, "longer than %zu characters", size - 1);
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

static bool tour_read_step(const char *file, const cJSON *json, const char *where, tour_step *s) {
    if (!cJSON_IsObject(json))
        return json_fail(file, where, NULL, "expected an object, got %s", json_kind(json));
    int frame = -1; /* absent: the last */
    if (!json_check_keys(file, json, where, tour_step_keys) || !tour_read_scene(file, json, where, s) ||
        !tour_read_text(file, json, where, "technique", true, s->technique, sizeof s->technique) ||
        !tour_read_text(file, json, where, "flags", false, s->flags, sizeof s->flags) ||
        !tour_read_text(file, json, where, "caption", false, s->caption, sizeof s->caption) ||
        !tour_read_seconds(file, json, where, s) || !tour_read_motion(file, json, where, s) ||
        !json_read_int(file, json, where, "frame", &frame))
        return false;
    if (cJSON_GetObjectItemCaseSensitive(json, "frame") && (frame < 0 || frame >= s->frame_count))
        return json_fail(file, where, "frame", "must be a frame of the step, 0 to %d (got %d)", s->frame_count - 1,
                         frame);
    s->shown_frame = frame >= 0 ? frame : s->frame_count - 1;
    return true;
}

static bool tour_read_root(const char *file, const cJSON *root, tour *t) {
    if (!cJSON_IsObject(root))
        return json_fail(file, "", NULL, "expected an object, got %s", json_kind(root));
    const cJSON *steps;
    if (!json_check_keys(file, root, "", tour_keys) ||
        !tour_read_text(file, root, "", "title", true, t->title, sizeof t->title) ||
        !json_lookup(file, root, "", "steps", true, &steps))
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
        if (!tour_read_step(file, entry, where, &t->steps[t->step_count]))
            return false;
        t->step_count++;
    }
    return true;
}

bool tour_load(tour *t, const char *path) {
    *t = (tour){0};
    cJSON *root = json_load(path, TOUR_MAX_FILE_SIZE);
    bool loaded = root && tour_read_root(path, root, t);
    cJSON_Delete(root);
    return loaded;
}
