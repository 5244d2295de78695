/* volume_draw: a scene's shadow volumes drawn, one caster for one light at
 * a time, for demos/volumes.c, which sets the stencil and depth state that
 * counts them.
 *
 * Per caster, built once per scene: its welded edge table (the CPU
 * volumes', demos/lib/volume_mesh.h) and its adjacency on the GPU
 * (demos/lib/volume_silhouette.h). A caster's sides come from the
 * geometry shader (--silhouette gpu) or from the CPU; its caps, which
 * z-fail needs, always from the CPU (see volume_silhouette.h for why).
 *
 * The CPU volumes are kept, one GPU buffer per light and one per point of
 * an area light's that is sampled (volume_cache), each caster's sides and
 * caps apart (the camera picks z-pass or z-fail each frame), built when a
 * caster is first drawn after volume_draw_forget (the light moved) and
 * drawn from there until the next; past
 * VOLUME_DRAW_CACHE_MAX_BYTES in all, the rest is built every time and
 * streamed. They are swept to infinity, or trimmed past a reach
 * (volume_draw_reach; volume_mesh_trim_for): the scene's receivers, not
 * only the visible ones, as the kept volumes outlive the camera.
 *
 * Every CPU volume is drawn by one program (volume.vert, volume.frag: the
 * depth pre-pass's vertex path; colour u_color for the overlays), whose
 * vertices are homogeneous, in the object's space. While `wide` is set
 * (volume_wide.h) the count draws with the CPU and GPU programs' wide
 * twins instead, which add a face's sign (volume_draw_wide_sign) to a
 * float target.
 */
#ifndef VOLUME_DRAW_H
#define VOLUME_DRAW_H

#include <stdbool.h>
#include <stddef.h>

#include "technique.h"
#include "volume_cache.h"
#include "volume_mesh.h"
#include "volume_silhouette.h"

/* The most the kept volumes take on the GPU, all lights together: far
 * more than the standard scenes' volumes need, caps and all (the HUD's
 * "all lights' kept" gives their size), so that only a scene far larger
 * streams its volumes. */
#define VOLUME_DRAW_MIB ((size_t)1 << 20)
#define VOLUME_DRAW_CACHE_MAX_BYTES (256 * VOLUME_DRAW_MIB)

/* Zero is an unmade one. */
typedef struct volume_draw {
    render_program cpu; /* the CPU volumes, and the overlays */
    int cpu_color;      /* its u_color */
    volume_silhouette gpu;
    render_program cpu_wide; /* the twins that count into a float target */
    int cpu_wide_color;
    volume_silhouette gpu_wide;
    bool wide;                         /* the count draws with the twins */
    float wide_sign;                   /* the twins' u_color.r as last set */
    mesh_edges *edges;                 /* per object; casters only */
    volume_silhouette_mesh *adjacency; /* per object; casters only */
    int object_count;
    unsigned stream_vao, stream_buffer; /* what is not kept */
    size_t stream_capacity;
    volume_mesh geometry; /* the caster at hand's CPU volume */
    /* VOLUME_DRAW_CACHES per light (volume_draw_cache), each made when
     * first kept in */
    volume_cache *caches;
    size_t cache_bytes;                     /* all caches' buffers */
    float receivers_lo[3], receivers_hi[3]; /* every receiver's box together; empty when none */
    /* The reach of the volumes built next, when they are trimmed. */
    bool reach_on;
    float reach_lo[3], reach_hi[3];
    int built, reused; /* CPU parts built, and drawn as kept: the HUD's (the caller zeroes them) */
} volume_draw;

/* False after printing why. */
bool volume_draw_init(volume_draw *d, const render_scene *gpu);
void volume_draw_destroy(volume_draw *d);
/* Drops light l's kept volumes, from its centre and its points. */
void volume_draw_forget(volume_draw *d, int l);
/* Frees the volumes kept for light l's points, and their buffers (its
 * area is sampled at other points now). */
void volume_draw_free_points(volume_draw *d, int l);
/* The volumes built from now on end past the light's reach (every
 * receiver, clipped to its range) when `trim`, else at infinity. */
void volume_draw_reach(volume_draw *d, const scene_light *light, bool trim);

/* The caches of one light: its centre's, then one per point of its area
 * (shading_sample_area_light's k). */
#define VOLUME_DRAW_CACHES (1 + SOFT_VISIBILITY_MAX_SAMPLES)
/* The cache that keeps light l's volumes from its centre
 * (SHADING_LIGHT_CENTRE) or from point k of its area. */
int volume_draw_cache(int l, int k);

/* The sign a front face adds while `wide` (1: z-pass; -1: z-fail, whose
 * faces count behind the surface), a back face the opposite. */
void volume_draw_wide_sign(volume_draw *d, float sign);

/* Caster i's volume for a light at `light` (homogeneous, world): its
 * sides, from the geometry shader when `gpu`, and for z-fail its caps
 * after them; `cache` (volume_draw_cache) keeps its CPU parts. */
void volume_draw_caster(volume_draw *d, const technique_frame *f, int cache, int i, const float light[4], bool gpu,
                        bool zfail);
/* Caster i's part for the light into d->geometry, with the CPU program
 * bound for it and the object's model matrix set; false after printing
 * why. */
bool volume_draw_build(volume_draw *d, const technique_frame *f, int i, const float light[4], volume_mesh_parts part);
/* Homogeneous vertices, with the CPU program's uniforms as they are, as
 * `primitive` (a GLenum), through the stream buffer. */
void volume_draw_stream(volume_draw *d, const float (*vertices)[4], size_t count, unsigned primitive);

#endif
