#include "frustum.h"

#include <math.h>

void frustum_plane_projection(const float plane[4], const float point[4], float out[4][4]) {
    float d = glm_vec4_dot((float *)plane, (float *)point);
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++)
            out[col][row] = (row == col ? d : 0.0f) - point[row] * plane[col];
}

void frustum_near_plane(const mat4 view_projection, float out[4]) {
    for (int k = 0; k < 4; k++)
        out[k] = view_projection[k][2] + view_projection[k][3];
}

void frustum_box_corners(const float lo[3], const float hi[3], float out[8][3]) {
    for (int c = 0; c < 8; c++)
        glm_vec3_copy((vec3){c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]}, out[c]);
}

bool frustum_box_ndc_bounds(const mat4 view_projection, const vec3 lo, const vec3 hi, vec2 ndc_lo, vec2 ndc_hi) {
    vec3 corners[8];
    frustum_box_corners(lo, hi, corners);
    ndc_lo[0] = ndc_lo[1] = INFINITY;
    ndc_hi[0] = ndc_hi[1] = -INFINITY;
    for (int c = 0; c < 8; c++) {
        vec4 clip;
        glm_mat4_mulv((vec4 *)view_projection, (vec4){corners[c][0], corners[c][1], corners[c][2], 1}, clip);
        if (clip[3] <= FRUSTUM_FLOAT_TOLERANCE)
            return false;
        for (int k = 0; k < 2; k++) {
            ndc_lo[k] = fminf(ndc_lo[k], clip[k] / clip[3]);
            ndc_hi[k] = fmaxf(ndc_hi[k], clip[k] / clip[3]);
        }
    }
    return true;
}

bool frustum_contains(const mat4 view_projection, const float p[3]) {
    vec4 clip, h = {p[0], p[1], p[2], 1};
    glm_mat4_mulv((vec4 *)view_projection, h, clip);
    float w = clip[3] * (1 + FRUSTUM_CLIP_TOLERANCE);
    return clip[3] > 0 && fabsf(clip[0]) <= w && fabsf(clip[1]) <= w && fabsf(clip[2]) <= w;
}

bool frustum_box_contains(const vec3 lo, const vec3 hi, const float p[3]) {
    float size = fmaxf(fmaxf(hi[0] - lo[0], hi[1] - lo[1]), hi[2] - lo[2]);
    for (int k = 0; k < 3; k++) {
        float margin = FRUSTUM_BOX_TOLERANCE * size + FRUSTUM_FLOAT_TOLERANCE * fmaxf(fabsf(lo[k]), fabsf(hi[k]));
        if (p[k] < lo[k] - margin || p[k] > hi[k] + margin)
            return false;
    }
    return true;
}

/* The frustum is where every clip plane's w + x, w - x, ... w - z is not
 * negative: each is linear in the world point, so a box whose eight
 * corners are all negative on one of them lies outside, whatever the sign
 * of w (behind the eye included). */
/* Plane k of the six in that order (left, right, bottom, top, near, far)
 * is tested where bit k of `planes` is set. */
static bool frustum_box_outside_planes(const mat4 view_projection, const vec3 lo, const vec3 hi, unsigned planes) {
    vec3 box[8];
    vec4 clip[8];
    frustum_box_corners(lo, hi, box);
    for (int c = 0; c < 8; c++)
        glm_mat4_mulv((vec4 *)view_projection, (vec4){box[c][0], box[c][1], box[c][2], 1}, clip[c]);
    for (int k = 0; k < 6; k++) {
        if (!(planes >> k & 1u))
            continue;
        float sign = k & 1 ? -1.0f : 1.0f;
        bool all_beyond = true;
        for (int c = 0; c < 8 && all_beyond; c++)
            all_beyond = clip[c][3] + sign * clip[c][k / 2] < -FRUSTUM_CLIP_TOLERANCE * fabsf(clip[c][3]);
        if (all_beyond)
            return true;
    }
    return false;
}

#define FRUSTUM_NEAR_PLANE_BIT (1u << 4)
#define FRUSTUM_ALL_PLANES 0x3fu

bool frustum_box_outside(const mat4 view_projection, const vec3 lo, const vec3 hi) {
    return frustum_box_outside_planes(view_projection, lo, hi, FRUSTUM_ALL_PLANES);
}

