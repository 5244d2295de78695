#include "dump.h"

#include <cJSON.h>
#include <errno.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image.h"
#include "json.h"
#include "path.h"

#define DUMP_MAX_META_SIZE (1 << 20)
#define DUMP_VISIBILITY_RGB "visibility_rgb.pfm"

bool dump_frame_create(dump_frame *d, int width, int height, const scene *s, int light_index) {
    size_t n = (size_t)width * (size_t)height;
    *d = (dump_frame){.width = width,
                      .height = height,
                      .light_index = light_index,
                      .camera = s->camera,
                      .object_count = s->object_count};
    scene_light_homogeneous(&s->lights[light_index], d->light);
    d->object_names = calloc((size_t)s->object_count, sizeof *d->object_names);
    d->visibility = malloc(n * sizeof *d->visibility);
    d->depth = malloc(n * sizeof *d->depth);
    d->ids = malloc(n * sizeof *d->ids);
    d->normal = calloc(n * 3, sizeof *d->normal);
    d->position = calloc(n * 3, sizeof *d->position);
    d->color = calloc(n * 4, 1);
    bool coloured = scene_translucent_casters(s) > 0;
    if (coloured)
        d->visibility_rgb = malloc(3 * n * sizeof *d->visibility_rgb);
    if (!d->object_names || !d->visibility || !d->depth || !d->ids || !d->normal || !d->position || !d->color ||
        (coloured && !d->visibility_rgb)) {
        fprintf(stderr, "dump: out of memory for a %dx%d frame\n", width, height);
        dump_frame_free(d);
        return false;
    }
    for (int i = 0; i < s->object_count; i++)
        memcpy(d->object_names[i], s->objects[i].name, SCENE_NAME_MAX);
    for (size_t i = 0; i < n; i++)
        d->visibility[i] = d->depth[i] = d->ids[i] = -1;
    dump_frame_grey_rgb(d);
    return true;
}

void dump_frame_grey_rgb(dump_frame *d) {
    for (size_t i = 0; d->visibility_rgb && i < (size_t)d->width * (size_t)d->height; i++)
        for (int k = 0; k < 3; k++)
            d->visibility_rgb[3 * i + (size_t)k] = d->visibility[i];
}

void dump_frame_free(dump_frame *d) {
    free(d->object_names);
    free(d->visibility);
    free(d->visibility_rgb);
    free(d->depth);
    free(d->ids);
    free(d->normal);
    free(d->position);
    free(d->color);
    *d = (dump_frame){0};
}

bool dump_write_pfm(const char *path, int width, int height, int channels, const float *data) {
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "%s: cannot create: %s\n", path, strerror(errno));
        return false;
    }
    bool ok = fprintf(f, "%s\n%d %d\n-1\n", channels == 3 ? "PF" : "Pf", width, height) > 0;
    size_t row = (size_t)width * (size_t)channels;
    for (int y = height - 1; ok && y >= 0; y--)
        ok = fwrite(data + (size_t)y * row, sizeof *data, row, f) == row;
    if (fclose(f) != 0 || !ok) {
        fprintf(stderr, "%s: cannot write: %s\n", path, strerror(errno));
        return false;
    }
    return true;
}

float *dump_read_pfm(const char *path, int *width, int *height, int channels) {
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "%s: cannot open: %s\n", path, strerror(errno));
        return NULL;
    }
    char magic[3] = "";
    float scale = 0;
    float *data = NULL;
    const char *problem = NULL;
    if (fscanf(f, "%2s %d %d %f", magic, width, height, &scale) != 4 || fgetc(f) != '\n' ||
        strcmp(magic, channels == 3 ? "PF" : "Pf") != 0) {
        problem = channels == 3 ? "not a three-channel PFM (PF)" : "not a one-channel PFM (Pf)";
    } else if (*width < 1 || *height < 1 || *width > 65536 || *height > 65536) {
        problem = "image size out of range";
    } else if (scale >= 0) {
        problem = "big-endian PFM (positive scale) is not supported";
    } else {
        size_t row = (size_t)*width * (size_t)channels;
        data = malloc(row * (size_t)*height * sizeof *data);
        for (int y = *height - 1; data && y >= 0 && !problem; y--)
            if (fread(data + (size_t)y * row, sizeof *data, row, f) != row)
                problem = "truncated";
        if (!data)
            problem = "out of memory";
    }
    fclose(f);
    if (problem) {
        fprintf(stderr, "%s: %s\n", path, problem);
        free(data);
        return NULL;
    }
    return data;
}

