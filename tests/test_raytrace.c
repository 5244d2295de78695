/* Tests of common/measure/raytrace.c, in-process: shadows against their analytic
 * shape, the spot cone, determinism, and the standard scenes. Run from the
 * repository root. Each measuring test prints what it measured.
 *
 * tests/data/raytrace_square.json: a square occluder (side 2s) at height h
 * straight below a point light at height H, over a ground plane at y = 0,
 * seen from straight above and to the side of the shadow. The square's
 * shadow is the square scaled by H / (H - h) about the point below the
 * light; with a light of radius r its edges blur over
 * w = 2 r h / (H - h) (similar triangles through the occluder's edge).
 *
 * tests/data/raytrace_grazing.json: a box and a sphere on a ground plane at
 * y = 0 under a sun that the test lowers to a few hundredths of a degree,
 * their shadows seen from two units above the ground; each ground pixel's
 * visibility against a shadow ray traced in double from the surface
 * itself. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "raytrace.h"
#include "shadowdiff.h"
#include "support.h"

#define SQUARE_SCENE "tests/data/raytrace_square.json"
#define SPOT_SCENE "tests/data/raytrace_spot.json"
#define GRAZING_SCENE "tests/data/raytrace_grazing.json"
#define SIZE 200
#define GROUND 0
#define OCCLUDER 1
#define AREA_LIGHT_RADIUS 0.5f
/* Enough that a pixel whose light is 1/256 uncovered still counts as
 * penumbra: the penumbra measured loses under a pixel at its two ends. */
#define AREA_LIGHT_SAMPLES 256
#define PENUMBRA_TOLERANCE_PIXELS 2.0
/* test_cone_skip_changes_nothing's frames: small, and samples enough to
 * stratify the penumbrae. */
#define CONE_SKIP_WIDTH 240
#define CONE_SKIP_HEIGHT 135
#define CONE_SKIP_SAMPLES 64

static void load(scene *s, const char *path) { assert_true(scene_load(s, path)); }

static void render(const scene *s, int width, int height, int samples, dump_frame *frame) {
    const raytrace_settings settings = {.light_samples = samples};
    assert_true(raytrace_render(s, width, height, 0, &settings, frame));
}

static const float *position_at(const dump_frame *f, int x, int y) {
    return f->position + 3 * ((size_t)y * (size_t)f->width + (size_t)x);
}

static bool sees(const dump_frame *f, int x, int y, int object) {
    return x >= 0 && y >= 0 && x < f->width && y < f->height &&
           f->ids[(size_t)y * (size_t)f->width + (size_t)x] == object;
}

/* The ground distance one pixel spans there: the largest step to a
 * neighbour that also sees the ground (0 when none does). */
