/* main of build/stress: `make stress`, adversarial scenes run through every
 * technique and the reference, as subprocesses that may crash or hang.
 *
 * One table of cases (stress_cases): each a name, a base scene (a box and a
 * sphere on a ground plane under a spot, point or directional light) and
 * the axis it pushes, with its value: the scene's scale, its distance from
 * the origin, the near/far ratio, where the light is (inside, on and just
 * above a caster, grazing, from below, very far, at the camera), the spot's
 * cone, where the camera is (inside a caster, on a shadow volume's plane),
 * huge and tiny primitives, needle and sliver triangles (a small OBJ beside
 * the scene), coplanar casters, mirrored transforms. Each case's scene is
 * written to OUT/scenes/CASE.json, ray traced by `raytrace --dump`, rendered
 * by each technique configuration of stress_configs with `--dump`, and the
 * pair compared by `shadowdiff --json` (planar on its receiver, the ground).
 * --quick runs the few cases marked quick, which pass (make test runs
 * them).
 *
 * Every row gets one verdict (stress_verdict, below, lists them).
 * The run writes OUT/table.csv and OUT/table.md (scene, technique, config,
 * bound, figures: misclassified %, MAE, each of shadowdiff's classes' MAE
 * ("none" where the truth has no pixel of it) and the pixels compared;
 * verdict, seconds, first stderr line) and prints a summary;
 * it exits 0 only if every row is pass, refused or unmeasured. What a row
 * leaves in OUT/runs/CASE/ROW/ (command.txt, its stderr, dump, shadowdiff's
 * output and heat map) is removed when the row is one of those three, kept
 * otherwise.
 *
 * Subprocesses run in stages (every reference, then every technique, then
 * every comparison), up to --jobs at a time, each in its own process group
 * with stdin from /dev/null: a run past its time has its whole group
 * killed, and every child is reaped before the stage ends, so nothing
 * outlives the run (Ctrl-C too). Plain POSIX: fork, exec, waitpid.
 */
#include <cJSON.h>
#include <errno.h>
#include <fcntl.h>
#include <fnmatch.h>
#include <ftw.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "flags.h"
#include "path.h"
#include "shadowdiff.h"

#define STRESS_EXIT_FAILED 1
#define STRESS_EXIT_INTERRUPTED 130
#define STRESS_DEFAULT_OUT "out/stress"
#define STRESS_DEFAULT_BIN "build"
#define STRESS_DEFAULT_WIDTH 320
#define STRESS_DEFAULT_HEIGHT 180
#define STRESS_DEFAULT_TIMEOUT 60
#define STRESS_MAX_TIMEOUT 3600
#define STRESS_MAX_JOBS 64
#define STRESS_PATH_MAX 1024
#define STRESS_MAX_ARGS 32
#define STRESS_MAX_FLAGS 4
#define STRESS_LINE_MAX 240
/* Of a stderr file, what is read to classify the run: a sanitizer report
 * or a GL error starts early. */
#define STRESS_STDERR_READ (1 << 20)
#define STRESS_JSON_READ (1 << 16)
#define STRESS_KEY_MAX 64
#define STRESS_MAE_DECIMALS 5     /* the whole MAE's and each class's */
#define STRESS_POLL_NS 5000000L   /* between looks at the running children */
#define STRESS_EXEC_FAILED 127    /* the shell's status for "cannot run" */
#define STRESS_SIGNAL_STATUS 128  /* at or above: a shell's death by signal */
#define STRESS_NOTHING_COMPARED 4 /* shadowdiff's exit statuses */
#define STRESS_NOT_FINITE 5

/* Each technique's bound: misclassified, in percent of compared pixels. */
#define STRESS_BOUND_VOLUMES 0.01
#define STRESS_BOUND_MAPS 0.5
#define STRESS_BOUND_PLANAR 0.05

static volatile sig_atomic_t stress_interrupted;

/* ---- the scenes ---- */

typedef enum stress_light_kind { STRESS_SPOT, STRESS_POINT, STRESS_DIRECTIONAL } stress_light_kind;
static const char *const stress_light_names[] = {"spot", "point", "directional"};

typedef enum stress_mesh { STRESS_MESH_PLANE, STRESS_MESH_BOX, STRESS_MESH_SPHERE, STRESS_MESH_MODEL } stress_mesh;

/* The OBJ written beside a scene for its STRESS_MESH_MODEL object. */
typedef enum stress_model {
    STRESS_NO_MODEL,
    STRESS_BLADES,  /* upright needle triangles, one-sided: an open mesh */
    STRESS_SPIKES,  /* needle tetrahedra: closed meshes */
    STRESS_SLIVERS, /* a square panel whose edges are sliver triangles */
} stress_model;

typedef struct stress_object {
    const char *name;
    stress_mesh mesh;
    double size[3]; /* box: x y z; plane: x, z in [0], [2]; sphere: radius in [0] */
    double translate[3], rotate[3], scale[3];
    bool casts;
} stress_object;

#define STRESS_MAX_OBJECTS 6
enum { STRESS_GROUND, STRESS_BOX, STRESS_SPHERE, STRESS_BASE_OBJECTS };

typedef struct stress_scene {
    double eye[3], target[3], up[3], fov, near, far;
    stress_light_kind light;
    double light_position[3], light_direction[3], inner, outer;
    stress_object objects[STRESS_MAX_OBJECTS];
    int object_count;
    stress_model model;
    double model_size; /* blades' and spikes' width, the slivers' height */
} stress_scene;

/* The base: a box and a sphere on a 20 x 20 ground, seen from above at
 * 45 degrees; a light of the case's kind from the upper left. */
static const stress_scene stress_base = {
    .eye = {7, 6, 9},
    .target = {0, 0.5, 0},
    .up = {0, 1, 0},
    .fov = 45,
    .near = 0.1,
    .far = 100,
    .light_position = {-4, 9, 5}, /* the spot's; aimed at the origin */
    .inner = 28,
    .outer = 38,
    .objects = {{"ground", STRESS_MESH_PLANE, {20, 0, 20}, {0, 0, 0}, {0, 0, 0}, {1, 1, 1}, false},
                {"box", STRESS_MESH_BOX, {1.6, 1.6, 1.6}, {-1.2, 0.8, 0.3}, {0, 25, 0}, {1, 1, 1}, true},
                {"sphere", STRESS_MESH_SPHERE, {0.8, 0, 0}, {1.4, 0.8, 1.0}, {0, 0, 0}, {1, 1, 1}, true}},
    .object_count = STRESS_BASE_OBJECTS,
};
static const double stress_base_point[3] = {-3, 7, 3};
static const double stress_base_sun[3] = {0.45, -0.8, -0.4};
static const double stress_colors[STRESS_MAX_OBJECTS][3] = {
    {0.8, 0.8, 0.78}, {0.85, 0.3, 0.25}, {0.25, 0.45, 0.85}, {0.9, 0.75, 0.3}, {0.3, 0.75, 0.35}, {0.7, 0.4, 0.8},
};
#define STRESS_SPHERE_SEGMENTS 32

/* Distances of the axes below, in the base scene's units. */
#define STRESS_GRAZING_DISTANCE 12                             /* a grazing point or spot light from the box */
#define STRESS_CONE_HEIGHT 4                                   /* a wide spot straight down from this height */
#define STRESS_CONE_INNER 0.9                                  /* its inner angle, as a share of the outer */
#define STRESS_VOLUME_LIGHT_BACK 4.3                           /* camera on a volume: the light behind the box */
#define STRESS_VOLUME_LIGHT_UP 0.8                             /* and above its top */
#define STRESS_VOLUME_SUN_SLOPE 0.15                           /* the sun's fall per unit along +z */
#define STRESS_VOLUME_EYE_HEIGHT 0.6                           /* where the camera meets the plane */
#define STRESS_GIANT_GAP 6                                     /* a huge caster's distance from the scene */
static const double stress_grazing_travel[3] = {0.8, 0, -0.6}; /* horizontal, unit */
static const double stress_model_at[3] = {-0.5, 0, 2.5};
static const double stress_panel_at[3] = {-1, 2.5, -1};

static void stress_set(double out[3], double x, double y, double z) {
    out[0] = x;
    out[1] = y;
    out[2] = z;
}

static void stress_unit(double v[3]) {
    double length = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; i++)
        v[i] /= length;
}

/* A spot's direction (or any light's, for the record) at point p. */
static void stress_aim(stress_scene *s, const double p[3]) {
    for (int i = 0; i < 3; i++)
        s->light_direction[i] = p[i] - s->light_position[i];
    stress_unit(s->light_direction);
}

static const double *stress_box_centre(const stress_scene *s) { return s->objects[STRESS_BOX].translate; }

static stress_object *stress_add(stress_scene *s, const stress_object *o) {
    s->objects[s->object_count] = *o;
    return &s->objects[s->object_count++];
}

static void stress_light_at(stress_scene *s, double x, double y, double z) { stress_set(s->light_position, x, y, z); }

/* ---- the axes: each changes the base scene by its value ---- */

typedef void stress_axis(stress_scene *s, double value);

static void stress_none(stress_scene *s, double value) { (void)s, (void)value; }

