/* scene: loads the JSON scene files described in scene.h. Every reader
 * reports its own problem and returns false; scene_load then frees what was
 * built, so the first problem is the only line printed. */
#include "scene.h"

#include <cglm/cglm.h>
#include <cjson/cJSON.h>
#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>
#include <string.h>
#include <strings.h>

#include "json.h"
#include "mesh_point.h"
#include "path.h"
#include "scene_internal.h"

/* Far beyond any hand-written scene: a wrong path (a device, a huge file)
 * must not be read whole. */
#define SCENE_MAX_FILE_SIZE (16u << 20)

typedef enum scene_range {
    SCENE_ANY,
    SCENE_NON_NEGATIVE,
    SCENE_POSITIVE,
    SCENE_NON_ZERO,
} scene_range;

/* The most keys one kind of light or mesh takes (a spot light). */
#define SCENE_VARIANT_MAX_KEYS 9

/* One value of a "type" or "kind" field, with the keys an object of that
 * type may hold. */
typedef struct scene_variant {
    const char *name;
    int value;
    const char *keys[SCENE_VARIANT_MAX_KEYS + 1]; /* NULL-terminated */
} scene_variant;

static const scene_variant scene_light_types[] = {
    {"point", SCENE_LIGHT_POINT, {"type", "position", "color", "intensity", "radius", "range", NULL}},
    {"spot",
     SCENE_LIGHT_SPOT,
     {"type", "position", "direction", "color", "intensity", "inner_angle", "outer_angle", "radius", "range", NULL}},
    {"directional", SCENE_LIGHT_DIRECTIONAL, {"type", "direction", "color", "intensity", "radius", NULL}},
    {NULL, 0, {NULL}},
};

/* The mesh kind "gltf": not an object's kind but a file of objects
 * (scene_include_gltf), each of kind SCENE_MESH_MODEL. */
#define SCENE_MESH_GLTF_FILE (-1)

static const scene_variant scene_mesh_kinds[] = {
    {"plane", SCENE_MESH_PLANE, {"kind", "size", NULL}},
    {"box", SCENE_MESH_BOX, {"kind", "size", NULL}},
    {"sphere", SCENE_MESH_SPHERE, {"kind", "radius", "segments", NULL}},
    {"torus", SCENE_MESH_TORUS, {"kind", "major_radius", "minor_radius", "segments", NULL}},
    {"cylinder", SCENE_MESH_CYLINDER, {"kind", "radius", "height", "segments", NULL}},
    {"model", SCENE_MESH_MODEL, {"kind", "path", NULL}},
    {"gltf", SCENE_MESH_GLTF_FILE, {"kind", "path", NULL}},
    {NULL, 0, {NULL}},
};

/* One JSON number less `offset` (subtracted in double, before the
 * rounding to float: see scene.h, "Large worlds"), as a float in the
 * range. */
static bool scene_number(const char *file, const char *where, const char *key, const cJSON *item, scene_range range,
                         double offset, float *out) {
    if (!cJSON_IsNumber(item)) {
        return json_fail(file, where, key, "expected a number, got %s", json_kind(item));
    }
    /* cJSON turns 1e999 into infinity; converting past FLT_MAX is undefined. */
    if (!(fabs(item->valuedouble) <= FLT_MAX && fabs(item->valuedouble - offset) <= FLT_MAX)) {
        return json_fail(file, where, key, "must be a finite number (got %g)", item->valuedouble);
    }
    float value = (float)(item->valuedouble - offset);
    if (range == SCENE_POSITIVE && !(value > 0)) {
        return json_fail(file, where, key, "must be positive (got %g)", item->valuedouble);
    }
    if (range == SCENE_NON_NEGATIVE && value < 0) {
        return json_fail(file, where, key, "must not be negative (got %g)", item->valuedouble);
    }
    /* The float, not the double: 1e-50 is 0 once stored. */
    if (range == SCENE_NON_ZERO && value == 0) {
        return json_fail(file, where, key, "must not be zero: it flattens the object (got %g)", item->valuedouble);
    }
    *out = value;
    return true;
}

static bool scene_read_float(const char *file, const cJSON *object, const char *where, const char *key, bool required,
                             scene_range range, float *out) {
    const cJSON *item;
    if (!json_lookup(file, object, where, key, required, &item))
        return false;
    return !item || scene_number(file, where, key, item, range, 0, out);
}

/* An array of exactly count numbers: every vector field. A point's
 * coordinates come less the scene's origin (offset, count of them; NULL
 * for none). */
static bool scene_read_floats(const char *file, const cJSON *object, const char *where, const char *key,
                              bool required, scene_range range, const double *offset, float *out, int count) {
    const cJSON *item;
    if (!json_lookup(file, object, where, key, required, &item))
        return false;
    if (!item)
        return true;
    if (!cJSON_IsArray(item) || cJSON_GetArraySize(item) != count) {
        return json_fail(file, where, key, "expected an array of %d numbers", count);
    }
    for (int i = 0; i < count; i++) {
        char element[80];
        snprintf(element, sizeof element, "%s[%d]", key, i);
        if (!scene_number(file, where, element, cJSON_GetArrayItem(item, i), range, offset ? offset[i] : 0, &out[i]))
            return false;
    }
    return true;
}

