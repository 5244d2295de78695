#include "registry.h"

extern const technique planar_technique;

const technique *const registry_techniques[] = {
    &planar_technique,
};
const int registry_technique_count = (int)(sizeof registry_techniques / sizeof *registry_techniques);
