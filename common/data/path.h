/* path: file-system helpers every program shares. */
#ifndef PATH_H
#define PATH_H

#include <stdbool.h>
#include <stddef.h>

/* mkdir -p; prints "DIR: cannot create directory: reason" on failure. */
bool path_make_directories(const char *dir);

/* The whole file as a NUL-terminated string (malloc'ed; *length without
 * the NUL when length is not NULL), or NULL after printing "PATH: cannot
 * open/read: reason" or "PATH: larger than N bytes". */
char *path_read_text(const char *path, size_t max_size, size_t *length);

/* The file name of `path` without its directory and extension
 * ("assets/scenes/simple.json" -> "simple"): what pictures and reports
 * name a scene by. False if it did not fit in `size`. */
bool path_stem(const char *path, char *out, size_t size);

/* `relative` as seen from the folder of `file` (a scene's model, a tour's
 * scene), or itself when absolute. False if it did not fit in `size`. */
bool path_beside(const char *file, const char *relative, char *out, size_t size);

/* The first "PREFIX-N.EXTENSION", N = 1, 2, ..., that names no file yet
 * (a screenshot never overwrites an earlier one, from this run or
 * another). False if none fits in `size` or after PATH_NUMBERED_MAX. */
#define PATH_NUMBERED_MAX 100000
bool path_numbered_unused(const char *prefix, const char *extension, char *out, size_t size);

/* The file `step` places after `path` (before, for a negative step),
 * wrapping around, among the files of path's directory whose names end in
 * one of `extensions` (NULL-terminated, any case: scene_extensions),
 * sorted by name: how the window pages through assets/scenes/. A path not
 * among them counts as before the first. False after printing why when the
 * directory cannot be read or holds none. */
bool path_next_in_directory(const char *path, const char *const *extensions, int step, char *out, size_t size);

/* "<directory of the executable>/../<relative>", resolved when it exists:
 * the programs live in build/, their shaders and assets beside it, so they
 * run from any working directory. */
void path_in_project(const char *relative, char *out, size_t size);

#endif
