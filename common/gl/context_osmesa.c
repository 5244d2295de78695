/* OSMesa backend, loaded with dlopen: Mesa 25.1 removed libOSMesa, so it is
 * optional at run time and never a link dependency. The few names used are
 * declared here from osmesa.h's ABI (stable since Mesa 10). */
#include "context.h"

#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>

#define OSMESA_RGBA 0x1908 /* GL_RGBA */
#define OSMESA_FORMAT 0x22
#define OSMESA_DEPTH_BITS 0x30
#define OSMESA_STENCIL_BITS 0x31
#define OSMESA_PROFILE 0x33
#define OSMESA_CORE_PROFILE 0x34
#define OSMESA_CONTEXT_MAJOR_VERSION 0x36
#define OSMESA_CONTEXT_MINOR_VERSION 0x37
#define OSMESA_UNSIGNED_BYTE 0x1401 /* GL_UNSIGNED_BYTE */

typedef struct osmesa_context *osmesa_handle;
typedef struct context_osmesa {
    void *library;
    osmesa_handle context;
    unsigned char pixel[4]; /* OSMesa must bind a colour buffer; ours is the target */
    osmesa_handle (*create_context_attribs)(const int *attribs, osmesa_handle share);
    unsigned char (*make_current)(osmesa_handle ctx, void *buffer, unsigned type, int width, int height);
    context_proc (*get_proc_address)(const char *name);
    void (*destroy_context)(osmesa_handle ctx);
} context_osmesa;

static context_osmesa *context_osmesa_current;

static context_proc context_osmesa_get_proc(const char *name) {
    return context_osmesa_current->get_proc_address(name);
}

static void *context_osmesa_open_library(void) {
    static const char *const names[] = {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"};
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        void *library = dlopen(names[i], RTLD_NOW | RTLD_LOCAL);
        if (library)
            return library;
    }
    return NULL;
}

context_loader context_osmesa_create(context *c, const context_settings *s) {
    (void)s;
    void *library = context_osmesa_open_library();
    if (!library) {
        fprintf(stderr, "context: osmesa: backend unavailable: libOSMesa is not installed "
                        "(Mesa 25.1 and later no longer ship it; use --backend egl)\n");
        return NULL;
    }
    context_osmesa *o = calloc(1, sizeof *o);
    if (!o) {
        dlclose(library);
        fprintf(stderr, "context: osmesa: out of memory\n");
        return NULL;
    }
    o->library = library;
    c->impl = o;
    /* POSIX guarantees that object and function pointers convert (dlsym). */
    *(void **)&o->create_context_attribs = dlsym(library, "OSMesaCreateContextAttribs");
    *(void **)&o->make_current = dlsym(library, "OSMesaMakeCurrent");
    *(void **)&o->get_proc_address = dlsym(library, "OSMesaGetProcAddress");
    *(void **)&o->destroy_context = dlsym(library, "OSMesaDestroyContext");
    if (!o->create_context_attribs || !o->make_current || !o->get_proc_address || !o->destroy_context) {
        fprintf(stderr, "context: osmesa: libOSMesa lacks OSMesaCreateContextAttribs (too old)\n");
        context_osmesa_destroy(c);
        return NULL;
    }
    static const int attribs[] = {
        OSMESA_FORMAT,
        OSMESA_RGBA,
        OSMESA_DEPTH_BITS,
        0,
        OSMESA_STENCIL_BITS,
        0,
        OSMESA_PROFILE,
        OSMESA_CORE_PROFILE,
        OSMESA_CONTEXT_MAJOR_VERSION,
        3,
        OSMESA_CONTEXT_MINOR_VERSION,
        3,
        0,
    };
    o->context = o->create_context_attribs(attribs, NULL);
    if (!o->context) {
        fprintf(stderr, "context: osmesa: OSMesaCreateContextAttribs failed (OpenGL 3.3 core)\n");
        context_osmesa_destroy(c);
        return NULL;
    }
    if (!o->make_current(o->context, o->pixel, OSMESA_UNSIGNED_BYTE, 1, 1)) {
        fprintf(stderr, "context: osmesa: OSMesaMakeCurrent failed\n");
        context_osmesa_destroy(c);
        return NULL;
    }
    context_osmesa_current = o;
    snprintf(c->platform, sizeof c->platform, "OSMesa");
    return context_osmesa_get_proc;
}

void context_osmesa_destroy(context *c) {
    context_osmesa *o = c->impl;
    if (!o)
        return;
    if (o->context)
        o->destroy_context(o->context);
    dlclose(o->library);
    free(o);
    context_osmesa_current = NULL;
    c->impl = NULL;
}
