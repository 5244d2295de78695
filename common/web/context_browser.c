/* Browser backend: the page's canvas as a GLFW window (Emscripten's GLFW,
 * which also delivers the keys and the mouse) with a WebGL 2 context.
 *
 * WebGL 2 is OpenGL ES 3.0. The suite is written against GL 3.3 core and
 * loads its entry points with glad's GL loader, so this backend's loader
 * answers for GL 3.3: GL_VERSION reads as 3.3, so that glad asks for every
 * 3.3 entry point; those WebGL 2 has (samplers, uniform blocks, buffer
 * copies) come back, those it lacks stay NULL, and the context's
 * features (context_set_features) say what is missing. A few desktop
 * names are answered by their ES spelling (glClearDepth by glClearDepthf)
 * or by a WebGL extension's function (glClipControl: EXT_clip_control;
 * glPolygonMode: WEBGL_polygon_mode), and the extensions the suite uses
 * are enabled here, where the browser has them.
 *
 * A run that is not interactive (--frames, --screenshot, --dump: what the
 * browser tests run) gets the canvas's context without a window, so the
 * program runs it as native programs run EGL: headless.
 *
 * The window is the canvas as the page lays it out: its drawing buffer
 * follows its box unless the program fixes its size, and fullscreen is
 * the browser's, of the canvas alone. */
#include <GLFW/glfw3.h>
#include <emscripten/emscripten.h>
#include <emscripten/html5.h>
#include <emscripten/html5_webgl.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "context.h"

/* GL_VERSION: this file includes no GL header. */
#define CONTEXT_BROWSER_GL_VERSION 0x1F02
/* The page's canvas, as Emscripten's html5 functions name it. */
#define CONTEXT_BROWSER_CANVAS "#canvas"

/* What WebGL 2 offers only as extensions, enabled where the browser has
 * them: float colour targets, their blending and linear filtering (the
 * soft sums, the float counter, the moment maps), and what
 * context_features names. */
static const char *const context_browser_extensions[] = {
    "EXT_color_buffer_float", "EXT_float_blend",    "OES_texture_float_linear", "EXT_depth_clamp",
    "EXT_clip_control",       "WEBGL_polygon_mode", "WEBGL_clip_cull_distance",
};
enum { context_browser_extension_count = sizeof context_browser_extensions / sizeof *context_browser_extensions };
static bool context_browser_enabled[context_browser_extension_count];

static bool context_browser_has(const char *extension) {
    for (int i = 0; i < context_browser_extension_count; i++)
        if (strcmp(context_browser_extensions[i], extension) == 0)
            return context_browser_enabled[i];
    return false;
}

EM_JS(void, context_browser_clip_control, (unsigned origin, unsigned depth),
      { GLctx.getExtension('EXT_clip_control').clipControlEXT(origin, depth); });
EM_JS(void, context_browser_polygon_mode, (unsigned face, unsigned mode),
      { GLctx.getExtension('WEBGL_polygon_mode').polygonModeWEBGL(face, mode); });

typedef const unsigned char *(*context_browser_get_string_fn)(unsigned name);
static context_browser_get_string_fn context_browser_webgl_get_string;
typedef void (*context_browser_clear_depthf_fn)(float depth);
static context_browser_clear_depthf_fn context_browser_webgl_clear_depthf;

static const unsigned char *context_browser_get_string(unsigned name) {
    if (name == CONTEXT_BROWSER_GL_VERSION)
        return (const unsigned char *)"3.3 (WebGL 2.0, loaded as GL 3.3 core: what it lacks stays NULL)";
    return context_browser_webgl_get_string(name);
}

static void context_browser_clear_depth(double depth) { context_browser_webgl_clear_depthf((float)depth); }

static context_proc context_browser_proc(const char *name) {
    if (strcmp(name, "glGetString") == 0)
        return (context_proc)context_browser_get_string;
    if (strcmp(name, "glClearDepth") == 0)
        return (context_proc)context_browser_clear_depth;
    if (strcmp(name, "glClipControl") == 0)
        return context_browser_has("EXT_clip_control") ? (context_proc)context_browser_clip_control : NULL;
    if (strcmp(name, "glPolygonMode") == 0)
        return context_browser_has("WEBGL_polygon_mode") ? (context_proc)context_browser_polygon_mode : NULL;
    return (context_proc)emscripten_webgl_get_proc_address(name);
}

