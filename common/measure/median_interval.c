#include "median_interval.h"

#include <math.h>
#include <stdlib.h>

int median_interval_rank(int n, double confidence) {
    double tail = (1.0 - confidence) / 2, term = pow(0.5, n), below = 0;
    int k = 0;
    for (int j = 0; j < n / 2; j++) {
        below += term; /* P(Binomial(n, 1/2) <= j) */
        if (below > tail)
            break;
        k = j + 1;
        term *= (double)(n - j) / (double)(j + 1);
    }
    return k;
}

int median_interval_min_samples(double confidence) {
    int n = 1;
    while (median_interval_rank(n, confidence) == 0)
        n++;
    return n;
}

static int median_interval_compare(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

median_interval median_interval_of(double *samples, int n, double confidence) {
    qsort(samples, (size_t)n, sizeof *samples, median_interval_compare);
    int k = median_interval_rank(n, confidence);
    return (median_interval){.median = samples[(n + 1) / 2 - 1],
                             .low = k > 0 ? samples[k - 1] : 0,
                             .high = k > 0 ? samples[n - k] : 0,
                             .bounded = k > 0};
}
