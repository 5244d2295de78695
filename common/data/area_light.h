/* area_light: points on an area light, taken one way by the ray-traced
 * reference and by every raster technique that samples the light, so
 * that a technique averaging hard shadows from enough of them converges
 * to exactly what the reference computes. No GL.
 *
 * A light with a radius (scene.h) is a disk facing the point it lights,
 * along `axis` (the unit vector from that point towards the light's
 * centre): of that radius about a point or spot light's position, or, for
 * a directional light, the cap of directions within its angular radius.
 * Sample k of n is the jittered centre of the k-th of n equal-area cells
 * of the unit square, carried to the disk by Shirley and Chiu's
 * concentric map ("A Low Distortion Map Between Disk and Square", JGT
 * 2(3), 1997), which keeps equal areas and compact strata, so every n
 * stratifies without weighting.
 *
 *   area_light_frame frame;
 *   area_light_frame_for(light, centre, axis, &frame);
 *   for k in 0..n-1:
 *     uint32_t jitter = area_light_hash(seed + k);
 *     area_light_sample(&frame, k, n, jitter, point);   homogeneous
 */
#ifndef AREA_LIGHT_H
#define AREA_LIGHT_H

#include <stdint.h>

#include "scene.h"

/* PCG hash: Jarzynski and Olano, "Hash Functions for GPU Rendering",
 * JCGT 9(3), 2020; good avalanche at the cost of a few multiplies. */
uint32_t area_light_hash(uint32_t v);
/* [0, 1) from the top 24 bits of a hash, exact in float. */
float area_light_unit(uint32_t h);

/* Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 6(1),
 * 2017: t and b complete the unit vector n without a branch on its axis. */
void area_light_basis(const float n[3], float t[3], float b[3]);
/* Sample k of n on the unit disk, jittered by (u, v) in [0, 1)^2 within
 * its cell (see top). */
void area_light_disk_sample(int k, int n, float jitter_u, float jitter_v, float disk[2]);

/* The disk of one light seen along one axis. */
typedef struct area_light_frame {
    float centre[4]; /* homogeneous: w 1 a position, 0 the direction towards the light */
    float axis[3], tangent[3], bitangent[3];
    float radius; /* world units; directional: unused */
    float cap;    /* directional: 1 - cos(angular radius), kept accurate for a small sun */
} area_light_frame;

/* `centre`: the light's homogeneous position (scene_light_homogeneous,
 * possibly rebased), `axis`: unit, from the lit point towards the light
 * (for a directional light, towards it). */
void area_light_frame_for(const scene_light *light, const float centre[4], const float axis[3],
                          area_light_frame *frame);
/* Sample k of n (see top) as a homogeneous point, or for a directional
 * light the unit direction towards it (w 0); `jitter` a hash of the
 * caller's (area_light_hash), its two units the cell's jitter. */
void area_light_sample(const area_light_frame *frame, int k, int n, uint32_t jitter, float out[4]);
/* For techniques that take one set of points for every pixel (a disk
 * turned towards one pixel is turned away from the others): sample k of
 * n of a point or spot light lifted off its disk into the ball of its
 * radius, along the axis by sqrt(1 - rho^2) sin(pi (w - 1/2)), w a third
 * unit of the jitter, which gives the ball the density 1 / sqrt(1 - r^2)
 * (r over the radius): the one whose projection along every direction is
 * the uniform disk (its Abel transform is constant), so that every pixel
 * sees the reference's disk, turned towards it. Along the axis the points
 * keep the disk's strata; w is the jitter's hash, unstratified (strata of
 * w in any fixed order correlate with the disk's rows and measured
 * worse). A directional light's disk is the same from
 * every pixel: area_light_sample's. */
void area_light_sample_ball(const area_light_frame *frame, int k, int n, uint32_t jitter, float out[4]);

/* The sample taken j-th of n by a technique that adds them over frames:
 * a permutation of 0..n-1 whose every first 4^i samples fall one in each
 * cell of a 2^i x 2^i grid over the square, so that a partial sum is
 * already spread over the whole disk (n a power of 4, a square of cells:
 * each cell's row and column are the bit-reversed halves of j's Morton
 * code; any other n: j itself). */
int area_light_progressive_index(int j, int n);

#endif