static void context_browser_error(int code, const char *description) {
    fprintf(stderr, "GLFW error 0x%x: %s\n", code, description);
}

context_loader context_browser_create(context *c, const context_settings *s) {
    glfwSetErrorCallback(context_browser_error);
    if (!glfwInit()) {
        fprintf(stderr, "context: browser: GLFW cannot initialize\n");
        return NULL;
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_ES_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
    /* Techniques draw into the off-screen target; the canvas only shows it. */
    glfwWindowHint(GLFW_DEPTH_BITS, 0);
    glfwWindowHint(GLFW_STENCIL_BITS, 0);
    GLFWwindow *window = glfwCreateWindow(s->width, s->height, s->title, NULL, NULL);
    if (!window) {
        fprintf(stderr, "context: browser: no WebGL 2 context on the canvas (does the browser have WebGL 2?)\n");
        glfwTerminate();
        return NULL;
    }
    glfwMakeContextCurrent(window);
    if (s->want_window)
        c->window = window;
    else
        c->impl = window;
    EMSCRIPTEN_WEBGL_CONTEXT_HANDLE gl = emscripten_webgl_get_current_context();
    for (int i = 0; i < context_browser_extension_count; i++)
        context_browser_enabled[i] = emscripten_webgl_enable_extension(gl, context_browser_extensions[i]);
    context_browser_webgl_get_string =
        (context_browser_get_string_fn)emscripten_webgl_get_proc_address("glGetString");
    context_browser_webgl_clear_depthf =
        (context_browser_clear_depthf_fn)emscripten_webgl_get_proc_address("glClearDepthf");
    /* WebGL 2's core has none of the rest (context.h). */
    context_set_features(&(context_features){
        .glsl_es = true,
        .polygon_mode = context_browser_has("WEBGL_polygon_mode"),
        .clip_distances = context_browser_has("WEBGL_clip_cull_distance"),
        .depth_clamp = context_browser_has("EXT_depth_clamp"),
        .clip_control = context_browser_has("EXT_clip_control"),
    });
    snprintf(c->platform, sizeof c->platform, "browser canvas (WebGL 2)");
    return context_browser_proc;
}

void context_browser_destroy(context *c) {
    glfwDestroyWindow(c->window ? c->window : c->impl);
    glfwTerminate();
}

/* The box's size times the device's pixel ratio, in whole pixels, or the
 * fixed size; the drawing buffer resized only when that changes (which
 * clears it). */
void context_window_size(context *c, int fixed_width, int fixed_height, int *width, int *height) {
    (void)c;
    int now_width, now_height, wanted_width = fixed_width, wanted_height = fixed_height;
    double box_width, box_height;
    emscripten_get_canvas_element_size(CONTEXT_BROWSER_CANVAS, &now_width, &now_height);
    if (fixed_width <= 0 && emscripten_get_element_css_size(CONTEXT_BROWSER_CANVAS, &box_width, &box_height) ==
                                EMSCRIPTEN_RESULT_SUCCESS) {
        double ratio = emscripten_get_device_pixel_ratio();
        wanted_width = (int)lround(box_width * ratio);
        wanted_height = (int)lround(box_height * ratio);
    }
    if (wanted_width > 0 && wanted_height > 0 && (wanted_width != now_width || wanted_height != now_height) &&
        emscripten_set_canvas_element_size(CONTEXT_BROWSER_CANVAS, wanted_width, wanted_height) ==
            EMSCRIPTEN_RESULT_SUCCESS) {
        now_width = wanted_width;
        now_height = wanted_height;
    }
    *width = now_width;
    *height = now_height;
}

EM_JS(int, context_browser_canvas_fullscreen, (void), { return document.fullscreenElement == Module.canvas; });

/* A browser goes fullscreen only while handling a click or a key (the
 * page's Fullscreen button presses F11): asked at any other time, it
 * refuses, which its promise says. */
EM_JS(void, context_browser_request_fullscreen, (int on), {
    if (!on)
        document.exitFullscreen();
    else
        Module.canvas.requestFullscreen().catch(function() {
            err("fullscreen: the browser refused: it goes fullscreen at a click or a key only " +
                "(the page's Fullscreen button)");
        });
});

bool context_fullscreen(const context *c) {
    (void)c;
    return context_browser_canvas_fullscreen();
}

bool context_set_fullscreen(context *c, bool on) {
    if (on != context_fullscreen(c))
        context_browser_request_fullscreen(on);
    return true;
}
