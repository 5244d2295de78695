/* frustum: boxes and frusta in world space, the geometry that fitting a
 * shadow map, choosing a volume's mode and culling all need. Pure math on
 * cglm types: no GL, no scene.
 *
 * A frustum is given by its view-projection matrix (world -> clip); its
 * corners are the clip cube's mapped back, numbered as a box's corners
 * are: bit 0 picks x, bit 1 y, bit 2 z from hi (for a frustum: +1 in
 * NDC), so corners 0-3 lie on the near plane.
 */
#ifndef FRUSTUM_H
#define FRUSTUM_H

#include <cglm/cglm.h>
#include <stdbool.h>

/* A point on a clip plane counts as inside: |x|, |y|, |z| <= w (1 + this). */
#define FRUSTUM_CLIP_TOLERANCE 1e-4f
/* A point counts as inside a box within this fraction of its largest side
 * (a plane's box is flat: its own thickness is no measure), plus float
 * rounding at the box's coordinates. */
#define FRUSTUM_BOX_TOLERANCE 1e-4f
#define FRUSTUM_FLOAT_TOLERANCE 1e-6f
/* |direction.y| above this: "up" for a view along it is +x instead of +y. */
#define FRUSTUM_NEARLY_VERTICAL 0.99f

/* The central projection from `point` (homogeneous; w = 0: a direction,
 * a parallel projection) onto `plane` (a x + b y + c z + d = 0), as a
 * matrix, column-major: S = (plane . point) I - point plane^T. S v lies on
 * the plane and on the line through v and the point; its w, (plane .
 * point) v.w - point.w (plane . v), has the sign of (plane . point) while
 * v lies nearer the plane than the point, on the point's side or beyond
 * the plane. Blinn's planar shadows (1988), and ZP+'s near-plane count. */
void frustum_plane_projection(const float plane[4], const float point[4], float out[4][4]);
/* The camera's near plane of `view_projection` (world; GL's clip z >= -w),
 * positive in front of it: the plane row 2 + row 3, not normalised. */
void frustum_near_plane(const mat4 view_projection, float out[4]);
/* Corners of the box lo..hi. */
void frustum_box_corners(const float lo[3], const float hi[3], float out[8][3]);
/* The box lo..hi's bounds on screen: the least and greatest NDC x and y of
 * its corners under `view_projection`, unclamped. False where a corner
 * lies at or behind the eye's plane (clip w <= FRUSTUM_FLOAT_TOLERANCE):
 * the box may then reach any pixel. */
bool frustum_box_ndc_bounds(const mat4 view_projection, const vec3 lo, const vec3 hi, vec2 ndc_lo, vec2 ndc_hi);
/* Corners of the frustum of `view_projection`. A camera's are in its
 * camera_view (camera.h): inverting a float projection loses a far plane
 * more than about 1e7 nears away. */
void frustum_corners(const mat4 view_projection, float out[8][3]);
bool frustum_contains(const mat4 view_projection, const float p[3]);
bool frustum_box_contains(const vec3 lo, const vec3 hi, const float p[3]);
/* The corners of the part of the box lo..hi inside the frustum (whose
 * corners are `corners`), at most `capacity` of them; returns how many. */
int frustum_box_part(const mat4 view_projection, const vec3 corners[8], const vec3 lo, const vec3 hi, float (*out)[3],
                     int capacity);
/* The box lo..hi lies wholly outside the frustum: all its corners beyond
 * one clip plane (by more than FRUSTUM_CLIP_TOLERANCE). Conservative, as
 * culling needs: a box that meets the frustum is never outside, though a
 * box beside a frustum's corner may not be found outside. */
bool frustum_box_outside(const mat4 view_projection, const vec3 lo, const vec3 hi);
/* The same without the near plane (w + z >= 0): for a view that draws
 * what lies before it at its near depth (GL_DEPTH_CLAMP). */
bool frustum_box_outside_sides_far(const mat4 view_projection, const vec3 lo, const vec3 hi);
/* The convex hull of a light and the box lo..hi, as planes (xyz: the unit
 * outward normal, w: the offset; a point p is inside where n.p + w <= 0),
 * at most FRUSTUM_HULL_MAX_PLANES of them; returns how many. The light is
 * homogeneous (scene_light_homogeneous): w = 1 a point, w = 0 a point at
 * infinity towards xyz, and the hull is then the box swept towards it.
 * The planes are the box's faces that turn away from the light and, through
 * each edge between a face turned towards it and one turned away, the
 * plane through that edge and the light. A caster wholly outside the hull
 * of a light and the receivers it might shadow cannot shadow them: every
 * segment from the light to a receiver point lies inside (Doom 3's caster
 * culling; Lengyel, "The mechanics of robust stencil shadows", 2002). */
#define FRUSTUM_HULL_MAX_PLANES 18
int frustum_light_hull(const float light[4], const vec3 lo, const vec3 hi, vec4 planes[FRUSTUM_HULL_MAX_PLANES]);
/* The box lo..hi lies wholly outside the convex region of `planes`: all
 * its corners beyond one plane by more than `margin` (world units).
 * Conservative like frustum_box_outside. */
bool frustum_planes_box_outside(const vec4 *planes, int count, const vec3 lo, const vec3 hi, float margin);
/* The sphere lies wholly outside the frustum: beyond one of its planes by
 * more than its radius. Conservative, as frustum_box_outside. */
bool frustum_sphere_outside(const mat4 view_projection, const float center[3], float radius);
/* Bounds of points in the space of `view`. */
void frustum_view_bounds(const mat4 view, const float (*points)[3], int n, float lo[3], float hi[3]);
/* A view from `eye` looking along `direction` (any up that is not along it). */
void frustum_look_along(const float eye[3], const float direction[3], mat4 view);

#endif
