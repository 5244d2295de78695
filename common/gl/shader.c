#include "shader.h"

#include <glad/gl.h>
#include <ctype.h>
#include <stdbool.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "context.h"
#include "path.h"
#include "scene.h"

#define SHADER_MAX_SOURCES 32 /* files, includes counted, in one stage */
#define SHADER_MAX_DEPTH 8
#define SHADER_MAX_FILE_SIZE (1 << 20)
/* Some drivers (Mesa 22) report errors inside functions with source number
 * 0 whatever #line said, but always with the line it gave: so the line
 * carries the file too, as file * SHADER_LINE_STRIDE + line. */
#define SHADER_LINE_STRIDE 100000

static char shader_dir[4096] = "shaders";

/* What every program sees (the lights block's size, shaders/lighting.glsl). */
static const shader_define shader_common_defines[] = {SHADER_DEFINE(SHADER_PASS_LIGHTS), {NULL, 0}};

/* GLSL ES 3.00's first lines, in place of a source's "#version 330 core":
 * a default precision for every type that has none or a lower one in
 * some stage (highp: what desktop GLSL computes in), then the source's
 * own #line. */
static const char shader_es_version[] = "#version 300 es\n";
static const char shader_es_precisions[] =
    "precision highp float;\nprecision highp int;\nprecision highp sampler2D;\nprecision highp samplerCube;\n"
    "precision highp sampler3D;\nprecision highp sampler2DArray;\nprecision highp sampler2DShadow;\n"
    "precision highp samplerCubeShadow;\nprecision highp sampler2DArrayShadow;\nprecision highp isampler2D;\n"
    "precision highp isampler3D;\nprecision highp isamplerCube;\nprecision highp isampler2DArray;\n"
    "precision highp usampler2D;\nprecision highp usampler3D;\nprecision highp usamplerCube;\n"
    "precision highp usampler2DArray;\n";
/* What ES has only as an extension: a source that uses `word` enables
 * each extension named for it (WebGL's under its browsers' names too; a
 * compiler that knows none of them only warns). */
static const struct {
    const char *word, *extensions;
} shader_es_extensions[] = {
    {"gl_ClipDistance",
     "#extension GL_EXT_clip_cull_distance : enable\n#extension GL_ANGLE_clip_cull_distance : enable\n"},
};

void shader_set_directory(const char *dir) { snprintf(shader_dir, sizeof shader_dir, "%s", dir); }
const char *shader_directory(void) { return shader_dir; }

/* One stage's text after includes, and which file each #line source number
 * stands for. */
typedef struct shader_source {
    char *text;
    size_t length, capacity;
    char files[SHADER_MAX_SOURCES][256]; /* names in the shader directory */
    int file_count;
} shader_source;

static bool shader_append(shader_source *s, const char *text, size_t n) {
    if (s->length + n + 1 > s->capacity) {
        size_t capacity = (s->length + n + 1) * 2;
        char *grown = realloc(s->text, capacity);
        if (!grown) {
            fprintf(stderr, "shader: out of memory\n");
            return false;
        }
        s->text = grown;
        s->capacity = capacity;
    }
    memcpy(s->text + s->length, text, n);
    s->length += n;
    s->text[s->length] = '\0';
    return true;
}

static bool shader_append_line_directive(shader_source *s, int line, int file) {
    char directive[48];
    int n = snprintf(directive, sizeof directive, "#line %d %d\n", file * SHADER_LINE_STRIDE + line, file);
    return shader_append(s, directive, (size_t)n);
}

static bool shader_append_defines(shader_source *s, const shader_define *defines) {
    bool ok = true;
    for (const shader_define *d = defines; ok && d && d->name; d++) {
        char line[128];
        int n = snprintf(line, sizeof line, "#define %s %d\n", d->name, d->value);
        ok = n > 0 && (size_t)n < sizeof line && shader_append(s, line, (size_t)n);
    }
    return ok;
}

/* What a source may test with #ifdef about the context (shader.h). */
static bool shader_append_features(shader_source *s) {
    static const char no_clip[] = "#define SHADER_NO_CLIP_DISTANCES 1\n";
    return context_current_features()->clip_distances || shader_append(s, no_clip, sizeof no_clip - 1);
}

