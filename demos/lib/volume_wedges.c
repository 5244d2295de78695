#include "volume_wedges.h"

#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "context.h"
#include "depth.h"
#include "shader.h"
#include "wedge_area.h"

/* The texture unit the wedges read the depth from. */
#define VOLUME_WEDGES_DEPTH_UNIT 0
/* The vertex attributes: position, first end, second end. */
enum { VOLUME_WEDGES_POSITION, VOLUME_WEDGES_A, VOLUME_WEDGES_B };
/* Window depth to NDC z: GL's standard (-1..1) and clip control's (0..1). */
static const float volume_wedges_standard_ndc[2] = {2, -1}, volume_wedges_reversed_ndc[2] = {1, 0};

/* The wedge's triangles as indices of its corners: the edge's ends a, b
 * (0, 1), then at infinity the lines where each end's side plane meets
 * the front plane (2 at a, 4 at b) and the back plane (3 at a, 5 at b). */
static const int volume_wedges_faces[VOLUME_WEDGES_EDGE_VERTICES] = {
    0, 1, 4, 0, 4, 2, /* front */
    0, 1, 5, 0, 5, 3, /* back */
    0, 2, 3,          /* a's side */
    1, 4, 5,          /* b's side */
    2, 4, 5, 2, 5, 3, /* far, at infinity */
};

/* ---- geometry (no GL) ---- */

static double volume_wedges_det4(const float *p0, const float *p1, const float *p2, const float *q) {
    const float *rows[4] = {p0, p1, p2, q};
    double m[4][4], det = 1;
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            m[r][c] = rows[r][c];
    for (int c = 0; c < 4; c++) { /* elimination with partial pivoting */
        int pivot = c;
        for (int r = c + 1; r < 4; r++)
            if (fabs(m[r][c]) > fabs(m[pivot][c]))
                pivot = r;
        if (m[pivot][c] == 0)
            return 0;
        if (pivot != c) {
            for (int k = 0; k < 4; k++) {
                double t = m[c][k];
                m[c][k] = m[pivot][k], m[pivot][k] = t;
            }
            det = -det;
        }
        det *= m[c][c];
        for (int r = c + 1; r < 4; r++) {
            double factor = m[r][c] / m[c][c];
            for (int k = c; k < 4; k++)
                m[r][k] -= factor * m[c][k];
        }
    }
    return det;
}

/* At point p: the unit axis away from the light, and the sine of the
 * half-angle of the cone the (grown) ball spans from there; false within
 * it. */
static bool volume_wedges_cone(const float p[3], const float light[4], float reach, vec3 away, float *sine) {
    for (int c = 0; c < 3; c++)
        away[c] = p[c] * light[3] - light[c];
    float distance = glm_vec3_norm(away);
    if (distance <= reach * VOLUME_WEDGES_GROWTH)
        return false;
    *sine = reach * VOLUME_WEDGES_GROWTH / distance;
    glm_vec3_scale(away, 1 / distance, away);
    return true;
}

/* The side plane's normal at an end whose edge leaves it along `along`
 * (unit): across the cone's axis towards the edge, tilted towards the
 * axis by the cone's half-angle, so that the edge and the whole cone lie
 * on its positive side; false where the edge runs too near the axis. */
static bool volume_wedges_side(const vec3 along, const vec3 away, float sine, vec3 out) {
    vec3 across;
    glm_vec3_scale((float *)away, glm_vec3_dot((float *)along, (float *)away), across);
    glm_vec3_sub((float *)along, across, across);
    float length = glm_vec3_norm(across);
    if (length < VOLUME_WEDGES_MIN_SIDE)
        return false;
    float cosine = sqrtf(1 - sine * sine);
    for (int c = 0; c < 3; c++)
        out[c] = across[c] / length * cosine + away[c] * sine;
    return glm_vec3_dot(out, (float *)along) > VOLUME_WEDGES_MIN_SIDE;
}

/* The direction at infinity where planes n and m meet, away from the
 * light (along `away`); false where they are parallel. */
