/* render: a scene on the GPU and the drawing every technique shares.
 *
 * render_scene_create uploads each object's mesh (one VAO each: attribute
 * 0 position, 1 normal, 2 texture coordinates) and the scene's textures
 * (texture.h: every level as made there, sRGB, trilinear, wrapped),
 * creates the uniform block of lights that
 * shaders/lighting.glsl reads, and loads the depth pre-pass's program;
 * the "lit" programs (lit.vert, lit.frag: Lambert plus ambient with no
 * shadows, of a set of lights) are compiled per set on first use
 * (render_use_lit). render_scene_update_lights copies the scene's lights into the
 * block; the app calls it each frame, since the user can move lights.
 * With visibility_of = K >= 0 the block is in visibility mode for light K
 * (see lighting.glsl): the frame then shows the technique's visibility.
 *
 * Light groups. A shader holds SHADER_PASS_LIGHTS lights (its slots, one
 * by one: samplers take only constant indices), and a scene may have up to
 * SCENE_MAX_LIGHTS: light l is slot l % SHADER_PASS_LIGHTS of group
 * l / SHADER_PASS_LIGHTS, and each group has a block of its own, bound
 * for its passes (render_bind_light_group; render_use_lit binds its set's).
 * Only group 0's block holds the ambient term. A scene of one group is
 * shaded as if groups did not exist; past one, each group's pass adds its
 * lights to the first's (render_unshadowed, the shading passes).
 *
 * Techniques load their own programs with render_program_load, which finds
 * the uniforms every scene-drawing program has (u_model, u_normal_matrix,
 * u_albedo, u_base_color, u_view_projection; any may be absent), then draw
 * objects with render_draw_object, or render_draw_objects for those of a
 * mask. A program that shades (shaders/surface.glsl) reads each object's
 * base-colour texture on RENDER_BASE_COLOR_UNIT, where
 * render_draw_object binds it, or a white texel for an object without
 * one (its colour then exactly the object's).
 *
 * View culling, the first of the skips (a scene's cost should follow what
 * the camera sees): the frame's owner calls render_cull_view once per
 * frame, which marks in r->in_view the objects whose world box meets the
 * camera's frustum (every object when culling is off), and hands the mask
 * to the technique in its frame. Techniques cull their camera passes with
 * it and only those: a pass from a light's side or over the whole scene
 * needs objects the camera does not see. The test is conservative (an
 * object with a visible pixel is never culled), so culling changes no
 * pixel.
 *
 * State contract: the app binds the target, clears it to SCENE_BACKGROUND
 * (depth: the far end, stencil 0) and calls render_reset_state, then
 * depth_use_camera (depth.h), before each technique frame; a technique may
 * leave any state behind. Camera passes draw through the view's
 * raster_view_projection (render_program_use) and take their depth tests
 * and offsets from depth.h.
 */
#ifndef RENDER_H
#define RENDER_H

#include <stdbool.h>
#include <stdint.h>
#include "camera.h"
#include "scene.h"
#include "shader.h"

/* The texture unit of u_base_color. The units below it are the
 * techniques' (a shadow map's camera pass takes every one, with the
 * units above it for its soft lights: demos/lib/map_internal.h); GL 3.3
 * promises 16. */
#define RENDER_BASE_COLOR_UNIT 14

/* Single-sided objects (scene_object's single_sided): render_draw_object
 * culls their back faces, so that a camera's pass sees them from the
 * front only, as the reference's camera rays do; a program that draws a
 * shadow's shape instead (from a light, or projected onto a plane or the
 * near plane) sets both_sides after loading, since every object casts
 * from both sides. */
typedef struct render_program {
    unsigned id;
    int model, normal_matrix, albedo, base_color, base_alpha, alpha_cutoff, view_projection;
    bool both_sides;
} render_program;