bool frustum_box_outside_sides_far(const mat4 view_projection, const vec3 lo, const vec3 hi) {
    return frustum_box_outside_planes(view_projection, lo, hi, FRUSTUM_ALL_PLANES & ~FRUSTUM_NEAR_PLANE_BIT);
}

/* Each clip plane w + x >= 0, w - x >= 0, ... is a world plane, the sum or
 * difference of two rows of the matrix: normalized, its value at the
 * centre is the centre's distance inside it. */
bool frustum_sphere_outside(const mat4 view_projection, const float center[3], float radius) {
    for (int k = 0; k < 6; k++) {
        float sign = k & 1 ? -1.0f : 1.0f;
        vec4 plane;
        for (int c = 0; c < 4; c++)
            plane[c] = view_projection[c][3] + sign * view_projection[c][k / 2];
        float length = glm_vec3_norm(plane);
        if (length > 0 && (glm_vec3_dot(plane, (float *)center) + plane[3]) / length < -radius)
            return true;
    }
    return false;
}

/* The vertices of the meeting of two convex bodies are the corners of each
 * inside the other and the crossings of each one's edges with the other's
 * faces. */
int frustum_box_part(const mat4 view_projection, const vec3 frustum[8], const vec3 lo, const vec3 hi, float (*out)[3],
                     int capacity) {
    vec3 box[8];
    frustum_box_corners(lo, hi, box);
    int n = 0;
    for (int c = 0; c < 8 && n < capacity; c++) {
        if (frustum_box_contains(lo, hi, frustum[c]))
            glm_vec3_copy((float *)frustum[c], out[n++]);
        if (n < capacity && frustum_contains(view_projection, box[c]))
            glm_vec3_copy(box[c], out[n++]);
    }
    for (int a = 0; a < 8; a++) {
        for (int bit = 1; bit < 8; bit <<= 1) {
            if (a & bit)
                continue;
            /* The frustum's edge a..a|bit across the box's six planes. */
            const float *fa = frustum[a], *fb = frustum[a | bit];
            for (int k = 0; k < 6 && n < capacity; k++) {
                float plane = k & 1 ? hi[k / 2] : lo[k / 2], da = fa[k / 2] - plane, db = fb[k / 2] - plane;
                if (da * db >= 0)
                    continue;
                glm_vec3_lerp((float *)fa, (float *)fb, da / (da - db), out[n]);
                out[n][k / 2] = plane;
                if (frustum_box_contains(lo, hi, out[n]))
                    n++;
            }
            /* The box's edge a..a|bit across the frustum's six planes:
             * clip x, y or z minus or plus w, linear along the edge. */
            vec4 ca, cb, ha = {box[a][0], box[a][1], box[a][2], 1},
                         hb = {box[a | bit][0], box[a | bit][1], box[a | bit][2], 1};
            glm_mat4_mulv((vec4 *)view_projection, ha, ca);
            glm_mat4_mulv((vec4 *)view_projection, hb, cb);
            for (int k = 0; k < 6 && n < capacity; k++) {
                float sign = k & 1 ? -1.0f : 1.0f, ga = ca[k / 2] * sign - ca[3], gb = cb[k / 2] * sign - cb[3];
                if (ga * gb >= 0)
                    continue;
                glm_vec3_lerp(box[a], box[a | bit], ga / (ga - gb), out[n]);
                if (frustum_contains(view_projection, out[n]))
                    n++;
            }
        }
    }
    return n;
}

void frustum_corners(const mat4 view_projection, float out[8][3]) {
    mat4 inverse;
    glm_mat4_inv((vec4 *)view_projection, inverse);
    for (int c = 0; c < 8; c++) {
        vec4 ndc = {c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1, 1}, world;
        glm_mat4_mulv(inverse, ndc, world);
        glm_vec3_scale(world, 1.0f / world[3], out[c]);
    }
}

void frustum_view_bounds(const mat4 view, const float (*points)[3], int n, float lo[3], float hi[3]) {
    glm_vec3_fill(lo, INFINITY);
    glm_vec3_fill(hi, -INFINITY);
    for (int i = 0; i < n; i++) {
        vec3 p;
        glm_mat4_mulv3((vec4 *)view, (float *)points[i], 1, p);
        glm_vec3_minv(lo, p, lo);
        glm_vec3_maxv(hi, p, hi);
    }
}

