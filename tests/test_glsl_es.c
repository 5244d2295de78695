/* The browser's dialect and subset, natively: every technique's shaders
 * compiled as GLSL ES 3.00 (--glsl-es) draw the same pictures and dumps,
 * byte for byte, as desktop GLSL; what needs a geometry shader refuses in
 * one line; a line only ES rejects is named by file and line; with
 * nothing beyond WebGL 2's core (--webgl2) every technique still draws,
 * its fallbacks within the golden tolerance. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "flags.h"
#include "registry.h"
#include "support.h"

#define OUT "out/test/glsl_es"
#define ES "--glsl-es"
/* The settings' sweep is about shaders compiling the same: a small frame. */
#define SETTINGS_SIZE "--size 320x180"

static const char *const scenes[] = {"simple", "bunny", "teapot", "soft_table"};
enum { SCENE_COUNT = sizeof scenes / sizeof *scenes };
static const char *const dump_files[] = {"visibility.pfm", "depth.pfm", "normal.pfm",
                                         "position.pfm",   "ids.pfm",   "color.png"};

/* Runs `program FLAGS` (its --size and --scene among them) and writes its
 * screenshot to PNG; fails the running test unless it exits 0. */
static void screenshot(const char *program, const char *flags, const char *png) {
    char command[2048], err[16384];
    snprintf(command, sizeof command, "%s --backend egl %s --screenshot %s", support_program(program), flags, png);
    if (support_run(command, err, sizeof err) != 0)
        fail_msg("%s failed:\n%s", command, err);
}

/* OUT/DESKTOP/NAME and OUT/ES/NAME are the same file, byte for byte. */
#define DESKTOP "desktop"
#define ES_DIR "es"
static void expect_same(const char *name, const char *what) {
    const char *names[] = {name};
    if (support_first_difference(OUT "/" DESKTOP, OUT "/" ES_DIR, names, 1))
        fail_msg("%s: the picture differs with " ES " (" OUT "/{" DESKTOP "," ES_DIR "}/%s)", what, name);
}

/* Every technique on every scene at the golden size: the dump (its
 * color.png the frame's picture) with and without --glsl-es, byte for
 * byte; and with nothing beyond WebGL 2's core (--webgl2), the picture
 * within the golden tolerance of the desktop one (the fallbacks:
 * discarded fragments for clip distances, no depth clamp, no exact depth
 * on huge receivers). */
static void test_dumps_identical_and_subset_close(void **state) {
    (void)state;
    int count = registry_technique_count * SCENE_COUNT;
    for (int i = 0; i < count; i += support_sweep_stride()) {
        const char *technique = registry_techniques[i / SCENE_COUNT]->name;
        const char *name = scenes[i % SCENE_COUNT];
        char scene[256], desktop[256], es[256], subset_flags[512], desktop_png[300], subset_png[256];
        snprintf(scene, sizeof scene, "assets/scenes/%s.json", name);
        snprintf(desktop, sizeof desktop, OUT "/%s_%s_desktop", technique, name);
        snprintf(es, sizeof es, OUT "/%s_%s_es", technique, name);
        assert_int_equal(support_dump(technique, scene, "", desktop), 0);
        assert_int_equal(support_dump(technique, scene, ES, es), 0);
        const char *differs =
            support_first_difference(desktop, es, dump_files, sizeof dump_files / sizeof *dump_files);
        if (differs)
            fail_msg("%s on %s: %s differs with " ES, technique, name, differs);
        snprintf(subset_flags, sizeof subset_flags, "--size 640x360 --scene %s --webgl2", scene);
        snprintf(subset_png, sizeof subset_png, OUT "/%s_%s_webgl2.png", technique, name);
        snprintf(desktop_png, sizeof desktop_png, "%s/color.png", desktop);
        screenshot(technique, subset_flags, subset_png);
        double differing = support_compare_images(desktop_png, subset_png);
        if (differing < 0 || differing > SUPPORT_MAX_DIFFERING)
            fail_msg("%s on %s with --webgl2: %g of the pixels differ", technique, name, differing);
    }
}

/* The flags of parameter p that pick each of its settings but the
 * default, into out[] (at most `room`); returns how many. */
static int setting_flags(const flags_param *p, char (*out)[128], int room) {
    int n = 0;
    if (p->kind == FLAGS_TOGGLE && n < room)
        snprintf(out[n++], sizeof *out, "--no-%s", p->name);
    for (int c = 1; p->kind == FLAGS_CHOICE && p->choices[c] && n < room; c++)
        snprintf(out[n++], sizeof *out, "--%s %s", p->name, p->choices[c]);
    return n;
}

/* Every setting of every technique's own (each a shader variant, or
 * another program), on simple or on soft_table's area light in turn: the same
 * picture in both dialects, or, where the setting needs a geometry
 * shader, a refusal under --glsl-es. */
