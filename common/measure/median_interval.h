/* median_interval: how sure a median of timed samples is, from the samples
 * alone.
 *
 * Of n samples sorted, X(k) and X(n + 1 - k) (ranks from 1) bound their
 * population's median with confidence at least c when
 * P(Binomial(n, 1/2) < k) <= (1 - c) / 2: each sample falls either side
 * of the median with even odds, whatever the distribution (the binomial
 * or sign-test interval of a median; Hollander and Wolfe, "Nonparametric
 * Statistical Methods", the distribution-free interval for a median). The
 * benchmark takes it for a row's paired ratios to the cost floor.
 */
#ifndef MEDIAN_INTERVAL_H
#define MEDIAN_INTERVAL_H

#include <stdbool.h>

/* The largest such k for n samples at confidence c (0 < c < 1); 0 where n
 * is too small for any. */
int median_interval_rank(int n, double confidence);
/* The fewest samples that have an interval at confidence c. */
int median_interval_min_samples(double confidence);

typedef struct median_interval {
    double median; /* nearest rank */
    double low, high;
    bool bounded; /* n has an interval at the confidence; else low and high are 0 */
} median_interval;

/* Sorts samples[0..n) (n >= 1) in place and returns their median and its
 * interval at confidence c. */
median_interval median_interval_of(double *samples, int n, double confidence);

#endif