/* Reads a "type" or "kind" field, then checks the object's keys against
 * those of that variant. */
static bool scene_read_variant(const char *file, const cJSON *object, const char *where, const char *key,
                               const char *what, const scene_variant table[], const scene_variant **out) {
    const char *name;
    if (!json_read_string(file, object, where, key, true, &name))
        return false;
    const char *names[16];
    int count = 0;
    for (const scene_variant *v = table; v->name; v++) {
        if (strcmp(v->name, name) == 0) {
            *out = v;
            return json_check_keys(file, object, where, v->keys);
        }
        names[count++] = v->name;
    }
    names[count] = NULL;
    char expected[256];
    json_join_names(names, expected, sizeof expected);
    return json_fail(file, where, key, "unknown %s \"%s\" (expected %s)", what, name, expected);
}

/* A list at the top level, with 1..max_count entries. */
static bool scene_read_list(const char *file, const cJSON *root, const char *key, int max_count, const cJSON **out) {
    if (!json_lookup(file, root, "", key, true, out))
        return false;
    if (!cJSON_IsArray(*out)) {
        return json_fail(file, "", key, "expected an array, got %s", json_kind(*out));
    }
    int count = cJSON_GetArraySize(*out);
    if (count == 0)
        return json_fail(file, "", key, "must not be empty");
    if (count > max_count) {
        return json_fail(file, "", key, "too many entries: %d (at most %d)", count, max_count);
    }
    return true;
}

/* In double: cglm's float normalize overflows on huge vectors and turns
 * tiny ones to zero. */
static bool scene_normalize(float v[3]) {
    double length = sqrt((double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2]);
    if (!(length > 0))
        return false;
    for (int k = 0; k < 3; k++)
        v[k] = (float)(v[k] / length);
    return true;
}

void scene_choose_origin(const scene_camera *c, double origin[3]) {
    double eye = 0, view = 0;
    for (int k = 0; k < 3; k++) {
        eye = fmax(eye, fabs((double)c->position[k]));
        view += ((double)c->target[k] - c->position[k]) * ((double)c->target[k] - c->position[k]);
    }
    bool rebase = eye > SCENE_REBASE_RATIO * sqrt(view);
    for (int k = 0; k < 3; k++)
        origin[k] = rebase ? c->position[k] : 0;
}

static bool scene_read_camera(const char *file, const cJSON *root, scene_camera *c, double origin[3]) {
    static const char *const keys[] = {"position", "target", "up", "fov", "near", "far", NULL};
    *c = (scene_camera){.up = {0, 1, 0}, .fov_deg = 45, .near_plane = 0.1f, .far_plane = 100};
    const cJSON *json;
    if (!json_read_object(file, root, "", "camera", &json) || !json_check_keys(file, json, "camera", keys) ||
        !scene_read_floats(file, json, "camera", "position", true, SCENE_ANY, NULL, c->position, 3) ||
        !scene_read_floats(file, json, "camera", "target", true, SCENE_ANY, NULL, c->target, 3) ||
        !scene_read_floats(file, json, "camera", "up", false, SCENE_ANY, NULL, c->up, 3) ||
        !scene_read_float(file, json, "camera", "fov", false, SCENE_POSITIVE, &c->fov_deg) ||
        !scene_read_float(file, json, "camera", "near", false, SCENE_POSITIVE, &c->near_plane) ||
        !scene_read_float(file, json, "camera", "far", false, SCENE_POSITIVE, &c->far_plane)) {
        return false;
    }
    /* Read again relative to the origin, now known (the first reading
     * was in world coordinates, and was valid). */
    scene_choose_origin(c, origin);
    if (!scene_read_floats(file, json, "camera", "position", true, SCENE_ANY, origin, c->position, 3) ||
        !scene_read_floats(file, json, "camera", "target", true, SCENE_ANY, origin, c->target, 3)) {
        return false;
    }
    if (c->fov_deg >= 180) {
        return json_fail(file, "camera", "fov", "must be less than 180 degrees (got %g)", c->fov_deg);
    }
    if (c->far_plane <= c->near_plane) {
        return json_fail(file, "camera", "far", "must be greater than near (%g <= %g)", c->far_plane, c->near_plane);
    }
    /* Either would leave the view matrix undefined (NaN). */
    vec3 view, side;
    glm_vec3_sub(c->target, c->position, view);
    if (!(glm_vec3_norm2(view) > 0))
        return json_fail(file, "camera", "target", "must differ from position");
    glm_vec3_cross(view, c->up, side);
    if (!(glm_vec3_norm2(side) > 0)) {
        return json_fail(file, "camera", "up", "must be non-zero and not parallel to the view direction");
    }
    return true;
}

