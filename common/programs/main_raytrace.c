/* raytrace: the ray-traced reference as a program (common/raytrace.h).
 *
 * Renders one scene with the raster camera and writes the picture
 * (--screenshot) and the per-pixel dump (--dump) that shadowdiff compares
 * techniques against. With neither it prints a one-line summary.
 *
 * Exit status: 0 success, 1 a run-time error (scene, model, Embree, file),
 * 2 a bad command line. Every error is one line on stderr.
 */
#include <limits.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flags.h"
#include "image.h"
#include "motion.h"
#include "path.h"
#include "progress.h"
#include "raytrace.h"

#define MAIN_EXIT_RUNTIME 1

static struct {
    const char *program;
    /* flags */
    int width, height, light_index, camera;
    int motion; /* motion_kind */
    int frames; /* 0: not given, the scene as it is (frame 0) */
    raytrace_settings settings;
    bool quiet; /* --quiet: no progress */
    progress progress;
    const char *scene_path, *screenshot, *dump_dir;
    char default_scene[PATH_MAX];
} main_flags;

static const flags_param main_flag_table[] = {
    {"scene", "scene file (assets/scenes/simple.json)", 0, FLAGS_STRING, .text = &main_flags.scene_path,
     .value_name = "PATH"},
    {"size", "image size (1280x720)", 0, FLAGS_SIZE, .width = &main_flags.width, .height = &main_flags.height},
    {"screenshot", "save the picture", 0, FLAGS_STRING, .text = &main_flags.screenshot, .extension = ".png",
     .value_name = "PATH.png"},
    {"dump", "save the per-pixel dump (see common/data/dump.h) for light K", 0, FLAGS_STRING,
     .text = &main_flags.dump_dir, .value_name = "DIR"},
    {"light", "the light whose visibility is dumped, from 0 (0)", 0, FLAGS_INT, .integer = &main_flags.light_index,
     .min = 0, .max = SCENE_MAX_LIGHTS - 1, .what = "a light index", .value_name = "K"},
    {"camera", "the scene's camera: a glTF file's in its order (0)", 0, FLAGS_INT, .integer = &main_flags.camera,
     .min = 0, .max = SCENE_MAX_CAMERA_INDEX, .what = "a camera index", .value_name = "N"},
    {"light-samples",
     "shadow rays per pixel for each area light (radius > 0),\n"
     "stratified, 1.." FLAGS_TEXT(RAYTRACE_MAX_LIGHT_SAMPLES) " (" FLAGS_TEXT(RAYTRACE_DEFAULT_LIGHT_SAMPLES) ")",
     0, FLAGS_INT, .integer = &main_flags.settings.light_samples, .min = 1, .max = RAYTRACE_MAX_LIGHT_SAMPLES,
     .what = "a count"},
    {"motion", "what moves, as the raster programs' --motion", 0, FLAGS_CHOICE, .index = &main_flags.motion,
     .choices = motion_names},
    {"frames", "trace frame N-1 of the motion (at (N-1)/60 s): the frame\na raster program's --frames N dumps last",
     0, FLAGS_INT, .integer = &main_flags.frames, .min = 1, .max = INT_MAX, .what = "a count"},
    {"verbose", "print the Embree version, thread count and timings, and\neach model's triangles and bounds", 0,
     FLAGS_SWITCH, .on = &main_flags.settings.verbose},
    {"quiet", "no progress (the rows done, on stderr where it is a terminal)", 0, FLAGS_SWITCH,
     .on = &main_flags.quiet},
    {.name = "help", .help = "this text", .kind = FLAGS_HELP},
};
enum { main_flag_count = sizeof main_flag_table / sizeof *main_flag_table };

static void main_usage(void) {
    printf("usage: %s [flags]\n"
           "Ray-traces the reference picture and per-pixel dump of a scene (Embree, on the CPU).\n",
           main_flags.program);
    flags_print_help(stdout, main_flag_table, main_flag_count, 2, 0);
    printf("Camera rays are built in double and the scene is traced relative to the eye, so\n"
           "any near/far ratio works and a scene far from the origin keeps its precision.\n"
           "Shadow rays start at the hit point itself, so a shadow's edge is exact at any\n"
           "angle of the light; a plane within %g float ulps of the point's coordinates (from\n"
           "the eye) is the surface the ray leaves, and every hit they meet is confirmed in\n"
           "double: nothing depends on the scene's size.\n"
           "Threads: OMP_NUM_THREADS (default: every core).\n",
           RAYTRACE_SURFACE_ULPS);
}

/* The rows done, on the line each band rewrites. */
static void main_progress(int rows_done, int rows) {
    progress_show(&main_flags.progress, "rows %d of %d", rows_done, rows);
}

static int main_run(void) {
    scene s;
    if (!scene_load_camera(&s, main_flags.scene_path, main_flags.camera))
        return MAIN_EXIT_RUNTIME;
    if (!scene_check_light_flag(&s, main_flags.scene_path, main_flags.light_index)) {
        scene_free(&s);
        return FLAGS_EXIT_USAGE;
    }
    if (main_flags.settings.verbose)
        scene_print_models(&s, main_flags.scene_path);
    /* The last of --frames N frames, moved as the app moves it. */
    double time = main_flags.frames > 0 ? (main_flags.frames - 1) / MOTION_FRAME_RATE : 0;
    const scene_camera base_camera = s.camera;
    scene_light base_lights[SCENE_MAX_LIGHTS];
    memcpy(base_lights, s.lights, sizeof base_lights);
    motion_lights((motion_kind)main_flags.motion, time, base_camera.target, base_lights, s.light_count,
                  main_flags.light_index, s.lights);
    motion_camera((motion_kind)main_flags.motion, time, &base_camera, &s.camera);
    main_flags.settings.scene_name = main_flags.scene_path;
    progress_start(&main_flags.progress, main_flags.program, main_flags.quiet);
    if (main_flags.progress.on)
        main_flags.settings.progress = main_progress;
    double start = omp_get_wtime();
    dump_frame frame;
    bool ok = raytrace_render(&s, main_flags.width, main_flags.height, main_flags.light_index, &main_flags.settings,
                              &frame);
    progress_end(&main_flags.progress);
    double seconds = omp_get_wtime() - start;
    if (ok) {
        ok = (!main_flags.screenshot ||
              image_write_png(main_flags.screenshot, frame.width, frame.height, frame.color)) &&
             (!main_flags.dump_dir || dump_write(&frame, main_flags.dump_dir));
        dump_frame_free(&frame);
    }
    if (ok && (main_flags.settings.verbose || (!main_flags.screenshot && !main_flags.dump_dir)))
        printf("%s: %s, %dx%d, %d light%s, %.3f s\n", main_flags.program, main_flags.scene_path, main_flags.width,
               main_flags.height, s.light_count, s.light_count == 1 ? "" : "s", seconds);
    scene_free(&s);
    return ok ? 0 : MAIN_EXIT_RUNTIME;
}

int main(int argc, char **argv) {
    main_flags.program = flags_program_name(argv[0]);
    main_flags.width = 1280;
    main_flags.height = 720;
    int status = flags_parse(main_flags.program, main_flag_table, main_flag_count, argc - 1, argv + 1);
    if (status == FLAGS_HELP_ASKED) {
        main_usage();
        return 0;
    }
    if (status)
        return status;
    path_in_project("assets/scenes/simple.json", main_flags.default_scene, sizeof main_flags.default_scene);
    if (!main_flags.scene_path)
        main_flags.scene_path = main_flags.default_scene;
    return main_run();
}
