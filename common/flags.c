#include "flags.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FLAGS_MAX_SIZE 16384

bool flags_parse_int(const char *text, int min, int max, int *out) {
    char *end;
    errno = 0;
    long v = strtol(text, &end, 10);
    if (errno || end == text || *end != '\0' || v < min || v > max)
        return false;
    *out = (int)v;
    return true;
}

bool flags_parse_size(const char *text, int *width, int *height) {
    char w[16], h[16];
    const char *x = strchr(text, 'x');
    if (!x || x - text >= (long)sizeof w || strlen(x + 1) >= sizeof h)
        return false;
    snprintf(w, sizeof w, "%.*s", (int)(x - text), text);
    snprintf(h, sizeof h, "%s", x + 1);
    return flags_parse_int(w, 1, FLAGS_MAX_SIZE, width) && flags_parse_int(h, 1, FLAGS_MAX_SIZE, height);
}

int flags_usage_error(const char *program, const char *message, const char *value) {
    if (value)
        fprintf(stderr, "%s: %s '%s' (see --help)\n", program, message, value);
    else
        fprintf(stderr, "%s: %s (see --help)\n", program, message);
    return FLAGS_EXIT_USAGE;
}
