#include "area_light.h"

#include <cglm/cglm.h>
#include <math.h>
#include <string.h>

#define AREA_LIGHT_PI GLM_PIf

uint32_t area_light_hash(uint32_t v) {
    uint32_t state = v * 747796405u + 2891336453u;
    uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

float area_light_unit(uint32_t h) { return (float)(h >> 8) * (1.0f / 16777216.0f); }

void area_light_basis(const float n[3], float t[3], float b[3]) {
    float sign = copysignf(1.0f, n[2]);
    float a = -1.0f / (sign + n[2]);
    float c = n[0] * n[1] * a;
    t[0] = 1.0f + sign * n[0] * n[0] * a;
    t[1] = sign * c;
    t[2] = -sign * n[0];
    b[0] = c;
    b[1] = sign + n[1] * n[1] * a;
    b[2] = -n[1];
}

/* The unit square's cells: floor(sqrt n) rows whose counts differ by at
 * most one, each row as tall as its share of the samples (n a square: the
 * usual sqrt(n) x sqrt(n) grid). */
void area_light_disk_sample(int k, int n, float jitter_u, float jitter_v, float disk[2]) {
    int rows = (int)sqrt((double)n);
    int base = n / rows, extra = n % rows; /* the first `extra` rows hold base + 1 */
    int long_cells = extra * (base + 1);
    int row = k < long_cells ? k / (base + 1) : extra + (k - long_cells) / base;
    int count = row < extra ? base + 1 : base;
    int first = row < extra ? row * (base + 1) : long_cells + (row - extra) * base;
    float a = 2.0f * ((float)(k - first) + jitter_u) / (float)count - 1.0f;
    float b = 2.0f * ((float)first + jitter_v * (float)count) / (float)n - 1.0f;
    float r, phi;
    if (a == 0 && b == 0) {
        r = phi = 0;
    } else if (fabsf(a) > fabsf(b)) {
        r = a;
        phi = AREA_LIGHT_PI / 4 * (b / a);
    } else {
        r = b;
        phi = AREA_LIGHT_PI / 2 - AREA_LIGHT_PI / 4 * (a / b);
    }
    disk[0] = r * cosf(phi);
    disk[1] = r * sinf(phi);
}

void area_light_frame_for(const scene_light *light, const float centre[4], const float axis[3],
                          area_light_frame *frame) {
    memcpy(frame->centre, centre, sizeof frame->centre);
    memcpy(frame->axis, axis, sizeof frame->axis);
    area_light_basis(axis, frame->tangent, frame->bitangent);
    frame->radius = light->radius;
    /* 2 sin^2(a/2), not 1 - cos a, which cancels to 0 for a sun-sized
     * radius; a radius past 180 degrees would wrap around. */
    float half_angle = glm_rad(fminf(light->radius, 180.0f)) / 2;
    frame->cap = 2.0f * sinf(half_angle) * sinf(half_angle);
}

/* Disk point `disk` of the frame as a homogeneous point, or a direction
 * towards a directional light (w 0). */
static void area_light_point(const area_light_frame *f, const float disk[2], float out[4]) {
    if (f->centre[3] == 0) {
        /* The disk onto the cap of directions within the angular radius,
         * keeping equal areas (Lambert's azimuthal map): a uniform sun
         * disk. */
        float r2 = disk[0] * disk[0] + disk[1] * disk[1];
        float one_minus_cos = r2 * f->cap;
        float sin_over_r = r2 > 0 ? sqrtf(one_minus_cos * (2.0f - one_minus_cos) / r2) : 0.0f;
        glm_vec3_scale((float *)f->axis, 1.0f - one_minus_cos, out);
        glm_vec3_muladds((float *)f->tangent, disk[0] * sin_over_r, out);
        glm_vec3_muladds((float *)f->bitangent, disk[1] * sin_over_r, out);
        out[3] = 0;
        return;
    }
    glm_vec4_copy((float *)f->centre, out);
    glm_vec3_muladds((float *)f->tangent, disk[0] * f->radius, out);
    glm_vec3_muladds((float *)f->bitangent, disk[1] * f->radius, out);
}

/* Sample k of n on the unit disk, its cell's jitter from `jitter`. */
static void area_light_jittered_disk(int k, int n, uint32_t jitter, float disk[2]) {
    area_light_disk_sample(k, n, area_light_unit(jitter), area_light_unit(area_light_hash(jitter)), disk);
}

void area_light_sample(const area_light_frame *f, int k, int n, uint32_t jitter, float out[4]) {
    float disk[2];
    area_light_jittered_disk(k, n, jitter, disk);
    area_light_point(f, disk, out);
}

void area_light_sample_ball(const area_light_frame *f, int k, int n, uint32_t jitter, float out[4]) {
    float disk[2];
    area_light_jittered_disk(k, n, jitter, disk);
    area_light_point(f, disk, out);
    if (f->centre[3] == 0)
        return;
    float rho2 = disk[0] * disk[0] + disk[1] * disk[1];
    float w = area_light_unit(area_light_hash(area_light_hash(jitter)));
    float lift = sqrtf(fmaxf(1.0f - rho2, 0.0f)) * sinf(AREA_LIGHT_PI * (w - 0.5f));
    glm_vec3_muladds((float *)f->axis, lift * f->radius, out);
}

int area_light_progressive_index(int j, int n) {
    int bits = 0; /* per axis: n = 4^bits */
    while (1 << (2 * bits) < n)
        bits++;
    if (1 << (2 * bits) != n)
        return j;
    int row = 0, column = 0;
    for (int b = 0; b < bits; b++) {
        /* bit b of each half of j's Morton code, to bit bits-1-b */
        column |= (j >> (2 * b) & 1) << (bits - 1 - b);
        row |= (j >> (2 * b + 1) & 1) << (bits - 1 - b);
    }
    return row * (1 << bits) + column;
}
