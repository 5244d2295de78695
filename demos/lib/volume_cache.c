#include "volume_cache.h"

#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>

void volume_cache_vertex_array(unsigned vao, unsigned buffer) {
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, (GLsizei)VOLUME_CACHE_VERTEX_BYTES, NULL);
    glBindVertexArray(0);
}

bool volume_cache_init(volume_cache *c, int object_count) {
    *c = (volume_cache){.object_count = object_count};
    c->ranges = malloc((size_t)object_count * sizeof *c->ranges);
    if (!c->ranges) {
        fprintf(stderr, "volumes: out of memory\n");
        return false;
    }
    glGenVertexArrays(1, &c->vao);
    volume_cache_forget(c);
    return true;
}

void volume_cache_free(volume_cache *c) {
    glDeleteVertexArrays(1, &c->vao);
    glDeleteBuffers(1, &c->buffer);
    free(c->ranges);
    *c = (volume_cache){0};
}

void volume_cache_forget(volume_cache *c) {
    c->used = 0;
    for (int i = 0; i < c->object_count; i++)
        for (int part = 0; part < VOLUME_CACHE_PARTS; part++)
            c->ranges[i][part] = (volume_cache_range){0, -1};
}

bool volume_cache_has(const volume_cache *c, int object, volume_mesh_parts part) {
    return c->ranges[object][part].count >= 0;
}

/* Room for `count` more vertices: the buffer doubles (at least to fit),
 * or grows just enough where doubling would pass the budget. */
static bool volume_cache_reserve(volume_cache *c, size_t count, size_t *bytes, size_t max_bytes) {
    size_t needed = c->used + count;
    if (needed <= c->capacity)
        return true;
    size_t capacity = needed > 2 * c->capacity ? needed : 2 * c->capacity;
    if (*bytes + (capacity - c->capacity) * VOLUME_CACHE_VERTEX_BYTES > max_bytes)
        capacity = needed;
    if (*bytes + (capacity - c->capacity) * VOLUME_CACHE_VERTEX_BYTES > max_bytes)
        return false;
    unsigned grown;
    glGenBuffers(1, &grown);
    glBindBuffer(GL_COPY_WRITE_BUFFER, grown);
    /* Refilled whenever its light moves. */
    glBufferData(GL_COPY_WRITE_BUFFER, (GLsizeiptr)(capacity * VOLUME_CACHE_VERTEX_BYTES), NULL, GL_DYNAMIC_DRAW);
    if (c->used > 0) {
        glBindBuffer(GL_COPY_READ_BUFFER, c->buffer);
        glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0,
                            (GLsizeiptr)(c->used * VOLUME_CACHE_VERTEX_BYTES));
    }
    glDeleteBuffers(1, &c->buffer);
    *bytes += (capacity - c->capacity) * VOLUME_CACHE_VERTEX_BYTES;
    c->buffer = grown;
    c->capacity = capacity;
    volume_cache_vertex_array(c->vao, c->buffer);
    return true;
}

bool volume_cache_keep(volume_cache *c, int object, volume_mesh_parts part, const volume_mesh *v, size_t *bytes,
                       size_t max_bytes) {
    if (!volume_cache_reserve(c, v->count, bytes, max_bytes))
        return false;
    /* An empty part (a caster whose volume has no sides, say) uploads
     * nothing: the buffer may not exist yet. */
    if (v->count > 0) {
        glBindBuffer(GL_ARRAY_BUFFER, c->buffer);
        glBufferSubData(GL_ARRAY_BUFFER, (GLintptr)(c->used * VOLUME_CACHE_VERTEX_BYTES),
                        (GLsizeiptr)(v->count * VOLUME_CACHE_VERTEX_BYTES), v->vertices);
    }
    c->ranges[object][part] = (volume_cache_range){(int)c->used, (int)v->count};
    c->used += v->count;
    return true;
}

void volume_cache_draw(const volume_cache *c, int object, volume_mesh_parts part) {
    const volume_cache_range *r = &c->ranges[object][part];
    glBindVertexArray(c->vao);
    glDrawArrays(GL_TRIANGLES, r->first, r->count);
}
