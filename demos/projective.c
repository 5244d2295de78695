/* projective: fake shadows with projective textures.
 *
 * The bridge from planar shadows to shadow maps: the obstacles are drawn
 * black into a white-bordered texture from the light, through a frustum
 * fitted to them, and that image is projected onto each receiver as a
 * texture (Segal, Korobkin, van Widenfelt, Foran & Haeberli, "Fast shadows
 * and lighting effects using texture mapping", SIGGRAPH 1992;
 * OpenSceneGraph's osgshadowtexture example: the occluder drawn black
 * into a texture cleared white with a white border, a frustum fitted to
 * its bounding sphere, eye-linear texture coordinates on a separate
 * receiver subgraph). It is a shadow map without depth: the texture says
 * that a caster lies on the ray, never where, so
 *   - no self-shadowing: an object that casts and receives, textured
 *     (--self-shadow on), darkens its own lit side with its own
 *     silhouette; by default it takes no texture and shows no shadow;
 *   - back-projection: a receiver nearer the light than the obstacle (or
 *     behind the light) takes its shadow cast backward. The fix (near
 *     cut, on by default) shadows only points beyond the casters' nearest
 *     depth from the light: exact where no receiver lies between the
 *     light and a caster;
 *   - a receiver behind another: the image lands on every receiver along
 *     its rays. The split of obstacles and receivers is the
 *     application's: here casters are the objects that cast, receivers
 *     those that receive; --no-receivers-cast takes the receivers out of
 *     the texture (only what casts alone is an obstacle), and a receiver
 *     hidden behind another then takes the obstacles' shadow through it
 *     and none of the other's.
 * Each light's frustum is fitted to its casters (demos/lib/projective_fit.h:
 * a cone round a positional light's, a box along a directional one's).
 * Each pixel's
 * decision is a stencil mark, shaded as planar's: the light added where
 * the receiver pass left no mark. Area lights are drawn hard, from their
 * centre.
 */
#include <GLFW/glfw3.h>
#include <glad/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "projective_fit.h"
#include "shading.h"
#include "map.h"
#include "technique.h"

/* A pixel is shadowed where its texel is below this percent of white
 * (the casters' black, 0). */
#define PROJECTIVE_LIT_PERCENT 50
/* How far from its point a lookup reads, in texels, for caster culling:
 * the nearest texel's half and more than a texel of safety. */
#define PROJECTIVE_READ_REACH_TEXELS 2.0f

typedef enum projective_self_shadow { PROJECTIVE_SELF_SHADOW_OFF, PROJECTIVE_SELF_SHADOW_ON } projective_self_shadow;

typedef struct projective_settings {
    int texture_size; /* choice: projective_sizes */
    int self_shadow;  /* choice: projective_self_shadow */
    bool no_near_cut, no_receivers_cast;
} projective_settings;

/* One light's texture and the frustum it was drawn through. */
typedef struct projective_light {
    unsigned texture;
    int size;         /* of the texture as made; 0: none yet */
    bool drawn_valid; /* `drawn` is what the texture holds */
    projective_frustum frustum;
    bool *drawn; /* per object: drawn into the texture */
} projective_light;

static const char *const projective_sizes[] = {"2048", "256", "512", "1024", "4096", NULL};
static const char *const projective_self_shadows[] = {"off", "on", NULL};

static struct {
    projective_settings settings;
    render_programs caster; /* solid casters, and cut-out ones through their variant (render.h) */
    render_program receiver;
    int light_texture, projected, depth_plane, nearest, cut;
    unsigned framebuffer;
    projective_light lights[SCENE_MAX_LIGHTS];
    bool *wanted;                   /* per object: a caster the lookups may read, this light, this frame */
    float (*corners)[3];            /* the casters' box corners, 8 per object, for the fit */
    float (*boxes)[2][3];           /* the visible receivers' boxes, for caster culling */
    scene_light_set clamped_warned; /* bit l: light l's clamped frustum said */
} projective;

static const flags_param projective_params[] = {
    {"near-cut", "back-projection: receivers nearer the light than every caster, or behind it, take the shadow too",
     GLFW_KEY_N, FLAGS_TOGGLE, .disabled = &projective.settings.no_near_cut},
    {"self-shadow",
     "objects that cast and receive (while receivers cast): off, they take no texture and show no shadow at all; "
     "on, they take it and their own silhouette darkens their lit side",
     GLFW_KEY_C, FLAGS_CHOICE, .index = &projective.settings.self_shadow, .choices = projective_self_shadows},
    {"receivers-cast",
     "receivers leave the texture (only what casts alone is an obstacle): a receiver behind another takes the "
     "obstacles' shadow through it, and none of the other's",
     GLFW_KEY_B, FLAGS_TOGGLE, .disabled = &projective.settings.no_receivers_cast},
    {"texture-size", "texels on a side of each light's projected texture", GLFW_KEY_M, FLAGS_CHOICE,
     .index = &projective.settings.texture_size, .choices = projective_sizes},
};