/* Appends `name` with its includes expanded. #version must stay the first
 * line of a stage, so the defines and the first #line directive go after
 * it. */
static bool shader_expand(shader_source *s, const char *name, int depth, const shader_define *defines) {
    if (depth > SHADER_MAX_DEPTH || s->file_count == SHADER_MAX_SOURCES) {
        fprintf(stderr, "%s/%s: includes nested too deep or too many\n", shader_dir, name);
        return false;
    }
    int file = s->file_count++;
    snprintf(s->files[file], sizeof s->files[file], "%s", name);
    char path[sizeof shader_dir + sizeof s->files[file] + 1];
    snprintf(path, sizeof path, "%s/%s", shader_dir, name);
    char *text = path_read_text(path, SHADER_MAX_FILE_SIZE, NULL);
    if (!text)
        return false;
    bool ok = depth == 0 || shader_append_line_directive(s, 1, file);
    int line = 1;
    bool joined = false; /* the line before ended in a continuation */
    for (char *p = text; ok && *p; line++) {
        char *end = strchr(p, '\n');
        size_t n = end ? (size_t)(end - p + 1) : strlen(p);
        char included[256];
        /* Blanks before the directive, within its line: sscanf's own
         * whitespace skip would run on over empty lines onto the next
         * directive and include it twice. */
        const char *directive = p + strspn(p, " \t");
        if (sscanf(directive, "#include \"%255[^\"]\"", included) == 1) {
            ok = shader_expand(s, included, depth + 1, NULL) && shader_append_line_directive(s, line + 1, file);
            if (!ok)
                fprintf(stderr, "%s/%s:%d: included from here\n", shader_dir, s->files[file], line);
        } else if (n >= 2 && p[n - 1] == '\n' && p[n - 2] == '\\') {
            /* A backslash ends the line: GLSL continues it from 4.20 on,
             * 3.30 does not, so the loader joins the two lines itself,
             * then says which line follows. */
            ok = shader_append(s, p, n - 2) && shader_append(s, " ", 1);
            joined = true;
        } else {
            ok = shader_append(s, p, n);
            if (ok && joined)
                ok = shader_append_line_directive(s, line + 1, file);
            joined = false;
            if (ok && depth == 0 && line == 1)
                ok = shader_append_defines(s, shader_common_defines) && shader_append_defines(s, defines) &&
                     shader_append_features(s) && shader_append_line_directive(s, 2, file);
        }
        p += n;
    }
    free(text);
    return ok;
}

/* Drivers write "0:12(5): error" (Mesa), "0(12) : error" (NVIDIA) or
 * "ERROR: 0:12: " (AMD); each line that names a source number and line is
 * printed as "FILE:LINE: message". */
static void shader_print_log(const shader_source *s, const char *log) {
    for (const char *p = log; *p;) {
        const char *end = strchr(p, '\n');
        int n = end ? (int)(end - p) : (int)strlen(p);
        const char *q = p;
        if (strncmp(q, "ERROR: ", 7) == 0 || strncmp(q, "WARNING: ", 9) == 0)
            q = strchr(q, ' ') + 1;
        int source, line, used = 0;
        bool located =
            sscanf(q, "%d:%d%n", &source, &line, &used) == 2 || sscanf(q, "%d(%d)%n", &source, &line, &used) == 2;
        if (located) {
            source = line / SHADER_LINE_STRIDE;
            line %= SHADER_LINE_STRIDE;
        }
        if (located && source >= 0 && source < s->file_count) {
            q += used;
            while (*q == '(' || isdigit((unsigned char)*q) || *q == ')' || *q == ':' || *q == ' ')
                q++;
            fprintf(stderr, "%s/%s:%d: %.*s\n", shader_dir, s->files[source], line, (int)(p + n - q), q);
        } else if (n > 0) {
            fprintf(stderr, "%.*s\n", n, p);
        }
        p += n + (end != NULL);
    }
}

