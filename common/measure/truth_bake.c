/* truth_bake: see truth_bake.h. */
#include "truth_bake.h"

#include <cJSON.h>
#include <dirent.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "image.h"
#include "json.h"
#include "path.h"

/* view.json names every object: room for the largest scenes'. */
#define TRUTH_BAKE_MAX_VIEW_FILE (4 << 20)
/* The depth's bits that are not stored, and their middle, added back. */
#define TRUTH_BAKE_DEPTH_DROPPED_BITS 8
#define TRUTH_BAKE_DEPTH_MIDDLE (1u << (TRUTH_BAKE_DEPTH_DROPPED_BITS - 1))
#define TRUTH_BAKE_DEPTH_MASK 0xffffffu
#define TRUTH_BAKE_DEPTH_SIGN 0x800000u
/* An octahedral coordinate's 16 bits: -1..1 as 0..65535. */
#define TRUTH_BAKE_OCTAHEDRAL_ONE 65535.0f
/* Ids are stored plus one in 16 bits; 0 is "no surface". */
#define TRUTH_BAKE_MAX_OBJECTS (UINT16_MAX - 1)
/* FNV-1a, 64 bits. */
#define TRUTH_BAKE_HASH_START 0xcbf29ce484222325ull
#define TRUTH_BAKE_HASH_PRIME 0x100000001b3ull

static const char *const truth_bake_images[] = {"color.png", "surface.png", "depth.png", "normal.png"};
enum { TRUTH_BAKE_COLOR, TRUTH_BAKE_SURFACE, TRUTH_BAKE_DEPTH, TRUTH_BAKE_NORMAL, TRUTH_BAKE_IMAGES };

void truth_bake_view_of(const scene *s, int width, int height, int light_index, const raytrace_settings *settings,
                        truth_bake_view *out) {
    *out = (truth_bake_view){
        .width = width,
        .height = height,
        .light_index = light_index,
        .light_samples =
            settings && settings->light_samples > 0 ? settings->light_samples : RAYTRACE_DEFAULT_LIGHT_SAMPLES,
    };
    float *n = out->numbers;
    int k = 0;
    const scene_camera *c = &s->camera;
    const float origin[3] = {(float)s->origin[0], (float)s->origin[1], (float)s->origin[2]};
    const float *triples[] = {c->position, c->target, c->up, origin, s->ambient};
    for (size_t t = 0; t < sizeof triples / sizeof *triples; t++)
        for (int i = 0; i < 3; i++)
            n[k++] = triples[t][i];
    n[k++] = c->fov_deg;
    n[k++] = c->near_plane;
    n[k++] = c->far_plane;
    n[k++] = c->reversed_depth ? 1.0f : 0.0f;
    n[k++] = (float)s->light_count;
    for (int l = 0; l < s->light_count; l++) {
        const scene_light *light = &s->lights[l];
        const float *light_triples[] = {light->position, light->direction, light->color};
        n[k++] = (float)light->type;
        for (int t = 0; t < 3; t++)
            for (int i = 0; i < 3; i++)
                n[k++] = light_triples[t][i];
        n[k++] = light->intensity;
        n[k++] = light->inner_angle_deg;
        n[k++] = light->outer_angle_deg;
        n[k++] = light->radius;
        n[k++] = light->range;
    }
    out->count = k;
}

static uint64_t truth_bake_hash(uint64_t h, const void *data, size_t size) {
    const unsigned char *bytes = data;
    for (size_t i = 0; i < size; i++)
        h = (h ^ bytes[i]) * TRUTH_BAKE_HASH_PRIME;
    return h;
}

/* The folder's name: the view and the objects' names hashed. */
static uint64_t truth_bake_key(const truth_bake_view *v, const scene *s) {
    const int ints[] = {v->width, v->height, v->light_index, v->light_samples, v->count};
    uint64_t h = truth_bake_hash(TRUTH_BAKE_HASH_START, ints, sizeof ints);
    h = truth_bake_hash(h, v->numbers, (size_t)v->count * sizeof *v->numbers);
    for (int i = 0; i < s->object_count; i++)
        h = truth_bake_hash(h, s->objects[i].name, strlen(s->objects[i].name) + 1);
    return h;
}

/* ---- the arrays as bytes ---- */

static void truth_bake_put16(unsigned char *bytes, unsigned value) {
    bytes[0] = (unsigned char)(value >> 8);
    bytes[1] = (unsigned char)value;
}

static unsigned truth_bake_get16(const unsigned char *bytes) { return (unsigned)bytes[0] << 8 | bytes[1]; }

