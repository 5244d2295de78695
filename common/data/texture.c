#include "texture.h"

#include <math.h>
#include <stb_image.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TEXTURE_CHANNELS 4
#define TEXTURE_ALPHA 3
#define TEXTURE_CODES 256

float texture_srgb_to_linear(unsigned char code) {
    static float table[TEXTURE_CODES];
    static bool made;
    if (!made) {
        for (int i = 0; i < TEXTURE_CODES; i++) {
            double c = i / 255.0;
            table[i] = (float)(c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4));
        }
        made = true;
    }
    return table[code];
}

unsigned char texture_linear_to_srgb(float linear) {
    double l = fmin(fmax(linear, 0.0), 1.0);
    double c = l <= 0.0031308 ? l * 12.92 : 1.055 * pow(l, 1 / 2.4) - 0.055;
    return (unsigned char)(c * 255.0 + 0.5);
}

static float texture_channel(const unsigned char *texel, int channel) {
    return channel == TEXTURE_ALPHA ? texel[channel] / 255.0f : texture_srgb_to_linear(texel[channel]);
}

/* Level `l` from level l - 1 (see the top). */
static void texture_reduce(const texture_level *above, texture_level *level) {
    for (int y = 0; y < level->height; y++)
        for (int x = 0; x < level->width; x++) {
            int x0 = 2 * x, y0 = 2 * y;
            int x1 = x0 + 1 < above->width ? x0 + 1 : x0, y1 = y0 + 1 < above->height ? y0 + 1 : y0;
            const unsigned char *block[4] = {
                above->rgba + TEXTURE_CHANNELS * ((size_t)y0 * (size_t)above->width + (size_t)x0),
                above->rgba + TEXTURE_CHANNELS * ((size_t)y0 * (size_t)above->width + (size_t)x1),
                above->rgba + TEXTURE_CHANNELS * ((size_t)y1 * (size_t)above->width + (size_t)x0),
                above->rgba + TEXTURE_CHANNELS * ((size_t)y1 * (size_t)above->width + (size_t)x1)};
            unsigned char *out = level->rgba + TEXTURE_CHANNELS * ((size_t)y * (size_t)level->width + (size_t)x);
            for (int c = 0; c < TEXTURE_CHANNELS; c++) {
                float mean = 0;
                for (int k = 0; k < 4; k++)
                    mean += 0.25f * texture_channel(block[k], c);
                out[c] = c == TEXTURE_ALPHA ? (unsigned char)(mean * 255.0f + 0.5f) : texture_linear_to_srgb(mean);
            }
        }
}

/* Whether an image of the size a file's header gives (width, height;
 * read: `known`) may be decoded; false after a line. */
static bool texture_size_fits(const char *name, bool known, int width, int height) {
    if (!known) {
        fprintf(stderr, "%s: not an image: %s\n", name, stbi_failure_reason());
        return false;
    }
    if (width >= 1 && height >= 1 && width <= TEXTURE_MAX_SIZE && height <= TEXTURE_MAX_SIZE)
        return true;
    fprintf(stderr, "%s: a %dx%d image: textures take 1 to %d texels a side\n", name, width, height,
            TEXTURE_MAX_SIZE);
    return false;
}

bool texture_from_pixels(texture *t, const char *name, int width, int height, const unsigned char *rgba) {
    *t = (texture){0};
    if (!texture_size_fits(name, true, width, height))
        return false;
    for (int w = width, h = height;; w = w > 1 ? w / 2 : 1, h = h > 1 ? h / 2 : 1) {
        texture_level *level = &t->levels[t->level_count];
        *level = (texture_level){.width = w, .height = h, .rgba = malloc(TEXTURE_CHANNELS * (size_t)w * (size_t)h)};
        if (!level->rgba) {
            fprintf(stderr, "%s: out of memory for a %dx%d texture\n", name, width, height);
            texture_free(t);
            return false;
        }
        t->level_count++;
        if (t->level_count == 1)
            memcpy(level->rgba, rgba, TEXTURE_CHANNELS * (size_t)w * (size_t)h);
        else
            texture_reduce(&t->levels[t->level_count - 2], level);
        if (w == 1 && h == 1)
            break;
    }
    return true;
}

/* stb_image's pixels (top row first) as a texture (bottom row first). */
static bool texture_from_decoded(texture *t, const char *name, unsigned char *pixels, int width, int height) {
    if (!pixels) {
        fprintf(stderr, "%s: not an image: %s\n", name, stbi_failure_reason());
        return false;
    }
    size_t row = TEXTURE_CHANNELS * (size_t)width;
    for (int y = 0; y < height / 2; y++)
        for (size_t k = 0; k < row; k++) {
            unsigned char *a = pixels + (size_t)y * row + k, *b = pixels + (size_t)(height - 1 - y) * row + k;
            unsigned char swap = *a;
            *a = *b;
            *b = swap;
        }
    bool made = texture_from_pixels(t, name, width, height, pixels);
    stbi_image_free(pixels);
    return made;
}

