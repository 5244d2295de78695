/* main of build/scenegen: writes the generated scenes of assets/scenes/
 * (`make scenes`), so that scenes at scale come from code, not by hand:
 *
 *   city_N.json  N objects (boxes, cylinders, spheres) in blocks on one
 *                ground plane (N + 1 objects in all), streets between the
 *                blocks, a street-level camera looking down a street, a sun
 *                and street lamps of limited range, most out of view;
 *   street.json  city_1000 seen down the same street from the city's edge,
 *                into the sun, the far plane across it, a sun and three spot lamps
 *                without a range, so that nothing is culled for being out
 *                of view or out of reach and only what is hidden can be;
 *   dense.json   a field of high-segment spheres and tori on a ground slab,
 *                every mesh closed, over 100k triangles, one light;
 *   stacked_300.json  300 thin slabs stacked under a sun, 256 wide ones
 *                and 44 half as wide above: the ground beside the narrow
 *                ones' shadow lies in exactly 256 shadow volumes, which
 *                the 8-bit stencil counts as 0 (demos/lib/volume_wide.h);
 *   stacked_10000.json  one open mesh (stacked_10000.obj) of 10,000
 *                stacked triangles, 256 of each size, smaller up the
 *                stack: every triangle its own occluder, so the ground
 *                lies in up to 10,000 volumes, in bands of multiples of
 *                256.
 *
 * Deterministic: one seeded PRNG (splitmix64), no clock, numbers rounded
 * to a few decimals, so the files are byte for byte the same on every run
 * and tests/test_scenegen.c can compare them with the committed ones.
 *
 * Every city has the same camera and lamps; its blocks are laid out in
 * square rings around the camera's block, each block drawn from its own
 * coordinates' random stream. A larger city is the smaller one plus more
 * rings, so every city shows the same street once it reaches past the far
 * plane: the sizes compare equal views. */
#include <cJSON.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flags.h"
#include "path.h"

#define SCENEGEN_EXIT_RUNTIME 1
#define SCENEGEN_DEFAULT_OUT "assets/scenes"
#define SCENEGEN_PATH_MAX 4096

/* The seed of every random stream: changing it changes every city. */
#define SCENEGEN_SEED 0x5eed5ce7e5ULL
/* Decimals kept: enough for the layout, few enough to read and diff. */
#define SCENEGEN_DECIMALS 100.0
#define SCENEGEN_DIRECTION_DECIMALS 10000.0

/* ---- the city's layout (world units: metres) ---- */
#define CITY_BLOCK 24.0  /* a block's side */
#define CITY_STREET 12.0 /* a street's width, kerb to kerb */
#define CITY_PITCH (CITY_BLOCK + CITY_STREET)
#define CITY_LOTS 3 /* lots along a block's side: 9 objects a block */
#define CITY_LOT (CITY_BLOCK / CITY_LOTS)
#define CITY_SETBACK_MIN 0.4 /* a building's gap to its lot's edge */
#define CITY_SETBACK_MAX 1.4
#define CITY_BOX_HEIGHT_MIN 5.0
#define CITY_BOX_HEIGHT_MAX 36.0
#define CITY_TOWER_SHARE 0.12 /* of the lots: cylinders */
#define CITY_DOME_SHARE 0.08  /* then spheres */
#define CITY_TOWER_HEIGHT_MIN 12.0
#define CITY_TOWER_HEIGHT_MAX 48.0
#define CITY_SEGMENTS 16    /* cylinders and spheres: cheap, still round */
#define CITY_COLOR_MIN 0.45 /* building colours: light, a little varied */
#define CITY_COLOR_SPREAD 0.4
#define CITY_GROUND_GREY 0.42 /* asphalt */

/* The street the camera looks down is the one between block columns 0
 * and 1 (x = CITY_PITCH / 2); the eye stands a little off its middle, half
 * a block back from the crossing, and looks along -z. */
