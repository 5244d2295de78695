/* volumes: stencil shadow volumes, z-pass, z-fail and the choice between
 * them, for any mesh: closed, open or non-manifold.
 *
 * Crow, "Shadow algorithms for computer graphics", SIGGRAPH 1977: the space
 * a caster shadows is bounded by polygons (its silhouette swept away from
 * the light, and caps); a point is in shadow when the eye ray to it enters
 * more of those volumes than it leaves. Heidmann (1991) counts in the
 * stencil buffer: volume faces in front of the visible surface, +1 for
 * front faces, -1 for back faces (z-pass). Wrong when the eye is inside a
 * volume (the count starts at 1, not 0), so Carmack's reverse (Bilodeau &
 * Songy, Carmack 2000; Everitt & Kilgard, "Practical and robust stenciled
 * shadow volumes", 2002) counts the faces behind the surface instead
 * (z-fail): back faces +1, front faces -1, which needs the volume closed by
 * caps. The far caps lie at infinity (w = 0) and depth clamp keeps them from
 * being clipped by the far plane.
 *
 * Which meshes: every triangle is its own occluder (Aldridge & Woods,
 * "Robust, geometry-independent shadow volumes", 2004): its prism from the
 * triangle away from the light counts +1 inside, whichever way it faces.
 * Where prisms of neighbouring triangles share a side, the sides cancel; an
 * edge of the welded edge table (mesh_edges_build) is drawn as many times
 * as the signed sum of its triangles' facing tests, its multiplicity: 0
 * inside a smooth surface, 1 or 2 on silhouettes and open borders, up to
 * the number of triangles at a non-manifold edge. A consistently oriented
 * closed mesh needs only its light-facing prisms (the back-facing ones
 * cover the same space twice over), so there back-facing triangles weigh 0
 * and silhouettes 1: the textbook volume. Counts are the number of
 * triangles between the surface and the light, wrapping at 256: wrong only
 * where a pixel is behind an exact multiple of 256 (closed: of 256 casters).
 *
 * Per light (up to 8, added over an ambient pass): clear the stencil in the
 * screen rectangle of the receivers; draw every caster's volume with colour
 * and depth writes off and both faces counted in one pass
 * (glStencilOpSeparate, wrapping increment and decrement); then add the
 * light where the stencil is 0 (everywhere on objects that receive no
 * shadows).
 *
 * --mode auto (default) takes z-pass, without caps, for a caster whose
 * volume cannot reach the camera's near-plane rectangle: its world box lies
 * wholly outside one face of the hull of the light and that rectangle (the
 * only place an occluder of the rectangle can be). Every other caster takes
 * z-fail with caps. The test is conservative and has no tolerance: a box
 * touching the hull takes z-fail. --mode zpass forces z-pass: with the
 * camera inside a shadow it visibly fails (shadows inverted).
 *
 * --silhouette gpu finds silhouettes in a geometry shader over
 * GL_TRIANGLES_ADJACENCY (shaders/volume_silhouette.geom), for z-pass
 * volumes of closed meshes: only they have the adjacency it needs. Open
 * meshes, and z-fail volumes, stay on the CPU path (the HUD says how
 * many): caps must lie at exactly the depth of the surface they cover, and
 * Mesa's llvmpipe rasterizes a geometry shader's triangles at slightly
 * different depths than the same triangles from a vertex shader (measured:
 * 0.2 to 0.4 % false shadow on simple and bunny with caps from the shader).
 *
 * For lectures, --overlay (key V): the volumes of light 0 drawn translucent
 * with their edges, the silhouette edges, or the stencil count as colour.
 */
#include <GLFW/glfw3.h>
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "technique.h"

typedef struct volumes_settings {
    int mode;       /* choice */
    int silhouette; /* choice */
    int overlay;    /* choice */
} volumes_settings;

