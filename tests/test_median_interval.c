/* Tests of common/measure/median_interval.c, the interval the benchmark
 * puts round a row's ratio to the cost floor: the ranks of the published
 * tables, the smallest samples, the interval of known samples, its
 * coverage over many draws, and the floor check's rule on samples wholly
 * below 1. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdint.h>

#include "median_interval.h"

/* The benchmark's confidence (main_bench.c) and a textbook one. */
#define CONFIDENCE_BENCH 0.999
#define CONFIDENCE_95 0.95
/* Coverage: draws of COVERAGE_SAMPLES samples each; the share whose
 * interval at CONFIDENCE_95 holds the true median must be at least
 * COVERAGE_MIN (the interval's own coverage is above its confidence, less
 * the draws' spread). */
#define COVERAGE_DRAWS 4000
#define COVERAGE_SAMPLES 30
#define COVERAGE_MIN 0.94
#define MAX_SAMPLES 64

/* The ranks k of X(k) and X(n + 1 - k): the sign test's table (thirty
 * samples at CONFIDENCE_95: X(10) and X(21)), and the first n that has
 * any. */
static void test_ranks_match_the_tables(void **state) {
    (void)state;
    static const struct {
        int n;
        double confidence;
        int rank;
    } cases[] = {
        {5, CONFIDENCE_95, 0},     {6, CONFIDENCE_95, 1},     {10, CONFIDENCE_95, 2},
        {20, CONFIDENCE_95, 6},    {30, CONFIDENCE_95, 10},   {10, CONFIDENCE_BENCH, 0},
        {11, CONFIDENCE_BENCH, 1}, {20, CONFIDENCE_BENCH, 3}, {30, CONFIDENCE_BENCH, 6},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++)
        assert_int_equal(median_interval_rank(cases[i].n, cases[i].confidence), cases[i].rank);
    assert_int_equal(median_interval_min_samples(CONFIDENCE_95), 6);
    assert_int_equal(median_interval_min_samples(CONFIDENCE_BENCH), 11);
}

/* 30 samples 1..30 in any order: the median 15, the bench's interval
 * [X(6), X(25)]; too few samples: the median alone. */
static void test_interval_of_known_samples(void **state) {
    (void)state;
    double samples[30];
    for (int i = 0; i < 30; i++)
        samples[i] = (double)((i * 7) % 30 + 1); /* a permutation of 1..30 */
    median_interval m = median_interval_of(samples, 30, CONFIDENCE_BENCH);
    assert_true(m.bounded);
    assert_true(m.median == 15 && m.low == 6 && m.high == 25);
    double few[] = {3, 1, 2};
    m = median_interval_of(few, 3, CONFIDENCE_BENCH);
    assert_false(m.bounded);
    assert_true(m.median == 2);
}

/* A deterministic generator: uniform in [0, 1). */
static double next_uniform(uint64_t *state) {
    *state = *state * 6364136223846793005u + 1442695040888963407u;
    return (double)(*state >> 11) / (double)(1ull << 53);
}

/* Skewed samples (exponential, median ln 2, as frame times have a long
 * tail): the interval at CONFIDENCE_95 holds the true median in at least
 * COVERAGE_MIN of the draws. */
static void test_interval_covers_the_median(void **state) {
    (void)state;
    uint64_t seed = 1;
    int covered = 0;
    double samples[MAX_SAMPLES];
    for (int d = 0; d < COVERAGE_DRAWS; d++) {
        for (int i = 0; i < COVERAGE_SAMPLES; i++)
            samples[i] = -log(1 - next_uniform(&seed));
        median_interval m = median_interval_of(samples, COVERAGE_SAMPLES, CONFIDENCE_95);
        covered += m.low <= log(2) && log(2) <= m.high;
    }
    assert_true(covered >= COVERAGE_MIN * COVERAGE_DRAWS);
}

/* The floor check's rule: a row is below the floor when its whole
 * interval is under 1. Ratios all under 1 are; ratios round 1, with one
 * pair in three slower, are not. */
static void test_floor_rule(void **state) {
    (void)state;
    double below[30], round_one[30];
    for (int i = 0; i < 30; i++) {
        below[i] = 0.9 + 0.003 * i;
        round_one[i] = i % 3 == 0 ? 1.05 : 0.98;
    }
    median_interval m = median_interval_of(below, 30, CONFIDENCE_BENCH);
    assert_true(m.bounded && m.high < 1);
    m = median_interval_of(round_one, 30, CONFIDENCE_BENCH);
    assert_true(m.bounded && m.high >= 1);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ranks_match_the_tables),
        cmocka_unit_test(test_interval_of_known_samples),
        cmocka_unit_test(test_interval_covers_the_median),
        cmocka_unit_test(test_floor_rule),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
