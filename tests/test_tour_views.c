/* Every lecture tour's views keep what each step is about in the picture
 * and clear of the HUD (assets/tours/), at each of view_sizes: each step
 * outside compare mode (whose HUD has a strip of its own above the cells)
 * names its subject, a box in its scene (tour.h), and the rectangle round
 * the box's eight corners, projected through the camera of the frame the
 * step shows, lies inside the picture and below or beside the panel of
 * the full HUD. That HUD is the window's: its text is what build/shadows
 * --tour --verbose says of each step ("hud: " lines, less the skips'
 * counters, which only F3 adds; the frame's number where the window says
 * its time), with the help's hint (APP_HELP_HINT) the window adds, its
 * panel hud_panel_size's,
 * the size hud_draw draws. The rectangle holds every pixel of the box, so
 * no pixel of the subject is hidden. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <glob.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "camera.h"
#include "hud.h"
#include "path.h"
#include "support.h"
#include "tour.h"

#define VIEWS_OUT "out/test/tour_views"
#define VIEWS_MAX_TOURS 16
#define VIEWS_MAX_SAID (1 << 20) /* what a tour's verbose run says on stderr */
#define VIEWS_HUD_PREFIX "hud: "
#define VIEWS_COUNTERS "\nskips" /* where the HUD's counters start (F3, --verbose) */
#define VIEWS_CORNERS 8

/* The lecture's sizes: a projector's and a full-HD screen's. */
static const int view_sizes[][2] = {{1280, 720}, {1920, 1080}};
enum { VIEW_SIZE_COUNT = sizeof view_sizes / sizeof *view_sizes };

static char tour_paths[VIEWS_MAX_TOURS][PATH_MAX];
static int tour_count;

/* A subject's place on screen, in pixels from the top-left corner. */
typedef struct views_rect {
    double left, top, right, bottom;
    bool behind; /* a corner at or behind the eye's plane: no rectangle */
} views_rect;

/* The box's rectangle seen from step s's camera at the frame it shows, in
 * a picture width x height of scene `sc`. */
static views_rect views_project(const scene *sc, const tour_step *s, const tour_box *box, int width, int height) {
    double time = s->shown_frame / (double)TOUR_FPS;
    scene_camera base = sc->camera, camera;
    tour_step_camera(s, time, sc->origin, &base);
    motion_camera(s->motion, time, &base, &camera);
    camera_view view;
    camera_view_compute(&camera, (float)width / (float)height, &view);
    views_rect r = {INFINITY, INFINITY, -INFINITY, -INFINITY, false};
    for (int c = 0; c < VIEWS_CORNERS; c++) {
        vec4 corner, clip;
        for (int k = 0; k < 3; k++)
            corner[k] = (float)(((c >> k) & 1 ? box->max[k] : box->min[k]) - sc->origin[k]);
        corner[3] = 1;
        glm_mat4_mulv(view.view_projection, corner, clip);
        if (!(clip[3] > 0)) {
            r.behind = true;
            return r;
        }
        double x = (clip[0] / clip[3] + 1) / 2 * width, y = (1 - clip[1] / clip[3]) / 2 * height;
        r.left = fmin(r.left, x);
        r.right = fmax(r.right, x);
        r.top = fmin(r.top, y);
        r.bottom = fmax(r.bottom, y);
    }
    return r;
}

/* The HUD's text of the step counted `step` of `count` (from 1) in what a
 * verbose tour run said, less the counters; false if it said none. */
