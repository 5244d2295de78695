/* map_atlas: where square tiles lie in a shadow atlas, one square depth
 * texture that holds the maps of many lights (map.h, "Atlas"). A buddy
 * allocator over a quadtree: the atlas is a square of `size` texels, each
 * node a square split into four of half its side, down to
 * MAP_ATLAS_MIN_TILE; a tile takes the node of its side, and a freed
 * tile's node joins its three siblings again when they are free too.
 * Tiles keep their place while they are held, so that a map cached in its
 * tile stays valid across frames; sides are powers of two (the maps'
 * sizes), which pack a quadtree without gaps. stb_rect_pack packs a whole
 * set at once and frees nothing, so it would move every tile whenever one
 * changed.
 *
 * Tiles are taken smallest-gap first: a free node of the side asked for
 * inside a split one before a larger free node is split, so that large
 * free squares stay whole.
 *
 * No GL: the tests check it on its own (test_map_atlas).
 */
#ifndef MAP_ATLAS_H
#define MAP_ATLAS_H

#include <stdbool.h>

/* The smallest tile's side, texels (the maps' least auto size). */
#define MAP_ATLAS_MIN_TILE 256

/* A tile: its lower left corner and side, in texels of the atlas. */
typedef struct map_tile {
    int x, y, size;
} map_tile;

typedef struct map_atlas {
    int size;             /* texels on a side: a power of two, MAP_ATLAS_MIN_TILE or more */
    int levels;           /* node sides from size (level 0) down to MAP_ATLAS_MIN_TILE */
    int node_count;       /* (4^levels - 1) / 3, the root first, node n's children 4n + 1 .. 4n + 4 */
    unsigned char *nodes; /* each node's map_atlas_node_state */
} map_atlas;

/* An empty atlas of `size` texels on a side; false where memory fails or
 * size is no power of two at least MAP_ATLAS_MIN_TILE. */
bool map_atlas_init(map_atlas *a, int size);
void map_atlas_destroy(map_atlas *a);
/* Every tile freed. */
void map_atlas_clear(map_atlas *a);
/* A tile of side `size` (a power of two from MAP_ATLAS_MIN_TILE to the
 * atlas's): its node, or -1 where no free square of that side is left. */
int map_atlas_take(map_atlas *a, int size);
/* The tile of node `node` (a taken one) freed. */
void map_atlas_free(map_atlas *a, int node);
/* Where node `node`'s square lies. */
map_tile map_atlas_tile(const map_atlas *a, int node);
/* The texels of the taken tiles. */
long map_atlas_used(const map_atlas *a);

#endif
