/* registry: the table of every technique. Adding a technique to the
 * multi-technique window, the gallery and the benchmark is one line in
 * registry.c. */
#ifndef REGISTRY_H
#define REGISTRY_H

#include "technique.h"

extern const technique *const registry_techniques[];
extern const int registry_technique_count;
/* The technique marked cost_floor: the benchmark's floor, every ratio's
 * denominator. */
const technique *registry_cost_floor(void);

#endif
