/* Every lecture tour's captions, true of its pictures (assets/tours/): one
 * table of claims, each a step of a tour rendered as the tour renders it
 * (a tour of that one step, headless on EGL at CLAIM_SIZE: the step's
 * scene, camera or path, motion and shown frame) and the same step with
 * the fix its caption speaks of (other flags, another technique), and a
 * measure of how the two pictures differ in the way the caption says, with
 * the amount it must reach. A step that only shows something (an overlay,
 * a compare step whose caption states no figure) has no row.
 *
 * A pixel's level is the sum of its three channels; plainly darker or
 * lighter is by more than CLAIM_DROP. The measures:
 *   darker, lighter     pixels plainly darker (lighter) in the step than
 *                       in the fix;
 *   darker on lit       plainly darker where the fix is lit, as lit as the
 *                       step unshadowed (technique unshadowed): false
 *                       shadow (acne), shadow spilt where there is none;
 *   darker on shadow    plainly darker where the fix is in shadow, darker
 *                       than the unshadowed picture: darker than the fix's
 *                       own shadow (double darkening);
 *   lighter on shadow   plainly lighter where the fix is in shadow: shadow
 *                       lost, or a blur's inner penumbra (its outer one is
 *                       darker on lit, against a sharper picture);
 *   warmer              the texel-size heat map's warm pixels (red above
 *                       green: a texel of more than about five pixels), the
 *                       step's less the fix's;
 *   warm                the step's warm pixels, at most the amount (its
 *                       legend's warm end among them);
 *   misclassified       a compare step's misclassified pixels against the
 *                       truth, as it prints them, at most the amount;
 *   false lit           a compare step's false-lit percentage, at least;
 *   less false lit,     the fix's false-lit (false-shadow) percentage over
 *   less false shadow   the step's, both compare steps: at least the ratio.
 * The counts are pixels of a CLAIM_SIZE picture. Each row's amount is the
 * least (the most, for misclassified and warm) that keeps the caption's
 * words true of the picture, with a margin for other rasterizers; the test
 * prints what it measured. The sanitizer pass takes every
 * support_sweep_stride()th row: the rows differ in pictures, not in the
 * code that renders and measures them. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"
#include "tour.h"

#define CLAIM_SIZE "640x360"
#define CLAIM_WIDTH 640
#define CLAIM_HEIGHT 360
#define CLAIM_OUT "out/test/tour_claims"
/* A sum of three channels: a drop of 16 a channel. */
#define CLAIM_DROP 48
/* Warm: red above green (and blue) by this much of 255. */
#define CLAIM_WARM_MARGIN 24
#define CLAIM_CHANNELS 4 /* support_read_png: RGBA */
#define CLAIM_MAX_PICTURES 96

typedef enum claim_measure {
    CLAIM_DARKER,
    CLAIM_LIGHTER,
    CLAIM_DARKER_ON_LIT,
    CLAIM_DARKER_ON_SHADOW,
    CLAIM_LIGHTER_ON_SHADOW,
    CLAIM_WARMER,
    CLAIM_WARM,
    CLAIM_MISCLASSIFIED,
    CLAIM_FALSE_LIT,
    CLAIM_LESS_FALSE_LIT,
    CLAIM_LESS_FALSE_SHADOW,
} claim_measure;

/* A picture of a step: the technique and flags it is rendered with
 * (technique NULL: the step's; flags NULL: the step's with its own
 * technique, none with another). */
typedef struct claim_variant {
    const char *technique, *flags;
} claim_variant;

typedef struct claim {
    const char *tour; /* assets/tours/NAME.json */
    int step;         /* from 1, as the tour's screenshots count */
    claim_variant as; /* the picture the caption shows (STEP: the step as it is) */
    claim_variant fix;
    claim_measure measure;
    double amount;    /* the least (misclassified: the most) */
    const char *what; /* the caption's words measured */
} claim;