static GLenum shader_stage(const char *file) {
    const char *dot = strrchr(file, '.');
    if (dot && strcmp(dot, ".vert") == 0)
        return GL_VERTEX_SHADER;
    if (dot && strcmp(dot, ".geom") == 0)
        return GL_GEOMETRY_SHADER;
    if (dot && strcmp(dot, ".frag") == 0)
        return GL_FRAGMENT_SHADER;
    return 0;
}

/* Each program's expanded sources, every stage's one after another, kept
 * from its link to its deletion for shader_uniform's check. */
#define SHADER_MAX_PROGRAMS 1024
static struct {
    unsigned program; /* 0: a free slot */
    char *text;
    char name[256]; /* its first file */
} shader_programs[SHADER_MAX_PROGRAMS];
static bool shader_uniform_missed; /* since shader_uniforms_ok's last call */

/* Appends one stage's expanded text to *all (NULL at first). */
static bool shader_keep_text(char **all, const char *text) {
    size_t had = *all ? strlen(*all) : 0, n = strlen(text);
    char *grown = realloc(*all, had + n + 1);
    if (!grown) {
        fprintf(stderr, "shader: out of memory\n");
        return false;
    }
    memcpy(grown + had, text, n + 1);
    *all = grown;
    return true;
}

/* The desktop source's first line, which the ES dialect replaces. */
static const char shader_desktop_version[] = "#version 330 core\n";

/* s's text in GLSL ES 3.00: its #version line replaced by ES's, the
 * extensions it needs and the precisions (the defines and the #line after
 * it stay, so every line keeps its number). */
static bool shader_to_es(shader_source *s) {
    size_t skip = sizeof shader_desktop_version - 1;
    if (strncmp(s->text, shader_desktop_version, skip) != 0) {
        fprintf(stderr, "%s/%s: the GLSL ES dialect needs \"%.*s\" as the first line\n", shader_dir, s->files[0],
                (int)skip - 1, shader_desktop_version);
        return false;
    }
    char *desktop = s->text;
    size_t length = s->length;
    s->text = NULL;
    s->length = s->capacity = 0;
    bool ok = shader_append(s, shader_es_version, sizeof shader_es_version - 1);
    for (size_t i = 0; ok && i < sizeof shader_es_extensions / sizeof *shader_es_extensions; i++)
        if (strstr(desktop, shader_es_extensions[i].word))
            ok = shader_append(s, shader_es_extensions[i].extensions, strlen(shader_es_extensions[i].extensions));
    ok = ok && shader_append(s, shader_es_precisions, sizeof shader_es_precisions - 1) &&
         shader_append(s, desktop + skip, length - skip);
    free(desktop);
    return ok;
}

/* es: in GLSL ES 3.00 (shader_to_es). */
static GLuint shader_compile(const char *file, bool es, const shader_define *defines, char **all) {
    GLenum stage = shader_stage(file);
    if (!stage) {
        fprintf(stderr, "%s/%s: unknown shader stage (expected .vert, .geom or .frag)\n", shader_dir, file);
        return 0;
    }
    shader_source s = {0};
    GLuint shader = 0;
    if (shader_expand(&s, file, 0, defines) && (!es || shader_to_es(&s))) {
        shader = glCreateShader(stage);
        const char *text = s.text;
        glShaderSource(shader, 1, &text, NULL);
        glCompileShader(shader);
        GLint ok = GL_FALSE;
        glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            char log[8192] = "";
            glGetShaderInfoLog(shader, sizeof log, NULL, log);
            fprintf(stderr, "%s/%s: compile error:\n", shader_dir, file);
            shader_print_log(&s, log);
        }
        if (!ok || !shader_keep_text(all, s.text)) {
            glDeleteShader(shader);
            shader = 0;
        }
    }
    free(s.text);
    return shader;
}

/* Keeps program's sources (text, which the table owns from then on)
 * under its first file's name; false after printing why (text still the
 * caller's). */