#define CITY_EYE_HEIGHT 1.7
#define CITY_EYE_X (CITY_PITCH / 2 - 1.0)
#define CITY_EYE_Z 40.0
#define CITY_LOOK_DISTANCE 100.0
#define CITY_LOOK_HEIGHT 6.0 /* a little up, so the tops show */
#define CITY_FOV 40.0
#define CITY_NEAR 0.1
#define CITY_FAR 130.0

/* The street scene: its far plane reaches across the largest ring of
 * city_1000, and its lamps, unranged spots over the street, light far. */
#define STREET_COUNT 1000
/* At the city's edge, looking across it into the sun, so that the
 * shadows come towards the eye. */
#define STREET_EYE_Z -200.0
#define STREET_LOOK 1.0 /* along +z */
#define STREET_FAR 450.0
#define STREET_NEAR 0.5 /* so that the 24-bit depth resolves the far end */
#define STREET_LAMP_INTENSITY 0.5
#define STREET_SPOT_INNER 25.0
#define STREET_SPOT_OUTER 40.0

#define CITY_LAMP_RANGE 14.0
#define CITY_LAMP_INTENSITY 0.8
#define CITY_SPOT_INNER 35.0
#define CITY_SPOT_OUTER 55.0

/* ---- the dense scene ---- */
#define DENSE_GRID 5 /* a 5 x 5 field */
#define DENSE_SPACING 4.5
#define DENSE_SEGMENTS 80 /* about 6,300 triangles a shape */
#define DENSE_SPHERE_RADIUS 1.6
#define DENSE_TORUS_MAJOR 1.5
#define DENSE_TORUS_MINOR 0.6
#define DENSE_TORUS_TILT 60.0 /* degrees about x: they cast on each other */
#define DENSE_HEIGHT 1.8      /* shapes' centres above the ground */
#define DENSE_SLAB 40.0       /* the ground is a closed box, not a plane */
#define DENSE_SLAB_THICKNESS 1.0

/* ---- the stacked scenes ---- */
#define STACKED_SLABS 300
#define STACKED_SLABS_WIDE 256 /* the lower ones; the rest half as wide */
#define STACKED_SLAB 3.0
#define STACKED_SLAB_THICKNESS 0.002
#define STACKED_PITCH 0.004 /* from a slab to the next */
#define STACKED_BASE 3.0    /* the lowest slab's height: the eye sees under it */
#define STACKED_LAYERS 10000
#define STACKED_GROUP 256 /* layers of one size */
#define STACKED_LAYER_PITCH 0.0001
#define STACKED_RADIUS 3.0 /* the lowest group's triangles' corners from the axis */
#define STACKED_SHRINK 0.8 /* of the radius, lost up to the last group */
#define STACKED_OBJ_DECIMALS 5
#define STACKED_GROUND 20.0 /* the ground plane's side */

/* Out of memory anywhere while building a tree sets this: one check at
 * the end instead of one per cJSON call. */
static struct { bool out_of_memory; } scenegen;

/* ---- numbers ---- */