static float truth_bake_sign(float v) { return v >= 0 ? 1.0f : -1.0f; }

/* A unit vector's octahedral coordinates, -1..1 each, and back. */
static void truth_bake_octahedral(const float n[3], float out[2]) {
    float sum = fabsf(n[0]) + fabsf(n[1]) + fabsf(n[2]);
    float x = sum > 0 ? n[0] / sum : 0, y = sum > 0 ? n[1] / sum : 0;
    if (n[2] < 0) {
        float folded_x = (1 - fabsf(y)) * truth_bake_sign(x);
        y = (1 - fabsf(x)) * truth_bake_sign(y);
        x = folded_x;
    }
    out[0] = x;
    out[1] = y;
}

static void truth_bake_from_octahedral(const float o[2], float out[3]) {
    float x = o[0], y = o[1], z = 1 - fabsf(x) - fabsf(y);
    if (z < 0) {
        float unfolded_x = (1 - fabsf(y)) * truth_bake_sign(x);
        y = (1 - fabsf(x)) * truth_bake_sign(y);
        x = unfolded_x;
    }
    vec3 n = {x, y, z};
    glm_vec3_normalize(n);
    glm_vec3_copy(n, out);
}

/* Pixel i's depth as stored: its binary32 bits but the lowest, 0 where no
 * surface is seen. */
static uint32_t truth_bake_depth_bits(const dump_frame *t, size_t i) {
    uint32_t bits = 0;
    if (t->ids[i] >= 0)
        memcpy(&bits, &t->depth[i], sizeof bits);
    return bits >> TRUTH_BAKE_DEPTH_DROPPED_BITS;
}

/* A step between two stored depths (modulo 2^24) as a 24-bit number
 * that is small when the step is small either way, and back. */
static uint32_t truth_bake_zigzag(uint32_t step) {
    step &= TRUTH_BAKE_DEPTH_MASK;
    return step & TRUTH_BAKE_DEPTH_SIGN ? (~step << 1 | 1) & TRUTH_BAKE_DEPTH_MASK : step << 1;
}

static uint32_t truth_bake_unzigzag(uint32_t z) { return z & 1 ? ~(z >> 1) & TRUTH_BAKE_DEPTH_MASK : z >> 1; }

static void truth_bake_encode(const dump_frame *t, size_t i, unsigned char *surface, unsigned char *depth,
                              unsigned char *normal) {
    bool seen = t->ids[i] >= 0;
    float visibility = seen ? fminf(fmaxf(t->visibility[i], 0), 1) : 0;
    truth_bake_put16(surface, (unsigned)lroundf(visibility * TRUTH_BAKE_VISIBILITY_ONE));
    truth_bake_put16(surface + 2, seen ? (unsigned)t->ids[i] + 1 : 0);
    uint32_t step =
        truth_bake_zigzag(truth_bake_depth_bits(t, i) - (i % (size_t)t->width ? truth_bake_depth_bits(t, i - 1) : 0));
    depth[0] = (unsigned char)(step >> 16);
    depth[1] = (unsigned char)(step >> 8);
    depth[2] = (unsigned char)step;
    depth[3] = UINT8_MAX;
    float o[2] = {0, 0};
    if (seen)
        truth_bake_octahedral(t->normal + 3 * i, o);
    for (int k = 0; k < 2; k++)
        truth_bake_put16(normal + 2 * k, (unsigned)lroundf((o[k] * 0.5f + 0.5f) * TRUTH_BAKE_OCTAHEDRAL_ONE));
}

/* Pixel i of the frame from its bytes and stored depth; the position
 * along the pixel's ray from `eye` (ray: unit). */
static void truth_bake_decode(const unsigned char *const images[TRUTH_BAKE_IMAGES], size_t i, uint32_t depth,
                              const float eye[3], const float ray[3], dump_frame *out) {
    memcpy(out->color + 4 * i, images[TRUTH_BAKE_COLOR] + 4 * i, 4);
    const unsigned char *surface = images[TRUTH_BAKE_SURFACE] + 4 * i;
    unsigned id = truth_bake_get16(surface + 2);
    if (id == 0)
        return; /* dump_frame_create's "no surface" */
    out->visibility[i] = (float)truth_bake_get16(surface) / TRUTH_BAKE_VISIBILITY_ONE;
    out->ids[i] = (float)(id - 1);
    uint32_t bits = depth << TRUTH_BAKE_DEPTH_DROPPED_BITS | TRUTH_BAKE_DEPTH_MIDDLE;
    memcpy(&out->depth[i], &bits, sizeof bits);
    const unsigned char *n = images[TRUTH_BAKE_NORMAL] + 4 * i;
    const float o[2] = {truth_bake_get16(n) / TRUTH_BAKE_OCTAHEDRAL_ONE * 2 - 1,
                        truth_bake_get16(n + 2) / TRUTH_BAKE_OCTAHEDRAL_ONE * 2 - 1};
    truth_bake_from_octahedral(o, out->normal + 3 * i);
    for (int k = 0; k < 3; k++)
        out->position[3 * i + (size_t)k] = eye[k] + ray[k] * out->depth[i];
}