/* Cut-out objects (scene_object's alpha_cutoff: glTF's alphaMode MASK)
 * have no surface where their alpha is below the cutoff. A pass whose
 * pixels are where a surface lies (the depth pre-pass, a shadow map's
 * depth, the dumps' geometry, a caster's shape) draws them through its
 * program's variant with SURFACE_CUT_OUT defined, which discards there
 * (shaders/surface.glsl); the passes with depth test GL_EQUAL after the
 * pre-pass need none. The variant is compiled only for a scene that has
 * cut-out objects, and draws only those: a shader that may discard tests
 * depth after it runs, not before, and no other object pays for it. */
typedef struct render_programs {
    render_program solid, cut_out; /* cut_out.id 0: the scene has no cut-out object */
} render_programs;

typedef struct render_mesh {
    unsigned vao, vertex_buffer, index_buffer;
    int index_count;
    float normal_matrix[3][3];
    float longest_edge; /* of its triangles, in world units (double, then rounded) */
} render_mesh;

/* Huge receivers: the rasterizer interpolates depth and every attribute
 * from a triangle's corners in float, so across a triangle far larger
 * than its distance from the eye what a pixel gets is off (a ground 1e5
 * across, two triangles, seen from 10 units: its depth 9e-5 of the
 * distance, 20 steps of the 24-bit buffer). An object is huge seen from
 * `eye` when its longest edge exceeds RENDER_HUGE_RATIO times the
 * distance from the eye to its world box (at least the near plane's);
 * what needs the exact surface there (the volumes' counting, the dumps'
 * positions) intersects the pixel's eye ray with the triangle's plane.
 * The ratio lies between the largest ground whose rasterized surface
 * still keeps the volumes within their bound and the smallest that does
 * not (test_volumes' test_huge_ground: with --no-exact-depth that ground
 * misclassifies over the bound), and above the standard scenes' largest,
 * long_view's, so none of those is huge. */
#define RENDER_HUGE_RATIO 1024.0

/* The groups of SHADER_PASS_LIGHTS a scene's lights can fill (see the
 * top). */
#define RENDER_LIGHT_GROUPS ((SCENE_MAX_LIGHTS + SHADER_PASS_LIGHTS - 1) / SHADER_PASS_LIGHTS)
#define RENDER_LIGHT_GROUP(l) ((l) / SHADER_PASS_LIGHTS)
#define RENDER_LIGHT_SLOT(l) ((l) % SHADER_PASS_LIGHTS)
/* The light in slot `slot` of group g: GROUP and SLOT undone. */
#define RENDER_GROUP_LIGHT(g, slot) ((g)*SHADER_PASS_LIGHTS + (slot))
/* Every set of a group's lights, as slot bits. */
#define RENDER_LIGHT_SETS (1u << SHADER_PASS_LIGHTS)

/* lit.frag's variants: plain, and with one light scaled by a soft
 * visibility sum (LIT_SOFT_VISIBILITY, soft_visibility.h). */
typedef enum render_lit_variant {
    RENDER_LIT_PLAIN,
    RENDER_LIT_SOFT_VISIBILITY,
    RENDER_LIT_VARIANTS
} render_lit_variant;

/* One lit program: a variant compiled for one set of lights. */
typedef struct render_lit_program {
    render_program program;
    int ambient; /* its u_ambient */
    /* RENDER_LIT_SOFT_VISIBILITY's u_soft_light, u_soft_visibility and
     * u_soft_scale (soft_visibility_use_lit); -1 in the plain one. */
    int soft_light, soft_visibility, soft_scale;
    bool loaded;
} render_lit_program;

/* The lit programs, each compiled on its first use. Each holds the lights
 * of its set fixed when it is compiled (LIT_LIGHTS), as the shadow maps'
 * camera pass does, rather than reading a list from uniforms: llvmpipe
 * then runs only those lights' code, with constant indices into the
 * lights' block, so the cost floor costs what the techniques' shading
 * costs with visibility 1. */
typedef struct render_lit_programs {
    render_lit_program programs[RENDER_LIT_VARIANTS][RENDER_LIGHT_SETS];
    bool failed; /* one failed to compile (said once): the frame fails (technique_render_frame) */
} render_lit_programs;