bool texture_from_memory(texture *t, const char *name, const unsigned char *bytes, size_t size) {
    *t = (texture){0};
    int width = 0, height = 0, channels = 0;
    if (size > (size_t)INT32_MAX) {
        fprintf(stderr, "%s: an image of %zu bytes: too large\n", name, size);
        return false;
    }
    bool known = stbi_info_from_memory(bytes, (int)size, &width, &height, &channels);
    if (!texture_size_fits(name, known, width, height))
        return false;
    unsigned char *pixels = stbi_load_from_memory(bytes, (int)size, &width, &height, &channels, TEXTURE_CHANNELS);
    return texture_from_decoded(t, name, pixels, width, height);
}

bool texture_load_file(texture *t, const char *name, const char *path) {
    *t = (texture){0};
    int width = 0, height = 0, channels = 0;
    bool known = stbi_info(path, &width, &height, &channels);
    if (!texture_size_fits(name, known, width, height))
        return false;
    unsigned char *pixels = stbi_load(path, &width, &height, &channels, TEXTURE_CHANNELS);
    return texture_from_decoded(t, name, pixels, width, height);
}

void texture_free(texture *t) {
    for (int l = 0; l < t->level_count; l++)
        free(t->levels[l].rgba);
    *t = (texture){0};
}

float texture_lod(const texture *t, const float duv_dx[2], const float duv_dy[2]) {
    float w = (float)t->levels[0].width, h = (float)t->levels[0].height;
    float x = hypotf(duv_dx[0] * w, duv_dx[1] * h), y = hypotf(duv_dy[0] * w, duv_dy[1] * h);
    float rho = fmaxf(x, y);
    return rho > 0 ? log2f(rho) : -INFINITY;
}

/* Texel index i of n, any i, by the wrap mode (OpenGL 4.6, 8.14.2). */
static int texture_wrap_index(texture_wrap wrap, int i, int n) {
    if (wrap == TEXTURE_CLAMP_TO_EDGE)
        return i < 0 ? 0 : i >= n ? n - 1 : i;
    int period = wrap == TEXTURE_MIRRORED_REPEAT ? 2 * n : n;
    int r = i % period;
    if (r < 0)
        r += period;
    if (wrap == TEXTURE_REPEAT)
        return r;
    int a = r - n; /* mirror(a): a where a >= 0, else -(1 + a) */
    return (n - 1) - (a >= 0 ? a : -(1 + a));
}

/* Bilinear at one level: linear RGBA added into rgba, times weight. */
static void texture_bilinear(const texture *t, const texture_level *level, const float uv[2], float weight,
                             float rgba[4]) {
    float x = uv[0] * (float)level->width - 0.5f, y = uv[1] * (float)level->height - 0.5f;
    float fx = floorf(x), fy = floorf(y);
    float ax = x - fx, ay = y - fy;
    /* Beyond int's range a coordinate says nothing of where it lands. */
    if (!(fabsf(fx) < (float)INT32_MAX / 2 && fabsf(fy) < (float)INT32_MAX / 2))
        fx = fy = ax = ay = 0;
    int x0 = texture_wrap_index(t->wrap[0], (int)fx, level->width);
    int x1 = texture_wrap_index(t->wrap[0], (int)fx + 1, level->width);
    int y0 = texture_wrap_index(t->wrap[1], (int)fy, level->height);
    int y1 = texture_wrap_index(t->wrap[1], (int)fy + 1, level->height);
    const struct {
        int x, y;
        float w;
    } taps[4] = {{x0, y0, (1 - ax) * (1 - ay)}, {x1, y0, ax * (1 - ay)}, {x0, y1, (1 - ax) * ay}, {x1, y1, ax * ay}};
    for (int k = 0; k < 4; k++) {
        const unsigned char *texel =
            level->rgba + TEXTURE_CHANNELS * ((size_t)taps[k].y * (size_t)level->width + (size_t)taps[k].x);
        for (int c = 0; c < TEXTURE_CHANNELS; c++)
            rgba[c] += weight * taps[k].w * texture_channel(texel, c);
    }
}

void texture_sample(const texture *t, const float uv[2], float lod, float rgba[4]) {
    for (int c = 0; c < TEXTURE_CHANNELS; c++)
        rgba[c] = 0;
    float top = (float)(t->level_count - 1);
    if (!(lod > 0)) { /* magnified (or no footprint): level 0 */
        texture_bilinear(t, &t->levels[0], uv, 1, rgba);
        return;
    }
    if (lod >= top) {
        texture_bilinear(t, &t->levels[t->level_count - 1], uv, 1, rgba);
        return;
    }
    int below = (int)floorf(lod);
    float between = lod - (float)below;
    texture_bilinear(t, &t->levels[below], uv, 1 - between, rgba);
    texture_bilinear(t, &t->levels[below + 1], uv, between, rgba);
}