static const char *const volumes_modes[] = {"auto", "zpass", "zfail", NULL};
static const char *const volumes_silhouettes[] = {"cpu", "gpu", NULL};
static const char *const volumes_overlays[] = {"none", "volumes", "silhouettes", "counts", NULL};
enum { VOLUMES_AUTO, VOLUMES_ZPASS, VOLUMES_ZFAIL };
enum { VOLUMES_CPU, VOLUMES_GPU };
enum { VOLUMES_OVERLAY_NONE, VOLUMES_OVERLAY_VOLUMES, VOLUMES_OVERLAY_SILHOUETTES, VOLUMES_OVERLAY_COUNTS };
/* What volumes_build makes: sides (z-pass), sides and caps (z-fail), or the
 * silhouette edges as lines (overlay). */
enum { VOLUMES_SIDES, VOLUMES_SIDES_AND_CAPS, VOLUMES_SILHOUETTE_LINES };

/* One caster's topology, built once per scene. */
typedef struct volumes_caster {
    mesh_edges edges;
    unsigned adjacency_vao, adjacency_buffer; /* closed meshes: GPU path */
    int adjacency_count;
} volumes_caster;

/* A growing array of homogeneous vertices: volume geometry of one caster. */
typedef struct volumes_geometry {
    float (*vertices)[4];
    size_t count, capacity;
    bool out_of_memory;
} volumes_geometry;

static struct {
    volumes_settings settings;
    render_program cpu, gpu, flat;
    int gpu_light, flat_color;
    volumes_caster *casters;
    int caster_count;
    unsigned stream_vao, stream_buffer;
    size_t stream_capacity;
    volumes_geometry geometry;
    signed char *weights; /* per triangle of the caster at hand */
    size_t weight_capacity;
    int zpass_count, zfail_count, gpu_fallback_count; /* light 0, last frame */
} volumes;

static const technique_param volumes_params[] = {
    {"mode", "z-pass (no caps) where safe, else z-fail (caps); or force one", GLFW_KEY_Z, TECHNIQUE_CHOICE,
     .index = &volumes.settings.mode, .choices = volumes_modes},
    {"silhouette", "where silhouettes are found: the CPU edge table or a geometry shader", GLFW_KEY_G,
     TECHNIQUE_CHOICE, .index = &volumes.settings.silhouette, .choices = volumes_silhouettes},
    {"overlay", "for lectures: the volumes, the silhouette edges, or the stencil count as colour", GLFW_KEY_V,
     TECHNIQUE_CHOICE, .index = &volumes.settings.overlay, .choices = volumes_overlays},
};

/* ---- geometry on the CPU ---- */

static void volumes_emit(volumes_geometry *g, const float p[3], float w) {
    if (g->count == g->capacity) {
        size_t capacity = g->capacity ? g->capacity * 2 : 4096;
        float(*grown)[4] = realloc(g->vertices, capacity * sizeof *grown);
        if (!grown) {
            g->out_of_memory = true;
            return;
        }
        g->vertices = grown;
        g->capacity = capacity;
    }
    float *v = g->vertices[g->count++];
    v[0] = p[0], v[1] = p[1], v[2] = p[2], v[3] = w;
}

/* p swept away from the light (object space) to infinity: a direction. */
static void volumes_extrude(const float p[3], const float light[4], float out[3]) {
    for (int k = 0; k < 3; k++)
        out[k] = p[k] * light[3] - light[k];
}

static void volumes_emit_triangle(volumes_geometry *g, const float *a, float wa, const float *b, float wb,
                                  const float *c, float wc) {
    volumes_emit(g, a, wa);
    volumes_emit(g, b, wb);
    volumes_emit(g, c, wc);
}

/* The side of edge a -> b swept to infinity, facing out of the prism of a
 * light-facing triangle that runs a -> b (reversed when sign < 0). A
 * directional light sends a and b to one point: one triangle. */
