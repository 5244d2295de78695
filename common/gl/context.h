/* context: an OpenGL 3.3 core context on one of three backends.
 *
 *   CONTEXT_GLFW    a window (GLFW 3.3), for interactive demos;
 *   CONTEXT_EGL     headless: EGL's device platform on a GPU
 *                   (EGL_EXT_platform_device), else Mesa's surfaceless
 *                   platform (software rasterizer);
 *   CONTEXT_OSMESA  headless: libOSMesa, loaded at run time with dlopen
 *                   because recent Mesa releases no longer ship it, so the
 *                   programs build and run where it is missing;
 *   CONTEXT_BROWSER the web build's only one (make web): the page's
 *                   canvas with WebGL 2 (common/web/context_browser.c);
 *   CONTEXT_AUTO    a window when asked for one and a display is there,
 *                   else EGL, else OSMesa; in the web build, the browser.
 *
 * context_create also loads the GL entry points (glad, through the
 * backend's get-proc-address: no GL symbol is linked directly) and turns on
 * KHR_debug output where the driver has it. GL errors are bugs here:
 * context_gl_ok reports every error raised since the last call, and any
 * uniform asked of a program that does not declare it (shader_uniform),
 * naming `where`, and returns false.
 *
 * Rendering never targets the window's framebuffer directly: see target.h.
 *
 * context_current_features says what the context has beyond WebGL 2's
 * core (OpenGL ES 3.0), the browser's: the one place a pass asks before
 * a call, capability or shader stage that WebGL 2 lacks or has only as an
 * extension. context_create fills it for a desktop GL 3.3 core context
 * (all of it, the ES dialect off); context_settings.glsl_es and .webgl2
 * turn off what WebGL 2 lacks, so that the browser's paths run natively; a
 * backend whose context is WebGL's gives its own (context_set_features).
 */
#ifndef CONTEXT_H
#define CONTEXT_H

#include <stdbool.h>

typedef enum context_backend {
    CONTEXT_AUTO,
    CONTEXT_GLFW,
    CONTEXT_EGL,
    CONTEXT_OSMESA,
    CONTEXT_BROWSER,
} context_backend;

typedef struct context_settings {
    context_backend backend;
    bool want_window;  /* AUTO picks GLFW only for interactive runs */
    int width, height; /* window size (headless: unused) */
    const char *title;
    bool verbose; /* print backend, platform and GL renderer */
    /* Shaders in GLSL ES 3.00, the browser's dialect, which has no
     * geometry stage (Mesa's desktop contexts take it). */
    bool glsl_es;
    /* That, and nothing beyond WebGL 2's core: its extensions' features
     * off too. */
    bool webgl2;
} context_settings;

typedef struct context_features {
    bool glsl_es;          /* shaders compile as GLSL ES 3.00 (shader.h) */
    bool desktop_gl;       /* desktop GL: desktop GLSL compiles, GL_TEXTURE_CUBE_MAP_SEAMLESS is a switch */
    bool geometry_shaders; /* the techniques' programs may have a geometry stage */
    bool primitive_id;     /* gl_PrimitiveID in a fragment shader: desktop GLSL's, not ES 3.00's */
    bool texture_buffers;  /* GL_TEXTURE_BUFFER and samplerBuffer: desktop GLSL's, not ES 3.00's */
    bool polygon_mode;     /* glPolygonMode (WEBGL_polygon_mode) */
    bool clip_distances;   /* gl_ClipDistance, GL_CLIP_DISTANCEi (WEBGL_clip_cull_distance) */
    bool depth_clamp;      /* GL_DEPTH_CLAMP (EXT_depth_clamp) */
    bool clip_control;     /* glClipControl (ARB_clip_control, EXT_clip_control) */
    bool depth_bounds;     /* glDepthBoundsEXT (EXT_depth_bounds_test) */
    bool depth_readback;   /* glReadPixels of GL_DEPTH_COMPONENT: desktop GL's, not ES's */
    /* Attributes interpolate across a large triangle as closely as the
     * dumps need (Mesa's do, short of render.h's huge objects); where not
     * known to (the browser's), a dump takes every surface where the
     * pixel's eye ray meets its triangle's plane (capture.c). */
    bool close_interpolation;
} context_features;

typedef struct context {
    context_backend backend;   /* the one in use, never AUTO */
    struct GLFWwindow *window; /* GLFW only */
    char platform[64];         /* e.g. "EGL device (NVIDIA)", "EGL surfaceless" */
    char renderer[256];        /* GL_RENDERER */
    void *impl;                /* backend's own state */
} context;

const char *context_backend_name(context_backend b);
/* By context_backend, NULL-terminated: the --backend flag's choices. */
extern const char *const context_backend_names[];

bool context_create(context *c, const context_settings *s);
void context_destroy(context *c);
bool context_gl_ok(const char *where);
/* The current context's features (all false before context_create). */
const context_features *context_current_features(void);
/* A backend's own features, for the context its create function makes
 * current: context_create then keeps them (the settings' glsl_es and
 * webgl2 unused). */
void context_set_features(const context_features *f);
/* The window (context_glfw.c; in the web build, the page's canvas:
 * context_browser.c) on the whole screen, or back as it was before.
 * False, having said why, where that cannot be; the page asks the
 * browser, which says later, on the console, when it refuses. */
bool context_set_fullscreen(context *c, bool on);
bool context_fullscreen(const context *c);
/* The window's framebuffer, in pixels. A native window's size is its
 * user's; the page's canvas this first makes fixed_width x fixed_height,
 * or, where fixed_width is 0, its box on the page times the device's
 * pixel ratio (the page shows it whole in its box). */
void context_window_size(context *c, int fixed_width, int fixed_height, int *width, int *height);
/* Whether GL_RENDERER names one of Mesa's software rasterizers, whose
 * timer queries see only the submission: time is then the CPU's. */
bool context_software_renderer(const char *renderer);

/* Backends (context_<name>.c); each fills c->platform and c->impl, makes
 * its context current and returns the loader glad should use. */
typedef void (*context_proc)(void);
typedef context_proc (*context_loader)(const char *name);
context_loader context_glfw_create(context *c, const context_settings *s);
context_loader context_egl_create(context *c, const context_settings *s);
context_loader context_osmesa_create(context *c, const context_settings *s);
void context_glfw_destroy(context *c);
void context_egl_destroy(context *c);
void context_osmesa_destroy(context *c);
context_loader context_browser_create(context *c, const context_settings *s);
void context_browser_destroy(context *c);

#endif
