/* planar: planar projected shadows.
 *
 * Blinn, "Me and My (Fake) Shadow", IEEE CG&A 8(1), 1988: every caster is
 * drawn a second time, squashed onto the receiver plane P by the shadow
 * matrix S = (P.L) I - L P^T, which sends each point v to where the line
 * from the light L (homogeneous: w = 1 point, w = 0 directional) through v
 * meets the plane. Only planar receivers (mesh "plane", receives) get
 * shadows; that is the technique's limit.
 *
 * For each light and receiver plane, three fixes, each a toggle so that a
 * lecture can show the artifact it prevents:
 *   stencil  the visible receiver pixels are marked 1; the projected
 *            casters turn marked pixels into 2, each pixel once however many
 *            projected triangles cover it; the light is then shaded
 *            (after a depth pre-pass, the first light with the ambient
 *            term) only where the stencil is not 2, so a shadowed pixel
 *            is exactly the picture without that light.
 *            Off: casters are blended dark straight into the picture, and
 *            overlapping triangles darken twice and spill past the
 *            receiver's edges.
 *   offset   the projected casters are coplanar with the receiver, so a
 *            depth test between them is a coin toss. With the stencil they
 *            need none: they are drawn with the depth test off, confined
 *            by the stencil to the receiver's visible pixels, which the
 *            receiver's own depth-equal pass marked; so the precision of
 *            the receiver's interpolated depth cannot matter (a ground of
 *            1e5 units, two giant triangles, would otherwise lose every
 *            shadow), and a caster between the receiver and the eye is
 *            not shadowed by its own flattened copy, which lies on the
 *            plane and only marks receiver pixels. Without the stencil,
 *            polygon offset pulls them towards the eye. Off: they are
 *            depth-tested as they are, and z-fight with the receiver.
 *   reject   the plane is oriented towards the light and clip distances
 *            drop what is below it or beyond the light; a caster with no
 *            part on the light's side of the plane is left out: one lying
 *            in it (a mat on the floor) is its own shadow, and one beyond
 *            it that touches it (a box on the ground, lit from below)
 *            would keep its faces in the plane, which clipping cannot
 *            drop, and darken the receiver's pixels under them, which the
 *            light reaches. Off: a light below the plane or a caster above
 *            the light casts anti-shadows.
 * An area light (--light-samples N) is N hard lights at its points
 * (Heckbert & Herf, "Simulating soft shadows with graphics hardware",
 * 1997): each marks the stencil as above and adds one to the light's sum
 * where it reaches, and the light is shaded once with the sum over N
 * (soft_visibility.h), in the window over frames
 * (shading_sample_area_light).
 */
#include <GLFW/glfw3.h>
#include <glad/gl.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "context.h"
#include "depth.h"
#include "frustum.h"
#include "planar.h"
#include "shading.h"
#include "technique.h"

/* Factor (slope) and units (depth-buffer steps) towards the eye: one step
 * is the smallest difference a 24-bit depth buffer resolves, and the
 * slope term covers receivers seen at grazing angles. */
#define PLANAR_OFFSET_FACTOR -1.0f
#define PLANAR_OFFSET_UNITS -2.0f
/* A caster's corner lies in a receiver's plane when it is within this
 * many float roundings of the plane, relative to the magnitudes the
 * distance is made of (the corner's coordinates and the plane's offset):
 * the model matrix and the plane round a few times each, and anything that
 * close to the plane z-fights with it in the picture. */
#define PLANAR_COPLANAR_ROUNDINGS 64.0f

static struct {
    planar_settings settings;
    render_programs flatten; /* solid casters, and cut-out ones through their variant (render.h) */
    struct {
        int shadow, plane, reject;
    } flatten_uniforms[RENDER_PROGRAMS_MAX_PASSES];
    bool *casters;               /* per object: it casts for the light at hand (caster culling) */
    soft_visibility soft;        /* an area light's visibility, sampled */
    scene_light_set soft_warned; /* bit l: light l's area said drawn hard */
} planar;