static bool scene_read_light(const char *file, const cJSON *json, const char *where, const double origin[3],
                             scene_light *l) {
    *l = (scene_light){.color = {1, 1, 1}, .intensity = 1, .inner_angle_deg = 20, .outer_angle_deg = 30};
    if (!cJSON_IsObject(json)) {
        return json_fail(file, where, NULL, "expected an object, got %s", json_kind(json));
    }
    const scene_variant *type;
    if (!scene_read_variant(file, json, where, "type", "light type", scene_light_types, &type))
        return false;
    l->type = (scene_light_type)type->value;
    bool positioned = l->type != SCENE_LIGHT_DIRECTIONAL;
    bool aimed = l->type != SCENE_LIGHT_POINT;
    if (!scene_read_floats(file, json, where, "position", positioned, SCENE_ANY, origin, l->position, 3) ||
        !scene_read_floats(file, json, where, "direction", aimed, SCENE_ANY, NULL, l->direction, 3) ||
        !scene_read_floats(file, json, where, "color", false, SCENE_NON_NEGATIVE, NULL, l->color, 3) ||
        !scene_read_float(file, json, where, "intensity", false, SCENE_NON_NEGATIVE, &l->intensity) ||
        !scene_read_float(file, json, where, "inner_angle", false, SCENE_NON_NEGATIVE, &l->inner_angle_deg) ||
        !scene_read_float(file, json, where, "outer_angle", false, SCENE_NON_NEGATIVE, &l->outer_angle_deg) ||
        !scene_read_float(file, json, where, "radius", false, SCENE_NON_NEGATIVE, &l->radius) ||
        !scene_read_float(file, json, where, "range", false, SCENE_POSITIVE, &l->range)) {
        return false;
    }
    if (aimed && !scene_normalize(l->direction))
        return json_fail(file, where, "direction", "must not be zero");
    /* The cone must open: at 90 degrees and beyond it is no cone at all. */
    if (l->outer_angle_deg >= 90) {
        return json_fail(file, where, "outer_angle", "must be less than 90 degrees (got %g)", l->outer_angle_deg);
    }
    if (l->outer_angle_deg < l->inner_angle_deg) {
        return json_fail(file, where, "outer_angle", "must not be less than inner_angle (%g < %g)",
                         l->outer_angle_deg, l->inner_angle_deg);
    }
    return true;
}

/* Where a failing mesh constructor's message goes while the scene builds an
 * object: "FILE: objects[i] "name": NAME: problem". */
typedef struct scene_mesh_context {
    const char *file;
    const char *object;
} scene_mesh_context;

static void scene_report_mesh_error(const char *name, const char *problem, void *user_data) {
    const scene_mesh_context *context = user_data;
    fprintf(stderr, "%s: %s: %s: %s\n", context->file, context->object, name, problem);
}

/* Model paths are relative to the scene file's folder, unless absolute. */
static bool scene_load_model(const char *file, const char *path, mesh *m, mesh_material *material) {
    char resolved[PATH_MAX];
    if (!path_beside(file, path, resolved, sizeof resolved))
        return json_fail(file, "", NULL, "model path too long");
    return mesh_load_file(m, resolved, material);
}

/* "segments": absent or 0 the default, else MESH_MIN_SEGMENTS..
 * MESH_MAX_SEGMENTS. */
static bool scene_read_segments(const char *file, const cJSON *json, const char *where, int *segments) {
    if (!json_read_int(file, json, where, "segments", segments))
        return false;
    if (*segments != 0 && (*segments < MESH_MIN_SEGMENTS || *segments > MESH_MAX_SEGMENTS))
        return json_fail(file, where, "segments", "must be %d to %d, or 0 for the default (got %d)",
                         MESH_MIN_SEGMENTS, MESH_MAX_SEGMENTS, *segments);
    return true;
}

