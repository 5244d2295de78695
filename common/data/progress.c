#include "progress.h"

#include <stdarg.h>
#include <stdio.h>
#include <unistd.h>

void progress_start(progress *p, const char *program, bool quiet) {
    *p = (progress){.program = program, .on = !quiet && isatty(STDERR_FILENO)};
}

void progress_show(progress *p, const char *format, ...) {
    if (!p->on)
        return;
    fprintf(stderr, PROGRESS_REWRITE "%s: ", p->program);
    va_list args;
    va_start(args, format);
    vfprintf(stderr, format, args);
    va_end(args);
    p->open = true;
}

void progress_clear(progress *p) {
    if (p->open)
        fputs(PROGRESS_REWRITE, stderr);
    p->open = false;
}

void progress_end(progress *p) {
    if (p->open)
        fputc('\n', stderr);
    p->open = false;
}
