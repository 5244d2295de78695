/* mesh_pack: see mesh_pack.h. */
#include "mesh_pack.h"

#include <errno.h>
#include <stdint.h>
#include <string.h>

#include "mesh_build.h"

typedef struct mesh_pack_header {
    char magic[sizeof MESH_PACK_MAGIC];
    uint32_t vertex_count, index_count, has_color;
    float color[3], bounds_min[3], bounds_max[3];
} mesh_pack_header;

bool mesh_pack_put(FILE *f, const mesh *m, const mesh_material *material) {
    mesh_pack_header h = {.magic = MESH_PACK_MAGIC,
                          .vertex_count = m->vertex_count,
                          .index_count = m->index_count,
                          .has_color = material && material->has_color};
    if (h.has_color)
        memcpy(h.color, material->color, sizeof h.color);
    memcpy(h.bounds_min, m->bounds_min, sizeof h.bounds_min);
    memcpy(h.bounds_max, m->bounds_max, sizeof h.bounds_max);
    return fwrite(&h, sizeof h, 1, f) == 1 &&
           fwrite(m->vertices, sizeof *m->vertices, m->vertex_count, f) == m->vertex_count &&
           fwrite(m->indices, sizeof *m->indices, m->index_count, f) == m->index_count;
}

bool mesh_pack_write(const char *path, const mesh *m, const mesh_material *material) {
    FILE *f = fopen(path, "wb");
    if (!f)
        return mesh_fail(NULL, path, "cannot create: %s", strerror(errno));
    bool ok = mesh_pack_put(f, m, material);
    int saved = errno;
    ok = fclose(f) == 0 && ok;
    return ok || mesh_fail(NULL, path, "cannot write: %s", strerror(errno ? errno : saved));
}

bool mesh_pack_get(FILE *f, const char *path, mesh *m, mesh_material *material) {
    *m = (mesh){0};
    mesh_pack_header h;
    if (!(fread(&h, sizeof h, 1, f) == 1 && memcmp(h.magic, MESH_PACK_MAGIC, sizeof h.magic) == 0 &&
          h.vertex_count <= MESH_MAX_VERTICES && h.index_count <= 3ull * MESH_MAX_TRIANGLES &&
          h.index_count % 3 == 0 && h.has_color <= 1))
        return mesh_fail(m, path, "not a mesh pack (build/bake writes them)");
    if (!mesh_alloc(m, path, h.vertex_count, h.index_count))
        return false;
    m->vertex_count = h.vertex_count;
    m->index_count = h.index_count;
    if (fread(m->vertices, sizeof *m->vertices, m->vertex_count, f) != m->vertex_count ||
        fread(m->indices, sizeof *m->indices, m->index_count, f) != m->index_count)
        return mesh_fail(m, path, "truncated");
    for (uint32_t i = 0; i < m->index_count; i++)
        if (m->indices[i] >= m->vertex_count)
            return mesh_fail(m, path, "index %u of %u vertices", m->indices[i], m->vertex_count);
    memcpy(m->bounds_min, h.bounds_min, sizeof h.bounds_min);
    memcpy(m->bounds_max, h.bounds_max, sizeof h.bounds_max);
    if (material) {
        material->has_color = h.has_color;
        memcpy(material->color, h.color, sizeof material->color);
    }
    return true;
}

bool mesh_pack_read(mesh *m, const char *path, mesh_material *material) {
    *m = (mesh){0};
    FILE *f = fopen(path, "rb");
    if (!f)
        return mesh_fail(m, path, "cannot open: %s", strerror(errno));
    bool ok = mesh_pack_get(f, path, m, material);
    bool longer = ok && fgetc(f) != EOF;
    fclose(f);
    if (longer)
        return mesh_fail(m, path, "longer than its counts");
    return ok;
}
