/* volumes: stencil shadow volumes, z-pass, z-fail and the choice between
 * them, for any mesh: closed, open or non-manifold.
 *
 * Crow, "Shadow algorithms for computer graphics", SIGGRAPH 1977: the space
 * a caster shadows is bounded by polygons (its silhouette swept away from
 * the light, and caps); a point is in shadow when the eye ray to it enters
 * more of those volumes than it leaves. Heidmann (1991) counts in the
 * stencil buffer the volume faces in front of the visible surface, +1 for
 * front faces, -1 for back faces (z-pass): wrong when the eye is inside a
 * volume. Carmack's reverse (Bilodeau & Songy, Carmack 2000; Everitt &
 * Kilgard, "Practical and robust stenciled shadow volumes", 2002) counts
 * the faces behind the surface instead (z-fail), which needs caps; the far
 * ones lie at infinity (w = 0), kept from the far plane by depth clamp.
 * The volumes are built by demos/lib/volume_mesh.h, whose top comment is
 * their manual (every triangle its own occluder, Aldridge & Woods 2004).
 * Counts wrap at 256: wrong only behind an exact multiple of 256 triangles
 * (closed meshes: casters).
 *
 * After a depth pre-pass, per light (up to 8): clear the stencil in the
 * screen rectangle of the receivers; draw every caster's volume with colour
 * and depth writes off, both faces counted in one pass (glStencilOpSeparate,
 * wrapping); shade the light where the stencil is 0 (everywhere on objects
 * that receive no shadows), the first light's pass with the ambient term
 * (technique_shade_light), so that one light costs one shading pass.
 * --mode auto (default) takes z-pass, without caps, where
 * volume_mesh_zpass_safe says the volume cannot reach the near-plane
 * rectangle, z-fail with caps elsewhere; --mode zpass with the camera
 * inside a shadow visibly fails (shadows inverted).
 *
 * --silhouette gpu finds silhouettes in a geometry shader over
 * GL_TRIANGLES_ADJACENCY (shaders/volume_silhouette.geom), for closed
 * meshes: only they have the adjacency; open meshes stay on the CPU (the
 * HUD counts them). It emits the sides alone: z-fail's caps come from the
 * CPU (kept like its sides) through volume.vert, the vertex path of the
 * depth pre-pass (lit.vert's invariant expression, the same uniforms),
 * since caps must lie at exactly the depth of their surface and llvmpipe
 * rasterizes a geometry shader's triangles at slightly other depths than
 * a vertex shader's (measured with the shader's caps: 0.2 to 0.4 % false
 * shadow on simple and bunny; with the vertex path's, as exact as the
 * CPU's).
 * --extrude reach (key T) trims the CPU volumes past the light's reach
 * (every receiver, clipped to its range; volume_mesh_trim_for), closed
 * there by far caps, so that they fill less; off by default: a shadow
 * edge's pixel may flip by the rounding of the shorter sides' depth
 * (measured: 8 to 60 of 230400 pixels on the standard scenes, no worse
 * against the reference). Not with --mode zpass (see volumes_trim).
 * Depth bounds (GL_EXT_depth_bounds_test, where present; --no-depth-bounds
 * turns them off): while counting a light, only pixels whose depth lies
 * within the visible receivers in its reach take stencil updates
 * (volume_mesh_depth_bounds); no decision changes, as the others keep the
 * cleared count where the light adds 0.
 * --overlay (key V), for lectures: the volumes of light 0 translucent with
 * their edges, its silhouette edges, or its stencil count as colour.
 *
 * Skips (README, "Skips"), none of which changes a count on a visible
 * receiver, the only pixels the stencil decides:
 * - casters whose shadow cannot reach a visible receiver draw no volume
 *   (technique_caster_needed: outside the hull of the light and the
 *   visible receivers' bounds; see volumes_caster_needed for why exact);
 * - volumes that miss the view draw none (volume_mesh_misses_view: no
 *   fragment of them would be drawn), counted as culled;
 * - the CPU volumes are kept, one GPU buffer per light, each caster's
 *   sides and caps apart (the camera picks z-pass or z-fail each frame),
 *   built when a caster is first needed after the light moved and drawn
 *   from there until it moves again (objects never move); past
 *   VOLUMES_CACHE_MAX_BYTES in all, the rest is built every frame.
 */
