/* wedge_area: how much of an area light's disk one silhouette edge uncovers
 * or covers, seen from a lit point, relative to the light's centre: the
 * per-pixel computation of penumbra wedges (Assarsson & Akenine-Moller,
 * "A geometry-based soft shadow volume algorithm using graphics hardware",
 * SIGGRAPH 2003). No GL: shaders/wedge_area.glsl is its twin, line for
 * line, and tests/test_wedge_area.c checks this C one.
 *
 * Seen from a point P, the silhouette of the casters (taken from the
 * light's centre) projects onto the plane through the centre c across the
 * line from P to c, where the light is a disk (area_light.h: the disk
 * turned towards P; a directional light's cap of directions becomes the
 * disk of radius tan(angular radius) on the plane one unit along the
 * direction). Fan the projected silhouette about c: each edge a -> b and c
 * make a triangle, and the triangles' signed areas within the disk sum to
 * the occluded area (the winding number of each point of the disk). The
 * triangle (c, a, b) within the disk is the sector of the disk from a to b
 * less the part of that sector beyond the line ab; the sectors sum to the
 * whole disk times the winding number at c, which is the centre's hard
 * shadow. So
 *
 *   visibility = (centre lit ? 1 : 0) + sum over edges of m * beyond / area
 *
 * m the edge's multiplicity (volume_mesh.h), beyond the signed area of the
 * disk within the sector a -> b and past the line ab: a circular segment
 * between the points where the edge enters and leaves the disk, or 0 when
 * the edge misses it; computed from the line's distance from the centre
 * and the ends' places along it, never from the ends themselves, which
 * lie far off the disk for an edge near the lit point. Exact where P sees the silhouette the centre sees
 * and every edge lies between P and the light.
 *
 * Orientation: an edge runs as a light-facing triangle (wound
 * counter-clockwise seen from the light) runs along it; on the plane, in
 * axes (t, b) with t x b along P -> c, such a triangle is
 * counter-clockwise and its winding number is positive (occluding).
 */
#ifndef WEDGE_AREA_H
#define WEDGE_AREA_H

/* Edges are clipped to the part farther from P than the light's distance
 * over this (nearer, projection blows up; behind P, nothing occludes),
 * and for a point light to the part nearer than the light. An int: the
 * shader gets it as a define. */
#define WEDGE_AREA_NEAR_RECIPROCAL 1000

/* The signed share of the unit disk (about the origin) within the sector
 * from a to b and past the line ab, over the disk's area (see top). */
float wedge_area_beyond(const float a[2], const float b[2]);
/* The change of light's visibility at p that edge a -> b (world) makes,
 * for multiplicity 1: `light` homogeneous (w 1 the centre, w 0 the
 * direction towards it), `size` the disk's radius, or for a directional
 * light tan(angular radius). */
float wedge_area_edge(const float p[3], const float light[4], float size, const float a[3], const float b[3]);

#endif
