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
 *   lamps_64.json  city_300 at night: 64 point lamps of limited range on
 *                poles along both kerbs of the street the camera looks
 *                down and of the street that crosses it, no sun: many
 *                shadowed lights, each lighting a small part of the frame;
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
 *                256;
 *   fence.gltf   a fence of boards and a tree whose crown is leaf cards,
 *                cut out by their textures' alpha, under a low sun;
 *   stained_glass.gltf  two overlapping panes of coloured glass and a
 *                window of four colours, translucent, and a box, under a
 *                spot: coloured shadows. The glTF files hold their
 *                buffers and textures (common/data/gltf_write.h).
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
#include "gltf_write.h"
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

/* The night street: LAMPS_PER_KERB lamps a kerb, LAMPS_SPACING apart,
 * centred on the crossing in front of the eye, each on a pole at the
 * kerb with its lamp on an arm over the street (the pole casts, the lamp
 * is outside it). */
#define LAMPS_COUNT 300
#define LAMPS_PER_KERB 16
#define LAMPS_SPACING 12.0
#define LAMPS_KERB_OFFSET (CITY_STREET / 2 - 0.5) /* a pole's distance from the street's middle */
#define LAMPS_ARM 1.2                             /* the lamp's, from its pole, over the street */
#define LAMPS_HEIGHT 6.0
#define LAMPS_POLE_RADIUS 0.12
#define LAMPS_POLE_SEGMENTS 8
#define LAMPS_RANGE 14.0
#define LAMPS_INTENSITY 0.9
#define LAMPS_AMBIENT 0.06

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

/* ---- the glTF scenes (world units: metres) ---- */
#define GLTF_MAX_VERTICES 4096 /* of one mesh */
#define GLTF_MAX_INDICES 8192
#define GLTF_ASPECT (16.0 / 9.0)
#define GLTF_NEAR 0.1
#define GLTF_FAR 50.0
/* fence.gltf: a fence of boards (a texture whose gaps are cut out) and a
 * tree whose crown is leaf cards (each a leaf cut out of its square),
 * under a low sun from behind the fence. */
#define FENCE_GROUND 16.0
#define FENCE_BOARDS_W 64 /* the boards' texture: a board 5 texels wide every 8, a rail across the middle */
#define FENCE_BOARDS_H 16
#define FENCE_BOARD_PITCH 8
#define FENCE_BOARD_WIDTH 5
#define FENCE_RAIL_FROM 6
#define FENCE_RAIL_TO 9
#define FENCE_CUTOFF 0.4f
#define FENCE_LEFT (-4.0)
#define FENCE_RIGHT 2.0
#define FENCE_HEIGHT 1.5
#define FENCE_REPEATS 3.0  /* the texture along the fence */
#define FENCE_LEAF_SIZE 32 /* the leaf's texture: a disc with a notch */
#define FENCE_LEAF_RADIUS 14.0
#define FENCE_LEAF_NOTCH 2.5
#define FENCE_TRUNK_HEIGHT 2.4
#define FENCE_TRUNK_HALF 0.15
#define FENCE_LEAVES 90
#define FENCE_CARD_HALF 0.22
#define FENCE_CROWN_RADIUS 1.3
static const double fence_tree[3] = {3.5, 0, -1.5};
#define FENCE_CROWN_HEIGHT 3.2
/* stained_glass.gltf: a red pane over a blue one, overlapping, a window
 * of four colours (a texture of their colours and alphas) and an opaque
 * box, translucent (alphaMode BLEND) but the box, under a spot. */
#define GLASS_GROUND 12.0
#define GLASS_SIZE 8 /* the window's texture: four panes of 4x4 texels */
#define GLASS_SPOT_INTENSITY 40.0
#define GLASS_SPOT_INNER 0.6 /* radians */
#define GLASS_SPOT_OUTER 0.95

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

/* The night street's: the city's camera, a faint ambient term, and
 * 64 point lamps on poles along the kerbs of the street the eye looks
 * down (x = CITY_PITCH / 2) and of the one crossing it in front
 * (z = -CITY_PITCH / 2). */