#define MAX_SETTINGS 16
static void test_settings_identical(void **state) {
    (void)state;
    int compared = 0, step = 0;
    for (int t = 0; t < registry_technique_count; t++) {
        const technique *tech = registry_techniques[t];
        for (int k = 0; k < tech->param_count; k++) {
            char settings[MAX_SETTINGS][128];
            int n = setting_flags(&tech->params[k], settings, MAX_SETTINGS);
            for (int s = 0; s < n; s++, step++) {
                if (step % support_sweep_stride() != 0)
                    continue;
                /* The settings taken take the two scenes in turn:
                 * each program's shaders compile on either. */
                const char *scene = step / support_sweep_stride() % 2 ? "soft_table" : "simple";
                if (strcmp(settings[s], "--silhouette gpu") == 0)
                    continue; /* test_geometry_shader_refused */
                char flags[2400], es_flags[2500];
                snprintf(flags, sizeof flags, SETTINGS_SIZE " --scene assets/scenes/%s.json %s", scene, settings[s]);
                snprintf(es_flags, sizeof es_flags, "%s " ES, flags);
                screenshot(tech->name, flags, OUT "/" DESKTOP "/setting.png");
                screenshot(tech->name, es_flags, OUT "/" ES_DIR "/setting.png");
                char what[2600];
                snprintf(what, sizeof what, "%s %s", tech->name, flags);
                expect_same("setting.png", what);
                compared++;
            }
        }
    }
    print_message("%d settings compared\n", compared);
    assert_true(compared > 0);
}

/* Volumes' GPU silhouettes are a geometry shader's: under --glsl-es one
 * line says so, and the program fails. */
static void test_geometry_shader_refused(void **state) {
    (void)state;
    char command[1024], err[16384];
    snprintf(command, sizeof command,
             "%s --backend egl " SETTINGS_SIZE " --silhouette gpu " ES " --screenshot " OUT "/refused.png",
             support_program("volumes"));
    assert_int_not_equal(support_run(command, err, sizeof err), 0);
    assert_int_equal(support_count_lines(err), 1);
    assert_non_null(strstr(err, "--silhouette gpu"));
    assert_non_null(strstr(err, "geometry shader"));
}

/* GLSL ES is stricter than GLSL 3.30 (no implicit int to float): a line
 * that only ES rejects, in a file an included file includes, is named by
 * file and line under --glsl-es, and compiles without it. */
#define BROKEN_SHADERS OUT "/broken_shaders"
#define BROKEN_FILE "map_2d.glsl"
#define BROKEN_LINE "5"
static void test_es_errors_name_file_and_line(void **state) {
    (void)state;
    char command[1024], err[16384];
    assert_int_equal(support_run("rm -rf " BROKEN_SHADERS " && cp -RL shaders " BROKEN_SHADERS
                                 " && sed -i '" BROKEN_LINE "s/$/ float broken = 1;/' " BROKEN_SHADERS
                                 "/" BROKEN_FILE,
                                 err, sizeof err),
                     0);
    snprintf(command, sizeof command,
             "%s --backend egl " SETTINGS_SIZE " --shader-dir " BROKEN_SHADERS " --screenshot " OUT "/broken.png",
             support_program("shadowmap"));
    assert_int_equal(support_run(command, err, sizeof err), 0);
    snprintf(command, sizeof command,
             "%s --backend egl " SETTINGS_SIZE " --shader-dir " BROKEN_SHADERS " " ES " --screenshot " OUT
             "/broken.png",
             support_program("shadowmap"));
    assert_int_not_equal(support_run(command, err, sizeof err), 0);
    if (!strstr(err, BROKEN_SHADERS "/" BROKEN_FILE ":" BROKEN_LINE ": "))
        fail_msg("the error does not name " BROKEN_FILE ":" BROKEN_LINE ":\n%s", err);
}

/* With nothing beyond WebGL 2's core the volumes' overlay says once that
 * it draws no wire edges. */
static void test_webgl2_says_no_wires(void **state) {
    (void)state;
    char command[1024], err[16384];
    snprintf(command, sizeof command,
             "%s --backend egl " SETTINGS_SIZE " --overlay volumes --frames 2 --webgl2"
             " --screenshot " OUT "/wires.png",
             support_program("volumes"));
    assert_int_equal(support_run(command, err, sizeof err), 0);
    assert_int_equal(support_count_lines(err), 1);
    assert_non_null(strstr(err, "no wire edges"));
}

static int make_directories(void **state) {
    (void)state;
    char err[1024];
    return support_run("mkdir -p " OUT "/" DESKTOP " " OUT "/" ES_DIR, err, sizeof err);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_geometry_shader_refused),
        cmocka_unit_test(test_es_errors_name_file_and_line),
        cmocka_unit_test(test_dumps_identical_and_subset_close),
        cmocka_unit_test(test_settings_identical),
        cmocka_unit_test(test_webgl2_says_no_wires),
    };
    return cmocka_run_group_tests(tests, make_directories, NULL);
}
