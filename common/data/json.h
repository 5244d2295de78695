/* json: what the JSON file readers share (scene.c, tour.c), and the
 * writing of a tree to a file. Every reader
 * reports its field's first problem as one line on stderr, "FILE:
 * WHERE.KEY: problem" (WHERE "steps[2]", or "" at the top), and returns
 * false; an optional field that is absent leaves *out as it was (its
 * default). A file's reader stops at its first problem (scene.c) or goes
 * on to say every one (tour.c). No GL. */
#ifndef JSON_H
#define JSON_H

#include <stdbool.h>
#include <stddef.h>

#include <cjson/cJSON.h>

/* The file parsed, or NULL after "PATH:LINE: JSON syntax error near 'c'"
 * or path_read_text's line (a file over max_size is not read). */
cJSON *json_load(const char *path, size_t max_size);
/* Writes `root` (then deleted) to `path` as cJSON_Print's text; false
 * after "PATH: cannot write: reason". */
bool json_save(cJSON *root, const char *path);

/* Prints "FILE: WHERE.KEY: problem"; where may be "" and key NULL.
 * Returns false. */
bool json_fail(const char *file, const char *where, const char *key, const char *format, ...)
    __attribute__((format(printf, 4, 5)));
/* "a number", "a string", ...: what errors say a value is. */
const char *json_kind(const cJSON *item);
/* The NULL-terminated names as "a, b, c or d". */
void json_join_names(const char *const names[], char *out, size_t size);
/* object's `key` into *item (NULL when absent); fails when required. */
bool json_lookup(const char *file, const cJSON *object, const char *where, const char *key, bool required,
                 const cJSON **item);
/* Fails on a key not in `allowed` (NULL-terminated: usually a typo, so
 * the nearest allowed one is suggested: typo.h) or a repeated one (which
 * hides a value). */
bool json_check_keys(const char *file, const cJSON *object, const char *where, const char *const allowed[]);
bool json_read_int(const char *file, const cJSON *object, const char *where, const char *key, int *out);
bool json_read_bool(const char *file, const cJSON *object, const char *where, const char *key, bool *out);
/* The string stays owned by the JSON tree. */
bool json_read_string(const char *file, const cJSON *object, const char *where, const char *key, bool required,
                      const char **out);
/* A required array of exactly count finite numbers, in double. */
bool json_read_numbers(const char *file, const cJSON *object, const char *where, const char *key, double *out,
                       int count);
/* A required object. */
bool json_read_object(const char *file, const cJSON *object, const char *where, const char *key, const cJSON **out);

#endif
