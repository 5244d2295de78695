#include "render.h"

#include <glad/gl.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "context.h"
#include "frustum.h"
#include "shader.h"

#define RENDER_NOT_A_CAPABILITY 0 /* glEnable(0): GL_INVALID_ENUM, for the test hook */

/* std140 mirror of the Lights block in shaders/lighting.glsl: one light
 * group's. */
typedef struct render_lights_block {
    float ambient[4];
    int count[4];
    float position[SHADER_PASS_LIGHTS][4];
    float direction[SHADER_PASS_LIGHTS][4];
    float color[SHADER_PASS_LIGHTS][4];
    float reach[SHADER_PASS_LIGHTS][4];
} render_lights_block;

/* std140: a vec4 or ivec4 and each element of an array of them take 16
 * bytes, members follow in order. */
#define RENDER_STD140_VEC4 16
_Static_assert(offsetof(render_lights_block, ambient) == 0, "Lights.lights_ambient");
_Static_assert(offsetof(render_lights_block, count) == RENDER_STD140_VEC4, "Lights.lights_count");
_Static_assert(offsetof(render_lights_block, position) == 2 * RENDER_STD140_VEC4, "Lights.lights_position");
_Static_assert(offsetof(render_lights_block, direction) == (2 + SHADER_PASS_LIGHTS) * RENDER_STD140_VEC4,
               "Lights.lights_direction");
_Static_assert(offsetof(render_lights_block, color) == (2 + 2 * SHADER_PASS_LIGHTS) * RENDER_STD140_VEC4,
               "Lights.lights_color");
_Static_assert(offsetof(render_lights_block, reach) == (2 + 3 * SHADER_PASS_LIGHTS) * RENDER_STD140_VEC4,
               "Lights.lights_reach");
_Static_assert(sizeof(render_lights_block) == (2 + 4 * SHADER_PASS_LIGHTS) * RENDER_STD140_VEC4, "Lights size");

bool render_program_load(render_program *p, const char *const *files, int count, const shader_define *defines) {
    *p = (render_program){.id = shader_load_program(files, count, defines)};
    if (!p->id)
        return false;
    /* The uniforms render_draw_object sets, each where the program has it
     * (a depth program has no albedo, an overlay no model). */
    p->model = shader_uniform_optional(p->id, "u_model");
    p->normal_matrix = shader_uniform_optional(p->id, "u_normal_matrix");
    p->albedo = shader_uniform_optional(p->id, "u_albedo");
    p->base_color = shader_uniform_optional(p->id, "u_base_color");
    p->base_alpha = shader_uniform_optional(p->id, "u_base_alpha");
    p->alpha_cutoff = shader_uniform_optional(p->id, "u_alpha_cutoff");
    p->view_projection = shader_uniform_optional(p->id, "u_view_projection");
    return true;
}

void render_program_destroy(render_program *p) {
    shader_delete_program(p->id);
    *p = (render_program){0};
}

bool render_programs_load(render_programs *p, const scene *s, const char *const *files, int count,
                          const shader_define *defines) {
    *p = (render_programs){0};
    if (!render_program_load(&p->solid, files, count, defines))
        return false;
    if (!scene_has_cut_outs(s))
        return true;
    /* The defines given, then SURFACE_CUT_OUT. */
    int n = 0;
    while (defines && defines[n].name)
        n++;
    shader_define *all = calloc((size_t)n + 2, sizeof *all);
    if (!all) {
        fprintf(stderr, "render: out of memory\n");
        render_program_destroy(&p->solid);
        return false;
    }
    if (n)
        memcpy(all, defines, (size_t)n * sizeof *all);
    all[n] = (shader_define){"SURFACE_CUT_OUT", 1};
    bool loaded = render_program_load(&p->cut_out, files, count, all);
    free(all);
    if (!loaded)
        render_program_destroy(&p->solid);
    return loaded;
}

void render_programs_destroy(render_programs *p) {
    render_program_destroy(&p->solid);
    render_program_destroy(&p->cut_out);
}

int render_programs_passes(const render_programs *p) { return p->cut_out.id ? 2 : 1; }

const render_program *render_programs_pass(const render_programs *p, int pass) {
    return pass ? &p->cut_out : &p->solid;
}

bool render_programs_draws(const render_programs *p, int pass, const scene_object *o) {
    return !p->cut_out.id || (o->alpha_cutoff > 0) == (pass == 1);
}

void render_program_use(const render_program *p, const camera_view *v) {
    glUseProgram(p->id);
    glUniformMatrix4fv(p->view_projection, 1, GL_FALSE, (const float *)v->raster_view_projection);
}

