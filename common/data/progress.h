/* progress: how far long work is, for the person waiting at a terminal:
 * one line on stderr, "PROGRAM: TEXT", that each update rewrites in
 * place, ended when the work is. Only where stderr is a terminal and the
 * program was not given --quiet: a pipe, a file or a log gets nothing,
 * and what the work writes is the same either way.
 *
 *   progress p;
 *   progress_start(&p, program, quiet);
 *   each step:   progress_show(&p, "frames %d of %d", done, total);
 *   before a line on stdout:  progress_clear(&p);   the next show redraws
 *   at the end:  progress_end(&p);    the last text stays, on its own line
 */
#ifndef PROGRESS_H
#define PROGRESS_H

#include <stdbool.h>

/* What each line starts with: back to the line's start, and everything
 * from there to its end erased (ANSI's erase in line), so that a shorter
 * text leaves nothing behind. */
#define PROGRESS_REWRITE "\r\033[K"

typedef struct progress {
    const char *program; /* each line's prefix */
    bool on;             /* stderr is a terminal and not --quiet */
    bool open;           /* a line is shown, the cursor at its end */
} progress;

void progress_start(progress *p, const char *program, bool quiet);
/* The line's text, printf's way, in place of the one shown. */
void progress_show(progress *p, const char *format, ...) __attribute__((format(printf, 2, 3)));
/* The shown line erased, the cursor at its start. */
void progress_clear(progress *p);
/* The shown line kept and ended. */
void progress_end(progress *p);

#endif
