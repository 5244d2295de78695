#include "registry.h"

extern const technique unshadowed_technique;
extern const technique planar_technique;
extern const technique projective_technique;
extern const technique shadowmap_technique;
extern const technique psm_technique;
extern const technique cascades_technique;
extern const technique volumes_technique;
extern const technique hybrid_technique;

/* Keys 1-9 in the window follow this order; the benchmark's cost floor is
 * the technique marked cost_floor (unshadowed). */
const technique *const registry_techniques[] = {
    &planar_technique,   &projective_technique, &shadowmap_technique,  &psm_technique,
    &cascades_technique, &volumes_technique,    &unshadowed_technique, &hybrid_technique,
};
const int registry_technique_count = (int)(sizeof registry_techniques / sizeof *registry_techniques);

const technique *registry_cost_floor(void) {
    for (int t = 0; t < registry_technique_count; t++)
        if (registry_techniques[t]->cost_floor)
            return registry_techniques[t];
    return NULL;
}