static bool dump_write_meta(const dump_frame *d, const char *path) {
    cJSON *root = cJSON_CreateObject();
    cJSON_AddNumberToObject(root, "width", d->width);
    cJSON_AddNumberToObject(root, "height", d->height);
    cJSON_AddNumberToObject(root, "light_index", d->light_index);
    cJSON_AddItemToObject(root, "light", cJSON_CreateFloatArray(d->light, 4));
    cJSON *names = cJSON_AddArrayToObject(root, "objects");
    for (int i = 0; i < d->object_count; i++)
        cJSON_AddItemToArray(names, cJSON_CreateString(d->object_names[i]));
    const scene_camera *c = &d->camera;
    cJSON *camera = cJSON_AddObjectToObject(root, "camera");
    cJSON_AddItemToObject(camera, "position", cJSON_CreateFloatArray(c->position, 3));
    cJSON_AddItemToObject(camera, "target", cJSON_CreateFloatArray(c->target, 3));
    cJSON_AddItemToObject(camera, "up", cJSON_CreateFloatArray(c->up, 3));
    cJSON_AddNumberToObject(camera, "fov", c->fov_deg);
    cJSON_AddNumberToObject(camera, "near", c->near_plane);
    cJSON_AddNumberToObject(camera, "far", c->far_plane);
    return json_save(root, path);
}

bool dump_write(const dump_frame *d, const char *dir) {
    if (!path_make_directories(dir))
        return false;
    char path[PATH_MAX];
    const struct {
        const char *name;
        int channels;
        const float *data;
    } files[] = {
        {"visibility.pfm", 1, d->visibility}, {"depth.pfm", 1, d->depth}, {"normal.pfm", 3, d->normal},
        {"position.pfm", 3, d->position},     {"ids.pfm", 1, d->ids},
    };
    for (size_t i = 0; i < sizeof files / sizeof *files; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, files[i].name);
        if (!dump_write_pfm(path, d->width, d->height, files[i].channels, files[i].data))
            return false;
    }
    /* Written for a scene with translucent casters; else none is left
     * from an earlier dump of another scene, which dump_read would take. */
    snprintf(path, sizeof path, "%s/" DUMP_VISIBILITY_RGB, dir);
    if (d->visibility_rgb && !dump_write_pfm(path, d->width, d->height, 3, d->visibility_rgb))
        return false;
    if (!d->visibility_rgb && remove(path) != 0 && errno != ENOENT) {
        fprintf(stderr, "%s: cannot remove: %s\n", path, strerror(errno));
        return false;
    }
    snprintf(path, sizeof path, "%s/color.png", dir);
    if (!image_write_png(path, d->width, d->height, d->color))
        return false;
    snprintf(path, sizeof path, "%s/meta.json", dir);
    return dump_write_meta(d, path);
}

/* `count` numbers of array `key` of `object` into out; false if it is not
 * that. */
static bool dump_read_numbers(const cJSON *object, const char *key, float *out, int count) {
    const cJSON *array = cJSON_GetObjectItemCaseSensitive(object, key);
    bool ok = cJSON_IsArray(array) && cJSON_GetArraySize(array) == count;
    for (int i = 0; ok && i < count; i++) {
        const cJSON *v = cJSON_GetArrayItem(array, i);
        ok = cJSON_IsNumber(v);
        out[i] = ok ? (float)v->valuedouble : 0;
    }
    return ok;
}

static bool dump_read_number(const cJSON *object, const char *key, float *out) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(object, key);
    *out = cJSON_IsNumber(v) ? (float)v->valuedouble : 0;
    return cJSON_IsNumber(v);
}

