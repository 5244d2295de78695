/* dump: what a program decided for each pixel of its final frame, in one
 * layout shared by every raster technique, the ray-traced reference and
 * shadowdiff. `--dump DIR` writes:
 *
 *   DIR/visibility.pfm  fraction of light K reaching the visible surface
 *                       (1 lit, 0 shadowed; a spot light reaches nothing
 *                       outside its outer cone); -1 where no surface.
 *                       Under translucent casters, the mean of
 *                       visibility_rgb's channels where they differ
 *   DIR/visibility_rgb.pfm  the same per channel (translucent casters
 *                       filter it: scene_object_transmittance); only for a
 *                       scene with translucent casters
 *   DIR/depth.pfm       distance from the eye to the visible surface; -1
 *   DIR/normal.pfm      world geometric (face) normal, unit, turned
 *                       towards the eye (the side that is seen); 0 if none
 *   DIR/position.pfm    position of the visible surface, as the scene's
 *                       positions, relative to its origin (scene.h,
 *                       "Large worlds"); 0 if none
 *   DIR/ids.pfm         index of the scene object seen; -1 if none
 *   DIR/color.png       the picture
 *   DIR/meta.json       {"width", "height", "light_index", "light":
 *                        [x,y,z,w] (w 0: direction towards the light;
 *                        a position is relative to the scene's origin),
 *                        "objects": [names by index], "camera":
 *                        {"position": [x,y,z], "target": [x,y,z], "up":
 *                        [x,y,z], "fov", "near", "far"} (the camera the
 *                        frame was rendered with, relative to the scene's
 *                        origin as position.pfm is; the projection's
 *                        aspect is width / height: what shimmer needs to
 *                        carry another frame's pixels into this one)}
 *
 * Arrays are top row first (PFM files store the bottom row first, as the
 * format says; dump_write and dump_read turn them). PFM: "Pf" one channel,
 * "PF" three, little-endian floats (scale -1).
 */
#ifndef DUMP_H
#define DUMP_H

#include <stdbool.h>
#include "scene.h"

typedef struct dump_frame {
    int width, height;
    int light_index;
    float light[4];
    scene_camera camera; /* reversed_depth is not stored: false when read */
    int object_count;
    char (*object_names)[SCENE_NAME_MAX];
    float *visibility;     /* width * height */
    float *visibility_rgb; /* 3 * width * height; NULL but for a scene with translucent casters */
    float *depth;          /* width * height */
    float *normal;         /* 3 * width * height */
    float *position;       /* 3 * width * height */
    float *ids;            /* width * height */
    unsigned char *color;  /* 4 * width * height, RGBA */
} dump_frame;

/* Allocates every array for a frame of scene `s` (its camera as it is
 * now) and light `light_index`, filled as "no surface": visibility, depth
 * and ids -1, the rest 0; visibility_rgb only where s has translucent
 * casters. */
bool dump_frame_create(dump_frame *d, int width, int height, const scene *s, int light_index);
void dump_frame_free(dump_frame *d);

/* Fills visibility_rgb, where the frame has it, with the visibility in
 * every channel: a producer that colours no shadow. */
void dump_frame_grey_rgb(dump_frame *d);

/* Creates DIR (and parents) if needed. Errors name the file.
 * visibility_rgb.pfm is read where the directory has it. */
bool dump_write(const dump_frame *d, const char *dir);
bool dump_read(dump_frame *d, const char *dir);

/* Single files, top row first; channels 1 or 3. */
bool dump_write_pfm(const char *path, int width, int height, int channels, const float *data);
/* Returns malloc'ed data, or NULL after printing why. */
float *dump_read_pfm(const char *path, int *width, int *height, int channels);

#endif
