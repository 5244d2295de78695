/* map: the uniform fit and the receiver points (see map.h).
 * Pure math on the scene: no GL. */
#include <math.h>

#include "frustum.h"
#include "map_internal.h"

/* The nearest near plane, as a fraction of far: a perspective map's depth
 * precision is spent near its near plane, and a caster touching the light
 * must not push that to 0. */
#define MAP_NEAR_RATIO 1e-3f
/* The fitted depth range is widened by this fraction of itself at each end
 * (plus float rounding at its distance), so the points it was fitted to
 * are not clipped by rounding. */
#define MAP_DEPTH_MARGIN 1e-3f
/* A spot's map is one degree wider than its cone each side, so bilinear
 * taps at the cone's edge read inside the map ... */
#define MAP_SPOT_MARGIN_DEG 1.0f
/* ... and at most this wide each side: a perspective map's texels grow as
 * 1 / cos^2 towards its edge and without bound at 90 degrees. */
#define MAP_SPOT_MAX_HALF_ANGLE_DEG 85.0f
#define MAP_CUBE_FACE_FOV_DEG 90.0f
/* A point light (or a spot wider than the limit above) whose visible
 * receivers lie in a cone of at most this half-angle gets one perspective
 * map around them instead of a cube: at 45 degrees (a cube face's, tan 45
 * = 1) its texels are nowhere larger than a face's, for one face's depth
 * pass instead of six, and far smaller where the receivers are far from
 * the light (a point light 1e6 away: a cube's texel spans 1000 units). */
#define MAP_RECEIVER_CONE_MAX_DEG 45.0f
/* That map is this fraction wider than the receivers' cone: room for the
 * kernel's taps at its edge (on a 256 map, 5 texels), in proportion,
 * since the cone may be a few microradians across. */
#define MAP_RECEIVER_CONE_MARGIN 0.02f

float map_nearest_caster(const scene *s, const mat4 view, const vec3 lo, const vec3 hi, bool orthographic) {
    float nearest = hi[2];
    for (int i = 0; i < s->object_count; i++) {
        vec3 corners[8], clo, chi, blo, bhi;
        if (!s->objects[i].casts)
            continue;
        scene_object_world_bounds(&s->objects[i], blo, bhi);
        frustum_box_corners(blo, bhi, corners);
        frustum_view_bounds(view, (const float(*)[3])corners, 8, clo, chi);
        /* A spot's caster counts if any of it is in front of the light. */
        bool overlaps =
            orthographic ? clo[0] <= hi[0] && chi[0] >= lo[0] && clo[1] <= hi[1] && chi[1] >= lo[1] : clo[2] < 0;
        if (overlaps)
            nearest = fmaxf(nearest, chi[2]);
    }
    return nearest;
}

void map_depth_range(float near_plane, float far_plane, float *near_out, float *far_out) {
    float margin = MAP_DEPTH_MARGIN * (far_plane - near_plane) + FRUSTUM_FLOAT_TOLERANCE * fabsf(far_plane);
    *far_out = far_plane + margin;
    *near_out = near_plane - margin;
}

void map_cascade_layer(map_light *m, int layer, const mat4 projection) {
    for (int k = 0; k < 3; k++) {
        m->cascade_scale[layer][k] = projection[k][k];
        m->cascade_offset[layer][k] = projection[3][k];
    }
    glm_mat4_mul((vec4 *)projection, m->cascade_view, m->layer_view_projection[layer]);
}

/* Directional: an orthographic box around the visible receivers, deepened
 * towards the light to every caster whose box overlaps them seen from the
 * light. Positional: a perspective map of the given half-angle looking
 * along `axis` (a spot's cone, or the cone around the receivers), from the
 * nearest caster in front of the light to the farthest receiver; its
 * texels measured as `texel_kind` says (the camera pass measures a
 * perspective texel along the light's own direction: a map looking
 * elsewhere is measured from its matrix, MAP_TEXEL_PROJECTIVE). The
 * depth range in view space runs along -z. */
