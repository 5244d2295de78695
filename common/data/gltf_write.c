#include "gltf_write.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"

/* glTF's numbers: component types, buffer view targets, sampler modes. */
#define GLTF_FLOAT 5126
#define GLTF_UNSIGNED_SHORT 5123
#define GLTF_ARRAY_BUFFER 34962
#define GLTF_ELEMENT_ARRAY_BUFFER 34963
#define GLTF_REPEAT 10497
#define GLTF_CLAMP_TO_EDGE 33071
/* Buffer views start on this many bytes (the largest component). */
#define GLTF_ALIGN 4

struct gltf_write {
    cJSON *root, *nodes, *scene_nodes, *meshes, *materials, *textures, *samplers, *images, *accessors, *views,
        *cameras, *lights;
    unsigned char *buffer;
    size_t size, capacity;
    bool out_of_memory;
};

static const char gltf_base64_digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/* "data:TYPE;base64,..." of `size` bytes; NULL when out of memory. */
static char *gltf_data_uri(const char *type, const unsigned char *bytes, size_t size) {
    size_t prefix = strlen("data:;base64,") + strlen(type), length = prefix + 4 * ((size + 2) / 3);
    char *uri = malloc(length + 1);
    if (!uri)
        return NULL;
    char *out = uri + sprintf(uri, "data:%s;base64,", type);
    for (size_t i = 0; i < size; i += 3) {
        uint32_t group = (uint32_t)bytes[i] << 16 | (i + 1 < size ? (uint32_t)bytes[i + 1] << 8 : 0) |
                         (i + 2 < size ? bytes[i + 2] : 0);
        size_t present = size - i < 3 ? size - i : 3; /* bytes of this group: its digits are one more */
        for (size_t k = 0; k < 4; k++)
            *out++ = k <= present ? gltf_base64_digits[(group >> (18 - 6 * k)) & 63] : '=';
    }
    *out = '\0';
    return uri;
}

/* `item` into an array (key NULL) or an object; a NULL item, a NULL `to`
 * (one whose making failed) or a failure marks the writer out of memory,
 * so that a part's fields need no check of their own: gltf_write_end
 * returns NULL. */
static cJSON *gltf_add(gltf_write *w, cJSON *to, const char *key, cJSON *item) {
    bool added = item && (key ? cJSON_AddItemToObject(to, key, item) : cJSON_AddItemToArray(to, item));
    if (!added) {
        cJSON_Delete(item);
        w->out_of_memory = true;
        return NULL;
    }
    return item;
}

static void gltf_number(gltf_write *w, cJSON *to, const char *key, double x) {
    gltf_add(w, to, key, cJSON_CreateNumber(x));
}

static void gltf_numbers(gltf_write *w, cJSON *to, const char *key, const double *x, int count) {
    gltf_add(w, to, key, cJSON_CreateDoubleArray(x, count));
}

/* A new object at the end of `list`; its index, or -1 (and NULL). */
static cJSON *gltf_entry(gltf_write *w, cJSON *list, int *index) {
    *index = cJSON_GetArraySize(list);
    cJSON *entry = gltf_add(w, list, NULL, cJSON_CreateObject());
    if (!entry)
        *index = -1;
    return entry;
}

/* `size` bytes into the buffer, aligned; a buffer view of them, its index. */
static int gltf_view(gltf_write *w, const void *bytes, size_t size, int target) {
    size_t offset = (w->size + GLTF_ALIGN - 1) / GLTF_ALIGN * GLTF_ALIGN;
    if (offset + size > w->capacity) {
        size_t capacity = 2 * (offset + size);
        unsigned char *grown = realloc(w->buffer, capacity);
        if (!grown) {
            w->out_of_memory = true;
            return -1;
        }
        w->buffer = grown;
        w->capacity = capacity;
    }
    memset(w->buffer + w->size, 0, offset - w->size);
    memcpy(w->buffer + offset, bytes, size);
    w->size = offset + size;
    int index;
    cJSON *view = gltf_entry(w, w->views, &index);
    gltf_number(w, view, "buffer", 0);
    gltf_number(w, view, "byteOffset", (double)offset);
    gltf_number(w, view, "byteLength", (double)size);
    if (target)
        gltf_number(w, view, "target", target);
    return index;
}