/* The object's mesh; a model's colour into *material. */
static bool scene_build_mesh(const char *file, const cJSON *json, const char *where, const char *object_where,
                             scene_object *o, mesh_material *material) {
    char object[SCENE_NAME_MAX + 64];
    snprintf(object, sizeof object, "%s \"%s\"", object_where, o->name);
    scene_mesh_context context = {file, object};
    float size[3], radius, minor_radius, height;
    int segments = 0;
    const char *path;
    bool built = false;
    mesh_set_error_handler(scene_report_mesh_error, &context);
    switch (o->mesh_kind) {
    case SCENE_MESH_PLANE:
        built = scene_read_floats(file, json, where, "size", true, SCENE_POSITIVE, NULL, size, 2) &&
                mesh_make_plane(&o->mesh, size[0], size[1]);
        break;
    case SCENE_MESH_BOX:
        built = scene_read_floats(file, json, where, "size", true, SCENE_POSITIVE, NULL, size, 3) &&
                mesh_make_box(&o->mesh, size[0], size[1], size[2]);
        break;
    case SCENE_MESH_SPHERE:
        built = scene_read_float(file, json, where, "radius", true, SCENE_POSITIVE, &radius) &&
                scene_read_segments(file, json, where, &segments) && mesh_make_sphere(&o->mesh, radius, segments);
        break;
    case SCENE_MESH_TORUS:
        built = scene_read_float(file, json, where, "major_radius", true, SCENE_POSITIVE, &radius) &&
                scene_read_float(file, json, where, "minor_radius", true, SCENE_POSITIVE, &minor_radius) &&
                scene_read_segments(file, json, where, &segments) &&
                mesh_make_torus(&o->mesh, radius, minor_radius, segments);
        break;
    case SCENE_MESH_CYLINDER:
        built = scene_read_float(file, json, where, "radius", true, SCENE_POSITIVE, &radius) &&
                scene_read_float(file, json, where, "height", true, SCENE_POSITIVE, &height) &&
                scene_read_segments(file, json, where, &segments) &&
                mesh_make_cylinder(&o->mesh, radius, height, segments);
        break;
    case SCENE_MESH_MODEL:
        built = json_read_string(file, json, where, "path", true, &path) &&
                scene_load_model(file, path, &o->mesh, material);
        break;
    }
    mesh_set_error_handler(NULL, NULL);
    return built;
}

/* Names pick objects (shadowdiff --receiver NAME): each is one object's. */
static bool scene_check_unique(const char *file, const char *where, const char *name, const scene_object *earlier,
                               int count) {
    for (int i = 0; i < count; i++)
        if (strcmp(earlier[i].name, name) == 0)
            return json_fail(file, where, "name", "\"%s\" is objects[%d]'s name too: each must be one object's", name,
                             i);
    return true;
}

static bool scene_check_name(const char *file, const char *where, const char *name) {
    size_t length = strlen(name);
    if (length == 0 || length >= SCENE_NAME_MAX) {
        return json_fail(file, where, "name", "must be 1 to %d bytes long (got %zu)", SCENE_NAME_MAX - 1, length);
    }
    /* It is quoted in messages, which must stay one line. */
    for (const char *c = name; *c; c++) {
        if (iscntrl((unsigned char)*c)) {
            return json_fail(file, where, "name", "must not contain control characters");
        }
    }
    return true;
}

/* "scale" is a vector or one number for all three axes; negative factors
 * mirror, zero ones would flatten the object. */
static bool scene_read_scale(const char *file, const cJSON *json, const char *where, float scale[3]) {
    const cJSON *item = cJSON_GetObjectItemCaseSensitive(json, "scale");
    if (!cJSON_IsNumber(item)) {
        return scene_read_floats(file, json, where, "scale", false, SCENE_NON_ZERO, NULL, scale, 3);
    }
    if (!scene_number(file, where, "scale", item, SCENE_NON_ZERO, 0, &scale[0]))
        return false;
    scale[1] = scale[2] = scale[0];
    return true;
}

/* M = T * Rz * Ry * Rx * S: scaled first, then turned about X, Y and Z, then
 * moved. */
static void scene_model_matrix(vec3 translate, const float rotate_deg[3], vec3 scale, float out[4][4]) {
    mat4 model;
    glm_translate_make(model, translate);
    glm_rotate_z(model, glm_rad(rotate_deg[2]), model);
    glm_rotate_y(model, glm_rad(rotate_deg[1]), model);
    glm_rotate_x(model, glm_rad(rotate_deg[0]), model);
    glm_scale(model, scale);
    memcpy(out, model, sizeof model);
}

/* A scene file's object of mesh kind "gltf": the file's objects, placed by
 * the object's transform, named after it. */
static bool scene_include_file(const char *file, const cJSON *json, const cJSON *mesh_json, const char *where,
                               const char *mesh_where, const scene_object *o, scene *s, int *capacity) {
    const char *path;
    char resolved[PATH_MAX];
    if (!json_read_string(file, mesh_json, mesh_where, "path", true, &path))
        return false;
    if (cJSON_GetObjectItemCaseSensitive(json, "color"))
        return json_fail(file, where, "color", "a glTF file's objects take their materials' colours");
    if (!path_beside(file, path, resolved, sizeof resolved))
        return json_fail(file, mesh_where, "path", "too long");
    if (access(resolved, R_OK) != 0)
        return json_fail(file, mesh_where, "path", "%s: %s", resolved, strerror(errno));
    return scene_include_gltf(s, capacity, resolved, o->model, o->name, o->casts, o->receives);
}

/* The object `json` after the s->object_count before it, s->objects grown
 * within *capacity. */
