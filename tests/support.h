/* support: what the tests share: running a program and capturing its
 * exit status and stderr, and comparing a screenshot with a golden image.
 *
 * Tests run from the repository root; programs are in $BUILD (build/ by
 * default, build-san/ for the sanitizer run) and write under out/test/.
 */
#ifndef SUPPORT_H
#define SUPPORT_H

#include <stdbool.h>
#include <stddef.h>

#include <cjson/cJSON.h>

#include "dump.h"
#include "shadowdiff.h"

/* Golden-image tolerance: at most a thousandth of the pixels may differ by
 * more than 8/255 in any channel (rasterizers may round an edge pixel
 * differently). */
#define SUPPORT_TOLERANCE 8
#define SUPPORT_MAX_DIFFERING 0.001

/* "$BUILD/NAME", behind `env LD_PRELOAD=...` when run.sh asks for it
 * (the sanitizer run; see run.sh). */
const char *support_program(const char *name);
/* The sweeps' stride. A sweep repeats one code path with other numbers
 * (light directions, cases of a table). Two tiers (run.sh's TEST_TIER):
 * make test-all's whole matrix takes every case in the plain pass, and
 * every SUPPORT_SANITIZER_STRIDE-th in the sanitizer pass, which runs
 * every program 2 to 3 times slower; make test's quick tier takes every
 * SUPPORT_QUICK_STRIDE-th in the plain pass and runs only run.sh's
 * sanitizer subset, at the sanitizer stride. Cases start with the first:
 * the paths are the same, and make test stays within CI's budget. Powers
 * of two: a table of odd length swept by pairs is then reached everywhere. */
#define SUPPORT_SANITIZER_STRIDE 8
#define SUPPORT_QUICK_STRIDE 4
_Static_assert((SUPPORT_SANITIZER_STRIDE & (SUPPORT_SANITIZER_STRIDE - 1)) == 0, "a power of two");
_Static_assert((SUPPORT_QUICK_STRIDE & (SUPPORT_QUICK_STRIDE - 1)) == 0, "a power of two");
int support_sweep_stride(void);
/* Whether a sweep of settings over `scene_count` scenes takes `setting` on
 * `scene`: every pair in the whole matrix, each setting on one scene in
 * turn otherwise (setting modulo scene_count). */
bool support_sweep_takes(int setting, int scene, int scene_count);
/* A sweep over pairs (i, k), k the faster of `count`: flat index i * count
 * + k in steps of the stride. An odd count is prime to the stride, which
 * then reaches every i and every k. */
#define SUPPORT_SWEEPABLE(count) _Static_assert((count) % 2 == 1, "an odd count, prime to the sanitizer stride")
/* Runs `command` through the shell with stderr captured; returns the exit
 * status (-1 if it did not exit normally). */
int support_run(const char *command, char *stderr_text, size_t capacity);
int support_count_lines(const char *text);
/* Fraction of pixels that differ by more than SUPPORT_TOLERANCE; -1 if an
 * image is unreadable or the sizes differ. When the fraction is over
 * SUPPORT_MAX_DIFFERING, writes `actual` with "_diff.png" beside it. */
double support_compare_images(const char *golden, const char *actual);
/* The RGBA pixels of the PNG at `path`, which must be width x height;
 * fails the running cmocka test otherwise. The caller frees them. */
unsigned char *support_read_png(const char *path, int width, int height);
/* The share of a heat map that its error discs must cover where there
 * are errors, to be seen in a hall: a thousandth of a 1080p compare cell
 * is a 21-pixel square. */
#define SUPPORT_VISIBLE_ERROR_SHARE 0.001
/* The share of the width x height rectangle at (x0, y0) of an RGBA
 * picture `stride` pixels wide that has a heat map's error colours
 * (false shadow or false lit). */