static bool volume_wedges_far(const vec3 n, const vec3 m, const vec3 away, float out[4]) {
    glm_vec3_cross((float *)n, (float *)m, out);
    float length = glm_vec3_norm(out);
    if (length == 0)
        return false;
    glm_vec3_scale(out, (glm_vec3_dot(out, (float *)away) < 0 ? -1 : 1) / length, out);
    out[3] = 0;
    return true;
}

/* The far corners (directions from the ends: 2 and 3 from a, 4 and 5
 * from b) moved onto the plane of the face of the box [lo, hi], grown,
 * through which all four leave it soonest, where the ends lie inside
 * that face's half-space: the wedge within it, which holds every point of
 * the box it held. Untouched where no face serves. */
static void volume_wedges_trim(float corners[6][4], const float lo[3], const float hi[3]) {
    float grow = VOLUME_WEDGES_TRIM_MARGIN * glm_vec3_distance((float *)lo, (float *)hi);
    float best = INFINITY, best_t[4];
    for (int face = 0; face < 6; face++) {
        int c = face / 2;
        float sign = face % 2 ? 1.0f : -1.0f;
        float limit = face % 2 ? hi[c] + grow : -(lo[c] - grow); /* inside: sign * x[c] <= limit */
        if (sign * corners[0][c] > limit || sign * corners[1][c] > limit)
            continue;
        float t[4], worst = 0;
        bool leaves = true;
        for (int k = 0; k < 4; k++) {
            const float *from = corners[k < 2 ? 0 : 1], *d = corners[2 + k];
            float along = sign * d[c];
            leaves = leaves && along >= VOLUME_WEDGES_MIN_SIDE;
            t[k] = leaves ? (limit - sign * from[c]) / along : INFINITY;
            worst = fmaxf(worst, t[k]);
        }
        if (leaves && worst < best) {
            best = worst;
            memcpy(best_t, t, sizeof t);
        }
    }
    if (best == INFINITY)
        return;
    for (int k = 0; k < 4; k++) {
        float *d = corners[2 + k];
        const float *from = corners[k < 2 ? 0 : 1];
        for (int c = 0; c < 3; c++)
            d[c] = from[c] + d[c] * best_t[k];
        d[3] = 1;
    }
}

