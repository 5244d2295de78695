/* test_map_atlas: demos/lib/map_atlas.c, the shadow atlas's tiles, on
 * their own (no GL): every held tile inside the atlas and apart from
 * every other, freed squares joined again, and the smallest gap taken
 * first, so that the large squares stay whole. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>

#include <cmocka.h>

#include "map_atlas.h"

#define ATLAS 1024
#define MAX_TILES ((ATLAS / MAP_ATLAS_MIN_TILE) * (ATLAS / MAP_ATLAS_MIN_TILE))

/* The held tiles overlap nowhere and lie inside the atlas, and the atlas
 * counts their texels. */
static void check_apart(const map_atlas *a, const int *nodes, int count) {
    long texels = 0;
    for (int i = 0; i < count; i++) {
        map_tile t = map_atlas_tile(a, nodes[i]);
        assert_true(t.x >= 0 && t.y >= 0 && t.x + t.size <= a->size && t.y + t.size <= a->size);
        texels += (long)t.size * t.size;
        for (int j = 0; j < i; j++) {
            map_tile u = map_atlas_tile(a, nodes[j]);
            bool apart = t.x + t.size <= u.x || u.x + u.size <= t.x || t.y + t.size <= u.y || u.y + u.size <= t.y;
            assert_true(apart);
        }
    }
    assert_int_equal(map_atlas_used(a), texels);
}

static void test_sizes_checked(void **state) {
    (void)state;
    map_atlas a;
    assert_false(map_atlas_init(&a, 1000));
    map_atlas_destroy(&a);
    assert_false(map_atlas_init(&a, MAP_ATLAS_MIN_TILE / 2));
    map_atlas_destroy(&a);
    assert_true(map_atlas_init(&a, ATLAS));
    assert_int_equal(map_atlas_take(&a, ATLAS * 2), -1);
    assert_int_equal(map_atlas_take(&a, 300), -1);
    assert_int_equal(map_atlas_take(&a, MAP_ATLAS_MIN_TILE / 2), -1);
    map_atlas_destroy(&a);
}

/* Four quarters fill it; a fifth tile of any side finds no room. */
static void test_quarters_fill(void **state) {
    (void)state;
    map_atlas a;
    assert_true(map_atlas_init(&a, ATLAS));
    int nodes[4];
    for (int i = 0; i < 4; i++)
        assert_true((nodes[i] = map_atlas_take(&a, ATLAS / 2)) >= 0);
    check_apart(&a, nodes, 4);
    assert_int_equal(map_atlas_used(&a), (long)ATLAS * ATLAS);
    assert_int_equal(map_atlas_take(&a, MAP_ATLAS_MIN_TILE), -1);
    map_atlas_destroy(&a);
}

/* Freed tiles join: sixteen of the least side, all freed, leave room for
 * the whole atlas again. */
static void test_freed_join(void **state) {
    (void)state;
    map_atlas a;
    assert_true(map_atlas_init(&a, ATLAS));
    int nodes[MAX_TILES];
    for (int i = 0; i < MAX_TILES; i++)
        assert_true((nodes[i] = map_atlas_take(&a, MAP_ATLAS_MIN_TILE)) >= 0);
    check_apart(&a, nodes, MAX_TILES);
    assert_int_equal(map_atlas_take(&a, MAP_ATLAS_MIN_TILE), -1);
    for (int i = 0; i < MAX_TILES; i++)
        map_atlas_free(&a, nodes[i]);
    assert_int_equal(map_atlas_used(&a), 0);
    int whole = map_atlas_take(&a, ATLAS);
    assert_true(whole >= 0);
    map_tile t = map_atlas_tile(&a, whole);
    assert_int_equal(t.x, 0);
    assert_int_equal(t.y, 0);
    assert_int_equal(t.size, ATLAS);
    map_atlas_destroy(&a);
}

/* Two small tiles share one quarter, so three quarters stay whole for
 * three tiles of half the side. */
static void test_smallest_gap_first(void **state) {
    (void)state;
    map_atlas a;
    assert_true(map_atlas_init(&a, ATLAS));
    int nodes[5];
    nodes[0] = map_atlas_take(&a, MAP_ATLAS_MIN_TILE);
    nodes[1] = map_atlas_take(&a, MAP_ATLAS_MIN_TILE);
    for (int i = 2; i < 5; i++)
        nodes[i] = map_atlas_take(&a, ATLAS / 2);
    for (int i = 0; i < 5; i++)
        assert_true(nodes[i] >= 0);
    check_apart(&a, nodes, 5);
    map_atlas_destroy(&a);
}

/* Tiles taken and freed in a fixed pseudo-random order: the held ones
 * always apart, and every free square of the least side found. */
static void test_taken_and_freed(void **state) {
    (void)state;
    map_atlas a;
    assert_true(map_atlas_init(&a, ATLAS));
    int held[MAX_TILES], count = 0;
    unsigned seed = 12345u;
    for (int step = 0; step < 2000; step++) {
        seed = seed * 1664525u + 1013904223u;
        if (count > 0 && (seed >> 16) % 3 == 0) {
            int i = (int)((seed >> 8) % (unsigned)count);
            map_atlas_free(&a, held[i]);
            held[i] = held[--count];
        } else {
            int side = MAP_ATLAS_MIN_TILE << ((seed >> 20) % 3);
            int n = map_atlas_take(&a, side);
            if (n >= 0)
                held[count++] = n;
            else /* refused only where no square of its side is free */
                assert_true(map_atlas_used(&a) + (long)side * side > (long)ATLAS * ATLAS ||
                            side > MAP_ATLAS_MIN_TILE);
        }
        check_apart(&a, held, count);
    }
    map_atlas_clear(&a);
    assert_int_equal(map_atlas_used(&a), 0);
    map_atlas_destroy(&a);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sizes_checked),   cmocka_unit_test(test_quarters_fill),
        cmocka_unit_test(test_freed_join),      cmocka_unit_test(test_smallest_gap_first),
        cmocka_unit_test(test_taken_and_freed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
