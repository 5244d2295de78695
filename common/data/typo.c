#include "typo.h"

#include <string.h>

int typo_distance(const char *a, const char *b) {
    int n = (int)strnlen(a, TYPO_NAME_MAX), m = (int)strnlen(b, TYPO_NAME_MAX);
    int d[TYPO_NAME_MAX + 1][TYPO_NAME_MAX + 1];
    for (int i = 0; i <= n; i++)
        d[i][0] = i;
    for (int j = 0; j <= m; j++)
        d[0][j] = j;
    for (int i = 1; i <= n; i++) {
        for (int j = 1; j <= m; j++) {
            int best = d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
            best = d[i - 1][j] + 1 < best ? d[i - 1][j] + 1 : best;
            best = d[i][j - 1] + 1 < best ? d[i][j - 1] + 1 : best;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] && d[i - 2][j - 2] + 1 < best)
                best = d[i - 2][j - 2] + 1;
            d[i][j] = best;
        }
    }
    return d[n][m];
}

int typo_near(int distance, int letters) { return distance <= TYPO_MAX_EDITS && 2 * distance < letters; }

const char *typo_nearest(const char *typed, const char *const names[]) {
    const char *nearest = NULL;
    int best = TYPO_MAX_EDITS + 1, letters = (int)strlen(typed);
    for (int i = 0; names[i]; i++) {
        int distance = typo_distance(typed, names[i]);
        if (distance < best && typo_near(distance, letters)) {
            best = distance;
            nearest = names[i];
        }
    }
    return nearest;
}