static void volumes_emit_side(volumes_geometry *g, const float *a, const float *b, const float light[4], int sign) {
    float a_far[3], b_far[3];
    volumes_extrude(a, light, a_far);
    volumes_extrude(b, light, b_far);
    if (sign < 0) {
        const float *t = a;
        a = b, b = t;
        float swap[3] = {a_far[0], a_far[1], a_far[2]};
        memcpy(a_far, b_far, sizeof a_far);
        memcpy(b_far, swap, sizeof b_far);
    }
    volumes_emit_triangle(g, b, 1, a, 1, a_far, 0);
    if (light[3] != 0)
        volumes_emit_triangle(g, b, 1, a_far, 0, b_far, 0);
}

/* +1: faces the light; otherwise -1, or 0 for a closed mesh (see top). */
static int volumes_weight(const mesh *m, uint32_t triangle, const float light[4], bool closed) {
    const float *p0 = m->vertices[m->indices[triangle * 3]].position;
    const float *p1 = m->vertices[m->indices[triangle * 3 + 1]].position;
    const float *p2 = m->vertices[m->indices[triangle * 3 + 2]].position;
    vec3 e1, e2, n, to_light;
    glm_vec3_sub((float *)p1, (float *)p0, e1);
    glm_vec3_sub((float *)p2, (float *)p0, e2);
    glm_vec3_cross(e1, e2, n);
    for (int k = 0; k < 3; k++)
        to_light[k] = light[k] - light[3] * p0[k];
    return glm_vec3_dot(n, to_light) > 0 ? 1 : closed ? 0 : -1;
}

/* Sides with their multiplicity, and caps for z-fail, in object space. */
static bool volumes_build(const mesh *m, const mesh_edges *e, const float light[4], int parts,
                          volumes_geometry *g) {
    uint32_t triangles = m->index_count / 3;
    if (triangles > volumes.weight_capacity) {
        signed char *grown = realloc(volumes.weights, triangles);
        if (!grown)
            return false;
        volumes.weights = grown;
        volumes.weight_capacity = triangles;
    }
    for (uint32_t t = 0; t < triangles; t++)
        volumes.weights[t] = (signed char)volumes_weight(m, t, light, e->closed);
    g->count = 0;
    for (uint32_t i = 0; i < e->edge_count; i++) {
        int multiplicity = 0;
        for (uint32_t k = 0; k < e->edges[i].use_count; k++) {
            const mesh_edge_use *u = &e->uses[e->edges[i].first_use + k];
            multiplicity += u->direction * volumes.weights[u->corner / 3];
        }
        const float *a = m->vertices[e->edges[i].a].position, *b = m->vertices[e->edges[i].b].position;
        if (parts == VOLUMES_SILHOUETTE_LINES && multiplicity != 0) {
            volumes_emit(g, a, 1);
            volumes_emit(g, b, 1);
            continue;
        }
        for (int k = 0; k < abs(multiplicity); k++)
            volumes_emit_side(g, a, b, light, multiplicity);
    }
    for (uint32_t t = 0; parts == VOLUMES_SIDES_AND_CAPS && t < triangles; t++) {
        if (volumes.weights[t] == 0)
            continue;
        const float *p[3];
        float far[3][3];
        for (int k = 0; k < 3; k++) {
            /* Prisms of back-facing triangles run the other way round. */
            int corner = volumes.weights[t] > 0 ? k : 2 - k;
            p[k] = m->vertices[m->indices[t * 3 + corner]].position;
            volumes_extrude(p[k], light, far[k]);
        }
        volumes_emit_triangle(g, p[0], 1, p[1], 1, p[2], 1);
        if (light[3] != 0) /* a directional light's far cap is a point */
            volumes_emit_triangle(g, far[0], 0, far[2], 0, far[1], 0);
    }
    return !g->out_of_memory;
}

/* ---- choosing z-pass or z-fail ---- */

/* Whether the world box [lo, hi] lies wholly on the negative side of the
 * plane n.x + d = 0. */