/* Every length times `value`, about the origin. */
static void stress_scale(stress_scene *s, double value) {
    for (int i = 0; i < 3; i++) {
        s->eye[i] *= value;
        s->target[i] *= value;
        s->light_position[i] *= value;
    }
    s->near *= value;
    s->far *= value;
    for (int o = 0; o < s->object_count; o++) {
        for (int i = 0; i < 3; i++) {
            s->objects[o].translate[i] *= value;
            s->objects[o].size[i] *= value;
        }
    }
}

/* Everything moved by (value, value / 4, -value). */
static void stress_translate(stress_scene *s, double value) {
    const double offset[3] = {value, value / 4, -value};
    for (int i = 0; i < 3; i++) {
        s->eye[i] += offset[i];
        s->target[i] += offset[i];
        s->light_position[i] += offset[i];
        for (int o = 0; o < s->object_count; o++)
            s->objects[o].translate[i] += offset[i];
    }
}

static void stress_near_ratio(stress_scene *s, double value) { s->near = s->far / value; }

static void stress_far_ratio(stress_scene *s, double value) { s->far = s->near * value; }

static void stress_light_inside(stress_scene *s, double value) {
    (void)value;
    const double *c = stress_box_centre(s);
    stress_light_at(s, c[0], c[1], c[2]);
}

/* `value` above the box's top face (0: on it). */
static void stress_light_above(stress_scene *s, double value) {
    const double *c = stress_box_centre(s);
    stress_light_at(s, c[0], c[1] + s->objects[STRESS_BOX].size[1] / 2 + value, c[2]);
}

/* `value` degrees above the ground's plane: a sun, or a light that far
 * from the box, aimed at it. */
static void stress_grazing(stress_scene *s, double value) {
    double a = value * M_PI / 180;
    const double *t = stress_grazing_travel, *c = stress_box_centre(s);
    stress_set(s->light_direction, t[0] * cos(a), -sin(a), t[2] * cos(a));
    for (int i = 0; i < 3; i++)
        s->light_position[i] = c[i] - STRESS_GRAZING_DISTANCE * s->light_direction[i];
}

/* `value` below the ground, aimed at the box, or a sun shining upwards;
 * the camera below too, so that what it sees is lit: the ground's
 * underside, where no caster (all above it) can shadow. */
static void stress_below(stress_scene *s, double value) {
    stress_light_at(s, 0.5, -value, 0.5);
    s->eye[1] = -s->eye[1];
    if (s->light == STRESS_DIRECTIONAL) {
        stress_set(s->light_direction, 0.3, 1, 0.2);
        stress_unit(s->light_direction);
    } else {
        stress_aim(s, stress_box_centre(s));
    }
}

/* `value` away from the box, the way the base light is. */
static void stress_far_light(stress_scene *s, double value) {
    const double *c = stress_box_centre(s);
    double away[3];
    for (int i = 0; i < 3; i++)
        away[i] = s->light_position[i] - c[i];
    stress_unit(away);
    for (int i = 0; i < 3; i++)
        s->light_position[i] = c[i] + value * away[i];
    stress_aim(s, c);
}

static void stress_light_at_camera(stress_scene *s, double value) {
    (void)value;
    memcpy(s->light_position, s->eye, sizeof s->light_position);
    stress_aim(s, s->target);
}

/* A point light `value` above the receiver's plane; 0: on it, where
 * planar's shadow matrix is singular and the ground is edge-on to the
 * light (lit by nothing: shadowdiff leaves it out). */
static void stress_light_on_ground(stress_scene *s, double value) {
    stress_light_at(s, 0.5, value, 3.5);
    stress_aim(s, stress_box_centre(s));
}

/* A spot straight down whose outer cone is `value` degrees. */
static void stress_spot_cone(stress_scene *s, double value) {
    stress_light_at(s, -1, STRESS_CONE_HEIGHT, 1);
    stress_set(s->light_direction, 0, -1, 0);
    s->outer = value;
    s->inner = value * STRESS_CONE_INNER;
}

static void stress_camera_inside(stress_scene *s, double value) {
    (void)value;
    memcpy(s->eye, stress_box_centre(s), sizeof s->eye);
    memcpy(s->target, s->objects[STRESS_SPHERE].translate, sizeof s->target);
}

/* The camera on the plane of the box's shadow volume through the top edge
 * facing +z (the box square to the axes, the light behind it), `value`
 * below that plane (0: on it; more: in the shadow), looking at the box. */
static void stress_camera_on_volume(stress_scene *s, double value) {
    stress_object *box = &s->objects[STRESS_BOX];
    memset(box->rotate, 0, sizeof box->rotate);
    const double *c = box->translate;
    const double edge[3] = {c[0], c[1] + box->size[1] / 2, c[2] + box->size[2] / 2};
    double d[3];
    if (s->light == STRESS_DIRECTIONAL) {
        stress_set(s->light_direction, 0, -STRESS_VOLUME_SUN_SLOPE, 1);
        stress_unit(s->light_direction);
        memcpy(d, s->light_direction, sizeof d);
    } else {
        stress_light_at(s, edge[0], edge[1] + STRESS_VOLUME_LIGHT_UP, edge[2] - STRESS_VOLUME_LIGHT_BACK);
        stress_aim(s, c);
        for (int i = 0; i < 3; i++)
            d[i] = edge[i] - s->light_position[i];
    }
    double beta = (edge[1] - STRESS_VOLUME_EYE_HEIGHT) / -d[1];
    for (int i = 0; i < 3; i++)
        s->eye[i] = edge[i] + beta * d[i];
    s->eye[1] -= value;
    memcpy(s->target, c, sizeof s->target);
}

static void stress_fov(stress_scene *s, double value) { s->fov = value; }

/* `value` straight above the origin, looking down (up along -z). */
static void stress_camera_down(stress_scene *s, double value) {
    stress_set(s->eye, 0, value, 0);
    stress_set(s->target, 0, 0, 0);
    stress_set(s->up, 0, 0, -1);
}

static void stress_huge_ground(stress_scene *s, double value) {
    s->objects[STRESS_GROUND].size[0] = s->objects[STRESS_GROUND].size[2] = value;
}

/* A sphere of radius `value` on the sun's side whose shadow's edge passes
 * through the origin (the line from the origin towards the sun touches it). */
static void stress_huge_caster(stress_scene *s, double value) {
    const double *d = s->light_direction;
    double side[3] = {-d[2], 0, d[0]}; /* d x up, horizontal */
    stress_unit(side);
    stress_object *o = stress_add(
        s, &(stress_object){"giant", STRESS_MESH_SPHERE, {value, 0, 0}, {0, 0, 0}, {0, 0, 0}, {1, 1, 1}, true});
    for (int i = 0; i < 3; i++)
        o->translate[i] = -d[i] * (value + STRESS_GIANT_GAP) + side[i] * value;
}

/* The box shrunk to `value` on a side, resting on the ground. */
static void stress_tiny_caster(stress_scene *s, double value) {
    stress_object *box = &s->objects[STRESS_BOX];
    stress_set(box->size, value, value, value);
    box->translate[1] = value / 2;
}

static void stress_with_model(stress_scene *s, stress_model model, double value, const double at[3]) {
    s->model = model;
    s->model_size = value;
    stress_object *o =
        stress_add(s, &(stress_object){"model", STRESS_MESH_MODEL, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {1, 1, 1}, true});
    memcpy(o->translate, at, sizeof o->translate);
}

static void stress_blades(stress_scene *s, double value) {
    stress_with_model(s, STRESS_BLADES, value, stress_model_at);
}

static void stress_spikes(stress_scene *s, double value) {
    stress_with_model(s, STRESS_SPIKES, value, stress_model_at);
}

static void stress_slivers(stress_scene *s, double value) {
    stress_with_model(s, STRESS_SLIVERS, value, stress_panel_at);
}

/* A second box like the first, moved by (0, value, 0) times its size:
 * 0 on the first (every face coplanar), 1 stacked on it (a shared face). */
static void stress_twin(stress_scene *s, double value) {
    stress_object *o = stress_add(s, &s->objects[STRESS_BOX]);
    o->name = "twin";
    o->translate[1] += value * o->size[1];
}

/* A second box beside the first, square to the axes, faces touching. */
static void stress_beside(stress_scene *s, double value) {
    (void)value;
    memset(s->objects[STRESS_BOX].rotate, 0, sizeof s->objects[STRESS_BOX].rotate);
    stress_object *o = stress_add(s, &s->objects[STRESS_BOX]);
    o->name = "beside";
    o->translate[2] -= o->size[2];
}

/* A plane of side `value` lying on the box's top face, casting. */
static void stress_panel(stress_scene *s, double value) {
    const stress_object *box = &s->objects[STRESS_BOX];
    stress_object *o = stress_add(
        s, &(stress_object){"panel", STRESS_MESH_PLANE, {value, 0, value}, {0, 0, 0}, {0, 0, 0}, {1, 1, 1}, true});
    memcpy(o->translate, box->translate, sizeof o->translate);
    o->translate[1] += box->size[1] / 2;
    memcpy(o->rotate, box->rotate, sizeof o->rotate);
}

/* The box's scale (-value, value, value): mirrored in x. */
static void stress_mirror(stress_scene *s, double value) {
    stress_set(s->objects[STRESS_BOX].scale, -value, value, value);
}

/* The sphere's scale -value on every axis: mirrored three times. */
static void stress_mirror_all(stress_scene *s, double value) {
    stress_set(s->objects[STRESS_SPHERE].scale, -value, -value, -value);
}