static float ground_pixel_size(const dump_frame *f, int x, int y) {
    static const int steps[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    float size = 0;
    for (int k = 0; k < 4; k++) {
        int nx = x + steps[k][0], ny = y + steps[k][1];
        if (sees(f, nx, ny, GROUND)) {
            const float *a = position_at(f, x, y), *b = position_at(f, nx, ny);
            size = fmaxf(size, sqrtf((a[0] - b[0]) * (a[0] - b[0]) + (a[2] - b[2]) * (a[2] - b[2])));
        }
    }
    return size;
}

/* The pixel seeing `object` whose position is nearest `target`. */
static size_t pixel_nearest(const dump_frame *f, int object, const float target[3]) {
    size_t best = 0;
    float best_distance = INFINITY;
    for (size_t i = 0; i < (size_t)f->width * (size_t)f->height; i++) {
        const float *p = f->position + 3 * i;
        float d = sqrtf((p[0] - target[0]) * (p[0] - target[0]) + (p[1] - target[1]) * (p[1] - target[1]) +
                        (p[2] - target[2]) * (p[2] - target[2]));
        if (f->ids[i] == object && d < best_distance) {
            best_distance = d;
            best = i;
        }
    }
    assert_true(best_distance < 0.1f);
    return best;
}

/* The analytic shadow of the square scene, read from the scene itself. */
typedef struct square_shadow {
    float light_height, occluder_height, half_side; /* H, h, s */
    float shadow_half_side;                         /* s H / (H - h), about the origin */
} square_shadow;

static square_shadow square_shadow_of(const scene *s) {
    square_shadow q = {
        .light_height = s->lights[0].position[1],
        .occluder_height = s->objects[OCCLUDER].model[3][1],
        .half_side = s->objects[OCCLUDER].mesh.bounds_max[0],
    };
    /* The light stands over the square's centre, at the origin. */
    assert_float_equal(s->lights[0].position[0], 0, 0);
    assert_float_equal(s->lights[0].position[2], 0, 0);
    q.shadow_half_side = q.half_side * q.light_height / (q.light_height - q.occluder_height);
    return q;
}

/* Signed distance on the ground from (x, z) to the shadow's edge:
 * negative inside. */
static float square_shadow_distance(const square_shadow *q, float x, float z) {
    float dx = fabsf(x) - q->shadow_half_side, dz = fabsf(z) - q->shadow_half_side;
    float outside = sqrtf(fmaxf(dx, 0) * fmaxf(dx, 0) + fmaxf(dz, 0) * fmaxf(dz, 0));
    return outside > 0 ? outside : fmaxf(dx, dz);
}

static void test_hard_shadow_matches_analytic_square(void **state) {
    (void)state;
    scene s;
    dump_frame f;
    load(&s, SQUARE_SCENE);
    square_shadow q = square_shadow_of(&s);
    render(&s, SIZE, SIZE, 1, &f);
    long compared = 0, excluded = 0, shadowed = 0, mismatches = 0;
    for (int y = 0; y < f.height; y++) {
        for (int x = 0; x < f.width; x++) {
            if (!sees(&f, x, y, GROUND))
                continue;
            const float *p = position_at(&f, x, y);
            float distance = square_shadow_distance(&q, p[0], p[2]);
            float pixel = ground_pixel_size(&f, x, y);
            if (pixel == 0 || fabsf(distance) < pixel) {
                excluded++;
                continue;
            }
            float expected = distance < 0 ? 0.0f : 1.0f;
            float visibility = f.visibility[(size_t)y * (size_t)f.width + (size_t)x];
            compared++;
            shadowed += expected == 0;
            mismatches += visibility != expected;
        }
    }
    printf("    hard shadow: %ld ground pixels compared (%ld in shadow), %ld within a pixel of the edge "
           "excluded, %ld mismatches\n",
           compared, shadowed, excluded, mismatches);
    assert_true(shadowed > 1000 && compared - shadowed > 1000);
    assert_int_equal(mismatches, 0);
    dump_frame_free(&f);
    scene_free(&s);
}

/* The square scene under an area light of AREA_LIGHT_RADIUS. */
static void load_area_square(scene *s) {
    load(s, SQUARE_SCENE);
    s->lights[0].radius = AREA_LIGHT_RADIUS;
}

static void test_area_light_penumbra_width(void **state) {
    (void)state;
    scene s;
    dump_frame f;
    load_area_square(&s);
    square_shadow q = square_shadow_of(&s);
    render(&s, SIZE, SIZE, AREA_LIGHT_SAMPLES, &f);
    /* The middle row crosses the shadow's straight edge x = s H / (H - h)
     * at z ~ 0, far from its corners. */
    int y = f.height / 2, first = -1, last = -1, penumbra = 0;
    for (int x = 0; x < f.width; x++) {
        if (!sees(&f, x, y, GROUND))
            continue;
        float v = f.visibility[(size_t)y * (size_t)f.width + (size_t)x];
        penumbra += v > 0 && v < 1;
        if (first < 0)
            first = x;
        last = x;
    }
    assert_true(last - first > f.width / 2);
    assert_true(fabsf(position_at(&f, first, y)[2]) < 0.1f * q.shadow_half_side);
    double pixel = (position_at(&f, last, y)[0] - position_at(&f, first, y)[0]) / (double)(last - first);
    double predicted = 2.0 * AREA_LIGHT_RADIUS * q.occluder_height / (q.light_height - q.occluder_height) / pixel;
    printf("    penumbra: predicted %.2f pixels (w = 2rh/(H-h) = %.3f, %.4f per pixel), measured %d pixels\n",
           predicted, predicted * pixel, pixel, penumbra);
    assert_true(fabs(penumbra - predicted) <= PENUMBRA_TOLERANCE_PIXELS);
    dump_frame_free(&f);
    scene_free(&s);
}

/* The area light's stratified rays converge: against many rays
 * (CONVERGED_SAMPLES), the penumbra's MAE with the default's rays is
 * below the 1/32 that shadowdiff's classes leave at either end for the
 * reference's own noise, and less than half that of a few rays. At a
 * quarter of SIZE across, for time. --light-samples takes 1 to the most,
 * anything else is one line and exit 2. */
#define CONVERGED_SAMPLES 4096
#define FEW_SAMPLES 16
#define CONVERGENCE_SIZE (SIZE / 4)
#define CONVERGENCE_GAIN 2.0
#define EXIT_USAGE 2
static double penumbra_mae_against(const dump_frame *converged, const scene *s, int samples) {
    dump_frame f;
    render(s, CONVERGENCE_SIZE, CONVERGENCE_SIZE, samples, &f);
    shadowdiff_result r;
    assert_true(shadowdiff_compare(converged, &f, NULL, &r, NULL));
    assert_true(r.class_pixels[SHADOWDIFF_CLASS_PENUMBRA] > 0);
    printf("    %d rays against %d: penumbra MAE %.5f over %ld pixels\n", samples, CONVERGED_SAMPLES,
           r.class_mae[SHADOWDIFF_CLASS_PENUMBRA], r.class_pixels[SHADOWDIFF_CLASS_PENUMBRA]);
    dump_frame_free(&f);
    return r.class_mae[SHADOWDIFF_CLASS_PENUMBRA];
}

static void test_area_light_rays_converge(void **state) {
    (void)state;
    scene s;
    dump_frame converged;
    load_area_square(&s);
    render(&s, CONVERGENCE_SIZE, CONVERGENCE_SIZE, CONVERGED_SAMPLES, &converged);
    double by_default = penumbra_mae_against(&converged, &s, RAYTRACE_DEFAULT_LIGHT_SAMPLES);
    double few = penumbra_mae_against(&converged, &s, FEW_SAMPLES);
    assert_true(by_default < SHADOWDIFF_UMBRA_MAX_VISIBILITY);
    assert_true(few > CONVERGENCE_GAIN * by_default);
    dump_frame_free(&converged);
    scene_free(&s);
    char too_many[32];
    snprintf(too_many, sizeof too_many, "%d", RAYTRACE_MAX_LIGHT_SAMPLES + 1);
    const char *const bad[] = {"0", too_many, "-4", "x"};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char command[512], err[4096];
        snprintf(command, sizeof command, "%s --scene " SQUARE_SCENE " --light-samples %s",
                 support_program("raytrace"), bad[i]);
        assert_int_equal(support_run(command, err, sizeof err), EXIT_USAGE);
        assert_int_equal(support_count_lines(err), 1);
        assert_non_null(strstr(err, "--light-samples"));
    }
}

