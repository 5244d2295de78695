#include "app.h"

#include <GLFW/glfw3.h>
#include <glad/gl.h>
#ifdef __EMSCRIPTEN__
#include <emscripten/emscripten.h>
#endif
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "capture.h"
#include "compare.h"
#include "context.h"
#include "depth.h"
#include "flags.h"
#include "gallery_page.h"
#include "hud.h"
#include "image.h"
#include "json.h"
#include "motion.h"
#include "path.h"
#include "progress.h"
#include "raytrace.h"
#include "shader.h"
#include "shadowdiff.h"
#include "target.h"
#include "technique_host.h"
#include "tour.h"
#include "video.h"

#define APP_EXIT_RUNTIME 1
#define APP_HEADLESS_FPS MOTION_FRAME_RATE
#define APP_HEADLESS_FRAMES 1 /* without --frames */
#define APP_MAX_FRAMES 1000000
#define APP_MAX_TECHNIQUES 9 /* keys 1-9 */
#define APP_MAX_GALLERY_SCENES 256
#define APP_TECHNIQUE_FLAG_WIDTH 26 /* one column for every technique in --help */
#define APP_LIGHT_STEP_RAD 0.05f
#define APP_ORBIT_RAD_PER_PIXEL 0.008f
/* Where a build that cannot trace (the page) finds its baked truths, in
 * the project's folder (truth_bake.h; make web bakes them). */
#define APP_BAKED_TRUTHS "truths"
#define APP_NOTE_SECONDS 4.0 /* how long the HUD shows "saved PATH" */
#define APP_RESET_KEY GLFW_KEY_0
#define APP_COMPARE_KEY GLFW_KEY_A /* "against the truth": C is the constant bias */
#define APP_DEFAULT_WIDTH 1280
#define APP_DEFAULT_HEIGHT 720
/* In the page (the web build) the window differs in two things. Its HUD
 * shows no frame time: the browser draws a frame after the frame's code
 * has returned, and paces the frames to the display, so that its clock
 * would time neither the drawing nor the frame (make web-bench times the
 * page's frames). And Esc, which leaves the browser's fullscreen, does
 * not stop it: a page has nothing to quit to. */
#ifdef __EMSCRIPTEN__
#define APP_IN_PAGE 1
#else
#define APP_IN_PAGE 0
#endif

/* The program's state, all of it zero when app_main starts: the page
 * runs one program after another in the same instance (index.html). */
static struct {
    const char *program;
    const technique *const *techniques;
    int technique_count, current;
    bool technique_given;                                /* --technique: the gallery shows that one only */
    const char *technique_names[APP_MAX_TECHNIQUES + 1]; /* --technique's choices */
    /* flags (zero: the default) */
    int backend;           /* context_backend */
    int width, height;     /* 0 until parsed: not given, so APP_DEFAULT_* */
    bool size_given;       /* --size: else the page's canvas follows its box (app_window_size) */
    bool fullscreen;       /* --fullscreen: the window on the whole screen (F11 toggles it) */
    int frames;            /* 0: not given, so one frame headless or a window */
    bool verbose, animate; /* animate: --motion light, the space key flips it */
    bool quiet;            /* --quiet: no progress */
    bool hud_in_pictures;  /* --hud: headless pictures carry the HUD too */
    bool hud_compact;      /* --hud-compact, Tab: the caption, technique and settings only */
    bool hud_counters;     /* --verbose, F3: the skips' counters and the hybrid's rays on the HUD */
    bool no_hud;           /* --no-hud: none in the window (F12 then saves a clean picture) */
    bool flags_markdown;   /* --flags-markdown: print the tables, then exit */
    bool compare_on;       /* --compare, A, a tour's step: the technique beside the truth (compare.h) */
    bool compare_given;    /* --compare: every step of a tour too */
    int hud_scale;         /* --hud-scale: 0, from the framebuffer's height */
    int motion;            /* motion_kind */
    bool hold_fit;         /* --hold-fit: the maps fitted to the frame before's camera */
    bool glsl_es, webgl2;  /* --glsl-es, --webgl2: context_settings' */
    render_skips skips;
    const char *scene_path, *screenshot, *dump_dir, *shader_dir, *record_path;
    int light;
    int camera;                                      /* --camera: scene_path's (0 once Page Up/Down leaves it) */
    const char *gallery[1 + APP_MAX_GALLERY_SCENES]; /* DIR SCENE... */
    int gallery_count;
    char default_shader_dir[PATH_MAX], default_scene[PATH_MAX];
    char baked_truths[PATH_MAX]; /* APP_BAKED_TRUTHS, in the project */
    const char *bake_truths_dir; /* --bake-truths */
    char paged_scene[PATH_MAX];  /* Page Up/Down's: the scene_path then */
    const char *tour_path;       /* --tour */
    tour tour;
    int tour_step;                    /* the step shown */
    technique_settings step_settings; /* its technique's, as its flags set them */
    bool step_scene, step_technique;  /* what the step has loaded and started, for leaving it */
    bool tour_failed;                 /* a step did not start in the window */
    /* run */
    context ctx;
    target target;     /* the technique's frame: the picture, or compare mode's cell */
    compare comparing; /* while compare_on */
    scene scene;
    render_scene gpu;
    scene_light base_lights[SCENE_MAX_LIGHTS];   /* before motion */
    scene_camera base_camera;                    /* before motion: what dragging moves */
    scene_light loaded_lights[SCENE_MAX_LIGHTS]; /* as the scene file has them: the reset key's */
    scene_camera loaded_camera;
    technique_host host;
    double time;
    video video;               /* --record: open while recording */
    unsigned char *frame_rgba; /* the picture read back for the video */
    progress progress;         /* headless: the frames done (app_show_progress) */
    int frames_done, frames_total;
    /* window */
    bool show_help, dragging;
    double drag_x, drag_y, frame_ms;
    double last_frame;               /* glfwGetTime at the last frame's end */
    char note[PATH_MAX + 64];        /* the HUD's last line until note_until (glfwGetTime) */
    char screenshot_asked[PATH_MAX]; /* F12's picture, saved before the frame is swapped */
    double note_until;
} app;

