/* test_map_layers: demos/lib/map.c's storage and depth pass (the
 * technique that uses them whole is test_shadowmap's), in-process on a
 * real headless GL context (EGL: a GPU's, else Mesa's llvmpipe, as in CI).
 * An array map (the cascades' storage) must hold in each layer exactly
 * what a 2D map rendered from that layer's matrix holds, through the
 * library's own depth pass (map_render_depth, whose layer passes
 * the frame's map_draw_depth runs too). The shader loader's check of
 * uniform names needs a context too, and is tested here. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <glad/gl.h>

#include "camera.h"
#include "context.h"
#include "render.h"
#include "scene.h"
#include "shader.h"
#include "map_internal.h"
#include "technique_host.h"

#define SCENE_PATH "assets/scenes/simple.json" /* a spot light: a 2D uniform fit */
#define VIEW_ASPECT (16.0f / 9.0f)
/* Small enough to read back quickly, large enough for every caster. */
#define MAP_SIZE 512
#define TEST_MAX_LAYERS 3

/* Layer l sees through the uniform fit's matrix, zoomed and shifted in its
 * clip space (x' = zoom x + shift w): each layer a different window. */
static const float layer_zoom[TEST_MAX_LAYERS] = {1.0f, 1.6f, 0.6f};
static const float layer_shift[TEST_MAX_LAYERS][2] = {{0, 0}, {0.25f, -0.3f}, {-0.2f, 0.1f}};

static struct {
    context ctx;
    scene scene;
    render_scene gpu;
    map_renderer *maps;
    map_light fitted; /* light 0's uniform fit */
    float receivers[SKIPS_MAX_RECEIVER_POINTS][3];
    unsigned readback; /* a framebuffer to read a layer's depth from */
    /* MAP_SIZE^2 depths each: the 2D map's, the array layer's, the 2D map of layer 0's */
    float *expected, *actual, *layer0;
} gl;

#define MAP_BYTES (sizeof(float) * MAP_SIZE * MAP_SIZE)

static int gl_setup(void **state) {
    (void)state;
    shader_set_directory("shaders");
    const context_settings settings = {.backend = CONTEXT_EGL};
    if (!context_create(&gl.ctx, &settings) || !scene_load(&gl.scene, SCENE_PATH) ||
        !render_scene_create(&gl.gpu, &gl.scene) || !(gl.maps = map_create(&(map_settings){0}, &gl.gpu)))
        return -1;
    camera_view view;
    camera_view_compute(&gl.scene.camera, VIEW_ASPECT, &view);
    int receiver_count = technique_host_receiver_points(&gl.scene, &view, gl.receivers, SKIPS_MAX_RECEIVER_POINTS);
    gl.fitted.size = MAP_SIZE;
    if (receiver_count == 0 ||
        !map_fit_uniform(&gl.scene, 0, &gl.fitted, (const float(*)[3])gl.receivers, receiver_count) ||
        gl.fitted.kind != MAP_2D)
        return -1;
    glGenFramebuffers(1, &gl.readback);
    glBindFramebuffer(GL_FRAMEBUFFER, gl.readback);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    gl.expected = malloc(MAP_BYTES);
    gl.actual = malloc(MAP_BYTES);
    gl.layer0 = malloc(MAP_BYTES);
    return gl.expected && gl.actual && gl.layer0 && context_gl_ok("setup") ? 0 : -1;
}

static int gl_teardown(void **state) {
    (void)state;
    free(gl.expected);
    free(gl.actual);
    free(gl.layer0);
    glDeleteFramebuffers(1, &gl.readback);
    map_destroy(gl.maps);
    render_scene_destroy(&gl.gpu);
    scene_free(&gl.scene);
    context_destroy(&gl.ctx);
    return 0;
}

/* A map of `kind` with `layer_count` layers, light 0's uniform fit but
 * seen through the windows of layers first .. first + layer_count - 1,
 * with no texture yet. */
static map_light test_map(map_kind kind, int first, int layer_count) {
    map_light m = gl.fitted;
    m.kind = kind;
    m.layer_count = layer_count;
    m.texture = (map_texture){0};
    for (int layer = 0; layer < layer_count; layer++) {
        mat4 window = GLM_MAT4_IDENTITY_INIT;
        window[0][0] = window[1][1] = layer_zoom[first + layer];
        window[3][0] = layer_shift[first + layer][0];
        window[3][1] = layer_shift[first + layer][1];
        glm_mat4_mul(window, gl.fitted.layer_view_projection[0], m.layer_view_projection[layer]);
    }
    return m;
}

