/* map_tiles: the shadow atlas's GL texture and each cube face's tile in
 * it (map.h, "Atlas"; map_atlas.c places the tiles). */
#include <glad/gl.h>
#include <string.h>

#include "map_internal.h"

bool map_tiles_wanted(const map_renderer *r, const map_settings *st, const scene_light *light, map_kind kind) {
    return st->many_lights && kind == MAP_CUBE && !map_light_soft(st, light) &&
           map_filter_moments(map_filter_in_use(st)) == MAP_MOMENTS_NONE && st->rays == MAP_RAYS_OFF &&
           !r->transmit.id;
}

int map_tiles_size(map_renderer *r, map_light *m, const scene_light *light, map_samples samples) {
    int size = map_auto_size(m, light, samples.samples, samples.count, samples.grazing);
    for (int face = 0; face < MAP_CUBE_FACES; face++) {
        int n = 0;
        for (int i = 0; i < samples.count; i++)
            if (warp_cube_face(light->position, samples.samples[i].position) == face)
                r->face_samples[n++] = samples.samples[i];
        bool seen = map_auto_size_or(m, light, r->face_samples, n, 0) > 0;
        m->tiles[face] = (map_tile){.size = seen ? size : MAP_ATLAS_MIN_TILE};
    }
    return size;
}

/* The atlas's side: MAP_ATLAS_SIZE, or the GL's largest power of two
 * below it. */
static int map_atlas_side(void) {
    int largest = 0, side = MAP_ATLAS_SIZE;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &largest);
    while (side > largest && side > MAP_ATLAS_MIN_TILE)
        side /= 2;
    return side;
}

bool map_atlas_prepare(map_renderer *r, const map_settings *st) {
    int filter = map_filter_in_use(st);
    if (r->atlas_texture && r->atlas_depth == st->depth) {
        if (r->atlas_filter != filter) {
            glBindTexture(GL_TEXTURE_2D, r->atlas_texture);
            map_depth_sampling(GL_TEXTURE_2D, filter);
            r->atlas_filter = filter;
        }
        return true;
    }
    if (!r->atlas.nodes && !map_atlas_init(&r->atlas, map_atlas_side())) {
        fprintf(stderr, "shadow maps: out of memory for the shadow atlas's tiles\n");
        return false;
    }
    /* A texture made again holds nothing: every tile is free. */
    map_atlas_clear(&r->atlas);
    memset(r->tile_nodes, -1, sizeof r->tile_nodes);
    glDeleteTextures(1, &r->atlas_texture);
    glGenTextures(1, &r->atlas_texture);
    glBindTexture(GL_TEXTURE_2D, r->atlas_texture);
    GLenum format, type;
    map_depth_format(st->depth, &format, &type);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)format, r->atlas.size, r->atlas.size, 0, GL_DEPTH_COMPONENT, type, NULL);
    map_depth_sampling(GL_TEXTURE_2D, filter);
    r->atlas_depth = st->depth;
    r->atlas_filter = filter;
    return true;
}

bool map_tile_held(const map_renderer *r, const map_light *m, int l, int face) {
    return r->tile_nodes[l][face] >= 0 && r->tile_asked[l][face] == m->tiles[face].size;
}

map_tile_placed map_tile_place(map_renderer *r, map_light *m, int l, int face) {
    int *node = &r->tile_nodes[l][face], asked = m->tiles[face].size;
    if (map_tile_held(r, m, l, face)) {
        m->tiles[face] = map_atlas_tile(&r->atlas, *node);
        return MAP_TILE_KEPT;
    }
    if (*node >= 0)
        map_atlas_free(&r->atlas, *node);
    *node = -1;
    r->tile_asked[l][face] = asked;
    for (int size = asked; size >= MAP_ATLAS_MIN_TILE && *node < 0; size /= 2)
        *node = map_atlas_take(&r->atlas, size);
    if (*node < 0)
        return MAP_TILE_NO_ROOM;
    m->tiles[face] = map_atlas_tile(&r->atlas, *node);
    r->tiles_short += m->tiles[face].size < asked;
    return MAP_TILE_NEW;
}

void map_tiles_release(map_renderer *r, int l) {
    for (int face = 0; face < MAP_CUBE_FACES; face++) {
        if (r->tile_nodes[l][face] >= 0)
            map_atlas_free(&r->atlas, r->tile_nodes[l][face]);
        r->tile_nodes[l][face] = -1;
    }
}

map_light map_atlas_as_map(const map_renderer *r) {
    return (map_light){.kind = MAP_2D,
                       .layer_count = 1,
                       .size = r->atlas.size,
                       .near_plane = 0,
                       .far_plane = 1,
                       .orthographic = true,
                       .texture = {.id = r->atlas_texture}};
}
