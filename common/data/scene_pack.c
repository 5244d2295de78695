/* scene_pack: see scene_pack.h. One walk of the scene's fields writes the
 * file and reads it back, so that the two orders cannot differ. */
#include "scene_pack.h"

#include <cglm/cglm.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh_pack.h"
#include "scene_internal.h"
#include "texture.h"

#define SCENE_PACK_CHANNELS 4 /* RGBA */
#define SCENE_PACK_NO_TEXTURE (-1)

typedef struct scene_pack_io {
    FILE *f;
    const char *path;
    bool writing;
    /* The first problem, NULL while there is none; `said` where a line
     * has said it already (a mesh pack's own). */
    const char *problem;
    bool said;
} scene_pack_io;

static bool scene_pack_ok(const scene_pack_io *io) { return !io->problem; }

static void scene_pack_fail(scene_pack_io *io, const char *problem) {
    if (!io->problem)
        io->problem = problem;
}

/* size bytes at data, written or read. */
static void scene_pack_bytes(scene_pack_io *io, void *data, size_t size) {
    if (!scene_pack_ok(io) || size == 0)
        return;
    if (io->writing ? fwrite(data, size, 1, io->f) != 1 : fread(data, size, 1, io->f) != 1)
        scene_pack_fail(io, io->writing ? "cannot write" : "truncated");
}

static void scene_pack_floats(scene_pack_io *io, float *values, size_t count) {
    scene_pack_bytes(io, values, count * sizeof *values);
}

/* A count, flag or kind as a uint32 of min..max: `value` written, or
 * the value read; either returned. */
static uint32_t scene_pack_number(scene_pack_io *io, uint32_t value, uint32_t min, uint32_t max, const char *what) {
    scene_pack_bytes(io, &value, sizeof value);
    if (scene_pack_ok(io) && (value < min || value > max))
        scene_pack_fail(io, what);
    return value;
}

static void scene_pack_flag(scene_pack_io *io, bool *flag) {
    uint32_t value = scene_pack_number(io, *flag, 0, 1, "a flag neither 0 nor 1");
    if (!io->writing)
        *flag = value;
}

/* Floats of a struct, in the order given: each run's place and length. */
typedef struct scene_pack_run {
    float *at;
    size_t count;
} scene_pack_run;

static void scene_pack_runs(scene_pack_io *io, const scene_pack_run *runs, size_t count) {
    for (size_t k = 0; k < count; k++)
        scene_pack_floats(io, runs[k].at, runs[k].count);
}

static void scene_pack_camera(scene_pack_io *io, scene_camera *c) {
    const scene_pack_run runs[] = {{c->position, 3}, {c->target, 3},      {c->up, 3},
                                   {&c->fov_deg, 1}, {&c->near_plane, 1}, {&c->far_plane, 1}};
    scene_pack_runs(io, runs, sizeof runs / sizeof *runs);
}

static void scene_pack_light(scene_pack_io *io, scene_light *l) {
    uint32_t type =
        scene_pack_number(io, l->type, SCENE_LIGHT_POINT, SCENE_LIGHT_DIRECTIONAL, "an unknown light type");
    if (!io->writing)
        l->type = (scene_light_type)type;
    const scene_pack_run runs[] = {
        {l->position, 3},         {l->direction, 3},        {l->color, 3},   {&l->intensity, 1},
        {&l->inner_angle_deg, 1}, {&l->outer_angle_deg, 1}, {&l->radius, 1}, {&l->range, 1}};
    scene_pack_runs(io, runs, sizeof runs / sizeof *runs);
}