#include <GLFW/glfw3.h>
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "technique.h"
#include "volume_cache.h"
#include "volume_mesh.h"

typedef struct volumes_settings {
    int mode;       /* choice */
    int silhouette; /* choice */
    int overlay;    /* choice */
    int extrude;    /* choice */
    bool no_depth_bounds; /* toggle */
} volumes_settings;

static const char *const volumes_modes[] = {"auto", "zpass", "zfail", NULL};
static const char *const volumes_silhouettes[] = {"cpu", "gpu", NULL};
static const char *const volumes_overlays[] = {"none", "volumes", "silhouettes", "counts", NULL};
static const char *const volumes_extrusions[] = {"infinity", "reach", NULL};
enum { VOLUMES_AUTO, VOLUMES_ZPASS, VOLUMES_ZFAIL };
enum { VOLUMES_CPU, VOLUMES_GPU };
enum { VOLUMES_EXTRUDE_INFINITY, VOLUMES_EXTRUDE_REACH };
enum { VOLUMES_OVERLAY_NONE, VOLUMES_OVERLAY_VOLUMES, VOLUMES_OVERLAY_SILHOUETTES, VOLUMES_OVERLAY_COUNTS };

/* Every bit of the 8-bit stencil: counts wrap at 256 (see top). */
#define VOLUMES_STENCIL_MASK 0xff
/* The counts overlay colours counts 1, 2, 3 and "this many or more", by a
 * ramp from blue to red, translucent so the picture shows through. */
#define VOLUMES_COUNT_STEPS 4
#define VOLUMES_COUNT_ALPHA 0.45f
static const float volumes_count_ramp[VOLUMES_COUNT_STEPS][3] = {
    {0.2f, 0.4f, 1}, {0.2f, 1, 0.3f}, {1, 0.9f, 0.1f}, {1, 0.2f, 0.1f}};
/* The volumes overlay: faint faces (many overlap), clearer edges; the
 * silhouettes overlay: opaque red lines. */
static const float volumes_overlay_faces[4] = {1.0f, 0.85f, 0.2f, 0.12f};
static const float volumes_overlay_edges[4] = {1.0f, 0.85f, 0.2f, 0.6f};
static const float volumes_overlay_silhouette[4] = {1.0f, 0.3f, 0.2f, 1.0f};
/* The whole screen in clip space (two triangles), for the counts overlay. */
static const float volumes_screen[6][4] = {{-1, -1, 0, 1}, {1, -1, 0, 1}, {1, 1, 0, 1},
                                           {-1, -1, 0, 1}, {1, 1, 0, 1},  {-1, 1, 0, 1}};

/* The most the kept volumes take on the GPU, all lights together
 * (measured: dense's 158k triangles under its directional light, z-fail
 * caps and all, 4.7 MiB; the city's 7 lights 0.1 MiB). */
#define VOLUMES_MIB ((size_t)1 << 20)
#define VOLUMES_CACHE_MAX_BYTES (256 * VOLUMES_MIB)

/* One caster's topology, built once per scene. */
typedef struct volumes_caster {
    mesh_edges edges;
    unsigned adjacency_vao, adjacency_buffer; /* closed meshes: GPU path */
    int adjacency_count;
} volumes_caster;

