#include "path.h"

#include <errno.h>
#include <libgen.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

bool path_make_directories(const char *path) {
    char partial[PATH_MAX];
    snprintf(partial, sizeof partial, "%s", path);
    for (char *p = partial + 1;; p++) {
        if (*p != '/' && *p != '\0')
            continue;
        char c = *p;
        *p = '\0';
        if (mkdir(partial, 0777) != 0 && errno != EEXIST) {
            fprintf(stderr, "%s: cannot create directory: %s\n", partial, strerror(errno));
            return false;
        }
        if (c == '\0')
            return true;
        *p = c;
    }
}

void path_in_project(const char *relative, char *out, size_t size) {
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    exe[n > 0 ? n : 0] = '\0';
    snprintf(out, size, "%s/../%s", n > 0 ? dirname(exe) : ".", relative);
    char *resolved = realpath(out, NULL);
    if (resolved)
        snprintf(out, size, "%s", resolved);
    free(resolved);
}

char *path_read_text(const char *path, size_t max_size, size_t *length) {
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "%s: cannot open: %s\n", path, strerror(errno));
        return NULL;
    }
    size_t capacity = 4096, used = 0;
    char *text = malloc(capacity);
    const char *problem = text ? NULL : "out of memory";
    /* Read in growing chunks: no fseek, so pipes and /proc files work too. */
    while (!problem) {
        used += fread(text + used, 1, capacity - 1 - used, f);
        if (used < capacity - 1)
            break; /* the end, or a read error */
        char *bigger = capacity > max_size ? NULL : realloc(text, capacity * 2);
        if (!bigger)
            problem = capacity > max_size ? "too large" : "out of memory";
        else
            text = bigger, capacity *= 2;
    }
    if (!problem && ferror(f))
        problem = strerror(errno);
    fclose(f);
    if (problem || used > max_size) {
        fprintf(stderr, "%s: cannot read: %s\n", path, problem ? problem : "too large");
        free(text);
        return NULL;
    }
    text[used] = '\0';
    if (length)
        *length = used;
    return text;
}

bool path_stem(const char *path, char *out, size_t size) {
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    const char *dot = strrchr(base, '.');
    return snprintf(out, size, "%.*s", dot ? (int)(dot - base) : (int)strlen(base), base) < (int)size;
}

bool path_numbered_unused(const char *prefix, const char *extension, char *out, size_t size) {
    for (int n = 1; n <= PATH_NUMBERED_MAX; n++) {
        if (snprintf(out, size, "%s-%d.%s", prefix, n, extension) >= (int)size)
            return false;
        struct stat st;
        if (stat(out, &st) != 0 && errno == ENOENT)
            return true;
    }
    return false;
}