static void scene_pack_texture(scene_pack_io *io, texture *t) {
    for (int k = 0; k < 2; k++) {
        uint32_t wrap =
            scene_pack_number(io, t->wrap[k], TEXTURE_REPEAT, TEXTURE_CLAMP_TO_EDGE, "an unknown wrap mode");
        if (!io->writing)
            t->wrap[k] = (texture_wrap)wrap;
    }
    uint32_t levels = scene_pack_number(io, (uint32_t)t->level_count, 1, TEXTURE_MAX_LEVELS, "a texture's levels");
    for (uint32_t l = 0; l < levels && scene_pack_ok(io); l++) {
        texture_level *level = &t->levels[l];
        uint32_t width = scene_pack_number(io, (uint32_t)level->width, 1, TEXTURE_MAX_SIZE, "a texture's width");
        uint32_t height = scene_pack_number(io, (uint32_t)level->height, 1, TEXTURE_MAX_SIZE, "a texture's height");
        size_t bytes = SCENE_PACK_CHANNELS * (size_t)width * height;
        if (!io->writing && scene_pack_ok(io)) {
            *level = (texture_level){.width = (int)width, .height = (int)height, .rgba = malloc(bytes)};
            t->level_count = (int)l + 1; /* what texture_free frees */
            if (!level->rgba)
                scene_pack_fail(io, "out of memory for a texture");
        }
        scene_pack_bytes(io, level->rgba, bytes);
    }
}

/* Object o, its texture an index among s's textures. */
static void scene_pack_object(scene_pack_io *io, scene *s, scene_object *o) {
    scene_pack_bytes(io, o->name, sizeof o->name);
    if (scene_pack_ok(io) && memchr(o->name, '\0', sizeof o->name) == NULL)
        scene_pack_fail(io, "an object's name without its end");
    uint32_t kind = scene_pack_number(io, o->mesh_kind, SCENE_MESH_PLANE, SCENE_MESH_MODEL, "an unknown mesh kind");
    const scene_pack_run runs[] = {{&o->model[0][0], sizeof o->model / sizeof o->model[0][0]}, {o->color, 3}};
    scene_pack_runs(io, runs, sizeof runs / sizeof *runs);
    int32_t texture = o->base_color ? (int32_t)(o->base_color - s->textures) : SCENE_PACK_NO_TEXTURE;
    texture = (int32_t)scene_pack_number(io, (uint32_t)(texture - SCENE_PACK_NO_TEXTURE), 0,
                                         (uint32_t)s->texture_count, "a texture index out of range") +
              SCENE_PACK_NO_TEXTURE;
    scene_pack_runs(io, (const scene_pack_run[]){{&o->alpha_cutoff, 1}, {&o->base_alpha, 1}}, 2);
    scene_pack_flag(io, &o->translucent);
    scene_pack_flag(io, &o->single_sided);
    scene_pack_flag(io, &o->casts);
    scene_pack_flag(io, &o->receives);
    if (!io->writing) {
        o->mesh_kind = (scene_mesh_kind)kind;
        o->base_color = texture == SCENE_PACK_NO_TEXTURE ? NULL : &s->textures[texture];
    }
    if (!scene_pack_ok(io))
        return;
    if (io->writing && !mesh_pack_put(io->f, &o->mesh, NULL))
        scene_pack_fail(io, "cannot write");
    if (!io->writing && !mesh_pack_get(io->f, io->path, &o->mesh, NULL)) {
        scene_pack_fail(io, "its mesh");
        io->said = true;
    }
}

/* The scene's arrays, allocated when read: `count` zeroed elements of
 * `size` bytes. */
static void *scene_pack_array(scene_pack_io *io, void *array, uint32_t count, size_t size) {
    if (io->writing || !scene_pack_ok(io) || count == 0)
        return array;
    void *made = calloc(count, size);
    if (!made)
        scene_pack_fail(io, "out of memory");
    return made;
}

