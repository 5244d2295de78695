#include "volume_bounds.h"
#include <glad/gl.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "volume_mesh.h"

void volume_bounds_light(const technique_frame *f, const skips_hull *hull, const int receivers_rect[4],
                         bool depth_bounds, volume_bounds *out) {
    *out = (volume_bounds){0};
    memcpy(out->rect, receivers_rect, sizeof out->rect);
    out->bounded = depth_bounds && !f->view->reversed_depth && f->skips->receiver_count < SKIPS_MAX_RECEIVER_POINTS &&
                   !hull->empty &&
                   volume_mesh_depth_bounds(f->view->view_projection, f->skips->receivers, f->skips->receiver_count,
                                            hull->lo, hull->hi, out->depth);
}

bool volume_bounds_caster(const technique_frame *f, const skips_hull *hull, int i, const volume_bounds *light,
                          volume_bounds *out) {
    light_mask_seen seen;
    if (!skips_caster_seen(f->skips, hull, i, &seen))
        return false;
    *out = *light;
    /* Clamped to the light's rectangle before they become pixels: "seen
     * everywhere" is infinite. */
    for (int k = 0; k < 2; k++) {
        float first = (float)light->rect[k], last = (float)(light->rect[k] + light->rect[2 + k]);
        int lo = (int)floorf(glm_clamp(seen.lo[k], first, last)), hi = (int)ceilf(glm_clamp(seen.hi[k], first, last));
        out->rect[k] = lo;
        out->rect[2 + k] = glm_max(hi - lo, 0);
    }
    out->depth[0] = fmaxf(light->depth[0], seen.lo[2]);
    out->depth[1] = fminf(light->depth[1], seen.hi[2]);
    f->skips->counts->casters_narrowed[hull->light] +=
        (int64_t)out->rect[2] * out->rect[3] < (int64_t)light->rect[2] * light->rect[3];
    return true;
}

void volume_bounds_use(const volume_bounds *b) {
    glScissor(b->rect[0], b->rect[1], b->rect[2], b->rect[3]);
    if (b->bounded)
        glDepthBoundsEXT(b->depth[0], glm_max(b->depth[0], b->depth[1]));
}