static bool scene_read_object(const char *file, const cJSON *json, const char *where, scene *s, int *capacity) {
    const double *origin = s->origin;
    scene_object *objects = s->objects, object;
    int count = s->object_count;
    scene_object *o = &object;
    static const char *const keys[] = {"name",  "mesh",  "translate", "rotate", "scale",
                                       "color", "casts", "receives",  NULL};
    vec3 translate = {(float)-origin[0], (float)-origin[1], (float)-origin[2]}, rotate_deg = {0, 0, 0},
         scale = {1, 1, 1};
    *o = (scene_object){.color = {0.8f, 0.8f, 0.8f}, .casts = true, .receives = true};
    if (!cJSON_IsObject(json)) {
        return json_fail(file, where, NULL, "expected an object, got %s", json_kind(json));
    }
    char mesh_where[64];
    snprintf(mesh_where, sizeof mesh_where, "%s.mesh", where);
    const char *name;
    const cJSON *mesh_json;
    const scene_variant *kind;
    if (!json_check_keys(file, json, where, keys) || !json_read_string(file, json, where, "name", true, &name) ||
        !scene_check_name(file, where, name) || !scene_check_unique(file, where, name, objects, count) ||
        !json_read_object(file, json, where, "mesh", &mesh_json) ||
        !scene_read_variant(file, mesh_json, mesh_where, "kind", "mesh kind", scene_mesh_kinds, &kind) ||
        !scene_read_floats(file, json, where, "translate", false, SCENE_ANY, origin, translate, 3) ||
        !scene_read_floats(file, json, where, "rotate", false, SCENE_ANY, NULL, rotate_deg, 3) ||
        !scene_read_scale(file, json, where, scale) ||
        !scene_read_floats(file, json, where, "color", false, SCENE_NON_NEGATIVE, NULL, o->color, 3) ||
        !json_read_bool(file, json, where, "casts", &o->casts) ||
        !json_read_bool(file, json, where, "receives", &o->receives)) {
        return false;
    }
    snprintf(o->name, sizeof o->name, "%s", name);
    /* An odd number of negative factors mirrors (a negative determinant),
     * which would turn the triangles clockwise seen from outside: the GL's
     * and the reference's front faces, and the volumes' facing, computed
     * from the object-space triangles and the light taken into object
     * space, would all see the object inside out. The mirror goes into
     * the mesh instead (mesh_reflect_x, winding reversed), and the matrix
     * keeps a positive determinant: its x column only changes sign, so
     * every world position is bit for bit the mirrored matrix's. */
    bool mirrored = ((scale[0] < 0) ^ (scale[1] < 0) ^ (scale[2] < 0)) != 0;
    if (kind->value == SCENE_MESH_GLTF_FILE) {
        /* Each of its objects turns a mirroring matrix as a glTF scene's. */
        scene_model_matrix(translate, rotate_deg, scale, o->model);
        return scene_include_file(file, json, mesh_json, where, mesh_where, o, s, capacity);
    }
    o->mesh_kind = (scene_mesh_kind)kind->value;
    if (mirrored)
        scale[0] = -scale[0];
    scene_model_matrix(translate, rotate_deg, scale, o->model);
    if (!scene_reserve_object(s, capacity, file))
        return false;
    /* Last: loading a model is the slow part, and every cheap check passed. */
    mesh_material material = {0};
    if (!scene_build_mesh(file, mesh_json, mesh_where, where, o, &material))
        return false;
    /* The model's own colour where the object gives none. */
    bool own_color = !cJSON_GetObjectItemCaseSensitive(json, "color");
    if (material.has_color && own_color)
        memcpy(o->color, material.color, sizeof o->color);
    /* Where the scene gives no colour, the picture is the model's own
     * colour without its textures: said, since it may look nothing like
     * the model. */
    if (material.textured && own_color)
        fprintf(stderr,
                "%s: %s: %u of the model's materials have textures, which only a glTF scene reads: drawn in the "
                "colour (%g, %g, %g) alone\n",
                file, where, material.textured, o->color[0], o->color[1], o->color[2]);
    if (mirrored)
        mesh_reflect_x(&o->mesh);
    s->objects[s->object_count++] = object;
    return true;
}

static bool scene_read_root(const char *file, const cJSON *root, scene *s) {
    static const char *const keys[] = {"camera", "ambient", "lights", "objects", NULL};
    if (!cJSON_IsObject(root)) {
        return json_fail(file, "", NULL, "expected an object at the top level, got %s", json_kind(root));
    }
    glm_vec3_fill(s->ambient, SCENE_DEFAULT_AMBIENT);
    const cJSON *lights, *objects, *entry;
    if (!json_check_keys(file, root, "", keys) || !scene_read_camera(file, root, &s->camera, s->origin) ||
        !scene_read_floats(file, root, "", "ambient", false, SCENE_NON_NEGATIVE, NULL, s->ambient, 3) ||
        !scene_read_list(file, root, "lights", SCENE_MAX_LIGHTS, &lights) ||
        !scene_read_list(file, root, "objects", INT_MAX, &objects)) {
        return false;
    }
    char where[32];
    cJSON_ArrayForEach(entry, lights) {
        snprintf(where, sizeof where, "lights[%d]", s->light_count);
        if (!scene_read_light(file, entry, where, s->origin, &s->lights[s->light_count]))
            return false;
        s->light_count++;
    }
    int capacity = cJSON_GetArraySize(objects), index = 0;
    s->objects = calloc((size_t)capacity, sizeof *s->objects);
    if (!s->objects)
        return json_fail(file, "", "objects", "out of memory");
    cJSON_ArrayForEach(entry, objects) {
        snprintf(where, sizeof where, "objects[%d]", index++);
        /* A failed object owns nothing: mesh constructors leave it empty. */
        if (!scene_read_object(file, entry, where, s, &capacity))
            return false;
    }
    return true;
}