static void scenegen_lamps_setting(cJSON *root) {
    scenegen_city_camera(root, CITY_EYE_Z, -1, CITY_NEAR, CITY_FAR);
    scenegen_vec3(root, "ambient", LAMPS_AMBIENT, LAMPS_AMBIENT, LAMPS_AMBIENT * 1.3, SCENEGEN_DECIMALS);
    cJSON *lights = cJSON_CreateArray();
    scenegen_put(root, "lights", lights);
    cJSON *objects = cJSON_CreateArray();
    scenegen_put(root, "objects", objects);
    const double street_x = CITY_PITCH / 2, street_z = -CITY_PITCH / 2;
    int number = 0;
    for (int street = 0; street < 2; street++)
        for (int kerb = -1; kerb <= 1; kerb += 2)
            for (int i = 0; i < LAMPS_PER_KERB; i++) {
                /* Along the street, staggered half a spacing on one kerb. */
                double along = (i - (LAMPS_PER_KERB - 1) / 2.0 + (kerb > 0 ? 0.25 : -0.25)) * LAMPS_SPACING;
                double across = kerb * LAMPS_KERB_OFFSET, arm = -kerb * LAMPS_ARM;
                double pole[2] = {street_x + across, street_z + along}, lamp[2] = {pole[0] + arm, pole[1]};
                if (street == 1) {
                    pole[0] = street_x + along;
                    pole[1] = street_z + across;
                    lamp[0] = pole[0];
                    lamp[1] = pole[1] + arm;
                }
                cJSON *l = scenegen_light(lights, "point", LAMPS_INTENSITY);
                scenegen_vec3(l, "position", lamp[0], LAMPS_HEIGHT, lamp[1], SCENEGEN_DECIMALS);
                scenegen_vec3(l, "color", 1, 0.82, 0.6, SCENEGEN_DECIMALS);
                scenegen_number(l, "range", LAMPS_RANGE);
                char name[32];
                cJSON *mesh;
                snprintf(name, sizeof name, "pole_%d", number++);
                cJSON *o = scenegen_object(objects, name, "cylinder", &mesh);
                scenegen_number(mesh, "radius", LAMPS_POLE_RADIUS);
                scenegen_number(mesh, "height", LAMPS_HEIGHT + 0.5);
                scenegen_put(mesh, "segments", cJSON_CreateNumber(LAMPS_POLE_SEGMENTS));
                scenegen_vec3(o, "translate", pole[0], (LAMPS_HEIGHT + 0.5) / 2, pole[1], SCENEGEN_DECIMALS);
                scenegen_vec3(o, "color", 0.3, 0.32, 0.3, SCENEGEN_DECIMALS);
            }
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
    cJSON *objects = cJSON_GetObjectItem(root, "objects"); /* a setting may have put some */
    if (!objects) {
        objects = cJSON_CreateArray();
        scenegen_put(root, "objects", objects);
    }
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

/* ---- the glTF scenes ---- */

/* One mesh's vertices and triangles as they are built. */
typedef struct scenegen_mesh {
    gltf_vertex vertices[GLTF_MAX_VERTICES];
    uint16_t indices[GLTF_MAX_INDICES];
    int vertex_count, index_count;
} scenegen_mesh;

/* A square's corners about its centre along its two edges, counter-
 * clockwise. */
static const double scenegen_quad_corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};

/* A quad of corners c (counter-clockwise seen from its normal's side)
 * and texture coordinates uv. */
