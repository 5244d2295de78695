/* GLFW backend: a window with a GL 3.3 core, forward-compatible context. */
#include "context.h"

#include <GLFW/glfw3.h>
#include <stdio.h>

/* Where the window was, and how large, before it took the whole screen. */
static struct { int x, y, width, height; } context_glfw_windowed;

static void context_glfw_error(int code, const char *description) {
    fprintf(stderr, "GLFW error 0x%x: %s\n", code, description);
}

context_loader context_glfw_create(context *c, const context_settings *s) {
    glfwSetErrorCallback(context_glfw_error);
    if (!glfwInit()) {
        fprintf(stderr, "context: glfw: cannot initialize (no display?)\n");
        return NULL;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    /* Techniques draw into the off-screen target; the window only shows it. */
    glfwWindowHint(GLFW_DEPTH_BITS, 0);
    glfwWindowHint(GLFW_STENCIL_BITS, 0);
    c->window = glfwCreateWindow(s->width, s->height, s->title, NULL, NULL);
    if (!c->window) {
        fprintf(stderr, "context: glfw: cannot create a %dx%d window with OpenGL 3.3 core\n", s->width, s->height);
        glfwTerminate();
        return NULL;
    }
    glfwMakeContextCurrent(c->window);
    glfwSwapInterval(1);
    snprintf(c->platform, sizeof c->platform, "GLFW window");
    return (context_loader)glfwGetProcAddress;
}

void context_glfw_destroy(context *c) {
    if (c->window)
        glfwDestroyWindow(c->window);
    glfwTerminate();
}

void context_window_size(context *c, int fixed_width, int fixed_height, int *width, int *height) {
    (void)fixed_width, (void)fixed_height;
    glfwGetFramebufferSize(c->window, width, height);
}

bool context_fullscreen(const context *c) { return glfwGetWindowMonitor(c->window) != NULL; }

/* Fullscreen on the primary monitor, in its current video mode. */
bool context_set_fullscreen(context *c, bool on) {
    if (on == context_fullscreen(c))
        return true;
    if (!on) {
        glfwSetWindowMonitor(c->window, NULL, context_glfw_windowed.x, context_glfw_windowed.y,
                             context_glfw_windowed.width, context_glfw_windowed.height, GLFW_DONT_CARE);
        return true;
    }
    GLFWmonitor *monitor = glfwGetPrimaryMonitor();
    const GLFWvidmode *mode = monitor ? glfwGetVideoMode(monitor) : NULL;
    if (!mode) {
        fprintf(stderr, "context: glfw: no monitor to fill, so the window stays as it is\n");
        return false;
    }
    glfwGetWindowPos(c->window, &context_glfw_windowed.x, &context_glfw_windowed.y);
    glfwGetWindowSize(c->window, &context_glfw_windowed.width, &context_glfw_windowed.height);
    glfwSetWindowMonitor(c->window, monitor, 0, 0, mode->width, mode->height, mode->refreshRate);
    return true;
}