/* Object i is drawn into the texture (projective_fit_casts). */
static bool projective_is_caster(const scene_object *o) {
    return projective_fit_casts(o, !projective.settings.no_receivers_cast);
}

/* Object i takes the projected texture. */
static bool projective_is_textured(const scene_object *o) {
    return o->receives && (!projective_is_caster(o) || projective.settings.self_shadow == PROJECTIVE_SELF_SHADOW_ON);
}

/* The casters light l's lookups may read this frame, into
 * projective.wanted: every caster, or with caster culling those whose
 * texture rectangle meets where the visible receivers read it (the
 * shadow maps' reads, map_layer_reads: exact, since a lookup reads
 * only its own texels, whatever their depth). Counted in f->skips->counts. */
static void projective_plan_casters(const technique_frame *f, int l, const projective_light *t) {
    const scene *s = f->gpu->scene;
    map_reads reads;
    if (f->skips->cull_casters) {
        map_read_setup setup = {.reach = PROJECTIVE_READ_REACH_TEXELS, .size = t->size, .any_depth = true};
        int boxes = map_light_receivers(f, l, projective.boxes);
        map_layer_reads(t->frustum.view_projection, &setup, f->skips->receivers, f->skips->receiver_count,
                        (const float(*)[2][3])projective.boxes, boxes, &reads);
    }
    for (int i = 0; i < s->object_count; i++) {
        vec3 lo, hi;
        projective.wanted[i] = false;
        if (!projective_is_caster(&s->objects[i]))
            continue;
        scene_object_world_bounds(&s->objects[i], lo, hi);
        projective.wanted[i] = !f->skips->cull_casters || map_caster_read(&reads, t->frustum.view_projection, lo, hi);
        if (projective.wanted[i])
            f->skips->counts->casters_drawn[l]++;
        else
            f->skips->counts->casters_culled[l]++;
    }
}

/* Light l's texture of `size` texels on a side, read a texel at a time
 * (texelFetch: the nearest, the cheapest lookup on a CPU rasterizer),
 * white beyond its border (the receiver shader's test); made again (and
 * its casters with it) when the size changes. */
static void projective_prepare_texture(projective_light *t, int size) {
    if (t->texture && t->size == size)
        return;
    if (!t->texture)
        glGenTextures(1, &t->texture);
    glBindTexture(GL_TEXTURE_2D, t->texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, size, size, 0, GL_RED, GL_UNSIGNED_BYTE, NULL);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    t->size = size;
    t->drawn_valid = false;
}

/* The casters of projective.wanted black on white into light l's
 * texture, unless it already holds them: nothing it depends on changed
 * (the light, the scene, the settings) and the same casters are wanted.
 * Restores the target and its viewport; false (said on stderr) where the
 * framebuffer is incomplete. */
static bool projective_draw_texture(const technique_frame *f, int l, projective_light *t) {
    const scene *s = f->gpu->scene;
    bool same =
        t->drawn_valid && !f->changed.scene && !f->changed.settings && !(f->changed.lights & SCENE_LIGHT_BIT(l));
    for (int i = 0; same && i < s->object_count; i++)
        same = t->drawn[i] == projective.wanted[i];
    if (same) {
        f->skips->counts->layers_reused++;
        return true;
    }
    GLint target, viewport[4];
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
    glGetIntegerv(GL_VIEWPORT, viewport);
    if (!projective.framebuffer)
        glGenFramebuffers(1, &projective.framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, projective.framebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t->texture, 0);
    bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    if (complete) {
        glViewport(0, 0, t->size, t->size);
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_STENCIL_TEST);
        glClearColor(1, 1, 1, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        for (int pass = 0; pass < render_programs_passes(&projective.caster); pass++) {
            const render_program *p = render_programs_pass(&projective.caster, pass);
            glUseProgram(p->id);
            glUniformMatrix4fv(p->view_projection, 1, GL_FALSE, (const float *)t->frustum.view_projection);
            for (int i = 0; i < s->object_count; i++)
                if (projective.wanted[i] && render_programs_draws(&projective.caster, pass, &s->objects[i]))
                    render_draw_object(f->gpu, p, i);
        }
        glEnable(GL_DEPTH_TEST);
        f->skips->counts->layers_rendered++;
        for (int i = 0; i < s->object_count; i++)
            t->drawn[i] = projective.wanted[i];
    } else {
        fprintf(stderr, "projective: light %d's %dx%d texture target is incomplete: the light unshadowed\n", l,
                t->size, t->size);
    }
    t->drawn_valid = complete;
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)target);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    return complete;
}

