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
#include "path.h"
#include "raytrace.h"

#define MAIN_EXIT_RUNTIME 1

static struct {
    const char *program;
    /* flags */
    int width, height, light_index;
    raytrace_settings settings;
    const char *scene_path, *screenshot, *dump_dir;
    char default_scene[PATH_MAX];
} main_flags;

static void main_usage(void) {
    printf("usage: %s [flags]\n"
           "Ray-traces the reference picture and per-pixel dump of a scene (Embree, on the CPU).\n"
           "  --scene PATH           scene file (assets/scenes/simple.json)\n"
           "  --size WxH             image size (1280x720)\n"
           "  --screenshot PATH.png  save the picture\n"
           "  --dump DIR             save the per-pixel dump (see common/dump.h) for light K\n"
           "  --light K              the light whose visibility is dumped, from 0 (0)\n"
           "  --light-samples N      shadow rays per pixel for each area light (radius > 0),\n"
           "                         stratified, 1..%d (%d)\n"
           "  --verbose              print the Embree version, thread count and timings\n"
           "  --help                 this text\n"
           "Shadow rays start %g x the diagonal of the box holding the scene and the origin\n"
           "off the surface, along its normal on the light's side, and stop as far short of\n"
           "the light: float rounding of hit points grows with the scene's coordinates.\n"
           "Threads: OMP_NUM_THREADS (default: every core).\n",
           main_flags.program, RAYTRACE_MAX_LIGHT_SAMPLES, RAYTRACE_DEFAULT_LIGHT_SAMPLES, (double)RAYTRACE_EPSILON);
}

static int main_usage_error(const char *message, const char *value) {
    return flags_usage_error(main_flags.program, message, value);
}

/* Returns 0 to run, -1 after --help, or an exit status. */
static int main_parse_flags(int argc, char **argv) {
    static const char *const with_value[] = {"--scene", "--size",  "--screenshot", "--dump",
                                             "--light", "--light-samples", NULL};
    flags_cursor c = {.program = main_flags.program, .argc = argc, .argv = argv, .next = 1, .with_value = with_value};
    const char *name, *value;
    int status;
    while ((status = flags_next(&c, &name, &value)) == 1) {
        if (strcmp(name, "--help") == 0 || strcmp(name, "-h") == 0) {
            main_usage();
            return -1;
        } else if (strcmp(name, "--scene") == 0) {
            main_flags.scene_path = value;
        } else if (strcmp(name, "--size") == 0) {
            if (!flags_parse_size(value, &main_flags.width, &main_flags.height))
                return main_usage_error("--size: expected WxH, each 1..16384, got", value);
        } else if (strcmp(name, "--screenshot") == 0) {
            main_flags.screenshot = value;
        } else if (strcmp(name, "--dump") == 0) {
            main_flags.dump_dir = value;
        } else if (strcmp(name, "--light") == 0) {
            if (!flags_parse_int(value, 0, SCENE_MAX_LIGHTS - 1, &main_flags.light_index))
                return main_usage_error("--light: expected a light index 0..7, got", value);
        } else if (strcmp(name, "--light-samples") == 0) {
            if (!flags_parse_int(value, 1, RAYTRACE_MAX_LIGHT_SAMPLES, &main_flags.settings.light_samples))
                return main_usage_error("--light-samples: expected a count 1..65536, got", value);
        } else if (strcmp(name, "--verbose") == 0) {
            main_flags.settings.verbose = true;
        } else {
            return main_usage_error(name[0] == '-' ? "unknown flag" : "unexpected argument", name);
        }
    }
    return status;
}

static int main_run(void) {
    scene s;
    if (!scene_load(&s, main_flags.scene_path))
        return MAIN_EXIT_RUNTIME;
    if (main_flags.light_index >= s.light_count) {
        char message[PATH_MAX + 64], index[16];
        snprintf(message, sizeof message, "--light: %s has lights 0..%d, got", main_flags.scene_path,
                 s.light_count - 1);
        snprintf(index, sizeof index, "%d", main_flags.light_index);
        scene_free(&s);
        return main_usage_error(message, index);
    }
    double start = omp_get_wtime();
    dump_frame frame;
    bool ok = raytrace_render(&s, main_flags.width, main_flags.height, main_flags.light_index, &main_flags.settings,
                              &frame);
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
    const char *slash = strrchr(argv[0], '/');
    main_flags.program = slash ? slash + 1 : argv[0];
    main_flags.width = 1280;
    main_flags.height = 720;
    int status = main_parse_flags(argc, argv);
    if (status)
        return status < 0 ? 0 : status;
    path_in_project("assets/scenes/simple.json", main_flags.default_scene, sizeof main_flags.default_scene);
    if (!main_flags.scene_path)
        main_flags.scene_path = main_flags.default_scene;
    return main_run();
}
