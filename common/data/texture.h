/* texture: a surface's base-colour image and the one texel rule that the
 * rasterizer and the ray-traced reference both apply to it.
 *
 *   texture t;
 *   texture_from_memory(&t, "truck.glb: image 0", bytes, size);   PNG, JPEG...
 *   GL:        every level uploaded as GL_SRGB8_ALPHA8, sampled trilinear
 *              with its wrap modes (common/gl/render.c, shaders/surface.glsl)
 *   reference: texture_sample(&t, uv, texture_lod(&t, duv_dx, duv_dy), rgba)
 *
 * The rule is OpenGL's for GL_LINEAR_MIPMAP_LINEAR on an sRGB texture,
 * with the texture's wrap modes (texture_wrap: glTF's sampler's): texels decoded to linear light before they are filtered,
 * the level of detail log2 of the larger of the pixel's two footprints in
 * level-0 texels, bilinear in the two levels about it (level 0 alone where
 * the footprint is smaller than a texel), texel centres at half-integers.
 * The mip chain is made here, once, and uploaded as it is, so that both
 * read the same texels: each level halves the one above (rounded down, at
 * least 1), each texel the mean in linear light of the 2x2 block above it
 * (an odd level's last row or column also the row or column before it).
 *
 * Rows run from v = 0 (the image's bottom row, as OpenGL's first row of a
 * texture is t = 0) upwards: assimp flips a glTF file's texture
 * coordinates to that convention. Colours are sRGB-encoded 8-bit RGBA,
 * alpha linear. */
#ifndef TEXTURE_H
#define TEXTURE_H

#include <stdbool.h>
#include <stddef.h>

/* Levels of an image of up to 2^(TEXTURE_MAX_LEVELS - 1) texels a side,
 * the largest it takes (checked from the file's header, before it is
 * decoded). */
#define TEXTURE_MAX_LEVELS 14
#define TEXTURE_MAX_SIZE (1 << (TEXTURE_MAX_LEVELS - 1))

typedef struct texture_level {
    int width, height;
    unsigned char *rgba; /* sRGB, row 0 at v = 0 */
} texture_level;

/* How texel coordinates beyond the image wrap, as OpenGL's wrap modes
 * (GL_REPEAT, GL_MIRRORED_REPEAT, GL_CLAMP_TO_EDGE), of texel indices. */
typedef enum texture_wrap {
    TEXTURE_REPEAT,
    TEXTURE_MIRRORED_REPEAT,
    TEXTURE_CLAMP_TO_EDGE,
} texture_wrap;

typedef struct texture {
    int level_count;
    texture_level levels[TEXTURE_MAX_LEVELS];
    texture_wrap wrap[2]; /* along u, v; zero: repeated */
} texture;

/* An image file's bytes (any format stb_image reads) decoded, with its mip
 * chain; false after "NAME: problem" on stderr (not an image, larger than
 * TEXTURE_MAX_SIZE a side, out of memory), t left empty. */
bool texture_from_memory(texture *t, const char *name, const unsigned char *bytes, size_t size);
/* The same from an image file, its lines naming it `name`. */
bool texture_load_file(texture *t, const char *name, const char *path);
/* The same from RGBA8 pixels, bottom row first (tests). */
bool texture_from_pixels(texture *t, const char *name, int width, int height, const unsigned char *rgba);
void texture_free(texture *t);

/* The level of detail of a pixel whose texture coordinates change by
 * duv_dx from its left to its right neighbour and by duv_dy from the one
 * below to the one above (not clamped: at most 0 is level 0). */
float texture_lod(const texture *t, const float duv_dx[2], const float duv_dy[2]);
/* The texture at uv (wrapped outside [0, 1]) at level of detail `lod`:
 * linear RGBA. */
void texture_sample(const texture *t, const float uv[2], float lod, float rgba[4]);

/* sRGB's transfer function, 8-bit code to linear light and back. */
float texture_srgb_to_linear(unsigned char code);
unsigned char texture_linear_to_srgb(float linear);

#endif
