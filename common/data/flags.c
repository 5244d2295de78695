#include "flags.h"

#include <errno.h>
#include <stdbool.h>
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

int flags_next(flags_cursor *c, const char **name, const char **value) {
    if (c->next >= c->argc)
        return 0;
    const char *arg = c->argv[c->next++];
    *value = NULL;
    if (arg[0] != '-') {
        *name = arg;
        return 1;
    }
    const char *eq = strncmp(arg, "--", 2) == 0 ? strchr(arg, '=') : NULL;
    snprintf(c->name, sizeof c->name, "%.*s", eq ? (int)(eq - arg) : (int)strlen(arg), arg);
    *name = c->name;
    bool needs_value = false;
    for (const char *const *w = c->with_value; w && *w; w++)
        needs_value |= strcmp(c->name, *w) == 0;
    needs_value |= c->takes_value && c->takes_value(c->name);
    if (needs_value && !eq) {
        if (c->next >= c->argc)
            return flags_usage_error(c->program, "missing value after", c->name);
        *value = c->argv[c->next++];
    } else if (needs_value) {
        *value = eq + 1;
    } else if (eq) {
        return flags_usage_error(c->program, "flag takes no value:", arg);
    }
    return 1;
}