static struct {
    volumes_settings settings;
    render_program cpu, gpu; /* volumes built on the CPU (and overlays), or found on the GPU */
    int gpu_light, cpu_color;
    volumes_caster *casters;
    int caster_count;
    unsigned stream_vao, stream_buffer;
    size_t stream_capacity;
    volume_mesh geometry; /* the caster at hand's volume */
    volume_cache caches[SCENE_MAX_LIGHTS];
    size_t cache_bytes; /* all caches' buffers */
    bool *needed;       /* per object: it casts a volume for the light at hand */
    float receivers_lo[3], receivers_hi[3]; /* every receiver's box together; empty when none */
    /* The light at hand's reach (volume_mesh_trim_for), when it trims. */
    bool reach_on;
    float reach_lo[3], reach_hi[3];
    int trim_kept; /* whether the kept volumes are trimmed; -1: none kept yet */
    bool has_depth_bounds; /* GL_EXT_depth_bounds_test */
    int built, reused;  /* parts, for the light at hand */
    /* Light 0, last frame: */
    int zpass_count, zfail_count, gpu_fallback_count, built_count, reused_count;
} volumes;

static const flags_param volumes_params[] = {
    {"mode", "z-pass (no caps) where safe, else z-fail (caps); or force one", GLFW_KEY_Z, FLAGS_CHOICE,
     .index = &volumes.settings.mode, .choices = volumes_modes},
    {"silhouette", "where silhouettes are found: the CPU edge table or a geometry shader", GLFW_KEY_G,
     FLAGS_CHOICE, .index = &volumes.settings.silhouette, .choices = volumes_silhouettes},
    {"overlay", "for lectures: the volumes, the silhouette edges, or the stencil count as colour", GLFW_KEY_V,
     FLAGS_CHOICE, .index = &volumes.settings.overlay, .choices = volumes_overlays},
    {"extrude", "CPU volumes swept to infinity, or trimmed past the light's reach (less fill; shadow edges may "
                "move by rounding)",
     GLFW_KEY_T, FLAGS_CHOICE, .index = &volumes.settings.extrude, .choices = volumes_extrusions},
    {"depth-bounds", "volumes also count where no receiver in the light's reach is (no decision changes)", GLFW_KEY_B,
     FLAGS_TOGGLE, .disabled = &volumes.settings.no_depth_bounds},
};

/* ---- set-up ---- */

/* Object i's edge table and, for a closed mesh, its adjacency indices on
 * the GPU. */
static bool volumes_init_caster(const render_scene *gpu, int i) {
    const mesh *m = &gpu->scene->objects[i].mesh;
    volumes_caster *c = &volumes.casters[i];
    if (!volume_mesh_edges_build(m, &c->edges))
        return false;
    size_t count = (size_t)m->index_count * 2; /* 6 per triangle: each corner, then the one across */
    uint32_t *adjacency = c->edges.closed ? malloc(count * sizeof *adjacency) : NULL;
    if (adjacency && mesh_adjacency_indices(m, &c->edges, adjacency)) {
        glGenVertexArrays(1, &c->adjacency_vao);
        glBindVertexArray(c->adjacency_vao);
        glBindBuffer(GL_ARRAY_BUFFER, gpu->meshes[i].vertex_buffer);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(mesh_vertex), NULL);
        glGenBuffers(1, &c->adjacency_buffer);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, c->adjacency_buffer);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(count * sizeof *adjacency), adjacency, GL_STATIC_DRAW);
        c->adjacency_count = (int)count;
        glBindVertexArray(0);
    }
    free(adjacency);
    return true;
}