/* ---- the cases ---- */

typedef struct stress_case {
    const char *name;
    bool quick; /* passes and is cheap: `make test` runs it (--quick) */
    stress_light_kind light;
    stress_axis *axis;
    double value;
    /* The camera sees no lit ground, so the configurations measured only
     * there (planar) compare nothing, rightly: "unmeasured", not a failure. */
    bool no_ground;
} stress_case;

#define STRESS_LIGHTS3(name, quick, axis, value)                                                                     \
    {name "_spot", quick, STRESS_SPOT, axis, value, false},                                                          \
        {name "_point", quick, STRESS_POINT, axis, value, false}, {                                                  \
        name "_directional", quick, STRESS_DIRECTIONAL, axis, value, false                                           \
    }

static const stress_case stress_cases[] = {
    STRESS_LIGHTS3("base", true, stress_none, 0),
    STRESS_LIGHTS3("scale_1e-3", false, stress_scale, 1e-3),
    STRESS_LIGHTS3("scale_1e-1", false, stress_scale, 1e-1),
    STRESS_LIGHTS3("scale_1e2", false, stress_scale, 1e2),
    {"scale_1e4_spot", true, STRESS_SPOT, stress_scale, 1e4, false},
    {"scale_1e4_point", false, STRESS_POINT, stress_scale, 1e4, false},
    {"scale_1e4_directional", false, STRESS_DIRECTIONAL, stress_scale, 1e4, false},
    STRESS_LIGHTS3("translate_1e3", false, stress_translate, 1e3),
    STRESS_LIGHTS3("translate_1e4", false, stress_translate, 1e4),
    STRESS_LIGHTS3("translate_1e5", false, stress_translate, 1e5),
    {"translate_1e6_spot", true, STRESS_SPOT, stress_translate, 1e6, false},
    {"translate_1e6_point", false, STRESS_POINT, stress_translate, 1e6, false},
    {"translate_1e6_directional", false, STRESS_DIRECTIONAL, stress_translate, 1e6, false},
    {"near_far_1e6_near_spot", true, STRESS_SPOT, stress_near_ratio, 1e6, false},
    {"near_far_1e9_near_spot", false, STRESS_SPOT, stress_near_ratio, 1e9, false},
    {"near_far_1e6_near_directional", false, STRESS_DIRECTIONAL, stress_near_ratio, 1e6, false},
    {"near_far_1e9_near_directional", false, STRESS_DIRECTIONAL, stress_near_ratio, 1e9, false},
    {"near_far_1e6_far_spot", false, STRESS_SPOT, stress_far_ratio, 1e6, false},
    {"near_far_1e9_far_spot", true, STRESS_SPOT, stress_far_ratio, 1e9, false},
    {"near_far_1e6_far_directional", false, STRESS_DIRECTIONAL, stress_far_ratio, 1e6, false},
    {"near_far_1e9_far_directional", false, STRESS_DIRECTIONAL, stress_far_ratio, 1e9, false},
    {"light_inside_point", false, STRESS_POINT, stress_light_inside, 0, false},
    {"light_inside_spot", false, STRESS_SPOT, stress_light_inside, 0, false},
    {"light_on_point", false, STRESS_POINT, stress_light_above, 0, false},
    {"light_on_spot", false, STRESS_SPOT, stress_light_above, 0, false},
    {"light_above_1e-3_point", false, STRESS_POINT, stress_light_above, 1e-3, false},
    {"light_above_1e-2_point", false, STRESS_POINT, stress_light_above, 1e-2, false},
    {"light_above_1e-3_spot", false, STRESS_SPOT, stress_light_above, 1e-3, false},
    {"grazing_0.1_directional", false, STRESS_DIRECTIONAL, stress_grazing, 0.1, false},
    {"grazing_0.5_directional", false, STRESS_DIRECTIONAL, stress_grazing, 0.5, false},
    {"grazing_1_directional", false, STRESS_DIRECTIONAL, stress_grazing, 1, false},
    {"grazing_2_directional", false, STRESS_DIRECTIONAL, stress_grazing, 2, false},
    {"grazing_5_directional", false, STRESS_DIRECTIONAL, stress_grazing, 5, false},
    {"grazing_1_spot", false, STRESS_SPOT, stress_grazing, 1, false},
    {"grazing_5_point", false, STRESS_POINT, stress_grazing, 5, false},
    {"below_point", false, STRESS_POINT, stress_below, 5, false},
    {"below_spot", false, STRESS_SPOT, stress_below, 5, false},
    {"below_directional", false, STRESS_DIRECTIONAL, stress_below, 5, false},
    {"far_light_1e4_point", false, STRESS_POINT, stress_far_light, 1e4, false},
    {"far_light_1e6_point", true, STRESS_POINT, stress_far_light, 1e6, false},
    {"far_light_1e4_spot", false, STRESS_SPOT, stress_far_light, 1e4, false},
    {"light_at_camera_point", false, STRESS_POINT, stress_light_at_camera, 0, false},
    {"light_at_camera_spot", false, STRESS_SPOT, stress_light_at_camera, 0, false},
    {"light_on_ground_point", false, STRESS_POINT, stress_light_on_ground, 0, .no_ground = true},
    {"light_above_ground_1e-3_point", false, STRESS_POINT, stress_light_on_ground, 1e-3, false},
    {"spot_cone_60", false, STRESS_SPOT, stress_spot_cone, 60, false},
    {"spot_cone_80", false, STRESS_SPOT, stress_spot_cone, 80, false},
    {"spot_cone_89", false, STRESS_SPOT, stress_spot_cone, 89, false},
    {"spot_cone_89.9", true, STRESS_SPOT, stress_spot_cone, 89.9, false},
    {"camera_inside_spot", false, STRESS_SPOT, stress_camera_inside, 0, .no_ground = true},
    {"camera_inside_directional", false, STRESS_DIRECTIONAL, stress_camera_inside, 0, .no_ground = true},
    {"camera_on_volume_point", true, STRESS_POINT, stress_camera_on_volume, 0, false},
    {"camera_on_volume_directional", false, STRESS_DIRECTIONAL, stress_camera_on_volume, 0, false},
    {"camera_in_shadow_point", false, STRESS_POINT, stress_camera_on_volume, 0.3, false},
    {"camera_in_shadow_directional", false, STRESS_DIRECTIONAL, stress_camera_on_volume, 0.3, false},
    {"camera_down_spot", false, STRESS_SPOT, stress_camera_down, 14, false},
    {"fov_1_spot", false, STRESS_SPOT, stress_fov, 1, false},
    {"fov_170_spot", false, STRESS_SPOT, stress_fov, 170, false},
    {"huge_ground_1e5_spot", false, STRESS_SPOT, stress_huge_ground, 1e5, false},
    {"huge_ground_1e6_directional", false, STRESS_DIRECTIONAL, stress_huge_ground, 1e6, false},
    {"huge_caster_1e3_directional", false, STRESS_DIRECTIONAL, stress_huge_caster, 1e3, false},
    {"huge_caster_1e5_directional", false, STRESS_DIRECTIONAL, stress_huge_caster, 1e5, false},
    {"tiny_caster_1e-2_spot", false, STRESS_SPOT, stress_tiny_caster, 1e-2, false},
    {"tiny_caster_1e-4_spot", false, STRESS_SPOT, stress_tiny_caster, 1e-4, false},
    {"needle_blades_5e-2_point", false, STRESS_POINT, stress_blades, 5e-2, false},
    {"needle_blades_1e-3_point", false, STRESS_POINT, stress_blades, 1e-3, false},
    {"needle_blades_1e-3_directional", false, STRESS_DIRECTIONAL, stress_blades, 1e-3, false},
    {"needle_spikes_5e-2_spot", true, STRESS_SPOT, stress_spikes, 5e-2, false},
    {"needle_spikes_1e-4_spot", false, STRESS_SPOT, stress_spikes, 1e-4, false},
    {"sliver_1e-4_spot", false, STRESS_SPOT, stress_slivers, 1e-4, false},
    {"sliver_1e-7_directional", false, STRESS_DIRECTIONAL, stress_slivers, 1e-7, false},
    {"coplanar_twin_spot", false, STRESS_SPOT, stress_twin, 0, false},
    {"coplanar_stack_spot", true, STRESS_SPOT, stress_twin, 1, false},
    {"coplanar_beside_spot", false, STRESS_SPOT, stress_beside, 0, false},
    {"coplanar_panel_spot", false, STRESS_SPOT, stress_panel, 3, false},
    {"mirror_box_spot", true, STRESS_SPOT, stress_mirror, 1, false},
    {"mirror_sphere_point", true, STRESS_POINT, stress_mirror_all, 1, false},
};
#define STRESS_CASE_COUNT ((int)(sizeof stress_cases / sizeof *stress_cases))

static void stress_build(const stress_case *c, stress_scene *s) {
    *s = stress_base;
    s->light = c->light;
    if (c->light == STRESS_POINT)
        memcpy(s->light_position, stress_base_point, sizeof s->light_position);
    if (c->light == STRESS_DIRECTIONAL) {
        memcpy(s->light_direction, stress_base_sun, sizeof s->light_direction);
        stress_unit(s->light_direction);
    } else {
        stress_aim(s, (const double[3]){0, 0, 0});
    }
    c->axis(s, c->value);
}