/* The variants a row names, one line each. */
/* clang-format off */
#define STEP {NULL, NULL}
#define UNSHADOWED {"unshadowed", NULL}
#define PLANAR {"planar", NULL}
/* clang-format on */
/* The acne under the default's disc: what the filter would average. */
#define ACNE_DISC "--no-constant-bias --no-slope-bias --filter poisson"

static const claim claims[] = {
    /* overview */
    {"overview", 1, STEP, PLANAR, CLAIM_LIGHTER, 3000, "without shadows: planar's shadows missing"},
    {"overview", 2, STEP, UNSHADOWED, CLAIM_DARKER, 3000, "planar shadows on the ground"},
    {"overview", 3, STEP, UNSHADOWED, CLAIM_DARKER, 3000, "projective shadows on the ground"},
    {"overview", 4, STEP, UNSHADOWED, CLAIM_DARKER, 3000, "shadow maps' shadows"},
    {"overview", 5, {NULL, "--warp uniform"}, STEP, CLAIM_DARKER_ON_LIT, 300, "psm sharp, where uniform smears"},
    {"overview", 6, STEP, UNSHADOWED, CLAIM_DARKER, 3000, "shadow volumes' shadows"},
    {"overview", 7, STEP, STEP, CLAIM_MISCLASSIFIED, 8, "the hybrid against the truth: exact to a few pixels"},
    /* planar */
    {"planar", 1, STEP, PLANAR, CLAIM_LIGHTER, 3000, "without shadows: planar's shadows missing"},
    {"planar", 2, STEP, UNSHADOWED, CLAIM_DARKER, 1000, "each caster flattened onto the ground, dark"},
    {"planar", 4, STEP, {NULL, ""}, CLAIM_DARKER_ON_SHADOW, 500, "stencil off: triangles darken twice"},
    {"planar", 4, STEP, {NULL, ""}, CLAIM_DARKER_ON_LIT, 500, "stencil off: shadows spill off the stage"},
    {"planar", 5, STEP, {NULL, ""}, CLAIM_LIGHTER, 500, "offset off: casters z-fight with the ground"},
    {"planar", 6, STEP, STEP, CLAIM_MISCLASSIFIED, 8, "against the truth: exact to a few pixels"},
    /* projective */
    {"projective", 1, STEP, UNSHADOWED, CLAIM_DARKER, 1000, "the casters' image projected onto the ground"},
    {"projective", 2, STEP, {"shadowmap", NULL}, CLAIM_LIGHTER_ON_SHADOW, 1000, "the table shows no shadow"},
    {"projective", 3, STEP, {NULL, ""}, CLAIM_DARKER_ON_LIT, 2000, "self-shadowing: the table's lit top blackened"},
    {"projective", 4, STEP, {NULL, ""}, CLAIM_DARKER, 800, "receivers out: the ball's shadow on the table"},
    {"projective", 4, STEP, {NULL, ""}, CLAIM_LIGHTER_ON_SHADOW, 2000, "receivers out: the table casts none"},
    {"projective", 5, STEP, {NULL, ""}, CLAIM_DARKER_ON_LIT, 200, "near cut off: the shelf shadowed backward"},
    {"projective", 6, STEP, STEP, CLAIM_MISCLASSIFIED, 8, "against the truth: exact to a few pixels"},
    {"projective", 7, STEP, {"projective", NULL}, CLAIM_DARKER, 1000, "a shadow map: the table's shadow of the ball"},
    {"projective", 7, STEP, {"projective", "--no-near-cut"}, CLAIM_LIGHTER, 400, "a shadow map: the shelf lit"},
    /* shadowmap */
    {"shadowmap", 1, STEP, {"shadowmap", NULL}, CLAIM_LIGHTER, 3000, "the problem: no shadows"},
    {"shadowmap", 1, PLANAR, {"shadowmap", NULL}, CLAIM_LIGHTER, 500, "a curved receiver no plane flattens onto"},
    {"shadowmap", 2, STEP, UNSHADOWED, CLAIM_DARKER, 1000, "the fix: depth from the light, per pixel"},
    {"shadowmap", 3, STEP, {NULL, ""}, CLAIM_DARKER_ON_LIT, 20000, "bias off: surfaces shadow themselves"},
    {"shadowmap", 3, STEP, {NULL, ACNE_DISC}, CLAIM_DARKER, 10000, "the filter off: no acne averaged away"},
    {"shadowmap", 4, STEP, {"volumes", NULL}, CLAIM_DARKER_ON_LIT, 50, "a staircase: steps out of the exact edge"},
    {"shadowmap", 4, STEP, {"volumes", NULL}, CLAIM_LIGHTER_ON_SHADOW, 50, "a staircase: steps into it"},
    {"shadowmap", 4, {NULL, "--map-size 256"}, STEP, CLAIM_DARKER_ON_LIT, 500, "filter off: none of its blur"},
    {"shadowmap", 6, STEP, STEP, CLAIM_MISCLASSIFIED, 20, "against the truth: errors only along edges"},
    {"shadowmap", 8, STEP, STEP, CLAIM_MISCLASSIFIED, 8, "rays where the map is unsure: exact"},
    /* psm */
    {"psm", 1, STEP, {NULL, ""}, CLAIM_DARKER_ON_LIT, 1000, "uniform: shadows smear near the viewer"},
    {"psm", 2, {NULL, "--warp uniform"}, STEP, CLAIM_LIGHTER_ON_SHADOW, 1000, "the fix: sharp up close"},
    {"psm", 3, STEP, {NULL, "--overlay texel-size"}, CLAIM_WARMER, 20000, "warp off: texels large near the viewer"},
    {"psm", 4, STEP, STEP, CLAIM_WARM, 1000, "warp on: no texel larger than a few pixels"},
    /* soft */
    {"soft", 1, STEP, STEP, CLAIM_FALSE_LIT, 0.1, "the thin poles' far shadows speckle"},
    {"soft", 2, {NULL, ""}, STEP, CLAIM_LIGHTER_ON_SHADOW, 700, "hard: one sharp edge, no penumbra in"},
    {"soft", 3, STEP, {NULL, ""}, CLAIM_DARKER_ON_LIT, 60, "wide PCF: soft at the foot, where PCSS is sharp"},
    {"soft", 4, STEP, {NULL, "--soft off"}, CLAIM_DARKER_ON_LIT, 1000, "PCSS: wide far from the pole"},
    {"soft", 6, STEP, {NULL, "--soft off"}, CLAIM_DARKER_ON_LIT, 250, "the ears' shadows soft at their tips"},
    {"soft", 7, STEP, STEP, CLAIM_FALSE_LIT, 1, "VSM: light bleeds through the bunny's shadow"},
    {"soft", 8, STEP, {NULL, "--filter vsm"}, CLAIM_LESS_FALSE_LIT, 1.5, "MSM: far less bleeding"},
    {"soft", 8, STEP, {NULL, "--filter vsm"}, CLAIM_LESS_FALSE_SHADOW, 2, "MSM: thinner rims"},
    {"soft",
     9,
     STEP,
     {NULL, "--light-samples 64"},
     CLAIM_LIGHTER_ON_SHADOW,
     1400,
     "volumes from the centre: one hard edge"},
    {"soft",
     10,
     STEP,
     {NULL, "--light-samples 1"},
     CLAIM_DARKER_ON_LIT,
     1000,
     "four points: a penumbra past the hard edge"},
    {"soft", 11, STEP, {NULL, "--light-samples 4"}, CLAIM_LIGHTER, 700, "sixteen points: the penumbra filling in"},
    {"soft", 12, STEP, STEP, CLAIM_MISCLASSIFIED, 200, "sixty-four points: the truth's penumbra"},
    {"soft", 13, STEP, STEP, CLAIM_MISCLASSIFIED, 120, "wedges beside the truth: smooth"},
    {"soft", 14, STEP, STEP, CLAIM_MISCLASSIFIED, 200, "wedges under the sun beside the truth"},
    /* the picture with sixty-four points, its "fix" the wedges: theirs the
     * more false shadow */
    {"soft",
     14,
     {NULL, "--light-samples 64"},
     STEP,
     CLAIM_LESS_FALSE_SHADOW,
     2,
     "wedges: the rim darker than sixty-four points'"},
    /* hybrid */
    {"hybrid", 1, STEP, STEP, CLAIM_FALSE_LIT, 0.05, "the map alone: wrong along the edges"},
    {"hybrid", 3, STEP, STEP, CLAIM_MISCLASSIFIED, 8, "rays where the map is unsure: exact"},
    {"hybrid", 4, STEP, STEP, CLAIM_MISCLASSIFIED, 8, "every pixel traced: the same, exact"},
    {"hybrid", 5, STEP, STEP, CLAIM_MISCLASSIFIED, 8, "cut-outs: exact"},
    /* volumes */
    {"volumes", 1, STEP, {"volumes", NULL}, CLAIM_DARKER, 50, "a map's texels show along the edge: out"},
    {"volumes", 1, STEP, {"volumes", NULL}, CLAIM_LIGHTER, 200, "a map's texels show along the edge: in"},
    {"volumes", 2, STEP, UNSHADOWED, CLAIM_DARKER, 1000, "the fix: volumes counted in the stencil"},
    {"volumes", 6, STEP, STEP, CLAIM_MISCLASSIFIED, 8, "against the truth: exact"},
    {"volumes",
     7,
     STEP,
     {"volumes", "--mode zfail"},
     CLAIM_LIGHTER_ON_SHADOW,
     10000,
     "z-pass from the eye in "
     "shadow: shadows lost"},
    {"volumes", 7, STEP, {"volumes", "--mode zfail"}, CLAIM_DARKER_ON_LIT, 10000, "and shadow where none is"},
    {"volumes", 8, STEP, STEP, CLAIM_MISCLASSIFIED, 8, "the eye's count: exact"},
    {"volumes",
     9,
     STEP,
     {"volumes", "--mode zfail --no-depth-clamp"},
     CLAIM_DARKER_ON_LIT,
     10000,
     "the near plane cut: shadow where none is"},
    {"volumes",
     9,
     STEP,
     {"volumes", "--mode zfail --no-depth-clamp"},
     CLAIM_LIGHTER_ON_SHADOW,
     10000,
     "and shadow lost"},
    {"volumes", 10, STEP, STEP, CLAIM_MISCLASSIFIED, 8, "ZP+: exact"},
    {"volumes", 11, STEP, STEP, CLAIM_MISCLASSIFIED, 8, "z-fail: exact"},
    {"volumes", 12, STEP, {"volumes", ""}, CLAIM_LIGHTER_ON_SHADOW, 1000, "8 bits wrap: under 256 slabs, lit"},
    {"volumes", 14, STEP, {"shadowmap", NULL}, CLAIM_DARKER_ON_LIT, 4000, "cut-outs: the fence's shadow has no gaps"},
};
enum { CLAIM_COUNT = sizeof claims / sizeof *claims };