static bool volumes_box_outside(const float n[3], float d, const float lo[3], const float hi[3]) {
    float best = d;
    for (int k = 0; k < 3; k++)
        best += n[k] * (n[k] > 0 ? hi[k] : lo[k]);
    return best < 0;
}

/* The plane through a and b containing the direction `along`, facing the
 * point `inside`; false when it is degenerate. */
static bool volumes_plane(const float a[3], const float b[3], const float along[3], const float inside[3],
                          float n[3], float *d) {
    vec3 ab;
    glm_vec3_sub((float *)b, (float *)a, ab);
    glm_vec3_cross(ab, (float *)along, n);
    if (glm_vec3_norm2(n) == 0)
        return false;
    *d = -glm_vec3_dot(n, (float *)a);
    if (glm_vec3_dot(n, (float *)inside) + *d < 0) {
        glm_vec3_negate(n);
        *d = -*d;
    }
    return true;
}

/* True when no point of the near-plane rectangle can be in the caster's
 * shadow: its box is outside a face of the hull of the light (a point, or
 * a direction swept to infinity) and the rectangle. */
static bool volumes_zpass_safe(const scene_object *o, const float light[4], const vec3 near_corners[4]) {
    float lo[3], hi[3], n[3], d;
    scene_object_world_bounds(o, lo, hi);
    vec3 centre = {0, 0, 0}, inside;
    for (int k = 0; k < 4; k++)
        glm_vec3_muladds((float *)near_corners[k], 0.25f, centre);
    for (int k = 0; k < 4; k++) {
        const float *a = near_corners[k], *b = near_corners[(k + 1) % 4];
        vec3 along;
        if (light[3] != 0)
            glm_vec3_sub((float *)light, (float *)a, along);
        else
            glm_vec3_copy((float *)light, along);
        if (volumes_plane(a, b, along, centre, n, &d) && volumes_box_outside(n, d, lo, hi))
            return true;
    }
    /* The rectangle's own plane: the hull lies on the light's side. */
    vec3 e1, e2;
    glm_vec3_sub((float *)near_corners[1], (float *)near_corners[0], e1);
    glm_vec3_sub((float *)near_corners[3], (float *)near_corners[0], e2);
    if (light[3] != 0)
        glm_vec3_copy((float *)light, inside);
    else
        glm_vec3_add(centre, (float *)light, inside);
    return volumes_plane(near_corners[0], near_corners[1], e2, inside, n, &d) && glm_vec3_dot(n, inside) + d > 0 &&
           volumes_box_outside(n, d, lo, hi);
}

static void volumes_near_corners(const camera_view *v, vec3 out[4]) {
    mat4 inverse;
    glm_mat4_inv((vec4 *)v->view_projection, inverse);
    static const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int k = 0; k < 4; k++) {
        vec4 ndc = {corners[k][0], corners[k][1], -1, 1}, world;
        glm_mat4_mulv(inverse, ndc, world);
        glm_vec3_scale(world, 1.0f / world[3], out[k]);
    }
}

/* ---- the technique ---- */

