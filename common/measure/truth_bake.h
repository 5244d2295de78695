/* truth_bake: the ray-traced truth of a view (raytrace.h), baked into a
 * few PNG images for a build that cannot trace: the web page's compare
 * mode (truth.h) finds the truth of the view it shows among those baked
 * natively (`--bake-truths DIR`; make web bakes every tour step shown in
 * compare mode, at the page's size).
 *
 * DIR/KEY/ holds one truth, KEY the 16 hex digits of a hash of its view:
 *   view.json     {"width", "height", "light_index", "light_samples",
 *                  "objects": [names], "view": [numbers]}: what it is
 *                  the truth of ("view": truth_bake_view's numbers)
 *   color.png     the truth's picture, as the dump's (dump.h)
 *   surface.png   R, G: the visibility times TRUTH_BAKE_VISIBILITY_ONE,
 *                 16 bits, high byte first (exact for any sample count
 *                 that divides it); B, A: the object's id plus one, 16
 *                 bits (0: no surface)
 *   depth.png     R, G, B: the depth's binary32 bits but the lowest 8,
 *                 high byte first; read back with the dropped bits' middle,
 *                 within 2^-16 of the depth, relative
 *   normal.png    R, G and B, A: the face normal in octahedral
 *                 coordinates (Meyer et al. 2010), 16 bits each
 * The position is not stored: read back, it is the eye plus the depth
 * along the ray through the pixel's centre, which is what shadowdiff
 * reads it for (whether the surface faces the light). So a baked truth
 * decides every pixel as the traced one, but for depths within 2^-16 of
 * shadowdiff's depth tolerance and surfaces within the normal's rounding
 * of edge-on to the light.
 *
 * A view matches a baked one when the size, light index, sample count and
 * object names are the same and every number of the view is within
 * TRUTH_BAKE_VIEW_TOLERANCE (relative above 1, absolute below): the same
 * camera computed by another libm matches, a camera moved by hand does
 * not.
 *
 * Errors are one line naming the file. */
#ifndef TRUTH_BAKE_H
#define TRUTH_BAKE_H

#include <stdbool.h>

#include "dump.h"
#include "raytrace.h"
#include "scene.h"

#define TRUTH_BAKE_VISIBILITY_ONE 32768
#define TRUTH_BAKE_VIEW_TOLERANCE 1e-6
/* The numbers of a view: the camera's position, target and up, the
 * origin and the ambient (3 each), the camera's fov, near, far and
 * reversed depth, the light count, and 17 per light (type, position,
 * direction, colour, intensity, the cone's angles, radius, range). */
#define TRUTH_BAKE_VIEW_MAX (20 + 17 * SCENE_MAX_LIGHTS)

/* What a truth is of. */
typedef struct truth_bake_view {
    int width, height, light_index, light_samples;
    float numbers[TRUTH_BAKE_VIEW_MAX];
    int count;
} truth_bake_view;

/* The view of light `light_index` of `s` traced at width x height with
 * `settings`' sample count. */
void truth_bake_view_of(const scene *s, int width, int height, int light_index, const raytrace_settings *settings,
                        truth_bake_view *out);
/* Writes `truth` (raytrace's frame of `s`) into DIR/KEY/, creating the
 * folders; prints the folder written. */
bool truth_bake_write(const char *dir, const dump_frame *truth, const scene *s, const raytrace_settings *settings);

typedef enum truth_bake_found {
    TRUTH_BAKE_FOUND,
    TRUTH_BAKE_NONE, /* no truth in DIR is of this view (nothing said) */
    TRUTH_BAKE_ERROR /* a baked truth of it could not be read (said) */
} truth_bake_found;

/* The truth baked in DIR of light `light_index` of `s` at width x height
 * into `out` (every array; its objects' names and camera `s`'s). */
truth_bake_found truth_bake_find(const char *dir, const scene *s, int width, int height, int light_index,
                                 const raytrace_settings *settings, dump_frame *out);

#endif