/* ---- pictures ---- */

/* The pictures rendered so far, by what decides them: the one-step
 * tour's text, less the caption and subject (steps showing the same
 * picture share it). */
static struct {
    char *key;
    char png[160], printed[160];
} pictures[CLAIM_MAX_PICTURES];
static int picture_count;

static char err[8192];

/* Step `step` of the tour as `v` says, alone in a tour of its own (its
 * scene by its absolute path, no caption); returns the picture's index,
 * rendered once a process. */
static int picture(const char *tour_name, int step, claim_variant v) {
    static tour t;
    char tour_path[PATH_MAX];
    snprintf(tour_path, sizeof tour_path, "assets/tours/%s.json", tour_name);
    assert_true(tour_load(&t, tour_path));
    assert_true(step >= 1 && step <= t.step_count);
    const tour_step *s = &t.steps[step - 1];
    cJSON *root = support_read_json(tour_path);
    cJSON *one = cJSON_Duplicate(cJSON_GetArrayItem(cJSON_GetObjectItem(root, "steps"), step - 1), true);
    assert_non_null(one);
    char scene[PATH_MAX];
    assert_non_null(realpath(s->scene, scene));
    static const char *const replaced[] = {"scene", "technique", "flags", "caption", "subject"};
    for (size_t k = 0; k < sizeof replaced / sizeof *replaced; k++)
        cJSON_DeleteItemFromObject(one, replaced[k]);
    cJSON_AddStringToObject(one, "scene", scene);
    cJSON_AddStringToObject(one, "technique", v.technique ? v.technique : s->technique);
    cJSON_AddStringToObject(one, "flags", v.flags ? v.flags : v.technique ? "" : s->flags);
    cJSON *steps = cJSON_CreateArray();
    cJSON_AddItemToArray(steps, one);
    cJSON_DeleteItemFromObject(root, "steps");
    cJSON_AddItemToObject(root, "steps", steps);
    cJSON_DeleteItemFromObject(root, "title");
    cJSON_AddStringToObject(root, "title", "a claim");
    char *key = cJSON_PrintUnformatted(root);
    assert_non_null(key);
    for (int i = 0; i < picture_count; i++)
        if (strcmp(pictures[i].key, key) == 0) {
            free(key);
            cJSON_Delete(root);
            return i;
        }
    assert_true(picture_count < CLAIM_MAX_PICTURES);
    int index = picture_count++;
    pictures[index].key = key;
    char name[64], path[256], stem[128], command[1024];
    snprintf(name, sizeof name, "tour_%d", index);
    support_write_json(root, CLAIM_OUT, name, path, sizeof path);
    cJSON_Delete(root);
    snprintf(stem, sizeof stem, CLAIM_OUT "/%s", name);
    snprintf(pictures[index].png, sizeof pictures[index].png, "%s-1.png", stem);
    snprintf(pictures[index].printed, sizeof pictures[index].printed, "%s.txt", stem);
    snprintf(command, sizeof command, "(%s --backend egl --size " CLAIM_SIZE " --tour %s --screenshot %s.png > %s)",
             support_program("shadows"), path, stem, pictures[index].printed);
    if (support_run(command, err, sizeof err) != 0)
        fail_msg("%s step %d: %s", tour_name, step, err);
    return index;
}