/* Ground points in tests/data/raytrace_spot.json: the spot hangs at
 * (0, 5, 0) pointing down, inner 20, outer 30 degrees; the sphere "ghost"
 * casts no shadow, though it stands between the light and ghost_shadow. */
static const float outside_cone[3] = {4.5f, 0, 4.5f}; /* 52 degrees off the axis */
static const float on_axis[3] = {0, 0, 0};
static const float between_cones[3] = {0, 0, 2.4f}; /* 26 degrees */
static const float ghost_shadow[3] = {2.5f, 0, 0};

static void test_spot_cone_respected(void **state) {
    (void)state;
    scene s;
    dump_frame f;
    load(&s, SPOT_SCENE);
    render(&s, SIZE, SIZE, 1, &f);
    size_t outside = pixel_nearest(&f, GROUND, outside_cone);
    size_t axis = pixel_nearest(&f, GROUND, on_axis);
    size_t between = pixel_nearest(&f, GROUND, between_cones);
    size_t ghost = pixel_nearest(&f, GROUND, ghost_shadow);
    assert_float_equal(f.visibility[outside], 0, 0);
    for (int k = 0; k < 3; k++) {
        float ambient_only = s.objects[GROUND].color[k] * s.ambient[k];
        assert_int_equal(f.color[4 * outside + (size_t)k], (int)(ambient_only * 255.0f + 0.5f));
    }
    assert_float_equal(f.visibility[axis], 1, 0);
    /* Inside the outer cone the light reaches, dimmed by the spot's
     * falloff: visibility says only whether something blocks it. */
    assert_float_equal(f.visibility[between], 1, 0);
    assert_true(f.color[4 * between] > f.color[4 * outside] && f.color[4 * between] < f.color[4 * axis]);
    assert_float_equal(f.visibility[ghost], 1, 0);
    dump_frame_free(&f);

    /* ghost_shadow is truly behind the sphere: once it casts, it is dark. */
    s.objects[1].casts = true;
    render(&s, SIZE, SIZE, 1, &f);
    assert_float_equal(f.visibility[ghost], 0, 0);
    dump_frame_free(&f);
    scene_free(&s);
}