/* ---- a case's files ---- */

static const double stress_ambient[3] = {0.15, 0.15, 0.17};

static void stress_put3(FILE *f, const char *key, const double v[3]) {
    fprintf(f, "\"%s\": [%.9g, %.9g, %.9g]", key, v[0], v[1], v[2]);
}

static void stress_write_object(FILE *f, const stress_object *o, int index, const char *model_file) {
    fprintf(f, "    {\"name\": \"%s\", \"mesh\": {\"kind\": ", o->name);
    switch (o->mesh) {
    case STRESS_MESH_PLANE: fprintf(f, "\"plane\", \"size\": [%.9g, %.9g]}", o->size[0], o->size[2]); break;
    case STRESS_MESH_BOX:
        fputs("\"box\", ", f);
        stress_put3(f, "size", o->size);
        fputc('}', f);
        break;
    case STRESS_MESH_SPHERE:
        fprintf(f, "\"sphere\", \"radius\": %.9g, \"segments\": %d}", o->size[0], STRESS_SPHERE_SEGMENTS);
        break;
    case STRESS_MESH_MODEL: fprintf(f, "\"model\", \"path\": \"%s\"}", model_file); break;
    }
    const char *keys[] = {"translate", "rotate", "scale", "color"};
    const double *values[] = {o->translate, o->rotate, o->scale, stress_colors[index]};
    for (int i = 0; i < 4; i++) {
        fputs(", ", f);
        stress_put3(f, keys[i], values[i]);
    }
    fprintf(f, ", \"casts\": %s}", o->casts ? "true" : "false");
}

/* The scene file: one line per light and per object, as the assets are. */
static bool stress_write_scene(const stress_scene *s, const char *path, const char *model_file) {
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "%s: cannot create: %s\n", path, strerror(errno));
        return false;
    }
    fputs("{\n  \"camera\": {", f);
    stress_put3(f, "position", s->eye);
    fputs(", ", f);
    stress_put3(f, "target", s->target);
    fputs(", ", f);
    stress_put3(f, "up", s->up);
    fprintf(f, ", \"fov\": %.9g, \"near\": %.9g, \"far\": %.9g},\n  ", s->fov, s->near, s->far);
    stress_put3(f, "ambient", stress_ambient);
    fprintf(f, ",\n  \"lights\": [\n    {\"type\": \"%s\"", stress_light_names[s->light]);
    if (s->light != STRESS_DIRECTIONAL) {
        fputs(", ", f);
        stress_put3(f, "position", s->light_position);
    }
    if (s->light != STRESS_POINT) {
        fputs(", ", f);
        stress_put3(f, "direction", s->light_direction);
    }
    if (s->light == STRESS_SPOT)
        fprintf(f, ", \"inner_angle\": %.9g, \"outer_angle\": %.9g", s->inner, s->outer);
    fputs("}\n  ],\n  \"objects\": [\n", f);
    for (int i = 0; i < s->object_count; i++) {
        stress_write_object(f, &s->objects[i], i, model_file);
        fputs(i + 1 < s->object_count ? ",\n" : "\n", f);
    }
    fputs("  ]\n}\n", f);
    if (ferror(f) | (fclose(f) != 0)) {
        fprintf(stderr, "%s: cannot write\n", path);
        return false;
    }
    return true;
}

/* The models: a row of blades or spikes along x, or one panel. */
#define STRESS_MODEL_COUNT 9
#define STRESS_MODEL_PITCH 0.75
#define STRESS_MODEL_HEIGHT 1.8
#define STRESS_PANEL_SIDE 2.0
#define STRESS_MODEL_MAX_VERTICES (4 * STRESS_MODEL_COUNT)
#define STRESS_PANEL_EDGES 4

typedef struct stress_obj {
    FILE *f;
    double v[STRESS_MODEL_MAX_VERTICES][3];
    int count;
} stress_obj;

/* Writes a vertex; returns its OBJ index (from 1). */
static int stress_obj_vertex(stress_obj *m, double x, double y, double z) {
    stress_set(m->v[m->count], x, y, z);
    fprintf(m->f, "v %.9g %.9g %.9g\n", x, y, z);
    return ++m->count;
}

/* The triangle a b c, wound so that its front faces along `out`. */
static void stress_obj_face(stress_obj *m, int a, int b, int c, const double out[3]) {
    const double *p = m->v[a - 1], *q = m->v[b - 1], *r = m->v[c - 1];
    double u[3], w[3];
    for (int i = 0; i < 3; i++) {
        u[i] = q[i] - p[i];
        w[i] = r[i] - p[i];
    }
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    bool flip = n[0] * out[0] + n[1] * out[1] + n[2] * out[2] < 0;
    fprintf(m->f, "f %d %d %d\n", a, flip ? c : b, flip ? b : c);
}

/* Upright triangles `width` wide at the foot: needles seen from the side. */
static void stress_obj_blades(stress_obj *m, double width) {
    static const double towards_camera[3] = {0, 0, 1};
    for (int i = 0; i < STRESS_MODEL_COUNT; i++) {
        double x = (i - STRESS_MODEL_COUNT / 2) * STRESS_MODEL_PITCH;
        int a = stress_obj_vertex(m, x - width / 2, 0, 0), b = stress_obj_vertex(m, x + width / 2, 0, 0);
        stress_obj_face(m, a, b, stress_obj_vertex(m, x, STRESS_MODEL_HEIGHT, 0), towards_camera);
    }
}

/* Tetrahedra on a foot `width` on a side: closed needles, faces outwards
 * (away from the corner each face leaves out). */
static void stress_obj_spikes(stress_obj *m, double width) {
    static const int faces[4][4] = {{0, 1, 2, 3}, {0, 1, 3, 2}, {1, 2, 3, 0}, {2, 0, 3, 1}}; /* + the one left out */
    for (int i = 0; i < STRESS_MODEL_COUNT; i++) {
        double x = (i - STRESS_MODEL_COUNT / 2) * STRESS_MODEL_PITCH, r = width / sqrt(3), p[4][3];
        for (int k = 0; k < 3; k++)
            stress_set(p[k], x + r * cos(M_PI / 2 + k * 2 * M_PI / 3), 0, r * sin(M_PI / 2 + k * 2 * M_PI / 3));
        stress_set(p[3], x, STRESS_MODEL_HEIGHT, 0);
        int first = m->count + 1;
        for (int k = 0; k < 4; k++)
            stress_obj_vertex(m, p[k][0], p[k][1], p[k][2]);
        for (int f = 0; f < 4; f++) {
            const int *t = faces[f];
            const double out[3] = {p[t[0]][0] - p[t[3]][0], p[t[0]][1] - p[t[3]][1], p[t[0]][2] - p[t[3]][2]};
            stress_obj_face(m, first + t[0], first + t[1], first + t[2], out);
        }
    }
}

/* A square panel facing up, each edge's middle pulled `height` inwards:
 * four slivers (an edge and that point) round a fan from the centre. */
static void stress_obj_slivers(stress_obj *m, double height) {
    static const double up[3] = {0, 1, 0};
    const double side = STRESS_PANEL_SIDE, half = side / 2;
    int corner[STRESS_PANEL_EDGES], pulled[STRESS_PANEL_EDGES];
    static const double corners[STRESS_PANEL_EDGES][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int e = 0; e < STRESS_PANEL_EDGES; e++)
        corner[e] = stress_obj_vertex(m, corners[e][0] * side, 0, corners[e][1] * side);
    for (int e = 0; e < STRESS_PANEL_EDGES; e++) {
        const double *p = corners[e], *q = corners[(e + 1) % STRESS_PANEL_EDGES];
        double mx = (p[0] + q[0]) / 2 * side, mz = (p[1] + q[1]) / 2 * side;
        double in[3] = {half - mx, 0, half - mz};
        stress_unit(in);
        pulled[e] = stress_obj_vertex(m, mx + height * in[0], 0, mz + height * in[2]);
    }
    int centre = stress_obj_vertex(m, half, 0, half);
    for (int e = 0; e < STRESS_PANEL_EDGES; e++) {
        int next = corner[(e + 1) % STRESS_PANEL_EDGES];
        stress_obj_face(m, corner[e], pulled[e], next, up);
        stress_obj_face(m, centre, corner[e], pulled[e], up);
        stress_obj_face(m, centre, pulled[e], next, up);
    }
}

static bool stress_write_model(const stress_scene *s, const char *path) {
    stress_obj m = {.f = fopen(path, "w")};
    if (!m.f) {
        fprintf(stderr, "%s: cannot create: %s\n", path, strerror(errno));
        return false;
    }
    switch (s->model) {
    case STRESS_NO_MODEL: break;
    case STRESS_BLADES: stress_obj_blades(&m, s->model_size); break;
    case STRESS_SPIKES: stress_obj_spikes(&m, s->model_size); break;
    case STRESS_SLIVERS: stress_obj_slivers(&m, s->model_size); break;
    }
    if (ferror(m.f) | (fclose(m.f) != 0)) {
        fprintf(stderr, "%s: cannot write\n", path);
        return false;
    }
    return true;
}

/* ---- subprocesses ---- */

/* --out and --bin at most this long, so that every path below fits in
 * STRESS_PATH_MAX and every command in STRESS_ARGS_TEXT. */