/* The flags every program takes; each technique's parameters follow. */
static const flags_param app_flags[] = {
    {"backend", "context (auto: a window if interactive and a display\nis there, else EGL, else OSMesa)", 0,
     FLAGS_CHOICE, .index = &app.backend, .choices = context_backend_names},
    {"size",
     "framebuffer size (1280x720; without it the page's canvas\nfills the page, following the browser window's size)",
     0, FLAGS_SIZE, .width = &app.width, .height = &app.height},
    {"fullscreen", "the window on the whole screen (F11); a headless run\nrefuses it in one line", 0, FLAGS_SWITCH,
     .on = &app.fullscreen},
    {"scene", "scene file (assets/scenes/simple.json)", 0, FLAGS_STRING, .text = &app.scene_path,
     .value_name = "PATH"},
    {"frames", "render N frames headless (time i/60 s), then exit", 0, FLAGS_INT, .integer = &app.frames, .min = 1,
     .max = APP_MAX_FRAMES, .what = "a count"},
    {"screenshot", "save the last frame (implies headless)", 0, FLAGS_STRING, .text = &app.screenshot,
     .extension = ".png", .value_name = "PATH.png"},
    {"record",
     "every frame to a video through ffmpeg, 60 frames a second\n(frame i at i/60 s, in the window too: the same frames\ngive the same video)",
     0, FLAGS_STRING, .text = &app.record_path, .value_name = "PATH.mp4"},
    {"dump",
     "write what the last frame decided per pixel for one\nlight: visibility, depth, normal, position, ids, colour\n"
     "(see common/data/dump.h; implies headless)",
     0, FLAGS_STRING, .text = &app.dump_dir, .value_name = "DIR"},
    {"light", "the light --dump reports (0)", 0, FLAGS_INT, .integer = &app.light, .min = 0,
     .max = SCENE_MAX_LIGHTS - 1, .what = "a light index", .value_name = "K"},
    {"camera", "the --scene file's camera: a glTF file's in its order (0)", 0, FLAGS_INT, .integer = &app.camera,
     .min = 0, .max = SCENE_MAX_CAMERA_INDEX, .what = "a camera index", .value_name = "N"},
    {"shader-dir", "where the GLSL files are (shaders/ beside build/)", 0, FLAGS_STRING, .text = &app.shader_dir,
     .value_name = "DIR"},
    {"technique", "which technique to start with", 0, FLAGS_CHOICE, .index = &app.current,
     .choices = app.technique_names},
    {"motion",
     "what moves over time: nothing, the lights (about the\ncamera target), the camera (about its target), the\ncamera forward and back along its view (dolly),\nlight --light K alone on a small circle (lamp), or\nevery light on its own (lamps)",
     0, FLAGS_CHOICE, .index = &app.motion, .choices = motion_names},
    {"animate", "--motion light (space in the window)", 0, FLAGS_SWITCH, .on = &app.animate},
    {"hold-fit",
     "shadow maps fitted to the frame before's camera, drawn\nfrom this frame's: with --dump, what only the fit's\nmotion changes (the benchmark's shimmer)",
     0, FLAGS_SWITCH, .on = &app.hold_fit},
    {"skip",
     "no skips at all: every pass draws the whole scene,\nevery light, every caster, every frame anew; the same\npicture at the full cost",
     0, FLAGS_TOGGLE, .disabled = &app.skips.no_skip},
    {"view-cull", "camera passes draw objects outside the view too", GLFW_KEY_K, FLAGS_TOGGLE,
     .disabled = &app.skips.no_view_cull},
    {"light-reach", "lights that reach nothing visible render anyway", GLFW_KEY_U, FLAGS_TOGGLE,
     .disabled = &app.skips.no_light_reach},
    {"caster-cull", "every caster casts for every light, seen or not", GLFW_KEY_X, FLAGS_TOGGLE,
     .disabled = &app.skips.no_caster_cull},
    {"hidden-cull", "casters and objects that the depth pre-pass shows\nhidden are drawn anyway", GLFW_KEY_I,
     FLAGS_TOGGLE, .disabled = &app.skips.no_hidden_cull},
    {"cache", "shadow maps and volumes made again every frame", GLFW_KEY_J, FLAGS_TOGGLE,
     .disabled = &app.skips.no_cache},
    {"marked-pass",
     "costly pixels (hybrid's rays) shaded in the one pass\nwith the others, not marked for a pass of their own",
     GLFW_KEY_Q, FLAGS_TOGGLE, .disabled = &app.skips.no_marked_pass},
    {"gallery", "every technique (or --technique's) on every scene, to\nDIR/TECH_SCENE.png", 0, FLAGS_LIST,
     .items = app.gallery, .count = &app.gallery_count, .min = 2, .max = 1 + APP_MAX_GALLERY_SCENES,
     .what = "DIR then at least one scene file", .value_name = "DIR SCENE..."},
    {"tour",
     "play a tour file (assets/tours/): in the window Space, Right\nor Page Down the next step, Left or Page Up the previous;\n"
     "headless every step (with --screenshot P.png, step K's\nshown frame to P-K.png)",
     0, FLAGS_STRING, .text = &app.tour_path, .value_name = "FILE"},
    {"compare",
     "the technique beside the ray-traced truth of the same view\n(traced in the background, progressively) and the heat\n"
     "map of its errors, with legend and figures: four cells under\nthe HUD's caption strip (A); headless, the finished picture",
     0, FLAGS_SWITCH, .on = &app.compare_on},
    {"bake-truths",
     "in compare mode, also bake each finished truth into DIR\n(what compare mode shows where the build cannot trace:\nmake web bakes the tours' into the page)",
     0, FLAGS_STRING, .text = &app.bake_truths_dir, .value_name = "DIR"},
    {"hud",
     "headless pictures (--screenshot, --gallery) carry the HUD\ntoo, frame time replaced by the frame's number and time",
     0, FLAGS_SWITCH, .on = &app.hud_in_pictures},
    {"hud-scale",
     "pixels per font unit of the HUD's text (default: one per\n360 lines of the framebuffer, 2 at 720, 3 at 1080, less\nwhere the text would not fit)",
     0, FLAGS_INT, .integer = &app.hud_scale, .min = 1, .max = HUD_MAX_SCALE, .what = "a scale"},
    {"no-hud", "the window shows no HUD, so that F12 saves the picture alone", 0, FLAGS_SWITCH, .on = &app.no_hud},
    {"hud-compact", "the HUD's caption, technique and settings only (Tab)", 0, FLAGS_SWITCH, .on = &app.hud_compact},
    {"glsl-es",
     "compile every shader as GLSL ES 3.00, the browser's dialect\n(Mesa's desktop contexts take it); no technique has a\ngeometry shader (a dump's own pass keeps its desktop one)",
     0, FLAGS_SWITCH, .on = &app.glsl_es},
    {"webgl2",
     "--glsl-es, and nothing beyond WebGL 2's core: what it has\nonly as extensions (clip distances, depth clamp, polygon\nmode, clip control) off, so the browser's fallbacks run",
     0, FLAGS_SWITCH, .on = &app.webgl2},
    {"verbose",
     "print the backend and GL renderer, each model's triangles\nand bounds, the HUD's text of each tour step, each F12 and\nthe last frame, and at the end the technique's state line\nand the skips' lines; the skips' counters and the rays a\ntechnique casts on the HUD too (F3)",
     0, FLAGS_SWITCH, .on = &app.verbose},
    {"quiet",
     "no progress (headless, the frames done and the truth's rows\nwhile waiting for it, on stderr where it is a terminal)",
     0, FLAGS_SWITCH, .on = &app.quiet},
    {"flags-markdown", "print every flag and key as the README's markdown tables\n(make readme-flags), then exit", 0,
     FLAGS_SWITCH, .on = &app.flags_markdown},
    {.name = "help", .help = "this text", .kind = FLAGS_HELP},
};
enum { app_flag_count = sizeof app_flags / sizeof *app_flags };

/* The window's keys that are no flag's (the flags' own are in their
 * tables): --help's window lines and the README's table. */
typedef struct app_window_key {
    int letter;        /* the key app_on_key takes, shown as its letter */
    const char *label; /* or, without one, what is pressed */
    const char *help;
} app_window_key;

static const app_window_key app_window_keys[] = {
    {0, "drag", "orbit (above the target; with Shift also below)"},
    {0, "scroll", "zoom"},
    {0, "arrows", "move the light"},
    {0, "Space", "animate the light (--animate)"},
    {APP_RESET_KEY, NULL, "camera and lights back as the scene file has them"},
    {0, "1-" FLAGS_TEXT(APP_MAX_TECHNIQUES), "the technique of that number in --help's list"},
    {0, "Page Down / Up", "the next / previous scene (JSON or glTF) of the scene's directory"},
    {APP_COMPARE_KEY, NULL, "compare against the ray-traced truth (--compare)"},
    {0, "Tab", "the HUD's caption, technique and settings only (--hud-compact)"},
    {0, "F3", "the skips' counters and the rays cast on the HUD (--verbose)"},
    {GLFW_KEY_H, NULL, "help on the HUD"},
    {0, "F11", "the window on the whole screen, or back (--fullscreen)"},
    {0, "F12", "the window's picture, HUD included (screenshot-TECHNIQUE-N.png, never overwritten)"},
    {0, "Esc", "quit"},
};
enum { app_window_key_count = sizeof app_window_keys / sizeof *app_window_keys };

static const char *app_window_key_name(const app_window_key *k, char *out, size_t size) {
    if (k->label)
        return k->label;
    snprintf(out, size, "%c", k->letter);
    return out;
}

static void app_usage(void) {
    printf("usage: %s [flags]\n", app.program);
    flags_print_help(stdout, app_flags, app_flag_count, 2, 0);
    printf("techniques (keys 1-%d in the window):\n", app.technique_count);
    for (int i = 0; i < app.technique_count; i++) {
        const technique *t = app.techniques[i];
        printf("  %d %-12s %s\n", i + 1, t->name, t->title);
        flags_print_help(stdout, t->params, t->param_count, 6, APP_TECHNIQUE_FLAG_WIDTH);
    }
    printf("window (besides the keys above):\n");
    for (const app_window_key *k = app_window_keys; k < app_window_keys + app_window_key_count; k++) {
        char letter[2];
        printf("  %-16s%s\n", app_window_key_name(k, letter, sizeof letter), k->help);
    }
}

/* --flags-markdown: the README's "Keys and flags" (make readme-flags),
 * from the tables --help prints; false after saying why when stdout did
 * not take it all. */
static bool app_print_markdown(void) {
    printf("The flags of `build/shadows` and of each technique's own program, and\n"
           "their keys in the window (`--help` prints the same):\n\n");
    flags_print_markdown(stdout, app_flags, app_flag_count);
    printf("\nThe window's keys besides the flags':\n\n| key | what it does |\n|---|---|\n");
    for (const app_window_key *k = app_window_keys; k < app_window_keys + app_window_key_count; k++) {
        char letter[2];
        printf("| %s | %s |\n", app_window_key_name(k, letter, sizeof letter), k->help);
    }
    printf("\nEach technique's parameters, flags of its own program (`build/NAME`) and\n"
           "of `build/shadows`, whose key N picks the technique:\n");
    for (int i = 0; i < app.technique_count; i++) {
        const technique *t = app.techniques[i];
        printf("\n**%d `%s`**: %s%s\n", i + 1, t->name, t->title, t->param_count ? "\n" : "; no parameters.");
        if (t->param_count)
            flags_print_markdown(stdout, t->params, t->param_count);
    }
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "%s: --flags-markdown: writing stdout: %s\n", app.program, strerror(errno));
        return false;
    }
    return true;
}