static bool volumes_init(const render_scene *gpu) {
    static const char *const cpu_files[] = {"volume.vert", "volume.frag"};
    static const char *const gpu_files[] = {"volume_adjacency.vert", "volume_silhouette.geom", "volume.frag"};
    static const char *const flat_files[] = {"volume.vert", "volume.frag"};
    if (!render_program_load(&volumes.cpu, cpu_files, 2, NULL) ||
        !render_program_load(&volumes.gpu, gpu_files, 3, NULL) || !render_program_load(&volumes.flat, flat_files, 2, NULL))
        return false;
    volumes.gpu_light = glGetUniformLocation(volumes.gpu.id, "u_light");
    volumes.flat_color = glGetUniformLocation(volumes.flat.id, "u_color");
    const scene *s = gpu->scene;
    volumes.casters = calloc((size_t)s->object_count, sizeof *volumes.casters);
    if (!volumes.casters) {
        fprintf(stderr, "volumes: out of memory\n");
        return false;
    }
    volumes.caster_count = s->object_count;
    for (int i = 0; i < s->object_count; i++) {
        const mesh *m = &s->objects[i].mesh;
        volumes_caster *c = &volumes.casters[i];
        mesh_topology t;
        if (!s->objects[i].casts)
            continue;
        if (!mesh_weld(m, &t))
            return false;
        bool ok = mesh_edges_build(m, &t, &c->edges);
        mesh_topology_free(&t);
        if (!ok)
            return false;
        uint32_t *adjacency = c->edges.closed ? malloc((size_t)m->index_count * 2 * sizeof *adjacency) : NULL;
        if (adjacency && mesh_adjacency_indices(m, &c->edges, adjacency)) {
            glGenVertexArrays(1, &c->adjacency_vao);
            glBindVertexArray(c->adjacency_vao);
            glBindBuffer(GL_ARRAY_BUFFER, gpu->meshes[i].vertex_buffer);
            glEnableVertexAttribArray(0);
            glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(mesh_vertex), NULL);
            glGenBuffers(1, &c->adjacency_buffer);
            glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, c->adjacency_buffer);
            glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)m->index_count * 2 * sizeof *adjacency, adjacency,
                         GL_STATIC_DRAW);
            c->adjacency_count = (int)m->index_count * 2;
            glBindVertexArray(0);
        }
        free(adjacency);
    }
    glGenVertexArrays(1, &volumes.stream_vao);
    glBindVertexArray(volumes.stream_vao);
    glGenBuffers(1, &volumes.stream_buffer);
    glBindBuffer(GL_ARRAY_BUFFER, volumes.stream_buffer);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 4 * sizeof(float), NULL);
    glBindVertexArray(0);
    return true;
}

static void volumes_destroy(void) {
    render_program_destroy(&volumes.cpu);
    render_program_destroy(&volumes.gpu);
    render_program_destroy(&volumes.flat);
    for (int i = 0; i < volumes.caster_count; i++) {
        mesh_edges_free(&volumes.casters[i].edges);
        glDeleteVertexArrays(1, &volumes.casters[i].adjacency_vao);
        glDeleteBuffers(1, &volumes.casters[i].adjacency_buffer);
    }
    free(volumes.casters);
    free(volumes.geometry.vertices);
    free(volumes.weights);
    glDeleteVertexArrays(1, &volumes.stream_vao);
    glDeleteBuffers(1, &volumes.stream_buffer);
    volumes.casters = NULL;
    volumes.caster_count = 0;
    volumes.geometry = (volumes_geometry){0};
    volumes.weights = NULL;
    volumes.weight_capacity = volumes.stream_capacity = 0;
    volumes.stream_vao = volumes.stream_buffer = 0;
}

/* Counting ops for both faces in one pass, wrapping so that more than 255
 * overlapping volumes still sum right. */
static void volumes_stencil_ops(bool zfail) {
    if (zfail) {
        glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_DECR_WRAP, GL_KEEP);
        glStencilOpSeparate(GL_BACK, GL_KEEP, GL_INCR_WRAP, GL_KEEP);
    } else {
        glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_KEEP, GL_INCR_WRAP);
        glStencilOpSeparate(GL_BACK, GL_KEEP, GL_KEEP, GL_DECR_WRAP);
    }
}

static void volumes_draw_stream(const volumes_geometry *g, GLenum primitive) {
    glBindVertexArray(volumes.stream_vao);
    glBindBuffer(GL_ARRAY_BUFFER, volumes.stream_buffer);
    size_t bytes = g->count * sizeof *g->vertices;
    if (bytes > volumes.stream_capacity) {
        volumes.stream_capacity = bytes * 2;
        glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)volumes.stream_capacity, NULL, GL_STREAM_DRAW);
    }
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)bytes, g->vertices);
    glDrawArrays(primitive, 0, (GLsizei)g->count);
}