bool render_object_begin(const render_scene *r, const render_program *p, int object) {
    const scene_object *o = &r->scene->objects[object];
    glUniformMatrix4fv(p->model, 1, GL_FALSE, (const float *)o->model);
    glUniformMatrix3fv(p->normal_matrix, 1, GL_FALSE, (const float *)r->meshes[object].normal_matrix);
    glUniform3fv(p->albedo, 1, o->color);
    glUniform1f(p->base_alpha, o->base_alpha);
    glUniform1f(p->alpha_cutoff, o->alpha_cutoff);
    if (p->base_color >= 0) {
        glUniform1i(p->base_color, RENDER_BASE_COLOR_UNIT);
        glActiveTexture(GL_TEXTURE0 + RENDER_BASE_COLOR_UNIT);
        glBindTexture(GL_TEXTURE_2D, o->base_color ? r->textures[o->base_color - r->scene->textures] : r->white);
        glActiveTexture(GL_TEXTURE0);
    }
    bool cull = o->single_sided && !p->both_sides;
    if (cull) {
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
    }
    return cull;
}

void render_object_end(const render_scene *r, bool culled) {
    if (culled)
        glDisable(GL_CULL_FACE);
    if (r->inject_gl_error)
        glEnable(RENDER_NOT_A_CAPABILITY);
}

void render_draw_object(const render_scene *r, const render_program *p, int object) {
    if (!p)
        return;
    bool culled = render_object_begin(r, p, object);
    glBindVertexArray(r->meshes[object].vao);
    glDrawElements(GL_TRIANGLES, r->meshes[object].index_count, GL_UNSIGNED_INT, NULL);
    render_object_end(r, culled);
}

bool render_in_mask(const bool *mask, int object) { return !mask || mask[object]; }

void render_draw_objects(const render_scene *r, const render_program *p, const bool *mask) {
    for (int i = 0; i < r->scene->object_count; i++)
        if (render_in_mask(mask, i))
            render_draw_object(r, p, i);
}

void render_draw_objects_receiving(const render_scene *r, const render_program *p, const bool *mask, bool receives) {
    for (int i = 0; i < r->scene->object_count; i++)
        if (render_in_mask(mask, i) && r->scene->objects[i].receives == receives)
            render_draw_object(r, p, i);
}

bool render_skip_on(const render_skips *skips, bool own_off) { return !skips->no_skip && !own_off; }

int render_cull_view(render_scene *r, const camera_view *v, const render_skips *skips) {
    bool cull = render_skip_on(skips, skips->no_view_cull);
    int count = 0;
    for (int i = 0; i < r->scene->object_count; i++) {
        float lo[3], hi[3];
        scene_object_world_bounds(&r->scene->objects[i], lo, hi);
        r->in_frustum[i] = !frustum_box_outside(v->view_projection, lo, hi);
        r->in_view[i] = !cull || r->in_frustum[i];
        count += r->in_view[i];
    }
    return count;
}

static float render_longest_edge(const scene_object *o) {
    double longest = 0;
    for (uint32_t t = 0; t < o->mesh.index_count / 3; t++) {
        double v[3][3];
        for (int k = 0; k < 3; k++)
            scene_object_world_corner(o, t, k, v[k]);
        for (int k = 0; k < 3; k++) {
            const double *a = v[k], *b = v[(k + 1) % 3];
            longest = fmax(longest, sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                                         (a[2] - b[2]) * (a[2] - b[2])));
        }
    }
    return (float)longest;
}

bool render_object_huge(const render_scene *r, int object, const float eye[3]) {
    float lo[3], hi[3];
    scene_object_world_bounds(&r->scene->objects[object], lo, hi);
    double squared = 0;
    for (int c = 0; c < 3; c++) {
        double outside = fmax(fmax((double)lo[c] - eye[c], (double)eye[c] - hi[c]), 0);
        squared += outside * outside;
    }
    double reach = RENDER_HUGE_RATIO * fmax(sqrt(squared), r->scene->camera.near_plane);
    return r->meshes[object].longest_edge > reach;
}

void render_eye_ray_uniforms(unsigned program, const camera_view *v, int width, int height) {
    float rotation[3][3];
    for (int c = 0; c < 3; c++)
        for (int row = 0; row < 3; row++)
            rotation[c][row] = v->view[c][row];
    glUniformMatrix3fv(shader_uniform(program, "u_view_rotation"), 1, GL_FALSE, (const float *)rotation);
    glUniform4f(shader_uniform(program, "u_ray"), 1 / v->projection[0][0], 1 / v->projection[1][1],
                v->projection[2][0], v->projection[2][1]);
    glUniform4f(shader_uniform(program, "u_viewport"), 0, 0, (float)width, (float)height);
}