static bool views_hud_text(const char *said, int step, int count, char *out, size_t size) {
    char first[64];
    snprintf(first, sizeof first, VIEWS_HUD_PREFIX "step %d/%d ", step, count);
    const char *at = strstr(said, first);
    if (!at)
        return false;
    size_t n = 0;
    out[0] = '\0';
    for (; strncmp(at, VIEWS_HUD_PREFIX, strlen(VIEWS_HUD_PREFIX)) == 0; at += strcspn(at, "\n") + 1) {
        const char *line = at + strlen(VIEWS_HUD_PREFIX);
        int length = (int)strcspn(line, "\n");
        n += (size_t)snprintf(out + n, size - n, "%s%.*s", n ? "\n" : "", length, line);
        assert_true(n < size);
    }
    char *counters = strstr(out, VIEWS_COUNTERS);
    if (counters)
        *counters = '\0';
    /* The window's HUD: its last line ends with the help's hint. */
    n = strlen(out);
    while (n > 0 && out[n - 1] == '\n')
        out[--n] = '\0';
    assert_true(n + strlen(APP_HELP_HINT) < size);
    strcat(out, APP_HELP_HINT);
    return true;
}

/* Tour `path`'s steps outside compare mode, rendered at width x height
 * headless with --verbose (in a tour of their own: a compare step would
 * trace its truth); every problem said, one line each, into `problems`
 * (empty: none), each step by its number in the tour file. */
static void views_check_tour(const char *path, int width, int height, char *problems, size_t size) {
    static tour t;
    static char said[VIEWS_MAX_SAID], hud[8192];
    assert_true(tour_load(&t, path));
    cJSON *root = support_read_json(path);
    cJSON *steps = cJSON_GetObjectItem(root, "steps"), *kept = cJSON_CreateArray();
    int kept_steps[TOUR_MAX_STEPS], kept_count = 0;
    for (int k = 0; k < t.step_count; k++) {
        if (t.steps[k].compare)
            continue;
        cJSON *step = cJSON_Duplicate(cJSON_GetArrayItem(steps, k), true);
        char scene[PATH_MAX];
        assert_non_null(realpath(t.steps[k].scene, scene));
        cJSON_DeleteItemFromObject(step, "scene");
        cJSON_AddStringToObject(step, "scene", scene);
        cJSON_AddItemToArray(kept, step);
        kept_steps[kept_count++] = k;
    }
    cJSON_DeleteItemFromObject(root, "steps");
    cJSON_AddItemToObject(root, "steps", kept);
    char stem[64], name[96], written[256], said_path[256], command[2048];
    assert_true(path_stem(path, stem, sizeof stem));
    snprintf(name, sizeof name, "%s-%dx%d", stem, width, height);
    support_write_json(root, VIEWS_OUT, name, written, sizeof written);
    cJSON_Delete(root);
    snprintf(said_path, sizeof said_path, VIEWS_OUT "/%s.txt", name);
    snprintf(command, sizeof command, "(%s --backend egl --size %dx%d --tour %s --verbose 2>%s)",
             support_program("shadows"), width, height, written, said_path);
    int status = support_run(command, said, sizeof said);
    char *text = path_read_text(said_path, VIEWS_MAX_SAID, NULL);
    if (status != 0)
        fail_msg("%s: exit %d: %s", command, status, text ? text : "");
    assert_non_null(text);
    size_t n = 0;
    problems[0] = '\0';
    for (int j = 0; j < kept_count; j++) {
        const tour_step *s = &t.steps[kept_steps[j]];
        char where[PATH_MAX + 64];
        snprintf(where, sizeof where, "%s step %d at %dx%d", path, kept_steps[j] + 1, width, height);
#define VIEWS_SAY(...) (n += n < size ? (size_t)snprintf(problems + n, size - n, __VA_ARGS__) : 0)
        if (!s->has_subject) {
            VIEWS_SAY("    %s: no \"subject\"\n", where);
            continue;
        }
        if (!views_hud_text(text, j + 1, kept_count, hud, sizeof hud))
            fail_msg("%s: no HUD said", where);
        int panel_width, panel_height;
        hud_panel_size(hud, width, height, 0, 0, &panel_width, &panel_height);
        static scene sc;
        assert_true(scene_load(&sc, s->scene));
        views_rect r = views_project(&sc, s, &s->subject, width, height);
        scene_free(&sc);
        if (r.behind) {
            VIEWS_SAY("    %s: the subject reaches behind the eye\n", where);
            continue;
        }
        printf("    %s: subject x %.0f..%.0f, y %.0f..%.0f; the HUD %dx%d\n", where, r.left, r.right, r.top, r.bottom,
               panel_width, panel_height);
        if (r.left < 0 || r.top < 0 || r.right > width || r.bottom > height)
            VIEWS_SAY("    %s: the subject (x %.0f..%.0f, y %.0f..%.0f) leaves the picture\n", where, r.left, r.right,
                      r.top, r.bottom);
        if (r.left < panel_width && r.top < panel_height)
            VIEWS_SAY("    %s: the subject (x %.0f..%.0f, y %.0f..%.0f) under the HUD (%dx%d at the top left)\n",
                      where, r.left, r.right, r.top, r.bottom, panel_width, panel_height);
#undef VIEWS_SAY
    }
    free(text);
}