/* Layer `layer` of m's texture into `depth`, as floats. */
static void read_layer(const map_light *m, int layer, float *depth) {
    glBindFramebuffer(GL_FRAMEBUFFER, gl.readback);
    if (m->kind == MAP_ARRAY)
        glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, m->texture.id, 0, layer);
    else
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, m->texture.id, 0);
    assert_int_equal(glCheckFramebufferStatus(GL_FRAMEBUFFER), GL_FRAMEBUFFER_COMPLETE);
    glReadPixels(0, 0, MAP_SIZE, MAP_SIZE, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
}

/* Something was drawn: a texel nearer than the cleared far plane. */
static bool depth_has_caster(const float *depth) {
    for (int i = 0; i < MAP_SIZE * MAP_SIZE; i++)
        if (depth[i] < 1.0f)
            return true;
    return false;
}

static int array_texture_layers(const map_light *m) {
    GLint layers = 0;
    glBindTexture(GL_TEXTURE_2D_ARRAY, m->texture.id);
    glGetTexLevelParameteriv(GL_TEXTURE_2D_ARRAY, 0, GL_TEXTURE_DEPTH, &layers);
    return layers;
}

/* Each layer of a 2- and then a 3-layer array map (one map: its texture is
 * remade for the new layer count), in either depth format, is bit for bit
 * the 2D map rendered from that layer's matrix, and differs from layer 0
 * (so a depth pass that gave every layer layer 0's matrix fails). */
static void test_array_layers_match_2d_maps(void **state) {
    (void)state;
    static const int layer_counts[] = {2, TEST_MAX_LAYERS};
    static const map_depth depths[] = {MAP_DEPTH_24, MAP_DEPTH_32F};
    render_reset_state(); /* what a frame starts with (the depth test on) */
    for (size_t d = 0; d < sizeof depths / sizeof *depths; d++) {
        map_settings settings = {.depth = depths[d]};
        map_light array = {0};
        for (size_t c = 0; c < sizeof layer_counts / sizeof *layer_counts; c++) {
            map_texture kept = array.texture;
            array = test_map(MAP_ARRAY, 0, layer_counts[c]);
            array.texture = kept;
            map_render_depth(gl.maps, &settings, &gl.gpu, &array);
            assert_int_equal(array_texture_layers(&array), layer_counts[c]);
            for (int layer = 0; layer < array.layer_count; layer++) {
                map_light flat = test_map(MAP_2D, layer, 1);
                map_render_depth(gl.maps, &settings, &gl.gpu, &flat);
                read_layer(&flat, 0, gl.expected);
                assert_true(depth_has_caster(gl.expected));
                if (layer == 0)
                    memcpy(gl.layer0, gl.expected, MAP_BYTES);
                else
                    assert_memory_not_equal(gl.expected, gl.layer0, MAP_BYTES);
                read_layer(&array, layer, gl.actual);
                assert_memory_equal(gl.actual, gl.expected, MAP_BYTES);
                glDeleteTextures(1, &flat.texture.id);
            }
            assert_true(context_gl_ok("array depth pass"));
        }
        glDeleteTextures(1, &array.texture.id);
    }
}

/* The texture is kept while nothing it was made with changes, and is an
 * array of the map's layer count. */
static void test_array_texture_kept(void **state) {
    (void)state;
    const map_settings settings = {0};
    render_reset_state();
    map_light array = test_map(MAP_ARRAY, 0, 2);
    map_render_depth(gl.maps, &settings, &gl.gpu, &array);
    unsigned first = array.texture.id;
    map_render_depth(gl.maps, &settings, &gl.gpu, &array);
    assert_int_equal(array.texture.id, first);
    assert_int_equal(array_texture_layers(&array), 2);
    assert_string_equal(map_kind_name(array.kind), "array");
    glDeleteTextures(1, &array.texture.id);
    assert_true(context_gl_ok("array texture"));
}

/* A uniform the program does not declare (a misspelt name) is an error
 * that the frame's owner's check reports once; one it declares is not. */
static void test_undeclared_uniform_is_an_error(void **state) {
    (void)state;
    static const char *const files[] = {"lit.vert", "lit.frag"};
    static const shader_define defines[] = {{"LIT_LIGHTS", 1}, {NULL, 0}};
    unsigned program = shader_load_program(files, 2, defines);
    assert_true(program != 0);
    assert_true(shader_uniform(program, "u_model") >= 0);
    assert_true(shader_uniform(program, "u_ambient") >= 0);
    assert_true(context_gl_ok("declared uniforms"));
    assert_int_equal(shader_uniform(program, "u_modle"), -1);
    assert_false(context_gl_ok("a misspelt uniform"));
    assert_true(context_gl_ok("after the report"));
    shader_delete_program(program);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_array_layers_match_2d_maps),
        cmocka_unit_test(test_array_texture_kept),
        cmocka_unit_test(test_undeclared_uniform_is_an_error),
    };
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