/* The light's clip space's x and y, -1 to 1, to the texture's 0 to 1,
 * before the division by w (column-major): the texture matrix of
 * eye-linear texture coordinates. */
static const mat4 projective_clip_to_texture = {{0.5f, 0, 0, 0}, {0, 0.5f, 0, 0}, {0, 0, 1, 0}, {0.5f, 0.5f, 0, 1}};

/* Stencil 1 on the textured receivers' visible pixels (depth equal to the
 * pre-pass's) where the projected image is black: `objects` are those
 * light l reaches. */
static void projective_mark(const technique_frame *f, const projective_light *t, const bool *objects) {
    const scene *s = f->gpu->scene;
    glClear(GL_STENCIL_BUFFER_BIT);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_EQUAL);
    render_program_use(&projective.receiver, f->view);
    mat4 texture;
    glm_mat4_mul((vec4 *)projective_clip_to_texture, (vec4 *)t->frustum.view_projection, texture);
    glUniformMatrix4fv(projective.light_texture, 1, GL_FALSE, (const float *)texture);
    glUniform4fv(projective.depth_plane, 1, t->frustum.depth_plane);
    glUniform1f(projective.nearest, t->frustum.nearest);
    glUniform1i(projective.cut, !projective.settings.no_near_cut);
    glUniform1i(projective.projected, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, t->texture);
    for (int i = 0; i < s->object_count; i++)
        if (render_in_mask(objects, i) && projective_is_textured(&s->objects[i]))
            render_draw_object(f->gpu, &projective.receiver, i);
    glBindTexture(GL_TEXTURE_2D, 0);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

/* Light l is blocked where the receiver pass marked 1. */
static const shading_stencil projective_lit = {
    .lit = GL_NOTEQUAL, .blocked = GL_EQUAL, .ref = 1, .mask = 0xff, .receivers_only = false};

static bool projective_init(const render_scene *gpu) {
    static const char *const caster_files[] = {"shadow_depth.vert", "projective_caster.frag"};
    static const char *const receiver_files[] = {"lit.vert", "projective_receiver.frag"};
    static const shader_define defines[] = {{"LIT_PROJECTED", 1}, SHADER_DEFINE(PROJECTIVE_LIT_PERCENT), {NULL, 0}};
    if (!render_programs_load(&projective.caster, gpu->scene, caster_files, 2, NULL) ||
        !render_program_load(&projective.receiver, receiver_files, 2, defines))
        return false;
    /* The casters' shape from the light (render.h). */
    projective.caster.solid.both_sides = projective.caster.cut_out.both_sides = true;
    unsigned id = projective.receiver.id;
    projective.light_texture = shader_uniform(id, "u_light_texture");
    projective.projected = shader_uniform(id, "u_projected");
    projective.depth_plane = shader_uniform(id, "u_depth_plane");
    projective.nearest = shader_uniform(id, "u_nearest");
    projective.cut = shader_uniform(id, "u_cut");
    int n = gpu->scene->object_count;
    /* The split the technique needs (see the top): a glTF scene's objects
     * all cast and receive. */
    bool any_textured = false;
    for (int i = 0; i < n; i++)
        any_textured |= projective_is_textured(&gpu->scene->objects[i]);
    if (!any_textured)
        fprintf(stderr, "projective: every receiver casts too, and takes no projected shadow without --self-shadow "
                        "on (key C): no shadows are drawn\n");
    projective.wanted = calloc((size_t)n + 1, sizeof *projective.wanted);
    projective.boxes = calloc((size_t)n + 1, sizeof *projective.boxes);
    projective.corners = calloc((size_t)n * 8 + 1, sizeof *projective.corners);
    bool ok = projective.wanted && projective.boxes && projective.corners;
    for (int l = 0; l < SCENE_MAX_LIGHTS && ok; l++) {
        projective.lights[l] = (projective_light){0};
        projective.lights[l].drawn = calloc((size_t)n + 1, sizeof *projective.lights[l].drawn);
        ok = projective.lights[l].drawn != NULL;
    }
    if (!ok)
        fprintf(stderr, "projective: out of memory\n");
    projective.clamped_warned = 0;
    return ok;
}