/* An accessor of `count` elements of `type` over a new view of `bytes`. */
static int gltf_accessor(gltf_write *w, const void *bytes, size_t size, int count, const char *type, int component,
                         int target) {
    int view = gltf_view(w, bytes, size, target), index;
    cJSON *a = gltf_entry(w, w->accessors, &index);
    gltf_number(w, a, "bufferView", view);
    gltf_number(w, a, "componentType", component);
    gltf_number(w, a, "count", count);
    gltf_add(w, a, "type", cJSON_CreateString(type));
    return index;
}

gltf_write *gltf_write_begin(const char *generator) {
    gltf_write *w = calloc(1, sizeof *w);
    if (!w)
        return NULL;
    w->root = cJSON_CreateObject();
    cJSON *asset = gltf_add(w, w->root, "asset", cJSON_CreateObject());
    gltf_add(w, asset, "version", cJSON_CreateString("2.0"));
    gltf_add(w, asset, "generator", cJSON_CreateString(generator));
    cJSON *used = gltf_add(w, w->root, "extensionsUsed", cJSON_CreateArray());
    gltf_add(w, used, NULL, cJSON_CreateString("KHR_lights_punctual"));
    cJSON *extensions = gltf_add(w, w->root, "extensions", cJSON_CreateObject());
    cJSON *punctual = gltf_add(w, extensions, "KHR_lights_punctual", cJSON_CreateObject());
    w->lights = gltf_add(w, punctual, "lights", cJSON_CreateArray());
    gltf_number(w, w->root, "scene", 0);
    cJSON *scenes = gltf_add(w, w->root, "scenes", cJSON_CreateArray());
    cJSON *scene = gltf_add(w, scenes, NULL, cJSON_CreateObject());
    w->scene_nodes = gltf_add(w, scene, "nodes", cJSON_CreateArray());
    static const char *const lists[] = {"nodes",    "cameras", "meshes",      "materials", "textures",
                                        "samplers", "images",  "bufferViews", "accessors"};
    cJSON **slots[] = {&w->nodes,    &w->cameras, &w->meshes, &w->materials, &w->textures,
                       &w->samplers, &w->images,  &w->views,  &w->accessors};
    for (size_t i = 0; i < sizeof lists / sizeof *lists; i++)
        *slots[i] = gltf_add(w, w->root, lists[i], cJSON_CreateArray());
    if (!w->root || w->out_of_memory) {
        cJSON_Delete(w->root);
        free(w);
        return NULL;
    }
    return w;
}

int gltf_write_texture(gltf_write *w, int width, int height, const unsigned char *rgba, bool clamp) {
    size_t size = 0;
    unsigned char *png = image_png_bytes(width, height, rgba, &size);
    char *uri = png ? gltf_data_uri("image/png", png, size) : NULL;
    free(png);
    int image, sampler, texture;
    cJSON *i = gltf_entry(w, w->images, &image);
    gltf_add(w, i, "uri", uri ? cJSON_CreateString(uri) : NULL);
    free(uri);
    cJSON *s = gltf_entry(w, w->samplers, &sampler);
    gltf_number(w, s, "wrapS", clamp ? GLTF_CLAMP_TO_EDGE : GLTF_REPEAT);
    gltf_number(w, s, "wrapT", clamp ? GLTF_CLAMP_TO_EDGE : GLTF_REPEAT);
    cJSON *t = gltf_entry(w, w->textures, &texture);
    gltf_number(w, t, "source", image);
    gltf_number(w, t, "sampler", sampler);
    return w->out_of_memory ? -1 : texture;
}