static bool shader_keep_program(unsigned program, const char *name, char *text) {
    for (int i = 0; i < SHADER_MAX_PROGRAMS; i++)
        if (shader_programs[i].program == 0) {
            shader_programs[i].program = program;
            shader_programs[i].text = text;
            snprintf(shader_programs[i].name, sizeof shader_programs[i].name, "%s", name);
            return true;
        }
    fprintf(stderr, "%s/%s: more than %d programs at once\n", shader_dir, name, SHADER_MAX_PROGRAMS);
    return false;
}

unsigned shader_load_program(const char *const *files, int count, const shader_define *defines) {
    /* GLSL ES has no geometry stage: a program with one is desktop GLSL
     * whole, which only a desktop context takes. */
    bool es = context_current_features()->glsl_es;
    for (int i = 0; i < count; i++)
        es = es && shader_stage(files[i]) != GL_GEOMETRY_SHADER;
    GLuint program = glCreateProgram();
    bool ok = true;
    char *text = NULL;
    for (int i = 0; i < count && ok; i++) {
        GLuint shader = shader_compile(files[i], es, defines, &text);
        ok = shader != 0;
        if (ok) {
            glAttachShader(program, shader);
            glDeleteShader(shader); /* freed with the program */
        }
    }
    if (ok) {
        glLinkProgram(program);
        GLint linked = GL_FALSE;
        glGetProgramiv(program, GL_LINK_STATUS, &linked);
        if (!linked) {
            char log[8192] = "";
            glGetProgramInfoLog(program, sizeof log, NULL, log);
            fprintf(stderr, "%s/%s: link error:\n%s\n", shader_dir, files[0], log);
            ok = false;
        }
    }
    if (!ok || !shader_keep_program(program, files[0], text)) {
        free(text);
        glDeleteProgram(program);
        return 0;
    }
    GLuint lights = glGetUniformBlockIndex(program, "Lights");
    if (lights != GL_INVALID_INDEX)
        glUniformBlockBinding(program, lights, SHADER_LIGHTS_BINDING);
    return program;
}

void shader_delete_program(unsigned program) {
    for (int i = 0; i < SHADER_MAX_PROGRAMS && program; i++)
        if (shader_programs[i].program == program) {
            free(shader_programs[i].text);
            shader_programs[i].program = 0;
            shader_programs[i].text = NULL;
        }
    glDeleteProgram(program);
}

static bool shader_identifier_char(char c) { return isalnum((unsigned char)c) || c == '_'; }

/* Whether `text` declares a uniform `name`: a statement from the word
 * "uniform" to its semicolon that holds the name as a whole word. */
static bool shader_declares(const char *text, const char *name) {
    size_t n = strlen(name);
    for (const char *p = strstr(text, "uniform"); p; p = strstr(p + 1, "uniform")) {
        bool word = (p == text || !shader_identifier_char(p[-1])) && isspace((unsigned char)p[7]);
        const char *end = strchr(p, ';');
        for (const char *q = p; word && end && (q = strstr(q, name)) && q < end; q += n) {
            if (!shader_identifier_char(q[-1]) && !shader_identifier_char(q[n]))
                return true;
        }
    }
    return false;
}

int shader_uniform(unsigned program, const char *name) {
    int location = glGetUniformLocation(program, name);
    if (location != -1)
        return location;
    char base[256];
    snprintf(base, sizeof base, "%s", name);
    base[strcspn(base, "[")] = '\0'; /* an element of an array: the array's name */
    for (int i = 0; i < SHADER_MAX_PROGRAMS; i++)
        if (shader_programs[i].program == program && program) {
            if (!shader_declares(shader_programs[i].text, base)) {
                fprintf(stderr, "%s/%s: the program declares no uniform %s\n", shader_dir, shader_programs[i].name,
                        base);
                shader_uniform_missed = true;
            }
            return -1;
        }
    fprintf(stderr, "shader: uniform %s asked of program %u, which shader_load_program did not make\n", name,
            program);
    shader_uniform_missed = true;
    return -1;
}

int shader_uniform_optional(unsigned program, const char *name) { return glGetUniformLocation(program, name); }

bool shader_uniforms_ok(void) {
    bool ok = !shader_uniform_missed;
    shader_uniform_missed = false;
    return ok;
}