static unsigned char *picture_pixels(int index) {
    return support_read_png(pictures[index].png, CLAIM_WIDTH, CLAIM_HEIGHT);
}

static int level(const unsigned char *p, long i) {
    return p[i * CLAIM_CHANNELS] + p[i * CLAIM_CHANNELS + 1] + p[i * CLAIM_CHANNELS + 2];
}

/* ---- measures ---- */

/* Pixels plainly darker in a than in b; with lit (the unshadowed picture),
 * only those where `shadowed` is as lit as it (on_lit) or darker (not
 * on_lit). */
static long darker(const unsigned char *a, const unsigned char *b, const unsigned char *lit,
                   const unsigned char *shadowed, bool on_lit) {
    long count = 0;
    for (long i = 0; i < (long)CLAIM_WIDTH * CLAIM_HEIGHT; i++)
        if (level(b, i) - level(a, i) > CLAIM_DROP &&
            (!lit || (level(lit, i) - level(shadowed, i) <= CLAIM_DROP) == on_lit))
            count++;
    return count;
}

/* The texel-size heat map's pixels of a texel above about five pixels. */
static long warm(const unsigned char *p) {
    long count = 0;
    for (long i = 0; i < (long)CLAIM_WIDTH * CLAIM_HEIGHT; i++) {
        const unsigned char *c = p + i * CLAIM_CHANNELS;
        count += c[0] > c[1] + CLAIM_WARM_MARGIN && c[0] > c[2] + CLAIM_WARM_MARGIN;
    }
    return count;
}