static bool volumes_init(const render_scene *gpu) {
    static const char *const cpu_files[] = {"volume.vert", "volume.frag"};
    static const char *const gpu_files[] = {"volume_adjacency.vert", "volume_silhouette.geom", "volume.frag"};
    if (!render_program_load(&volumes.cpu, cpu_files, (int)(sizeof cpu_files / sizeof *cpu_files), NULL) ||
        !render_program_load(&volumes.gpu, gpu_files, (int)(sizeof gpu_files / sizeof *gpu_files), NULL))
        return false;
    volumes.gpu_light = glGetUniformLocation(volumes.gpu.id, "u_light");
    volumes.cpu_color = glGetUniformLocation(volumes.cpu.id, "u_color");
    const scene *s = gpu->scene;
    size_t objects = (size_t)s->object_count;
    volumes.casters = calloc(objects, sizeof *volumes.casters);
    volumes.needed = calloc(objects, sizeof *volumes.needed);
    if (!volumes.casters || !volumes.needed) {
        fprintf(stderr, "volumes: out of memory\n");
        return false;
    }
    for (int l = 0; l < s->light_count; l++)
        if (!volume_cache_init(&volumes.caches[l], s->object_count))
            return false;
    volumes.caster_count = s->object_count;
    volumes.trim_kept = -1;
    volumes.has_depth_bounds = GLAD_GL_EXT_depth_bounds_test;
    glm_vec3_fill(volumes.receivers_lo, INFINITY);
    glm_vec3_fill(volumes.receivers_hi, -INFINITY);
    for (int i = 0; i < s->object_count; i++) {
        if (s->objects[i].casts && !volumes_init_caster(gpu, i))
            return false;
        float lo[3], hi[3];
        scene_object_world_bounds(&s->objects[i], lo, hi);
        if (s->objects[i].receives) {
            glm_vec3_minv(volumes.receivers_lo, lo, volumes.receivers_lo);
            glm_vec3_maxv(volumes.receivers_hi, hi, volumes.receivers_hi);
        }
    }
    glGenVertexArrays(1, &volumes.stream_vao);
    glGenBuffers(1, &volumes.stream_buffer);
    volume_cache_vertex_array(volumes.stream_vao, volumes.stream_buffer);
    return true;
}

static void volumes_destroy(void) {
    render_program_destroy(&volumes.cpu);
    render_program_destroy(&volumes.gpu);
    for (int i = 0; i < volumes.caster_count; i++) {
        mesh_edges_free(&volumes.casters[i].edges);
        glDeleteVertexArrays(1, &volumes.casters[i].adjacency_vao);
        glDeleteBuffers(1, &volumes.casters[i].adjacency_buffer);
    }
    for (int l = 0; l < SCENE_MAX_LIGHTS; l++)
        volume_cache_free(&volumes.caches[l]);
    free(volumes.casters);
    free(volumes.needed);
    volume_mesh_free(&volumes.geometry);
    glDeleteVertexArrays(1, &volumes.stream_vao);
    glDeleteBuffers(1, &volumes.stream_buffer);
    volumes.casters = NULL;
    volumes.needed = NULL;
    volumes.caster_count = 0;
    volumes.stream_capacity = volumes.cache_bytes = 0;
    volumes.stream_vao = volumes.stream_buffer = 0;
}

/* ---- counting ---- */

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

/* Homogeneous vertices from the CPU, through the stream buffer. */
static void volumes_draw_stream(const float (*vertices)[4], size_t count, GLenum primitive) {
    glBindVertexArray(volumes.stream_vao);
    glBindBuffer(GL_ARRAY_BUFFER, volumes.stream_buffer);
    size_t bytes = count * sizeof *vertices;
    if (bytes > volumes.stream_capacity) {
        volumes.stream_capacity = bytes * 2;
        glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)volumes.stream_capacity, NULL, GL_STREAM_DRAW);
    }
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)bytes, vertices);
    glDrawArrays(primitive, 0, (GLsizei)count);
}

static bool volumes_on_gpu(const volumes_caster *c) {
    return volumes.settings.silhouette == VOLUMES_GPU && c->adjacency_vao;
}

/* Whether volumes end past their light's reach (volume_mesh_trim_for):
 * not for forced z-pass, whose count from an eye inside a volume (wrong,
 * for lectures) a trim could change. */