/* The app's flags and every technique's in one table, so that a flag
 * several techniques share (--no-offset) sets each of them. Returns 0 to
 * run, FLAGS_HELP_ASKED after --help or --flags-markdown, or an exit
 * status. */
static int app_parse_flags(int argc, char **argv, const flags_elsewhere *elsewhere, int elsewhere_count) {
    int count = app_flag_count;
    for (int i = 0; i < app.technique_count; i++)
        count += app.techniques[i]->param_count;
    flags_param *params = malloc((size_t)count * sizeof *params);
    if (!params) {
        fprintf(stderr, "%s: out of memory for %d flags\n", app.program, count);
        return APP_EXIT_RUNTIME;
    }
    memcpy(params, app_flags, sizeof app_flags);
    for (int i = 0, n = app_flag_count; i < app.technique_count; i++)
        for (int k = 0; k < app.techniques[i]->param_count; k++)
            params[n++] = app.techniques[i]->params[k];
    int status = flags_parse_among(app.program, params, count, argc - 1, argv + 1, elsewhere, elsewhere_count);
    free(params);
    app.hud_counters = app.verbose;
    if (status == FLAGS_HELP_ASKED)
        app_usage();
    else if (status == 0 && app.flags_markdown)
        status = app_print_markdown() ? FLAGS_HELP_ASKED : APP_EXIT_RUNTIME;
    return status;
}

static const technique *app_technique(void) { return app.techniques[app.current]; }

static bool app_load_scene(const char *path, int camera) {
    if (!scene_load_camera(&app.scene, path, camera))
        return false;
    if (!camera_check_depth(&app.scene, path, depth_reversed_available())) {
        scene_free(&app.scene);
        return false;
    }
    if (!scene_check_light_flag(&app.scene, path, app.light)) {
        scene_free(&app.scene);
        return false;
    }
    if (app.verbose)
        scene_print_models(&app.scene, path);
    memcpy(app.base_lights, app.scene.lights, sizeof app.base_lights);
    memcpy(app.loaded_lights, app.scene.lights, sizeof app.loaded_lights);
    app.base_camera = app.loaded_camera = app.scene.camera;
    if (!render_scene_create(&app.gpu, &app.scene)) {
        scene_free(&app.scene);
        return false;
    }
    return true;
}

static void app_unload_scene(void) {
    if (app.compare_on) /* the truth's thread lets go of the scene first */
        compare_forget(&app.comparing);
    render_scene_destroy(&app.gpu);
    scene_free(&app.scene);
}

static motion_kind app_motion(void) { return app.animate ? MOTION_LIGHT : (motion_kind)app.motion; }

/* The tour's step with a path, or NULL: its camera moves with the time. */
static const tour_step *app_step_path(void) {
    const tour_step *s = app.tour_path ? &app.tour.steps[app.tour_step] : NULL;
    return s && tour_step_has_path(s) ? s : NULL;
}

/* The camera at `time` (the motion's, or a tour step's path), and its view. */
static void app_camera_at(double time, scene_camera *camera, camera_view *view) {
    motion_camera(app_motion(), time, &app.base_camera, camera);
    const tour_step *path = app_step_path();
    if (path)
        tour_step_camera(path, time, app.scene.origin, camera);
    camera_view_compute(camera, (float)app.target.width / (float)app.target.height, view);
}

/* This frame's lights and camera (app.time), and the view. */
static void app_view(camera_view *view) {
    scene *s = &app.scene;
    motion_lights(app_motion(), app.time, app.base_camera.target, app.base_lights, s->light_count, app.light,
                  s->lights);
    app_camera_at(app.time, &s->camera, view);
}

/* visibility_of: -1 for the picture, K for light K's visibility (see
 * capture.h). With --hold-fit the maps are fitted to the camera of the
 * frame before (a headless frame's step, 1/60 s). */
static bool app_render_frame(int visibility_of) {
    camera_view view, fit_view;
    app_view(&view);
    scene_camera held;
    if (app.hold_fit)
        app_camera_at(app.time - 1 / APP_HEADLESS_FPS, &held, &fit_view);
    app.host.counters = app.hud_counters;
    return technique_host_frame(&app.host, &view, app.hold_fit ? &fit_view : NULL, &app.target, app.time,
                                visibility_of);
}

/* What is saved, recorded and shown: compare mode's four cells, else the
 * technique's frame. */
static const target *app_picture(void) { return app.compare_on ? &app.comparing.picture : &app.target; }

static bool app_save_screenshot(const char *path) {
    const target *picture = app_picture();
    size_t bytes = (size_t)picture->width * (size_t)picture->height * 4;
    unsigned char *rgba = malloc(bytes);
    bool ok = rgba && target_read_rgba(picture, rgba) && image_write_png(path, picture->width, picture->height, rgba);
    if (!rgba)
        fprintf(stderr, "%s: out of memory for a %dx%d screenshot\n", path, picture->width, picture->height);
    free(rgba);
    return ok;
}

static bool app_start_technique(int index) {
    app.current = index;
    if (app.compare_on)
        compare_decisions_changed(&app.comparing);
    return technique_host_start(&app.host, app_technique(), &app.gpu, &app.skips);
}

/* What this frame decided for light `light` (capture.h); on failure the
 * dump owns nothing. */
static bool app_capture(int light, dump_frame *dump) {
    camera_view view;
    app_view(&view);
    return capture_dump(&app.gpu, &view, &app.target, light, app_technique()->coloured_shadows, app_render_frame,
                        dump);
}

static bool app_dump(const char *dir) {
    dump_frame dump;
    if (!app_capture(app.light, &dump))
        return false;
    bool ok = dump_write(&dump, dir);
    dump_frame_free(&dump);
    return ok;
}

/* ---- progress ---- */

/* Headless, the frames done of the run's, and while a compare frame waits
 * for its truth (truth_rows of truth_height; 0 of 0: none) the rows traced
 * of it: raytrace_settings' progress. A finished truth's line is erased
 * at once: compare mode may print the folder it bakes it into next. */
static void app_show_progress(int truth_rows, int truth_height) {
    if (truth_height > 0)
        progress_show(&app.progress, "frames %d of %d, truth rows %d of %d", app.frames_done, app.frames_total,
                      truth_rows, truth_height);
    else
        progress_show(&app.progress, "frames %d of %d", app.frames_done, app.frames_total);
    if (truth_height > 0 && truth_rows == truth_height)
        progress_clear(&app.progress);
}

/* The frames tour step s renders headless, [*first, *end): with a video
 * each of its frames; else only the one it shows (the same picture:
 * frames are a function of their time). */
static void app_step_frames(const tour_step *s, int *first, int *end) {
    *first = app.record_path ? 0 : s->shown_frame;
    *end = app.record_path ? s->frame_count : s->shown_frame + 1;
}

/* The run's progress: headless only, where it renders more than one frame
 * or has a truth to wait for. */
static void app_start_progress(void) {
    int frames = app.frames ? app.frames : APP_HEADLESS_FRAMES;
    if (app.tour_path)
        frames = 0;
    for (int k = 0; app.tour_path && k < app.tour.step_count; k++) {
        int first, end;
        app_step_frames(&app.tour.steps[k], &first, &end);
        frames += end - first;
    }
    app.frames_done = 0;
    app.frames_total = frames;
    bool wanted = !app.ctx.window && !app.gallery_count && (frames > 1 || app.compare_on || app.tour_path);
    progress_start(&app.progress, app.program, app.quiet || !wanted);
}

/* ---- compare mode ---- */

/* The frame's targets for a picture of width x height: in compare mode the
 * technique's is one of the four cells. */
static bool app_create_targets(int width, int height) {
    if (!app.compare_on)
        return target_create(&app.target, width, height);
    const raytrace_settings settings = {.scene_name = app.scene_path,
                                        .progress = app.progress.on ? app_show_progress : NULL};
    if (!compare_create(&app.comparing, width, height, &settings, raytrace_available() ? NULL : app.baked_truths))
        return false;
    app.comparing.bake_into = app.bake_truths_dir;
    /* Only the interactive window shows how long the truth took: pictures
     * (headless, or the window's scripted --frames) stay the same bytes. */
    app.comparing.show_seconds = app.ctx.window && app.frames <= 0;
    if (!target_create(&app.target, app.comparing.cell_width, app.comparing.cell_height)) {
        compare_destroy(&app.comparing);
        return false;
    }
    return true;
}

static void app_destroy_targets(void) {
    if (app.compare_on)
        compare_destroy(&app.comparing);
    target_destroy(&app.target);
}

/* Compare mode on or off (the A key, a tour's step), the picture's size
 * kept. */
static bool app_set_compare(bool on) {
    if (on == app.compare_on)
        return true;
    int width = app_picture()->width, height = app_picture()->height;
    app_destroy_targets();
    app.compare_on = on;
    return app_create_targets(width, height);
}

/* The picture of this frame: the technique's frame; in compare mode first
 * the truth and heat map of its view (with `wait`, the finished ones), and
 * the four cells after. */