static const flags_param planar_params[] = {
    {"stencil", "shadows blend twice where projected triangles overlap and spill off the receiver", GLFW_KEY_S,
     FLAGS_TOGGLE, .disabled = &planar.settings.no_stencil},
    {"offset", "projected shadows z-fight with the receiver", GLFW_KEY_O, FLAGS_TOGGLE,
     .disabled = &planar.settings.no_offset},
    {"reject", "lights below the plane and casters beyond the light cast anti-shadows", GLFW_KEY_R, FLAGS_TOGGLE,
     .disabled = &planar.settings.no_reject},
    {"light-samples",
     "points of each area light, each a hard shadow, averaged (Heckbert & Herf 1997); 1: hard, from its centre",
     GLFW_KEY_L, FLAGS_CHOICE, .index = &planar.settings.light_samples, .choices = soft_visibility_sample_counts},
};

void planar_receiver_plane(const scene_object *o, float plane[4]) {
    vec3 normal = {0, 1, 0}, origin;
    mat3 normal_matrix;
    scene_object_normal_matrix(o, normal_matrix);
    glm_mat3_mulv(normal_matrix, normal, normal);
    glm_vec3_normalize(normal);
    glm_vec3_copy((float *)o->model[3], origin);
    glm_vec4(normal, -glm_vec3_dot(normal, origin), plane);
}

bool planar_casts_nothing(const scene_object *o, const float plane[4]) {
    float corners[8][3];
    frustum_box_corners(o->mesh.bounds_min, o->mesh.bounds_max, corners);
    for (int c = 0; c < 8; c++) {
        vec3 world;
        glm_mat4_mulv3((vec4 *)o->model, corners[c], 1.0f, world);
        float magnitude = fabsf(world[0]) + fabsf(world[1]) + fabsf(world[2]) + fabsf(plane[3]);
        float distance = glm_vec3_dot((float *)plane, world) + plane[3];
        if (distance > PLANAR_COPLANAR_ROUNDINGS * FLT_EPSILON * magnitude)
            return false;
    }
    return true;
}

static bool planar_init(const render_scene *gpu) {
    static const char *const files[] = {"planar_shadow.vert", "planar_shadow.frag"};
    if (!render_programs_load(&planar.flatten, gpu->scene, files, 2, NULL))
        return false;
    /* The casters' shape on a plane (render.h). */
    planar.flatten.solid.both_sides = planar.flatten.cut_out.both_sides = true;
    for (int pass = 0; pass < render_programs_passes(&planar.flatten); pass++) {
        unsigned id = render_programs_pass(&planar.flatten, pass)->id;
        planar.flatten_uniforms[pass].shadow = shader_uniform(id, "u_shadow");
        planar.flatten_uniforms[pass].plane = shader_uniform(id, "u_plane");
        planar.flatten_uniforms[pass].reject = shader_uniform(id, "u_reject");
    }
    /* Shadows land on planes only (a glTF scene's ground is a mesh). */
    bool any_plane = false;
    for (int i = 0; i < gpu->scene->object_count; i++)
        any_plane |= gpu->scene->objects[i].receives && gpu->scene->objects[i].mesh_kind == SCENE_MESH_PLANE;
    if (!any_plane)
        fprintf(stderr, "planar: no object is a receiving plane (mesh \"plane\" of a scene file): no shadows are "
                        "drawn\n");
    planar.casters = malloc((size_t)gpu->scene->object_count * sizeof *planar.casters);
    if (!planar.casters) {
        fprintf(stderr, "planar: out of memory\n");
        return false;
    }
    planar.soft_warned = 0;
    return soft_visibility_init(&planar.soft);
}

static void planar_destroy(void) {
    soft_visibility_destroy(&planar.soft);
    render_programs_destroy(&planar.flatten);
    free(planar.casters);
    planar.casters = NULL;
}

/* The casters flattened onto the receiver's plane. `stenciled`: the
 * stencil confines them to the receiver's visible pixels, so they need
 * no depth test (see "offset" above). */