int gltf_write_material(gltf_write *w, const gltf_material *m) {
    static const char *const modes[] = {[GLTF_OPAQUE] = "OPAQUE", [GLTF_MASK] = "MASK", [GLTF_BLEND] = "BLEND"};
    int index;
    cJSON *material = gltf_entry(w, w->materials, &index);
    gltf_add(w, material, "name", cJSON_CreateString(m->name));
    cJSON *pbr = gltf_add(w, material, "pbrMetallicRoughness", cJSON_CreateObject());
    const double color[4] = {m->color[0], m->color[1], m->color[2], m->color[3]};
    gltf_numbers(w, pbr, "baseColorFactor", color, 4);
    gltf_number(w, pbr, "metallicFactor", 0);
    if (m->texture >= 0)
        gltf_number(w, gltf_add(w, pbr, "baseColorTexture", cJSON_CreateObject()), "index", m->texture);
    if (m->alpha != GLTF_OPAQUE)
        gltf_add(w, material, "alphaMode", cJSON_CreateString(modes[m->alpha]));
    if (m->alpha == GLTF_MASK && m->cutoff > 0)
        gltf_number(w, material, "alphaCutoff", m->cutoff);
    if (m->double_sided)
        gltf_add(w, material, "doubleSided", cJSON_CreateTrue());
    return w->out_of_memory ? -1 : index;
}

int gltf_write_mesh(gltf_write *w, const gltf_vertex *vertices, int vertex_count, const uint16_t *indices,
                    int index_count, int material) {
    size_t n = (size_t)vertex_count;
    float *columns = malloc(n * 8 * sizeof *columns);
    if (!columns) {
        w->out_of_memory = true;
        return -1;
    }
    double low[3] = {INFINITY, INFINITY, INFINITY}, high[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < n; v++) {
        memcpy(columns + 3 * v, vertices[v].position, sizeof vertices[v].position);
        memcpy(columns + 3 * n + 3 * v, vertices[v].normal, sizeof vertices[v].normal);
        memcpy(columns + 6 * n + 2 * v, vertices[v].uv, sizeof vertices[v].uv);
        for (int k = 0; k < 3; k++) {
            low[k] = fmin(low[k], vertices[v].position[k]);
            high[k] = fmax(high[k], vertices[v].position[k]);
        }
    }
    int position =
        gltf_accessor(w, columns, 3 * n * sizeof *columns, vertex_count, "VEC3", GLTF_FLOAT, GLTF_ARRAY_BUFFER);
    int normal = gltf_accessor(w, columns + 3 * n, 3 * n * sizeof *columns, vertex_count, "VEC3", GLTF_FLOAT,
                               GLTF_ARRAY_BUFFER);
    int uv = gltf_accessor(w, columns + 6 * n, 2 * n * sizeof *columns, vertex_count, "VEC2", GLTF_FLOAT,
                           GLTF_ARRAY_BUFFER);
    free(columns);
    int index_accessor = gltf_accessor(w, indices, (size_t)index_count * sizeof *indices, index_count, "SCALAR",
                                       GLTF_UNSIGNED_SHORT, GLTF_ELEMENT_ARRAY_BUFFER);
    cJSON *bounds = cJSON_GetArrayItem(w->accessors, position);
    gltf_numbers(w, bounds, "min", low, 3);
    gltf_numbers(w, bounds, "max", high, 3);
    int index;
    cJSON *mesh = gltf_entry(w, w->meshes, &index);
    cJSON *primitives = gltf_add(w, mesh, "primitives", cJSON_CreateArray());
    cJSON *primitive = gltf_add(w, primitives, NULL, cJSON_CreateObject());
    cJSON *attributes = gltf_add(w, primitive, "attributes", cJSON_CreateObject());
    gltf_number(w, attributes, "POSITION", position);
    gltf_number(w, attributes, "NORMAL", normal);
    gltf_number(w, attributes, "TEXCOORD_0", uv);
    gltf_number(w, primitive, "indices", index_accessor);
    gltf_number(w, primitive, "material", material);
    return w->out_of_memory ? -1 : index;
}

/* A node of the scene, named; its index. */
static cJSON *gltf_node(gltf_write *w, const char *name, int *index) {
    cJSON *node = gltf_entry(w, w->nodes, index);
    gltf_add(w, node, "name", cJSON_CreateString(name));
    gltf_add(w, w->scene_nodes, NULL, cJSON_CreateNumber(*index));
    return node;
}