static bool app_render_picture(bool wait) {
    if (!app.compare_on)
        return app_render_frame(-1);
    camera_view view;
    app_view(&view); /* the frame's camera and lights, which the truth is asked for */
    return compare_update(&app.comparing, &app.scene, app.light, app_capture, wait) && app_render_frame(-1) &&
           compare_draw(&app.comparing, &app.target);
}

/* Headless, what a compare picture measured. */
static void app_print_compared(void) {
    progress_clear(&app.progress);
    char figures[512];
    compare_figures_text(&app.comparing, figures, sizeof figures);
    printf("compare: %s on %s: %s\n", app_technique()->name, app.scene_path, figures);
}

static void app_hud(int width, int height, int frame);
static void app_say_frame(int width, int height, int frame);

/* With --hud, the HUD drawn into the picture (frame: as app_hud). */
static bool app_hud_in_picture(int frame) {
    if (!app.hud_in_pictures)
        return true;
    const target *picture = app_picture();
    target_bind(picture);
    app_hud(picture->width, picture->height, frame);
    return context_gl_ok("hud");
}

/* The picture as the video's next frame. */
static bool app_record_frame(void) {
    return target_read_rgba(app_picture(), app.frame_rgba) && video_write_frame(&app.video, app.frame_rgba);
}

static bool app_start_recording(void) {
    const target *picture = app_picture();
    size_t bytes = (size_t)picture->width * (size_t)picture->height * 4;
    app.frame_rgba = malloc(bytes);
    if (!app.frame_rgba) {
        fprintf(stderr, "%s: out of memory for %dx%d frames\n", app.record_path, picture->width, picture->height);
        return false;
    }
    return video_open(&app.video, app.record_path, picture->width, picture->height);
}

static bool app_stop_recording(void) {
    bool was_open = app.video.pipe != NULL;
    bool ok = video_close(&app.video);
    free(app.frame_rgba);
    app.frame_rgba = NULL;
    if (ok && was_open)
        printf("%s: %ld frames\n", app.record_path, app.video.frames);
    return ok;
}

/* Headless frame i at time i/60 s; `kept` (a screenshot's) or a video's
 * carries the HUD with --hud. Counted in the run's progress. */
static bool app_headless_frame(int i, bool kept) {
    app.time = i / APP_HEADLESS_FPS;
    kept = kept || app.video.pipe;
    /* Only a kept frame needs the truth. */
    bool ok = (kept ? app_render_picture(true) : app_render_frame(-1)) && (!kept || app_hud_in_picture(i)) &&
              (!app.video.pipe || app_record_frame());
    app.frames_done++;
    app_show_progress(0, 0);
    return ok;
}

/* Renders `frames` frames at the fixed headless rate, each into the video
 * when recording, then the screenshot (with --hud, the HUD drawn over
 * what is kept). */
static bool app_run_headless(int frames, const char *screenshot) {
    bool ok = true;
    for (int i = 0; i < frames && ok; i++)
        ok = app_headless_frame(i, screenshot && i == frames - 1);
    progress_end(&app.progress);
    return ok && (!screenshot || app_save_screenshot(screenshot));
}

/* ---- tours ---- */

static int app_technique_index(const char *name) {
    for (int i = 0; i < app.technique_count; i++)
        if (strcmp(app.techniques[i]->name, name) == 0)
            return i;
    return -1;
}

/* The tour file loaded and every step's technique and flags checked
 * before anything renders, each problem one line "FILE: steps[i].KEY:
 * ..." (flags: the technique's own error), the file's and these all
 * said at once. A step whose technique the file did not give has its
 * line already. */
static bool app_load_tour(void) {
    bool ok = tour_load(&app.tour, app.tour_path);
    for (int k = 0; k < app.tour.step_count; k++) {
        const tour_step *s = &app.tour.steps[k];
        int t = app_technique_index(s->technique);
        if (t < 0 && s->technique[0]) {
            char expected[256];
            json_join_names(app.technique_names, expected, sizeof expected);
            fprintf(stderr, "%s: steps[%d].technique: unknown technique \"%s\" (expected %s)\n", app.tour_path, k,
                    s->technique, expected);
        }
        if (t < 0) {
            ok = false;
            continue;
        }
        char who[PATH_MAX + 64];
        snprintf(who, sizeof who, "%s: steps[%d].flags: %s", app.tour_path, k, s->technique);
        bool configured = technique_apply_config_as(app.techniques[t], s->flags, who);
        ok = technique_apply_config(app.techniques[t], "") && configured && ok;
    }
    return ok;
}

/* Whether step s is shown in compare mode: its own "compare", or
 * --compare's for every step. */
static bool app_step_compare(const tour_step *s) { return app.compare_given || s->compare; }

/* What differs between the tour's step and what is shown: the technique
 * and its settings (technique_settings_changes), and compare mode, into
 * out ("technique volumes", "constant-bias OFF, compare off"); false, out
 * "", where nothing does and the step's caption describes the picture.
 * The view and the lights are no setting of the step's: moving them
 * leaves its caption as it is. */
static bool app_step_changes(char *out, size_t size) {
    bool changed = technique_settings_changes(&app.step_settings, app_technique(), out, size);
    if (app.compare_on != app_step_compare(&app.tour.steps[app.tour_step])) {
        size_t n = strlen(out);
        snprintf(out + n, size - n, "%scompare %s", changed ? ", " : "", app.compare_on ? "on" : "off");
    }
    return out[0] != '\0';
}

/* Step k's scene loaded, its camera (or its path's start) the one motion
 * and the window's keys start from, its technique configured and started,
 * its motion from time 0. */
static bool app_enter_step(int k) {
    const tour_step *s = &app.tour.steps[k];
    app.tour_step = k;
    app.current = app_technique_index(s->technique);
    app.motion = (int)s->motion;
    app.animate = false;
    app.time = 0;
    app.scene_path = s->scene;
    if (!app_set_compare(app_step_compare(s)))
        return false;
    if (!technique_apply_config(app_technique(), s->flags) || !(app.step_scene = app_load_scene(s->scene, 0)) ||
        !tour_step_check_views(app.tour_path, k, s, app.scene.origin, &app.scene.camera))
        return false;
    technique_settings_save(app_technique(), &app.step_settings);
    tour_step_camera(s, 0, app.scene.origin, &app.base_camera);
    app.loaded_camera = app.base_camera;
    app.step_technique = true; /* destroy() follows a failed init too */
    return app_start_technique(app.current);
}

static void app_leave_step(void) {
    if (app.step_technique)
        technique_host_stop(&app.host);
    if (app.step_scene)
        app_unload_scene();
    app.step_technique = app.step_scene = false;
}

/* "P.png" -> "P-K.png" (--screenshot ends in .png, in any case): step
 * k's (from 1) picture. */
static bool app_step_screenshot(int k) {
    char path[PATH_MAX];
    int stem = (int)(strlen(app.screenshot) - strlen(".png"));
    snprintf(path, sizeof path, "%.*s-%d.png", stem, app.screenshot, k + 1);
    if (!app_save_screenshot(path))
        return false;
    progress_clear(&app.progress);
    printf("%s\n", path);
    return true;
}

/* Every step headless, its frames app_step_frames'; with --verbose each
 * step's shown frame is said as a single run's last. */
static bool app_run_tour_headless(void) {
    bool ok = true;
    for (int k = 0; k < app.tour.step_count && ok; k++) {
        const tour_step *s = &app.tour.steps[k];
        progress_clear(&app.progress); /* loading the step's scene may say something */
        ok = app_enter_step(k);
        int first, end;
        app_step_frames(s, &first, &end);
        for (int i = first; i < end && ok; i++) {
            ok = app_headless_frame(i, app.screenshot && i == s->shown_frame) &&
                 (!app.screenshot || i != s->shown_frame || app_step_screenshot(k));
            if (ok && app.verbose && i == s->shown_frame)
                app_say_frame(app_picture()->width, app_picture()->height, i);
        }
        if (ok && app.compare_on && (app.screenshot || app.video.pipe)) /* a kept frame was compared */
            app_print_compared();
        app_leave_step();
    }
    progress_end(&app.progress);
    return ok;
}

/* The gallery's page rows: one a picture, at most every technique's two
 * (its own and its lecture picture) on every scene. */
#define APP_GALLERY_MAX_ROWS (2 * APP_MAX_TECHNIQUES * APP_MAX_GALLERY_SCENES)
/* The classes' MAEs on the page, with the whole picture's decimals. */
#define APP_GALLERY_MAE_DECIMALS 5
_Static_assert(SHADOWDIFF_CLASS_COUNT <= GALLERY_PAGE_MAX_FIGURES, "a row holds every class's figures");

/* Light 0's decisions of the running technique against `reference`: the
 * row's figures (each of shadowdiff's classes' too), and the heat map into DIR/STEM_heatmap.png. A frame
 * shadowdiff can say nothing of stays unmeasured on the page. */
