/* Command-line behaviour of the programs: bad input gets one clear line
 * naming the problem and a non-zero exit, never a crash or a silent
 * picture. Everything runs headless with EGL. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "path.h"
#include "progress.h"
#include "registry.h"
#include "render.h"
#include "support.h"

#define EXIT_RUNTIME 1
#define EXIT_USAGE 2
#define README_MAX_BYTES (1 << 20)

static char err[16384];

/* Runs build/planar with `args` and checks the status and that stderr is
 * one line containing each of the `expect` strings. */
static void expect_failure(const char *args, int status, const char *expect1, const char *expect2) {
    char command[2048];
    snprintf(command, sizeof command, "%s --backend egl %s", support_program("planar"), args);
    assert_int_equal(support_run(command, err, sizeof err), status);
    assert_int_equal(support_count_lines(err), 1);
    assert_non_null(strstr(err, expect1));
    if (expect2)
        assert_non_null(strstr(err, expect2));
}

static void test_unknown_flag(void **state) {
    (void)state;
    expect_failure("--frames 1 --bogus", EXIT_USAGE, "unknown flag", "--bogus");
}

/* Runs `program args` (args may go on as a shell command list, and send
 * stdout to stderr) and checks the status and that stderr is one line
 * containing `expect`. */
static void expect_line(const char *program, const char *args, int status, const char *expect) {
    char command[2048];
    snprintf(command, sizeof command, "{ %s %s; }", support_program(program), args);
    int got = support_run(command, err, sizeof err);
    if (got != status || support_count_lines(err) != 1 || !strstr(err, expect))
        fail_msg("%s %s: exit %d, said \"%s\"; expected exit %d and one line with \"%s\"", program, args, got, err,
                 status, expect);
}

/* A flag the program does not have: the nearest of its own when a typo
 * away, and the other techniques' programs that have it. */
static void test_unknown_flag_suggestions(void **state) {
    (void)state;
    expect_line("planar", "--frame 1", EXIT_USAGE, "planar: unknown flag '--frame', did you mean --frames?");
    expect_line("planar", "--stencil", EXIT_USAGE, "did you mean --no-stencil?");
    expect_line("shadows", "--tecnique psm", EXIT_USAGE, "did you mean --technique?");
    /* Named as this one is run: beside it, in $BUILD. */
    const char *build = getenv("BUILD") ? getenv("BUILD") : "build";
    char expected[512];
    snprintf(expected, sizeof expected,
             "shadowmap: unknown flag '--warp': %s/psm (or %s/shadows --technique psm) has it", build, build);
    expect_line("shadowmap", "--warp psm", EXIT_USAGE, expected);
    snprintf(expected, sizeof expected,
             "%s/psm (or %s/shadows --technique psm), %s/cascades (or %s/shadows --technique cascades) and "
             "%s/hybrid (or %s/shadows --technique hybrid) have it",
             build, build, build, build, build, build);
    expect_line("planar", "--filter pcf3", EXIT_USAGE, expected);
    expect_line("shadows", "--receiver ground", EXIT_USAGE, "shadows: unknown flag '--receiver' (see --help)");
}

/* A flag that takes a value, given twice (the first value would be
 * silently lost), whether the app's or a technique's; a toggle or switch
 * given twice is harmless. */
static void test_value_flag_given_twice(void **state) {
    (void)state;
    expect_line("shadows", "--scene a.json --scene b.json", EXIT_USAGE,
                "shadows: --scene given twice, 'a.json' then 'b.json'");
    expect_line("shadows", "--map-size 512 --filter pcf3 --map-size=1024", EXIT_USAGE, "--map-size given twice");
    expect_line("raytrace", "--size 64x36 --size 32x18", EXIT_USAGE, "--size given twice");
    expect_line("shadowdiff", "a b --receiver ground --receiver box", EXIT_USAGE, "--receiver given twice");
    expect_line("planar", "--backend egl --size 64x36 --frames 1 --no-stencil --no-stencil --hud --hud 1>&2", 0,
                "1 frame of");
}

