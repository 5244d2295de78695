#include "video.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#define VIDEO_COMMAND_MAX 4096

static void (*video_old_sigpipe)(int);

static bool video_have_ffmpeg(void) { return system("command -v ffmpeg >/dev/null 2>&1") == 0; }

/* The path in single quotes for the shell, quotes inside escaped. */
static bool video_quote(const char *path, char *out, size_t size) {
    size_t n = 0;
    out[n++] = '\'';
    for (const char *c = path; *c; c++) {
        const char *piece = *c == '\'' ? "'\\''" : (char[2]){*c, 0};
        size_t length = strlen(piece);
        if (n + length + 2 > size)
            return false;
        memcpy(out + n, piece, length);
        n += length;
    }
    out[n++] = '\'';
    out[n] = '\0';
    return true;
}

bool video_open(video *v, const char *path, int width, int height) {
    *v = (video){.path = path, .width = width, .height = height};
    if (!video_have_ffmpeg()) {
        fprintf(stderr, "%s: cannot record: ffmpeg is not installed (Debian package ffmpeg)\n", path);
        return false;
    }
    /* Here, in one line, rather than in ffmpeg's words after it started. */
    FILE *probe = fopen(path, "wb");
    if (!probe || fclose(probe) != 0) {
        fprintf(stderr, "%s: cannot write: %s\n", path, strerror(errno));
        return false;
    }
    char quoted[VIDEO_COMMAND_MAX / 2], command[VIDEO_COMMAND_MAX];
    if (!video_quote(path, quoted, sizeof quoted)) {
        fprintf(stderr, "%s: cannot record: path too long\n", path);
        return false;
    }
    /* H.264 in 4:2:0 wants even sizes: pad by a pixel where odd. One
     * thread, so the same frames give the same bytes. */
    snprintf(command, sizeof command,
             "ffmpeg -hide_banner -loglevel error -y -f rawvideo -pix_fmt rgba -s %dx%d -r %d -i - "
             "-vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -threads 1 -pix_fmt yuv420p %s",
             width, height, VIDEO_FPS, quoted);
    video_old_sigpipe = signal(SIGPIPE, SIG_IGN);
    v->pipe = popen(command, "w");
    if (!v->pipe) {
        perror(path);
        signal(SIGPIPE, video_old_sigpipe);
        return false;
    }
    return true;
}

bool video_write_frame(video *v, const unsigned char *rgba) {
    size_t bytes = (size_t)v->width * (size_t)v->height * 4;
    if (!v->pipe || v->failed)
        return false;
    if (fwrite(rgba, 1, bytes, v->pipe) != bytes) {
        v->failed = true; /* video_close says why */
        return false;
    }
    v->frames++;
    return true;
}

bool video_close(video *v) {
    if (!v->pipe)
        return true;
    int status = pclose(v->pipe);
    v->pipe = NULL;
    signal(SIGPIPE, video_old_sigpipe);
    if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        fprintf(stderr, "%s: ffmpeg failed (exit status %d) after %ld frames\n", v->path,
                status == -1 || !WIFEXITED(status) ? -1 : WEXITSTATUS(status), v->frames);
        return false;
    }
    return !v->failed;
}