int volume_wedges_edge(const float a[3], const float b[3], const float light[4], float reach, const float *box_lo,
                       const float *box_hi, float out[VOLUME_WEDGES_EDGE_VERTICES][4]) {
    vec3 along, back, away_a, away_b, side_a, side_b;
    float sine_a, sine_b;
    glm_vec3_sub((float *)b, (float *)a, along);
    float length = glm_vec3_norm(along);
    if (length == 0 || !volume_wedges_cone(a, light, reach, away_a, &sine_a) ||
        !volume_wedges_cone(b, light, reach, away_b, &sine_b))
        return 0;
    glm_vec3_scale(along, 1 / length, along);
    glm_vec3_negate_to(along, back);
    if (!volume_wedges_side(along, away_a, sine_a, side_a) || !volume_wedges_side(back, away_b, sine_b, side_b))
        return 0;
    /* The front and back planes: through the edge's line, tangent to the
     * ball, each with the light on its positive side. */
    vec3 to_light, across, turn, front, rear;
    for (int c = 0; c < 3; c++)
        to_light[c] = light[c] - a[c] * light[3];
    glm_vec3_scale(along, glm_vec3_dot(to_light, along), across);
    glm_vec3_sub(to_light, across, across);
    float height = glm_vec3_norm(across);
    if (height <= reach * VOLUME_WEDGES_GROWTH)
        return 0;
    glm_vec3_scale(across, 1 / height, across);
    glm_vec3_cross(along, across, turn);
    float sine = reach * VOLUME_WEDGES_GROWTH / height, cosine = sqrtf(1 - sine * sine);
    for (int c = 0; c < 3; c++) {
        front[c] = across[c] * sine + turn[c] * cosine;
        rear[c] = across[c] * sine - turn[c] * cosine;
    }
    float corners[6][4] = {{a[0], a[1], a[2], 1}, {b[0], b[1], b[2], 1}};
    if (!volume_wedges_far(side_a, front, away_a, corners[2]) ||
        !volume_wedges_far(side_a, rear, away_a, corners[3]) ||
        !volume_wedges_far(side_b, front, away_b, corners[4]) || !volume_wedges_far(side_b, rear, away_b, corners[5]))
        return 0;
    if (box_lo)
        volume_wedges_trim(corners, box_lo, box_hi);
    /* A point inside: the edge's middle moved along every far direction
     * (to a far corner, a share of the way). */
    float inside[4] = {(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2, 1};
    for (int k = 2; k < 6; k++)
        for (int c = 0; c < 3; c++)
            inside[c] += corners[k][3] != 0 ? (corners[k][c] - inside[c]) / 8 : corners[k][c] * length;
    for (int t = 0; t < VOLUME_WEDGES_EDGE_VERTICES; t += 3) {
        const float *p0 = corners[volume_wedges_faces[t]], *p1 = corners[volume_wedges_faces[t + 1]],
                    *p2 = corners[volume_wedges_faces[t + 2]];
        /* Outwards counter-clockwise: det[p0; p1; p2; inside] > 0. */
        if (volume_wedges_det4(p0, p1, p2, inside) < 0) {
            const float *swap = p1;
            p1 = p2, p2 = swap;
        }
        memcpy(out[t], p0, sizeof out[t]);
        memcpy(out[t + 1], p1, sizeof out[t]);
        memcpy(out[t + 2], p2, sizeof out[t]);
    }
    return VOLUME_WEDGES_EDGE_VERTICES;
}

/* ---- GL ---- */

static bool volume_wedges_load(volume_wedges_program *p, const char *vertex, const char *fragment) {
    const char *const files[] = {vertex, fragment};
    static const shader_define defines[] = {
        SHADER_DEFINE(WEDGE_AREA_NEAR_RECIPROCAL), SHADER_DEFINE(VOLUME_WEDGES_LIFT_RECIPROCAL), {NULL, 0}};
    p->id = shader_load_program(files, 2, defines);
    if (!p->id)
        return false;
    p->view_projection = shader_uniform_optional(p->id, "u_view_projection");
    p->inverse_view_projection = shader_uniform(p->id, "u_inverse_view_projection");
    p->depth_to_ndc = shader_uniform(p->id, "u_depth_to_ndc");
    p->far_depth = shader_uniform(p->id, "u_far_depth");
    p->light = shader_uniform(p->id, "u_light");
    p->size = shader_uniform(p->id, "u_size");
    p->depth = shader_uniform(p->id, "u_depth");
    p->eye = shader_uniform(p->id, "u_eye");
    return true;
}

bool volume_wedges_init(volume_wedges *w) {
    *w = (volume_wedges){0};
    if (!volume_wedges_load(&w->wedge, "wedge.vert", "wedge.frag"))
        return false;
    glGenVertexArrays(1, &w->vao);
    glGenBuffers(1, &w->buffer);
    glBindVertexArray(w->vao);
    glBindBuffer(GL_ARRAY_BUFFER, w->buffer);
    static const size_t offsets[3] = {offsetof(volume_wedges_vertex, position), offsetof(volume_wedges_vertex, a),
                                      offsetof(volume_wedges_vertex, b)};
    for (int k = VOLUME_WEDGES_POSITION; k <= VOLUME_WEDGES_B; k++) {
        glEnableVertexAttribArray((GLuint)k);
        glVertexAttribPointer((GLuint)k, 4, GL_FLOAT, GL_FALSE, sizeof(volume_wedges_vertex), (void *)offsets[k]);
    }
    glBindVertexArray(0);
    glGenFramebuffers(1, &w->depth_framebuffer);
    glGenTextures(1, &w->depth_texture);
    return context_gl_ok("volume_wedges_init");
}

void volume_wedges_destroy(volume_wedges *w) {
    shader_delete_program(w->wedge.id);
    glDeleteVertexArrays(1, &w->vao);
    glDeleteBuffers(1, &w->buffer);
    glDeleteFramebuffers(1, &w->depth_framebuffer);
    glDeleteTextures(1, &w->depth_texture);
    free(w->vertices);
    volume_mesh_free(&w->edges);
    *w = (volume_wedges){0};
}

/* The depth texture at the bound target's size and depth format. */
static bool volume_wedges_match(volume_wedges *w, int target) {
    GLint viewport[4], type, name, format = GL_DEPTH24_STENCIL8;
    glGetIntegerv(GL_VIEWPORT, viewport);
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT,
                                          GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT,
                                          GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
    if (type == GL_RENDERBUFFER) {
        glBindRenderbuffer(GL_RENDERBUFFER, (GLuint)name);
        glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_INTERNAL_FORMAT, &format);
    }
    if (viewport[2] == w->width && viewport[3] == w->height && format == w->depth_format)
        return true;
    w->width = viewport[2];
    w->height = viewport[3];
    w->depth_format = format;
    bool float_depth = format == GL_DEPTH32F_STENCIL8;
    glBindTexture(GL_TEXTURE_2D, w->depth_texture);
    glTexImage2D(GL_TEXTURE_2D, 0, format, w->width, w->height, 0, GL_DEPTH_STENCIL,
                 float_depth ? GL_FLOAT_32_UNSIGNED_INT_24_8_REV : GL_UNSIGNED_INT_24_8, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glBindFramebuffer(GL_FRAMEBUFFER, w->depth_framebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, w->depth_texture, 0);
    static const GLenum none = GL_NONE;
    glDrawBuffers(1, &none);
    glReadBuffer(GL_NONE);
    bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)target);
    if (!complete) {
        fprintf(stderr, "volume_wedges: a %dx%d depth copy is incomplete\n", w->width, w->height);
        w->width = 0;
    }
    return complete;
}