static bool volumes_trim(void) {
    return volumes.settings.extrude == VOLUMES_EXTRUDE_REACH && volumes.settings.mode != VOLUMES_ZPASS;
}

/* Light l's reach for the volumes built next: every receiver, clipped to
 * its range. Not only the visible ones: the kept volumes outlive the
 * camera. */
static void volumes_set_reach(const scene *s, int l) {
    glm_vec3_copy(volumes.receivers_lo, volumes.reach_lo);
    glm_vec3_copy(volumes.receivers_hi, volumes.reach_hi);
    volumes.reach_on = volumes_trim() && scene_light_clip_to_range(&s->lights[l], volumes.reach_lo, volumes.reach_hi);
}

/* Caster i's volume part for the light (homogeneous, world) into
 * volumes.geometry, with the CPU program bound for it; false after
 * printing why. */
static bool volumes_build(const technique_frame *f, int i, const float light[4], volume_mesh_parts part) {
    const scene_object *o = &f->gpu->scene->objects[i];
    float object_light[4];
    volume_mesh_object_light(o->model, light, object_light);
    volume_mesh_trim trim = {0};
    if (volumes.reach_on)
        volume_mesh_trim_for(o->model, object_light, &o->mesh, volumes.reach_lo, volumes.reach_hi, &trim);
    render_program_use(&volumes.cpu, f->view);
    glUniformMatrix4fv(volumes.cpu.model, 1, GL_FALSE, (const float *)o->model);
    if (volume_mesh_build(&volumes.geometry, &o->mesh, &volumes.casters[i].edges, object_light, &trim, part))
        return true;
    fprintf(stderr, "volumes: %s: out of memory building its volume\n", o->name);
    return false;
}

/* Caster i's part for light l, from the light's cache, kept there first
 * if it is not yet (streamed when it does not fit). */
static void volumes_draw_kept(const technique_frame *f, int l, int i, const float light[4], volume_mesh_parts part) {
    volume_cache *c = &volumes.caches[l];
    if (volume_cache_has(c, i, part)) {
        volumes.reused++;
        render_program_use(&volumes.cpu, f->view);
        glUniformMatrix4fv(volumes.cpu.model, 1, GL_FALSE, (const float *)f->gpu->scene->objects[i].model);
    } else {
        volumes.built++;
        if (!volumes_build(f, i, light, part))
            return;
        const volume_mesh *v = &volumes.geometry;
        if (!volume_cache_keep(c, i, part, v, &volumes.cache_bytes, VOLUMES_CACHE_MAX_BYTES)) {
            volumes_draw_stream(v->vertices, v->count, GL_TRIANGLES);
            return;
        }
    }
    volume_cache_draw(c, i, part);
}

/* Caster i's volume for light l counted into the stencil: sides (from the
 * geometry shader or the CPU), and caps after them for z-fail, always
 * from the CPU through volume.vert (see top). */
static void volumes_count_caster(const technique_frame *f, int l, int i, const float light[4], bool zfail) {
    const scene_object *o = &f->gpu->scene->objects[i];
    const volumes_caster *c = &volumes.casters[i];
    volumes_stencil_ops(zfail);
    if (volumes_on_gpu(c)) {
        float object_light[4];
        volume_mesh_object_light(o->model, light, object_light);
        render_program_use(&volumes.gpu, f->view);
        glUniformMatrix4fv(volumes.gpu.model, 1, GL_FALSE, (const float *)o->model);
        glUniform4fv(volumes.gpu_light, 1, object_light);
        glBindVertexArray(c->adjacency_vao);
        glDrawElements(GL_TRIANGLES_ADJACENCY, c->adjacency_count, GL_UNSIGNED_INT, NULL);
    } else {
        volumes_draw_kept(f, l, i, light, VOLUME_MESH_SIDES);
    }
    if (zfail)
        volumes_draw_kept(f, l, i, light, VOLUME_MESH_CAPS);
}

