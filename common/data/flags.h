/* flags: parsing of flag values, the same for every program, so that
 * "--size 640by480" fails alike everywhere. Each returns false on a
 * malformed or out-of-range value; the caller prints the one-line error
 * (program: --flag: expected ..., got 'value') and exits 2. */
#ifndef FLAGS_H
#define FLAGS_H

#include <stdbool.h>

#define FLAGS_EXIT_USAGE 2
#define FLAGS_NAME_MAX 64

/* Walks a command line. Flags take their value as "--name=value" or as
 * the next argument when the name is in with_value (NULL-terminated); a
 * flag not in with_value must not have a value. An argument that does not
 * start with '-' is positional: name is the argument, value NULL. */
typedef struct flags_cursor {
    const char *program;
    int argc;
    char **argv;
    int next; /* index of the next argument: start at 1 */
    const char *const *with_value;
    bool (*takes_value)(const char *name); /* more flags with values; may be NULL */
    char name[FLAGS_NAME_MAX];
} flags_cursor;

/* 1 with the next argument in *name and *value, 0 at the end, or
 * FLAGS_EXIT_USAGE after printing the one-line error. */
int flags_next(flags_cursor *c, const char **name, const char **value);

/* A whole decimal integer in [min, max]. */
bool flags_parse_int(const char *text, int min, int max, int *out);
/* "WxH", each 1..16384. */
bool flags_parse_size(const char *text, int *width, int *height);
/* Prints "program: message 'value' (see --help)" (value may be NULL) and
 * returns FLAGS_EXIT_USAGE. */
int flags_usage_error(const char *program, const char *message, const char *value);

#endif