static bool volumes_on_gpu(const volumes_caster *c, int parts) {
    return volumes.settings.silhouette == VOLUMES_GPU && c->adjacency_vao && parts == VOLUMES_SIDES;
}

/* Caster i's volume for the light (homogeneous, world): counted into the
 * stencil when `overlay` is NULL, else drawn with the overlay's program. */
static void volumes_draw_caster(const technique_frame *f, int i, const float light[4], int parts,
                                const render_program *overlay) {
    const scene_object *o = &f->gpu->scene->objects[i];
    const volumes_caster *c = &volumes.casters[i];
    vec4 object_light;
    mat4 inverse;
    glm_mat4_inv((vec4 *)o->model, inverse);
    glm_mat4_mulv(inverse, (float *)light, object_light);
    if (volumes_on_gpu(c, parts) && !overlay) {
        render_program_use(&volumes.gpu, f->view);
        glUniformMatrix4fv(volumes.gpu.model, 1, GL_FALSE, (const float *)o->model);
        glUniform4fv(volumes.gpu_light, 1, object_light);
        glBindVertexArray(c->adjacency_vao);
        glDrawElements(GL_TRIANGLES_ADJACENCY, c->adjacency_count, GL_UNSIGNED_INT, NULL);
        return;
    }
    const render_program *p = overlay ? overlay : &volumes.cpu;
    render_program_use(p, f->view);
    glUniformMatrix4fv(p->model, 1, GL_FALSE, (const float *)o->model);
    if (!volumes_build(&o->mesh, &c->edges, object_light, parts, &volumes.geometry)) {
        fprintf(stderr, "volumes: %s: out of memory building its volume\n", o->name);
        volumes.geometry.out_of_memory = false;
        return;
    }
    volumes_draw_stream(&volumes.geometry, parts == VOLUMES_SILHOUETTE_LINES ? GL_LINES : GL_TRIANGLES);
}

/* Stencil = number of volumes of light l around each visible pixel. */
static void volumes_count(const technique_frame *f, int l, const float light[4]) {
    const scene *s = f->gpu->scene;
    vec3 near_corners[4];
    volumes_near_corners(f->view, near_corners);
    int zpass = 0, zfail = 0, fallback = 0;
    glEnable(GL_DEPTH_CLAMP); /* far caps at infinity stay in */
    glDisable(GL_CULL_FACE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_LESS); /* a surface's own cap, at its depth, counts as behind it */
    glStencilFunc(GL_ALWAYS, 0, 0xff);
    for (int i = 0; i < s->object_count; i++) {
        if (!s->objects[i].casts)
            continue;
        int mode = volumes.settings.mode;
        bool use_zfail = mode == VOLUMES_ZFAIL ||
                         (mode == VOLUMES_AUTO && !volumes_zpass_safe(&s->objects[i], light, near_corners));
        zfail += use_zfail;
        zpass += !use_zfail;
        int parts = use_zfail ? VOLUMES_SIDES_AND_CAPS : VOLUMES_SIDES;
        fallback += volumes.settings.silhouette == VOLUMES_GPU && !volumes_on_gpu(&volumes.casters[i], parts);
        volumes_stencil_ops(use_zfail);
        volumes_draw_caster(f, i, light, parts, NULL);
    }
    glDisable(GL_DEPTH_CLAMP);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (l == 0) {
        volumes.zpass_count = zpass;
        volumes.zfail_count = zfail;
        volumes.gpu_fallback_count = fallback;
    }
}

/* The screen rectangle of every receiver's box: no light reaches pixels
 * outside it. The whole viewport when a box reaches behind the eye. */