static bool app_gallery_measure(const dump_frame *reference, const char *dir, const char *stem,
                                gallery_page_row *row) {
    dump_frame dump;
    if (!app_capture(0, &dump))
        return false;
    unsigned char *heatmap = malloc((size_t)dump.width * (size_t)dump.height * 4);
    shadowdiff_result r;
    bool ok = heatmap != NULL;
    row->measured = ok && shadowdiff_compare(reference, &dump, NULL, &r, heatmap);
    ok = ok && (!row->measured ||
                shadowdiff_heatmap_magnify(heatmap, dump.width, dump.height, shadowdiff_magnify_radius(dump.height)));
    if (row->measured && ok) {
        char path[PATH_MAX];
        snprintf(row->heatmap, sizeof row->heatmap, "%s_heatmap.png", stem);
        snprintf(path, sizeof path, "%s/%s", dir, row->heatmap);
        ok = image_write_png(path, dump.width, dump.height, heatmap);
        row->misclassified_percent = r.misclassified_percent;
        row->mean_abs_error = r.mean_abs_error;
        row->compared = r.compared;
        for (int c = 0; c < SHADOWDIFF_CLASS_COUNT; c++)
            shadowdiff_class_figures_text(&r, (shadowdiff_class)c, APP_GALLERY_MAE_DECIMALS, row->figures[c],
                                          sizeof row->figures[c]);
        row->figure_count = SHADOWDIFF_CLASS_COUNT;
    }
    if (!heatmap)
        fprintf(stderr, "%s: out of memory for a heat map\n", dir);
    free(heatmap);
    dump_frame_free(&dump);
    return ok;
}

/* One picture of technique t on the loaded scene (its lecture picture
 * with `config`), to DIR/STEM.png, and its row. */
static bool app_gallery_picture(int t, const char *config, const char *stem, const char *scene_name,
                                const dump_frame *reference, const char *reference_file, gallery_page_row *row) {
    const char *dir = app.gallery[0];
    const technique *tech = app.techniques[t];
    char path[PATH_MAX];
    *row = (gallery_page_row){0};
    snprintf(row->technique, sizeof row->technique, "%s", tech->name);
    snprintf(row->flags, sizeof row->flags, "%s", config ? config : "");
    snprintf(row->scene, sizeof row->scene, "%s", scene_name);
    snprintf(row->picture, sizeof row->picture, "%s.png", stem);
    snprintf(row->reference, sizeof row->reference, "%s", reference_file);
    snprintf(path, sizeof path, "%s/%s", dir, row->picture);
    bool ok =
        (!config || technique_apply_config(tech, config)) && app_start_technique(t) && app_run_headless(1, path);
    /* A lecture picture's overlays are drawn over its decisions. */
    ok = ok && (config || app_gallery_measure(reference, dir, stem, row));
    technique_host_stop(&app.host);
    ok = (!config || technique_apply_config(tech, "")) && ok;
    if (ok)
        printf("%s\n", path);
    return ok;
}

/* Every technique (or --technique's) on every scene, each picture beside
 * the reference's and its heat map on DIR/index.html. */
static bool app_run_gallery(void) {
    const char *dir = app.gallery[0];
    if (!path_make_directories(dir))
        return false;
    int first = app.technique_given ? app.current : 0;
    int end = app.technique_given ? app.current + 1 : app.technique_count;
    gallery_page_row *rows = malloc(APP_GALLERY_MAX_ROWS * sizeof *rows);
    if (!rows) {
        fprintf(stderr, "%s: out of memory for the gallery's page\n", dir);
        return false;
    }
    int row_count = 0;
    bool ok = true;
    for (int s = 1; s < app.gallery_count && ok; s++) {
        const char *scene_path = app.gallery[s];
        if (!app_load_scene(scene_path, 0)) {
            ok = false;
            break;
        }
        char name[GALLERY_PAGE_NAME_MAX / 2], reference_file[GALLERY_PAGE_NAME_MAX], path[PATH_MAX];
        path_stem(scene_path, name, sizeof name);
        snprintf(reference_file, sizeof reference_file, "reference_%s.png", name);
        snprintf(path, sizeof path, "%s/%s", dir, reference_file);
        const raytrace_settings settings = {.scene_name = scene_path};
        dump_frame reference = {0};
        ok = raytrace_render(&app.scene, app.target.width, app.target.height, 0, &settings, &reference);
        ok = ok && image_write_png(path, reference.width, reference.height, reference.color);
        for (int t = first; t < end && ok; t++) {
            const technique *tech = app.techniques[t];
            char stem[GALLERY_PAGE_NAME_MAX];
            snprintf(stem, sizeof stem, "%s_%s", tech->name, name);
            ok = app_gallery_picture(t, NULL, stem, name, &reference, reference_file, &rows[row_count++]);
            if (ok && tech->gallery_config) {
                snprintf(stem, sizeof stem, "%s-lecture_%s", tech->name, name);
                ok = app_gallery_picture(t, tech->gallery_config, stem, name, &reference, reference_file,
                                         &rows[row_count++]);
            }
        }
        if (reference.width)
            dump_frame_free(&reference);
        app_unload_scene();
    }
    gallery_page_key key[SHADOWDIFF_PIXEL_KIND_COUNT];
    for (int k = 0; k < SHADOWDIFF_PIXEL_KIND_COUNT; k++) {
        shadowdiff_pixel kind = shadowdiff_legend_kinds[k];
        key[k] = (gallery_page_key){.name = shadowdiff_pixel_names[kind]};
        memcpy(key[k].rgb, shadowdiff_pixel_colors[kind], sizeof key[k].rgb);
    }
    char note[64];
    snprintf(note, sizeof note, "each error drawn %d px wide", 2 * shadowdiff_magnify_radius(app.height) + 1);
    ok = ok && gallery_page_write(dir, rows, row_count, key, SHADOWDIFF_PIXEL_KIND_COUNT, note);
    free(rows);
    return ok;
}

/* The skips' state for the HUD and --verbose: each one's key, whether it
 * is on, and what it saved in the last frame. */
static int app_skips_text(char *out, size_t size) {
    const render_skips *k = &app.skips;
    const skips_counts *c = &app.host.counts;
    const char *off = "OFF";
    int n = snprintf(out, size, "skips%s   [K] view culling: ", k->no_skip ? " (--no-skip: all OFF)" : "");
#define APP_TEXT(...) (n += n < (int)size ? snprintf(out + n, size - (size_t)n, __VA_ARGS__) : 0)
    if (render_skip_on(k, k->no_view_cull))
        APP_TEXT("objects drawn %d / culled %d", app.host.objects_in_view,
                 app.scene.object_count - app.host.objects_in_view);
    else
        APP_TEXT("%s", off);
    APP_TEXT("   [U] light reach: ");
    if (render_skip_on(k, k->no_light_reach))
        APP_TEXT("lights skipped %d of %d", c->lights_skipped, app.scene.light_count);
    else
        APP_TEXT("%s", off);
    bool casters = render_skip_on(k, k->no_caster_cull);
    APP_TEXT("\n[X] caster culling: %s", casters ? "casters drawn / culled per light:" : off);
    for (int l = 0; casters && l < app.scene.light_count; l++)
        APP_TEXT(" %d: %d/%d", l, c->casters_drawn[l], c->casters_culled[l]);
    APP_TEXT("   [I] hidden casters: ");
    if (!render_skip_on(k, k->no_hidden_cull))
        APP_TEXT("%s", off);
    else if (app.host.hidden_idle > 0)
        APP_TEXT("nothing to cull: asleep %d frames", app.host.hidden_idle);
    else
        for (int l = 0; l < app.scene.light_count; l++)
            APP_TEXT("%s%d: %d/%d", l ? " " : "culled / narrowed per light ", l, c->casters_hidden[l],
                     c->casters_narrowed[l]);
    if (render_skip_on(k, k->no_hidden_cull) && app.host.hidden_idle == 0)
        APP_TEXT("; objects hidden %d; lights narrowed %d", c->objects_hidden,
                 __builtin_popcountll(c->lights_narrowed));
    APP_TEXT("   [J] caching: ");
    if (render_skip_on(k, k->no_cache))
        APP_TEXT("map layers reused %d of %d", c->layers_reused, c->layers_reused + c->layers_rendered);
    else
        APP_TEXT("%s", off);
    if (c->layers_unread)
        APP_TEXT("; layers out of view, not drawn %d", c->layers_unread);
    if (c->maps_kept)
        APP_TEXT("; maps kept past the budget %d", c->maps_kept);
    APP_TEXT("   [Q] marked pass: ");
    if (render_skip_on(k, k->no_marked_pass))
        APP_TEXT("passes %d", c->marked_passes);
    else
        APP_TEXT("%s", off);
#undef APP_TEXT
    return n < (int)size ? n : (int)size - 1;
}

/* ---- the window ---- */