static void scenegen_quad(scenegen_mesh *m, const double c[4][3], const double uv[4][2]) {
    double e1[3], e2[3], n[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = c[1][k] - c[0][k];
        e2[k] = c[2][k] - c[0][k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double length = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    uint16_t first = (uint16_t)m->vertex_count;
    for (int v = 0; v < 4; v++) {
        gltf_vertex *out = &m->vertices[m->vertex_count++];
        for (int k = 0; k < 3; k++) {
            out->position[k] = (float)scenegen_round(c[v][k], SCENEGEN_DIRECTION_DECIMALS);
            out->normal[k] = (float)scenegen_round(n[k] / length, SCENEGEN_DIRECTION_DECIMALS);
        }
        out->uv[0] = (float)uv[v][0];
        out->uv[1] = (float)uv[v][1];
    }
    static const int corners[6] = {0, 1, 2, 0, 2, 3};
    for (int k = 0; k < 6; k++)
        m->indices[m->index_count++] = (uint16_t)(first + corners[k]);
}

/* A quad of the unit square's texture coordinates, v down. */
static void scenegen_square(scenegen_mesh *m, const double c[4][3]) {
    static const double uv[4][2] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    scenegen_quad(m, c, uv);
}

/* A horizontal quad at height y over [x0, x1] x [z0, z1], facing up. */
static void scenegen_level(scenegen_mesh *m, double x0, double x1, double y, double z0, double z1) {
    const double c[4][3] = {{x0, y, z1}, {x1, y, z1}, {x1, y, z0}, {x0, y, z0}};
    scenegen_square(m, c);
}

/* An axis-aligned box of half-sizes h about `centre`. */
static void scenegen_box(scenegen_mesh *m, const double centre[3], const double h[3]) {
    /* Each face: its normal's axis and sign; the quad's corners go round
     * it counter-clockwise seen from outside. */
    for (int axis = 0; axis < 3; axis++)
        for (int sign = -1; sign <= 1; sign += 2) {
            int u = (axis + 1) % 3, v = (axis + 2) % 3;
            double c[4][3];
            for (int q = 0; q < 4; q++) {
                c[q][axis] = centre[axis] + sign * h[axis];
                c[q][u] = centre[u] + scenegen_quad_corners[q][0] * h[u] * sign;
                c[q][v] = centre[v] + scenegen_quad_corners[q][1] * h[v];
            }
            scenegen_square(m, c);
        }
}

/* The mesh into the file as a node named `name` of `material`. */
static void scenegen_put_mesh(gltf_write *w, const char *name, const scenegen_mesh *m, int material) {
    int mesh = gltf_write_mesh(w, m->vertices, m->vertex_count, m->indices, m->index_count, material);
    gltf_write_mesh_node(w, name, mesh);
}

static void scenegen_texel(unsigned char *rgba, int width, int x, int y, const unsigned char texel[4]) {
    memcpy(rgba + 4 * ((size_t)y * (size_t)width + (size_t)x), texel, 4);
}

static cJSON *scenegen_fence(void) {
    gltf_write *w = gltf_write_begin("build/scenegen: a fence of boards and a tree of leaf cards, cut out by their "
                                     "textures' alpha (alphaMode MASK), under a low sun");
    if (!w)
        return NULL;
    static unsigned char boards[FENCE_BOARDS_H][FENCE_BOARDS_W][4], leaf[FENCE_LEAF_SIZE][FENCE_LEAF_SIZE][4];
    static const unsigned char wood[4] = {150, 110, 70, 255}, green[4] = {60, 140, 50, 255}, none[4] = {0, 0, 0, 0};
    for (int y = 0; y < FENCE_BOARDS_H; y++)
        for (int x = 0; x < FENCE_BOARDS_W; x++) {
            bool solid = x % FENCE_BOARD_PITCH < FENCE_BOARD_WIDTH || (y >= FENCE_RAIL_FROM && y < FENCE_RAIL_TO);
            scenegen_texel(&boards[0][0][0], FENCE_BOARDS_W, x, y, solid ? wood : none);
        }
    for (int y = 0; y < FENCE_LEAF_SIZE; y++)
        for (int x = 0; x < FENCE_LEAF_SIZE; x++) {
            double dx = x - (FENCE_LEAF_SIZE - 1) / 2.0, dy = y - (FENCE_LEAF_SIZE - 1) / 2.0;
            bool inside =
                dx * dx + dy * dy < FENCE_LEAF_RADIUS * FENCE_LEAF_RADIUS && !(fabs(dx) < FENCE_LEAF_NOTCH && dy < 0);
            scenegen_texel(&leaf[0][0][0], FENCE_LEAF_SIZE, x, y, inside ? green : none);
        }
    int boards_texture = gltf_write_texture(w, FENCE_BOARDS_W, FENCE_BOARDS_H, &boards[0][0][0], false);
    int leaf_texture = gltf_write_texture(w, FENCE_LEAF_SIZE, FENCE_LEAF_SIZE, &leaf[0][0][0], true);
    int grass =
        gltf_write_material(w, &(gltf_material){.name = "grass", .color = {0.62f, 0.72f, 0.5f, 1}, .texture = -1});
    int bark =
        gltf_write_material(w, &(gltf_material){.name = "bark", .color = {0.35f, 0.25f, 0.18f, 1}, .texture = -1});
    int wood_material = gltf_write_material(
        w, &(gltf_material){"boards", {1, 1, 1, 1}, boards_texture, GLTF_MASK, FENCE_CUTOFF, .double_sided = true});
    int leaf_material =
        gltf_write_material(w, &(gltf_material){"leaf", {1, 1, 1, 1}, leaf_texture, GLTF_MASK, .double_sided = true});

    static scenegen_mesh m;
    m = (scenegen_mesh){0};
    scenegen_level(&m, -FENCE_GROUND / 2, FENCE_GROUND / 2, 0, -FENCE_GROUND / 2, FENCE_GROUND / 2);
    scenegen_put_mesh(w, "ground", &m, grass);
    m = (scenegen_mesh){0};
    const double fence[4][3] = {
        {FENCE_LEFT, 0, 0}, {FENCE_RIGHT, 0, 0}, {FENCE_RIGHT, FENCE_HEIGHT, 0}, {FENCE_LEFT, FENCE_HEIGHT, 0}};
    const double fence_uv[4][2] = {{0, 1}, {FENCE_REPEATS, 1}, {FENCE_REPEATS, 0}, {0, 0}};
    scenegen_quad(&m, fence, fence_uv);
    scenegen_put_mesh(w, "fence", &m, wood_material);
    m = (scenegen_mesh){0};
    const double trunk[3] = {fence_tree[0], FENCE_TRUNK_HEIGHT / 2, fence_tree[2]};
    scenegen_box(&m, trunk, (const double[3]){FENCE_TRUNK_HALF, FENCE_TRUNK_HEIGHT / 2, FENCE_TRUNK_HALF});
    scenegen_put_mesh(w, "trunk", &m, bark);
    /* The crown: each card's centre uniform in a ball, its normal
     * uniform on the sphere, its edges any two perpendicular to it. */
    m = (scenegen_mesh){0};
    uint64_t rng = SCENEGEN_SEED;
    for (int i = 0; i < FENCE_LEAVES; i++) {
        double p[3], n[3], t[3], b[3];
        do {
            for (int k = 0; k < 3; k++)
                p[k] = scenegen_uniform(&rng, -1, 1);
        } while (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] > 1);
        double z = scenegen_uniform(&rng, -1, 1), angle = scenegen_uniform(&rng, 0, 2 * M_PI);
        n[0] = sqrt(1 - z * z) * cos(angle), n[1] = z, n[2] = sqrt(1 - z * z) * sin(angle);
        const double *helper = fabs(n[1]) < 0.9 ? (const double[3]){0, 1, 0} : (const double[3]){1, 0, 0};
        t[0] = helper[1] * n[2] - helper[2] * n[1];
        t[1] = helper[2] * n[0] - helper[0] * n[2];
        t[2] = helper[0] * n[1] - helper[1] * n[0];
        double length = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
        for (int k = 0; k < 3; k++)
            t[k] /= length;
        b[0] = n[1] * t[2] - n[2] * t[1], b[1] = n[2] * t[0] - n[0] * t[2], b[2] = n[0] * t[1] - n[1] * t[0];
        double c[4][3];
        for (int q = 0; q < 4; q++)
            for (int k = 0; k < 3; k++)
                c[q][k] = fence_tree[k] + (k == 1 ? FENCE_CROWN_HEIGHT : 0) + FENCE_CROWN_RADIUS * p[k] +
                          FENCE_CARD_HALF * (scenegen_quad_corners[q][0] * t[k] + scenegen_quad_corners[q][1] * b[k]);
        scenegen_square(&m, c);
    }
    scenegen_put_mesh(w, "leaves", &m, leaf_material);
    const double eye[3] = {1.5, 3.2, 9.0}, target[3] = {0.5, 1.0, -1.0};
    gltf_write_camera(w, "camera", eye, target, 0.8, GLTF_ASPECT, GLTF_NEAR, GLTF_FAR);
    gltf_write_light(w, "sun", "directional", (const float[3]){1, 0.97f, 0.92f}, 3, 0, 0,
                     &(gltf_place){.look = {-0.25, -0.62, 0.75}});
    return gltf_write_end(w);
}

static cJSON *scenegen_stained_glass(void) {
    gltf_write *w = gltf_write_begin("build/scenegen: two overlapping panes of coloured glass, a stained-glass "
                                     "window of four colours and an opaque box over a ground, translucent "
                                     "(alphaMode BLEND), under a spot");
    if (!w)
        return NULL;
    static const unsigned char panes[4][4] = {
        {255, 210, 40, 150}, {40, 110, 255, 210}, {60, 200, 80, 120}, {230, 60, 200, 230}};
    unsigned char window[GLASS_SIZE][GLASS_SIZE][4];
    for (int y = 0; y < GLASS_SIZE; y++)
        for (int x = 0; x < GLASS_SIZE; x++)
            scenegen_texel(&window[0][0][0], GLASS_SIZE, x, y,
                           panes[x / (GLASS_SIZE / 2) + 2 * (y / (GLASS_SIZE / 2))]);
    int window_texture = gltf_write_texture(w, GLASS_SIZE, GLASS_SIZE, &window[0][0][0], true);
    const gltf_material materials[] = {
        {.name = "floor", .color = {0.85f, 0.85f, 0.82f, 1}, .texture = -1},
        {"red", {0.95f, 0.15f, 0.1f, 0.7f}, -1, GLTF_BLEND, .double_sided = true},
        {"blue", {0.2f, 0.35f, 0.95f, 0.6f}, -1, GLTF_BLEND, .double_sided = true},
        {"stained", {1, 1, 1, 1}, window_texture, GLTF_BLEND, .double_sided = true},
        {.name = "stone", .color = {0.6f, 0.6f, 0.65f, 1}, .texture = -1},
    };
    int material[sizeof materials / sizeof *materials];
    for (size_t i = 0; i < sizeof materials / sizeof *materials; i++)
        material[i] = gltf_write_material(w, &materials[i]);
    static scenegen_mesh m;
    m = (scenegen_mesh){0};
    scenegen_level(&m, -GLASS_GROUND / 2, GLASS_GROUND / 2, 0, -GLASS_GROUND / 2, GLASS_GROUND / 2);
    scenegen_put_mesh(w, "ground", &m, material[0]);
    m = (scenegen_mesh){0};
    scenegen_level(&m, -2, 0.5, 2.5, -1, 1);
    scenegen_put_mesh(w, "red_glass", &m, material[1]);
    m = (scenegen_mesh){0};
    scenegen_level(&m, -0.5, 2, 2.0, -1, 1);
    scenegen_put_mesh(w, "blue_glass", &m, material[2]);
    m = (scenegen_mesh){0};
    scenegen_level(&m, -3, -1.2, 1.5, 1.4, 3.2);
    scenegen_put_mesh(w, "window", &m, material[3]);
    m = (scenegen_mesh){0};
    scenegen_box(&m, (const double[3]){2.2, 0.5, 2.2}, (const double[3]){0.5, 0.5, 0.5});
    scenegen_put_mesh(w, "box", &m, material[4]);
    const double eye[3] = {0.5, 7.5, 8.5}, target[3] = {0, 0, 0};
    gltf_write_camera(w, "camera", eye, target, 0.8, GLTF_ASPECT, GLTF_NEAR, GLTF_FAR);
    gltf_write_light(w, "spot", "spot", (const float[3]){1, 1, 1}, GLASS_SPOT_INTENSITY, GLASS_SPOT_INNER,
                     GLASS_SPOT_OUTER, &(gltf_place){{0.3, 5.5, 0.4}, {0, -1, 0.05}});
    return gltf_write_end(w);
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
           scenegen_emit(scenegen_city(LAMPS_COUNT, scenegen_lamps_setting), dir, "lamps_64.json") &&
           scenegen_emit(scenegen_dense(), dir, "dense.json") &&
           scenegen_emit(scenegen_stacked_slabs(), dir, "stacked_300.json") &&
           scenegen_write_file(dir, "stacked_10000.obj", scenegen_stacked_obj_body, NULL) &&
           scenegen_emit(scenegen_stacked_mesh("stacked_10000.obj"), dir, "stacked_10000.json") &&
           scenegen_emit(scenegen_fence(), dir, "fence.gltf") &&
           scenegen_emit(scenegen_stained_glass(), dir, "stained_glass.gltf");
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
               "(city_1000 seen to the far side, unranged lamps), lamps_64.json (city_300 at night\n"
               "under 64 shadowed point lamps), dense.json, and stacked_300.json\n"
               "and stacked_10000.json (with its .obj), deeper than the 8-bit stencil counts, and the\n"
               "glTF scenes fence.gltf (cut-out boards and leaves) and stained_glass.gltf (translucent panes).\n",
               program);
        flags_print_help(stdout, params, count, 2, 0);
        return 0;
    }
    if (status)
        return status;
    return scenegen_run(out ? out : SCENEGEN_DEFAULT_OUT) ? 0 : SCENEGEN_EXIT_RUNTIME;
}
