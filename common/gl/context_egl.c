/* EGL backend: no window, no surface at all (EGL_KHR_surfaceless_context):
 * techniques render into the off-screen target.
 *
 * The display comes from the device platform when a hardware device is
 * enumerated (on NVIDIA this is the only headless path), else from Mesa's
 * surfaceless platform, else EGL's default display. */
#include "context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct context_egl {
    EGLDisplay display;
    EGLContext context;
} context_egl;

static const char *context_egl_error(void) {
    static char text[32];
    EGLint code = eglGetError();
    switch (code) {
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: snprintf(text, sizeof text, "EGL error 0x%04x", (unsigned)code); return text;
    }
}

static bool context_egl_has(const char *extensions, const char *name) {
    size_t n = strlen(name);
    for (const char *p = extensions; p && (p = strstr(p, name)); p += n)
        if ((p == extensions || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return true;
    return false;
}

/* The first enumerated device that is not Mesa's software rasterizer. */
static EGLDisplay context_egl_device_display(PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display) {
    PFNEGLQUERYDEVICESEXTPROC query_devices = (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
    PFNEGLQUERYDEVICESTRINGEXTPROC query_device_string =
        (PFNEGLQUERYDEVICESTRINGEXTPROC)eglGetProcAddress("eglQueryDeviceStringEXT");
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (!query_devices || !query_device_string || !query_devices(16, devices, &count))
        return EGL_NO_DISPLAY;
    for (EGLint i = 0; i < count; i++) {
        const char *extensions = query_device_string(devices[i], EGL_EXTENSIONS);
        if (context_egl_has(extensions, "EGL_MESA_device_software"))
            continue;
        return get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], NULL);
    }
    return EGL_NO_DISPLAY;
}

static EGLDisplay context_egl_open_display(context *c) {
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    EGLDisplay d = EGL_NO_DISPLAY;
    if (get_platform_display && context_egl_has(client, "EGL_EXT_platform_device")) {
        d = context_egl_device_display(get_platform_display);
        snprintf(c->platform, sizeof c->platform, "EGL device platform");
    }
    if (d == EGL_NO_DISPLAY && get_platform_display && context_egl_has(client, "EGL_MESA_platform_surfaceless")) {
        d = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
        snprintf(c->platform, sizeof c->platform, "EGL surfaceless platform");
    }
    if (d == EGL_NO_DISPLAY) {
        d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
        snprintf(c->platform, sizeof c->platform, "EGL default display");
    }
    return d;
}

context_loader context_egl_create(context *c, const context_settings *s) {
    (void)s;
    context_egl *egl = calloc(1, sizeof *egl);
    if (!egl) {
        fprintf(stderr, "context: egl: out of memory\n");
        return NULL;
    }
    c->impl = egl;
    static const EGLint config_attribs[] = {
        EGL_RENDERABLE_TYPE,
        EGL_OPENGL_BIT,
        EGL_SURFACE_TYPE,
        0, /* no surface: any config will do */
        EGL_NONE,
    };
    static const EGLint context_attribs[] = {
        EGL_CONTEXT_MAJOR_VERSION,           3,        EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE,
    };
    EGLConfig config;
    EGLint config_count = 0;
    const char *step;
    egl->display = context_egl_open_display(c);
    if (egl->display == EGL_NO_DISPLAY) {
        step = "no display";
    } else if (!eglInitialize(egl->display, NULL, NULL)) {
        egl->display = EGL_NO_DISPLAY;
        step = "eglInitialize";
    } else if (!context_egl_has(eglQueryString(egl->display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context")) {
        fprintf(stderr, "context: egl: %s lacks EGL_KHR_surfaceless_context\n", c->platform);
        context_egl_destroy(c);
        return NULL;
    } else if (!eglBindAPI(EGL_OPENGL_API)) {
        step = "eglBindAPI(EGL_OPENGL_API)";
    } else if (!eglChooseConfig(egl->display, config_attribs, &config, 1, &config_count) || config_count < 1) {
        step = "eglChooseConfig (OpenGL)";
    } else if ((egl->context = eglCreateContext(egl->display, config, EGL_NO_CONTEXT, context_attribs)) ==
               EGL_NO_CONTEXT) {
        step = "eglCreateContext (OpenGL 3.3 core)";
    } else if (!eglMakeCurrent(egl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, egl->context)) {
        step = "eglMakeCurrent";
    } else {
        return (context_loader)eglGetProcAddress;
    }
    fprintf(stderr, "context: egl: %s: %s failed: %s\n", c->platform, step, context_egl_error());
    context_egl_destroy(c);
    return NULL;
}

void context_egl_destroy(context *c) {
    context_egl *egl = c->impl;
    if (!egl)
        return;
    if (egl->display != EGL_NO_DISPLAY) {
        eglMakeCurrent(egl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (egl->context != EGL_NO_CONTEXT)
            eglDestroyContext(egl->display, egl->context);
        eglTerminate(egl->display);
    }
    eglReleaseThread();
    free(egl);
    c->impl = NULL;
}