/* Whether the caster with world box [lo, hi] takes z-fail, with caps, for
 * the light (see top). */
static bool volumes_use_zfail(const float lo[3], const float hi[3], const float light[4],
                              const vec3 near_rectangle[4]) {
    if (volumes.settings.mode != VOLUMES_AUTO)
        return volumes.settings.mode == VOLUMES_ZFAIL;
    return !volume_mesh_zpass_safe(lo, hi, light, near_rectangle);
}

/* Whether caster i draws a volume for the hull's light; counted once,
 * drawn or culled. Leaving one out is exact when its count is 0 on every
 * visible receiver. A volume that misses the view has no fragment. A
 * point inside a caster's volume lies beyond the caster on a segment from
 * the light, so outside the hull of the light and the visible receivers'
 * bounds (convex) it contains no visible receiver point: z-fail counts
 * there exactly that, 0, and so does z-pass where it starts from 0, which
 * auto takes z-pass only where volume_mesh_zpass_safe says; forced z-pass
 * keeps casters that may shadow the eye (they count there). */
static bool volumes_caster_needed(const technique_frame *f, const technique_hull *hull, int i, const float light[4],
                                  const vec3 near_rectangle[4]) {
    const scene_object *o = &f->gpu->scene->objects[i];
    if (!o->casts)
        return false;
    float lo[3], hi[3];
    scene_object_world_bounds(o, lo, hi);
    if (f->cull_casters && volume_mesh_misses_view(lo, hi, light, f->view->view_projection)) {
        f->counts->casters_culled[hull->light]++;
        return false;
    }
    if (volumes.settings.mode == VOLUMES_ZPASS && !volume_mesh_zpass_safe(lo, hi, light, near_rectangle)) {
        f->counts->casters_drawn[hull->light]++;
        return true;
    }
    return technique_caster_needed(f, hull, i);
}

/* Stencil = number of volumes of light l around each visible pixel, of
 * the casters `needed` (NULL: every caster). */
static void volumes_count(const technique_frame *f, int l, const float light[4], const bool *needed) {
    const scene *s = f->gpu->scene;
    vec3 near_rectangle[4];
    volume_mesh_near_rectangle(f->view->view_projection, near_rectangle);
    int zpass = 0, zfail = 0, fallback = 0;
    volumes.built = volumes.reused = 0;
    glEnable(GL_DEPTH_CLAMP); /* far caps at infinity stay in */
    glDisable(GL_CULL_FACE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_LESS); /* a surface's own cap, at its depth, counts as behind it */
    glStencilFunc(GL_ALWAYS, 0, VOLUMES_STENCIL_MASK);
    /* Not only casters in view: one outside may cast a volume across it. */
    for (int i = 0; i < s->object_count; i++) {
        if (!s->objects[i].casts || (needed && !needed[i]))
            continue;
        float lo[3], hi[3];
        scene_object_world_bounds(&s->objects[i], lo, hi);
        bool use_zfail = volumes_use_zfail(lo, hi, light, near_rectangle);
        zfail += use_zfail;
        zpass += !use_zfail;
        fallback += volumes.settings.silhouette == VOLUMES_GPU && !volumes_on_gpu(&volumes.casters[i]);
        volumes_count_caster(f, l, i, light, use_zfail);
    }
    glDisable(GL_DEPTH_CLAMP);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (l == 0 && needed) {
        volumes.zpass_count = zpass;
        volumes.zfail_count = zfail;
        volumes.gpu_fallback_count = fallback;
        volumes.built_count = volumes.built;
        volumes.reused_count = volumes.reused;
    }
}

/* Turns on the depth bounds of the hull's light (volume_mesh_depth_bounds:
 * the visible receivers within its range, hull->lo..hi) where the
 * extension is and the frame's receivers are all there (not cut short);
 * false: left off. */