static void render_mesh_upload(render_mesh *g, const scene_object *o) {
    const mesh *m = &o->mesh;
    glGenVertexArrays(1, &g->vao);
    glBindVertexArray(g->vao);
    glGenBuffers(1, &g->vertex_buffer);
    glBindBuffer(GL_ARRAY_BUFFER, g->vertex_buffer);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(m->vertex_count * sizeof *m->vertices), m->vertices, GL_STATIC_DRAW);
    glGenBuffers(1, &g->index_buffer);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g->index_buffer);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(m->index_count * sizeof *m->indices), m->indices,
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(mesh_vertex), (void *)offsetof(mesh_vertex, position));
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(mesh_vertex), (void *)offsetof(mesh_vertex, normal));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, sizeof(mesh_vertex), (void *)offsetof(mesh_vertex, uv));
    glBindVertexArray(0);
    g->index_count = (int)m->index_count;
    scene_object_normal_matrix(o, g->normal_matrix);
    g->longest_edge = render_longest_edge(o);
}

/* Texture t's levels, as texture.h made them, sampled as it samples. */
static void render_texture_upload(unsigned name, const texture *t) {
    glBindTexture(GL_TEXTURE_2D, name);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int l = 0; l < t->level_count; l++)
        glTexImage2D(GL_TEXTURE_2D, l, GL_SRGB8_ALPHA8, t->levels[l].width, t->levels[l].height, 0, GL_RGBA,
                     GL_UNSIGNED_BYTE, t->levels[l].rgba);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, t->level_count - 1);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    static const GLint wraps[] = {[TEXTURE_REPEAT] = GL_REPEAT,
                                  [TEXTURE_MIRRORED_REPEAT] = GL_MIRRORED_REPEAT,
                                  [TEXTURE_CLAMP_TO_EDGE] = GL_CLAMP_TO_EDGE};
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wraps[t->wrap[0]]);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wraps[t->wrap[1]]);
}

/* The scene's textures and the white texel; false when out of memory. */
static bool render_textures_create(render_scene *r) {
    const scene *s = r->scene;
    r->textures = calloc((size_t)s->texture_count + 1, sizeof *r->textures);
    if (!r->textures)
        return false;
    glGenTextures(s->texture_count, r->textures);
    for (int t = 0; t < s->texture_count; t++)
        render_texture_upload(r->textures[t], &s->textures[t]);
    /* Nearest, one level: exactly 1 in every channel, so that the colour
     * of an object without a texture is its own to the bit. */
    static const unsigned char white[4] = {255, 255, 255, 255};
    glGenTextures(1, &r->white);
    glBindTexture(GL_TEXTURE_2D, r->white);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_SRGB8_ALPHA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, white);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, 0);
    return true;
}

bool render_scene_create(render_scene *r, const scene *s) {
    *r = (render_scene){.scene = s, .inject_gl_error = getenv(RENDER_INJECT_GL_ERROR_ENV) != NULL};
    r->meshes = calloc((size_t)s->object_count, sizeof *r->meshes);
    /* One block: in_view, in_frustum, then each light's lit_by. */
    r->in_view = malloc((size_t)s->object_count * (2 + SCENE_MAX_LIGHTS) * sizeof *r->in_view);
    r->in_frustum = r->in_view ? r->in_view + s->object_count : NULL;
    for (int l = 0; r->in_view && l < SCENE_MAX_LIGHTS; l++)
        r->lit_by[l] = r->in_view + (size_t)s->object_count * (size_t)(2 + l);
    if (!r->meshes || !r->in_view || !render_textures_create(r)) {
        free(r->meshes);
        free(r->in_view);
        fprintf(stderr, "render: out of memory\n");
        return false;
    }
    for (int i = 0; i < s->object_count; i++)
        render_mesh_upload(&r->meshes[i], &s->objects[i]);
    glGenBuffers(render_light_groups(r), r->lights_buffers);
    for (int g = 0; g < render_light_groups(r); g++) {
        glBindBuffer(GL_UNIFORM_BUFFER, r->lights_buffers[g]);
        glBufferData(GL_UNIFORM_BUFFER, sizeof(render_lights_block), NULL, GL_DYNAMIC_DRAW);
    }
    render_bind_light_group(r, 0);
    render_scene_update_lights(r, -1);
    static const char *const depth_files[] = {"lit.vert", "depth.frag"};
    r->lit = calloc(1, sizeof *r->lit);
    if (!r->lit || !render_programs_load(&r->depth, s, depth_files, 2, NULL)) {
        if (!r->lit)
            fprintf(stderr, "render: out of memory\n");
        render_scene_destroy(r);
        return false;
    }
    return context_gl_ok("render_scene_create");
}