/* The technique's settings for the HUD: each one a key changes, and
 * each other one that is not at its default (a flag's), as "[K] name:
 * value" (the key where it has one); with `defaults_left_out` only those
 * not at their defaults, or that they all are. */
static int app_settings_text(const technique *t, bool defaults_left_out, char *out, size_t size) {
    int n = 0;
    out[0] = '\0';
    for (int k = 0; k < t->param_count && n < (int)size; k++) {
        const flags_param *p = &t->params[k];
        if ((defaults_left_out || !p->key) && !technique_param_changed(p))
            continue;
        char value[32], key[8] = "";
        technique_param_text(p, value, sizeof value);
        if (p->key)
            snprintf(key, sizeof key, "[%c] ", p->key);
        n += snprintf(out + n, size - (size_t)n, "%s%s%s: %s", n ? "   " : "", key, p->name, value);
    }
    if (n == 0 && defaults_left_out && t->param_count)
        n = snprintf(out, size, "settings: the defaults");
    return n < (int)size ? n : (int)size - 1;
}

/* The HUD's text, for a lecture: the tour's caption, the technique (its
 * title outside a tour: the caption says what it would) and scene, the
 * technique's state line and its settings; compact (Tab, and compare
 * mode's caption strip) the caption, the technique and its settings
 * alone, and with `defaults_left_out` (compact only) the settings not at
 * their defaults (app_settings_text) on the technique's line. A caption
 * the picture no longer shows (app_step_changes) is followed by
 * "changed: ..." and is its first line, which the HUD dims: returns 1
 * then, else 0. The skips' counters follow with --verbose or F3. In the
 * window (frame < 0) with the frame time, the help and the last note (a
 * saved screenshot, a scene that did not load); in a headless picture
 * with the frame's number and time instead, so that the same command
 * gives the same picture. */
static int app_hud_text(char *text, size_t size, int frame, bool defaults_left_out) {
    const technique *t = app_technique();
    bool compact = app.hud_compact || app.compare_on;
    char timing[64] = "", scene_name[PATH_MAX];
    if (frame < 0 && !APP_IN_PAGE)
        snprintf(timing, sizeof timing, "   %.2f ms/frame (CPU)", app.frame_ms);
    else if (frame >= 0)
        snprintf(timing, sizeof timing, "   frame %d at %.3f s", frame, app.time);
    if (!path_stem(app.scene_path, scene_name, sizeof scene_name))
        snprintf(scene_name, sizeof scene_name, "%s", app.scene_path);
    int n = 0, dimmed = 0;
#define APP_HUD(...) (n += n < (int)size ? snprintf(text + n, size - (size_t)n, __VA_ARGS__) : 0)
    if (app.tour_path) {
        char changes[TOUR_TEXT_MAX];
        APP_HUD("step %d/%d   %s\n", app.tour_step + 1, app.tour.step_count, app.tour.steps[app.tour_step].caption);
        if (app_step_changes(changes, sizeof changes)) {
            APP_HUD("changed: %s\n", changes);
            dimmed = 1;
        }
    }
    if (compact || app.tour_path)
        APP_HUD("%s on %s   %dx%d%s%s", t->name, scene_name, app.target.width, app.target.height, timing,
                defaults_left_out && t->param_count ? "   " : "\n");
    else
        APP_HUD("%d/%d %s: %s\nscene %s   %dx%d%s%s%s\n", app.current + 1, app.technique_count, t->name, t->title,
                scene_name, app.target.width, app.target.height, timing, app_motion() ? "   moving: " : "",
                app_motion() ? motion_names[app_motion()] : "");
    if (!compact && t->describe && n < (int)size) {
        t->describe(text + n, size - (size_t)n);
        n += (int)strlen(text + n);
        APP_HUD("\n");
    }
    const scene *s = app.gpu.scene;
    for (int l = 0; !compact && l < s->light_count; l++)
        if (s->lights[l].radius > 0)
            APP_HUD("light %d: area light, radius %g%s: %s\n", l, s->lights[l].radius,
                    scene_light_radius_unit(&s->lights[l]), technique_area_light_text(t, &s->lights[l], l));
    if (n < (int)size)
        n += app_settings_text(t, defaults_left_out, text + n, size - (size_t)n);
    if (!compact && app.hud_counters && n < (int)size) {
        APP_HUD("\n");
        if (n < (int)size)
            n += app_skips_text(text + n, size - (size_t)n);
    }
    if (frame < 0 && app.show_help)
        APP_HUD("\ndrag: orbit (Shift: below too)   scroll: zoom   arrows: move light   space: animate light\n"
                "1-%d: technique   PgUp/PgDn: scene   0: reset view   A: compare   K U X I J: skips   F3: their "
                "counters   Tab: compact HUD   F12: screenshot   H: hide help   Esc: quit",
                app.technique_count);
    else if (frame < 0)
        APP_HUD(APP_HELP_HINT);
    if (frame < 0 && glfwGetTime() < app.note_until)
        APP_HUD("\n%s", app.note);
#undef APP_HUD
    return dimmed;
}

/* How the HUD lies over a picture of `width` x `height`. */
typedef struct app_hud_layout {
    char text[4096]; /* app_hud_text's */
    int dimmed_lines;
    int room;  /* pixels from the picture's top */
    int scale; /* hud_draw's */
} app_hud_layout;

/* The HUD over a picture of `width` x `height` (frame: as app_hud_text).
 * In compare mode in its caption strip, over no cell, at the scale of the
 * whole picture's HUD: where all of it would not fit, the settings at
 * their defaults left out and the others on the technique's line (the
 * caption, the technique and the settings that differ from the defaults
 * always stay), smaller only where that would not fit either. */
static void app_hud_lay_out(int width, int height, int frame, app_hud_layout *out) {
    out->dimmed_lines = app_hud_text(out->text, sizeof out->text, frame, false);
    out->room = app.compare_on ? app.comparing.strip_height * height / app.comparing.picture.height : height;
    int full = app.hud_scale ? app.hud_scale : hud_scale_for(height);
    if (app.compare_on && hud_scale_to_fit(out->text, width, out->room, full, height) < full)
        out->dimmed_lines = app_hud_text(out->text, sizeof out->text, frame, true);
    out->scale = hud_scale_to_fit(out->text, width, out->room, full, height);
}

static void app_hud(int width, int height, int frame) {
    app_hud_layout hud;
    app_hud_lay_out(width, height, frame, &hud);
    glViewport(0, height - hud.room, width, hud.room);
    hud_draw(hud.text, width, hud.room, hud.scale, hud.dimmed_lines);
}

/* --verbose: the HUD's text as app_hud draws it over a picture of `width`
 * x `height`, a line "hud: ..." each on stderr. */
static void app_print_hud(int width, int height, int frame) {
    progress_clear(&app.progress); /* not on the progress line */
    app_hud_layout hud;
    app_hud_lay_out(width, height, frame, &hud);
    for (char *line = hud.text, *end; *line; line = end + (*end == '\n')) {
        end = line + strcspn(line, "\n");
        fprintf(stderr, "hud: %.*s\n", (int)(end - line), line);
    }
}

/* --verbose, after a run or at a headless tour step's shown frame: the
 * technique's state line, the skips' counters and the HUD's text (as
 * app_print_hud), on stderr. */
static void app_say_frame(int width, int height, int frame) {
    progress_clear(&app.progress);
    if (app_technique()->describe) {
        char line[512];
        app_technique()->describe(line, sizeof line);
        fprintf(stderr, "%s: %s\n", app_technique()->name, line);
    }
    char skips[512];
    app_skips_text(skips, sizeof skips);
    fprintf(stderr, "%s\n", skips);
    app_print_hud(width, height, frame);
}

/* app_load_scene, what it says on stderr also kept: its first line into
 * `problem` (for the HUD: nobody in a lecture hall sees the terminal),
 * the whole still on stderr. */
static bool app_load_scene_saying(const char *path, char *problem, size_t size) {
    fflush(stderr);
    FILE *said = tmpfile();
    int saved = said ? dup(STDERR_FILENO) : -1;
    bool redirected = saved >= 0 && dup2(fileno(said), STDERR_FILENO) >= 0;
    bool loaded = app_load_scene(path, 0);
    fflush(stderr);
    if (redirected)
        dup2(saved, STDERR_FILENO);
    if (saved >= 0)
        close(saved);
    snprintf(problem, size, "%s (see stderr)", path);
    if (!said)
        return loaded;
    rewind(said);
    char line[PATH_MAX + 256];
    for (bool first = true; fgets(line, sizeof line, said); first = false) {
        fputs(line, stderr);
        if (first)
            snprintf(problem, size, "%.*s", (int)strcspn(line, "\n"), line);
    }
    fclose(said);
    return loaded;
}

/* Page Down / Up: the next or previous scene (JSON or glTF) of the
 * current one's directory, the technique restarted on it. A scene that does not load
 * says why and the current one stays. */