/* A compare step's figure NAME ("misclassified", "false lit"), in percent,
 * and the pixels compared, from what it printed. */
static double compared_figure(int index, const char *name, long *compared) {
    FILE *f = fopen(pictures[index].printed, "r");
    assert_non_null(f);
    char text[4096];
    size_t length = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[length] = '\0';
    char pattern[64];
    snprintf(pattern, sizeof pattern, "%s ", name);
    const char *at = strstr(text, "compare: ");
    const char *figure = at ? strstr(at, pattern) : NULL, *pixels = at ? strstr(at, " pixels compared") : NULL;
    if (!figure || !pixels)
        fail_msg("%s: no compare figures in \"%s\"", pictures[index].png, text);
    while (pixels > at && pixels[-1] >= '0' && pixels[-1] <= '9')
        pixels--;
    *compared = strtol(pixels, NULL, 10);
    return strtod(figure + strlen(pattern), NULL);
}

static double measure(const claim *c) {
    int a = picture(c->tour, c->step, c->as), b = picture(c->tour, c->step, c->fix);
    long compared;
    switch (c->measure) {
    case CLAIM_MISCLASSIFIED: return compared_figure(a, "misclassified", &compared) / 100 * (double)compared;
    case CLAIM_FALSE_LIT: return compared_figure(a, "false lit", &compared);
    case CLAIM_LESS_FALSE_LIT:
        return compared_figure(b, "false lit", &compared) / compared_figure(a, "false lit", &compared);
    case CLAIM_LESS_FALSE_SHADOW:
        return compared_figure(b, "false shadow", &compared) / compared_figure(a, "false shadow", &compared);
    default: break;
    }
    unsigned char *pa = picture_pixels(a), *pb = picture_pixels(b), *lit = NULL;
    if (c->measure == CLAIM_DARKER_ON_LIT || c->measure == CLAIM_DARKER_ON_SHADOW ||
        c->measure == CLAIM_LIGHTER_ON_SHADOW)
        lit = picture_pixels(picture(c->tour, c->step, (claim_variant)UNSHADOWED));
    double value = 0;
    switch (c->measure) {
    case CLAIM_DARKER: value = (double)darker(pa, pb, NULL, NULL, false); break;
    case CLAIM_LIGHTER: value = (double)darker(pb, pa, NULL, NULL, false); break;
    case CLAIM_DARKER_ON_LIT: value = (double)darker(pa, pb, lit, pb, true); break;
    case CLAIM_DARKER_ON_SHADOW: value = (double)darker(pa, pb, lit, pb, false); break;
    case CLAIM_LIGHTER_ON_SHADOW: value = (double)darker(pb, pa, lit, pb, false); break;
    case CLAIM_WARMER: value = (double)(warm(pa) - warm(pb)); break;
    case CLAIM_WARM: value = (double)warm(pa); break;
    default: break;
    }
    free(pa);
    free(pb);
    free(lit);
    return value;
}

static void test_claim(void **state) {
    const claim *c = *state;
    double value = measure(c);
    bool at_most = c->measure == CLAIM_MISCLASSIFIED || c->measure == CLAIM_WARM;
    fprintf(stderr, "    %s %d: %s: %.4g (%s %.4g)\n", c->tour, c->step, c->what, value,
            at_most ? "at most" : "at least", c->amount);
    if (isnan(value) || (at_most ? value > c->amount : value < c->amount))
        fail_msg("%s step %d, \"%s\": measured %.4g, %s %.4g", c->tour, c->step, c->what, value,
                 at_most ? "at most" : "at least", c->amount);
}

int main(void) {
    static struct CMUnitTest tests[CLAIM_COUNT];
    static char names[CLAIM_COUNT][96];
    size_t count = 0;
    for (size_t i = 0; i < CLAIM_COUNT; i += (size_t)support_sweep_stride(), count++) {
        snprintf(names[count], sizeof names[count], "%s_%d_%zu", claims[i].tour, claims[i].step, i);
        tests[count] =
            (struct CMUnitTest){.name = names[count], .test_func = test_claim, .initial_state = (void *)&claims[i]};
    }
    return _cmocka_run_group_tests("tour claims", tests, count, NULL, NULL);
}