static void planar_draw_casters(const technique_frame *f, int receiver, const float plane[4], const float light[4],
                                bool stenciled) {
    const scene *s = f->gpu->scene;
    mat4 shadow;
    frustum_plane_projection(plane, light, shadow);
    /* Without clip distances the shaders discard instead (shader.h). */
    bool clip = context_current_features()->clip_distances;
    if (clip) {
        glEnable(GL_CLIP_DISTANCE0);
        glEnable(GL_CLIP_DISTANCE1);
    }
    if (planar.settings.no_offset) {
        glDepthFunc(depth_func(f->view, GL_LESS)); /* the artifact: a coin toss against the receiver */
    } else if (stenciled) {
        glDepthFunc(GL_ALWAYS);
    } else {
        glEnable(GL_POLYGON_OFFSET_FILL);
        depth_polygon_offset(f->view, PLANAR_OFFSET_FACTOR, PLANAR_OFFSET_UNITS);
    }
    glDepthMask(GL_FALSE);
    /* Not only casters in view: one outside the view may shadow a
     * receiver inside it; planar.casters are those that may. A cut-out
     * caster's program discards where it has no surface. */
    for (int pass = 0; pass < render_programs_passes(&planar.flatten); pass++) {
        const render_program *p = render_programs_pass(&planar.flatten, pass);
        render_program_use(p, f->view);
        glUniformMatrix4fv(planar.flatten_uniforms[pass].shadow, 1, GL_FALSE, (const float *)shadow);
        glUniform4fv(planar.flatten_uniforms[pass].plane, 1, plane);
        glUniform1i(planar.flatten_uniforms[pass].reject, !planar.settings.no_reject);
        for (int i = 0; i < s->object_count; i++)
            if (i != receiver && planar.casters[i] && render_programs_draws(&planar.flatten, pass, &s->objects[i]) &&
                (planar.settings.no_reject || !planar_casts_nothing(&s->objects[i], plane)))
                render_draw_object(f->gpu, p, i);
    }
    if (clip) {
        glDisable(GL_CLIP_DISTANCE0);
        glDisable(GL_CLIP_DISTANCE1);
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDepthFunc(depth_func(f->view, GL_LESS));
}

/* The plane of receiver r as the shadow matrix needs it for this light;
 * false when nothing is to be drawn. */
static bool planar_receiver_facing(const scene_object *o, const float light_h[4], float plane[4]) {
    if (!o->receives || o->mesh_kind != SCENE_MESH_PLANE)
        return false;
    planar_receiver_plane(o, plane);
    float facing = glm_vec4_dot(plane, (float *)light_h);
    if (!planar.settings.no_reject && facing < 0) {
        glm_vec4_negate(plane);
        facing = -facing;
    }
    return facing != 0; /* light in the plane: S is singular, the plane unlit */
}

/* Receiver r's visible pixels (depth equal to the pre-pass's) through
 * the stencil function and depth-pass operation given. */
static void planar_stencil_receiver(const technique_frame *f, int r, GLenum func, GLenum op) {
    glStencilFunc(func, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, op);
    glDepthFunc(GL_EQUAL);
    /* A receiver is a plane of the scene file's: never cut out. */
    render_program_use(&f->gpu->depth.solid, f->view);
    render_draw_object(f->gpu, &f->gpu->depth.solid, r);
}

/* Stencil 2 where light l is blocked: each visible receiver pixel is
 * marked 1, and projected casters turn a 1 into a 2 once, however many of
 * their triangles cover it. The receiver's pixels left at 1 are then
 * cleared, so that only the next receiver's pixels are 1 when casters are
 * flattened onto its plane: they are not depth-tested, and would shadow
 * any pixel left at 1 that their projection covers. */
static void planar_mark_shadows(const technique_frame *f, int light, int k, const float light_h[4]) {
    const scene *s = f->gpu->scene;
    /* Stencil marks only the visible receivers' pixels, so a caster whose
     * shadow reaches none of them marks nothing: culling it is exact (by
     * the hull of the point at hand, for a point of an area light). */
    skips_hull hull;
    if (k == SHADING_LIGHT_CENTRE)
        skips_light_hull(f->skips, light, &hull);
    else
        skips_point_hull(f->skips, light, light_h, &hull);
    for (int i = 0; i < s->object_count; i++)
        planar.casters[i] = skips_caster_needed(f->skips, &hull, i);
    glClear(GL_STENCIL_BUFFER_BIT);
    glEnable(GL_STENCIL_TEST);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);
    for (int r = 0; r < s->object_count; r++) {
        float plane[4];
        if (!planar_receiver_facing(&s->objects[r], light_h, plane))
            continue;
        planar_stencil_receiver(f, r, GL_ALWAYS, GL_REPLACE);
        glStencilFunc(GL_EQUAL, 1, 0xff);
        glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
        planar_draw_casters(f, r, plane, light_h, true);
        planar_stencil_receiver(f, r, GL_EQUAL, GL_ZERO);
    }
    glDepthFunc(depth_func(f->view, GL_LESS));
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

/* Light l is blocked where its stencil is 2, on any object (only
 * receivers are ever marked). */
static const shading_stencil planar_lit = {
    .lit = GL_NOTEQUAL, .blocked = GL_EQUAL, .ref = 2, .mask = 0xff, .receivers_only = false};

/* After a depth pre-pass, each light shaded where the stencil does not
 * mark it blocked, the first with the ambient term (shading_light).
 * Adding non-negative terms clamps to the same 8-bit value in any order,
 * so a shadowed pixel is exactly the picture without that light, however
 * bright the other lights make it. */
static void planar_render_stencil(const technique_frame *f) {
    const scene *s = f->gpu->scene;
    render_depth_prepass(f->gpu, f->view, f->skips->in_view);
    /* A caster's anti-shadow (reject off) lies nearer the light than the
     * caster: the masks of what is seen bound true shadows only. */
    if (!planar.settings.no_reject)
        technique_see(f);
    for (int l = 0; l < s->light_count; l++) {
        if (!skips_light_on(f->skips, l))
            continue;
        float light_h[4];
        scene_light_homogeneous(&s->lights[l], light_h);
        /* Marks only where the light reaches: outside its rectangle the
         * stencil stays as cleared, since the ambient light, the only
         * one shaded outside its rectangle, marks first. */
        shading_light_pass(f, l);
        int samples =
            soft_visibility_samples("planar", planar.settings.light_samples, &s->lights[l], l, &planar.soft_warned);
        if (samples > 1) {
            /* An area light: each point's shadows marked as a hard
             * light's, one added to its sum where the point reaches. */
            if (shading_sample_area_light(f, l, samples, &planar.soft, &planar_lit, planar_mark_shadows))
                shading_light_soft(f, l, &planar.soft, planar_lit.receivers_only);
            continue;
        }
        planar_mark_shadows(f, l, SHADING_LIGHT_CENTRE, light_h);
        shading_light(f, l, &planar_lit);
        glDisable(GL_STENCIL_TEST);
    }
    if (shading_ambient_light(f) < 0)
        shading_ambient(f);
}

/* The textbook path the stencil fixes: the lit picture darkened by
 * blending, once per layer of projected triangles (a closed caster's
 * front and back triangles are two layers everywhere; where two casters'
 * shadows or a caster's own folds overlap, four). Its shadows spill off
 * the receivers onto the whole plane, so every caster draws (no caster
 * culling: it would change that picture), and the counts say so. */
static void planar_render_blended(const technique_frame *f) {
    const scene *s = f->gpu->scene;
    render_unshadowed(f->gpu, f->view, f->skips->in_view, f->skips->lights);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ZERO, GL_SRC_COLOR);
    int caster_count = 0;
    for (int i = 0; i < s->object_count; i++) {
        planar.casters[i] = s->objects[i].casts;
        caster_count += planar.casters[i];
    }
    for (int l = 0; l < s->light_count; l++) {
        if (!skips_light_on(f->skips, l))
            continue;
        f->skips->counts->casters_drawn[l] += caster_count;
        float light_h[4];
        scene_light_homogeneous(&s->lights[l], light_h);
        for (int r = 0; r < s->object_count; r++) {
            float plane[4];
            if (planar_receiver_facing(&s->objects[r], light_h, plane))
                planar_draw_casters(f, r, plane, light_h, false);
        }
    }
    glDisable(GL_BLEND);
}

/* The fixes cost little; the sweep shows what each one buys in accuracy,
 * and an area light's points their convergence to the truth. */
static const char *const planar_bench_configs[] = {"",
                                                   "--no-offset",
                                                   "--no-stencil",
                                                   "--no-reject",
                                                   "--light-samples 4",
                                                   "--light-samples 16",
                                                   "--light-samples 64",
                                                   "--light-samples 256"};

static void planar_render(const technique_frame *f) {
    if (planar.settings.no_stencil)
        planar_render_blended(f);
    else
        planar_render_stencil(f);
}

static const char *planar_area_light(const scene_light *light, int l) {
    (void)light;
    return soft_visibility_area_light_text(&planar.soft, planar.settings.light_samples, l);
}

const technique planar_technique = {
    .name = "planar",
    .title = "planar projected shadows (Blinn 1988) with stencil",
    .params = planar_params,
    .param_count = (int)(sizeof planar_params / sizeof *planar_params),
    .bench_configs = planar_bench_configs,
    .bench_config_count = (int)(sizeof planar_bench_configs / sizeof *planar_bench_configs),
    .init = planar_init,
    .render = planar_render,
    .destroy = planar_destroy,
    .area_light = planar_area_light,
};