void scene_object_place(scene_object *o, const float world[4][4]) {
    memcpy(o->model, world, sizeof o->model);
    if (glm_mat4_det(o->model) < 0) {
        mesh_reflect_x(&o->mesh);
        glm_vec4_negate(o->model[0]);
    }
}

bool scene_reserve_object(scene *s, int *capacity, const char *file) {
    if (s->object_count < *capacity)
        return true;
    int grown_capacity = *capacity > 0 ? 2 * *capacity : SCENE_FIRST_CAPACITY;
    scene_object *grown = realloc(s->objects, (size_t)grown_capacity * sizeof *grown);
    if (!grown) {
        fprintf(stderr, "%s: out of memory for %d objects\n", file, grown_capacity);
        return false;
    }
    s->objects = grown;
    *capacity = grown_capacity;
    return true;
}

bool scene_reserve_textures(scene *s, size_t more, const char *file) {
    if (more == 0)
        return true;
    texture *grown = realloc(s->textures, ((size_t)s->texture_count + more) * sizeof *grown);
    if (!grown) {
        fprintf(stderr, "%s: out of memory for %zu textures\n", file, (size_t)s->texture_count + more);
        return false;
    }
    for (int i = 0; i < s->object_count; i++)
        if (s->objects[i].base_color)
            s->objects[i].base_color = grown + (s->objects[i].base_color - s->textures);
    s->textures = grown;
    memset(grown + s->texture_count, 0, more * sizeof *grown);
    return true;
}

bool scene_load(scene *s, const char *path) { return scene_load_camera(s, path, 0); }

static bool scene_load_json(scene *s, const char *path, int camera) {
    *s = (scene){0};
    if (camera != 0) {
        fprintf(stderr, "%s: --camera %d: the scene has camera 0 only\n", path, camera);
        return false;
    }
    cJSON *root = json_load(path, SCENE_MAX_FILE_SIZE);
    if (!root)
        return false;
    bool loaded = scene_read_root(path, root, s);
    cJSON_Delete(root);
    if (!loaded)
        scene_free(s);
    return loaded;
}

/* Whether the point (world, w 1) lies within object o's world bounds. */
static bool scene_object_bounds_hold(const scene_object *o, const float point[4]) {
    float lo[3], hi[3];
    scene_object_world_bounds(o, lo, hi);
    for (int k = 0; k < 3; k++)
        if (!(point[k] >= lo[k] && point[k] <= hi[k]))
            return false;
    return true;
}

/* Whether the point (world, w 1) lies inside closed object o, off its
 * surface: its bounds first, the winding number only within them. */
static bool scene_object_holds(const scene_object *o, const float point[4]) {
    float local[4];
    if (!scene_object_bounds_hold(o, point))
        return false;
    mesh_point_to_object(o->model, point, local);
    return mesh_point_winding(&o->mesh, local) > MESH_POINT_WITHIN_WINDING;
}

/* The first caster whose closed mesh holds light l while the eye is
 * outside it, or -1: such a light lights nothing the eye can see of the
 * scene. */
static int scene_light_holder(const scene *s, int l) {
    float light[4];
    scene_light_homogeneous(&s->lights[l], light);
    const float eye[4] = {s->camera.position[0], s->camera.position[1], s->camera.position[2], 1};
    for (int i = 0; light[3] != 0 && i < s->object_count; i++) {
        const scene_object *o = &s->objects[i];
        if (!o->casts || !scene_object_holds(o, light) || scene_object_holds(o, eye))
            continue;
        mesh_edges edges;
        if (!mesh_edges_build_welded(&o->mesh, &edges))
            continue; /* said; the hint is not worth failing the load */
        bool closed = edges.closed;
        mesh_edges_free(&edges);
        if (closed)
            return i;
    }
    return -1;
}

const char *const scene_extensions[] = {".json", ".gltf", ".glb", NULL};

bool scene_is_gltf(const char *path) {
    const char *extension = strrchr(path, '.');
    return extension && (strcasecmp(extension, ".gltf") == 0 || strcasecmp(extension, ".glb") == 0);
}