#define STRESS_DIR_MAX 256
#define STRESS_ARGS_TEXT (6 * STRESS_PATH_MAX)

typedef enum stress_end { STRESS_NOT_RUN, STRESS_EXITED, STRESS_SIGNALED } stress_end;

typedef struct stress_process {
    char text[STRESS_ARGS_TEXT]; /* the arguments, each ending in a NUL */
    size_t used;
    int argc;
    char out_path[STRESS_PATH_MAX], err_path[STRESS_PATH_MAX];
    pid_t pid;
    double started, deadline, seconds;
    stress_end end;
    int code;       /* the exit status, or the signal */
    bool killed;    /* its group was sent SIGKILL */
    bool timed_out; /* ... because it ran past its deadline */
} stress_process;

/* A path into a STRESS_PATH_MAX buffer: it fits, since --out and --bin
 * are at most STRESS_DIR_MAX long and names are short. */
__attribute__((format(printf, 2, 3))) static void stress_path(char *out, const char *format, ...) {
    va_list list;
    va_start(list, format);
    vsnprintf(out, STRESS_PATH_MAX, format, list);
    va_end(list);
}

static double stress_now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

/* Appends arguments up to a NULL. Each is a path or a flag: they fit. */
static void stress_args(stress_process *p, ...) {
    va_list list;
    va_start(list, p);
    for (const char *a; (a = va_arg(list, const char *));) {
        size_t n = strlen(a) + 1;
        memcpy(p->text + p->used, a, n);
        p->used += n;
        p->argc++;
    }
    va_end(list);
}

