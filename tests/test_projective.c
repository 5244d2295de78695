/* Projective-texture shadows against the ray-traced reference, one table
 * of cases: on the ground of the standard scenes (a spot, a point and a
 * directional light) within the goal, where no receiver lies between a
 * light and its casters; and the technique's limits, each a receiver of
 * the scene designed to show it (assets/scenes/projective_limits.json:
 * a shelf between the light and the ball, a table that casts and
 * receives over the floor; planar_stage's stage on its base), where the
 * bound must bite, and where the toggle that shows the limit leaves it.
 * Then the caster counts and the HUD's words for self-shadowing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dump.h"
#include "image.h"
#include "shadowdiff.h"
#include "support.h"

/* The goal on a receiver no other receiver stands in front of: at most
 * this share of its compared pixels misclassified. */
#define PROJECTIVE_MAX_MISCLASSIFIED_PERCENT 0.05
#define LIMITS "assets/scenes/projective_limits.json"

typedef struct projective_case {
    const char *name;
    const char *scene;
    const char *flags;
    const char *receiver; /* NULL: every object */
    bool exceeds;         /* a limit shown: the bound must bite */
} projective_case;

static const projective_case projective_cases[] = {
    {"simple_ground", "assets/scenes/simple.json", "", "ground", false},
    {"bunny_ground", "assets/scenes/bunny.json", "", "ground", false},
    {"teapot_ground", "assets/scenes/teapot.json", "", "ground", false},
    /* Every receiver: the bunny, which casts, shows none of its own
     * shadows. */
    {"bunny_all", "assets/scenes/bunny.json", "", NULL, true},
    /* The floor beside and under the table, the table in the image. */
    {"limits_floor", LIMITS, "", "floor", false},
    /* The shelf, nearer the light than the ball: lit with the near cut,
     * the ball's shadow cast backward onto it without. */
    {"limits_shelf", LIMITS, "", "shelf", false},
    {"limits_shelf_no_cut", LIMITS, "--no-near-cut", "shelf", true},
    /* The table casts and receives: off, no shadow of the ball on it;
     * on, its own silhouette over its lit top. Out of the image it takes
     * the ball's shadow right, and the floor beneath it misses the
     * table's. */
    {"limits_table", LIMITS, "", "table", true},
    {"limits_table_self", LIMITS, "--self-shadow on", "table", true},
    {"limits_table_split", LIMITS, "--no-receivers-cast", "table", false},
    {"limits_floor_split", LIMITS, "--no-receivers-cast", "floor", true},
    /* The stage lies between the sun and its base, a caster: the base's
     * image lands on it. */
    {"stage_floor", "assets/scenes/planar_stage.json", "", "floor", false},
    {"stage_stage", "assets/scenes/planar_stage.json", "", "stage", true},
};
enum { PROJECTIVE_CASE_COUNT = sizeof projective_cases / sizeof *projective_cases };

static void test_projective_case(void **state) {
    const projective_case *c = *state;
    long receiver_pixels;
    shadowdiff_result r = support_measure_receiver("projective", "projective", c->name, c->scene, "", c->flags,
                                                   c->receiver, &receiver_pixels);
    /* Most of the receiver is compared, so that a picture that lost it
     * cannot pass. */
    assert_true(receiver_pixels > 0);
    assert_true(r.compared * 2 > receiver_pixels);
    if (c->exceeds)
        assert_true(r.misclassified_percent > PROJECTIVE_MAX_MISCLASSIFIED_PERCENT);
    else
        assert_true(r.misclassified_percent <= PROJECTIVE_MAX_MISCLASSIFIED_PERCENT);
}

/* Receivers out of the image: simple's objects all receive, so nothing
 * is drawn into it; by default its three casters are. */
static void test_casters_counted(void **state) {
    (void)state;
    static const struct {
        const char *flags, *count;
    } cases[] = {
        {"", "casters drawn / culled per light: 0: 3/0"},
        {"--no-receivers-cast", "casters drawn / culled per light: 0: 0/0"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        const char *line =
            support_verbose_line("projective", "assets/scenes/simple.json", cases[i].flags, "[X] caster culling");
        if (!line || !strstr(line, cases[i].count))
            fail_msg("projective %s: \"%s\", expected \"%s\"", cases[i].flags, line ? line : "(no caster line)",
                     cases[i].count);
    }
}

/* The HUD's state line says what becomes of casters that receive, as
 * set. */
static void test_self_shadow_said(void **state) {
    (void)state;
    static const struct {
        const char *flags, *words;
    } cases[] = {
        {"", "casters show no shadow"},
        {"--self-shadow on", "casters darken their own lit side"},
        {"--no-receivers-cast", "receivers cast nothing"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        const char *line = support_verbose_line("projective", LIMITS, cases[i].flags, "light 0: ");
        if (!line || !strstr(line, cases[i].words))
            fail_msg("projective %s: \"%s\", expected \"%s\"", cases[i].flags, line ? line : "(no state line)",
                     cases[i].words);
    }
}

int main(void) {
    static const struct CMUnitTest units[] = {
        cmocka_unit_test(test_casters_counted),
        cmocka_unit_test(test_self_shadow_said),
    };
    enum { UNIT_COUNT = sizeof units / sizeof *units };
    static struct CMUnitTest tests[UNIT_COUNT + PROJECTIVE_CASE_COUNT];
    size_t count = 0;
    for (size_t i = 0; i < UNIT_COUNT; i++)
        tests[count++] = units[i];
    for (size_t i = 0; i < PROJECTIVE_CASE_COUNT; i++)
        tests[count++] = (struct CMUnitTest){.name = projective_cases[i].name,
                                             .test_func = test_projective_case,
                                             .initial_state = (void *)&projective_cases[i]};
    return _cmocka_run_group_tests("projective", tests, count, NULL, NULL);
}