static bool volumes_depth_bounds(const technique_frame *f, const technique_hull *hull) {
    if (!volumes.has_depth_bounds || volumes.settings.no_depth_bounds ||
        f->receiver_count >= TECHNIQUE_MAX_RECEIVER_POINTS || hull->empty)
        return false;
    float bounds[2];
    if (!volume_mesh_depth_bounds(f->view->view_projection, f->receivers, f->receiver_count, hull->lo, hull->hi,
                                  bounds))
        return false;
    glEnable(GL_DEPTH_BOUNDS_TEST_EXT);
    glDepthBoundsEXT(bounds[0], bounds[1]);
    return true;
}

/* ---- lighting ---- */

/* Light l is blocked on receivers where a volume counts; the rest take no
 * shadows and are lit everywhere. */
static const technique_stencil_lit volumes_lit = {
    .lit = GL_EQUAL, .blocked = GL_NOTEQUAL, .ref = 0, .mask = VOLUMES_STENCIL_MASK, .receivers_only = true};

/* ---- overlays ---- */

/* The stencil still holds the last light's counts: recount light 0, then
 * colour each count by the ramp over the whole screen. */
static void volumes_draw_counts(const technique_frame *f, const float light[4]) {
    glEnable(GL_STENCIL_TEST);
    glClear(GL_STENCIL_BUFFER_BIT);
    volumes_count(f, 0, light, NULL); /* every volume: the overlay colours every pixel */
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    camera_view identity = {0};
    glm_mat4_identity(identity.view_projection);
    render_program_use(&volumes.cpu, &identity);
    glUniformMatrix4fv(volumes.cpu.model, 1, GL_FALSE, (const float *)identity.view_projection);
    for (int k = 1; k <= VOLUMES_COUNT_STEPS; k++) {
        glStencilFunc(k < VOLUMES_COUNT_STEPS ? GL_EQUAL : GL_LEQUAL, k, VOLUMES_STENCIL_MASK);
        glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
        const float *c = volumes_count_ramp[k - 1];
        glUniform4f(volumes.cpu_color, c[0], c[1], c[2], VOLUMES_COUNT_ALPHA);
        volumes_draw_stream(volumes_screen, sizeof volumes_screen / sizeof *volumes_screen, GL_TRIANGLES);
    }
    glDisable(GL_BLEND);
    glDisable(GL_STENCIL_TEST);
    glEnable(GL_DEPTH_TEST);
}

/* Light 0's volumes translucent with their edges, or its silhouettes. */
static void volumes_draw_shapes(const technique_frame *f, const float light[4]) {
    const scene *s = f->gpu->scene;
    glDisable(GL_STENCIL_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_LEQUAL);
    glEnable(GL_DEPTH_CLAMP);
    bool faces = volumes.settings.overlay == VOLUMES_OVERLAY_VOLUMES;
    for (int i = 0; i < s->object_count; i++) {
        if (!s->objects[i].casts ||
            !volumes_build(f, i, light, faces ? VOLUME_MESH_SIDES : VOLUME_MESH_SILHOUETTE_LINES))
            continue;
        const volume_mesh *v = &volumes.geometry;
        if (faces) {
            glUniform4fv(volumes.cpu_color, 1, volumes_overlay_faces);
            volumes_draw_stream(v->vertices, v->count, GL_TRIANGLES);
            glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
            glUniform4fv(volumes.cpu_color, 1, volumes_overlay_edges);
            volumes_draw_stream(v->vertices, v->count, GL_TRIANGLES);
            glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        } else {
            glUniform4fv(volumes.cpu_color, 1, volumes_overlay_silhouette);
            glDepthFunc(GL_ALWAYS);
            volumes_draw_stream(v->vertices, v->count, GL_LINES);
            glDepthFunc(GL_LEQUAL);
        }
    }
    glDisable(GL_DEPTH_CLAMP);
    glDisable(GL_BLEND);
}

