/* map_tiles: the shadow atlas's GL texture and each cube face's tile in
 * it (map.h, "Atlas"; map_atlas.c places the tiles). */
#include <glad/gl.h>
#include <stdlib.h>
#include <string.h>

#include "map_internal.h"

bool map_tiles_wanted(const map_renderer *r, const map_settings *st, const scene_light *light, map_kind kind) {
    return st->many_lights && kind == MAP_CUBE && !map_light_soft(st, light) &&
           map_filter_moments(map_filter_in_use(st)) == MAP_MOMENTS_NONE && !r->transmit[0].id;
}

int map_tiles_size(map_renderer *r, map_light *m, const scene_light *light, map_samples samples, map_auto_rule rule) {
    int size = map_auto_size(m, light, samples, rule);
    for (int face = 0; face < MAP_CUBE_FACES; face++) {
        int n = 0;
        for (int i = 0; i < samples.count; i++)
            if (warp_cube_face(light->position, samples.samples[i].position) == face)
                r->face_samples[n++] = samples.samples[i];
        bool seen = map_auto_size_or(m, light, r->face_samples, n, 0, rule) > 0;
        m->tiles[face] = (map_tile){.size = seen ? size : MAP_ATLAS_MIN_TILE};
    }
    return size;
}

/* A tile a fitted light asks for: light l's layer. */
typedef struct map_tile_ask {
    int light, layer, size;
} map_tile_ask;

/* Every fitted light's tiles, into asks (room for a cube's faces a
 * light): how many. */
static int map_tile_asks(const map_renderer *r, int light_count, map_tile_ask *asks) {
    int count = 0;
    for (int l = 0; l < light_count; l++)
        for (int layer = 0; r->fitted[l] && r->maps[l].tiled && layer < r->maps[l].layer_count; layer++)
            asks[count++] = (map_tile_ask){l, layer, r->maps[l].tiles[layer].size};
    return count;
}

/* The asked tiles' area, in texels. */
static double map_tile_asks_area(const map_tile_ask *asks, int count) {
    double area = 0;
    for (int i = 0; i < count; i++)
        area += (double)asks[i].size * asks[i].size;
    return area;
}

/* The atlas's largest side: MAP_ATLAS_SIZE or the GL's largest power of
 * two below it. */
static int map_atlas_largest_side(const map_renderer *r) {
    return map_side_within_gl(r, MAP_ATLAS_SIZE, MAP_ATLAS_MIN_TILE);
}

/* The atlas's side for the asked tiles: the least power of two from
 * MAP_ATLAS_MIN_TILE whose square holds MAP_ATLAS_ROOM times their area,
 * up to the largest (0: no tile asked). */
static int map_atlas_side_wanted(const map_renderer *r, const map_tile_ask *asks, int count) {
    double area = map_tile_asks_area(asks, count);
    if (area == 0)
        return 0;
    int side = MAP_ATLAS_MIN_TILE, largest = map_atlas_largest_side(r);
    while (side < largest && (double)side * side < MAP_ATLAS_ROOM * area)
        side *= 2;
    return side;
}

/* Asks past the largest atlas (MAP_ATLAS_ROOM times their area more than
 * its square) are halved, every tile above MAP_ATLAS_MIN_TILE at once,
 * until they fit, each light's faces told their new size: the lights
 * share the atlas in the proportions their shares of the screen asked,
 * at a coarser texel, where each light's own cube map beside a full
 * atlas would hold as much memory as the lights ask (lamps without a
 * range, each measured over the whole street, ask for the largest). */
static void map_tile_asks_fit(map_renderer *r, map_tile_ask *asks, int count) {
    double largest = map_atlas_largest_side(r), room = largest * largest / MAP_ATLAS_ROOM;
    for (bool shrunk = true; shrunk && map_tile_asks_area(asks, count) > room;) {
        shrunk = false;
        for (int i = 0; i < count; i++)
            if (asks[i].size > MAP_ATLAS_MIN_TILE) {
                asks[i].size /= 2;
                shrunk = true;
            }
        r->tiles_halved += shrunk;
    }
    for (int i = 0; i < count; i++)
        r->maps[asks[i].light].tiles[asks[i].layer].size = asks[i].size;
}

/* Larger tiles first. */
static int map_tile_ask_larger(const void *a, const void *b) {
    const map_tile_ask *x = a, *y = b;
    return (y->size > x->size) - (y->size < x->size);
}

/* Into a fresh atlas, the asked tiles, the largest first: a quadtree
 * packs squares of powers of two whole in that order, so a frame's tiles
 * fit wherever their area does. */
static void map_atlas_place_all(map_renderer *r, map_tile_ask *asks, int count) {
    qsort(asks, (size_t)count, sizeof *asks, map_tile_ask_larger);
    for (int i = 0; i < count; i++) {
        map_light *m = &r->maps[asks[i].light];
        map_tile_place(r, m, asks[i].light, asks[i].layer);
        m->tiles[asks[i].layer].size = asks[i].size; /* the size asked, which map_place_tiles finds held */
    }
}

bool map_atlas_plan(map_renderer *r, const map_settings *st, int light_count) {
    map_tile_ask asks[SCENE_MAX_LIGHTS * MAP_CUBE_FACES];
    int count = map_tile_asks(r, light_count, asks);
    map_tile_asks_fit(r, asks, count);
    int filter = map_filter_in_use(st), side = map_atlas_side_wanted(r, asks, count);
    if (side == 0)
        return false;
    if (r->atlas_texture && r->atlas_depth == st->depth && r->atlas.size >= side && r->atlas.size < 2 * side) {
        if (r->atlas_filter != filter) {
            glBindTexture(GL_TEXTURE_2D, r->atlas_texture);
            map_depth_sampling(GL_TEXTURE_2D, filter);
            r->atlas_filter = filter;
        }
        return false;
    }
    /* A texture made again holds nothing: every tile is free. */
    memset(r->tile_nodes, -1, sizeof r->tile_nodes);
    glDeleteTextures(1, &r->atlas_texture);
    r->atlas_texture = 0;
    if (r->atlas.nodes && r->atlas.size != side)
        map_atlas_destroy(&r->atlas);
    if (!r->atlas.nodes && !map_atlas_init(&r->atlas, side)) {
        fprintf(stderr, "shadow maps: out of memory for the shadow atlas's tiles\n");
        return true;
    }
    map_atlas_clear(&r->atlas);
    glGenTextures(1, &r->atlas_texture);
    glBindTexture(GL_TEXTURE_2D, r->atlas_texture);
    GLenum format, type;
    map_depth_format(st->depth, &format, &type);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)format, r->atlas.size, r->atlas.size, 0, GL_DEPTH_COMPONENT, type, NULL);
    map_depth_sampling(GL_TEXTURE_2D, filter);
    /* Cleared to the far plane: where no tile is drawn it holds nothing,
     * as the map overlay shows it, not whatever the memory held. */
    glBindFramebuffer(GL_FRAMEBUFFER, r->framebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, r->atlas_texture, 0);
    glViewport(0, 0, r->atlas.size, r->atlas.size);
    glDisable(GL_SCISSOR_TEST);
    glDepthMask(GL_TRUE);
    glClear(GL_DEPTH_BUFFER_BIT);
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)r->target_framebuffer);
    glViewport(r->viewport[0], r->viewport[1], r->viewport[2], r->viewport[3]);
    r->atlas_depth = st->depth;
    r->atlas_filter = filter;
    map_atlas_place_all(r, asks, count);
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
