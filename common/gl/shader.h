/* shader: GLSL programs from files in the shader directory.
 *
 * shader_load_program(files, n) compiles each file (its stage from the
 * extension: .vert, .geom, .frag) and links them. A line
 *     #include "name.glsl"
 * is replaced by that file from the same directory (nested includes too),
 * with #line directives so that the driver's messages keep their lines
 * (as after a line ending in a backslash, which the loader joins to the
 * next: GLSL 3.30 has no line continuation, 4.20 on has); on
 * a compile or link error the log is printed with each "source:line"
 * rewritten as "FILE:LINE", and 0 is returned.
 *
 * Every source is desktop GLSL 3.30 ("#version 330 core" first) that is
 * also GLSL ES 3.00, WebGL 2's dialect, once its first line says so: where
 * the context's features say glsl_es (context.h), the loader compiles the
 * vertex and fragment stages as ES, with highp as every type's default
 * precision and the #extension lines of what ES has only as an extension
 * (gl_ClipDistance). A program with a geometry stage, which ES lacks,
 * stays desktop GLSL.
 *
 * Where the context has no clip distances (context.h), every source has
 * SHADER_NO_CLIP_DISTANCES defined: one that would write gl_ClipDistance
 * passes the distances on and its fragment stage discards where one is
 * negative instead.
 *
 * A uniform block named "Lights" is bound to SHADER_LIGHTS_BINDING, where
 * render.c keeps a group of the scene's lights, SHADER_PASS_LIGHTS of
 * them (see shaders/lighting.glsl and render.h, "Light groups").
 *
 * The C/GLSL contract: every enum value and limit a shader shares with C
 * is defined once, in C, and reaches the shader as "#define NAME VALUE"
 * right after its #version line (so #line numbers stay true): the limits
 * every program needs (SHADER_PASS_LIGHTS) always, a program's own through
 * `defines`, a list ended by {NULL} built with SHADER_DEFINE(CONSTANT),
 * which names the constant as C does. A shader compares with those names,
 * never with a bare number; one that uses a name it was not given fails
 * to compile.
 */
#ifndef SHADER_H
#define SHADER_H

#include <stdbool.h>

#define SHADER_LIGHTS_BINDING 0
/* The lights one program holds: its slots (render.h, "Light groups"). */
#define SHADER_PASS_LIGHTS 8

typedef struct shader_define {
    const char *name; /* NULL ends a list */
    int value;
} shader_define;
#define SHADER_DEFINE(constant)                                                                                      \
    { #constant, (int)(constant) }

void shader_set_directory(const char *dir);
const char *shader_directory(void);
/* defines: NULL, or a list ended by {NULL}. */
unsigned shader_load_program(const char *const *files, int count, const shader_define *defines);
/* Deletes a program of shader_load_program's (0: nothing). */
void shader_delete_program(unsigned program);
/* The location of uniform `name` (an array's element: "u_x[3]") in a
 * program of shader_load_program's. -1 where the program declares it but
 * does not use it (the compiler dropped it): setting -1 does nothing, by
 * the GL's rule. A name the program's sources do not declare (a misspelt
 * uniform) is said on stderr, naming the program and the uniform, and
 * shader_uniforms_ok is false until its next call: the frame's owner
 * checks it with the GL's errors (context_gl_ok). */
int shader_uniform(unsigned program, const char *name);
/* A uniform that some programs of one loader lack by design (a depth-only
 * program has no colour; render_program_load's): its location, or -1,
 * never an error. */
int shader_uniform_optional(unsigned program, const char *name);
/* No uniform was missed since the last call. */
bool shader_uniforms_ok(void);

#endif