int render_light_groups(const render_scene *r) {
    int count = r->scene->light_count;
    return count > 0 ? RENDER_LIGHT_GROUP(count - 1) + 1 : 1;
}

unsigned render_group_slots(scene_light_set lights, int g) {
    return (unsigned)(lights >> (g * SHADER_PASS_LIGHTS)) & (RENDER_LIGHT_SETS - 1);
}

/* The lights of group g's slot bits: render_group_slots undone. */
static scene_light_set render_group_lights(unsigned slots, int g) {
    return (scene_light_set)slots << (g * SHADER_PASS_LIGHTS);
}

void render_bind_light_group(const render_scene *r, int g) {
    glBindBufferBase(GL_UNIFORM_BUFFER, SHADER_LIGHTS_BINDING, r->lights_buffers[g]);
}

void render_blend_add(void) {
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
}

void render_group_pass_begin(int g, bool *blending) {
    if (g == 0) {
        *blending = glIsEnabled(GL_BLEND);
        return;
    }
    render_blend_add();
}

void render_group_pass_end(bool blending) {
    if (!blending)
        glDisable(GL_BLEND);
}

/* Light l's entries of the block: slot i's. */
static void render_light_entries(const scene_light *l, render_lights_block *b, int i) {
    scene_light_homogeneous(l, b->position[i]);
    glm_vec3_copy((float *)l->direction, b->direction[i]);
    glm_vec3_scale((float *)l->color, l->intensity, b->color[i]);
    bool spot = l->type == SCENE_LIGHT_SPOT;
    /* Outside any cone: smoothstep(-3, -2, cos) is 1 for every angle. */
    b->reach[i][0] = spot ? cosf(glm_rad(l->outer_angle_deg)) : -3.0f;
    b->reach[i][1] = spot ? cosf(glm_rad(l->inner_angle_deg)) : -2.0f;
    b->reach[i][2] = l->type == SCENE_LIGHT_DIRECTIONAL ? 0 : l->range;
}

/* Group g's block: its lights in their slots, the ambient term in group
 * 0's alone, and visibility mode's light as its slot here (past the
 * slots where it is another group's: then nothing here adds). */
static void render_update_group(const render_scene *r, int g, int visibility_of) {
    const scene *s = r->scene;
    int first = RENDER_GROUP_LIGHT(g, 0), count = s->light_count - first;
    count = count < SHADER_PASS_LIGHTS ? count : SHADER_PASS_LIGHTS;
    int visible = visibility_of < 0                        ? -1
                  : RENDER_LIGHT_GROUP(visibility_of) == g ? RENDER_LIGHT_SLOT(visibility_of)
                                                           : SHADER_PASS_LIGHTS;
    render_lights_block b = {.count = {count, visible}};
    if (g == 0)
        glm_vec3_copy((float *)s->ambient, b.ambient);
    for (int i = 0; i < count; i++)
        render_light_entries(&s->lights[first + i], &b, i);
    glBindBuffer(GL_UNIFORM_BUFFER, r->lights_buffers[g]);
    glBufferSubData(GL_UNIFORM_BUFFER, 0, sizeof b, &b);
}

void render_scene_update_lights(const render_scene *r, int visibility_of) {
    for (int g = 0; g < render_light_groups(r); g++)
        render_update_group(r, g, visibility_of);
}

void render_scene_light_as(const render_scene *r, int l, const scene_light *as) {
    render_lights_block b;
    int slot = RENDER_LIGHT_SLOT(l);
    render_light_entries(as, &b, slot);
    glBindBuffer(GL_UNIFORM_BUFFER, r->lights_buffers[RENDER_LIGHT_GROUP(l)]);
    const size_t entries[] = {offsetof(render_lights_block, position), offsetof(render_lights_block, direction),
                              offsetof(render_lights_block, color), offsetof(render_lights_block, reach)};
    for (size_t e = 0; e < sizeof entries / sizeof *entries; e++) {
        size_t at = entries[e] + (size_t)slot * RENDER_STD140_VEC4;
        glBufferSubData(GL_UNIFORM_BUFFER, (GLintptr)at, RENDER_STD140_VEC4, (const char *)&b + at);
    }
}