/* ---- writing ---- */

static bool truth_bake_write_view(const char *path, const truth_bake_view *v, const scene *s) {
    cJSON *root = cJSON_CreateObject();
    cJSON_AddNumberToObject(root, "width", v->width);
    cJSON_AddNumberToObject(root, "height", v->height);
    cJSON_AddNumberToObject(root, "light_index", v->light_index);
    cJSON_AddNumberToObject(root, "light_samples", v->light_samples);
    cJSON *names = cJSON_AddArrayToObject(root, "objects");
    for (int i = 0; i < s->object_count; i++)
        cJSON_AddItemToArray(names, cJSON_CreateString(s->objects[i].name));
    cJSON_AddItemToObject(root, "view", cJSON_CreateFloatArray(v->numbers, v->count));
    return json_save(root, path);
}

bool truth_bake_write(const char *dir, const dump_frame *truth, const scene *s, const raytrace_settings *settings) {
    if (s->object_count > TRUTH_BAKE_MAX_OBJECTS) {
        fprintf(stderr, "%s: a baked truth holds at most %d objects, the scene has %d\n", dir, TRUTH_BAKE_MAX_OBJECTS,
                s->object_count);
        return false;
    }
    truth_bake_view view;
    truth_bake_view_of(s, truth->width, truth->height, truth->light_index, settings, &view);
    char folder[PATH_MAX], path[PATH_MAX + 32];
    snprintf(folder, sizeof folder, "%s/%016llx", dir, (unsigned long long)truth_bake_key(&view, s));
    if (!path_make_directories(folder))
        return false;
    size_t n = (size_t)truth->width * (size_t)truth->height;
    unsigned char *bytes = malloc(3 * 4 * n);
    if (!bytes) {
        fprintf(stderr, "%s: out of memory for a %dx%d truth\n", folder, truth->width, truth->height);
        return false;
    }
    const unsigned char *images[TRUTH_BAKE_IMAGES] = {truth->color, bytes, bytes + 4 * n, bytes + 8 * n};
    for (size_t i = 0; i < n; i++)
        truth_bake_encode(truth, i, bytes + 4 * i, bytes + 4 * n + 4 * i, bytes + 8 * n + 4 * i);
    bool ok = true;
    for (int k = 0; k < TRUTH_BAKE_IMAGES && ok; k++) {
        snprintf(path, sizeof path, "%s/%s", folder, truth_bake_images[k]);
        ok = image_write_png(path, truth->width, truth->height, images[k]);
    }
    free(bytes);
    snprintf(path, sizeof path, "%s/view.json", folder);
    ok = ok && truth_bake_write_view(path, &view, s);
    if (ok)
        printf("%s\n", folder);
    return ok;
}

/* ---- finding ---- */

static bool truth_bake_close(double a, double b) {
    return fabs(a - b) <= TRUTH_BAKE_VIEW_TOLERANCE * fmax(1.0, fmax(fabs(a), fabs(b)));
}

static bool truth_bake_number_is(const cJSON *root, const char *key, int value) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(root, key);
    return cJSON_IsNumber(v) && v->valuedouble == value;
}

/* Whether view.json at `path` is of `want` (the objects `s`'s); a file
 * that cannot be read says so and is none. */
static bool truth_bake_is_of(const char *path, const truth_bake_view *want, const scene *s, bool *error) {
    cJSON *root = json_load(path, TRUTH_BAKE_MAX_VIEW_FILE);
    if (!root) {
        *error = true;
        return false;
    }
    const cJSON *numbers = cJSON_GetObjectItemCaseSensitive(root, "view");
    const cJSON *names = cJSON_GetObjectItemCaseSensitive(root, "objects");
    bool same = truth_bake_number_is(root, "width", want->width) &&
                truth_bake_number_is(root, "height", want->height) &&
                truth_bake_number_is(root, "light_index", want->light_index) &&
                truth_bake_number_is(root, "light_samples", want->light_samples) && cJSON_IsArray(numbers) &&
                cJSON_GetArraySize(numbers) == want->count && cJSON_IsArray(names) &&
                cJSON_GetArraySize(names) == s->object_count;
    for (int i = 0; same && i < want->count; i++) {
        const cJSON *v = cJSON_GetArrayItem(numbers, i);
        same = cJSON_IsNumber(v) && truth_bake_close(v->valuedouble, want->numbers[i]);
    }
    for (int i = 0; same && i < s->object_count; i++) {
        const cJSON *name = cJSON_GetArrayItem(names, i);
        same = cJSON_IsString(name) && strcmp(name->valuestring, s->objects[i].name) == 0;
    }
    cJSON_Delete(root);
    return same;
}