/* In the child: its streams, then the program. Never returns. */
static void stress_exec(stress_process *p) {
    char *argv[STRESS_MAX_ARGS + 1];
    for (int i = 0, at = 0; i < p->argc; i++) {
        argv[i] = p->text + at;
        at += (int)strlen(argv[i]) + 1;
    }
    argv[p->argc] = NULL;
    int in = open("/dev/null", O_RDONLY), out = open(p->out_path, O_WRONLY | O_CREAT | O_TRUNC, 0644),
        err = open(p->err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (in < 0 || out < 0 || err < 0 || dup2(in, STDIN_FILENO) < 0 || dup2(out, STDOUT_FILENO) < 0 ||
        dup2(err, STDERR_FILENO) < 0)
        _exit(STRESS_EXEC_FAILED);
    execv(argv[0], argv);
    dprintf(STDERR_FILENO, "%s: cannot run: %s\n", argv[0], strerror(errno));
    _exit(STRESS_EXEC_FAILED);
}

static bool stress_start(stress_process *p, double timeout) {
    pid_t pid = fork();
    if (pid == 0) {
        setpgid(0, 0); /* its own group: a timeout kills what it started too */
        stress_exec(p);
    }
    if (pid < 0) {
        fprintf(stderr, "stress: cannot fork: %s\n", strerror(errno));
        return false;
    }
    setpgid(pid, pid); /* here as well: the group exists before any kill */
    p->pid = pid;
    p->started = stress_now();
    p->deadline = p->started + timeout;
    return true;
}

static void stress_reap(stress_process *p, int status) {
    p->seconds = stress_now() - p->started;
    p->end = WIFSIGNALED(status) ? STRESS_SIGNALED : STRESS_EXITED;
    p->code = WIFSIGNALED(status) ? WTERMSIG(status) : WEXITSTATUS(status);
    kill(-p->pid, SIGKILL); /* whatever it left running in its group */
}

/* Runs every process, at most `jobs` at once, each killed (its group) past
 * `timeout` seconds; returns when every one started has been reaped. After
 * an interrupt, none more starts and the running ones are killed. */
static void stress_run_all(stress_process *const *list, int count, int jobs, double timeout) {
    stress_process *running[STRESS_MAX_JOBS];
    int active = 0, next = 0;
    while ((next < count && !stress_interrupted) || active > 0) {
        while (active < jobs && next < count && !stress_interrupted) {
            stress_process *p = list[next++];
            if (stress_start(p, timeout))
                running[active++] = p;
        }
        int status;
        pid_t pid = waitpid(-1, &status, WNOHANG);
        int done = -1;
        for (int i = 0; pid > 0 && i < active && done < 0; i++)
            done = running[i]->pid == pid ? i : -1;
        if (done >= 0) {
            stress_reap(running[done], status);
            running[done] = running[--active];
            continue;
        }
        double now = stress_now();
        for (int i = 0; i < active; i++) {
            stress_process *p = running[i];
            if (!p->killed && (now > p->deadline || stress_interrupted)) {
                p->killed = true;
                p->timed_out = !stress_interrupted;
                kill(-p->pid, SIGKILL);
            }
        }
        nanosleep(&(struct timespec){0, STRESS_POLL_NS}, NULL);
    }
}

static void stress_on_signal(int signal_number) {
    (void)signal_number;
    stress_interrupted = 1;
}

/* ---- what runs on each case ---- */

typedef struct stress_config {
    const char *technique; /* the program, in the --bin directory */
    const char *name;
    const char *flags[STRESS_MAX_FLAGS + 1]; /* NULL-terminated */
    double bound;                            /* misclassified %, at most */
    const char *receiver;                    /* compared only there, or NULL: everywhere */
} stress_config;

/* Each technique's defaults and the configurations that take another path
 * through it. Planar shadows fall on planes only: measured on the ground. */
static const stress_config stress_configs[] = {
    {"planar", "default", {NULL}, STRESS_BOUND_PLANAR, "ground"},
    {"shadowmap", "default", {NULL}, STRESS_BOUND_MAPS, NULL},
    {"shadowmap", "filter-none", {"--filter", "none", NULL}, STRESS_BOUND_MAPS, NULL},
    {"shadowmap", "depth-32f", {"--depth", "32f", NULL}, STRESS_BOUND_MAPS, NULL},
    {"psm", "default", {NULL}, STRESS_BOUND_MAPS, NULL},
    {"psm", "lispsm", {"--warp", "lispsm", NULL}, STRESS_BOUND_MAPS, NULL},
    {"cascades", "default", {NULL}, STRESS_BOUND_MAPS, NULL},
    {"volumes", "default", {NULL}, STRESS_BOUND_VOLUMES, NULL},
    {"volumes", "zfail", {"--mode", "zfail", NULL}, STRESS_BOUND_VOLUMES, NULL},
    {"volumes", "gpu-silhouette", {"--silhouette", "gpu", NULL}, STRESS_BOUND_VOLUMES, NULL},
};
#define STRESS_CONFIG_COUNT ((int)(sizeof stress_configs / sizeof *stress_configs))
static const stress_config stress_reference = {"raytrace", "reference", {NULL}, 0, NULL};
#define STRESS_ROWS_PER_CASE (1 + STRESS_CONFIG_COUNT)

/* A row's verdict:
 *   pass              misclassified within the technique's bound (the
 *                     reference's row: it ran)
 *   fail              over the bound
 *   refused           a non-zero exit with exactly one stderr line naming
 *                     the case's scene or model file (a documented refusal)
 *   crash             killed by a signal, an exit status of 128 or more, or
 *                     a sanitizer's report on stderr
 *   nan               shadowdiff exit 5: NaN or infinity in a dump
 *   nothing-compared  shadowdiff exit 4
 *   gl-error          stderr mentions "GL error"
 *   timeout           ran past --timeout seconds (its process group killed)
 *   error             any other failure (several lines, an exit status 1
 *                     without naming the file, shadowdiff's own failure)
 *   no-reference      the technique ran but the reference did not
 *   unmeasured        nothing compared on the receiver of a case whose
 *                     camera sees none of it lit (stress_case.no_ground) */
typedef enum stress_verdict {
    STRESS_PASS,
    STRESS_FAIL,
    STRESS_REFUSED,
    STRESS_CRASH,
    STRESS_NAN,
    STRESS_NOTHING_COMPARED_VERDICT,
    STRESS_GL_ERROR,
    STRESS_TIMEOUT,
    STRESS_ERROR,
    STRESS_NO_REFERENCE,
    STRESS_UNMEASURED,
    STRESS_VERDICT_COUNT
} stress_verdict;
static const char *const stress_verdict_names[STRESS_VERDICT_COUNT] = {
    "pass",     "fail",    "refused", "crash",        "nan",        "nothing-compared",
    "gl-error", "timeout", "error",   "no-reference", "unmeasured",
};

typedef struct stress_row {
    const stress_case *c;
    const stress_config *config;
    const struct stress_row *reference; /* the case's reference row */
    char files[STRESS_PATH_MAX];        /* OUT/scenes/CASE. : what a refusal names */
    char dir[STRESS_PATH_MAX];          /* OUT/runs/CASE/ROW: dump, logs, heat map */
    stress_process run, diff;
    bool ran; /* the run ended well: the diff is to run */
    stress_verdict verdict;
    bool measured;
    double misclassified, mae;
    long compared;
    shadowdiff_result classes;  /* measured: each class's pixels (0: none) and MAE */
    char line[STRESS_LINE_MAX]; /* the first stderr line, or why it ended */
} stress_row;

static bool stress_is_ok(stress_verdict v) {
    return v == STRESS_PASS || v == STRESS_REFUSED || v == STRESS_UNMEASURED;
}

/* ---- verdicts ---- */

/* The start of a file (at most STRESS_STDERR_READ bytes), malloc'ed and
 * NUL-terminated; "" when it is missing. */
static char *stress_read_start(const char *path) {
    char *text = malloc(STRESS_STDERR_READ + 1);
    if (!text)
        return NULL;
    FILE *f = fopen(path, "r");
    size_t n = f ? fread(text, 1, STRESS_STDERR_READ, f) : 0;
    if (f)
        fclose(f);
    text[n] = '\0';
    return text;
}

/* The line of `text` at `at` into line, without its newline. */
static void stress_copy_line(const char *at, char *line, size_t size) {
    size_t n = strcspn(at, "\n");
    snprintf(line, size, "%.*s", (int)(n < size ? n : size - 1), at);
}

static const char *const stress_sanitizer_marks[] = {"ERROR: AddressSanitizer", "ERROR: LeakSanitizer",
                                                     "runtime error:", NULL};

static const char *stress_sanitizer_report(const char *text) {
    const char *at = NULL;
    for (int i = 0; stress_sanitizer_marks[i] && !at; i++)
        at = strstr(text, stress_sanitizer_marks[i]);
    return at;
}

/* How a process ended: STRESS_PASS when it exited 0 cleanly; a refusal
 * only when `files` (may be NULL) is named by its single stderr line. The
 * line says why: the sanitizer's line, stderr's first or what ended it. */
static stress_verdict stress_classify(const stress_process *p, const char *files, char *line, size_t size) {
    char *text = stress_read_start(p->err_path);
    if (!text) {
        snprintf(line, size, "stress: out of memory reading a stderr file");
        return STRESS_ERROR;
    }
    int lines = 0;
    for (const char *c = text; *c; c++)
        lines += *c == '\n' || !c[1];
    const char *report = stress_sanitizer_report(text);
    stress_copy_line(report ? report : text, line, size);
    stress_verdict v = STRESS_ERROR;
    if (p->end == STRESS_NOT_RUN)
        snprintf(line, size, "not run");
    else if (p->timed_out)
        v = STRESS_TIMEOUT;
    else if (p->end == STRESS_SIGNALED || p->code >= STRESS_SIGNAL_STATUS || report)
        v = STRESS_CRASH;
    else if (strstr(text, "GL error"))
        v = STRESS_GL_ERROR;
    else if (p->code == 0)
        v = STRESS_PASS;
    else if (lines == 1 && files && strstr(text, files))
        v = STRESS_REFUSED;
    if (!line[0] && v == STRESS_TIMEOUT)
        snprintf(line, size, "no output; killed after %.0f s", p->seconds);
    else if (!line[0] && p->end == STRESS_SIGNALED)
        snprintf(line, size, "no output; killed by signal %d (%s)", p->code, strsignal(p->code));
    else if (!line[0] && v != STRESS_PASS)
        snprintf(line, size, "no output; exit status %d", p->code);
    free(text);
    return v;
}

/* Class c's figures from shadowdiff's JSON (its CLASS_pixels, and its
 * CLASS_mae: null where it has no pixel) into r->classes; false where
 * either is missing or of the wrong type. */
static bool stress_read_class(stress_row *r, const cJSON *root, shadowdiff_class c) {
    char key[STRESS_KEY_MAX];
    snprintf(key, sizeof key, "%s_pixels", shadowdiff_class_names[c]);
    const cJSON *pixels = cJSON_GetObjectItemCaseSensitive(root, key);
    snprintf(key, sizeof key, "%s_mae", shadowdiff_class_names[c]);
    const cJSON *mae = cJSON_GetObjectItemCaseSensitive(root, key);
    if (!cJSON_IsNumber(pixels) || !(cJSON_IsNumber(mae) || (cJSON_IsNull(mae) && pixels->valuedouble == 0)))
        return false;
    r->classes.class_pixels[c] = (long)pixels->valuedouble;
    r->classes.class_mae[c] = cJSON_IsNumber(mae) ? mae->valuedouble : 0;
    return true;
}

/* shadowdiff's figures from its --json line. */
static bool stress_read_figures(stress_row *r) {
    char *text = path_read_text(r->diff.out_path, STRESS_JSON_READ, NULL);
    cJSON *root = text ? cJSON_Parse(text) : NULL;
    const cJSON *compared = cJSON_GetObjectItemCaseSensitive(root, "compared"),
                *misclassified = cJSON_GetObjectItemCaseSensitive(root, "misclassified_percent"),
                *mae = cJSON_GetObjectItemCaseSensitive(root, "mean_abs_error");
    r->measured = cJSON_IsNumber(compared) && cJSON_IsNumber(misclassified) && cJSON_IsNumber(mae);
    for (int c = 0; c < SHADOWDIFF_CLASS_COUNT && r->measured; c++)
        r->measured = stress_read_class(r, root, (shadowdiff_class)c);
    if (r->measured) {
        r->compared = (long)compared->valuedouble;
        r->misclassified = misclassified->valuedouble;
        r->mae = mae->valuedouble;
    }
    cJSON_Delete(root);
    free(text);
    return r->measured;
}

/* After the run: its verdict, unless it is to be compared (r->ran). */
static void stress_judge_run(stress_row *r) {
    stress_verdict v = stress_classify(&r->run, r->files, r->line, sizeof r->line);
    bool reference = r->config == &stress_reference;
    r->ran = v == STRESS_PASS && !reference && r->reference->verdict == STRESS_PASS;
    r->verdict = v == STRESS_PASS && !reference && !r->ran ? STRESS_NO_REFERENCE : v;
}

/* After the comparison: the row's verdict, by the technique's bound. */
static void stress_judge_diff(stress_row *r) {
    char line[STRESS_LINE_MAX];
    stress_verdict v = stress_classify(&r->diff, NULL, line, sizeof line);
    if (v == STRESS_ERROR && r->diff.end == STRESS_EXITED && r->diff.code == STRESS_NOTHING_COMPARED)
        v = r->c->no_ground && r->config->receiver ? STRESS_UNMEASURED : STRESS_NOTHING_COMPARED_VERDICT;
    if (v == STRESS_ERROR && r->diff.end == STRESS_EXITED && r->diff.code == STRESS_NOT_FINITE)
        v = STRESS_NAN;
    if (v == STRESS_PASS && !stress_read_figures(r)) {
        v = STRESS_ERROR;
        snprintf(line, sizeof line, "%s: no figures in shadowdiff's output", r->diff.out_path);
    }
    if (v == STRESS_PASS)
        v = r->misclassified <= r->config->bound ? STRESS_PASS : STRESS_FAIL;
    else
        memcpy(r->line, line, sizeof line);
    r->verdict = v;
}

/* ---- the table ---- */

static void stress_csv_field(FILE *f, const char *text, const char *after) {
    if (!strpbrk(text, ",\"\n")) {
        fprintf(f, "%s%s", text, after);
        return;
    }
    fputc('"', f);
    for (const char *c = text; *c; c++) {
        if (*c == '"')
            fputc('"', f); /* doubled */
        fputc(*c, f);
    }
    fprintf(f, "\"%s", after);
}

/* The figures as text: empty where there are none. */
typedef struct stress_cells {
    char bound[32], misclassified[32], mae[32], compared[32], seconds[32];
    char class_mae[SHADOWDIFF_CLASS_COUNT][SHADOWDIFF_FIGURE_TEXT_MAX];
} stress_cells;

static void stress_cells_of(const stress_row *r, stress_cells *c) {
    memset(c, 0, sizeof *c);
    if (r->config != &stress_reference)
        snprintf(c->bound, sizeof c->bound, "%g", r->config->bound);
    if (r->measured) {
        snprintf(c->misclassified, sizeof c->misclassified, "%.4f", r->misclassified);
        snprintf(c->mae, sizeof c->mae, "%.*f", STRESS_MAE_DECIMALS, r->mae);
        snprintf(c->compared, sizeof c->compared, "%ld", r->compared);
        for (int k = 0; k < SHADOWDIFF_CLASS_COUNT; k++)
            shadowdiff_class_mae_text(&r->classes, (shadowdiff_class)k, STRESS_MAE_DECIMALS, c->class_mae[k],
                                      sizeof c->class_mae[k]);
    }
    if (r->run.end != STRESS_NOT_RUN)
        snprintf(c->seconds, sizeof c->seconds, "%.2f", r->run.seconds);
}

static bool stress_write_csv(const char *path, const stress_row *rows, int count) {
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "%s: cannot create: %s\n", path, strerror(errno));
        return false;
    }
    fputs("scene,technique,config,bound_percent,misclassified_percent,mae", f);
    for (int k = 0; k < SHADOWDIFF_CLASS_COUNT; k++)
        fprintf(f, ",%s_mae", shadowdiff_class_names[k]);
    fputs(",compared,verdict,seconds,stderr\n", f);
    for (int i = 0; i < count; i++) {
        const stress_row *r = &rows[i];
        stress_cells c;
        stress_cells_of(r, &c);
        fprintf(f, "%s,%s,%s,%s,%s,%s,", r->c->name, r->config->technique, r->config->name, c.bound, c.misclassified,
                c.mae);
        for (int k = 0; k < SHADOWDIFF_CLASS_COUNT; k++)
            fprintf(f, "%s,", c.class_mae[k]);
        fprintf(f, "%s,%s,%s,", c.compared, stress_verdict_names[r->verdict], c.seconds);
        stress_csv_field(f, r->line, "\n");
    }
    if (ferror(f) | (fclose(f) != 0)) {
        fprintf(stderr, "%s: cannot write\n", path);
        return false;
    }
    return true;
}