static bool map_fit_2d(const scene *s, const scene_light *l, map_light *m, const float (*receivers)[3],
                       int receiver_count, const float axis[3], float half_angle, map_texel_kind texel_kind) {
    bool directional = l->type == SCENE_LIGHT_DIRECTIONAL;
    mat4 view, projection;
    vec3 lo, hi, eye;
    if (directional) {
        vec3 center = GLM_VEC3_ZERO_INIT;
        for (int i = 0; i < receiver_count; i++)
            glm_vec3_add(center, (float *)receivers[i], center);
        glm_vec3_scale(center, 1.0f / (float)receiver_count, center);
        glm_vec3_copy(center, eye); /* any point on the axis: depths are relative */
    } else {
        glm_vec3_copy((float *)l->position, eye);
    }
    frustum_look_along(eye, axis, view);
    frustum_view_bounds(view, receivers, receiver_count, lo, hi);
    map_depth_range(-map_nearest_caster(s, view, lo, hi, directional), -lo[2], &m->near_plane, &m->far_plane);
    m->orthographic = directional;
    if (directional) {
        glm_ortho(lo[0], hi[0], lo[1], hi[1], m->near_plane, m->far_plane, projection);
        m->texel_kind = MAP_TEXEL_ORTHOGRAPHIC;
        m->texel_scale = fmaxf(hi[0] - lo[0], hi[1] - lo[1]) / (float)m->size;
    } else {
        m->near_plane = fmaxf(m->near_plane, m->far_plane * MAP_NEAR_RATIO);
        glm_perspective(2 * half_angle, 1, m->near_plane, m->far_plane, projection);
        m->texel_kind = texel_kind;
        m->texel_scale = 2 * tanf(half_angle) / (float)m->size;
    }
    glm_mat4_mul(projection, view, m->layer_view_projection[0]);
    return m->far_plane > m->near_plane;
}

static float map_box_distance(const scene_object *o, const float p[3]) {
    vec3 lo, hi, d;
    scene_object_world_bounds(o, lo, hi);
    for (int k = 0; k < 3; k++)
        d[k] = fmaxf(fmaxf(lo[k] - p[k], 0), p[k] - hi[k]);
    return glm_vec3_norm(d);
}

