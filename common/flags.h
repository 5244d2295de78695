/* flags: parsing of flag values, the same for every program, so that
 * "--size 640by480" fails alike everywhere. Each returns false on a
 * malformed or out-of-range value; the caller prints the one-line error
 * (program: --flag: expected ..., got 'value') and exits 2. */
#ifndef FLAGS_H
#define FLAGS_H

#include <stdbool.h>

#define FLAGS_EXIT_USAGE 2

/* A whole decimal integer in [min, max]. */
bool flags_parse_int(const char *text, int min, int max, int *out);
/* "WxH", each 1..16384. */
bool flags_parse_size(const char *text, int *width, int *height);
/* Prints "program: message 'value' (see --help)" (value may be NULL) and
 * returns FLAGS_EXIT_USAGE. */
int flags_usage_error(const char *program, const char *message, const char *value);

#endif
