/* Tests of common/data/tour.c (tour files, good and bad; a step's camera
 * and its path's interpolation), of how build/shadows --tour checks a
 * tour's techniques, flags and views, and of what a step's caption is
 * measured against (technique_settings). Run from the repository root. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <GLFW/glfw3.h>

#include "registry.h"
#include "support.h"
#include "technique.h"
#include "tour.h"

#define TOUR_DATA "tests/data/"

static char err[4096];

/* Defaults where the file says nothing; the scene beside the tour file,
 * an absolute one as it is. */
static void test_good_tour(void **state) {
    (void)state;
    static tour t;
    assert_true(tour_load(&t, TOUR_DATA "tour_good.json"));
    assert_string_equal(t.title, "A test tour");
    const tour_step *a = &t.steps[0], *b = &t.steps[1];
    assert_string_equal(a->scene, TOUR_DATA "../../assets/scenes/simple.json");
    assert_string_equal(a->technique, "planar");
    assert_string_equal(a->flags, "");
    assert_string_equal(a->caption, "");
    assert_true(a->seconds == TOUR_DEFAULT_SECONDS);
    assert_int_equal(a->motion, MOTION_STATIC);
    assert_int_equal(a->frame_count, (int)(TOUR_DEFAULT_SECONDS * TOUR_FPS));
    assert_int_equal(a->shown_frame, a->frame_count - 1);
    assert_string_equal(b->scene, "/abs/scene.json");
    assert_string_equal(b->flags, "--warp uniform");
    assert_string_equal(b->caption, "uniform");
    assert_int_equal(b->motion, MOTION_CAMERA);
    assert_int_equal(b->frame_count, 30);
    assert_int_equal(b->shown_frame, 3);
    assert_int_equal(a->view_count, 0);
    assert_int_equal(b->view_count, 1);
    assert_false(tour_step_has_path(b));
    assert_true(b->views[0].position[1] == 2 && b->views[0].target[2] == -1e6);
    assert_false(a->has_subject);
    assert_true(b->has_subject);
    assert_true(b->subject.min[2] == -2 && b->subject.max[2] == 2.5);
    const tour_step *c = &t.steps[2];
    assert_int_equal(t.step_count, 3);
    assert_int_equal(c->motion, MOTION_LIGHT);
    assert_int_equal(c->view_count, 3);
    assert_true(tour_step_has_path(c));
    assert_true(c->views[1].position[0] == 5 && c->views[2].position[2] == -5 && c->views[1].target[1] == 1);
}

