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
 *                "motion": "static" | "light" | "camera" | "dolly"
 *                                                             (as --motion)
 *                "frame": N   (the frame a headless run shows, 0 up to the
 *                              step's last; default its last)
 *                "camera": {"position": [x,y,z], "target": [x,y,z]}
 *                             (the step's eye, in the scene file's world
 *                              coordinates; fov, up, near and far stay the
 *                              scene's; "motion": "camera" orbits it)
 *                "path": [ TOUR_MIN_PATH_VIEWS..TOUR_MAX_PATH_VIEWS of
 *                          {"position": [x,y,z], "target": [x,y,z]} ]
 *                             (a fly-through, spread evenly over the step:
 *                              tour_path_view; not with "camera" nor with
 *                              a motion that moves the camera)
 *                "compare": true  (compare mode, as --compare: the step
 *                                  beside the ray-traced truth)
 *                "subject": {"min": [x,y,z], "max": [x,y,z]}
 *                             (what the caption speaks of, its casters and
 *                              their shadows, as a box in the scene file's
 *                              world coordinates; nothing renders it: the
 *                              tours' test keeps it in view and clear of
 *                              the HUD, tests/test_tour_views.c) } ]
 * Unknown keys and wrong types are errors, each reported as one line
 * "FILE: steps[i].key: problem" (json.h), every one the file has (a JSON
 * syntax error, or "steps" not a list of steps, is the only one). The
 * technique's name and flags are the caller's to check: this layer does
 * not know the techniques.
 *
 * Numbers must be finite and each view's position must differ from its
 * target; every frame's view (between two views too) is checked against
 * the scene once it is known (tour_step_check_views).
 *
 * Frame i of a step is at time i / TOUR_FPS within the step (the headless
 * rate), so a step renders the same wherever it is played: a path's view
 * is a function of that time alone.
 */
#ifndef TOUR_H
#define TOUR_H

#include <limits.h>
#include <stdbool.h>

#include "motion.h"
#include "video.h"

#define TOUR_MAX_STEPS 32
#define TOUR_TEXT_MAX 256 /* title, caption, technique, flags */
#define TOUR_DEFAULT_SECONDS 2.0
#define TOUR_MAX_SECONDS 600.0 /* ten minutes: longer is a typo */
#define TOUR_FPS VIDEO_FPS     /* the headless rate and the video's */
#define TOUR_MIN_PATH_VIEWS 2  /* fewer is a "camera" */
#define TOUR_MAX_PATH_VIEWS 16

/* Where the eye is and what it looks at, in the scene file's world
 * coordinates (before the scene's origin is subtracted: scene.h, "Large
 * worlds"), in double as the file's numbers. */
typedef struct tour_view {
    double position[3], target[3];
} tour_view;

/* A box in the scene file's world coordinates, max nowhere below min. */
typedef struct tour_box {
    double min[3], max[3];
} tour_box;

typedef struct tour_step {
    char scene[PATH_MAX]; /* resolved against the tour file's folder */
    char technique[TOUR_TEXT_MAX], flags[TOUR_TEXT_MAX], caption[TOUR_TEXT_MAX];
    double seconds;
    motion_kind motion;
    bool compare;    /* "compare" */
    int frame_count; /* seconds at TOUR_FPS, at least 1 */
    int shown_frame; /* what a headless run shows: "frame", or the last */
    /* 0: the scene's camera; 1: "camera"; TOUR_MIN_PATH_VIEWS or more:
     * "path" */
    int view_count;
    tour_view views[TOUR_MAX_PATH_VIEWS];
    bool has_subject; /* "subject" */
    tour_box subject;
} tour_step;

typedef struct tour {
    char title[TOUR_TEXT_MAX];
    tour_step steps[TOUR_MAX_STEPS];
    int step_count;
} tour;

/* False after printing every problem of the file, each one line. The
 * steps read are there even then (step_count of them; a field that failed
 * is empty), so that the caller adds its own checks' lines to the
 * file's. */
bool tour_load(tour *t, const char *path);

static inline bool tour_step_has_path(const tour_step *s) { return s->view_count >= TOUR_MIN_PATH_VIEWS; }

/* The path through count views at u: 0 is the first view, 1 the last,
 * clamped beyond; the views stand at even steps of u between. Within a
 * segment, position and target go linearly from one view to the next,
 * eased by smoothstep (3w^2 - 2w^3): the camera passes every view exactly
 * and rests on it an instant (each is a viewpoint the lecture chose to
 * show), never overshoots as a spline would (through a wall, or past the
 * target), and starts and stops gently where a plain lerp would jerk into
 * motion. The ends are exact: u <= 0 gives views[0], u >= 1
 * views[count - 1], bit for bit. */
tour_view tour_path_view(const tour_view *views, int count, double u);

/* Step s's view (it has one) at `time` within the step: its "camera", or
 * its path with the first view at frame 0 and the last at the step's last
 * frame (a headless run's default picture is where the path ends). */
tour_view tour_step_view(const tour_step *s, double time);

/* A step with a camera or a path: its view at `time`, less the scene's
 * origin, as camera's position and target (the rest stays). A step
 * without: camera as it was. */
void tour_step_camera(const tour_step *s, double time, const double origin[3], scene_camera *camera);

/* Step k's views against its scene, once loaded (its origin and camera):
 * false after "FILE: steps[k].camera|path: ..." where a frame's view, in
 * float less the origin as the renderer gets it, has no direction, looks
 * along the camera's up (the view matrix would be undefined) or does not
 * fit a float. The view between frames (a window's clock) is assumed as
 * good as the frames about it. */
bool tour_step_check_views(const char *file, int k, const tour_step *s, const double origin[3],
                           const scene_camera *camera);

#endif