/* The bound target's depth into w's texture, which the wedges read. */
static bool volume_wedges_copy_depth(volume_wedges *w) {
    GLint target;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
    if (!volume_wedges_match(w, target))
        return false;
    GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST);
    glDisable(GL_SCISSOR_TEST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)target);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, w->depth_framebuffer);
    glBlitFramebuffer(0, 0, w->width, w->height, 0, 0, w->width, w->height, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)target);
    if (scissor)
        glEnable(GL_SCISSOR_TEST);
    return true;
}

/* Adds the centre's share where the bound target's stencil (its bits:
 * stencil_mask) holds the count n of the casters that take the closed
 * rule, 1 - n, or (open) of those that take the open rule, -1 where n is
 * not 0; within the scissor as set. */
static void volume_wedges_add_centre(soft_visibility *v, int l, unsigned stencil_mask, bool open) {
    glEnable(GL_STENCIL_TEST);
    if (open) {
        glStencilFunc(GL_NOTEQUAL, 0, stencil_mask);
        soft_visibility_add(v, l, -1);
    }
    for (int n = 0; !open && n <= VOLUME_WEDGES_DEEPEST; n++) {
        glStencilFunc(n < VOLUME_WEDGES_DEEPEST ? GL_EQUAL : GL_LEQUAL, n, stencil_mask);
        if (n != 1) /* 1 - 1 adds nothing */
            soft_visibility_add(v, l, (float)(1 - n));
    }
    glDisable(GL_STENCIL_TEST);
}

/* Whether caster i takes the open rule for the light (homogeneous,
 * world): volume_mesh_closed_rule's "no". */
static bool volume_wedges_open(const technique_frame *f, int i, const mesh_edges *edges, const float light[4]) {
    const scene_object *o = &f->gpu->scene->objects[i];
    float object_light[4];
    mesh_point_to_object(o->model, light, object_light);
    return !volume_mesh_closed_rule(&o->mesh, &edges[i], object_light);
}

/* Appends the wedge of edge a -> b (multiplicity m) to w's vertices;
 * false when it has none. */
