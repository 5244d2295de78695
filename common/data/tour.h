/* tour: tour files, the prepared sequences of steps a lecture plays
 * (build/shadows --tour FILE; assets/tours/). No GL. A tour file holds:
 *   "title": "..."                                                (required)
 *   "steps": [ 1..TOUR_MAX_STEPS of
 *              { "scene": "../scenes/long_view.json"   (required; relative
 *                                                       to the tour file)
 *                "technique": "psm"                     (required)
 *                "flags": "--warp uniform"  (the technique's own flags, as
 *                                            its --gallery and bench configs)
 *                "caption": "..."           (the HUD's first line)
 *                "seconds": 2               (> 0: how long the step plays)
 *                "motion": "static" | "light" | "camera"      (as --motion)
 *                "frame": N   (the frame a headless run shows, 0 up to the
 *                              step's last; default its last) } ]
 * Unknown keys and wrong types are errors, reported as one line
 * "FILE: steps[i].key: problem" (json.h). The technique's name and flags
 * are the caller's to check: this layer does not know the techniques.
 *
 * Frame i of a step is at time i / TOUR_FPS within the step (the headless
 * rate), so a step renders the same wherever it is played.
 */
#ifndef TOUR_H
#define TOUR_H

#include <limits.h>
#include <stdbool.h>

#include "motion.h"
#include "video.h"

#define TOUR_MAX_STEPS 32
#define TOUR_TEXT_MAX 256   /* title, caption, technique, flags */
#define TOUR_DEFAULT_SECONDS 2.0
#define TOUR_MAX_SECONDS 600.0 /* ten minutes: longer is a typo */
#define TOUR_FPS VIDEO_FPS /* the headless rate and the video's */

typedef struct tour_step {
    char scene[PATH_MAX]; /* resolved against the tour file's folder */
    char technique[TOUR_TEXT_MAX], flags[TOUR_TEXT_MAX], caption[TOUR_TEXT_MAX];
    double seconds;
    motion_kind motion;
    int frame_count; /* seconds at TOUR_FPS, at least 1 */
    int shown_frame; /* what a headless run shows: "frame", or the last */
} tour_step;

typedef struct tour {
    char title[TOUR_TEXT_MAX];
    tour_step steps[TOUR_MAX_STEPS];
    int step_count;
} tour;

/* False after printing the file's first problem. */
bool tour_load(tour *t, const char *path);

#endif