static void projective_destroy(void) {
    render_programs_destroy(&projective.caster);
    render_program_destroy(&projective.receiver);
    glDeleteFramebuffers(1, &projective.framebuffer);
    projective.framebuffer = 0;
    for (int l = 0; l < SCENE_MAX_LIGHTS; l++) {
        glDeleteTextures(1, &projective.lights[l].texture);
        free(projective.lights[l].drawn);
        projective.lights[l] = (projective_light){0};
    }
    free(projective.wanted);
    free(projective.boxes);
    free(projective.corners);
    projective.wanted = NULL;
    projective.boxes = NULL;
    projective.corners = NULL;
}

/* The frame: the casters' image from each light, projected onto the
 * receivers, then the light shaded where it was not black. */
static void projective_render(const technique_frame *f) {
    const scene *s = f->gpu->scene;
    int size = atoi(projective_sizes[projective.settings.texture_size]);
    /* 1. The camera's depth pre-pass: what is seen. */
    render_depth_prepass(f->gpu, f->view, f->skips->in_view);
    technique_see(f);
    for (int l = 0; l < s->light_count; l++) {
        if (!skips_light_on(f->skips, l))
            continue;
        projective_light *t = &projective.lights[l];
        /* 2. A frustum from the light fitted to its casters: a cone round
         * their bounding sphere, or a box along a directional light. */
        projective_fit(s, &s->lights[l], !projective.settings.no_receivers_cast, projective.corners, &t->frustum);
        if (t->frustum.clamped && !(projective.clamped_warned & SCENE_LIGHT_BIT(l)))
            fprintf(stderr,
                    "projective: light %d lies among its casters: a %g-degree frustum, casters beyond it cast "
                    "nothing\n",
                    l, (double)PROJECTIVE_FIT_MAX_HALF_ANGLE_DEG * 2);
        projective.clamped_warned |= t->frustum.clamped ? SCENE_LIGHT_BIT(l) : 0;
        /* 3. The casters black on white into the light's texture (those
         * the visible receivers' lookups may read; kept while nothing
         * moves). */
        bool drawn = false;
        if (t->frustum.fitted) {
            projective_prepare_texture(t, size);
            projective_plan_casters(f, l, t);
            drawn = projective_draw_texture(f, l, t);
        }
        /* 4. The texture projected onto the receivers the light reaches:
         * stencil 1 where it is black (and, with the near cut, beyond the
         * casters' nearest depth). */
        const bool *objects = shading_light_pass(f, l);
        if (drawn)
            projective_mark(f, t, objects);
        else
            glClear(GL_STENCIL_BUFFER_BIT);
        /* 5. The light shaded where nothing was marked, the first with
         * the ambient term. */
        shading_light(f, l, &projective_lit);
        glDisable(GL_STENCIL_TEST);
    }
    if (shading_ambient_light(f) < 0)
        shading_ambient(f);
}

static void projective_describe(char *out, size_t size) {
    const projective_light *t = &projective.lights[0];
    const char *self = projective.settings.no_receivers_cast ? "receivers cast nothing"
                       : projective.settings.self_shadow == PROJECTIVE_SELF_SHADOW_ON
                           ? "casters darken their own lit side"
                           : "casters show no shadow";
    if (!t->frustum.fitted)
        snprintf(out, size, "light 0: no caster; %s", self);
    else if (t->frustum.orthographic)
        snprintf(out, size, "light 0: %d texture, a box round the casters; %s", t->size, self);
    else
        snprintf(out, size, "light 0: %d texture, a %.3g-degree cone round the casters%s; %s", t->size,
                 (double)t->frustum.half_angle_deg * 2, t->frustum.clamped ? " (light among them: clamped)" : "",
                 self);
}

/* The fixes and limits each as the lecture shows it, and the texture's
 * size against its cost. */
static const char *const projective_bench_configs[] = {
    "",
    "--no-near-cut",
    "--self-shadow on",
    "--no-receivers-cast",
    "--texture-size 512",
    "--texture-size 1024",
    "--texture-size 4096",
};

const technique projective_technique = {
    .name = "projective",
    .title = "projective-texture shadows (Segal et al. 1992): the casters' image projected onto receivers",
    .params = projective_params,
    .param_count = (int)(sizeof projective_params / sizeof *projective_params),
    .bench_configs = projective_bench_configs,
    .bench_config_count = (int)(sizeof projective_bench_configs / sizeof *projective_bench_configs),
    .init = projective_init,
    .render = projective_render,
    .destroy = projective_destroy,
    .describe = projective_describe,
};