static bool volume_wedges_add(volume_wedges *w, const float a[3], const float b[3], float m, const float light[4],
                              float reach) {
    float corners[VOLUME_WEDGES_EDGE_VERTICES][4];
    if (!volume_wedges_edge(a, b, light, reach, w->box_lo, w->box_hi, corners))
        return false;
    if (w->count + VOLUME_WEDGES_EDGE_VERTICES > w->capacity) {
        size_t capacity = w->capacity ? w->capacity * 2 : VOLUME_WEDGES_EDGE_VERTICES * 256;
        volume_wedges_vertex *grown = realloc(w->vertices, capacity * sizeof *grown);
        if (!grown) {
            fprintf(stderr, "volume_wedges: out of memory\n");
            return false;
        }
        w->vertices = grown;
        w->capacity = capacity;
    }
    for (int k = 0; k < VOLUME_WEDGES_EDGE_VERTICES; k++) {
        volume_wedges_vertex *v = &w->vertices[w->count++];
        memcpy(v->position, corners[k], sizeof v->position);
        memcpy(v->a, a, 3 * sizeof *a);
        memcpy(v->b, b, 3 * sizeof *b);
        v->a[3] = m;
        v->b[3] = 0;
    }
    return true;
}

/* Every caster's silhouette edges from the light's centre, as wedges into
 * w's vertices. */
static void volume_wedges_build(volume_wedges *w, const technique_frame *f, const mesh_edges *edges,
                                const float centre[4], float reach, bool reported) {
    const scene *s = f->gpu->scene;
    int wedges = 0, skipped = 0;
    w->count = 0;
    for (int i = 0; i < s->object_count; i++) {
        const scene_object *o = &s->objects[i];
        if (!o->casts)
            continue;
        float object_light[4];
        mesh_point_to_object(o->model, centre, object_light);
        if (!volume_mesh_build(&w->edges, &o->mesh, &edges[i], object_light, NULL, VOLUME_MESH_SILHOUETTE_EDGES)) {
            fprintf(stderr, "volumes: %s: out of memory finding its silhouette\n", o->name);
            continue;
        }
        /* A mirroring model turns the edges' orientation round. */
        mat3 linear;
        glm_mat4_pick3((vec4 *)o->model, linear);
        float mirror = glm_mat3_det(linear) < 0 ? -1.0f : 1.0f;
        bool open = !volume_mesh_closed_rule(&o->mesh, &edges[i], object_light);
        for (size_t k = 0; k + 1 < w->edges.count; k += 2) {
            vec3 a, b;
            glm_mat4_mulv3((vec4 *)o->model, w->edges.vertices[k], 1, a);
            glm_mat4_mulv3((vec4 *)o->model, w->edges.vertices[k + 1], 1, b);
            float m = w->edges.vertices[k][3];
            if (open) /* a fold's two layers count once */
                m = copysignf(ceilf(fabsf(m) / 2), m);
            if (volume_wedges_add(w, a, b, m * mirror, centre, reach))
                wedges++;
            else
                skipped++;
        }
    }
    if (reported) {
        w->wedge_count = wedges;
        w->skipped_count = skipped;
    }
}

/* Binds program p with the frame's and the light's uniforms. */
static void volume_wedges_use(const volume_wedges *w, const volume_wedges_program *p, const technique_frame *f,
                              const float centre[4], float size) {
    glUseProgram(p->id);
    mat4 inverse;
    glm_mat4_inv((vec4 *)f->view->raster_view_projection, inverse);
    if (p->view_projection >= 0)
        glUniformMatrix4fv(p->view_projection, 1, GL_FALSE, (const float *)f->view->raster_view_projection);
    glUniformMatrix4fv(p->inverse_view_projection, 1, GL_FALSE, (const float *)inverse);
    glUniform2fv(p->depth_to_ndc, 1,
                 f->view->reversed_depth ? volume_wedges_reversed_ndc : volume_wedges_standard_ndc);
    glUniform1f(p->far_depth, depth_far(f->view));
    glUniform4fv(p->light, 1, centre);
    glUniform1f(p->size, size);
    glUniform3fv(p->eye, 1, f->view->eye);
    glUniform1i(p->depth, VOLUME_WEDGES_DEPTH_UNIT);
    glActiveTexture(GL_TEXTURE0 + VOLUME_WEDGES_DEPTH_UNIT);
    glBindTexture(GL_TEXTURE_2D, w->depth_texture);
}

