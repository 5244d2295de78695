/* typo: the nearest of a list of names to one mistyped, for "did you
 * mean" in the errors of flags (flags.h) and of JSON files' keys
 * (json.h).
 *
 * Distance is the optimal string alignment distance: insertions,
 * deletions, substitutions and swaps of two neighbours, one edit each,
 * over the first TYPO_NAME_MAX characters of each name. A name is near
 * when at most TYPO_MAX_EDITS edits away, and fewer than half its
 * letters. */
#ifndef TYPO_H
#define TYPO_H

#define TYPO_NAME_MAX 64
#define TYPO_MAX_EDITS 2

int typo_distance(const char *a, const char *b);
/* Whether `distance` edits make a near miss of a name of `letters`
 * letters. */
int typo_near(int distance, int letters);
/* The name of `names` (NULL-terminated) nearest `typed`, or NULL where
 * none is a near miss. */
const char *typo_nearest(const char *typed, const char *const names[]);

#endif
