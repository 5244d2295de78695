/* video: frames (8-bit RGBA, top row first, as image.h) piped to ffmpeg
 * (Debian's ffmpeg package), which encodes them as H.264 in the file's
 * container (.mp4, .mkv) at a fixed rate. Frames carry no clock: the
 * caller renders frame i at time i / fps, so the same command writes the
 * same video.
 *
 * video_open checks that ffmpeg is there, and otherwise says so in one
 * line naming the file and the package. A write to an ffmpeg that has
 * died fails (SIGPIPE is ignored while a video is open), and video_close
 * reports ffmpeg's failure: never a crash, never a silently short video.
 */
#ifndef VIDEO_H
#define VIDEO_H

#include <stdbool.h>
#include <stdio.h>

/* Frames a second: the headless frame rate (frame i at i / 60 s). */
#define VIDEO_FPS 60

typedef struct video {
    FILE *pipe; /* ffmpeg's standard input; NULL when not open */
    const char *path;
    int width, height;
    long frames;
    bool failed; /* a write failed: ffmpeg is gone */
} video;

bool video_open(video *v, const char *path, int width, int height);
bool video_write_frame(video *v, const unsigned char *rgba);
/* Waits for ffmpeg; false if it failed or a write had. Safe on a video
 * that is not open. */
bool video_close(video *v);

#endif