static void volumes_scissor(const technique_frame *f) {
    const scene *s = f->gpu->scene;
    float lo[2] = {1, 1}, hi[2] = {-1, -1};
    for (int i = 0; i < s->object_count; i++) {
        float box_lo[3], box_hi[3];
        if (!s->objects[i].receives)
            continue;
        scene_object_world_bounds(&s->objects[i], box_lo, box_hi);
        for (int c = 0; c < 8; c++) {
            vec4 p = {c & 1 ? box_hi[0] : box_lo[0], c & 2 ? box_hi[1] : box_lo[1], c & 4 ? box_hi[2] : box_lo[2], 1};
            glm_mat4_mulv((vec4 *)f->view->view_projection, p, p);
            if (p[3] <= 0) {
                glScissor(0, 0, f->width, f->height);
                return;
            }
            for (int k = 0; k < 2; k++) {
                lo[k] = fminf(lo[k], p[k] / p[3]);
                hi[k] = fmaxf(hi[k], p[k] / p[3]);
            }
        }
    }
    int x0 = (int)floorf((glm_clamp(lo[0], -1, 1) * 0.5f + 0.5f) * (float)f->width);
    int y0 = (int)floorf((glm_clamp(lo[1], -1, 1) * 0.5f + 0.5f) * (float)f->height);
    int x1 = (int)ceilf((glm_clamp(hi[0], -1, 1) * 0.5f + 0.5f) * (float)f->width);
    int y1 = (int)ceilf((glm_clamp(hi[1], -1, 1) * 0.5f + 0.5f) * (float)f->height);
    glScissor(x0, y0, x1 > x0 ? x1 - x0 : 0, y1 > y0 ? y1 - y0 : 0);
}

static void volumes_draw_all(const technique_frame *f) {
    for (int i = 0; i < f->gpu->scene->object_count; i++)
        render_draw_object(f->gpu, &f->gpu->lit, i);
}

/* Light l's share: on receivers where no volume counts, on the rest
 * everywhere (they take no shadows). */
static void volumes_add_light(const technique_frame *f, int l) {
    const scene *s = f->gpu->scene;
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glDepthFunc(GL_EQUAL);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    render_use_lit(f->gpu, f->view, l, l + 1, false);
    for (int i = 0; i < s->object_count; i++) {
        glStencilFunc(s->objects[i].receives ? GL_EQUAL : GL_ALWAYS, 0, 0xff);
        render_draw_object(f->gpu, &f->gpu->lit, i);
    }
    glDisable(GL_BLEND);
}

/* For lectures, over the finished picture: light 0's volumes translucent
 * with their edges, its silhouettes, or its stencil count as colour. */