/* glm_lookat's matrix, from the direction itself: through a target at
 * eye + direction (glm_look) the direction would be rounded to the eye's
 * float spacing, 0.008 at 1e5 from the origin, an error of a degree for a
 * unit direction there. */
void frustum_look_along(const float eye[3], const float direction[3], mat4 view) {
    vec3 up = {0, 1, 0}, forward, side, true_up;
    if (fabsf(direction[1]) > FRUSTUM_NEARLY_VERTICAL)
        glm_vec3_copy((vec3){1, 0, 0}, up);
    glm_vec3_normalize_to((float *)direction, forward);
    glm_vec3_crossn(forward, up, side);
    glm_vec3_cross(side, forward, true_up);
    glm_mat4_identity(view);
    for (int k = 0; k < 3; k++) {
        view[k][0] = side[k];
        view[k][1] = true_up[k];
        view[k][2] = -forward[k];
    }
    view[3][0] = -glm_vec3_dot(side, (float *)eye);
    view[3][1] = -glm_vec3_dot(true_up, (float *)eye);
    view[3][2] = glm_vec3_dot(forward, (float *)eye);
}

/* Face 2k + 1 is the box's +axis-k face, 2k its -axis-k face. */
static void frustum_box_face(const vec3 lo, const vec3 hi, int face, vec4 out) {
    int axis = face / 2;
    float sign = face & 1 ? 1.0f : -1.0f;
    glm_vec4_zero(out);
    out[axis] = sign;
    out[3] = -sign * (face & 1 ? hi[axis] : lo[axis]);
}

int frustum_light_hull(const float light[4], const vec3 lo, const vec3 hi, vec4 planes[FRUSTUM_HULL_MAX_PLANES]) {
    enum { FACES = 6 };
    bool towards[FACES];
    int n = 0;
    for (int face = 0; face < FACES; face++) {
        vec4 plane;
        frustum_box_face(lo, hi, face, plane);
        /* Not glm_vec4_dot: the light need not be 16-byte aligned. */
        towards[face] = plane[0] * light[0] + plane[1] * light[1] + plane[2] * light[2] + plane[3] * light[3] > 0;
        if (!towards[face])
            glm_vec4_copy(plane, planes[n++]);
    }
    vec3 center;
    glm_vec3_center((float *)lo, (float *)hi, center);
    /* The edges along axis k, between the faces of the other two axes. */
    for (int k = 0; k < 3; k++) {
        int a = (k + 1) % 3, b = (k + 2) % 3;
        for (int side = 0; side < 4; side++) {
            int face_a = 2 * a + (side & 1), face_b = 2 * b + (side >> 1);
            if (towards[face_a] == towards[face_b])
                continue;
            vec3 start, end, edge, to_light, normal;
            start[k] = lo[k];
            end[k] = hi[k];
            start[a] = end[a] = side & 1 ? hi[a] : lo[a];
            start[b] = end[b] = side & 2 ? hi[b] : lo[b];
            glm_vec3_sub(end, start, edge);
            glm_vec3_scale(start, light[3], to_light);
            glm_vec3_sub((float *)light, to_light, to_light);
            glm_vec3_cross(edge, to_light, normal);
            float length = glm_vec3_norm(normal);
            if (!(length > 0))
                continue; /* the light on the edge's line: the faces bound the hull */
            glm_vec3_scale(normal, 1.0f / length, normal);
            float offset = -glm_vec3_dot(normal, start);
            if (glm_vec3_dot(normal, center) + offset > 0) {
                glm_vec3_negate(normal);
                offset = -offset;
            }
            glm_vec4(normal, offset, planes[n++]);
        }
    }
    return n;
}

bool frustum_planes_box_outside(const vec4 *planes, int count, const vec3 lo, const vec3 hi, float margin) {
    for (int i = 0; i < count; i++) {
        /* The corner farthest inside the plane: beyond it, all are. */
        float nearest = planes[i][3];
        for (int k = 0; k < 3; k++)
            nearest += planes[i][k] * (planes[i][k] > 0 ? lo[k] : hi[k]);
        if (nearest > margin)
            return true;
    }
    return false;
}