/* Pictures are PNG: a path ending otherwise is refused before anything
 * runs, and nothing is written there. */
static void test_pictures_must_be_png(void **state) {
    (void)state;
    static const char *const cases[][2] = {
        {"planar", "--backend egl --size 64x36 --screenshot out/test/picture.jpg"},
        {"shadows", "--backend egl --size 64x36 --screenshot out/test/picture.jpg"},
        {"raytrace", "--size 64x36 --screenshot out/test/picture.jpg"},
    };
    assert_int_equal(system("mkdir -p out/test && rm -f out/test/picture.jpg"), 0);
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        expect_line(cases[i][0], cases[i][1], EXIT_USAGE,
                    "--screenshot: expected a file name ending in .png, got 'out/test/picture.jpg'");
        assert_int_equal(system("test -e out/test/picture.jpg"), 256);
    }
    expect_line("shadowdiff", "a b --heatmap out/test/heat.gif", EXIT_USAGE,
                "--heatmap: expected a file name ending");
    expect_line("planar", "--backend egl --size 64x36 --screenshot out/test/upper_case.PNG && ls out/test/*.PNG 1>&2",
                0, "out/test/upper_case.PNG");
}

/* --verbose: each model file's object, its triangles, its box in the
 * scene's world coordinates and its colour. */
static void test_verbose_prints_models(void **state) {
    (void)state;
    const char *line = support_verbose_line("unshadowed", "tests/data/scene_model_color.json", "",
                                            "tests/data/scene_model_color.json: objects[1]");
    const char *expected = "tests/data/scene_model_color.json: objects[1] \"repainted\": model of 5 triangles, "
                           "bounds (0, 0, -1) to (5, 1, -1), colour (0, 1, 0)\n";
    assert_non_null(line);
    assert_int_equal(strncmp(line, expected, strlen(expected)), 0);
}

static void test_malformed_values(void **state) {
    (void)state;
    expect_failure("--size 640by480", EXIT_USAGE, "--size", "640by480");
    expect_failure("--size 0x480", EXIT_USAGE, "--size", "0x480");
    expect_failure("--frames -3", EXIT_USAGE, "--frames", "-3");
    expect_failure("--backend vulkan", EXIT_USAGE, "--backend", "vulkan");
    expect_failure("--frames", EXIT_USAGE, "missing value", "--frames");
    expect_failure("--technique nonesuch --frames 1", EXIT_USAGE, "unknown technique", "nonesuch");
    expect_failure("--verbose=yes", EXIT_USAGE, "takes no value", "--verbose");
}

