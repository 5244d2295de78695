/* The web page (make web, out/web/) in headless Chromium against the
 * native programs: each technique on each standard scene, and a glTF
 * scene from its scene pack, at 640x360, the page's picture and decisions
 * (its own --dump, run in the browser on WebGL 2) against native EGL's. At most WEB_MAX_DIFFERING of the pixels
 * may differ by more than SUPPORT_TOLERANCE, and at most WEB_MAX_DECISIONS
 * of the visibility decisions (no surface, lit, shadowed) may differ. A
 * page that fails fails the test with the browser console's lines. The
 * page's own parts too: its window, menu and HUD, and what it says
 * without WebGL 2. Headless runs go several to a page (web_run), each
 * from a fresh start, which web_batched_runs_start_afresh proves.
 *
 * Skipped where the page is not built (make test builds it where Debian's
 * emscripten is installed) or Chromium is missing, and in the sanitizer
 * pass: the page is one build either way. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <dirent.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "dump.h"
#include "flags.h"
#include "hud.h"
#include "image.h"
#include "path.h"
#include "registry.h"
#include "support.h"

#define OUT "out/test/web"
#define WEB_PAGE "out/web/index.html"
#define WEB_SIZE "640x360"
/* The browser's rasterizer (SwiftShader under ANGLE) is not Mesa's: a
 * two-hundredth of the pixels may round an edge differently. */
#define WEB_MAX_DIFFERING 0.005
#define WEB_MAX_DECISIONS 0.0005
/* Headless Chromium on SwiftShader, as the checks were made; the
 * virtual time budget only bounds a page that never finishes. */
#define WEB_CHROMIUM                                                                                                 \
    "chromium --headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader "                          \
    "--virtual-time-budget=120000 --dump-dom"
#define WEB_MAX_DOM (64 << 20)

static const char *const web_scenes[] = {"simple", "bunny", "teapot"};
enum { web_scene_count = sizeof web_scenes / sizeof *web_scenes };

/* The page, which make web writes into the repository's out/ (a test runs
 * in a directory of its own whose entries link to the repository's, all
 * but out/: tests/run.sh). */
static char web_root[PATH_MAX], web_page[PATH_MAX];

/* Whether the page can be tested here; says why not. */
static bool web_available(void) {
    if (getenv("TEST_SANITIZER"))
        return false;
    assert_non_null(realpath("Makefile", web_root));
    *strrchr(web_root, '/') = '\0';
    snprintf(web_page, sizeof web_page, "%.*s/" WEB_PAGE, (int)(sizeof web_page - sizeof WEB_PAGE - 1), web_root);
    if (access(web_page, R_OK) != 0) {
        printf("web: %s not built (make web needs Debian's emscripten: make deps)\n", web_page);
        return false;
    }
    if (!support_have_command("chromium")) {
        printf("web: chromium not installed (make deps)\n");
        return false;
    }
    return true;
}