double support_error_share(const unsigned char *rgba, int stride, int x0, int y0, int width, int height);
/* Runs `PROGRAM --size 640x360 --scene SCENE FLAGS --screenshot
 * out/test/NAME.png`, fails the running cmocka test unless it exits 0,
 * and returns the picture's RGBA pixels (640 x 360; the caller frees
 * them). */
#define SUPPORT_SCREENSHOT_WIDTH 640
#define SUPPORT_SCREENSHOT_HEIGHT 360
unsigned char *support_screenshot(const char *program, const char *scene, const char *flags, const char *name);
/* Pictures' regions: rect is x, y, width and height in pixels from the
 * bottom-left corner of an RGBA picture of width x height (rows stored
 * from the top), clipped to it. The pixels of rect that are grey (r = g =
 * b) no lighter than max_grey: how many (*count), and the span of their
 * grey between the 5th and the 95th percentile (0 where there are none). */
int support_grey_spread(const unsigned char *rgba, int width, int height, const int rect[4], int max_grey,
                        long *count);
/* The RGBA pixel at (x, y) from the bottom-left. */
const unsigned char *support_pixel(const unsigned char *rgba, int width, int height, int x, int y);
/* The pixels of rect of colour rgb (each channel within 1). */
long support_count_color(const unsigned char *rgba, int width, int height, const int rect[4],
                         const unsigned char rgb[3]);
/* Whether rect holds a square of side x side pixels all of colour rgb
 * (each channel within 1). */
bool support_find_square(const unsigned char *rgba, int width, int height, const int rect[4],
                         const unsigned char rgb[3], int side);
/* Light 0's map insets (demos/lib/map.h, "The map inset") in the
 * screenshot `name` of PROGRAM with FLAGS on SCENE (support_screenshot),
 * whose light 0 has a map of `kind` with `layer_count` layers: each inset
 * but those `empty` marks (bit k: inset k holds nothing) shows at least
 * SUPPORT_INSET_MIN_HELD pixels of held depth (grey, no lighter than the
 * ramp's farthest), whose grey spans at least SUPPORT_INSET_MIN_SPREAD
 * levels (of 255) between its 5th and 95th percentiles; prints each
 * inset's figures, fails the running cmocka test otherwise, and returns
 * the picture (the caller frees it). */
#define SUPPORT_INSET_MIN_HELD 8
#define SUPPORT_INSET_MIN_SPREAD 64
unsigned char *support_expect_insets_fitted(const char *program, const char *scene, const char *flags,
                                            const char *name, int kind, int layer_count, unsigned empty);
bool support_have_command(const char *name);
/* The command prefix that runs a program in a window under a virtual X
 * server (the server without this process's LD_PRELOAD: support_program
 * gives the program its own), one such server at a time across
 * processes; skips the running cmocka test, saying so, where xvfb-run is
 * not installed. */
const char *support_xvfb_run(void);
/* A tour's caption kept true in the window and in the page: the tour
 * SUPPORT_CAPTION_TOUR at SUPPORT_CAPTION_SIZE with its HUD and
 * --verbose, stepped to step SUPPORT_CAPTION_STEP (from 1), F12 there, then
 * key 6 (volumes), F12, key 3 (the step's technique again), F12, key C
 * (its constant bias off), F12: SUPPORT_CAPTION_PICTURES pictures.
 * support_expect_captions fails the running cmocka test unless the HUD
 * text each F12 printed (`log`'s "hud: " lines, one block from each
 * "hud: step") names what changed (nothing, "technique volumes",
 * nothing, "constant-bias OFF"), and each picture's caption line (the
 * first of the HUD) is drawn white where nothing changed and dimmed
 * where something did. */
#define SUPPORT_CAPTION_TOUR "assets/tours/overview.json"
#define SUPPORT_CAPTION_SIZE "640x360"
#define SUPPORT_CAPTION_STEP 4 /* shadow maps on the bunny */
#define SUPPORT_CAPTION_PICTURES 4
void support_expect_captions(const char *log, const char *const pictures[SUPPORT_CAPTION_PICTURES]);
/* The first of the count files `names` that differs between directories
 * a and b (or is missing from one), or NULL when all are byte-identical. */
