#include "path.h"

#include <errno.h>
#include <libgen.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <dirent.h>
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

bool path_beside(const char *file, const char *relative, char *out, size_t size) {
    const char *slash = strrchr(file, '/');
    int folder_length = relative[0] == '/' || !slash ? 0 : (int)(slash - file + 1);
    return snprintf(out, size, "%.*s%s", folder_length, file, relative) < (int)size;
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

static int path_compare_names(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* Whether `name` ends in one of `extensions` (NULL-terminated), in any
 * case. */
static bool path_has_extension(const char *name, const char *const *extensions) {
    size_t length = strlen(name);
    for (const char *const *e = extensions; *e; e++) {
        size_t n = strlen(*e);
        if (length > n && strcasecmp(name + length - n, *e) == 0)
            return true;
    }
    return false;
}

bool path_next_in_directory(const char *path, const char *const *extensions, int step, char *out, size_t size) {
    char copy[PATH_MAX], dir[PATH_MAX];
    snprintf(copy, sizeof copy, "%s", path);
    snprintf(dir, sizeof dir, "%s", dirname(copy));
    snprintf(copy, sizeof copy, "%s", path);
    const char *name = basename(copy);
    DIR *d = opendir(dir);
    if (!d) {
        fprintf(stderr, "%s: cannot open directory: %s\n", dir, strerror(errno));
        return false;
    }
    char **names = NULL;
    size_t count = 0, capacity = 0;
    bool ok = true;
    for (struct dirent *e; ok && (e = readdir(d));) {
        if (!path_has_extension(e->d_name, extensions))
            continue;
        if (count == capacity) {
            capacity = capacity ? 2 * capacity : 16;
            char **grown = realloc(names, capacity * sizeof *names);
            ok = grown != NULL;
            names = grown ? grown : names;
        }
        if (ok && !(names[count] = strdup(e->d_name)))
            ok = false;
        count += ok;
    }
    closedir(d);
    if (!ok)
        fprintf(stderr, "%s: out of memory listing the directory\n", dir);
    else if (count == 0) {
        fprintf(stderr, "%s: no file ending in", dir);
        for (const char *const *e = extensions; *e; e++)
            fprintf(stderr, " %s", *e);
        fputc('\n', stderr);
    }
    if (ok && count > 0) {
        qsort(names, count, sizeof *names, path_compare_names);
        long here = -1; /* before the first */
        for (size_t i = 0; i < count; i++)
            if (strcmp(names[i], name) == 0)
                here = (long)i;
        long n = (long)count;
        long next = here < 0 ? (step > 0 ? step - 1 : n + step) : here + step;
        next = ((next % n) + n) % n;
        ok = snprintf(out, size, "%s/%s", dir, names[next]) < (int)size;
    }
    for (size_t i = 0; i < count; i++)
        free(names[i]);
    free(names);
    return ok && count > 0;
}