/* The sun of the grazing scene: each of grazing_degrees above the ground,
 * travelling horizontally along grazing_travel. */
static const double grazing_travel[2] = {0.8, -0.6}; /* x, z; unit */
static const double grazing_degrees[] = {0.05, 0.1, 0.25, 0.5, 1};
/* A crossing nearer the start than this, in world units, is the start's
 * own plane (the ground under the box's bottom face). */
#define GRAZING_MIN_DISTANCE 1e-9
#define GRAZING_CASTERS 2 /* the box and the sphere */

/* Möller and Trumbore's ray-triangle test in double: the distance along the
 * unit `direction` from `origin` to triangle (a, b, c), or INFINITY. */
static double ray_triangle(const double origin[3], const double direction[3], const double a[3], const double b[3],
                           const double c[3]) {
    double e1[3], e2[3], p[3], q[3], s[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = b[k] - a[k];
        e2[k] = c[k] - a[k];
        s[k] = origin[k] - a[k];
    }
    p[0] = direction[1] * e2[2] - direction[2] * e2[1];
    p[1] = direction[2] * e2[0] - direction[0] * e2[2];
    p[2] = direction[0] * e2[1] - direction[1] * e2[0];
    double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (det == 0)
        return INFINITY;
    double u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) / det;
    q[0] = s[1] * e1[2] - s[2] * e1[1];
    q[1] = s[2] * e1[0] - s[0] * e1[2];
    q[2] = s[0] * e1[1] - s[1] * e1[0];
    double v = (direction[0] * q[0] + direction[1] * q[1] + direction[2] * q[2]) / det;
    double t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
    return u >= 0 && v >= 0 && u + v <= 1 && t > GRAZING_MIN_DISTANCE ? t : INFINITY;
}

/* Vertex v of `caster` in world units, in double. */
static void grazing_world(const scene_object *caster, uint32_t v, double out[3]) {
    const float *p = caster->mesh.vertices[v].position;
    for (int k = 0; k < 3; k++)
        out[k] = (double)caster->model[3][k] + (double)caster->model[0][k] * p[0] +
                 (double)caster->model[1][k] * p[1] + (double)caster->model[2][k] * p[2];
}

/* A caster, and the sphere about its first vertex through its farthest. */
typedef struct grazing_caster {
    const scene_object *object;
    double centre[3], radius;
} grazing_caster;

static grazing_caster grazing_caster_of(const scene_object *o) {
    grazing_caster c = {.object = o};
    grazing_world(o, 0, c.centre);
    for (uint32_t v = 0; v < o->mesh.vertex_count; v++) {
        double p[3];
        grazing_world(o, v, p);
        c.radius = fmax(c.radius, sqrt((p[0] - c.centre[0]) * (p[0] - c.centre[0]) +
                                       (p[1] - c.centre[1]) * (p[1] - c.centre[1]) +
                                       (p[2] - c.centre[2]) * (p[2] - c.centre[2])));
    }
    return c;
}

/* Whether the ray from `origin` along the unit `to_light` misses every
 * triangle of caster c, in world units and double; a ray that passes c's
 * sphere misses without a look at the triangles. */