static void test_bad_technique_parameters(void **state) {
    (void)state;
    char command[1024];
    static const char *const cases[][4] = {
        {"shadowmap", "--map-size 3", "--map-size", "'3'"},
        {"shadowmap", "--filter blur", "--filter", "'blur'"},
        {"shadowmap", "--constant-texels -1", "--constant-texels", "'-1'"},
        {"shadowmap", "--normal-texels x", "--normal-texels", "'x'"},
        {"volumes", "--mode zmiddle", "--mode", "'zmiddle'"},
        {"volumes", "--silhouette tpu", "--silhouette", "'tpu'"},
        {"psm", "--warp tsm", "--warp", "'tsm'"},
        {"psm", "--map-size 3", "--map-size", "'3'"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        snprintf(command, sizeof command, "%s --backend egl --frames 1 %s", support_program(cases[i][0]),
                 cases[i][1]);
        assert_int_equal(support_run(command, err, sizeof err), EXIT_USAGE);
        assert_int_equal(support_count_lines(err), 1);
        assert_non_null(strstr(err, cases[i][2]));
        assert_non_null(strstr(err, cases[i][3]));
    }
}

static void test_missing_scene(void **state) {
    (void)state;
    expect_failure("--frames 1 --scene tests/data/no_such_scene.json", EXIT_RUNTIME, "no_such_scene.json",
                   "No such file");
}

static void test_malformed_scene(void **state) {
    (void)state;
    expect_failure("--frames 1 --scene tests/data/cli_syntax_error.json", EXIT_RUNTIME, "cli_syntax_error.json",
                   "syntax");
}

static void test_broken_model_file(void **state) {
    (void)state;
    expect_failure("--frames 1 --scene tests/data/cli_broken_model.json", EXIT_RUNTIME, "cli_broken_model.json",
                   "malformed.obj");
}

/* A model whose header claims 100 M vertices (the file holds 8): each
 * program refuses it at once, naming the scene, the object and the claim,
 * where assimp would allocate and zero 1.2 GB and post-process for
 * seconds (OutOfMemory.off of assimp-testmodels: 16 GB and a kill). */
static void test_model_claiming_too_much(void **state) {
    (void)state;
    static const char *const programs[][2] = {
        {"planar", "--backend egl --frames 1"}, {"volumes", "--backend egl --frames 1"}, {"raytrace", ""}};
    for (size_t i = 0; i < sizeof programs / sizeof *programs; i++) {
        char command[2048];
        snprintf(command, sizeof command,
                 "timeout 60 %s %s --size 64x36 --scene tests/data/io_cli_model_claims_too_much.json "
                 "--screenshot out/test/io_claims_%s.png",
                 support_program(programs[i][0]), programs[i][1], programs[i][0]);
        assert_int_equal(support_run(command, err, sizeof err), EXIT_RUNTIME);
        assert_int_equal(support_count_lines(err), 1);
        assert_non_null(strstr(err, "io_cli_model_claims_too_much.json: objects[0] \"claims\""));
        assert_non_null(strstr(err, "io_off_claims_too_many.off: OFF header claims 100000000 vertices"));
    }
}

static void test_missing_shader_dir(void **state) {
    (void)state;
    /* The HUD's (every legend's text) is the first any run loads. */
    expect_failure("--frames 1 --shader-dir out/test/no_such_dir", EXIT_RUNTIME, "out/test/no_such_dir/hud.vert",
                   "cannot open");
}

/* A shader with a syntax error: the message names the file and its line
 * (also through an include), then the driver's log follows. */
static void test_broken_shader_names_file_and_line(void **state) {
    (void)state;
    char command[2048];
    /* -L: the shaders' directory may be a link (tests/run.sh runs each
     * build in a tree of links), and the copy must be files of its own. */
    assert_int_equal(system("rm -rf out/test/broken_shaders && mkdir -p out/test && "
                            "cp -rL shaders out/test/broken_shaders && "
                            "sed -i '3s/.*/this is not GLSL;/' out/test/broken_shaders/lighting.glsl"),
                     0);
    snprintf(command, sizeof command, "%s --backend egl --frames 1 --shader-dir out/test/broken_shaders",
             support_program("planar"));
    assert_int_equal(support_run(command, err, sizeof err), EXIT_RUNTIME);
    assert_non_null(strstr(err, "out/test/broken_shaders/lighting.glsl:3:"));
    assert_non_null(strstr(err, "lit.frag"));
    /* An error inside a function of an included file: drivers report those
     * differently from syntax errors, and the file must still be right. */
    assert_int_equal(system("cp shaders/lighting.glsl out/test/broken_shaders/lighting.glsl && "
                            "sed -i 's/return lights_count.y >= 0 ? vec3(0.0).*/return no_such_name;/' "
                            "out/test/broken_shaders/lighting.glsl && "
                            "grep -n no_such_name out/test/broken_shaders/lighting.glsl | "
                            "cut -d: -f1 > out/test/broken_shaders/line.txt"),
                     0);
    char expected[128], line[16] = "";
    FILE *f = fopen("out/test/broken_shaders/line.txt", "r");
    assert_non_null(f);
    assert_non_null(fgets(line, sizeof line, f));
    fclose(f);
    line[strcspn(line, "\n")] = '\0';
    snprintf(expected, sizeof expected, "out/test/broken_shaders/lighting.glsl:%s:", line);
    assert_int_equal(support_run(command, err, sizeof err), EXIT_RUNTIME);
    assert_non_null(strstr(err, expected));
}

static void test_help_lists_flags_and_toggles(void **state) {
    (void)state;
    char command[4096];
    snprintf(command, sizeof command,
             "%s --help | grep -q -- '--no-stencil' && %s --help | grep -q -- "
             "'--backend auto|glfw|egl|osmesa'",
             support_program("planar"), support_program("shadows"));
    assert_int_equal(support_run(command, err, sizeof err), 0);
}

/* README.md's "Keys and flags" is what build/shadows --flags-markdown
 * prints now, between its markers with a blank line either side (as
 * make readme-flags writes it). */
static void test_readme_flags_current(void **state) {
    (void)state;
    char command[1024];
    snprintf(command, sizeof command, "{ %s --flags-markdown > out/test/readme_flags.md; }",
             support_program("shadows"));
    assert_int_equal(support_run(command, err, sizeof err), 0);
    size_t length;
    char *table = path_read_text("out/test/readme_flags.md", README_MAX_BYTES, &length);
    char *readme = path_read_text("README.md", README_MAX_BYTES, NULL);
    assert_non_null(table);
    assert_non_null(readme);
    size_t size = length + 64;
    char *expected = malloc(size);
    assert_non_null(expected);
    snprintf(expected, size, "\n<!-- flags:begin -->\n\n%s\n<!-- flags:end -->\n", table);
    bool current = strstr(readme, expected) != NULL;
    if (!current)
        print_message(
            "README.md's keys and flags are not build/shadows --flags-markdown's: run `make readme-flags`\n");
    free(expected);
    free(readme);
    free(table);
    assert_true(current);
}

/* Long work says how far it is, on a terminal only, on one line each
 * step rewrites (through `script`, which gives it a terminal):
 * build/raytrace's rows; build/shadows' frames headless, recording a
 * video, a tour's (its steps' frames), and baking a truth (the rows traced
 * while it waits for one). Nothing under --quiet, nor where stderr is not
 * a terminal; the picture the same either way. */
static void test_long_work_progress(void **state) {
    (void)state;
    if (!support_have_command("script")) {
        print_message("script (util-linux) is not installed here: skipped\n");
        skip();
    }
    static const struct {
        const char *name, *program, *flags;
        const char *said, *said_too; /* on a terminal (said_too: or NULL) */
        const char *picture;         /* --screenshot's file, after out/test/progress_NAME_MODE */
    } works[] = {
        {"raytrace", "raytrace", "--size 64x36", "raytrace: rows 36 of 36", NULL, ".png"},
        {"record", "shadows", "--backend egl --size 64x36 --frames 3 --record out/test/progress_record.mp4",
         "shadows: frames 3 of 3", NULL, ".png"},
        /* two steps of 3 frames each */
        {"tour", "shadows",
         "--backend egl --size 160x90 --tour tests/data/progress_tour.json --record out/test/progress_tour.mp4",
         "shadows: frames 6 of 6", "shadows: frames 3 of 6, truth rows 17 of 17", "-2.png"},
        {"bake", "shadows", "--backend egl --size 160x90 --compare --bake-truths out/test/progress_truths",
         "shadows: frames 0 of 1, truth rows 17 of 17", "shadows: frames 1 of 1", ".png"},
    };
    static const struct {
        const char *name;
        bool terminal;
        const char *flags;
    } modes[] = {{"terminal", true, ""}, {"quiet", true, "--quiet"}, {"pipe", false, ""}};
    /* The sanitizer pass takes the terminal alone, the one mode that
     * runs the progress line's code; the others only leave it out. */
    size_t mode_count = getenv("TEST_SANITIZER") ? 1 : sizeof modes / sizeof *modes;
    for (size_t w = 0; w < sizeof works / sizeof *works; w++)
        for (size_t m = 0; m < mode_count; m++) {
            char run[1024], command[1200];
            snprintf(run, sizeof run, "%s %s --screenshot out/test/progress_%s_%s.png %s",
                     support_program(works[w].program), works[w].flags, works[w].name, modes[m].name, modes[m].flags);
            if (modes[m].terminal)
                snprintf(command, sizeof command, "{ script -qec \"%s\" /dev/null 1>&2; }", run);
            else
                snprintf(command, sizeof command, "%s", run);
            int status = support_run(command, err, sizeof err);
            if (status != 0)
                fail_msg("%s: exit %d, said \"%s\"", command, status, err);
            bool expected = modes[m].terminal && !modes[m].flags[0];
            bool said = strstr(err, works[w].said) && (!works[w].said_too || strstr(err, works[w].said_too));
            bool any = strstr(err, PROGRESS_REWRITE) != NULL;
            if (expected ? !said : any)
                fail_msg("%s: expected %s, said \"%s\"", command, expected ? works[w].said : "no progress", err);
            char same[512];
            snprintf(same, sizeof same, "cmp -s out/test/progress_%s_%s%s out/test/progress_%s_%s%s", works[w].name,
                     modes[0].name, works[w].picture, works[w].name, modes[m].name, works[w].picture);
            if (system(same) != 0)
                fail_msg("%s: the picture differs from the terminal's", command);
        }
}

/* A headless run that writes nothing says so, and names the flags that
 * would write something. */
static void test_headless_run_says_nothing_written(void **state) {
    (void)state;
    char command[2048];
    snprintf(command, sizeof command, "{ %s --backend egl --size 64x36 --frames 2 1>&2; }",
             support_program("planar"));
    assert_int_equal(support_run(command, err, sizeof err), 0);
    assert_int_equal(support_count_lines(err), 1);
    assert_non_null(strstr(err, "2 frames of"));
    assert_non_null(strstr(err, "nothing written"));
    assert_non_null(strstr(err, "--screenshot"));
}

/* --fullscreen is the window's: a headless run, whether its backend or
 * its output makes it so, refuses it in one line, and every program
 * takes it. */
static void test_headless_run_refuses_fullscreen(void **state) {
    (void)state;
    expect_line("shadows", "--backend egl --size 64x36 --fullscreen", EXIT_RUNTIME,
                "shadows: --fullscreen: this run is headless (egl), with no window to fill");
    expect_line("planar", "--fullscreen --size 64x36 --screenshot out/test/fullscreen.png", EXIT_RUNTIME,
                "planar: --fullscreen: this run is headless");
}

/* A technique that draws an area light hard says so once in three frames,
 * giving the radius in the scene's unit: a sun's in degrees, a point
 * light's in the scene's units. */
static void test_area_light_drawn_hard_said_once_with_its_unit(void **state) {
    (void)state;
    static const struct {
        const char *program, *flags, *scene, *said;
    } cases[] = {
        {"planar", "", "soft_sun", "planar: light 0 is an area light (radius 3 degrees), drawn hard from its centre"},
        {"volumes", "", "soft_sun", "volumes: light 0 is an area light (radius 3 degrees), drawn hard"},
        {"shadowmap", "--soft off", "soft_sun",
         "shadow maps: light 0 is an area light (radius 3 degrees), drawn hard"},
        {"projective", "", "soft_sun", "projective: light 0 is an area light (radius 3 degrees): drawn hard"},
        {"projective", "", "soft_table", "projective: light 0 is an area light (radius 0.8): drawn hard"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        char args[512];
        snprintf(args, sizeof args,
                 "%s --backend egl --size 64x36 --frames 3 --scene assets/scenes/%s.json --screenshot "
                 "out/test/area_light_hard.png",
                 cases[i].flags, cases[i].scene);
        expect_line(cases[i].program, args, 0, cases[i].said);
    }
}

/* The gallery's list of scenes ends at the next flag: --technique there
 * picks the one technique to show; a flag before any scene is exit 2. */
static void test_gallery_takes_flags_after_its_scenes(void **state) {
    (void)state;
    char command[2048];
    snprintf(command, sizeof command,
             "rm -rf out/test/gallery_one && %s --backend egl --size 64x36 --gallery out/test/gallery_one "
             "assets/scenes/simple.json --technique volumes && test -f out/test/gallery_one/volumes_simple.png && "
             "test \"$(ls out/test/gallery_one | tr '\\n' ' ')\" = "
             "'index.html reference_simple.png volumes_simple.png volumes_simple_heatmap.png '",
             support_program("shadows"));
    assert_int_equal(support_run(command, err, sizeof err), 0);
    expect_failure("--gallery out/test/gallery_one --frames 1 assets/scenes/simple.json", EXIT_USAGE, "--gallery",
                   "at least one scene");
}

/* --record: the video ffmpeg wrote has every frame at the picture's size,
 * and the same command writes the same bytes; a path that cannot be
 * written is one line and exit 1. */
static void test_record_writes_a_video(void **state) {
    (void)state;
    expect_failure("--frames 2 --record out/test/no_such_dir/video.mp4", EXIT_RUNTIME, "no_such_dir/video.mp4",
                   "cannot write");
    if (!support_have_command("ffmpeg") || !support_have_command("ffprobe")) {
        fprintf(stderr, "    ffmpeg is not installed here: skipped\n");
        return;
    }
    char command[2048];
    for (int run = 0; run < 2; run++) {
        snprintf(command, sizeof command,
                 "%s --backend egl --size 160x90 --frames 12 --motion light --record out/test/video_%d.mp4",
                 support_program("planar"), run);
        assert_int_equal(support_run(command, err, sizeof err), 0);
    }
    snprintf(command, sizeof command,
             "test \"$(ffprobe -v error -count_frames -select_streams v:0 -show_entries "
             "stream=nb_read_frames,width,height -of csv=p=0 out/test/video_0.mp4)\" = 160,90,12 && "
             "cmp -s out/test/video_0.mp4 out/test/video_1.mp4");
    assert_int_equal(support_run(command, err, sizeof err), 0);
}

/* A GL error raised inside any technique's frame (the test hook of
 * render.h: every object drawn also calls glEnable(0)) fails the run with
 * exit 1 and a line naming the technique: no technique can swallow it. */
static void test_gl_error_in_any_technique_fails(void **state) {
    (void)state;
    for (int t = 0; t < registry_technique_count; t++) {
        const char *name = registry_techniques[t]->name;
        char command[2048], expect[128];
        snprintf(command, sizeof command,
                 RENDER_INJECT_GL_ERROR_ENV "=1 %s --backend egl --size 64x36 --frames 1 --screenshot "
                                            "out/test/gl_error_%s.png",
                 support_program(name), name);
        assert_int_equal(support_run(command, err, sizeof err), EXIT_RUNTIME);
        snprintf(expect, sizeof expect, "%s: GL", name);
        assert_non_null(strstr(err, expect));
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_unknown_flag),
        cmocka_unit_test(test_unknown_flag_suggestions),
        cmocka_unit_test(test_value_flag_given_twice),
        cmocka_unit_test(test_pictures_must_be_png),
        cmocka_unit_test(test_verbose_prints_models),
        cmocka_unit_test(test_malformed_values),
        cmocka_unit_test(test_bad_technique_parameters),
        cmocka_unit_test(test_missing_scene),
        cmocka_unit_test(test_malformed_scene),
        cmocka_unit_test(test_broken_model_file),
        cmocka_unit_test(test_model_claiming_too_much),
        cmocka_unit_test(test_missing_shader_dir),
        cmocka_unit_test(test_broken_shader_names_file_and_line),
        cmocka_unit_test(test_help_lists_flags_and_toggles),
        cmocka_unit_test(test_readme_flags_current),
        cmocka_unit_test(test_headless_run_says_nothing_written),
        cmocka_unit_test(test_long_work_progress),
        cmocka_unit_test(test_headless_run_refuses_fullscreen),
        cmocka_unit_test(test_area_light_drawn_hard_said_once_with_its_unit),
        cmocka_unit_test(test_gallery_takes_flags_after_its_scenes),
        cmocka_unit_test(test_record_writes_a_video),
        cmocka_unit_test(test_gl_error_in_any_technique_fails),
    };
    return cmocka_run_group_tests_name("command line", tests, NULL, NULL);
}