typedef struct render_scene {
    const scene *scene;
    render_mesh *meshes;            /* one per scene object */
    bool *in_view;                  /* one per scene object: render_cull_view's mask */
    bool *in_frustum;               /* one per scene object: its box meets the view, whatever the skips */
    bool *lit_by[SCENE_MAX_LIGHTS]; /* one per scene object: in view and in light l's reach (technique.h) */
    unsigned lights_buffers[RENDER_LIGHT_GROUPS]; /* each group's block; those the scene fills */
    unsigned *textures;                           /* one per scene texture (GL names) */
    unsigned white;                               /* the texture of an object without one: a white texel */
    render_lit_programs *lit;                     /* compiled on use, through a const render_scene too */
    render_programs depth;                        /* lit.vert with depth.frag: render_depth_prepass */
    bool inject_gl_error;                         /* test hook: see RENDER_INJECT_GL_ERROR_ENV */
} render_scene;

/* A test-only hook: with this variable set in the environment, every
 * render_draw_object also raises a GL error (GL_INVALID_ENUM), so that a
 * test can show that an error raised inside any technique's frame reaches
 * the frame's owner and fails the run (tests/test_cli.c). */
#define RENDER_INJECT_GL_ERROR_ENV "SHADOWS_TEST_INJECT_GL_ERROR"

/* The program-wide skips, each a toggle (--no-NAME) where zero means on;
 * no_skip (--no-skip) turns every one off. What each skips is in
 * technique.h (technique_frame); none changes a pixel. */
typedef struct render_skips {
    bool no_skip;
    bool no_view_cull;   /* --no-view-cull: camera passes draw objects outside the view */
    bool no_light_reach; /* --no-light-reach: lights that reach nothing visible still render */
    bool no_caster_cull; /* --no-caster-cull: every caster casts for every light */
    bool no_hidden_cull; /* --no-hidden-cull: casters and objects hidden behind the pre-pass's depth drawn */
    bool no_cache;       /* --no-cache: maps and volumes are made again every frame */
    bool no_marked_pass; /* --no-marked-pass: costly pixels shaded in the one pass with the others */
} render_skips;

bool render_object_huge(const render_scene *r, int object, const float eye[3]);
/* The uniforms of shaders/eye_ray.glsl in `program` (in use) for view v
 * and a framebuffer of width x height. */
void render_eye_ray_uniforms(unsigned program, const camera_view *v, int width, int height);

bool render_scene_create(render_scene *r, const scene *s);
void render_scene_update_lights(const render_scene *r, int visibility_of);
/* Light l's entries of its group's block as `as` has it, until the next
 * render_scene_update_lights: a light drawn where it was (a shadow map's
 * budget, demos/lib/map.h). */
void render_scene_light_as(const render_scene *r, int l, const scene_light *as);
void render_scene_destroy(render_scene *r);

/* files: count shader files; defines: NULL or the program's own C
 * constants (see shader.h). */
bool render_program_load(render_program *p, const char *const *files, int count, const shader_define *defines);
void render_program_destroy(render_program *p);
void render_program_use(const render_program *p, const camera_view *v);
/* The program of files with defines as p->solid, and for a scene with
 * cut-out objects (scene_has_cut_outs) its SURFACE_CUT_OUT variant as
 * p->cut_out. */
bool render_programs_load(render_programs *p, const scene *s, const char *const *files, int count,
                          const shader_define *defines);
void render_programs_destroy(render_programs *p);
/* A pass draws through p in passes: pass 0 the solid objects through
 * p->solid, and where there is a variant, pass 1 the cut-out ones through
 * it; at most RENDER_PROGRAMS_MAX_PASSES (for per-pass uniforms). */