static bool grazing_misses(const grazing_caster *c, const double origin[3], const double to_light[3]) {
    double to_centre[3], corner[3][3];
    for (int k = 0; k < 3; k++)
        to_centre[k] = c->centre[k] - origin[k];
    double along = to_centre[0] * to_light[0] + to_centre[1] * to_light[1] + to_centre[2] * to_light[2];
    double square = to_centre[0] * to_centre[0] + to_centre[1] * to_centre[1] + to_centre[2] * to_centre[2];
    if (along < -c->radius || square - along * along > c->radius * c->radius)
        return true;
    const mesh *m = &c->object->mesh;
    for (uint32_t i = 0; i < m->index_count; i += 3) {
        for (int k = 0; k < 3; k++)
            grazing_world(c->object, m->indices[i + (uint32_t)k], corner[k]);
        if (ray_triangle(origin, to_light, corner[0], corner[1], corner[2]) < INFINITY)
            return false;
    }
    return true;
}

/* Whether the ray from `origin` towards the light (against the sun's
 * `travel`) misses each of the `count` casters. */
static bool grazing_unoccluded(const grazing_caster *casters, int count, const double origin[3],
                               const double travel[3]) {
    const double to_light[3] = {-travel[0], -travel[1], -travel[2]};
    for (int c = 0; c < count; c++)
        if (!grazing_misses(&casters[c], origin, to_light))
            return false;
    return true;
}

/* With the sun from 0.05 to 1 degree above the ground, every ground pixel's
 * visibility is that of a ray traced in double from its point on the plane
 * y = 0 (the dump's position, its height put back on the plane): a shadow
 * ray lifted off the surface would move the shadow's edge by its lift over
 * the tangent of the sun's elevation. */
static void test_grazing_sun_matches_double_trace(void **state) {
    (void)state;
    scene s;
    load(&s, GRAZING_SCENE);
    grazing_caster casters[GRAZING_CASTERS];
    int caster_count = 0;
    for (int o = 0; o < s.object_count; o++)
        if (s.objects[o].casts) {
            assert_true(caster_count < GRAZING_CASTERS);
            casters[caster_count++] = grazing_caster_of(&s.objects[o]);
        }
    assert_int_equal(caster_count, GRAZING_CASTERS);
    long differing = 0;
    for (size_t a = 0; a < sizeof grazing_degrees / sizeof *grazing_degrees; a++) {
        double radians = grazing_degrees[a] * M_PI / 180;
        const double travel[3] = {grazing_travel[0] * cos(radians), -sin(radians), grazing_travel[1] * cos(radians)};
        for (int k = 0; k < 3; k++)
            s.lights[0].direction[k] = (float)travel[k];
        const double exact[3] = {s.lights[0].direction[0], s.lights[0].direction[1], s.lights[0].direction[2]};
        dump_frame f;
        render(&s, SUPPORT_SCREENSHOT_WIDTH, SUPPORT_SCREENSHOT_HEIGHT, 1, &f);
        long compared = 0, shadowed = 0, mismatches = 0;
        for (size_t i = 0; i < (size_t)f.width * (size_t)f.height; i++) {
            if (f.ids[i] != GROUND)
                continue;
            const double point[3] = {f.position[3 * i], 0, f.position[3 * i + 2]};
            float expected = grazing_unoccluded(casters, caster_count, point, exact) ? 1.0f : 0.0f;
            compared++;
            shadowed += expected == 0;
            mismatches += f.visibility[i] != expected;
        }
        printf("    sun %.2f degrees up: %ld ground pixels, %ld in shadow, %ld differ from the double trace\n",
               grazing_degrees[a], compared, shadowed, mismatches);
        assert_true(shadowed > 0 && compared - shadowed > 0);
        differing += mismatches;
        dump_frame_free(&f);
    }
    assert_int_equal(differing, 0);
    scene_free(&s);
}

