/* volume_counter: a light's plan (volume_plan.h) counted per pixel, for
 * demos/volumes.c, into the stencil its lighting pass reads.
 *
 * The stencil in the plan's rectangle starts from 0, or from the number
 * of the plan's volumes that hold the eye (--mode eye-count,
 * volume_plan_eye_count), or (ZP+) from 0 plus each pixel's count on the
 * near plane (volume_near.h), drawn first, without depth clamp. Each needed caster's volume (volume_draw.h) is
 * drawn with colour and depth writes off, both faces in one pass, +1 for
 * front faces and -1 for back faces, in front of the surface (z-pass) or
 * behind it (z-fail), within its bounds. Into the 8-bit stencil, whose
 * counts wrap at 256, where the light's bound (volume_count_bound.h) says
 * no pixel's count reaches it; else into volume_wide.h's float target,
 * written back into the stencil after. With depth clamp (the default) far
 * caps at infinity stay in and faces before the near plane count at its
 * depth; without it the planes clip them, as the lecture's near-plane
 * failure needs.
 *
 *   volume_counter_init(&c, &draw, objects)   once
 *   per count, in this order:
 *     volume_counter_clear(&c, f, &plan)    the start, in the plan's rectangle
 *     volume_counter_begin(&c, f, &plan)    8 bits or float
 *     volume_counter_draw(&c, f, &plan)     every needed caster's volume
 *     volume_counter_end(&c, f)             a float count into the stencil
 *   volume_counter_destroy(&c)
 */
#ifndef VOLUME_COUNTER_H
#define VOLUME_COUNTER_H

#include <stdbool.h>

#include "volume_draw.h"
#include "volume_near.h"
#include "volume_plan.h"
#include "volume_wide.h"

/* Every bit of the 8-bit stencil: counts wrap at 256. */
#define VOLUME_COUNTER_STENCIL_MASK 0xff

/* --counter: float where the bound passes the stencil's, or one forced. */
typedef enum volume_counter_kind {
    VOLUME_COUNTER_AUTO,
    VOLUME_COUNTER_STENCIL,
    VOLUME_COUNTER_FLOAT
} volume_counter_kind;

/* The technique's settings a count follows. */
typedef struct volume_counter_settings {
    volume_plan_mode mode;
    volume_counter_kind kind;
    bool gpu_silhouettes; /* sides from the geometry shader */
    bool no_depth_clamp;
} volume_counter_settings;

typedef struct volume_counter {
    volume_draw *draw;
    volume_wide wide;
    volume_near near;                 /* ZP+'s count on the near plane */
    volume_counter_settings settings; /* the caller's, set before each frame's counts */
    bool counting_wide;               /* the count at hand is the float target's */
    int start;                        /* the count at hand's start */
    /* Of the last count whose plan is reported (light 0), for the HUD: */
    int zpass, zfail; /* casters counted each way */
    int near_counted; /* ZP+: of the z-pass ones, those counted from the near plane */
    int eye;          /* --mode eye-count: the volumes that hold the eye */
    int bound;        /* volume_wide_bound */
    bool bound_wide;  /* counted in the float target */
} volume_counter;

/* False after one line on stderr. */
bool volume_counter_init(volume_counter *c, volume_draw *draw, int object_count);
void volume_counter_destroy(volume_counter *c);
/* Scissor on, to the plan's rectangle, the stencil there set to the
 * start; stencil test on. */
void volume_counter_clear(volume_counter *c, const technique_frame *f, const volume_plan *plan);
void volume_counter_begin(volume_counter *c, const technique_frame *f, const volume_plan *plan);
void volume_counter_draw(volume_counter *c, const technique_frame *f, const volume_plan *plan);
void volume_counter_end(volume_counter *c, const technique_frame *f);
/* The HUD's words for the counter of the last reported count. */
int volume_counter_describe(const volume_counter *c, char *out, size_t size);

#endif