/* The unit ray through the centre of pixel (x, y), y = 0 the top row,
 * from the near plane's corners (camera_view). */
static void truth_bake_pixel_ray(const camera_view *v, int width, int height, int x, int y, float ray[3]) {
    float u = ((float)x + 0.5f) / (float)width, w = 1.0f - ((float)y + 0.5f) / (float)height;
    vec3 bottom, top, point;
    glm_vec3_lerp((float *)v->corners[0], (float *)v->corners[1], u, bottom);
    glm_vec3_lerp((float *)v->corners[2], (float *)v->corners[3], u, top);
    glm_vec3_lerp(bottom, top, w, point);
    glm_vec3_sub(point, (float *)v->eye, point);
    glm_vec3_normalize(point);
    glm_vec3_copy(point, ray);
}

static bool truth_bake_read(const char *folder, const scene *s, const truth_bake_view *v, dump_frame *out) {
    if (!dump_frame_create(out, v->width, v->height, s, v->light_index)) {
        fprintf(stderr, "%s: out of memory for a %dx%d truth\n", folder, v->width, v->height);
        return false;
    }
    unsigned char *images[TRUTH_BAKE_IMAGES] = {0};
    bool ok = true;
    for (int k = 0; k < TRUTH_BAKE_IMAGES && ok; k++) {
        char path[PATH_MAX + 32];
        snprintf(path, sizeof path, "%s/%s", folder, truth_bake_images[k]);
        int width, height;
        ok = (images[k] = image_read_png(path, &width, &height)) != NULL;
        if (ok && (width != v->width || height != v->height)) {
            fprintf(stderr, "%s: %dx%d, but view.json says %dx%d\n", path, width, height, v->width, v->height);
            ok = false;
        }
    }
    if (ok) {
        camera_view view;
        camera_view_compute(&s->camera, (float)v->width / (float)v->height, &view);
        for (int y = 0; y < v->height; y++) {
            uint32_t depth = 0; /* the row's steps summed */
            for (int x = 0; x < v->width; x++) {
                size_t i = (size_t)y * (size_t)v->width + (size_t)x;
                const unsigned char *step = images[TRUTH_BAKE_DEPTH] + 4 * i;
                depth = (depth + truth_bake_unzigzag((uint32_t)step[0] << 16 | (uint32_t)step[1] << 8 | step[2])) &
                        TRUTH_BAKE_DEPTH_MASK;
                float ray[3];
                truth_bake_pixel_ray(&view, v->width, v->height, x, y, ray);
                truth_bake_decode((const unsigned char *const *)images, i, depth, view.eye, ray, out);
            }
        }
    }
    for (int k = 0; k < TRUTH_BAKE_IMAGES; k++)
        free(images[k]);
    if (!ok)
        dump_frame_free(out);
    return ok;
}

truth_bake_found truth_bake_find(const char *dir, const scene *s, int width, int height, int light_index,
                                 const raytrace_settings *settings, dump_frame *out) {
    truth_bake_view want;
    truth_bake_view_of(s, width, height, light_index, settings, &want);
    DIR *folders = opendir(dir);
    if (!folders)
        return TRUTH_BAKE_NONE;
    truth_bake_found found = TRUTH_BAKE_NONE;
    const struct dirent *entry;
    while (found == TRUTH_BAKE_NONE && (entry = readdir(folders))) {
        if (entry->d_name[0] == '.')
            continue;
        char folder[PATH_MAX], path[PATH_MAX + 32];
        snprintf(folder, sizeof folder, "%s/%s", dir, entry->d_name);
        snprintf(path, sizeof path, "%s/view.json", folder);
        bool error = false;
        if (truth_bake_is_of(path, &want, s, &error))
            found = truth_bake_read(folder, s, &want, out) ? TRUTH_BAKE_FOUND : TRUTH_BAKE_ERROR;
        else if (error)
            found = TRUTH_BAKE_ERROR;
    }
    closedir(folders);
    return found;
}