/* Every array of two dumps the same, byte for byte; frees both. */
static void assert_dumps_equal_then_free(dump_frame *a, dump_frame *b) {
    assert_int_equal(a->width, b->width);
    assert_int_equal(a->height, b->height);
    size_t n = (size_t)a->width * (size_t)a->height;
    assert_memory_equal(a->visibility, b->visibility, n * sizeof *a->visibility);
    assert_memory_equal(a->depth, b->depth, n * sizeof *a->depth);
    assert_memory_equal(a->normal, b->normal, 3 * n * sizeof *a->normal);
    assert_memory_equal(a->position, b->position, 3 * n * sizeof *a->position);
    assert_memory_equal(a->ids, b->ids, n * sizeof *a->ids);
    assert_memory_equal(a->color, b->color, 4 * n);
    dump_frame_free(a);
    dump_frame_free(b);
}

static void test_render_is_deterministic(void **state) {
    (void)state;
    scene s;
    dump_frame a, b;
    load(&s, SQUARE_SCENE);
    s.lights[0].radius = AREA_LIGHT_RADIUS; /* the jittered samples too */
    render(&s, 100, 80, 10, &a);
    render(&s, 100, 80, 10, &b);
    assert_dumps_equal_then_free(&a, &b);
    scene_free(&s);
}

/* An area light's samples are not traced where the cone to its disk
 * meets no caster's box (raytrace.c, raytrace_cone_clear): the dumps are
 * those of every sample traced, byte for byte, under an area point light
 * over a table (soft_table), an area sun (soft_sun) and an area point
 * light through stained glass (gltf_glass_area). */
static void test_cone_skip_changes_nothing(void **state) {
    (void)state;
    static const char *const scenes[] = {"assets/scenes/soft_table.json", "assets/scenes/soft_sun.json",
                                         "tests/data/gltf_glass_area.json"};
    for (size_t k = 0; k < sizeof scenes / sizeof *scenes; k++) {
        scene s;
        dump_frame skipping, every;
        load(&s, scenes[k]);
        const raytrace_settings skip = {.light_samples = CONE_SKIP_SAMPLES},
                                all = {.light_samples = CONE_SKIP_SAMPLES, .trace_every_sample = true};
        assert_true(raytrace_render(&s, CONE_SKIP_WIDTH, CONE_SKIP_HEIGHT, 0, &skip, &skipping));
        assert_true(raytrace_render(&s, CONE_SKIP_WIDTH, CONE_SKIP_HEIGHT, 0, &all, &every));
        assert_dumps_equal_then_free(&skipping, &every);
        scene_free(&s);
    }
}

static bool all_finite(const float *values, size_t count) {
    for (size_t i = 0; i < count; i++)
        if (!isfinite(values[i]))
            return false;
    return true;
}

static void test_standard_scenes_are_sane(void **state) {
    (void)state;
    static const char *const scenes[] = {"assets/scenes/simple.json", "assets/scenes/bunny.json",
                                         "assets/scenes/teapot.json"};
    for (size_t k = 0; k < sizeof scenes / sizeof *scenes; k++) {
        scene s;
        dump_frame f;
        load(&s, scenes[k]);
        render(&s, 160, 90, 0, &f);
        size_t n = (size_t)f.width * (size_t)f.height;
        assert_true(all_finite(f.visibility, n) && all_finite(f.depth, n) && all_finite(f.ids, n) &&
                    all_finite(f.normal, 3 * n) && all_finite(f.position, 3 * n));
        long shadowed = 0, lit = 0;
        for (size_t i = 0; i < n; i++) {
            shadowed += f.ids[i] >= 0 && f.visibility[i] == 0;
            lit += f.visibility[i] == 1;
        }
        printf("    %s: %ld shadowed, %ld lit pixels of %zu\n", scenes[k], shadowed, lit, n);
        assert_true(shadowed > 0 && lit > 0);
        dump_frame_free(&f);
        scene_free(&s);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hard_shadow_matches_analytic_square),
        cmocka_unit_test(test_area_light_penumbra_width),
        cmocka_unit_test(test_area_light_rays_converge),
        cmocka_unit_test(test_spot_cone_respected),
        cmocka_unit_test(test_grazing_sun_matches_double_trace),
        cmocka_unit_test(test_render_is_deterministic),
        cmocka_unit_test(test_cone_skip_changes_nothing),
        cmocka_unit_test(test_standard_scenes_are_sane),
    };
    return cmocka_run_group_tests_name("ray-traced reference", tests, NULL, NULL);
}