const char *support_first_difference(const char *a, const char *b, const char *const *names, size_t count);
/* Runs `PROGRAM --size 640x360 --scene SCENE FLAGS --frames 1 --verbose`
 * (--size and --frames only where FLAGS do not give them: a flag that
 * takes a value is given once), fails the running cmocka test unless it
 * exits 0, and returns the first line of its stderr that starts with
 * `marker` (the line goes on to the end of the text), or NULL. The text
 * lives until the next call. */
const char *support_verbose_line(const char *program, const char *scene, const char *flags, const char *marker);
/* Runs `program --size 640x360 --scene SCENE FLAGS --dump DIR` (the
 * accuracy tests' size, where FLAGS give no --size); returns its exit
 * status. */
int support_dump(const char *program, const char *scene, const char *flags, const char *dir);
/* The ray-traced reference and PROGRAM's dump of `scene` at `size`
 * ("--size WxH", or "" for 640x360) with `flags`, in
 * $TEST_REFERENCES/HASH (out/test/reference/HASH where run.sh does not set
 * it), traced once a run for each scene text, size and build (a lock file
 * beside it lets one of the processes that need it trace it while the
 * others wait), and out/test/PROGRAM/NAME, compared with
 * shadowdiff's rules over every object; prints the figures. Fails the
 * running cmocka test when a program fails. support_measure_dumps hands
 * back the dumps and the heat map (red false shadow, blue false lit) for
 * the caller to free. */
shadowdiff_result support_measure_dumps(const char *program, const char *scene, const char *size, const char *flags,
                                        const char *name, dump_frame *reference, dump_frame *test,
                                        unsigned char **heatmap);
shadowdiff_result support_measure(const char *program, const char *scene, const char *size, const char *flags,
                                  const char *name);
/* PROGRAM's dump of `scene` with `flags` against the reference's with
 * `reference_flags`, at 640x360 (support_dump), in out/test/GROUP/NAME and
 * out/test/GROUP/NAME_reference, compared with shadowdiff's rules on the
 * object `receiver` (NULL: every object), the heat map written beside as
 * NAME_heatmap.png; prints the figures and sets *receiver_pixels to the
 * reference's pixels of the receiver (of any object, for NULL). Fails the
 * running cmocka test when a program fails. */
shadowdiff_result support_measure_receiver(const char *program, const char *group, const char *name,
                                           const char *scene, const char *reference_flags, const char *flags,
                                           const char *receiver, long *receiver_pixels);
/* PROGRAM's defaults on each standard scene (a spot, a point and a
 * directional light) at 640x360: most receiver pixels compared
 * (SUPPORT_STANDARD_MIN_COMPARED of 230400), at most max_percent
 * misclassified; fails the running cmocka test otherwise. */
#define SUPPORT_STANDARD_MIN_COMPARED 50000
void support_standard_scenes_within(const char *program, double max_percent);
/* The JSON of the scene file at `path` (at most SUPPORT_MAX_SCENE_BYTES,
 * the most a scene file may hold, a glTF binary's bytes too: the
 * references' key), for a test to change and write back
 * (support_write_json); fails the running cmocka test when it cannot.
 * The caller cJSON_Deletes it. */
#define SUPPORT_MAX_SCENE_BYTES (16 << 20)
cJSON *support_read_json(const char *path);
/* Writes the JSON `root` to DIR/NAME.json (making DIR), its path into
 * `path`; fails the running cmocka test when it cannot. */
void support_write_json(const cJSON *root, const char *dir, const char *name, char *path, size_t size);
/* Sends stderr to a temporary file until support_release_stderr, which
 * returns what was written. cmocka reports failures on stderr too, so no
 * assertion may run in between. */
void support_capture_stderr(void);
const char *support_release_stderr(void);

#endif