/* splitmix64: one step of the stream. */
static uint64_t scenegen_next(uint64_t *state) {
    uint64_t z = (*state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/* Uniform in [lo, hi), from the top 53 bits. */
static double scenegen_uniform(uint64_t *state, double lo, double hi) {
    return lo + (hi - lo) * (double)(scenegen_next(state) >> 11) * 0x1.0p-53;
}

/* The stream of one block: its own, whatever the city's size. */
static uint64_t scenegen_block_stream(int bx, int bz) {
    uint64_t state = SCENEGEN_SEED ^ ((uint64_t)(uint32_t)bx << 32 | (uint32_t)bz);
    scenegen_next(&state);
    return state;
}

static double scenegen_round(double x, double decimals) { return round(x * decimals) / decimals; }

/* ---- JSON ---- */

static void scenegen_put(cJSON *object, const char *key, cJSON *item) {
    if (!item || !cJSON_AddItemToObject(object, key, item)) {
        cJSON_Delete(item);
        scenegen.out_of_memory = true;
    }
}

static void scenegen_append(cJSON *array, cJSON *item) {
    if (!item || !cJSON_AddItemToArray(array, item)) {
        cJSON_Delete(item);
        scenegen.out_of_memory = true;
    }
}

static void scenegen_vec3(cJSON *object, const char *key, double x, double y, double z, double decimals) {
    const double v[3] = {scenegen_round(x, decimals), scenegen_round(y, decimals), scenegen_round(z, decimals)};
    scenegen_put(object, key, cJSON_CreateDoubleArray(v, 3));
}

static void scenegen_number(cJSON *object, const char *key, double x) {
    scenegen_put(object, key, cJSON_CreateNumber(scenegen_round(x, SCENEGEN_DECIMALS)));
}

static void scenegen_unit(cJSON *object, const char *key, double x, double y, double z) {
    double length = sqrt(x * x + y * y + z * z);
    scenegen_vec3(object, key, x / length, y / length, z / length, SCENEGEN_DIRECTION_DECIMALS);
}

/* A new object: {"name", "mesh": {"kind"}}, its mesh returned in *mesh. */
static cJSON *scenegen_object(cJSON *objects, const char *name, const char *kind, cJSON **mesh) {
    cJSON *o = cJSON_CreateObject();
    scenegen_append(objects, o);
    scenegen_put(o, "name", cJSON_CreateString(name));
    *mesh = cJSON_CreateObject();
    scenegen_put(o, "mesh", *mesh);
    scenegen_put(*mesh, "kind", cJSON_CreateString(kind));
    return o;
}

static cJSON *scenegen_light(cJSON *lights, const char *type, double intensity) {
    cJSON *l = cJSON_CreateObject();
    scenegen_append(lights, l);
    scenegen_put(l, "type", cJSON_CreateString(type));
    scenegen_number(l, "intensity", intensity);
    return l;
}

static void scenegen_camera(cJSON *root, const double eye[3], const double target[3], double fov, double near,
                            double far) {
    cJSON *c = cJSON_CreateObject();
    scenegen_put(root, "camera", c);
    scenegen_vec3(c, "position", eye[0], eye[1], eye[2], SCENEGEN_DECIMALS);
    scenegen_vec3(c, "target", target[0], target[1], target[2], SCENEGEN_DECIMALS);
    scenegen_number(c, "fov", fov);
    scenegen_number(c, "near", near);
    scenegen_number(c, "far", far);
}

/* Writes DIR/NAME with `body` (false where a write failed); false after
 * one line on stderr. */
static bool scenegen_write_file(const char *dir, const char *name, bool (*body)(FILE *f, const void *what),
                                const void *what) {
    char path[SCENEGEN_PATH_MAX];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        return false;
    }
    bool ok = body(f, what);
    if (fclose(f) != 0 || !ok) {
        fprintf(stderr, "%s: cannot write\n", path);
        return false;
    }
    return true;
}

/* Pretty enough to diff: one line per light and per object. */
static bool scenegen_json_body(FILE *f, const void *what) {
    const cJSON *root = what;
    bool ok = fputs("{\n", f) >= 0;
    for (const cJSON *item = root->child; ok && item; item = item->next) {
        bool list = cJSON_IsArray(item) && cJSON_IsObject(item->child);
        ok = fprintf(f, "  \"%s\": %s", item->string, list ? "[\n" : "") >= 0;
        for (const cJSON *part = list ? item->child : item; ok && part; part = list ? part->next : NULL) {
            char *text = cJSON_PrintUnformatted(part);
            ok = text && fprintf(f, "%s%s%s", list ? "    " : "", text, list && part->next ? ",\n" : "") >= 0;
            free(text);
        }
        ok = ok && fprintf(f, "%s%s", list ? "\n  ]" : "", item->next ? ",\n" : "\n") >= 0;
    }
    return ok && fputs("}\n", f) >= 0;
}

static bool scenegen_write(const cJSON *root, const char *dir, const char *name) {
    return scenegen_write_file(dir, name, scenegen_json_body, root);
}

/* ---- the city ---- */

/* The sun of every city: a low afternoon sun from behind on the right,
 * so that the buildings on the right throw long shadows across the
 * street and the crossings let it through. */
static void scenegen_city_sun(cJSON *root, cJSON **lights) {
    scenegen_vec3(root, "ambient", 0.24, 0.25, 0.28, SCENEGEN_DECIMALS);
    *lights = cJSON_CreateArray();
    scenegen_put(root, "lights", *lights);
    cJSON *sun = scenegen_light(*lights, "directional", 1);
    scenegen_unit(sun, "direction", -0.5, -0.65, -0.55);
    scenegen_vec3(sun, "color", 1, 0.95, 0.85, SCENEGEN_DECIMALS);
}

/* The eye at eye_z, looking along z's `look` (1 or -1), near and far. */
static void scenegen_city_camera(cJSON *root, double eye_z, double look, double near, double far) {
    const double eye[3] = {CITY_EYE_X, CITY_EYE_HEIGHT, eye_z};
    const double target[3] = {CITY_EYE_X, CITY_LOOK_HEIGHT, eye_z + look * CITY_LOOK_DISTANCE};
    scenegen_camera(root, eye, target, CITY_FOV, near, far);
}

/* A spot lamp looking straight down; range 0: none. */
static void scenegen_spot(cJSON *lights, double x, double y, double z, double intensity, double range, double inner,
                          double outer) {
    cJSON *l = scenegen_light(lights, "spot", intensity);
    scenegen_vec3(l, "position", x, y, z, SCENEGEN_DECIMALS);
    scenegen_vec3(l, "color", 1, 0.82, 0.6, SCENEGEN_DECIMALS);
    if (range > 0)
        scenegen_number(l, "range", range);
    scenegen_vec3(l, "direction", 0, -1, 0, SCENEGEN_DIRECTION_DECIMALS);
    scenegen_number(l, "inner_angle", inner);
    scenegen_number(l, "outer_angle", outer);
}

/* The camera, the ambient term and the lights: the same in every city. */
static void scenegen_city_setting(cJSON *root) {
    scenegen_city_camera(root, CITY_EYE_Z, -1, CITY_NEAR, CITY_FAR);
    cJSON *lights;
    scenegen_city_sun(root, &lights);
    /* Street lamps on the kerbs: two down the street in view, the others
     * behind the camera or down side streets, out of view. */
    static const struct {
        bool spot;
        double x, y, z;
    } lamps[] = {
        {true, CITY_PITCH / 2 - 5, 6, 18},
        {false, CITY_PITCH / 2 + 5, 4, -14},
        {true, CITY_PITCH / 2 + 5, 6, 78},
        {false, -CITY_PITCH * 1.5, 4, CITY_PITCH / 2 + 4},
        {true, CITY_PITCH * 2.5, 6, -CITY_PITCH / 2 - 4},
        {false, -CITY_PITCH / 2, 4, CITY_PITCH * 2.5},
    };
    for (size_t i = 0; i < sizeof lamps / sizeof *lamps; i++) {
        if (lamps[i].spot) {
            scenegen_spot(lights, lamps[i].x, lamps[i].y, lamps[i].z, CITY_LAMP_INTENSITY, CITY_LAMP_RANGE,
                          CITY_SPOT_INNER, CITY_SPOT_OUTER);
            continue;
        }
        cJSON *l = scenegen_light(lights, "point", CITY_LAMP_INTENSITY);
        scenegen_vec3(l, "position", lamps[i].x, lamps[i].y, lamps[i].z, SCENEGEN_DECIMALS);
        scenegen_vec3(l, "color", 1, 0.82, 0.6, SCENEGEN_DECIMALS);
        scenegen_number(l, "range", CITY_LAMP_RANGE);
    }
}

/* The street scene's: the eye at the city's edge, the far plane across
 * it, three unranged spots down the street, on alternate kerbs. */
static void scenegen_street_setting(cJSON *root) {
    scenegen_city_camera(root, STREET_EYE_Z, STREET_LOOK, STREET_NEAR, STREET_FAR);
    cJSON *lights;
    scenegen_city_sun(root, &lights);
    static const double lamps[][3] = {{CITY_PITCH / 2 - 5, 8, STREET_EYE_Z + STREET_LOOK * 25},
                                      {CITY_PITCH / 2 + 5, 8, STREET_EYE_Z + STREET_LOOK * 70},
                                      {CITY_PITCH / 2 - 5, 8, STREET_EYE_Z + STREET_LOOK * 120}};
    for (size_t i = 0; i < sizeof lamps / sizeof *lamps; i++)
        scenegen_spot(lights, lamps[i][0], lamps[i][1], lamps[i][2], STREET_LAMP_INTENSITY, 0, STREET_SPOT_INNER,
                      STREET_SPOT_OUTER);
}

/* The block `index` in ring order: ring 0 is block (0, 0), ring r the 8r
 * blocks at Chebyshev distance r, walked from its top-left corner round. */
static void scenegen_block_at(int index, int *bx, int *bz, int *ring) {
    int r = 0;
    while ((2 * r + 1) * (2 * r + 1) <= index)
        r++;
    *ring = r;
    if (r == 0) {
        *bx = *bz = 0;
        return;
    }
    int k = index - (2 * r - 1) * (2 * r - 1), side = k / (2 * r), step = k % (2 * r);
    static const int start[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}},
                     walk[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    *bx = start[side][0] * r + walk[side][0] * step;
    *bz = start[side][1] * r + walk[side][1] * step;
}

/* One lot's building: a box mostly, now and then a tower or a dome. */
static void scenegen_lot(cJSON *objects, uint64_t *rng, double cx, double cz, int number) {
    double setback = scenegen_uniform(rng, CITY_SETBACK_MIN, CITY_SETBACK_MAX);
    double width = CITY_LOT - 2 * setback,
           depth = CITY_LOT - 2 * scenegen_uniform(rng, CITY_SETBACK_MIN, CITY_SETBACK_MAX);
    double kind = scenegen_uniform(rng, 0, 1), shape = scenegen_uniform(rng, 0, 1);
    double color[3];
    for (int c = 0; c < 3; c++)
        color[c] = CITY_COLOR_MIN + CITY_COLOR_SPREAD * scenegen_uniform(rng, 0, 1);
    char name[32];
    cJSON *mesh, *o;
    double y;
    if (kind < CITY_TOWER_SHARE) {
        double height = CITY_TOWER_HEIGHT_MIN + (CITY_TOWER_HEIGHT_MAX - CITY_TOWER_HEIGHT_MIN) * shape;
        snprintf(name, sizeof name, "tower_%d", number);
        o = scenegen_object(objects, name, "cylinder", &mesh);
        scenegen_number(mesh, "radius", fmin(width, depth) / 2);
        scenegen_number(mesh, "height", height);
        scenegen_put(mesh, "segments", cJSON_CreateNumber(CITY_SEGMENTS));
        y = height / 2;
    } else if (kind < CITY_TOWER_SHARE + CITY_DOME_SHARE) {
        double radius = fmin(width, depth) / 2;
        snprintf(name, sizeof name, "dome_%d", number);
        o = scenegen_object(objects, name, "sphere", &mesh);
        scenegen_number(mesh, "radius", radius);
        scenegen_put(mesh, "segments", cJSON_CreateNumber(CITY_SEGMENTS));
        y = radius; /* resting on the ground */
    } else {
        /* Squared: many low buildings, a few tall ones. */
        double height = CITY_BOX_HEIGHT_MIN + (CITY_BOX_HEIGHT_MAX - CITY_BOX_HEIGHT_MIN) * shape * shape;
        snprintf(name, sizeof name, "box_%d", number);
        o = scenegen_object(objects, name, "box", &mesh);
        scenegen_vec3(mesh, "size", width, height, depth, SCENEGEN_DECIMALS);
        y = height / 2;
    }
    scenegen_vec3(o, "translate", cx, y, cz, SCENEGEN_DECIMALS);
    scenegen_vec3(o, "color", color[0], color[1], color[2], SCENEGEN_DECIMALS);
}

static cJSON *scenegen_city(int count, void (*setting)(cJSON *root)) {
    cJSON *root = cJSON_CreateObject();
    setting(root);
    cJSON *objects = cJSON_CreateArray();
    scenegen_put(root, "objects", objects);
    cJSON *mesh, *ground = scenegen_object(objects, "ground", "plane", &mesh);
    int made = 0, ring = 0;
    for (int block = 0; made < count; block++) {
        int bx, bz;
        scenegen_block_at(block, &bx, &bz, &ring);
        uint64_t rng = scenegen_block_stream(bx, bz);
        for (int lot = 0; lot < CITY_LOTS * CITY_LOTS && made < count; lot++) {
            double cx = bx * CITY_PITCH + (lot % CITY_LOTS - (CITY_LOTS - 1) / 2.0) * CITY_LOT;
            double cz = bz * CITY_PITCH + (lot / CITY_LOTS - (CITY_LOTS - 1) / 2.0) * CITY_LOT;
            scenegen_lot(objects, &rng, cx, cz, made++);
        }
    }
    /* The ground covers every ring built: the same density at every size. */
    double side = (2 * ring + 1) * CITY_PITCH;
    const double size[2] = {side, side};
    scenegen_put(mesh, "size", cJSON_CreateDoubleArray(size, 2));
    scenegen_vec3(ground, "color", CITY_GROUND_GREY, CITY_GROUND_GREY, CITY_GROUND_GREY + 0.02, SCENEGEN_DECIMALS);
    scenegen_put(ground, "casts", cJSON_CreateFalse());
    return root;
}

/* ---- the dense scene ---- */

/* A scene under one sun (travelling along `sun`): its camera, a grey
 * ambient, the sun, and its empty list of objects in *objects. */
static cJSON *scenegen_sun_scene(const double eye[3], const double target[3], double near, const double sun[3],
                                 cJSON **objects) {
    cJSON *root = cJSON_CreateObject();
    scenegen_camera(root, eye, target, 45, near, 100);
    scenegen_vec3(root, "ambient", 0.15, 0.15, 0.17, SCENEGEN_DECIMALS);
    cJSON *lights = cJSON_CreateArray();
    scenegen_put(root, "lights", lights);
    scenegen_unit(scenegen_light(lights, "directional", 0.9), "direction", sun[0], sun[1], sun[2]);
    *objects = cJSON_CreateArray();
    scenegen_put(root, "objects", *objects);
    return root;
}

static cJSON *scenegen_dense(void) {
    const double eye[3] = {0, 17, 25}, target[3] = {0, 0, 1}, sun[3] = {-0.6, -0.7, -0.4};
    cJSON *objects, *root = scenegen_sun_scene(eye, target, 0.5, sun, &objects);
    cJSON *mesh, *slab = scenegen_object(objects, "ground", "box", &mesh);
    scenegen_vec3(mesh, "size", DENSE_SLAB, DENSE_SLAB_THICKNESS, DENSE_SLAB, SCENEGEN_DECIMALS);
    scenegen_vec3(slab, "translate", 0, -DENSE_SLAB_THICKNESS / 2, 0, SCENEGEN_DECIMALS);
    scenegen_vec3(slab, "color", 0.75, 0.75, 0.72, SCENEGEN_DECIMALS);
    scenegen_put(slab, "casts", cJSON_CreateFalse());
    uint64_t rng = SCENEGEN_SEED;
    for (int i = 0; i < DENSE_GRID * DENSE_GRID; i++) {
        double x = (i % DENSE_GRID - (DENSE_GRID - 1) / 2.0) * DENSE_SPACING;
        double z = (i / DENSE_GRID - (DENSE_GRID - 1) / 2.0) * DENSE_SPACING;
        bool torus = i % 2;
        char name[32];
        snprintf(name, sizeof name, "%s_%d", torus ? "torus" : "sphere", i);
        cJSON *o = scenegen_object(objects, name, torus ? "torus" : "sphere", &mesh);
        if (torus) {
            scenegen_number(mesh, "major_radius", DENSE_TORUS_MAJOR);
            scenegen_number(mesh, "minor_radius", DENSE_TORUS_MINOR);
        } else {
            scenegen_number(mesh, "radius", DENSE_SPHERE_RADIUS);
        }
        scenegen_put(mesh, "segments", cJSON_CreateNumber(DENSE_SEGMENTS));
        scenegen_vec3(o, "translate", x, DENSE_HEIGHT, z, SCENEGEN_DECIMALS);
        if (torus)
            scenegen_vec3(o, "rotate", DENSE_TORUS_TILT, scenegen_uniform(&rng, 0, 180), 0, SCENEGEN_DECIMALS);
        scenegen_vec3(o, "color", scenegen_uniform(&rng, 0.3, 0.9), scenegen_uniform(&rng, 0.3, 0.9),
                      scenegen_uniform(&rng, 0.3, 0.9), SCENEGEN_DECIMALS);
    }
    return root;
}

/* ---- the stacked scenes ---- */

/* Their ground, sun and camera (low, looking under the stack). */
static cJSON *scenegen_stacked_setting(cJSON **objects) {
    const double eye[3] = {5.5, 3.2, 6.5}, target[3] = {0.6, 1.2, 0.4}, sun[3] = {0.4, -1.0, 0.25};
    const double size[2] = {STACKED_GROUND, STACKED_GROUND};
    cJSON *root = scenegen_sun_scene(eye, target, 0.1, sun, objects);
    cJSON *mesh, *ground = scenegen_object(*objects, "ground", "plane", &mesh);
    scenegen_put(mesh, "size", cJSON_CreateDoubleArray(size, 2));
    scenegen_vec3(ground, "color", 0.8, 0.8, 0.78, SCENEGEN_DECIMALS);
    scenegen_put(ground, "casts", cJSON_CreateFalse());
    return root;
}

static cJSON *scenegen_stacked_slabs(void) {
    cJSON *objects, *mesh, *root = scenegen_stacked_setting(&objects);
    for (int i = 0; i < STACKED_SLABS; i++) {
        char name[32];
        snprintf(name, sizeof name, "slab_%03d", i);
        cJSON *o = scenegen_object(objects, name, "box", &mesh);
        double side = i < STACKED_SLABS_WIDE ? STACKED_SLAB : STACKED_SLAB / 2;
        scenegen_vec3(mesh, "size", side, STACKED_SLAB_THICKNESS, side, SCENEGEN_DIRECTION_DECIMALS);
        scenegen_vec3(o, "translate", 0, STACKED_BASE + i * STACKED_PITCH, 0, SCENEGEN_DIRECTION_DECIMALS);
        scenegen_vec3(o, "color", 0.3 + 0.4 * i / STACKED_SLABS, 0.45, 0.7 - 0.4 * i / STACKED_SLABS,
                      SCENEGEN_DECIMALS);
        scenegen_put(o, "receives", cJSON_CreateFalse());
    }
    return root;
}

/* The 10,000 triangles as an OBJ beside the scene: layer i a triangle
 * round the axis at its height, its group's radius. */
static bool scenegen_stacked_obj_body(FILE *f, const void *what) {
    (void)what;
    bool ok =
        fprintf(f, "# %d stacked triangles, %d of each size (build/scenegen)\n", STACKED_LAYERS, STACKED_GROUP) >= 0;
    int groups = (STACKED_LAYERS + STACKED_GROUP - 1) / STACKED_GROUP;
    for (int i = 0; ok && i < STACKED_LAYERS; i++) {
        double radius = STACKED_RADIUS * (1 - STACKED_SHRINK * (i / STACKED_GROUP) / (groups - 1));
        double y = STACKED_BASE + i * STACKED_LAYER_PITCH;
        for (int k = 0; ok && k < 3; k++) {
            double angle = (90.0 + 120.0 * k) * M_PI / 180.0;
            ok = fprintf(f, "v %.*f %.*f %.*f\n", STACKED_OBJ_DECIMALS, radius * cos(angle), STACKED_OBJ_DECIMALS, y,
                         STACKED_OBJ_DECIMALS, -radius * sin(angle)) >= 0;
        }
    }
    for (int i = 0; ok && i < STACKED_LAYERS; i++)
        ok = fprintf(f, "f %d %d %d\n", 3 * i + 1, 3 * i + 2, 3 * i + 3) >= 0;
    return ok;
}

static cJSON *scenegen_stacked_mesh(const char *obj) {
    cJSON *objects, *mesh, *root = scenegen_stacked_setting(&objects);
    cJSON *o = scenegen_object(objects, "stack", "model", &mesh);
    scenegen_put(mesh, "path", cJSON_CreateString(obj));
    scenegen_vec3(o, "color", 0.35, 0.5, 0.75, SCENEGEN_DECIMALS);
    scenegen_put(o, "receives", cJSON_CreateFalse());
    return root;
}

/* ---- main ---- */

static const int scenegen_city_counts[] = {100, 300, 1000, 3000};

static bool scenegen_emit(cJSON *root, const char *dir, const char *name) {
    bool ok = root && !scenegen.out_of_memory;
    if (!ok)
        fprintf(stderr, "scenegen: out of memory building %s\n", name);
    ok = ok && scenegen_write(root, dir, name);
    cJSON_Delete(root);
    return ok;
}

static bool scenegen_run(const char *dir) {
    bool ok = path_make_directories(dir);
    for (size_t i = 0; ok && i < sizeof scenegen_city_counts / sizeof *scenegen_city_counts; i++) {
        char name[32];
        snprintf(name, sizeof name, "city_%d.json", scenegen_city_counts[i]);
        ok = scenegen_emit(scenegen_city(scenegen_city_counts[i], scenegen_city_setting), dir, name);
    }
    return ok && scenegen_emit(scenegen_city(STREET_COUNT, scenegen_street_setting), dir, "street.json") &&
           scenegen_emit(scenegen_dense(), dir, "dense.json") &&
           scenegen_emit(scenegen_stacked_slabs(), dir, "stacked_300.json") &&
           scenegen_write_file(dir, "stacked_10000.obj", scenegen_stacked_obj_body, NULL) &&
           scenegen_emit(scenegen_stacked_mesh("stacked_10000.obj"), dir, "stacked_10000.json");
}

int main(int argc, char **argv) {
    const char *program = flags_program_name(argv[0]), *out = NULL;
    const flags_param params[] = {
        {"out", "the directory to write them to (" SCENEGEN_DEFAULT_OUT ")", 0, FLAGS_STRING, .text = &out,
         .value_name = "DIR"},
        {.name = "help", .help = "this text", .kind = FLAGS_HELP},
    };
    int count = (int)(sizeof params / sizeof *params);
    int status = flags_parse(program, params, count, argc - 1, argv + 1);
    if (status == FLAGS_HELP_ASKED) {
        printf("usage: %s [flags]\n"
               "Writes the generated scenes, the same bytes on every run: city_100, city_300,\n"
               "city_1000 and city_3000.json (that many objects plus the ground), street.json\n"
               "(city_1000 seen to the far side, unranged lamps), dense.json, and stacked_300.json\n"
               "and stacked_10000.json (with its .obj), deeper than the 8-bit stencil counts.\n",
               program);
        flags_print_help(stdout, params, count, 2, 0);
        return 0;
    }
    if (status)
        return status;
    return scenegen_run(out ? out : SCENEGEN_DEFAULT_OUT) ? 0 : SCENEGEN_EXIT_RUNTIME;
}