/* Each bad file fails with its one line, naming the step and the key. */
static void test_bad_tours(void **state) {
    (void)state;
    static const struct {
        const char *file, *line;
    } cases[] = {
        {"tour_unknown_key.json", "steps[1]: unknown key \"captoin\" (expected scene, technique, flags, caption, "
                                  "seconds, motion, frame, camera, path, compare or subject), did you mean "
                                  "\"caption\"?"},
        {"tour_bad_motion.json",
         "steps[0].motion: unknown motion \"orbit\" (expected static, light, camera, dolly, lamp or lamps)"},
        {"tour_bad_frame.json", "steps[0].frame: must be a frame of the step, 0 to 59 (got 60)"},
        {"tour_bad_seconds.json", "steps[0].seconds: expected a number, got a string"},
        {"tour_no_scene.json", "steps[0].scene: missing required field"},
        {"tour_no_steps.json", "steps: expected 1 to 32 steps, got 0"},
        {"tour_syntax_error.json", "2: JSON syntax error near '}'"},
        {"tour_path_and_camera.json", "steps[0].path: not with \"camera\": the path places the camera"},
        {"tour_path_and_camera_motion.json",
         "steps[1].path: not with \"motion\": \"camera\": the path moves the camera"},
        {"tour_path_one_view.json", "steps[0].path: expected 2 to 16 views, got 1"},
        {"tour_path_unknown_key.json", "steps[0].path[1]: unknown key \"fov\" (expected position or target)"},
        {"tour_camera_infinite.json", "steps[0].camera.position[1]: must be a finite number (got inf)"},
        {"tour_camera_at_target.json", "steps[0].camera.target: must differ from position"},
        {"tour_camera_short.json", "steps[0].camera.position: expected an array of 3 numbers"},
        {"tour_bad_subject.json", "steps[0].subject.max: below min (axis 1: 0.5 < 1)"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        static tour t;
        char path[256], expected[512];
        snprintf(path, sizeof path, TOUR_DATA "%s", cases[i].file);
        support_capture_stderr();
        bool loaded = tour_load(&t, path);
        const char *text = support_release_stderr();
        snprintf(expected, sizeof expected, "%s%s%s\n", path, cases[i].line[0] == '2' ? ":" : ": ", cases[i].line);
        if (loaded || strcmp(text, expected) != 0)
            fail_msg("%s: loaded %d, said \"%s\", expected \"%s\"", cases[i].file, loaded, text, expected);
    }
}

/* The problems of the file's steps, every one at once, each its line in
 * the steps' order: the file's own (tour_load), then with build/shadows
 * also what the program checks (techniques, their flags), each step's
 * after the file's. */
#define SEVERAL_ERRORS TOUR_DATA "tour_several_errors.json"
static const char *const file_errors[] = {
    SEVERAL_ERRORS ": steps[0]: unknown key \"captoin\" (expected scene, technique, flags, caption, seconds, motion, "
                   "frame, camera, path, compare or subject), did you mean \"caption\"?\n",
    SEVERAL_ERRORS
    ": steps[0].motion: unknown motion \"orbit\" (expected static, light, camera, dolly, lamp or lamps)\n",
    SEVERAL_ERRORS ": steps[1].seconds: expected a number, got a string\n",
    SEVERAL_ERRORS ": steps[2].frame: must be a frame of the step, 0 to 119 (got 999)\n",
    SEVERAL_ERRORS ": steps[3].scene: missing required field\n",
};
static const char *const program_errors[] = {
    SEVERAL_ERRORS ": steps[1].technique: unknown technique \"shadowvolumes\"",
    SEVERAL_ERRORS ": steps[2].flags: planar: unknown flag '--no-stencl', did you mean --no-stencil?",
    SEVERAL_ERRORS ": steps[3].flags: psm: --warp given twice, 'uniform' then 'lispsm'",
};
#define FILE_ERRORS (sizeof file_errors / sizeof *file_errors)
#define PROGRAM_ERRORS (sizeof program_errors / sizeof *program_errors)

static void test_every_problem_at_once(void **state) {
    (void)state;
    static tour t;
    support_capture_stderr();
    bool loaded = tour_load(&t, SEVERAL_ERRORS);
    const char *text = support_release_stderr();
    assert_false(loaded);
    char expected[2048] = "";
    for (size_t i = 0; i < FILE_ERRORS; i++)
        strncat(expected, file_errors[i], sizeof expected - strlen(expected) - 1);
    assert_string_equal(text, expected);
    assert_int_equal(t.step_count, 4); /* there for the caller's checks */
    assert_string_equal(t.steps[1].technique, "shadowvolumes");
    char command[512];
    snprintf(command, sizeof command, "%s --tour " SEVERAL_ERRORS " --screenshot out/test/never.png",
             support_program("shadows"));
    assert_int_equal(support_run(command, err, sizeof err), 1);
    assert_int_equal(support_count_lines(err), (int)(FILE_ERRORS + PROGRAM_ERRORS));
    const char *after = err;
    for (size_t i = 0; i < FILE_ERRORS; i++)
        assert_non_null(strstr(err, file_errors[i]));
    for (size_t i = 0; i < PROGRAM_ERRORS; i++) {
        const char *at = strstr(err, program_errors[i]);
        if (!at || at < after)
            fail_msg("expected \"%s\" after the file's lines and the step before's, in \"%s\"", program_errors[i],
                     err);
        after = at;
    }
}

static tour_view view(double px, double py, double pz, double tx, double ty, double tz) {
    return (tour_view){.position = {px, py, pz}, .target = {tx, ty, tz}};
}

static void assert_view_equal(tour_view actual, tour_view expected) {
    for (int k = 0; k < 3; k++)
        if (actual.position[k] != expected.position[k] || actual.target[k] != expected.target[k])
            fail_msg("coordinate %d: position %.17g (expected %.17g), target %.17g (expected %.17g)", k,
                     actual.position[k], expected.position[k], actual.target[k], expected.target[k]);
}

/* The ends bit for bit (numbers that a + w (b - a) would round off), the
 * views between at their smoothstep weights, clamped beyond either end. */
static void test_path_interpolation(void **state) {
    (void)state;
    const tour_view views[] = {view(0.1, 0.7, -3.3, 1e-3, 0.3, 7.9), view(2.9, -1.1, 0.3, 0.6, 0.2, -0.4),
                               view(-5, 4, 1, 1, 1, 1)};
    assert_view_equal(tour_path_view(views, 2, 0), views[0]);
    assert_view_equal(tour_path_view(views, 2, 1), views[1]);
    assert_view_equal(tour_path_view(views, 3, 1), views[2]);
    assert_view_equal(tour_path_view(views, 3, 0.5), views[1]); /* the middle view of three */
    assert_view_equal(tour_path_view(views, 3, -2), views[0]);
    assert_view_equal(tour_path_view(views, 3, 7), views[2]);
    assert_view_equal(tour_path_view(views, 3, 0.0 / 0.0), views[0]);
    /* Halfway along a segment smoothstep weighs both ends alike; a
     * quarter along, 3/16 - 2/64 = 0.15625 of the way (0.25 linearly). */
    tour_view half = tour_path_view(views, 2, 0.5), quarter = tour_path_view(views + 1, 2, 0.25);
    for (int k = 0; k < 3; k++) {
        assert_float_equal(half.position[k], (views[0].position[k] + views[1].position[k]) / 2, 1e-12);
        assert_float_equal(half.target[k], (views[0].target[k] + views[1].target[k]) / 2, 1e-12);
        double along = views[2].position[k] - views[1].position[k];
        assert_float_equal(quarter.position[k], views[1].position[k] + 0.15625 * along, 1e-12);
    }
    /* Gentle: the first of 60 frames moves a twentieth of a lerp's even
     * 1/59 of the way (3u^2 - 2u^3 at u = 1/59); a tenth is the bound. */
    double lerp_step = 1.0 / 59, moved = tour_path_view(views, 2, lerp_step).position[0] - views[0].position[0];
    assert_true(fabs(moved) < lerp_step * (views[1].position[0] - views[0].position[0]) / 10);
}

/* A step's path starts at frame 0 and ends on its last frame exactly
 * (also where i / TOUR_FPS * TOUR_FPS is not i: 31 frames), holds after;
 * a "camera" is the same at every time; and either lands less the
 * scene's origin in the camera, the rest of it kept. */
static void test_step_view_and_camera(void **state) {
    (void)state;
    tour_step s = {.frame_count = 31,
                   .view_count = 3,
                   .views = {view(0, 1, 5, 0, 0, 0), view(5, 1, 0, 0, 1, 0), view(0, 3, -5, 0, 0, 0)}};
    assert_view_equal(tour_step_view(&s, 0), s.views[0]);
    assert_view_equal(tour_step_view(&s, 15.0 / TOUR_FPS), s.views[1]);
    assert_view_equal(tour_step_view(&s, 30.0 / TOUR_FPS), s.views[2]);
    assert_view_equal(tour_step_view(&s, 1000), s.views[2]);
    const double origin[3] = {100, 0, -100};
    scene_camera camera = {.up = {0, 1, 0}, .fov_deg = 45, .near_plane = 0.1f, .far_plane = 100};
    tour_step_camera(&s, 15.0 / TOUR_FPS, origin, &camera);
    assert_true(camera.position[0] == -95 && camera.position[1] == 1 && camera.position[2] == 100);
    assert_true(camera.target[0] == -100 && camera.target[1] == 1 && camera.target[2] == 100);
    assert_true(camera.fov_deg == 45 && camera.up[1] == 1 && camera.far_plane == 100);
    s.view_count = 1;
    assert_view_equal(tour_step_view(&s, 12.5), s.views[0]);
    s.view_count = 0;
    scene_camera before = camera;
    tour_step_camera(&s, 0, origin, &camera);
    assert_memory_equal(&camera, &before, sizeof camera);
}

/* Against the scene: a view looking along its up, a path whose frame
 * meets its target, a view that no float holds once less the origin. */
static void test_step_views_against_the_scene(void **state) {
    (void)state;
    const double origin[3] = {0, 0, 0}, far_origin[3] = {-FLT_MAX, 0, 0};
    const scene_camera camera = {.up = {0, 1, 0}};
    tour_step down = {.frame_count = 60, .view_count = 1, .views = {view(0, 9, 0, 0, 0, 0)}};
    tour_step swap = {.frame_count = 3, .view_count = 2, .views = {view(0, 1, 4, 0, 1, 0), view(0, 1, 0, 0, 1, 4)}};
    tour_step fine = {.frame_count = 3, .view_count = 2, .views = {view(0, 1, 4, 0, 1, 0), view(4, 1, 0, 0, 1, 0)}};
    tour_step far = {.frame_count = 1, .view_count = 1, .views = {view(FLT_MAX, 1, 4, 0, 1, 0)}};
    const struct {
        const tour_step *step;
        const double *origin;
        const char *line;
    } cases[] = {
        {&down, origin, "t.json: steps[2].camera: at frame 0 the view looks along the scene's up\n"},
        {&swap, origin, "t.json: steps[2].path: at frame 1 the position meets the target\n"},
        {&far, far_origin, "t.json: steps[2].camera: frame 0 lies too far from the scene's origin\n"},
        {&fine, origin, ""},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        support_capture_stderr();
        bool good = tour_step_check_views("t.json", 2, cases[i].step, cases[i].origin, &camera);
        const char *text = support_release_stderr();
        if (good != !cases[i].line[0] || strcmp(text, cases[i].line) != 0)
            fail_msg("case %zu: good %d, said \"%s\", expected \"%s\"", i, good, text, cases[i].line);
    }
}

/* A technique not in the registry, or flags it does not take, stop the
 * run before it opens a context: exit 1, the step named. So do views the
 * step's scene cannot show, when the step starts. */
static void test_tour_checks_techniques_and_flags(void **state) {
    (void)state;
    static const struct {
        const char *file, *line;
    } cases[] = {
        {"tour_unknown_technique.json", "steps[1].technique: unknown technique \"shadowvolumes\""},
        {"tour_bad_flags.json", "steps[0].flags: planar: unknown flag '--no-stencl'"},
        {"tour_camera_along_up.json", "steps[1].camera: at frame 0 the view looks along the scene's up"},
        {"tour_path_meets_target.json", "steps[0].path: at frame 1 the position meets the target"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char command[512];
        snprintf(command, sizeof command, "%s --tour " TOUR_DATA "%s --screenshot out/test/never.png",
                 support_program("shadows"), cases[i].file);
        assert_int_equal(support_run(command, err, sizeof err), 1);
        if (!strstr(err, cases[i].line))
            fail_msg("%s: said \"%s\", expected \"%s\"", cases[i].file, err, cases[i].line);
    }
}

/* The tour CI records whole: every technique and a path, the tour a
 * lecture opens with. */
#define RECORDED_TOUR "assets/tours/overview.json"
/* Small, for time: a recording's time grows with its pixels, and the two
 * recordings and the ffprobe must stay short under the sanitizers too
 * (run.sh prints each program's time). */
#define RECORDED_WIDTH 160
#define RECORDED_HEIGHT 90

/* A real tour recorded headless: the video holds every step's frames
 * (the sum of their frame counts) at the size asked, and a second
 * recording writes the same bytes (frames are a function of their time,
 * a path's camera too). */
static void test_tour_records_every_frame(void **state) {
    (void)state;
    if (!support_have_command("ffmpeg") || !support_have_command("ffprobe")) {
        fprintf(stderr, "    ffmpeg is not installed here: skipped\n");
        return;
    }
    static tour t;
    assert_true(tour_load(&t, RECORDED_TOUR));
    int frames = 0;
    for (int k = 0; k < t.step_count; k++)
        frames += t.steps[k].frame_count;
    char command[2048];
    for (int run = 0; run < 2; run++) {
        snprintf(command, sizeof command,
                 "%s --backend egl --size %dx%d --tour " RECORDED_TOUR " --record out/test/tour_video_%d.mp4",
                 support_program("shadows"), RECORDED_WIDTH, RECORDED_HEIGHT, run);
        assert_int_equal(support_run(command, err, sizeof err), 0);
    }
    snprintf(command, sizeof command,
             "test \"$(ffprobe -v error -count_frames -select_streams v:0 -show_entries "
             "stream=nb_read_frames,width,height -of csv=p=0 out/test/tour_video_0.mp4)\" = %d,%d,%d && "
             "cmp -s out/test/tour_video_0.mp4 out/test/tour_video_1.mp4",
             RECORDED_WIDTH, RECORDED_HEIGHT, frames);
    assert_int_equal(support_run(command, err, sizeof err), 0);
}

static const technique *tour_technique(const char *name) {
    for (int i = 0; i < registry_technique_count; i++)
        if (strcmp(registry_techniques[i]->name, name) == 0)
            return registry_techniques[i];
    fail_msg("no technique %s", name);
    return NULL;
}

/* A step's settings against the live ones: each setting the keys moved
 * away from the step's is named with its value, whichever way it went,
 * and another technique by its name; back at the step's, nothing is. A
 * toggle whose feature the GL lacks changes nothing drawn: volumes' depth
 * bounds, never started here (no GL), so lacking. */
static void test_step_settings_changes(void **state) {
    (void)state;
    const technique *shadowmap = tour_technique("shadowmap"), *volumes = tour_technique("volumes");
    technique_settings step;
    char changes[TOUR_TEXT_MAX];
    assert_true(technique_apply_config(shadowmap, "--no-constant-bias --filter pcf3"));
    technique_settings_save(shadowmap, &step);
    assert_false(technique_settings_changes(&step, shadowmap, changes, sizeof changes));
    assert_string_equal(changes, "");
    assert_true(technique_press_key(shadowmap, GLFW_KEY_C)); /* the fix the step turned off, on */
    assert_true(technique_settings_changes(&step, shadowmap, changes, sizeof changes));
    assert_string_equal(changes, "constant-bias on");
    assert_true(technique_press_key(shadowmap, GLFW_KEY_F));
    assert_true(technique_settings_changes(&step, shadowmap, changes, sizeof changes));
    assert_string_equal(changes, "filter pcf5, constant-bias on");
    assert_true(technique_press_key(shadowmap, GLFW_KEY_C));
    assert_true(technique_settings_changes(&step, shadowmap, changes, sizeof changes));
    assert_string_equal(changes, "filter pcf5");
    assert_true(technique_settings_changes(&step, volumes, changes, sizeof changes));
    assert_string_equal(changes, "technique volumes");
    assert_true(technique_apply_config(shadowmap, "--filter pcf3 --no-constant-bias"));
    assert_false(technique_settings_changes(&step, shadowmap, changes, sizeof changes));
    assert_true(technique_apply_config(shadowmap, ""));

    technique_settings_save(volumes, &step);
    assert_true(technique_press_key(volumes, GLFW_KEY_B)); /* depth bounds */
    assert_false(technique_settings_changes(&step, volumes, changes, sizeof changes));
    assert_true(technique_press_key(volumes, GLFW_KEY_Z)); /* the mode */
    assert_true(technique_settings_changes(&step, volumes, changes, sizeof changes));
    assert_string_equal(changes, "mode zpass");
    assert_true(technique_apply_config(volumes, ""));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_good_tour),
        cmocka_unit_test(test_bad_tours),
        cmocka_unit_test(test_every_problem_at_once),
        cmocka_unit_test(test_path_interpolation),
        cmocka_unit_test(test_step_view_and_camera),
        cmocka_unit_test(test_step_views_against_the_scene),
        cmocka_unit_test(test_tour_checks_techniques_and_flags),
        cmocka_unit_test(test_tour_records_every_frame),
        cmocka_unit_test(test_step_settings_changes),
    };
    return cmocka_run_group_tests_name("tours", tests, NULL, NULL);
}