static void app_switch_scene(int step) {
    char path[PATH_MAX];
    if (!path_next_in_directory(app.scene_path, scene_extensions, step, path, sizeof path))
        return;
    technique_host_stop(&app.host);
    app_unload_scene();
    char problem[sizeof app.note] = "";
    bool loaded = app_load_scene_saying(path, problem, sizeof problem);
    if (loaded) {
        snprintf(app.paged_scene, sizeof app.paged_scene, "%s", path);
        app.scene_path = app.paged_scene;
        app.camera = 0;
        snprintf(app.note, sizeof app.note, "scene %s", path);
    } else {
        snprintf(app.note, sizeof app.note, "did NOT load: %s", problem);
    }
    app.note_until = glfwGetTime() + APP_NOTE_SECONDS;
    app.time = 0;
    if ((!loaded && !app_load_scene(app.scene_path, app.camera)) || !app_start_technique(app.current))
        glfwSetWindowShouldClose(app.ctx.window, GLFW_TRUE);
}

static void app_switch_technique(int index) {
    if (index == app.current || index >= app.technique_count)
        return;
    technique_host_stop(&app.host);
    if (!app_start_technique(index))
        glfwSetWindowShouldClose(app.ctx.window, GLFW_TRUE);
}

/* The tour's next or previous step in the window, staying at either end.
 * A step that does not start closes the window (the run fails). */
static void app_tour_go(int step) {
    int k = app.tour_step + step;
    if (k < 0 || k >= app.tour.step_count)
        return;
    app_leave_step();
    if (!app_enter_step(k)) {
        app.tour_failed = true;
        glfwSetWindowShouldClose(app.ctx.window, GLFW_TRUE);
    }
}

/* In a tour, the stepping keys step (their usual meanings wait). */
static bool app_tour_key(int key) {
    if (!app.tour_path)
        return false;
    if (key == GLFW_KEY_SPACE || key == GLFW_KEY_RIGHT || key == GLFW_KEY_PAGE_DOWN)
        app_tour_go(1);
    else if (key == GLFW_KEY_LEFT || key == GLFW_KEY_PAGE_UP)
        app_tour_go(-1);
    else
        return false;
    return true;
}

static void app_on_key(GLFWwindow *w, int key, int scancode, int action, int mods) {
    (void)scancode, (void)mods;
    if (action == GLFW_RELEASE)
        return;
    if (app.compare_on) /* a key may change the technique's decisions */
        compare_decisions_changed(&app.comparing);
    if (app_tour_key(key))
        return;
    float yaw = 0, pitch = 0;
    switch (key) {
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(w, !APP_IN_PAGE); return;
    case GLFW_KEY_H: app.show_help = !app.show_help; return;
    case GLFW_KEY_TAB: app.hud_compact = !app.hud_compact; return;
    case GLFW_KEY_F3: app.hud_counters = !app.hud_counters; return;
    case GLFW_KEY_F11: context_set_fullscreen(&app.ctx, !context_fullscreen(&app.ctx)); return;
    case APP_COMPARE_KEY:
        if (!app_set_compare(!app.compare_on))
            glfwSetWindowShouldClose(w, GLFW_TRUE);
        return;
    case GLFW_KEY_PAGE_DOWN: app_switch_scene(1); return;
    case GLFW_KEY_PAGE_UP: app_switch_scene(-1); return;
    case GLFW_KEY_SPACE: app.animate = !app.animate; return;
    case GLFW_KEY_LEFT: yaw = -APP_LIGHT_STEP_RAD; break;
    case GLFW_KEY_RIGHT: yaw = APP_LIGHT_STEP_RAD; break;
    case GLFW_KEY_UP: pitch = APP_LIGHT_STEP_RAD; break;
    case GLFW_KEY_DOWN: pitch = -APP_LIGHT_STEP_RAD; break;
    case GLFW_KEY_F12: {
        char prefix[64];
        snprintf(prefix, sizeof prefix, "screenshot-%s", app_technique()->name);
        if (!path_numbered_unused(prefix, "png", app.screenshot_asked, sizeof app.screenshot_asked)) {
            snprintf(app.note, sizeof app.note, "screenshot NOT saved (%s: see stderr)", prefix);
            app.note_until = glfwGetTime() + APP_NOTE_SECONDS;
        }
        return;
    }
    case APP_RESET_KEY:
        memcpy(app.base_lights, app.loaded_lights, sizeof app.base_lights);
        app.base_camera = app.loaded_camera;
        app.time = 0;
        return;
    default:
        if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9 && action == GLFW_PRESS) {
            app_switch_technique(key - GLFW_KEY_1);
            return;
        }
        if (action == GLFW_PRESS && !flags_press_key(app_flags, app_flag_count, key) &&
            technique_press_key(app_technique(), key))
            technique_host_settings_changed(&app.host);
        return;
    }
    for (int i = 0; i < app.scene.light_count; i++)
        camera_orbit_light(&app.base_lights[i], app.base_camera.target, yaw, pitch);
}

static void app_on_mouse_button(GLFWwindow *w, int button, int action, int mods) {
    (void)mods;
    if (button == GLFW_MOUSE_BUTTON_LEFT) {
        app.dragging = action == GLFW_PRESS;
        glfwGetCursorPos(w, &app.drag_x, &app.drag_y);
    }
}

static void app_on_cursor(GLFWwindow *w, double x, double y) {
    if (!app.dragging)
        return;
    bool below =
        glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
    camera_orbit(&app.base_camera, -(float)(x - app.drag_x) * APP_ORBIT_RAD_PER_PIXEL,
                 (float)(y - app.drag_y) * APP_ORBIT_RAD_PER_PIXEL, 1, below ? CAMERA_ORBIT_ANY : CAMERA_ORBIT_ABOVE);
    app.drag_x = x;
    app.drag_y = y;
}

static void app_on_scroll(GLFWwindow *w, double dx, double dy) {
    (void)w, (void)dx;
    camera_orbit(&app.base_camera, 0, 0, powf(0.9f, (float)dy), CAMERA_ORBIT_ANY);
}

/* The window's size. The page's canvas follows its box on the page,
 * except at --size, and in compare mode where the truths are baked (make
 * web bakes them at the default size). */
static void app_window_size(int *width, int *height) {
    bool fixed = app.size_given || (app.compare_on && !raytrace_available());
    context_window_size(&app.ctx, fixed ? app.width : 0, fixed ? app.height : 0, width, height);
}

/* F12's picture: the window as it is about to be shown, HUD included;
 * its path printed and noted on the HUD, or why not; with --verbose, the
 * text of the HUD it holds. */
static void app_save_window(int width, int height) {
    const char *path = app.screenshot_asked;
    unsigned char *rgba = malloc((size_t)width * (size_t)height * 4);
    bool saved = rgba && target_read_window_rgba(width, height, rgba) && image_write_png(path, width, height, rgba);
    if (!rgba)
        fprintf(stderr, "%s: out of memory for a %dx%d screenshot\n", path, width, height);
    free(rgba);
    if (saved && app.verbose && app.hud_in_pictures)
        app_print_hud(app_picture()->width, app_picture()->height, -1);
    else if (saved && app.verbose && !app.no_hud)
        app_print_hud(width, height, -1);
    snprintf(app.note, sizeof app.note, saved ? "saved %s" : "screenshot %s NOT saved (see stderr)", path);
    app.note_until = glfwGetTime() + APP_NOTE_SECONDS;
    if (saved)
        printf("%s\n", path);
    app.screenshot_asked[0] = '\0';
}

/* Window frame `frame` of `frames`; interactive when frames <= 0, and
 * then `frame` is not used (the clock gives the time). */
static bool app_window_frame(int frame, int frames) {
    GLFWwindow *w = app.ctx.window;
    bool ok = true;
    int width, height;
    app_window_size(&width, &height);
    bool resized = width != app_picture()->width || height != app_picture()->height;
    if (resized && width > 0 && height > 0 && !app.video.pipe) { /* a video keeps its size */
        app_destroy_targets();
        ok = app_create_targets(width, height);
    }
    if (frames > 0)
        app.time = frame / APP_HEADLESS_FPS;
    ok = ok && app_render_picture(frames > 0); /* --frames: a script, which waits for the truth */
    /* --hud: into the picture, so that screenshots and the video
     * carry it; else over the window only. */
    if (frames <= 0 && app.hud_in_pictures)
        ok = ok && app_hud_in_picture(-1);
    ok = ok && (!app.video.pipe || app_record_frame());
    target_blit_to_window(app_picture(), width, height);
    if (frames <= 0 && !app.hud_in_pictures && !app.no_hud)
        app_hud(width, height, -1);
    if (app.screenshot_asked[0])
        app_save_window(width, height);
    ok = ok && context_gl_ok("window");
    glfwSwapBuffers(w);
    glfwPollEvents();
    double now = glfwGetTime();
    /* The clock lives here, not in techniques: it only advances the
     * animation and smooths the HUD's frame time. */
    if (frames <= 0 && (app_motion() || app_step_path()))
        app.time += app.video.pipe ? 1.0 / VIDEO_FPS : now - app.last_frame; /* a video keeps its own clock */
    app.frame_ms += ((now - app.last_frame) * 1000.0 - app.frame_ms) * 0.1;
    app.last_frame = now;
    return ok;
}