/* The wedges' triangles, back faces only, added. */
static void volume_wedges_draw_wedges(volume_wedges *w, const technique_frame *f, const float centre[4], float size) {
    if (w->count == 0)
        return;
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT); /* the back faces: each pixel of a wedge once */
    volume_wedges_use(w, &w->wedge, f, centre, size);
    glBindVertexArray(w->vao);
    glBindBuffer(GL_ARRAY_BUFFER, w->buffer);
    size_t bytes = w->count * sizeof *w->vertices;
    if (bytes > w->buffer_capacity) {
        w->buffer_capacity = bytes * 2;
        glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)w->buffer_capacity, NULL, GL_STREAM_DRAW);
    }
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)bytes, w->vertices);
    glDrawArrays(GL_TRIANGLES, 0, (GLsizei)w->count);
    glDisable(GL_CULL_FACE);
}

/* Light l's wedges of every caster (edges: per object, the casters'
 * tables), added into v's target; the caller's scissor stays. */
static void volume_wedges_draw(volume_wedges *w, const technique_frame *f, int l, const mesh_edges *edges,
                               soft_visibility *v) {
    const scene_light *light = &f->gpu->scene->lights[l];
    float centre[4], reach, size;
    scene_light_homogeneous(light, centre);
    if (centre[3] != 0) {
        reach = size = light->radius;
    } else {
        glm_vec3_normalize(centre);
        float angle = glm_rad(light->radius);
        reach = sinf(angle);
        size = tanf(angle);
    }
    /* Every wedge ends past the visible receivers; none without them. */
    if (f->skips->receivers_lo[0] > f->skips->receivers_hi[0])
        return;
    w->box_lo = f->skips->receivers_lo;
    w->box_hi = f->skips->receivers_hi;
    volume_wedges_build(w, f, edges, centre, reach, l == 0);
    GLboolean cull = glIsEnabled(GL_CULL_FACE), depth_test = glIsEnabled(GL_DEPTH_TEST),
              blend = glIsEnabled(GL_BLEND);
    GLint cull_mode, depth_func_was;
    GLboolean depth_mask;
    glGetIntegerv(GL_CULL_FACE_MODE, &cull_mode);
    glGetIntegerv(GL_DEPTH_FUNC, &depth_func_was);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask);
    glBindFramebuffer(GL_FRAMEBUFFER, v->lights[l].framebuffer);
    /* A pixel whose point lies in a wedge sees the wedge's back face at
     * or behind it: the rest are left out by the frame's depth (which v's
     * target shares). */
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(depth_func(f->view, GL_GEQUAL));
    glDepthMask(GL_FALSE);
    glDisable(GL_STENCIL_TEST);
    depth_clamp(true);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    volume_wedges_draw_wedges(w, f, centre, size);
    glBindVertexArray(0);
    if (!blend)
        glDisable(GL_BLEND);
    depth_clamp(false);
    glCullFace((GLenum)cull_mode);
    if (cull)
        glEnable(GL_CULL_FACE);
    glDepthFunc((GLenum)depth_func_was);
    glDepthMask(depth_mask);
    if (!depth_test)
        glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, v->target_framebuffer);
}

bool volume_wedges_light(volume_wedges *w, const technique_frame *f, int l, const volume_plan *plan,
                         volume_plan_caster *group, const mesh_edges *edges, soft_visibility *v,
                         unsigned stencil_mask, volume_wedges_count count) {
    if (!soft_visibility_begin(v, l, 1, true) || !volume_wedges_copy_depth(w))
        return false;
    for (int open = 0; open <= 1; open++) {
        volume_plan part = *plan;
        part.casters = group;
        part.reported = plan->reported && !open;
        bool any = false;
        for (int i = 0; i < f->gpu->scene->object_count; i++) {
            group[i] = plan->casters[i];
            group[i].needed = group[i].needed && volume_wedges_open(f, i, edges, plan->position) == (bool)open;
            any = any || group[i].needed;
        }
        if (open && !any)
            break;
        count(f, &part);
        volume_wedges_add_centre(v, l, stencil_mask, open);
    }
    volume_wedges_draw(w, f, l, edges, v);
    return true;
}
