#include "volume_silhouette.h"

#include <glad/gl.h>
#include <stdio.h>
#include <stdlib.h>

#include "volume_mesh.h"

/* The corner before `corner` in its triangle: the vertex off the edge
 * that `corner` starts. */
static uint32_t volume_silhouette_third(uint32_t corner) { return corner / 3 * 3 + (corner + 2) % 3; }

void volume_silhouette_adjacency(const mesh *m, const mesh_edges *e, uint32_t *out) {
    for (uint32_t i = 0; i < e->edge_count; i++) {
        const mesh_edge_use *u = &e->uses[e->edges[i].first_use];
        uint32_t uses = e->edges[i].use_count;
        for (uint32_t k = 0; k < uses; k++) {
            /* Across: the one other triangle, where it holds the edge's
             * ends at the same positions, or on a border this one. */
            uint32_t corner = u[k].corner;
            uint32_t across = uses == 2 && mesh_edge_uses_meet(m, &u[0], &u[1]) ? u[1 - k].corner : corner;
            uint32_t *slot = &out[corner / 3 * VOLUME_SILHOUETTE_INDICES_PER_TRIANGLE + corner % 3 * 2];
            slot[0] = m->indices[corner];
            slot[1] = m->indices[volume_silhouette_third(across)];
        }
    }
}

bool volume_silhouette_load(volume_silhouette *s, bool wide) {
    static const char *const files[] = {"volume_adjacency.vert", "volume_silhouette.geom", "volume.frag"};
    /* The wide count's define last, where it ends the list when not wide. */
    const shader_define defines[] = {SHADER_DEFINE(VOLUME_SILHOUETTE_CLOSED),
                                     SHADER_DEFINE(VOLUME_SILHOUETTE_OPEN),
                                     SHADER_DEFINE(MESH_POINT_EDGE_ON_RECIPROCAL),
                                     {wide ? VOLUME_SILHOUETTE_WIDE_DEFINE : NULL, 1},
                                     {NULL, 0}};
    if (!render_program_load(&s->program, files, (int)(sizeof files / sizeof *files), defines))
        return false;
    s->color = shader_uniform(s->program.id, "u_color");
    s->light = shader_uniform(s->program.id, "u_light");
    s->topology = shader_uniform(s->program.id, "u_topology");
    return true;
}

void volume_silhouette_destroy(volume_silhouette *s) {
    render_program_destroy(&s->program);
    *s = (volume_silhouette){0};
}

bool volume_silhouette_mesh_init(volume_silhouette_mesh *out, const mesh *m, const mesh_edges *e,
                                 unsigned vertex_buffer) {
    size_t count = (size_t)m->index_count / 3 * VOLUME_SILHOUETTE_INDICES_PER_TRIANGLE;
    uint32_t *indices = malloc((count ? count : 1) * sizeof *indices);
    if (!indices) {
        fprintf(stderr, "volumes: out of memory for the adjacency indices\n");
        return false;
    }
    volume_silhouette_adjacency(m, e, indices);
    glGenVertexArrays(1, &out->vao);
    glBindVertexArray(out->vao);
    glBindBuffer(GL_ARRAY_BUFFER, vertex_buffer);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(mesh_vertex), NULL);
    glGenBuffers(1, &out->index_buffer);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, out->index_buffer);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(count * sizeof *indices), indices, GL_STATIC_DRAW);
    glBindVertexArray(0);
    free(indices);
    out->index_count = (int)count;
    out->topology = e->closed ? VOLUME_SILHOUETTE_CLOSED : VOLUME_SILHOUETTE_OPEN;
    return true;
}

void volume_silhouette_mesh_free(volume_silhouette_mesh *m) {
    glDeleteVertexArrays(1, &m->vao);
    glDeleteBuffers(1, &m->index_buffer);
    *m = (volume_silhouette_mesh){0};
}

void volume_silhouette_draw(const volume_silhouette *s, const volume_silhouette_mesh *m, const camera_view *view,
                            const float *model, const float light[4], bool closed_rule) {
    render_program_use(&s->program, view);
    glUniformMatrix4fv(s->program.model, 1, GL_FALSE, model);
    glUniform4fv(s->light, 1, light);
    glUniform1i(s->topology, closed_rule ? m->topology : VOLUME_SILHOUETTE_OPEN);
    glBindVertexArray(m->vao);
    glDrawElements(GL_TRIANGLES_ADJACENCY, m->index_count, GL_UNSIGNED_INT, NULL);
}