/* Each tour at each size: every problem of every step said at once. */
static void test_tour_views(void **state) {
    const char *path = *state;
    static char problems[VIEW_SIZE_COUNT][16384];
    bool ok = true;
    for (int i = 0; i < VIEW_SIZE_COUNT; i++) {
        views_check_tour(path, view_sizes[i][0], view_sizes[i][1], problems[i], sizeof problems[i]);
        ok = ok && !problems[i][0];
    }
    if (!ok) {
        fprintf(stderr, "%s's views:\n%s%s", path, problems[0], problems[1]);
        fail_msg("%s: a step's subject hidden, outside the picture or not named (above)", path);
    }
}

/* Whether the line of `problems` about `step` says `what`. */
static bool views_said(const char *problems, const char *step, const char *what) {
    const char *line = strstr(problems, step);
    return line && strstr(line, what) && strstr(line, what) < line + strcspn(line, "\n");
}

/* The check fails where it should: a subject high in the view, under the
 * HUD; one left of the picture; a step without one. */
static void test_check_sees_a_hidden_subject(void **state) {
    (void)state;
    char problems[4096];
    views_check_tour("tests/data/tour_subject_hidden.json", view_sizes[0][0], view_sizes[0][1], problems,
                     sizeof problems);
    printf("%s", problems);
    assert_true(views_said(problems, "step 1 at 1280x720", "under the HUD"));
    assert_false(views_said(problems, "step 1 at 1280x720", "leaves the picture"));
    assert_true(views_said(problems, "step 2 at 1280x720", "leaves the picture"));
    assert_false(views_said(problems, "step 2 at 1280x720", "under the HUD"));
    assert_true(views_said(problems, "step 3 at 1280x720", "no \"subject\""));
}

int main(void) {
    glob_t found;
    if (glob("assets/tours/*.json", 0, NULL, &found) != 0 || found.gl_pathc > VIEWS_MAX_TOURS) {
        fprintf(stderr, "test_tour_views: no tours in assets/tours, or more than %d\n", VIEWS_MAX_TOURS);
        return 1;
    }
    static struct CMUnitTest tests[VIEWS_MAX_TOURS + 1];
    static char names[VIEWS_MAX_TOURS][64];
    size_t count = 0;
    tests[count++] = (struct CMUnitTest)cmocka_unit_test(test_check_sees_a_hidden_subject);
    for (size_t i = 0; i < found.gl_pathc; i++, tour_count++) {
        snprintf(tour_paths[tour_count], sizeof tour_paths[tour_count], "%s", found.gl_pathv[i]);
        char stem[64];
        path_stem(tour_paths[tour_count], stem, sizeof stem);
        snprintf(names[tour_count], sizeof names[tour_count], "%s", stem);
        tests[count++] = (struct CMUnitTest){
            .name = names[tour_count], .test_func = test_tour_views, .initial_state = tour_paths[tour_count]};
    }
    globfree(&found);
    return _cmocka_run_group_tests("tour views", tests, count, NULL, NULL);
}