static void scene_pack_scene(scene_pack_io *io, scene *s) {
    char magic[sizeof SCENE_PACK_MAGIC] = SCENE_PACK_MAGIC;
    scene_pack_bytes(io, magic, sizeof magic);
    if (scene_pack_ok(io) && memcmp(magic, SCENE_PACK_MAGIC, sizeof magic) != 0)
        scene_pack_fail(io, "not a scene pack (build/bake writes them)");
    /* Every object has a triangle, and every texture an object. */
    uint32_t objects = scene_pack_number(io, (uint32_t)s->object_count, 1, MESH_MAX_TRIANGLES, "an object count");
    uint32_t textures = scene_pack_number(io, (uint32_t)s->texture_count, 0, objects, "a texture count");
    uint32_t lights = scene_pack_number(io, (uint32_t)s->light_count, 0, SCENE_MAX_LIGHTS, "a light count");
    scene_pack_bytes(io, s->origin, sizeof s->origin);
    scene_pack_camera(io, &s->camera);
    scene_pack_floats(io, s->ambient, 3);
    for (uint32_t l = 0; l < lights && scene_pack_ok(io); l++) {
        scene_pack_light(io, &s->lights[l]);
        s->light_count = io->writing ? s->light_count : (int)l + 1;
    }
    s->textures = scene_pack_array(io, s->textures, textures, sizeof *s->textures);
    if (scene_pack_ok(io))
        s->texture_count = (int)textures;
    for (uint32_t t = 0; t < textures && scene_pack_ok(io); t++)
        scene_pack_texture(io, &s->textures[t]);
    s->objects = scene_pack_array(io, s->objects, objects, sizeof *s->objects);
    for (uint32_t i = 0; i < objects && scene_pack_ok(io); i++) {
        scene_pack_object(io, s, &s->objects[i]);
        s->object_count = io->writing ? s->object_count : (int)i + 1; /* what scene_free frees */
    }
}

bool scene_pack_write(const char *path, const scene *s) {
    scene_pack_io io = {.f = fopen(path, "wb"), .path = path, .writing = true};
    if (!io.f) {
        fprintf(stderr, "%s: cannot create: %s\n", path, strerror(errno));
        return false;
    }
    /* Written, never changed: the walk's pointers are a copy's. */
    scene view = *s;
    scene_pack_scene(&io, &view);
    int saved = errno;
    if (fclose(io.f) != 0)
        scene_pack_fail(&io, "cannot write");
    if (io.problem)
        fprintf(stderr, "%s: %s: %s\n", path, io.problem, strerror(errno ? errno : saved));
    return !io.problem;
}

bool scene_pack_read(scene *s, const char *path) {
    *s = (scene){0};
    scene_pack_io io = {.f = fopen(path, "rb"), .path = path};
    if (!io.f) {
        fprintf(stderr, "%s: cannot open: %s\n", path, strerror(errno));
        return false;
    }
    scene_pack_scene(&io, s);
    if (scene_pack_ok(&io) && fgetc(io.f) != EOF)
        scene_pack_fail(&io, "longer than its counts");
    fclose(io.f);
    if (io.problem && !io.said)
        fprintf(stderr, "%s: %s\n", path, io.problem);
    if (io.problem)
        scene_free(s);
    return !io.problem;
}

/* Object o of a pack placed by `model`, as scene_include_gltf places a
 * node's mesh (scene_object_place). */
static void scene_pack_place(scene_object *o, const double origin[3], const float model[4][4]) {
    mat4 own, placed, world;
    memcpy(own, o->model, sizeof own);
    for (int k = 0; k < 3; k++)
        own[3][k] = (float)(own[3][k] + origin[k]);
    memcpy(placed, model, sizeof placed);
    glm_mat4_mul(placed, own, world);
    scene_object_place(o, world);
}

bool scene_pack_include(scene *s, int *capacity, const char *path, const float model[4][4], const char *prefix,
                        bool casts, bool receives) {
    scene part;
    if (!scene_pack_read(&part, path))
        return false;
    /* The pack's textures become s's, after its own. */
    bool ok = scene_reserve_textures(s, (size_t)part.texture_count, path);
    texture *first = ok ? s->textures + s->texture_count : NULL;
    if (ok) {
        memcpy(first, part.textures, (size_t)part.texture_count * sizeof *first);
        s->texture_count += part.texture_count;
        part.texture_count = 0;
    }
    for (int i = 0; ok && i < part.object_count; i++) {
        ok = scene_reserve_object(s, capacity, path);
        if (!ok)
            break;
        scene_object *o = &s->objects[s->object_count++];
        *o = part.objects[i];
        part.objects[i].mesh = (mesh){0};
        snprintf(o->name, sizeof o->name, "%.*s/%.*s", SCENE_GLTF_PREFIX_MAX, prefix, SCENE_GLTF_NODE_NAME_MAX,
                 part.objects[i].name);
        if (o->base_color)
            o->base_color = first + (o->base_color - part.textures);
        o->single_sided = false;
        o->casts = casts;
        o->receives = receives;
        scene_pack_place(o, part.origin, model);
    }
    scene_free(&part);
    return ok;
}