/* Point: six faces from the nearest caster to the farthest receiver. */
static bool map_fit_cube(const scene *s, const scene_light *l, map_light *m, const float (*receivers)[3],
                         int receiver_count) {
    static const float axes[MAP_CUBE_FACES][3] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                                  {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    /* GL's cube faces look along each axis with these "up" vectors. */
    static const float ups[MAP_CUBE_FACES][3] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1},
                                                 {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    float far_plane = 0, nearest = INFINITY;
    for (int i = 0; i < receiver_count; i++)
        far_plane = fmaxf(far_plane, glm_vec3_distance((float *)l->position, (float *)receivers[i]));
    for (int i = 0; i < s->object_count; i++)
        if (s->objects[i].casts)
            nearest = fminf(nearest, map_box_distance(&s->objects[i], l->position));
    m->far_plane = far_plane * (1 + MAP_DEPTH_MARGIN);
    /* A face's near plane cuts along its axis, and a point's distance along
     * the axis of its face is at least its distance over sqrt(3). */
    m->near_plane =
        fmaxf(fminf(nearest, far_plane) * (1 - MAP_DEPTH_MARGIN) / sqrtf(3), m->far_plane * MAP_NEAR_RATIO);
    m->orthographic = false;
    mat4 projection;
    glm_perspective(glm_rad(MAP_CUBE_FACE_FOV_DEG), 1, m->near_plane, m->far_plane, projection);
    for (int face = 0; face < MAP_CUBE_FACES; face++) {
        vec3 target;
        mat4 view;
        glm_vec3_add((float *)l->position, (float *)axes[face], target);
        glm_lookat((float *)l->position, target, (float *)ups[face], view);
        glm_mat4_mul(projection, view, m->layer_view_projection[face]);
    }
    return m->far_plane > m->near_plane;
}

/* The cone from the light at `apex` around the receiver points: its axis
 * (their mean direction) and half-angle (the widest of them from it).
 * False where there is none (half-angle 0): a receiver at the apex, or
 * directions that cancel out. */
static bool map_receiver_cone(const float apex[3], const float (*receivers)[3], int receiver_count, vec3 axis,
                              float *half_angle) {
    vec3 sum = GLM_VEC3_ZERO_INIT, d;
    *half_angle = 0;
    for (int i = 0; i < receiver_count; i++) {
        glm_vec3_sub((float *)receivers[i], (float *)apex, d);
        float length = glm_vec3_norm(d);
        if (!(length > 0))
            return false;
        glm_vec3_muladds(d, 1 / length, sum);
    }
    if (!(glm_vec3_norm(sum) > 0))
        return false;
    glm_vec3_normalize_to(sum, axis);
    /* atan2 of sine and cosine, not acos of the cosine: a float cosine is
     * 1 below 3e-4 radians, the cone of receivers 1e5 away. */
    for (int i = 0; i < receiver_count; i++) {
        vec3 across;
        glm_vec3_sub((float *)receivers[i], (float *)apex, d);
        glm_vec3_cross(d, axis, across);
        *half_angle = fmaxf(*half_angle, atan2f(glm_vec3_norm(across), glm_vec3_dot(d, axis)));
    }
    return true;
}

bool map_fit_uniform(const scene *s, int light, map_light *m, const float (*receivers)[3], int receiver_count) {
    const scene_light *l = &s->lights[light];
    m->kind = MAP_2D;
    m->layer_count = 1;
    m->casters = NULL;
    if (l->type == SCENE_LIGHT_DIRECTIONAL)
        return map_fit_2d(s, l, m, receivers, receiver_count, l->direction, 0, MAP_TEXEL_ORTHOGRAPHIC);
    vec3 axis;
    float half_angle;
    bool around = map_receiver_cone(l->position, receivers, receiver_count, axis, &half_angle);
    half_angle *= 1 + MAP_RECEIVER_CONE_MARGIN;
    float spot_half_angle = glm_rad(l->outer_angle_deg) + glm_rad(MAP_SPOT_MARGIN_DEG);
    bool spot = l->type == SCENE_LIGHT_SPOT && spot_half_angle <= glm_rad(MAP_SPOT_MAX_HALF_ANGLE_DEG);
    /* A spot lights nothing outside its cone and the camera sees nothing
     * outside the receivers': its map covers the narrower of the two. The
     * receivers' is narrower for a spot far from what it lights (1e4 away,
     * a 38-degree cone's map spans 16000 units, its texels 4 at 4096, and
     * would lose the shadow of a sphere of radius 0.8:
     * tests/data/shadowmap_far_spot.json, test_shadowmap's stress
     * extremes). */
    if (spot && !(around && half_angle < spot_half_angle))
        return map_fit_2d(s, l, m, receivers, receiver_count, l->direction, spot_half_angle, MAP_TEXEL_PERSPECTIVE);
    /* That spot, a point light, or a spot too wide for one map: one map
     * around the receivers where they lie in a narrow enough cone, else a
     * cube (a spot lights nothing outside its cone: the cone decides
     * there). */
    if (around && (spot || half_angle <= glm_rad(MAP_RECEIVER_CONE_MAX_DEG)))
        return map_fit_2d(s, l, m, receivers, receiver_count, axis, half_angle, MAP_TEXEL_PROJECTIVE);
    m->kind = MAP_CUBE;
    m->layer_count = MAP_CUBE_FACES;
    return map_fit_cube(s, l, m, receivers, receiver_count);
}

bool map_fit_uniform_light(const technique_frame *f, int light, map_light *m, const float (*receivers)[3],
                           int receiver_count) {
    return map_fit_uniform(f->gpu->scene, light, m, receivers, receiver_count);
}