/* One markdown row; '|' in the stderr line escaped. */
static void stress_md_row(FILE *f, const stress_row *r) {
    stress_cells c;
    stress_cells_of(r, &c);
    fprintf(f, "| %s | %s | %s | %s | %s | %s | ", r->c->name, r->config->technique, r->config->name, c.bound,
            c.misclassified, c.mae);
    for (int k = 0; k < SHADOWDIFF_CLASS_COUNT; k++)
        fprintf(f, "%s | ", c.class_mae[k]);
    fprintf(f, "%s | %s | %s | ", c.compared, stress_verdict_names[r->verdict], c.seconds);
    for (const char *ch = r->line; *ch; ch++) {
        if (*ch == '|')
            fputc('\\', f);
        fputc(*ch, f);
    }
    fputs(" |\n", f);
}

static void stress_md_header(FILE *f) {
    fputs("| scene | technique | config | bound % | misclassified % | MAE |", f);
    for (int k = 0; k < SHADOWDIFF_CLASS_COUNT; k++)
        fprintf(f, " %s MAE |", shadowdiff_class_names[k]);
    fputs(" compared | verdict | s | stderr |\n|---|---|---|---|---|---|", f);
    for (int k = 0; k < SHADOWDIFF_CLASS_COUNT; k++)
        fputs("---|", f);
    fputs("---|---|---|---|\n", f);
}

/* The techniques in table order: the reference, then each once. */
static int stress_techniques(const char *names[STRESS_ROWS_PER_CASE]) {
    int count = 0;
    names[count++] = stress_reference.technique;
    for (int i = 0; i < STRESS_CONFIG_COUNT; i++)
        if (strcmp(names[count - 1], stress_configs[i].technique) != 0)
            names[count++] = stress_configs[i].technique;
    return count;
}

/* Counts per technique and verdict, then every row that is not ok. */
static void stress_write_summary(FILE *f, const stress_row *rows, int count) {
    const char *names[STRESS_ROWS_PER_CASE];
    int techniques = stress_techniques(names);
    fputs("| technique |", f);
    for (int v = 0; v < STRESS_VERDICT_COUNT; v++)
        fprintf(f, " %s |", stress_verdict_names[v]);
    fputs("\n|---|", f);
    for (int v = 0; v < STRESS_VERDICT_COUNT; v++)
        fputs("---|", f);
    fputc('\n', f);
    for (int t = 0; t < techniques; t++) {
        int counts[STRESS_VERDICT_COUNT] = {0};
        for (int i = 0; i < count; i++)
            if (strcmp(rows[i].config->technique, names[t]) == 0)
                counts[rows[i].verdict]++;
        fprintf(f, "| %s |", names[t]);
        for (int v = 0; v < STRESS_VERDICT_COUNT; v++)
            fprintf(f, " %d |", counts[v]);
        fputc('\n', f);
    }
    int failing = 0;
    for (int i = 0; i < count; i++)
        failing += !stress_is_ok(rows[i].verdict);
    fprintf(f, "\n%d of %d rows are not pass, refused or unmeasured%s\n", failing, count, failing ? ":\n" : ".");
    if (failing)
        stress_md_header(f);
    for (int i = 0; i < count; i++)
        if (!stress_is_ok(rows[i].verdict))
            stress_md_row(f, &rows[i]);
}

static bool stress_write_md(const char *path, const stress_row *rows, int count, int width, int height) {
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "%s: cannot create: %s\n", path, strerror(errno));
        return false;
    }
    fprintf(f,
            "# Stress run\n\n%d rows at %dx%d. Bounds, misclassified %% of compared pixels: volumes %g, shadow "
            "maps %g, planar %g on the ground.\n\n## Summary\n\n",
            count, width, height, STRESS_BOUND_VOLUMES, STRESS_BOUND_MAPS, STRESS_BOUND_PLANAR);
    stress_write_summary(f, rows, count);
    fputs("\n## Every row\n\n", f);
    stress_md_header(f);
    for (int i = 0; i < count; i++)
        stress_md_row(f, &rows[i]);
    if (ferror(f) | (fclose(f) != 0)) {
        fprintf(stderr, "%s: cannot write\n", path);
        return false;
    }
    return true;
}

/* ---- the run ---- */

typedef struct stress_options {
    const char *program, *out, *bin, *only;
    bool quick, list;
    int jobs, timeout, width, height;
} stress_options;

static bool stress_selected(const stress_options *o, const stress_case *c) {
    return (!o->quick || c->quick) && (!o->only || fnmatch(o->only, c->name, 0) == 0);
}

static int stress_remove_entry(const char *path, const struct stat *st, int flag, struct FTW *walk) {
    (void)st, (void)flag, (void)walk;
    return remove(path) == 0 || errno == ENOENT ? 0 : -1;
}

/* rm -rf: what a row or case left behind. */
static void stress_remove_tree(const char *dir) {
    enum { STRESS_WALK_FDS = 16 };
    nftw(dir, stress_remove_entry, STRESS_WALK_FDS, FTW_DEPTH | FTW_PHYS);
}

/* ROW/command.txt: the row's commands, to run again by hand. */
static bool stress_write_commands(const stress_row *r) {
    char path[STRESS_PATH_MAX];
    stress_path(path, "%s/command.txt", r->dir);
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "%s: cannot create: %s\n", path, strerror(errno));
        return false;
    }
    const stress_process *commands[] = {&r->run, &r->diff};
    for (int c = 0; c < (r->config == &stress_reference ? 1 : 2); c++) {
        const char *arg = commands[c]->text;
        for (int i = 0; i < commands[c]->argc; i++, arg += strlen(arg) + 1)
            fprintf(f, "%s%s", arg, i + 1 < commands[c]->argc ? " " : "\n");
    }
    if (ferror(f) | (fclose(f) != 0)) {
        fprintf(stderr, "%s: cannot write\n", path);
        return false;
    }
    return true;
}

/* The case's files, then its rows (the reference first) with their
 * commands and a clean directory each. */
static bool stress_prepare(const stress_options *o, const stress_case *c, stress_row *rows) {
    char scene_path[STRESS_PATH_MAX], model_path[STRESS_PATH_MAX], model_file[STRESS_PATH_MAX], runs[STRESS_PATH_MAX];
    stress_scene s;
    stress_build(c, &s);
    stress_path(scene_path, "%s/scenes/%s.json", o->out, c->name);
    stress_path(model_file, "%s.obj", c->name);
    stress_path(model_path, "%s/scenes/%s", o->out, model_file);
    stress_path(runs, "%s/runs/%s", o->out, c->name);
    stress_remove_tree(runs);
    if (!stress_write_scene(&s, scene_path, model_file) || (s.model && !stress_write_model(&s, model_path)))
        return false;
    char size[32], program[STRESS_PATH_MAX], heatmap[STRESS_PATH_MAX];
    snprintf(size, sizeof size, "%dx%d", o->width, o->height);
    for (int i = 0; i < STRESS_ROWS_PER_CASE; i++) {
        stress_row *r = &rows[i];
        r->c = c;
        r->config = i == 0 ? &stress_reference : &stress_configs[i - 1];
        r->reference = &rows[0];
        stress_path(r->files, "%s/scenes/%s.", o->out, c->name);
        if (i == 0)
            stress_path(r->dir, "%s/reference", runs);
        else
            stress_path(r->dir, "%s/%s-%s", runs, r->config->technique, r->config->name);
        if (!path_make_directories(r->dir))
            return false;
        stress_path(program, "%s/%s", o->bin, r->config->technique);
        stress_args(&r->run, program, "--scene", scene_path, "--size", size, "--dump", r->dir, (char *)NULL);
        for (int f = 0; r->config->flags[f]; f++)
            stress_args(&r->run, r->config->flags[f], (char *)NULL);
        stress_path(r->run.out_path, "%s/stdout.txt", r->dir);
        stress_path(r->run.err_path, "%s/stderr.txt", r->dir);
        stress_path(program, "%s/shadowdiff", o->bin);
        stress_path(heatmap, "%s/heatmap.png", r->dir);
        stress_args(&r->diff, program, rows[0].dir, r->dir, "--json", "--heatmap", heatmap, (char *)NULL);
        if (r->config->receiver)
            stress_args(&r->diff, "--receiver", r->config->receiver, (char *)NULL);
        stress_path(r->diff.out_path, "%s/diff.json", r->dir);
        stress_path(r->diff.err_path, "%s/diff-stderr.txt", r->dir);
        if (!stress_write_commands(r))
            return false;
    }
    return true;
}

typedef enum stress_stage { STRESS_STAGE_REFERENCE, STRESS_STAGE_TECHNIQUE, STRESS_STAGE_DIFF } stress_stage;
static const char *const stress_stage_names[] = {"references", "techniques", "comparisons"};