bool scene_load_camera(scene *s, const char *path, int camera) {
    if (!(scene_is_gltf(path) ? scene_load_gltf(s, path, camera) : scene_load_json(s, path, camera)))
        return false;
    for (int l = 0; l < s->light_count; l++) {
        int i = scene_light_holder(s, l);
        if (i >= 0)
            fprintf(stderr, "%s: light %d lies inside object %d (%s): it lights nothing outside it\n", path, l, i,
                    s->objects[i].name);
    }
    return true;
}

void scene_free(scene *s) {
    for (int i = 0; i < s->object_count; i++)
        mesh_free(&s->objects[i].mesh);
    free(s->objects);
    for (int t = 0; t < s->texture_count; t++)
        texture_free(&s->textures[t]);
    free(s->textures);
    *s = (scene){0};
}

bool scene_check_light_flag(const scene *s, const char *file, int light) {
    if (light < s->light_count)
        return true;
    if (s->light_count == 1)
        fprintf(stderr, "%s: --light %d: the scene has light 0 only\n", file, light);
    else
        fprintf(stderr, "%s: --light %d: the scene has lights 0 to %d\n", file, light, s->light_count - 1);
    return false;
}

/* The object's texel at the point of `triangle` of barycentric `weight`,
 * read at level 0; white where it has no texture. */
static void scene_object_texel(const scene_object *o, uint32_t triangle, const float weight[3], float texel[4]) {
    if (!o->base_color) {
        glm_vec4_one(texel);
        return;
    }
    float uv[2] = {0, 0};
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < 2; k++)
            uv[k] += weight[c] * o->mesh.vertices[o->mesh.indices[3 * triangle + (uint32_t)c]].uv[k];
    texture_sample(o->base_color, uv, 0, texel);
}

bool scene_object_cut_out(const scene_object *o, uint32_t triangle, const float weight[3]) {
    if (!(o->alpha_cutoff > 0))
        return false;
    float texel[4];
    scene_object_texel(o, triangle, weight, texel);
    return o->base_alpha * texel[3] < o->alpha_cutoff;
}

void scene_object_transmittance(const scene_object *o, uint32_t triangle, const float weight[3], float out[3]) {
    float texel[4];
    scene_object_texel(o, triangle, weight, texel);
    float alpha = o->base_alpha * texel[3];
    for (int k = 0; k < 3; k++)
        out[k] = 1.0f - alpha + alpha * o->color[k] * texel[k];
}

int scene_translucent_casters(const scene *s) {
    int count = 0;
    for (int i = 0; i < s->object_count; i++)
        count += s->objects[i].translucent && s->objects[i].casts;
    return count;
}

bool scene_has_cut_outs(const scene *s) {
    for (int i = 0; i < s->object_count; i++)
        if (s->objects[i].alpha_cutoff > 0)
            return true;
    return false;
}

bool scene_light_reaches_cut_out(const scene *s, const scene_light *l) {
    for (int i = 0; i < s->object_count; i++) {
        const scene_object *o = &s->objects[i];
        float lo[3], hi[3];
        if (!(o->alpha_cutoff > 0) || !o->casts)
            continue;
        scene_object_world_bounds(o, lo, hi);
        if (scene_light_reaches_box(l, lo, hi))
            return true;
    }
    return false;
}

void scene_print_models(const scene *s, const char *file) {
    for (int i = 0; i < s->object_count; i++) {
        const scene_object *o = &s->objects[i];
        float lo[3], hi[3];
        if (o->mesh_kind != SCENE_MESH_MODEL)
            continue;
        scene_object_world_bounds(o, lo, hi);
        char texture[64] = "";
        if (o->base_color)
            snprintf(texture, sizeof texture, " times a %dx%d texture", o->base_color->levels[0].width,
                     o->base_color->levels[0].height);
        fprintf(stderr,
                "%s: objects[%d] \"%s\": model of %u triangles, bounds (%g, %g, %g) to (%g, %g, %g), colour (%g, %g, "
                "%g)%s\n",
                file, i, o->name, o->mesh.index_count / 3, lo[0] + s->origin[0], lo[1] + s->origin[1],
                lo[2] + s->origin[2], hi[0] + s->origin[0], hi[1] + s->origin[1], hi[2] + s->origin[2], o->color[0],
                o->color[1], o->color[2], texture);
    }
}

void scene_object_world_corner(const scene_object *o, uint32_t t, int k, double out[3]) {
    const float *p = o->mesh.vertices[o->mesh.indices[3 * t + (uint32_t)k]].position;
    for (int row = 0; row < 3; row++)
        out[row] = (double)o->model[0][row] * p[0] + (double)o->model[1][row] * p[1] +
                   (double)o->model[2][row] * p[2] + (double)o->model[3][row];
}

/* Arvo's method: each world axis gathers, per object axis, the smaller and
 * larger of that column's contribution at the two bounds. Exact for the
 * transformed box, without transforming its 8 corners. */