/* `text` with every byte but [A-Za-z0-9-_.,/] as %XX. */
static void web_url_encode(const char *text, char *out, size_t size) {
    size_t n = 0;
    for (const unsigned char *c = (const unsigned char *)text; *c && n + 4 < size; c++) {
        if ((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') || strchr("-_.,/", *c))
            out[n++] = (char)*c;
        else
            n += (size_t)snprintf(out + n, size - n, "%%%02X", *c);
    }
    out[n] = '\0';
}

/* A copy of the text of <pre id="ID"...> up to its </pre> ("" when
 * absent); the caller frees it. */
static char *web_element(const char *dom, const char *id) {
    char open[64];
    snprintf(open, sizeof open, "<pre id=\"%s\"", id);
    const char *start = strstr(dom, open);
    start = start ? strchr(start, '>') : NULL;
    if (!start)
        return strdup("");
    start++;
    const char *end = strstr(start, "</pre>");
    return strndup(start, end ? (size_t)(end - start) : strlen(start));
}

static int web_base64_value(char c) {
    const char *alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const char *at = c ? strchr(alphabet, c) : NULL;
    return at ? (int)(at - alphabet) : -1;
}

/* Decodes `length` characters of base64 into `path`. */
static bool web_write_base64(const char *text, size_t length, const char *path) {
    FILE *f = fopen(path, "wb");
    if (!f)
        return false;
    unsigned bits = 0;
    int count = 0;
    for (size_t i = 0; i < length; i++) {
        int v = web_base64_value(text[i]);
        if (v < 0)
            continue; /* padding */
        bits = bits << 6 | (unsigned)v;
        count += 6;
        if (count >= 8) {
            count -= 8;
            fputc((int)(bits >> count & 0xff), f);
        }
    }
    return fclose(f) == 0;
}

/* The most headless runs one page takes (?args= once each, index.html):
 * each run but the first is spared the browser's start and the page's
 * load, and a bound keeps one page well within the virtual time budget. */
#define WEB_BATCH_RUNS 8

/* Run K's part of the page's console: the lines after its "== run K: "
 * line, up to the next run's (the page's whole console for one run). */
static char *web_run_console(const char *console, int k, int count) {
    if (count == 1)
        return strdup(console);
    char marker[32];
    snprintf(marker, sizeof marker, "== run %d: ", k);
    const char *start = strstr(console, marker);
    if (!start)
        return strdup("");
    start += strcspn(start, "\n");
    start += *start == '\n';
    const char *end = strstr(start, "== run ");
    return strndup(start, end ? (size_t)(end - start) : strlen(start));
}

/* Runs the page in headless Chromium with the program's args[0..count)
 * (one run, or up to WEB_BATCH_RUNS headless ones, one after another),
 * the page's `query` (keys, frames: index.html) and its own `browser`
 * flags. Run K's files under /out (of the names in `exported`) and its
 * console's lines (console.txt) go into dirs[K], made anew (no picture of
 * an earlier run stays to be found there), the page's DOM (page.html)
 * into dirs[0]. Fails the running test, with the page's console, unless
 * each run's status line starts with `expected`. */
static void web_run_page(const char *const *args, int count, const char *query, const char *exported,
                         const char *browser, const char *expected, const char *const *dirs) {
    assert_true(count >= 1 && count <= WEB_BATCH_RUNS);
    char url[8192], dom_path[PATH_MAX + 16], command[16384];
    int n = snprintf(url, sizeof url, "file://%s?", web_page);
    for (int k = 0; k < count; k++) {
        char encoded[2048];
        web_url_encode(args[k], encoded, sizeof encoded);
        n += snprintf(url + n, sizeof url - (size_t)n, "%sargs=%s", k ? "&" : "", encoded);
    }
    n += snprintf(url + n, sizeof url - (size_t)n, "&export=%s%s", exported, query);
    assert_true(n < (int)sizeof url);
    n = snprintf(command, sizeof command, "{ ");
    for (int k = 0; k < count; k++)
        n += snprintf(command + n, sizeof command - (size_t)n, "rm -rf %s && mkdir -p %s && ", dirs[k], dirs[k]);
    /* The DOM to a file, and Chromium's own log (its sandbox and bus
     * notes) to another: support_run redirects the command's outputs. */
    snprintf(dom_path, sizeof dom_path, "%s/page.html", dirs[0]);
    n += snprintf(command + n, sizeof command - (size_t)n,
                  WEB_CHROMIUM
                  " %s --user-data-dir=\"$PWD/%s/profile\" '%s' > %s 2> %s/chromium.log; rm -rf %s/profile; }",
                  browser, dirs[0], url, dom_path, dirs[0], dirs[0]);
    assert_true(n < (int)sizeof command);
    char errors[4096];
    int status = support_run(command, errors, sizeof errors);
    size_t length;
    char *dom = path_read_text(dom_path, WEB_MAX_DOM, &length);
    assert_non_null(dom);
    char *exit_lines = web_element(dom, "status"), *console = web_element(dom, "console");
    char *files = web_element(dom, "files");
    free(dom);
    bool ok = status == 0;
    const char *line = exit_lines;
    for (int k = 0; k < count; k++) {
        char console_path[PATH_MAX + 16];
        snprintf(console_path, sizeof console_path, "%s/console.txt", dirs[k]);
        char *said = web_run_console(console, k, count);
        FILE *console_file = fopen(console_path, "w");
        bool written = console_file && fputs(said, console_file) >= 0;
        written = (console_file && fclose(console_file) == 0) && written;
        free(said);
        size_t line_length = strcspn(line, "\n");
        bool run_ok = written && strncmp(line, expected, strlen(expected)) == 0;
        printf("web: %s: %s%.*s\n", args[k], run_ok ? "" : "failed: ", (int)line_length, line);
        ok = ok && run_ok;
        line += line_length + (line[line_length] == '\n');
    }
    if (!ok)
        printf("web: chromium %d, the page's console:\n%s\n", status, console);
    for (char *entry = files, *next; ok && *entry; entry = next) {
        next = entry + strcspn(entry, "\n");
        if (*next)
            *next++ = '\0';
        char *space = strchr(entry, ' ');
        if (!space)
            continue;
        *space = '\0';
        /* "/out-K/..." for run K of several, "/out/..." for one. */
        int k = count > 1 ? atoi(entry + strlen("/out-")) : 0;
        const char *name = strrchr(entry, '/') ? strrchr(entry, '/') + 1 : entry;
        char path[2 * PATH_MAX];
        snprintf(path, sizeof path, "%s/%s", dirs[k >= 0 && k < count ? k : 0], name);
        ok = web_write_base64(space + 1, strlen(space + 1), path);
    }
    free(exit_lines);
    free(console);
    free(files);
    assert_true(ok);
}

/* One run of the page (a window, or what the page says without one):
 * web_run_page's with one run, whose files go into dir. */
static void web_open_page(const char *args, const char *query, const char *exported, const char *browser,
                          const char *expected, const char *dir) {
    web_run_page(&args, 1, query, exported, browser, expected, &dir);
}

/* Headless runs of the program in pages of up to WEB_BATCH_RUNS runs
 * each, which must exit 0: run K's files in dirs[K]. */
static void web_run(const char *const *args, int count, const char *exported, const char *const *dirs) {
    for (int first = 0; first < count; first += WEB_BATCH_RUNS) {
        int batch = count - first < WEB_BATCH_RUNS ? count - first : WEB_BATCH_RUNS;
        web_run_page(args + first, batch, "", exported, "", "exit 0 ", dirs + first);
    }
}

/* The share of pixels whose decision (no surface, lit, shadowed at half
 * the light) differs between two visibility.pfm files. */
static double web_decisions_differing(const char *a_dir, const char *b_dir) {
    char a_path[PATH_MAX + 16], b_path[PATH_MAX + 16];
    snprintf(a_path, sizeof a_path, "%s/visibility.pfm", a_dir);
    snprintf(b_path, sizeof b_path, "%s/visibility.pfm", b_dir);
    int aw, ah, bw, bh;
    float *a = dump_read_pfm(a_path, &aw, &ah, 1), *b = dump_read_pfm(b_path, &bw, &bh, 1);
    assert_non_null(a);
    assert_non_null(b);
    assert_true(aw == bw && ah == bh);
    long differing = 0;
    for (long i = 0; i < (long)aw * ah; i++) {
        int da = a[i] < 0 ? 0 : a[i] >= 0.5f ? 1 : 2, db = b[i] < 0 ? 0 : b[i] >= 0.5f ? 1 : 2;
        differing += da != db;
    }
    free(a);
    free(b);
    return (double)differing / ((double)aw * ah);
}

/* A technique on a scene file (from the repository's root, the page's
 * own path too), its pictures and decisions in OUT/NAME_native and
 * OUT/NAME_web. */
typedef struct web_case {
    char technique[64], scene[128], name[256];
    char native_dir[PATH_MAX], web_dir[PATH_MAX], args[512];
} web_case;
/* Every technique on every standard scene, at most. */
#define WEB_MAX_CASES 64

/* The page's picture and decisions against native EGL's, for each of
 * `count` cases: the native runs, then the page's (in batches: web_run),
 * then each case's figures. */
static void web_compare_with_native(web_case *cases, int count) {
    const char *args[WEB_MAX_CASES], *dirs[WEB_MAX_CASES];
    assert_true(count <= WEB_MAX_CASES);
    for (int c = 0; c < count; c++) {
        web_case *w = &cases[c];
        char flags[256];
        snprintf(w->native_dir, sizeof w->native_dir, OUT "/%s_native", w->name);
        snprintf(w->web_dir, sizeof w->web_dir, OUT "/%s_web", w->name);
        snprintf(flags, sizeof flags, "--backend egl --technique %s", w->technique);
        assert_int_equal(support_dump("shadows", w->scene, flags, w->native_dir), 0);
        snprintf(w->args, sizeof w->args, "--technique %s --scene /%s --size " WEB_SIZE " --dump dump", w->technique,
                 w->scene);
        args[c] = w->args;
        dirs[c] = w->web_dir;
    }
    web_run(args, count, "color.png,visibility.pfm", dirs);
    for (int c = 0; c < count; c++) {
        const web_case *w = &cases[c];
        char native_png[PATH_MAX + 16], web_png[PATH_MAX + 16];
        snprintf(native_png, sizeof native_png, "%s/color.png", w->native_dir);
        snprintf(web_png, sizeof web_png, "%s/color.png", w->web_dir);
        double pixels = support_compare_images(native_png, web_png);
        double decisions = web_decisions_differing(w->native_dir, w->web_dir);
        printf("web: %s on %s: %.3f %% of the pixels differ, %.4f %% of the decisions\n", w->technique, w->scene,
               100 * pixels, 100 * decisions);
        assert_true(pixels >= 0 && pixels <= WEB_MAX_DIFFERING);
        assert_true(decisions <= WEB_MAX_DECISIONS);
    }
}

/* Every technique on every standard scene (in make test's quick tier, each
 * technique on one scene in turn): the page against native EGL. */
static void web_matches_native(void **state) {
    (void)state;
    if (!web_available())
        skip();
    static web_case cases[WEB_MAX_CASES];
    int count = 0;
    assert_true(registry_technique_count * web_scene_count <= WEB_MAX_CASES);
    for (int t = 0; t < registry_technique_count; t++) {
        for (int s = 0; s < web_scene_count; s++) {
            if (!support_sweep_takes(t, s, web_scene_count))
                continue;
            web_case *w = &cases[count++];
            snprintf(w->technique, sizeof w->technique, "%s", registry_techniques[t]->name);
            snprintf(w->scene, sizeof w->scene, "assets/scenes/%s.json", web_scenes[s]);
            snprintf(w->name, sizeof w->name, "%s_%s", registry_techniques[t]->name, web_scenes[s]);
        }
    }
    web_compare_with_native(cases, count);
}

/* The glTF scenes in the page, their scene packs baked from the files
 * (the fence's cut-out leaves, textures and single-sided boards; the
 * stained glass's translucent panes), each with one technique against
 * native EGL, which reads the glTF file itself: volumes, whose cut-out
 * casters cast their whole shadow in both, and shadowmap, whose
 * transmittance maps must fit the page's sampler units. */
#define WEB_GLTF_SCENE "assets/scenes/fence.gltf"
#define WEB_GLTF_TECHNIQUE "volumes"
#define WEB_GLASS_SCENE "assets/scenes/stained_glass.gltf"
#define WEB_GLASS_TECHNIQUE "shadowmap"
static void web_gltf_scene_matches_native(void **state) {
    (void)state;
    if (!web_available())
        skip();
    static web_case cases[] = {
        {.technique = WEB_GLTF_TECHNIQUE, .scene = WEB_GLTF_SCENE, .name = WEB_GLTF_TECHNIQUE "_fence"},
        {.technique = WEB_GLASS_TECHNIQUE, .scene = WEB_GLASS_SCENE, .name = WEB_GLASS_TECHNIQUE "_glass"},
    };
    web_compare_with_native(cases, sizeof cases / sizeof *cases);
}

/* The window's keys in the page (each a GLFW key through Emscripten's
 * GLFW, as a keyboard's): 3 picks the shadow maps, F12 saves the window's
 * picture, C and L turn the biases off, which must change it; each
 * picture is the native program's with the same technique and flags. */
static void web_keys_switch_and_toggle(void **state) {
    (void)state;
    if (!web_available())
        skip();
    const char *dir = OUT "/keys";
    web_open_page("--no-hud --size " WEB_SIZE " --scene /assets/scenes/simple.json",
                  "&keys=2:3,4:F12,5:C,5:L,7:F12&frames=8", "screenshot-shadowmap-1.png,screenshot-shadowmap-2.png",
                  "", "frames 8", dir);
    static const struct {
        const char *web, *flags;
    } pictures[] = {
        {"screenshot-shadowmap-1.png", ""},
        {"screenshot-shadowmap-2.png", "--no-constant-bias --no-slope-bias"},
    };
    for (size_t i = 0; i < sizeof pictures / sizeof *pictures; i++) {
        char name[64], flags[256], native[PATH_MAX], web[PATH_MAX];
        snprintf(name, sizeof name, "web/keys_native_%zu", i);
        snprintf(flags, sizeof flags, "--backend egl --technique shadowmap %s", pictures[i].flags);
        free(support_screenshot("shadows", "assets/scenes/simple.json", flags, name));
        snprintf(native, sizeof native, "out/test/%s.png", name);
        snprintf(web, sizeof web, "%s/%s", dir, pictures[i].web);
        double differing = support_compare_images(native, web);
        printf("web: keys: %s: %.3f %% of the pixels differ from native %s\n", pictures[i].web, 100 * differing,
               flags);
        assert_true(differing >= 0 && differing <= WEB_MAX_DIFFERING);
    }
    char before[PATH_MAX], after[PATH_MAX];
    snprintf(before, sizeof before, "%s/%s", dir, pictures[0].web);
    snprintf(after, sizeof after, "%s/%s", dir, pictures[1].web);
    assert_true(support_compare_images(before, after) > WEB_MAX_DIFFERING);
}

/* The page's window without --size, in a Chromium window
 * WEB_WINDOW_WIDTH wide at WEB_PIXEL_RATIO device pixels to a CSS pixel:
 * the canvas spans the page's width in device pixels, and is less tall
 * than the window (the menu and the status share it). The menu's
 * technique button starts its technique (F12's picture is named by it)
 * and shows it pressed; the scene menu lists the glTF scenes; Esc does
 * not stop the page. The HUD shows no frame time, which the browser's
 * clock cannot measure: its second line ends with the picture's size,
 * nothing in white after it. The menu's compare button turns compare
 * mode on, whose picture takes the size its truths are baked at (make
 * web: build/shadows' default) whatever the window's. */
#define WEB_WINDOW_WIDTH 1000
#define WEB_WINDOW_HEIGHT 700
#define WEB_PIXEL_RATIO 1.5
#define WEB_WINDOW_FLAGS "--window-size=1000,700 --force-device-scale-factor=1.5"
#define WEB_HUD_SCALE 2
#define WEB_HUD_WHITE 250 /* the HUD's text is white; its panel and the sky behind it dark */
#define WEB_MENU_TECHNIQUE "shadowmap"
#define WEB_BAKED_WIDTH 1280
#define WEB_BAKED_HEIGHT 720

/* The pixels of `picture` in [x0, x1) x [y0, y1) that are white in every
 * channel. */
static long web_white_pixels(const unsigned char *picture, int width, int x0, int x1, int y0, int y1) {
    long white = 0;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1 && x < width; x++) {
            const unsigned char *p = picture + 4 * ((size_t)y * (size_t)width + (size_t)x);
            white += p[0] >= WEB_HUD_WHITE && p[1] >= WEB_HUD_WHITE && p[2] >= WEB_HUD_WHITE;
        }
    return white;
}

/* The glTF scenes the page embeds, which its scene menu lists. */
static const char *const web_menu_gltf_scenes[] = {"fence.gltf", "stained_glass.gltf"};

static void web_window_fills_the_page_and_menu_drives_it(void **state) {
    (void)state;
    if (!web_available())
        skip();
    const char *dir = OUT "/menu";
    web_open_page("--hud-scale " FLAGS_TEXT(WEB_HUD_SCALE),
                  "&click=2:technique-" WEB_MENU_TECHNIQUE ",5:compare&keys=3:Escape,4:F12,7:F12&frames=7",
                  "screenshot-" WEB_MENU_TECHNIQUE "-1.png,screenshot-" WEB_MENU_TECHNIQUE "-2.png", WEB_WINDOW_FLAGS,
                  "frames 7", dir);
    int width, height;
    unsigned char *picture = image_read_png(OUT "/menu/screenshot-" WEB_MENU_TECHNIQUE "-1.png", &width, &height);
    if (!picture)
        fail_msg("the menu's %s button did not start it: no F12 picture of it", WEB_MENU_TECHNIQUE);
    printf("web: the page's window: %dx%d device pixels\n", width, height);
    assert_int_equal(width, (int)(WEB_WINDOW_WIDTH * WEB_PIXEL_RATIO));
    assert_true(height > 0 && height < (int)(WEB_WINDOW_HEIGHT * WEB_PIXEL_RATIO));
    char *dom = path_read_text(OUT "/menu/page.html", WEB_MAX_DOM, NULL);
    assert_non_null(dom);
    assert_non_null(strstr(dom, "id=\"technique-" WEB_MENU_TECHNIQUE "\" aria-pressed=\"true\""));
    for (size_t k = 0; k < sizeof web_menu_gltf_scenes / sizeof *web_menu_gltf_scenes; k++) {
        char option[128];
        snprintf(option, sizeof option, "<option value=\"%s\">", web_menu_gltf_scenes[k]);
        if (!strstr(dom, option))
            fail_msg("the scene menu has no %s", option);
    }
    free(dom);
    char size_line[64];
    snprintf(size_line, sizeof size_line, "scene simple   %dx%d", width, height);
    int top = (HUD_MARGIN + HUD_LINE_UNITS) * WEB_HUD_SCALE, bottom = top + HUD_LINE_UNITS * WEB_HUD_SCALE;
    int end = (HUD_MARGIN + hud_text_width(size_line)) * WEB_HUD_SCALE;
    long said = web_white_pixels(picture, width, HUD_MARGIN * WEB_HUD_SCALE, end, top, bottom);
    long after = web_white_pixels(picture, width, end, width, top, bottom);
    printf("web: the HUD's second line: %ld white pixels in \"%s\", %ld after it\n", said, size_line, after);
    assert_true(said > 0);
    assert_int_equal(after, 0);
    free(picture);
    picture = image_read_png(OUT "/menu/screenshot-" WEB_MENU_TECHNIQUE "-2.png", &width, &height);
    assert_non_null(picture);
    printf("web: the page's window in compare mode: %dx%d device pixels\n", width, height);
    assert_int_equal(width, WEB_BAKED_WIDTH);
    assert_int_equal(height, WEB_BAKED_HEIGHT);
    free(picture);
}

/* Without WebGL 2 (Chromium's --disable-webgl) the page says so in one
 * sentence and starts nothing: no line of the program's. */
#define WEB_NO_WEBGL2 "This page needs WebGL 2, which this browser does not offer."
static void web_without_webgl2_says_so(void **state) {
    (void)state;
    if (!web_available())
        skip();
    web_open_page("", "", "", "--disable-webgl", WEB_NO_WEBGL2, OUT "/no_webgl2");
    char *status = path_read_text(OUT "/no_webgl2/page.html", WEB_MAX_DOM, NULL);
    assert_non_null(status);
    char *said = web_element(status, "status"),
         *console = path_read_text(OUT "/no_webgl2/console.txt", 1 << 16, NULL);
    assert_string_equal(said, WEB_NO_WEBGL2);
    assert_non_null(console);
    assert_string_equal(console, "");
    free(said);
    free(console);
    free(status);
}

/* Runs batched in one page start afresh: a run after another that set
 * other flags, another technique's, and compare mode (whose layout a
 * program that kept it would draw) dumps the same files as the same run
 * before it. */
#define WEB_FRESH_RUN "--technique shadowmap --scene /assets/scenes/simple.json --size 320x180 --dump dump"
#define WEB_OTHER_RUN                                                                                                \
    "--technique shadowmap --filter hw --no-constant-bias --map-size 256 --scene /assets/scenes/bunny.json "         \
    "--compare --size 320x180 --screenshot other.png"
static void web_batched_runs_start_afresh(void **state) {
    (void)state;
    if (!web_available())
        skip();
    const char *args[] = {WEB_FRESH_RUN, WEB_OTHER_RUN, WEB_FRESH_RUN};
    const char *dirs[] = {OUT "/fresh_first", OUT "/fresh_other", OUT "/fresh_after"};
    web_run(args, 3, "color.png,visibility.pfm,other.png", dirs);
    static const char *const files[] = {"color.png", "visibility.pfm"};
    const char *differs = support_first_difference(dirs[0], dirs[2], files, 2);
    if (differs)
        fail_msg("%s differs between a run and the same run after " WEB_OTHER_RUN, differs);
}

/* A tour in the page: Space steps it, and the step shown is the native
 * headless tour's picture of that step. */
#define WEB_TOUR "shadowmap"
#define WEB_TOUR_STEP 4 /* from 1: a step whose light and camera stay put */
/* F12's picture of that step: its technique's first. */
#define WEB_TOUR_PICTURE "screenshot-shadowmap-1.png"
static void web_tour_steps(void **state) {
    (void)state;
    if (!web_available())
        skip();
    const char *dir = OUT "/tour";
    web_open_page("--no-hud --size " WEB_SIZE " --tour /assets/tours/" WEB_TOUR ".json",
                  "&keys=2:Space,3:Space,4:Space,6:F12&frames=7", WEB_TOUR_PICTURE, "", "frames 7", dir);
    char command[512], errors[4096];
    snprintf(command, sizeof command,
             "%s --backend egl --size " WEB_SIZE " --tour assets/tours/" WEB_TOUR ".json --screenshot " OUT
             "/tour_native.png > /dev/null",
             support_program("shadows"));
    assert_int_equal(support_run(command, errors, sizeof errors), 0);
    char native[PATH_MAX];
    snprintf(native, sizeof native, OUT "/tour_native-%d.png", WEB_TOUR_STEP);
    const char *web = OUT "/tour/" WEB_TOUR_PICTURE;
    double differing = support_compare_images(native, web);
    printf("web: tour " WEB_TOUR " step %d: %.3f %% of the pixels differ from native\n", WEB_TOUR_STEP,
           100 * differing);
    assert_true(differing >= 0 && differing <= WEB_MAX_DIFFERING);
}

/* A tour's caption in the page, as in the window (tests/window_input.sh):
 * the keys of support_expect_captions, which checks what each F12's HUD
 * said (the page's console) and how its caption is drawn. The step is
 * reached at frame 4; a key that changes the technique starts it, a frame
 * before F12 shows it. */
static void web_tour_caption_stays_true(void **state) {
    (void)state;
    if (!web_available())
        skip();
    const char *dir = OUT "/caption";
    web_open_page("--verbose --size " SUPPORT_CAPTION_SIZE " --tour /" SUPPORT_CAPTION_TOUR,
                  "&keys=2:Space,3:Space,4:Space,6:F12,7:6,9:F12,10:3,12:F12,13:C,15:F12&frames=16",
                  "screenshot-shadowmap-1.png,screenshot-volumes-1.png,screenshot-shadowmap-2.png,"
                  "screenshot-shadowmap-3.png",
                  "", "frames 16", dir);
    char *console = path_read_text(OUT "/caption/console.txt", WEB_MAX_DOM, NULL);
    assert_non_null(console);
    static const char *const pictures[SUPPORT_CAPTION_PICTURES] = {
        OUT "/caption/screenshot-shadowmap-1.png", OUT "/caption/screenshot-volumes-1.png",
        OUT "/caption/screenshot-shadowmap-2.png", OUT "/caption/screenshot-shadowmap-3.png"};
    support_expect_captions(console, pictures);
    free(console);
}

/* Every tour, every step headless in the page at the page's own size
 * (build/shadows' default, the canvas's in compare mode), and each
 * standard and soft scene's loaded view in compare mode, against the native EGL run that
 * baked their truths (make web: build-web/baking/RUN/, its pictures and
 * figures.txt): each picture within WEB_MAX_TOUR_DIFFERING, the lecture's
 * artifacts (z-fighting, acne) being each rasterizer's own coin tosses;
 * each compare picture's figures against its baked truth within
 * WEB_MAX_DECISIONS of native's against the traced one: the share of
 * pixels misclassified, and of pixels compared. Where the page's technique
 * itself decides otherwise than native's, its run says by how much more
 * the misclassified share may differ. (The scenes simple, teapot,
 * long_view and soft_table are the tours' compare steps.)
 * The quick tier takes every support_sweep_stride()th run. */
#define WEB_MAX_TOUR_DIFFERING 0.02
#define WEB_BAKING "build-web/baking"
#define WEB_MAX_COMPARED 16
static const struct {
    const char *baked;        /* the run's folder in WEB_BAKING */
    const char *args;         /* the same run in the page, its pictures named as native's */
    double misclassified_gap; /* a share; 0: WEB_MAX_DECISIONS */
} web_baked_runs[] = {
    {"tours/overview", "--tour /assets/tours/overview.json --screenshot step.png", 0},
    {"tours/planar", "--tour /assets/tours/planar.json --screenshot step.png", 0},
    {"tours/projective", "--tour /assets/tours/projective.json --screenshot step.png", 0},
    {"tours/shadowmap", "--tour /assets/tours/shadowmap.json --screenshot step.png", 0},
    /* SwiftShader places psm's warped map on long_view a little otherwise
     * than Mesa (which, under --webgl2, matches native): the page's psm
     * itself decides some pixels otherwise, so its compare step's
     * misclassified share may differ by up to a hundredth. */
    {"tours/psm", "--tour /assets/tours/psm.json --screenshot step.png", 0.01},
    {"tours/soft", "--tour /assets/tours/soft.json --screenshot step.png", 0},
    {"tours/volumes", "--tour /assets/tours/volumes.json --screenshot step.png", 0},
    {"tours/hybrid", "--tour /assets/tours/hybrid.json --screenshot step.png", 0},
    {"scenes/bunny", "--scene /assets/scenes/bunny.json --compare --screenshot compare.png", 0},
    {"scenes/soft_sun", "--scene /assets/scenes/soft_sun.json --compare --screenshot compare.png", 0},
    {"scenes/fence", "--scene /assets/scenes/fence.gltf --compare --screenshot compare.png", 0},
};

/* A compare picture's figures, as compare_figures_text writes them. */
typedef struct web_figures {
    double misclassified_percent;
    long compared;
} web_figures;

/* The figures of each "compare: " line of the text file at `path`, in
 * order. */
static int web_read_figures(const char *path, web_figures out[WEB_MAX_COMPARED]) {
    char *text = path_read_text(path, WEB_MAX_DOM, NULL);
    assert_non_null(text);
    int n = 0;
    for (const char *at = text; n < WEB_MAX_COMPARED && (at = strstr(at, "compare: ")); at++) {
        const char *misclassified = strstr(at, "misclassified "), *error = strstr(at, "mean absolute error ");
        double mean;
        if (misclassified && error &&
            sscanf(misclassified, "misclassified %lf", &out[n].misclassified_percent) == 1 &&
            sscanf(error, "mean absolute error %lf, %ld pixels compared", &mean, &out[n].compared) == 2)
            n++;
    }
    free(text);
    return n;
}

static void web_baked_runs_match_native(void **state) {
    (void)state;
    if (!web_available())
        skip();
    enum { run_count = sizeof web_baked_runs / sizeof *web_baked_runs };
    const char *args[run_count], *dirs[run_count];
    char dir_names[run_count][256];
    size_t taken[run_count];
    int count = 0;
    for (size_t r = 0; r < run_count; r += (size_t)support_sweep_stride()) {
        snprintf(dir_names[count], sizeof dir_names[count], OUT "/%s", web_baked_runs[r].baked);
        args[count] = web_baked_runs[r].args;
        dirs[count] = dir_names[count];
        taken[count++] = r;
    }
    web_run(args, count, "", dirs);
    for (int c = 0; c < count; c++) {
        size_t r = taken[c];
        const char *dir = dirs[c];
        char native_dir[2 * PATH_MAX], native[3 * PATH_MAX], web[3 * PATH_MAX];
        snprintf(native_dir, sizeof native_dir, "%s/" WEB_BAKING "/%s", web_root, web_baked_runs[r].baked);
        DIR *pictures = opendir(native_dir);
        if (!pictures)
            fail_msg("%s: not baked (make web)", native_dir);
        int compared = 0;
        for (const struct dirent *e; (e = readdir(pictures));) {
            size_t length = strlen(e->d_name);
            if (length < 4 || strcmp(e->d_name + length - 4, ".png") != 0)
                continue;
            snprintf(native, sizeof native, "%s/%s", native_dir, e->d_name);
            snprintf(web, sizeof web, "%s/%s", dir, e->d_name);
            double differing = support_compare_images(native, web);
            printf("web: %s %s: %.3f %% of the pixels differ from native\n", web_baked_runs[r].baked, e->d_name,
                   100 * differing);
            assert_true(differing >= 0 && differing <= WEB_MAX_TOUR_DIFFERING);
            compared++;
        }
        closedir(pictures);
        assert_true(compared > 0);
        web_figures native_figures[WEB_MAX_COMPARED], page_figures[WEB_MAX_COMPARED];
        snprintf(native, sizeof native, "%s/figures.txt", native_dir);
        snprintf(web, sizeof web, "%s/console.txt", dir);
        int count = web_read_figures(native, native_figures);
        assert_int_equal(web_read_figures(web, page_figures), count);
        for (int k = 0; k < count; k++) {
            const web_figures *a = &page_figures[k], *b = &native_figures[k];
            printf("web: %s compare picture %d: misclassified %.4f %% (native %.4f %%), %ld pixels compared "
                   "(native %ld)\n",
                   web_baked_runs[r].baked, k + 1, a->misclassified_percent, b->misclassified_percent, a->compared,
                   b->compared);
            double gap =
                web_baked_runs[r].misclassified_gap ? web_baked_runs[r].misclassified_gap : WEB_MAX_DECISIONS;
            assert_true(fabs(a->misclassified_percent - b->misclassified_percent) / 100 <= gap);
            assert_true(fabs((double)(a->compared - b->compared)) / (double)b->compared <= WEB_MAX_DECISIONS);
        }
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(web_matches_native),
        cmocka_unit_test(web_gltf_scene_matches_native),
        cmocka_unit_test(web_keys_switch_and_toggle),
        cmocka_unit_test(web_window_fills_the_page_and_menu_drives_it),
        cmocka_unit_test(web_without_webgl2_says_so),
        cmocka_unit_test(web_batched_runs_start_afresh),
        cmocka_unit_test(web_tour_steps),
        cmocka_unit_test(web_tour_caption_stays_true),
        cmocka_unit_test(web_baked_runs_match_native),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