static void volumes_draw_overlay(const technique_frame *f, const float light[4]) {
    const scene *s = f->gpu->scene;
    int overlay = volumes.settings.overlay;
    if (overlay == VOLUMES_OVERLAY_COUNTS) {
        /* The stencil still holds the last light's counts: recount light 0,
         * then colour each count by a ramp. */
        glEnable(GL_STENCIL_TEST);
        glClear(GL_STENCIL_BUFFER_BIT);
        volumes_count(f, 0, light);
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);
        glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        static const float ramp[4][3] = {{0.2f, 0.4f, 1}, {0.2f, 1, 0.3f}, {1, 0.9f, 0.1f}, {1, 0.2f, 0.1f}};
        static const float screen[6][4] = {{-1, -1, 0, 1}, {1, -1, 0, 1}, {1, 1, 0, 1},
                                           {-1, -1, 0, 1}, {1, 1, 0, 1},  {-1, 1, 0, 1}};
        volumes_geometry quad = {.vertices = (float(*)[4])screen, .count = 6};
        camera_view identity = {0};
        glm_mat4_identity(identity.view_projection);
        render_program_use(&volumes.flat, &identity);
        glUniformMatrix4fv(volumes.flat.model, 1, GL_FALSE, (const float *)identity.view_projection);
        for (int k = 1; k <= 4; k++) {
            glStencilFunc(k < 4 ? GL_EQUAL : GL_LEQUAL, k, 0xff);
            glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
            glUniform4f(volumes.flat_color, ramp[k - 1][0], ramp[k - 1][1], ramp[k - 1][2], 0.45f);
            volumes_draw_stream(&quad, GL_TRIANGLES);
        }
        glDisable(GL_BLEND);
        glDisable(GL_STENCIL_TEST);
        glEnable(GL_DEPTH_TEST);
        return;
    }
    glDisable(GL_STENCIL_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_LEQUAL);
    glEnable(GL_DEPTH_CLAMP);
    render_program_use(&volumes.flat, f->view);
    for (int i = 0; i < s->object_count; i++) {
        if (!s->objects[i].casts)
            continue;
        if (overlay == VOLUMES_OVERLAY_VOLUMES) {
            glUniform4f(volumes.flat_color, 1.0f, 0.85f, 0.2f, 0.12f);
            volumes_draw_caster(f, i, light, VOLUMES_SIDES, &volumes.flat);
            glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
            glUniform4f(volumes.flat_color, 1.0f, 0.85f, 0.2f, 0.6f);
            volumes_draw_stream(&volumes.geometry, GL_TRIANGLES);
            glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        } else {
            glUniform4f(volumes.flat_color, 1.0f, 0.3f, 0.2f, 1.0f);
            glDepthFunc(GL_ALWAYS);
            volumes_draw_caster(f, i, light, VOLUMES_SILHOUETTE_LINES, &volumes.flat);
            glDepthFunc(GL_LEQUAL);
        }
    }
    glDisable(GL_DEPTH_CLAMP);
    glDisable(GL_BLEND);
}

static void volumes_render(const technique_frame *f) {
    const scene *s = f->gpu->scene;
    render_use_lit(f->gpu, f->view, 0, 0, true);
    volumes_draw_all(f);
    for (int l = 0; l < s->light_count; l++) {
        float light[4];
        scene_light_homogeneous(&s->lights[l], light);
        glEnable(GL_SCISSOR_TEST);
        volumes_scissor(f);
        glClear(GL_STENCIL_BUFFER_BIT);
        glEnable(GL_STENCIL_TEST);
        volumes_count(f, l, light);
        glDisable(GL_SCISSOR_TEST); /* objects that take no shadows may lie outside */
        volumes_add_light(f, l);
        glDisable(GL_STENCIL_TEST);
    }
    if (volumes.settings.overlay != VOLUMES_OVERLAY_NONE && s->light_count > 0) {
        float light[4];
        scene_light_homogeneous(&s->lights[0], light);
        volumes_draw_overlay(f, light);
    }
}

static void volumes_describe(char *out, size_t size) {
    int n = snprintf(out, size, "light 0: %d casters z-pass, %d z-fail", volumes.zpass_count, volumes.zfail_count);
    if (volumes.gpu_fallback_count > 0 && n > 0 && (size_t)n < size)
        snprintf(out + n, size - (size_t)n, "; %d open or z-fail: CPU silhouettes", volumes.gpu_fallback_count);
}

/* The sweep: mode x silhouette path. */
static const char *const volumes_bench_configs[] = {
    "", "--mode zpass", "--mode zfail", "--silhouette gpu", "--mode zfail --silhouette gpu",
};

const technique volumes_technique = {
    .name = "volumes",
    .title = "stencil shadow volumes (Crow 1977), z-pass and z-fail, any mesh (Aldridge & Woods 2004)",
    .params = volumes_params,
    .param_count = (int)(sizeof volumes_params / sizeof *volumes_params),
    .bench_configs = volumes_bench_configs,
    .bench_config_count = (int)(sizeof volumes_bench_configs / sizeof *volumes_bench_configs),
    .init = volumes_init,
    .render = volumes_render,
    .destroy = volumes_destroy,
    .describe = volumes_describe,
};