#define RENDER_PROGRAMS_MAX_PASSES 2
int render_programs_passes(const render_programs *p);
const render_program *render_programs_pass(const render_programs *p, int pass);
/* Whether pass `pass` of p draws object o. */
bool render_programs_draws(const render_programs *p, int pass, const scene_object *o);
/* p NULL (a lit program that failed to compile, said once): nothing. */
void render_draw_object(const render_scene *r, const render_program *p, int object);
/* What render_draw_object sets before it draws object `object` through p
 * (in use), for a draw of the object's triangles laid out otherwise: its
 * uniforms, its base-colour texture, and back faces culled for a
 * single-sided object unless p draws both sides (returned: whether they
 * are); render_object_end after the draw undoes the culling. */
bool render_object_begin(const render_scene *r, const render_program *p, int object);
void render_object_end(const render_scene *r, bool culled);
/* Object i where mask is NULL or mask[i] holds. */
bool render_in_mask(const bool *mask, int object);
/* Every object in `mask` (NULL: all), in scene order. */
void render_draw_objects(const render_scene *r, const render_program *p, const bool *mask);
/* Those of them whose `receives` is as given: a shadow technique draws the
 * receivers with its shadow test and the others ("receives": false) lit,
 * as the reference sees them. */
void render_draw_objects_receiving(const render_scene *r, const render_program *p, const bool *mask, bool receives);

/* A skip is on unless its own flag (own_off: skips->no_NAME) or
 * --no-skip turned it off. */
bool render_skip_on(const render_skips *skips, bool own_off);
/* Fills r->in_frustum for the camera view v: true where the object's
 * world box meets v's frustum (frustum_box_outside, done once a frame for
 * every pass that asks); and r->in_view: the same, or everywhere when
 * culling is off. Returns how many objects are in the view mask. */
int render_cull_view(render_scene *r, const camera_view *v, const render_skips *skips);

/* How many light groups the scene's lights fill: at least one. */
int render_light_groups(const render_scene *r);
/* The lights of `lights` in group g, as slot bits. */
unsigned render_group_slots(scene_light_set lights, int g);
/* Binds group g's block of lights for the passes that follow. */
void render_bind_light_group(const render_scene *r, int g);
/* What the passes draw from here on adds to the target's colour
 * (GL_ONE, GL_ONE): a light's share to the picture so far, a sample's
 * visibility to the sum. */
void render_blend_add(void);
/* The passes of a pass's groups after its first add their light
 * (render_blend_add): on for g > 0 (the state *blending was, at g 0,
 * kept for render_group_pass_end). */
void render_group_pass_begin(int g, bool *blending);
void render_group_pass_end(bool blending);
/* Binds the lit program of `variant` for the set `lights`
 * (SCENE_LIGHT_BIT; those the scene has, all of one group) and its
 * group's block, with or without the ambient term, and returns it (its
 * program to draw with); NULL where it failed to compile, or after one
 * line on stderr where the set spans groups. */
const render_lit_program *render_use_lit_variant(const render_scene *r, render_lit_variant variant,
                                                 const camera_view *v, scene_light_set lights, bool ambient);
/* The plain one's program. */
const render_program *render_use_lit(const render_scene *r, const camera_view *v, scene_light_set lights,
                                     bool ambient);
/* The depth of the objects in `mask` (NULL: all), nothing else written:
 * the pre-pass after which every shading pass meets each visible pixel
 * once (GL_EQUAL), so a costly fragment stage (a shadow map's filter) runs
 * once per pixel, not once per overdrawn layer. The same vertex stage as
 * the lit program (lit.vert, invariant gl_Position), so the depths are
 * bit for bit those of any program on lit.vert. Leaves the depth test
 * GL_EQUAL with depth writes off. */
void render_depth_prepass(const render_scene *r, const camera_view *v, const bool *mask);
/* The scene lit by the set `lights`, nothing shadowed, under the depth
 * test as it is, with the ambient term; past one group, each group's
 * pass after the first adds its lights: the cost floor's lit pass after
 * its pre-pass, which
 * skips as the techniques' camera passes do (mask: the frame's in_view,
 * NULL: all; lights: those that reach the view), so that ratios to it
 * measure shadows, not culling. */
void render_unshadowed(const render_scene *r, const camera_view *v, const bool *mask, scene_light_set lights);
void render_reset_state(void);

#endif
