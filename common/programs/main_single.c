/* main of a demo binary that hosts one technique: the Makefile compiles
 * this once per demo with -DDEMO_TECHNIQUE=<name>_technique. An unknown
 * flag that another technique of the registry has is named with that
 * technique's program, beside this one, and build/shadows. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "registry.h"

/* "DIR/psm (or DIR/shadows --technique psm)" */
#define MAIN_ELSEWHERE_NAME_MAX (2 * PATH_MAX)

extern const technique DEMO_TECHNIQUE;

int main(int argc, char **argv) {
    const technique *const techniques[] = {&DEMO_TECHNIQUE};
    const char *slash = strrchr(argv[0], '/');
    int directory = slash ? (int)(slash + 1 - argv[0]) : 0;
    flags_elsewhere *elsewhere = calloc((size_t)registry_technique_count, sizeof *elsewhere);
    char(*names)[MAIN_ELSEWHERE_NAME_MAX] = calloc((size_t)registry_technique_count, sizeof *names);
    int count = 0;
    /* Without the memory the errors only leave the other programs out. */
    for (int t = 0; elsewhere && names && t < registry_technique_count; t++) {
        const technique *other = registry_techniques[t];
        if (other == &DEMO_TECHNIQUE)
            continue;
        snprintf(names[count], sizeof *names, "%.*s%s (or %.*sshadows --technique %s)", directory, argv[0],
                 other->name, directory, argv[0], other->name);
        elsewhere[count] = (flags_elsewhere){names[count], other->params, other->param_count};
        count++;
    }
    int status = app_main(argc, argv, techniques, 1, elsewhere, count);
    free(names);
    free(elsewhere);
    return status;
}