/* meta.json's "camera" (dump.h), every key required. */
static bool dump_read_camera(const cJSON *root, scene_camera *c) {
    const cJSON *camera = cJSON_GetObjectItemCaseSensitive(root, "camera");
    return cJSON_IsObject(camera) && dump_read_numbers(camera, "position", c->position, 3) &&
           dump_read_numbers(camera, "target", c->target, 3) && dump_read_numbers(camera, "up", c->up, 3) &&
           dump_read_number(camera, "fov", &c->fov_deg) && dump_read_number(camera, "near", &c->near_plane) &&
           dump_read_number(camera, "far", &c->far_plane);
}

/* meta.json, checked as strictly as scene files: a dump from another
 * program or version must not be compared silently. */
static bool dump_read_meta(dump_frame *d, const char *path) {
    char *text = path_read_text(path, DUMP_MAX_META_SIZE, NULL);
    if (!text)
        return false;
    cJSON *root = cJSON_Parse(text);
    free(text);
    if (!root) {
        fprintf(stderr, "%s: not valid JSON\n", path);
        return false;
    }
    const cJSON *names = cJSON_GetObjectItemCaseSensitive(root, "objects");
    const cJSON *index = cJSON_GetObjectItemCaseSensitive(root, "light_index");
    bool ok = dump_read_numbers(root, "light", d->light, 4) && cJSON_IsArray(names) && cJSON_IsNumber(index) &&
              dump_read_camera(root, &d->camera);
    if (ok) {
        d->light_index = index->valueint;
        d->object_count = cJSON_GetArraySize(names);
        d->object_names = calloc((size_t)d->object_count + 1, sizeof *d->object_names);
        ok = d->object_names != NULL;
        for (int i = 0; ok && i < d->object_count; i++) {
            const cJSON *name = cJSON_GetArrayItem(names, i);
            ok = cJSON_IsString(name);
            if (ok)
                snprintf(d->object_names[i], SCENE_NAME_MAX, "%s", name->valuestring);
        }
    }
    if (!ok)
        fprintf(stderr,
                "%s: expected \"light\" (4 numbers), \"light_index\", \"objects\" (names) and \"camera\" "
                "(\"position\", \"target\", \"up\": 3 numbers each; \"fov\", \"near\", \"far\")\n",
                path);
    cJSON_Delete(root);
    return ok;
}

/* Whether the file at `path`, w x h, is the size of visibility.pfm, read
 * first; says so where it is not. */
static bool dump_same_size(const dump_frame *d, const char *path, int w, int h) {
    if (w == d->width && h == d->height)
        return true;
    fprintf(stderr, "%s: %dx%d, but visibility.pfm is %dx%d\n", path, w, h, d->width, d->height);
    return false;
}

bool dump_read(dump_frame *d, const char *dir) {
    *d = (dump_frame){0};
    char path[PATH_MAX];
    snprintf(path, sizeof path, "%s/meta.json", dir);
    if (!dump_read_meta(d, path)) {
        dump_frame_free(d);
        return false;
    }
    struct {
        const char *name;
        int channels;
        float **data;
    } files[] = {
        {"visibility.pfm", 1, &d->visibility}, {"depth.pfm", 1, &d->depth}, {"normal.pfm", 3, &d->normal},
        {"position.pfm", 3, &d->position},     {"ids.pfm", 1, &d->ids},
    };
    for (size_t i = 0; i < sizeof files / sizeof *files; i++) {
        int w, h;
        snprintf(path, sizeof path, "%s/%s", dir, files[i].name);
        *files[i].data = dump_read_pfm(path, &w, &h, files[i].channels);
        bool ok = *files[i].data != NULL;
        if (ok && i == 0) {
            d->width = w;
            d->height = h;
        }
        if (!ok || !dump_same_size(d, path, w, h)) {
            dump_frame_free(d);
            return false;
        }
    }
    int w, h;
    snprintf(path, sizeof path, "%s/color.png", dir);
    d->color = image_read_png(path, &w, &h);
    if (!d->color || !dump_same_size(d, path, w, h)) {
        dump_frame_free(d);
        return false;
    }
    snprintf(path, sizeof path, "%s/" DUMP_VISIBILITY_RGB, dir);
    if (access(path, F_OK) != 0)
        return true;
    d->visibility_rgb = dump_read_pfm(path, &w, &h, 3);
    if (!d->visibility_rgb || !dump_same_size(d, path, w, h)) {
        dump_frame_free(d);
        return false;
    }
    return true;
}