/* ---- the frame ---- */

static void volumes_render(const technique_frame *f) {
    const scene *s = f->gpu->scene;
    render_depth_prepass(f->gpu, f->view, f->in_view); /* the depth every pass tests against */
    bool trim_changed = volumes.trim_kept != (int)volumes_trim();
    volumes.trim_kept = volumes_trim();
    for (int l = 0; l < s->light_count; l++)
        if (f->changed.scene || trim_changed || (f->changed.lights & RENDER_LIGHT_BIT(l)))
            volume_cache_forget(&volumes.caches[l]);
    vec3 near_rectangle[4];
    volume_mesh_near_rectangle(f->view->view_projection, near_rectangle);
    /* The screen rectangle of every receiver's box, the same for every
     * light: no shadow is counted outside it. */
    int receivers_rect[4];
    volume_mesh_receivers_scissor(s, f->view->view_projection, f->width, f->height, receivers_rect);
    for (int l = 0; l < s->light_count; l++) {
        if (!technique_light_on(f, l))
            continue;
        float light[4];
        scene_light_homogeneous(&s->lights[l], light);
        technique_hull hull;
        technique_light_hull(f, l, &hull);
        volumes_set_reach(s, l);
        for (int i = 0; i < s->object_count; i++)
            volumes.needed[i] = volumes_caster_needed(f, &hull, i, light, (const vec3 *)near_rectangle);
        glEnable(GL_SCISSOR_TEST);
        glScissor(receivers_rect[0], receivers_rect[1], receivers_rect[2], receivers_rect[3]);
        glClear(GL_STENCIL_BUFFER_BIT);
        glEnable(GL_STENCIL_TEST);
        bool bounded = volumes_depth_bounds(f, &hull);
        volumes_count(f, l, light, volumes.needed);
        if (bounded)
            glDisable(GL_DEPTH_BOUNDS_TEST_EXT);
        /* Its own scissor: objects that take no shadows may lie outside the receivers'. */
        technique_shade_light(f, l, &volumes_lit);
        glDisable(GL_STENCIL_TEST);
    }
    if (technique_ambient_light(f) < 0)
        technique_shade_ambient(f);
    if (volumes.settings.overlay == VOLUMES_OVERLAY_NONE || s->light_count == 0)
        return;
    float light[4]; /* for lectures, over the finished picture: light 0's */
    scene_light_homogeneous(&s->lights[0], light);
    volumes_set_reach(s, 0);
    if (volumes.settings.overlay == VOLUMES_OVERLAY_COUNTS)
        volumes_draw_counts(f, light);
    else
        volumes_draw_shapes(f, light);
}

static void volumes_describe(char *out, size_t size) {
    int n = snprintf(out, size, "light 0: %d casters z-pass, %d z-fail", volumes.zpass_count, volumes.zfail_count);
    if (volumes.gpu_fallback_count > 0 && n > 0 && (size_t)n < size)
        n += snprintf(out + n, size - (size_t)n, "; %d open: CPU silhouettes", volumes.gpu_fallback_count);
    if (n > 0 && (size_t)n < size)
        n += snprintf(out + n, size - (size_t)n, "; volumes built %d, kept %d; all lights' kept %.1f MiB",
                      volumes.built_count, volumes.reused_count, (double)volumes.cache_bytes / VOLUMES_MIB);
    if (n > 0 && (size_t)n < size)
        snprintf(out + n, size - (size_t)n, "; depth bounds %s",
                 !volumes.has_depth_bounds           ? "off (no GL_EXT_depth_bounds_test)"
                 : volumes.settings.no_depth_bounds ? "OFF"
                                                    : "on");
}

/* The sweep: mode x silhouette path, and the trim. */
static const char *const volumes_bench_configs[] = {
    "", "--mode zpass", "--mode zfail", "--silhouette gpu", "--mode zfail --silhouette gpu", "--extrude reach",
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