void render_scene_destroy(render_scene *r) {
    for (int i = 0; r->meshes && i < r->scene->object_count; i++) {
        glDeleteVertexArrays(1, &r->meshes[i].vao);
        glDeleteBuffers(1, &r->meshes[i].vertex_buffer);
        glDeleteBuffers(1, &r->meshes[i].index_buffer);
    }
    free(r->meshes);
    free(r->in_view);
    if (r->textures) {
        glDeleteTextures(r->scene->texture_count, r->textures);
        glDeleteTextures(1, &r->white);
    }
    free(r->textures);
    if (r->scene)
        glDeleteBuffers(render_light_groups(r), r->lights_buffers);
    for (int v = 0; r->lit && v < RENDER_LIT_VARIANTS; v++)
        for (unsigned set = 0; set < RENDER_LIGHT_SETS; set++)
            render_program_destroy(&r->lit->programs[v][set].program);
    free(r->lit);
    render_programs_destroy(&r->depth);
    *r = (render_scene){0};
}

/* Loads the lit program of `variant` for `set`; false after one line on
 * stderr (the shader loader's own before it). */
static bool render_lit_load(render_lit_programs *lit, render_lit_variant variant, unsigned set) {
    static const char *const lit_files[] = {"lit.vert", "lit.frag"};
    /* The plain variant's list ends after LIT_LIGHTS (a NULL name ends it). */
    const shader_define defines[] = {{"LIT_LIGHTS", (int)set},
                                     {variant == RENDER_LIT_SOFT_VISIBILITY ? "LIT_SOFT_VISIBILITY" : NULL, 1},
                                     {NULL, 0}};
    render_lit_program *p = &lit->programs[variant][set];
    if (!render_program_load(&p->program, lit_files, 2, defines)) {
        fprintf(stderr, "render: the lit program of lights 0x%x does not compile\n", set);
        lit->failed = true;
        return false;
    }
    unsigned id = p->program.id;
    bool soft = variant == RENDER_LIT_SOFT_VISIBILITY;
    p->ambient = shader_uniform(id, "u_ambient");
    p->soft_light = soft ? shader_uniform(id, "u_soft_light") : -1;
    p->soft_visibility = soft ? shader_uniform(id, "u_soft_visibility") : -1;
    p->soft_scale = soft ? shader_uniform(id, "u_soft_scale") : -1;
    p->loaded = true;
    return true;
}

const render_lit_program *render_use_lit_variant(const render_scene *r, render_lit_variant variant,
                                                 const camera_view *v, scene_light_set lights, bool ambient) {
    lights &= SCENE_ALL_LIGHTS(r->scene->light_count);
    int g = lights ? RENDER_LIGHT_GROUP(__builtin_ctzll(lights)) : 0;
    unsigned set = render_group_slots(lights, g);
    if (lights != render_group_lights(set, g)) {
        fprintf(stderr, "render: the lit program's lights 0x%llx span groups of %d\n", (unsigned long long)lights,
                SHADER_PASS_LIGHTS);
        return NULL;
    }
    render_bind_light_group(r, g);
    render_lit_program *p = &r->lit->programs[variant][set];
    if (!p->loaded && (r->lit->failed || !render_lit_load(r->lit, variant, set)))
        return NULL;
    render_program_use(&p->program, v);
    glUniform1f(p->ambient, ambient ? 1.0f : 0.0f);
    return p;
}

const render_program *render_use_lit(const render_scene *r, const camera_view *v, scene_light_set lights,
                                     bool ambient) {
    const render_lit_program *p = render_use_lit_variant(r, RENDER_LIT_PLAIN, v, lights, ambient);
    return p ? &p->program : NULL;
}

void render_depth_prepass(const render_scene *r, const camera_view *v, const bool *mask) {
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    for (int pass = 0; pass < render_programs_passes(&r->depth); pass++) {
        const render_program *p = render_programs_pass(&r->depth, pass);
        render_program_use(p, v);
        for (int i = 0; i < r->scene->object_count; i++)
            if (render_in_mask(mask, i) && render_programs_draws(&r->depth, pass, &r->scene->objects[i]))
                render_draw_object(r, p, i);
    }
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthFunc(GL_EQUAL);
    glDepthMask(GL_FALSE);
}

void render_unshadowed(const render_scene *r, const camera_view *v, const bool *mask, scene_light_set lights) {
    bool blending;
    for (int g = 0; g < render_light_groups(r); g++) {
        unsigned slots = render_group_slots(lights, g);
        render_group_pass_begin(g, &blending);
        if (g == 0 || slots)
            render_draw_objects(r, render_use_lit(r, v, render_group_lights(slots, g), g == 0), mask);
    }
    render_group_pass_end(blending);
}

void render_reset_state(void) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glDisable(GL_STENCIL_TEST);
    glStencilMask(0xff);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
}
