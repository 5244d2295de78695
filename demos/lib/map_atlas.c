/* map_atlas: a buddy allocator of square tiles over a quadtree (see
 * map_atlas.h). */
#include "map_atlas.h"

#include <stdlib.h>
#include <string.h>

/* A node is free (whole, its children meaningless), split into four, or
 * taken by a tile. */
typedef enum map_atlas_node_state { MAP_ATLAS_FREE, MAP_ATLAS_SPLIT, MAP_ATLAS_TAKEN } map_atlas_node_state;

#define MAP_ATLAS_CHILDREN 4

bool map_atlas_init(map_atlas *a, int size) {
    *a = (map_atlas){.size = size};
    if (size < MAP_ATLAS_MIN_TILE || (size & (size - 1)) != 0)
        return false;
    int nodes = 0, level_nodes = 1;
    for (int side = size; side >= MAP_ATLAS_MIN_TILE; side /= 2) {
        nodes += level_nodes;
        level_nodes *= MAP_ATLAS_CHILDREN;
        a->levels++;
    }
    a->node_count = nodes;
    a->nodes = calloc((size_t)nodes, 1);
    return a->nodes != NULL;
}

void map_atlas_destroy(map_atlas *a) {
    free(a->nodes);
    *a = (map_atlas){0};
}

void map_atlas_clear(map_atlas *a) { memset(a->nodes, MAP_ATLAS_FREE, (size_t)a->node_count); }

/* Node n's first child (n above the last level). */
static int map_atlas_first_child(int n) { return MAP_ATLAS_CHILDREN * n + 1; }

/* A free node at `level` below node n at depth `depth`, through split
 * nodes only; -1: none. */
static int map_atlas_find_free(const map_atlas *a, int n, int depth, int level) {
    if (depth == level)
        return a->nodes[n] == MAP_ATLAS_FREE ? n : -1;
    if (a->nodes[n] != MAP_ATLAS_SPLIT)
        return -1;
    for (int c = 0; c < MAP_ATLAS_CHILDREN; c++) {
        int found = map_atlas_find_free(a, map_atlas_first_child(n) + c, depth + 1, level);
        if (found >= 0)
            return found;
    }
    return -1;
}

int map_atlas_take(map_atlas *a, int size) {
    int target = 0;
    for (int side = a->size; side > size && target < a->levels - 1; side /= 2)
        target++;
    if (size < MAP_ATLAS_MIN_TILE || (a->size >> target) != size)
        return -1;
    /* The smallest free square that holds the tile: its own side first. */
    for (int level = target; level >= 0; level--) {
        int n = map_atlas_find_free(a, 0, 0, level);
        if (n < 0)
            continue;
        for (; level < target; level++) {
            a->nodes[n] = MAP_ATLAS_SPLIT;
            n = map_atlas_first_child(n);
            memset(a->nodes + n, MAP_ATLAS_FREE, MAP_ATLAS_CHILDREN);
        }
        a->nodes[n] = MAP_ATLAS_TAKEN;
        return n;
    }
    return -1;
}

void map_atlas_free(map_atlas *a, int node) {
    a->nodes[node] = MAP_ATLAS_FREE;
    while (node > 0) {
        int parent = (node - 1) / MAP_ATLAS_CHILDREN, first = map_atlas_first_child(parent);
        for (int c = 0; c < MAP_ATLAS_CHILDREN; c++)
            if (a->nodes[first + c] != MAP_ATLAS_FREE)
                return;
        a->nodes[parent] = MAP_ATLAS_FREE;
        node = parent;
    }
}

/* Node n's level: its depth below the root. */
static int map_atlas_level(int n) {
    int level = 0;
    for (; n > 0; n = (n - 1) / MAP_ATLAS_CHILDREN)
        level++;
    return level;
}

map_tile map_atlas_tile(const map_atlas *a, int node) {
    int side = a->size >> map_atlas_level(node);
    map_tile t = {0, 0, side};
    /* Child c of its parent: c's low bit along x, its high bit along y. */
    for (int n = node; n > 0; n = (n - 1) / MAP_ATLAS_CHILDREN, side *= 2) {
        int c = (n - 1) % MAP_ATLAS_CHILDREN;
        t.x += (c & 1) * side;
        t.y += (c >> 1) * side;
    }
    return t;
}

long map_atlas_used(const map_atlas *a) {
    long texels = 0;
    for (int n = 0; n < a->node_count; n++)
        if (a->nodes[n] == MAP_ATLAS_TAKEN) {
            long side = a->size >> map_atlas_level(n);
            texels += side * side;
        }
    return texels;
}