#ifdef __EMSCRIPTEN__
/* What the page's menu shows (common/web/index.html): the techniques by
 * their numbers from 0 (NULL past the last), the one shown, whether
 * compare mode is on, and the scene's file. */
EMSCRIPTEN_KEEPALIVE const char *app_technique_name(int index) {
    return index >= 0 && index < app.technique_count ? app.technique_names[index] : NULL;
}
EMSCRIPTEN_KEEPALIVE int app_technique_shown(void) { return app.current; }
EMSCRIPTEN_KEEPALIVE int app_compare_shown(void) { return app.compare_on; }
EMSCRIPTEN_KEEPALIVE const char *app_scene_shown(void) { return app.scene_path; }

/* The page's frame, called by the browser for each frame it shows; a
 * frame that fails stops the page's loop (its line is on the console). */
static void app_browser_frame(void) {
    if (glfwWindowShouldClose(app.ctx.window) || app.tour_failed || !app_window_frame(0, 0)) {
        fprintf(stderr, "%s: stopped\n", app.program);
        emscripten_cancel_main_loop();
    }
}
#endif

/* Interactive when frames <= 0; otherwise that many frames, then exit
 * (how the window is tested under Xvfb). In the page, the browser calls
 * the interactive window's frames and this never returns. */
static bool app_run_window(int frames) {
    GLFWwindow *w = app.ctx.window;
    glfwSetKeyCallback(w, app_on_key);
    glfwSetMouseButtonCallback(w, app_on_mouse_button);
    glfwSetCursorPosCallback(w, app_on_cursor);
    glfwSetScrollCallback(w, app_on_scroll);
    app.last_frame = glfwGetTime();
#ifdef __EMSCRIPTEN__
    if (frames <= 0)
        emscripten_set_main_loop(app_browser_frame, 0, true);
#endif
    bool ok = true;
    for (int frame = 0; ok && !glfwWindowShouldClose(w) && (frames <= 0 || frame < frames); frame++)
        ok = app_window_frame(frame, frames);
    return ok;
}

/* A headless run that writes nothing says so, and how to get output:
 * without a display, a bare run would otherwise end silently. */
static void app_say_nothing_written(bool wanted_window) {
    int frames = app.frames ? app.frames : APP_HEADLESS_FRAMES;
    printf("%s: %s%d frame%s of %s rendered headless (%s), nothing written: --screenshot PATH.png saves the "
           "last, --dump DIR its decisions, --gallery DIR SCENE... every technique's picture\n",
           app.program, wanted_window ? "no display for a window, so " : "", frames, frames == 1 ? "" : "s",
           app.scene_path, context_backend_name(app.ctx.backend));
}

static bool app_run(void) {
    bool interactive = !app.frames && !app.screenshot && !app.dump_dir && !app.gallery_count;
    const context_settings settings = {
        .backend = (context_backend)app.backend,
        .want_window = interactive,
        .width = app.width,
        .height = app.height,
        .title = "shadows",
        .verbose = app.verbose,
        .glsl_es = app.glsl_es,
        .webgl2 = app.webgl2,
    };
    if (!context_create(&app.ctx, &settings))
        return false;
    if (app.fullscreen && (!app.ctx.window || !context_set_fullscreen(&app.ctx, true))) {
        if (!app.ctx.window)
            fprintf(stderr, "%s: --fullscreen: this run is headless (%s), with no window to fill\n", app.program,
                    context_backend_name(app.ctx.backend));
        context_destroy(&app.ctx);
        return false;
    }
    app.host.light_points = app.ctx.window ? TECHNIQUE_HOST_PROGRESSIVE_POINTS : 0;
    int width = app.width, height = app.height;
    if (app.ctx.window)
        app_window_size(&width, &height);
    app_start_progress();
    /* The HUD's text is also every legend's (compare mode's, the
     * techniques' overlays'), so it is there in every run. */
    bool ok = app_create_targets(width, height) && hud_init();
    if (ok && app.gallery_count) {
        ok = app_run_gallery();
    } else if (ok && app.tour_path) {
        ok = !app.record_path || app_start_recording();
        if (ok && app.ctx.window)
            ok = app_enter_step(0) && app_run_window(app.frames) && !app.tour_failed &&
                 (!app.screenshot || app_step_screenshot(app.tour_step));
        else if (ok)
            ok = app_run_tour_headless();
        ok = app_stop_recording() && ok;
        app_leave_step();
        if (ok && !app.ctx.window && !app.screenshot && !app.record_path)
            printf("%s: %d steps of %s rendered headless (%s), nothing written: --screenshot PATH.png saves step "
                   "K's picture to PATH-K.png, --record PATH.mp4 every frame of every step\n",
                   app.program, app.tour.step_count, app.tour_path, context_backend_name(app.ctx.backend));
    } else if (ok && (ok = app_load_scene(app.scene_path, app.camera))) {
        ok = app_start_technique(app.current) && (!app.record_path || app_start_recording());
        if (ok && app.ctx.window)
            ok = app_run_window(app.frames) && (!app.screenshot || app_save_screenshot(app.screenshot));
        else if (ok)
            ok = app_run_headless(app.frames ? app.frames : APP_HEADLESS_FRAMES, app.screenshot);
        if (ok && !app.ctx.window && app.compare_on)
            app_print_compared();
        ok = app_stop_recording() && ok;
        if (ok && !app.ctx.window && !app.screenshot && !app.dump_dir && !app.record_path)
            app_say_nothing_written(interactive);
        ok = ok && (!app.dump_dir || app_dump(app.dump_dir));
        bool interactive = app.ctx.window && app.frames <= 0; /* its HUD's as the window's last */
        if (ok && app.verbose)
            app_say_frame(app_picture()->width, app_picture()->height,
                          interactive ? -1 : (app.frames > 0 ? app.frames : 1) - 1);
        technique_host_stop(&app.host);
        app_unload_scene();
    }
    hud_destroy();
    app_destroy_targets();
    context_destroy(&app.ctx);
    return ok;
}

int app_main(int argc, char **argv, const technique *const *techniques, int technique_count,
             const flags_elsewhere *elsewhere, int elsewhere_count) {
    memset(&app, 0, sizeof app);
    app.program = flags_program_name(argv[0]);
    if (technique_count > APP_MAX_TECHNIQUES) {
        fprintf(stderr, "%s: %d techniques, more than keys 1-%d\n", app.program, technique_count, APP_MAX_TECHNIQUES);
        return APP_EXIT_RUNTIME;
    }
    for (int i = 0; i < technique_count; i++)
        if (techniques[i]->param_count > TECHNIQUE_MAX_PARAMS) { /* a tour step's are saved (technique_settings) */
            fprintf(stderr, "%s: %s has %d settings, more than %d\n", app.program, techniques[i]->name,
                    techniques[i]->param_count, TECHNIQUE_MAX_PARAMS);
            return APP_EXIT_RUNTIME;
        }
    app.techniques = techniques;
    app.technique_count = technique_count;
    for (int i = 0; i < technique_count; i++) {
        app.technique_names[i] = techniques[i]->name;
        flags_reset(techniques[i]->params, techniques[i]->param_count); /* as a run before this one left them */
    }
    app.current = -1; /* until --technique says */
    int status = app_parse_flags(argc, argv, elsewhere, elsewhere_count);
    if (status)
        return status == FLAGS_HELP_ASKED ? 0 : status;
    app.technique_given = app.current >= 0;
    app.size_given = app.width > 0;
    if (!app.size_given) {
        app.width = APP_DEFAULT_WIDTH;
        app.height = APP_DEFAULT_HEIGHT;
    }
    app.compare_given = app.compare_on;
    if (!app.technique_given)
        app.current = 0;
    path_in_project("shaders", app.default_shader_dir, sizeof app.default_shader_dir);
    path_in_project(APP_BAKED_TRUTHS, app.baked_truths, sizeof app.baked_truths);
    path_in_project("assets/scenes/simple.json", app.default_scene, sizeof app.default_scene);
    shader_set_directory(app.shader_dir ? app.shader_dir : app.default_shader_dir);
    if (!app.scene_path)
        app.scene_path = app.default_scene;
    if (app.tour_path && app.gallery_count)
        return flags_usage_error(app.program, "--tour and --gallery: one at a time", NULL);
    if (app.compare_on && app.gallery_count) /* the gallery has its own references and heat maps */
        return flags_usage_error(app.program, "--compare and --gallery: one at a time", NULL);
    if (app.tour_path && !app_load_tour())
        return APP_EXIT_RUNTIME;
    return app_run() ? 0 : APP_EXIT_RUNTIME;
}