/* One stage over every row it concerns, then each row judged. */
static void stress_stage_run(const stress_options *o, stress_row *rows, int count, stress_process **list,
                             stress_stage stage) {
    int n = 0;
    for (int i = 0; i < count; i++) {
        bool reference = rows[i].config == &stress_reference;
        if (stage == STRESS_STAGE_REFERENCE ? reference : stage == STRESS_STAGE_TECHNIQUE ? !reference : rows[i].ran)
            list[n++] = stage == STRESS_STAGE_DIFF ? &rows[i].diff : &rows[i].run;
    }
    double start = stress_now();
    stress_run_all(list, n, o->jobs, o->timeout);
    if (!stress_interrupted)
        printf("stress: %d %s in %.1f s\n", n, stress_stage_names[stage], stress_now() - start);
    fflush(stdout);
    for (int i = 0; i < count && !stress_interrupted; i++) {
        bool reference = rows[i].config == &stress_reference;
        if (stage == STRESS_STAGE_DIFF && rows[i].ran)
            stress_judge_diff(&rows[i]);
        else if (stage != STRESS_STAGE_DIFF && reference == (stage == STRESS_STAGE_REFERENCE))
            stress_judge_run(&rows[i]);
    }
}

/* What passed or was refused leaves nothing behind; a case whose rows
 * all did, not even its reference. */
static void stress_clean(const stress_options *o, const stress_row *rows, int count) {
    for (int first = 0; first < count; first += STRESS_ROWS_PER_CASE) {
        bool all_ok = true;
        for (int i = first + 1; i < first + STRESS_ROWS_PER_CASE; i++) {
            if (stress_is_ok(rows[i].verdict))
                stress_remove_tree(rows[i].dir);
            all_ok = all_ok && stress_is_ok(rows[i].verdict);
        }
        if (all_ok && stress_is_ok(rows[first].verdict)) {
            char runs[STRESS_PATH_MAX];
            stress_path(runs, "%s/runs/%s", o->out, rows[first].c->name);
            stress_remove_tree(runs);
        }
    }
}

static int stress_run(const stress_options *o) {
    int cases = 0;
    for (int i = 0; i < STRESS_CASE_COUNT; i++)
        cases += stress_selected(o, &stress_cases[i]);
    int count = cases * STRESS_ROWS_PER_CASE;
    stress_row *rows = calloc((size_t)count, sizeof *rows);
    stress_process **list = calloc((size_t)count, sizeof *list);
    char scenes[STRESS_PATH_MAX];
    stress_path(scenes, "%s/scenes", o->out);
    bool ok = rows && list && path_make_directories(scenes);
    if (!rows || !list)
        fprintf(stderr, "stress: out of memory for %d rows\n", count);
    for (int i = 0, at = 0; ok && i < STRESS_CASE_COUNT; i++) {
        if (stress_selected(o, &stress_cases[i])) {
            ok = stress_prepare(o, &stress_cases[i], &rows[at]);
            at += STRESS_ROWS_PER_CASE;
        }
    }
    if (ok) {
        printf("stress: %d cases, %d rows at %dx%d, %d jobs, programs from %s/, out to %s/\n", cases, count, o->width,
               o->height, o->jobs, o->bin, o->out);
        fflush(stdout);
    }
    for (int stage = STRESS_STAGE_REFERENCE; ok && stage <= STRESS_STAGE_DIFF && !stress_interrupted; stage++)
        stress_stage_run(o, rows, count, list, (stress_stage)stage);
    int status = ok ? 0 : STRESS_EXIT_FAILED;
    if (stress_interrupted) {
        fprintf(stderr, "stress: interrupted; every program it started is gone, no table written\n");
        status = STRESS_EXIT_INTERRUPTED;
    }
    char csv[STRESS_PATH_MAX], md[STRESS_PATH_MAX];
    stress_path(csv, "%s/table.csv", o->out);
    stress_path(md, "%s/table.md", o->out);
    if (!status) {
        stress_clean(o, rows, count);
        bool written = stress_write_csv(csv, rows, count) && stress_write_md(md, rows, count, o->width, o->height);
        stress_write_summary(stdout, rows, count);
        printf("table: %s, %s\n", md, csv);
        for (int i = 0; i < count; i++)
            written = written && stress_is_ok(rows[i].verdict);
        status = written ? 0 : STRESS_EXIT_FAILED;
    }
    free(rows);
    free(list);
    return status;
}

/* -j N and -jN are --jobs N: the make-like spelling. */
static void stress_jobs_spelling(int argc, char **argv, char *joined, size_t size) {
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-j") == 0) {
            argv[i] = "--jobs";
        } else if (strncmp(argv[i], "-j", 2) == 0) {
            snprintf(joined, size, "--jobs=%s", argv[i] + 2);
            argv[i] = joined;
        }
    }
}

static int stress_parse(int argc, char **argv, stress_options *o) {
    const flags_param params[] = {
        {"quick", "only the cases that pass today (make test runs them)", 0, FLAGS_SWITCH, .on = &o->quick},
        {"only", "only the cases whose name matches PATTERN (fnmatch:\n'scale_*')", 0, FLAGS_STRING, .text = &o->only,
         .value_name = "PATTERN"},
        {"list", "print the cases' names (quick ones marked) and exit", 0, FLAGS_SWITCH, .on = &o->list},
        {"out", "where the scenes, the runs and the table go (" STRESS_DEFAULT_OUT ")", 0, FLAGS_STRING,
         .text = &o->out, .value_name = "DIR"},
        {"bin", "where the programs are (the directory of this one)", 0, FLAGS_STRING, .text = &o->bin,
         .value_name = "DIR"},
        {"jobs", "programs run at once, also -j N (the processors)", 0, FLAGS_INT, .integer = &o->jobs, .min = 1,
         .max = STRESS_MAX_JOBS, .what = "a count", .value_name = "N"},
        {"timeout", "seconds a program may run before it is killed (" FLAGS_TEXT(STRESS_DEFAULT_TIMEOUT) ")", 0,
         FLAGS_INT, .integer = &o->timeout, .min = 1, .max = STRESS_MAX_TIMEOUT, .what = "seconds",
         .value_name = "S"},
        {"size", "the pictures' size (" FLAGS_TEXT(STRESS_DEFAULT_WIDTH) "x" FLAGS_TEXT(STRESS_DEFAULT_HEIGHT) ")", 0,
         FLAGS_SIZE, .width = &o->width, .height = &o->height},
        {.name = "help", .help = "this text", .kind = FLAGS_HELP},
    };
    int count = (int)(sizeof params / sizeof *params);
    char joined[64];
    stress_jobs_spelling(argc, argv, joined, sizeof joined);
    int status = flags_parse(o->program, params, count, argc - 1, argv + 1);
    if (status == FLAGS_HELP_ASKED) {
        printf("usage: %s [flags]\n"
               "Writes adversarial scenes, runs the reference and every technique configuration\n"
               "on each (subprocesses with --dump), compares them with shadowdiff and writes\n"
               "OUT/table.md and OUT/table.csv. Exit status 0 when every row passes, is refused\n"
               "(one stderr line naming the scene) or unmeasured (planar where no lit ground is\n"
               "seen), 1 otherwise, 2 a bad command line.\n",
               o->program);
        flags_print_help(stdout, params, count, 2, 0);
    }
    return status;
}

int main(int argc, char **argv) {
    char bin[STRESS_DIR_MAX + 1];
    const char *slash = strrchr(argv[0], '/');
    snprintf(bin, sizeof bin, "%.*s", slash ? (int)(slash - argv[0]) : (int)strlen(STRESS_DEFAULT_BIN),
             slash ? argv[0] : STRESS_DEFAULT_BIN);
    stress_options o = {.program = flags_program_name(argv[0]), .out = STRESS_DEFAULT_OUT, .bin = bin};
    int status = stress_parse(argc, argv, &o);
    if (status)
        return status == FLAGS_HELP_ASKED ? 0 : status;
    if (strlen(o.out) > STRESS_DIR_MAX || strlen(o.bin) > STRESS_DIR_MAX)
        return flags_usage_error(o.program, "--out and --bin take at most " FLAGS_TEXT(STRESS_DIR_MAX) " bytes",
                                 NULL);
    o.jobs = o.jobs ? o.jobs : (int)sysconf(_SC_NPROCESSORS_ONLN);
    o.jobs = o.jobs < 1 ? 1 : o.jobs > STRESS_MAX_JOBS ? STRESS_MAX_JOBS : o.jobs;
    o.timeout = o.timeout ? o.timeout : STRESS_DEFAULT_TIMEOUT;
    o.width = o.width ? o.width : STRESS_DEFAULT_WIDTH;
    o.height = o.height ? o.height : STRESS_DEFAULT_HEIGHT;
    int selected = 0;
    for (int i = 0; i < STRESS_CASE_COUNT; i++)
        selected += stress_selected(&o, &stress_cases[i]);
    if (!selected)
        return flags_usage_error(o.program, "no case matches --only", o.only);
    if (o.list) {
        for (int i = 0; i < STRESS_CASE_COUNT; i++)
            if (stress_selected(&o, &stress_cases[i]))
                printf("%s%s\n", stress_cases[i].name, stress_cases[i].quick ? " (quick)" : "");
        return 0;
    }
    struct sigaction on_signal = {.sa_handler = stress_on_signal};
    sigemptyset(&on_signal.sa_mask);
    sigaction(SIGINT, &on_signal, NULL);
    sigaction(SIGTERM, &on_signal, NULL);
    return stress_run(&o);
}