/* The unit quaternion (x, y, z, w) turning -Z to `look`. */
static void gltf_look_rotation(const double look[3], double q[4]) {
    double length = sqrt(look[0] * look[0] + look[1] * look[1] + look[2] * look[2]);
    double b[3] = {look[0] / length, look[1] / length, look[2] / length};
    /* a x b and 1 + a . b, a = (0, 0, -1); half-way when b is +Z. */
    double x = b[1], y = -b[0], w = 1 - b[2];
    if (w < 1e-12) {
        x = 0, y = 1, w = 0;
    }
    double norm = sqrt(x * x + y * y + w * w);
    q[0] = x / norm, q[1] = y / norm, q[2] = 0, q[3] = w / norm;
}

static void gltf_place_node(gltf_write *w, cJSON *node, const gltf_place *place) {
    gltf_numbers(w, node, "translation", place->translation, 3);
    if (place->look[0] != 0 || place->look[1] != 0 || place->look[2] != 0) {
        double q[4];
        gltf_look_rotation(place->look, q);
        gltf_numbers(w, node, "rotation", q, 4);
    }
}

int gltf_write_mesh_node(gltf_write *w, const char *name, int mesh) {
    int index;
    cJSON *node = gltf_node(w, name, &index);
    gltf_number(w, node, "mesh", mesh);
    return w->out_of_memory ? -1 : index;
}

int gltf_write_camera(gltf_write *w, const char *name, const double eye[3], const double target[3], double yfov,
                      double aspect, double znear, double zfar) {
    int camera, index;
    cJSON *c = gltf_entry(w, w->cameras, &camera);
    gltf_add(w, c, "type", cJSON_CreateString("perspective"));
    cJSON *p = gltf_add(w, c, "perspective", cJSON_CreateObject());
    gltf_number(w, p, "yfov", yfov);
    gltf_number(w, p, "aspectRatio", aspect);
    gltf_number(w, p, "znear", znear);
    gltf_number(w, p, "zfar", zfar);
    cJSON *node = gltf_node(w, name, &index);
    gltf_number(w, node, "camera", camera);
    gltf_place place = {{eye[0], eye[1], eye[2]}, {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]}};
    gltf_place_node(w, node, &place);
    return w->out_of_memory ? -1 : index;
}

int gltf_write_light(gltf_write *w, const char *name, const char *type, const float color[3], double intensity,
                     double inner_cone, double outer_cone, const gltf_place *place) {
    int light, index;
    cJSON *l = gltf_entry(w, w->lights, &light);
    const double rgb[3] = {color[0], color[1], color[2]};
    gltf_add(w, l, "name", cJSON_CreateString(name));
    gltf_add(w, l, "type", cJSON_CreateString(type));
    gltf_numbers(w, l, "color", rgb, 3);
    gltf_number(w, l, "intensity", intensity);
    if (strcmp(type, "spot") == 0) {
        cJSON *spot = gltf_add(w, l, "spot", cJSON_CreateObject());
        gltf_number(w, spot, "innerConeAngle", inner_cone);
        gltf_number(w, spot, "outerConeAngle", outer_cone);
    }
    char node_name[128];
    snprintf(node_name, sizeof node_name, "%s_node", name);
    cJSON *node = gltf_node(w, node_name, &index);
    gltf_place_node(w, node, place);
    cJSON *extensions = gltf_add(w, node, "extensions", cJSON_CreateObject());
    cJSON *punctual = gltf_add(w, extensions, "KHR_lights_punctual", cJSON_CreateObject());
    gltf_number(w, punctual, "light", light);
    return w->out_of_memory ? -1 : index;
}

cJSON *gltf_write_end(gltf_write *w) {
    char *uri = w->out_of_memory ? NULL : gltf_data_uri("application/octet-stream", w->buffer, w->size);
    cJSON *buffers = gltf_add(w, w->root, "buffers", cJSON_CreateArray());
    cJSON *buffer = gltf_add(w, buffers, NULL, cJSON_CreateObject());
    gltf_number(w, buffer, "byteLength", (double)w->size);
    gltf_add(w, buffer, "uri", uri ? cJSON_CreateString(uri) : NULL);
    free(uri);
    free(w->buffer);
    cJSON *root = w->root;
    bool failed = w->out_of_memory;
    free(w);
    if (failed) {
        fprintf(stderr, "gltf_write: out of memory\n");
        cJSON_Delete(root);
        return NULL;
    }
    return root;
}
