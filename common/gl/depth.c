#include "depth.h"

#include <glad/gl.h>

#include "context.h"

/* The standard convention's far end; the reversed one's is 0. */
#define DEPTH_STANDARD_FAR 1.0f

bool depth_reversed_available(void) { return context_current_features()->clip_control; }

void depth_clamp(bool on) {
    if (!context_current_features()->depth_clamp)
        return;
    if (on)
        glEnable(GL_DEPTH_CLAMP);
    else
        glDisable(GL_DEPTH_CLAMP);
}

unsigned depth_func(const camera_view *v, unsigned standard) {
    if (!v->reversed_depth)
        return standard;
    switch (standard) {
    case GL_LESS: return GL_GREATER;
    case GL_LEQUAL: return GL_GEQUAL;
    case GL_GREATER: return GL_LESS;
    case GL_GEQUAL: return GL_LEQUAL;
    default: return standard; /* GL_EQUAL, GL_NOTEQUAL, GL_ALWAYS, GL_NEVER */
    }
}

void depth_polygon_offset(const camera_view *v, float factor, float units) {
    float sign = v->reversed_depth ? -1.0f : 1.0f;
    glPolygonOffset(sign * factor, sign * units);
}

float depth_far(const camera_view *v) { return v->reversed_depth ? 0.0f : DEPTH_STANDARD_FAR; }

void depth_use_camera(const camera_view *v) {
    if (!v->reversed_depth)
        return;
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glClearDepth(depth_far(v));
    glDepthFunc(depth_func(v, GL_LESS));
}

void depth_use_standard(const camera_view *v) {
    if (!v->reversed_depth)
        return;
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glClearDepth(DEPTH_STANDARD_FAR);
    glDepthFunc(GL_LESS);
}
