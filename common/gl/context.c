#include "context.h"

#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shader.h"

/* The browser is a choice in the web build only. */
#ifdef __EMSCRIPTEN__
#define CONTEXT_BROWSER_NAME "browser"
#else
#define CONTEXT_BROWSER_NAME NULL
#endif
const char *const context_backend_names[] = {
    [CONTEXT_AUTO] = "auto",
    [CONTEXT_GLFW] = "glfw",
    [CONTEXT_EGL] = "egl",
    [CONTEXT_OSMESA] = "osmesa",
    [CONTEXT_BROWSER] = CONTEXT_BROWSER_NAME,
    NULL,
};

static context_features context_features_now;
static bool context_features_given; /* by the backend (context_set_features) */

const context_features *context_current_features(void) { return &context_features_now; }
void context_set_features(const context_features *f) {
    context_features_now = *f;
    context_features_given = true;
}

/* A desktop GL 3.3 core context's features, less those s turns off. */
static context_features context_desktop_features(const context_settings *s) {
    bool webgl2 = s->webgl2;
    return (context_features){
        .glsl_es = s->glsl_es || webgl2,
        .desktop_gl = true,
        .geometry_shaders = !s->glsl_es && !webgl2,
        .primitive_id = !s->glsl_es && !webgl2,
        .texture_buffers = !s->glsl_es && !webgl2,
        .polygon_mode = !webgl2,
        .clip_distances = !webgl2,
        .depth_clamp = !webgl2,
        .clip_control = !webgl2 && GLAD_GL_ARB_clip_control,
        .depth_bounds = !webgl2 && GLAD_GL_EXT_depth_bounds_test,
        .depth_readback = !webgl2,
        .close_interpolation = true,
    };
}

/* Errors seen by the KHR_debug callback since the last context_gl_ok. */
static int context_debug_errors;
static bool context_verbose;

const char *context_backend_name(context_backend b) { return context_backend_names[b]; }

static void GLAD_API_PTR context_debug_message(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                               const GLchar *message, const void *user) {
    (void)id, (void)length, (void)user;
    /* shader.c reports compile errors itself, with file names and lines. */
    if (source == GL_DEBUG_SOURCE_SHADER_COMPILER)
        return;
    if (type == GL_DEBUG_TYPE_ERROR) {
        context_debug_errors++;
        fprintf(stderr, "GL error: %s\n", message);
    } else if (severity == GL_DEBUG_SEVERITY_HIGH || (context_verbose && severity == GL_DEBUG_SEVERITY_MEDIUM)) {
        fprintf(stderr, "GL: %s\n", message);
    }
}

static const char *context_gl_error_name(GLenum e) {
    switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    default: return "unknown GL error";
    }
}

bool context_gl_ok(const char *where) {
    bool ok = context_debug_errors == 0;
    context_debug_errors = 0;
    for (GLenum e; (e = glGetError()) != GL_NO_ERROR;) {
        fprintf(stderr, "%s: %s (0x%04x)\n", where, context_gl_error_name(e), e);
        ok = false;
    }
    if (!ok && context_debug_errors == 0)
        fprintf(stderr, "%s: GL errors reported (see above)\n", where);
    if (!shader_uniforms_ok()) {
        fprintf(stderr, "%s: a uniform asked for that its program does not declare (see above)\n", where);
        ok = false;
    }
    return ok;
}

/* Mesa's software rasterizers name themselves in GL_RENDERER. */
bool context_software_renderer(const char *renderer) {
    return strstr(renderer, "llvmpipe") || strstr(renderer, "softpipe");
}

/* The backends a build has: the native ones, or the web build's browser. */
#ifdef __EMSCRIPTEN__
#define CONTEXT_ONLY_BROWSER 1
static context_loader context_create_backend(context *c, const context_settings *s, context_backend b) {
    c->backend = CONTEXT_BROWSER;
    if (b == CONTEXT_BROWSER || b == CONTEXT_AUTO)
        return context_browser_create(c, s);
    fprintf(stderr, "context: %s: not in the web build, whose only context is the page's canvas\n",
            context_backend_name(b));
    return NULL;
}

static void context_destroy_backend(context *c) {
    if (c->backend == CONTEXT_BROWSER)
        context_browser_destroy(c);
}
#else
#define CONTEXT_ONLY_BROWSER 0
static context_loader context_create_backend(context *c, const context_settings *s, context_backend b) {
    c->backend = b;
    switch (b) {
    case CONTEXT_GLFW: return context_glfw_create(c, s);
    case CONTEXT_EGL: return context_egl_create(c, s);
    case CONTEXT_OSMESA: return context_osmesa_create(c, s);
    case CONTEXT_BROWSER:
    case CONTEXT_AUTO: break;
    }
    return NULL;
}

static void context_destroy_backend(context *c) {
    switch (c->backend) {
    case CONTEXT_GLFW: context_glfw_destroy(c); break;
    case CONTEXT_EGL: context_egl_destroy(c); break;
    case CONTEXT_OSMESA: context_osmesa_destroy(c); break;
    case CONTEXT_BROWSER:
    case CONTEXT_AUTO: break;
    }
}
#endif

static bool context_display_available(void) {
    const char *x11 = getenv("DISPLAY"), *wayland = getenv("WAYLAND_DISPLAY");
    return (x11 && *x11) || (wayland && *wayland);
}

bool context_create(context *c, const context_settings *s) {
    *c = (context){0};
    context_features_given = false;
    context_verbose = s->verbose;
    context_loader loader = NULL;
    if (s->backend != CONTEXT_AUTO || CONTEXT_ONLY_BROWSER) {
        loader = context_create_backend(c, s, s->backend);
    } else {
        /* Each failed attempt has already said why on stderr. */
        if (s->want_window && context_display_available())
            loader = context_create_backend(c, s, CONTEXT_GLFW);
        if (!loader)
            loader = context_create_backend(c, s, CONTEXT_EGL);
        if (!loader)
            loader = context_create_backend(c, s, CONTEXT_OSMESA);
    }
    if (!loader) {
        fprintf(stderr, "context: no OpenGL 3.3 core context could be created with backend %s\n",
                context_backend_name(s->backend));
        return false;
    }
    int version = gladLoadGL((GLADloadfunc)loader);
    if (!version || GLAD_VERSION_MAJOR(version) * 10 + GLAD_VERSION_MINOR(version) < 33) {
        fprintf(stderr, "context: %s: could not load OpenGL 3.3 core entry points\n", c->platform);
        context_destroy(c);
        return false;
    }
    snprintf(c->renderer, sizeof c->renderer, "%s", (const char *)glGetString(GL_RENDERER));
    if (!context_features_given)
        context_features_now = context_desktop_features(s);
    if (GLAD_GL_KHR_debug) {
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(context_debug_message, NULL);
    }
    if (s->verbose)
        fprintf(stderr, "backend: %s (%s)\nGL renderer: %s\nGL version: %s\n", context_backend_name(c->backend),
                c->platform, c->renderer, (const char *)glGetString(GL_VERSION));
    return context_gl_ok("context_create");
}

void context_destroy(context *c) {
    context_destroy_backend(c);
    *c = (context){0};
    context_features_now = (context_features){0};
    context_features_given = false;
}
