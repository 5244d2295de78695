/* shader: GLSL programs from files in the shader directory.
 *
 * shader_load_program(files, n) compiles each file (its stage from the
 * extension: .vert, .geom, .frag) and links them. A line
 *     #include "name.glsl"
 * is replaced by that file from the same directory (nested includes too),
 * with #line directives so that the driver's messages keep their lines; on
 * a compile or link error the log is printed with each "source:line"
 * rewritten as "FILE:LINE", and 0 is returned.
 *
 * A uniform block named "Lights" is bound to SHADER_LIGHTS_BINDING, where
 * render.c keeps the scene's lights (see shaders/lighting.glsl).
 */
#ifndef SHADER_H
#define SHADER_H

#define SHADER_LIGHTS_BINDING 0

void shader_set_directory(const char *dir);
const char *shader_directory(void);
unsigned shader_load_program(const char *const *files, int count);

#endif