void scene_object_world_bounds(const scene_object *o, float min[3], float max[3]) {
    for (int row = 0; row < 3; row++) {
        min[row] = max[row] = o->model[3][row];
        for (int column = 0; column < 3; column++) {
            float a = o->model[column][row] * o->mesh.bounds_min[column];
            float b = o->model[column][row] * o->mesh.bounds_max[column];
            min[row] += fminf(a, b);
            max[row] += fmaxf(a, b);
        }
    }
}

void scene_receivers_bounds(const scene *s, float min[3], float max[3]) {
    for (int k = 0; k < 3; k++) {
        min[k] = INFINITY;
        max[k] = -INFINITY;
    }
    for (int i = 0; i < s->object_count; i++) {
        float lo[3], hi[3];
        if (!s->objects[i].receives)
            continue;
        scene_object_world_bounds(&s->objects[i], lo, hi);
        for (int k = 0; k < 3; k++) {
            min[k] = fminf(min[k], lo[k]);
            max[k] = fmaxf(max[k], hi[k]);
        }
    }
}

const char *scene_light_radius_unit(const scene_light *l) {
    return l->type == SCENE_LIGHT_DIRECTIONAL ? " degrees" : "";
}

float scene_light_range_window(const scene_light *l, float distance) {
    if (!(l->range > 0))
        return 1;
    float x = distance / l->range, x4 = x * x * x * x, w = fmaxf(1 - x4, 0);
    return w * w;
}

bool scene_light_reaches_box(const scene_light *l, const float lo[3], const float hi[3]) {
    if (l->type == SCENE_LIGHT_DIRECTIONAL)
        return true;
    /* The range: the box's nearest point to the light. */
    float nearest_sq = 0;
    for (int k = 0; k < 3; k++) {
        float d = fmaxf(fmaxf(lo[k] - l->position[k], 0), l->position[k] - hi[k]);
        nearest_sq += d * d;
    }
    float range = l->range * (1 + SCENE_REACH_RANGE_MARGIN);
    if (l->range > 0 && nearest_sq > range * range)
        return false;
    if (l->type != SCENE_LIGHT_SPOT)
        return true;
    /* The cone against the box's bounding sphere: the sphere meets the cone
     * when the angle from the axis to its centre is at most the cone's
     * half-angle plus the angle the sphere subtends. */
    float center[3], to_center[3], radius_sq = 0, distance_sq = 0;
    for (int k = 0; k < 3; k++) {
        center[k] = 0.5f * (lo[k] + hi[k]);
        radius_sq += 0.25f * (hi[k] - lo[k]) * (hi[k] - lo[k]);
        to_center[k] = center[k] - l->position[k];
        distance_sq += to_center[k] * to_center[k];
    }
    if (distance_sq <= radius_sq)
        return true; /* the light is inside the sphere */
    float distance = sqrtf(distance_sq), axis_cos = 0;
    for (int k = 0; k < 3; k++)
        axis_cos += to_center[k] * l->direction[k] / distance;
    float axis_angle = acosf(fminf(fmaxf(axis_cos, -1), 1));
    float subtended = asinf(sqrtf(radius_sq) / distance);
    return axis_angle <= glm_rad(l->outer_angle_deg) + subtended + SCENE_REACH_ANGLE_MARGIN_RAD;
}

bool scene_light_range_box(const scene_light *l, float lo[3], float hi[3]) {
    if (l->type == SCENE_LIGHT_DIRECTIONAL || !(l->range > 0))
        return false;
    float range = l->range * (1 + SCENE_REACH_RANGE_MARGIN);
    for (int k = 0; k < 3; k++) {
        lo[k] = l->position[k] - range;
        hi[k] = l->position[k] + range;
    }
    return true;
}

bool scene_light_clip_to_range(const scene_light *l, float lo[3], float hi[3]) {
    float range_lo[3], range_hi[3];
    bool ranged = scene_light_range_box(l, range_lo, range_hi);
    bool empty = false;
    for (int k = 0; k < 3; k++) {
        if (ranged) {
            lo[k] = fmaxf(lo[k], range_lo[k]);
            hi[k] = fminf(hi[k], range_hi[k]);
        }
        empty = empty || !(lo[k] <= hi[k]);
    }
    return !empty;
}

void scene_light_homogeneous(const scene_light *l, float out[4]) {
    bool directional = l->type == SCENE_LIGHT_DIRECTIONAL;
    for (int i = 0; i < 3; i++)
        out[i] = directional ? -l->direction[i] : l->position[i];
    out[3] = directional ? 0.0f : 1.0f;
}

void scene_object_normal_matrix(const scene_object *o, float out[3][3]) {
    mat3 upper;
    glm_mat4_pick3((vec4 *)o->model, upper);
    glm_mat3_inv(upper, upper);
    glm_mat3_transpose_to(upper, out);
}
