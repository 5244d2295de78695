/* image: 8-bit RGBA images (top row first) as PNG files, and the
 * comparison used by the screenshot tests.
 *
 * image_compare counts the pixels whose largest channel difference exceeds
 * `tolerance` (0..255) and, when `diff` is given, fills it with a picture
 * of where they are: matching pixels as a faded grey copy of `a`, differing
 * ones in red with brightness by the size of the difference.
 */
#ifndef IMAGE_H
#define IMAGE_H

#include <stdbool.h>
#include <stddef.h>

bool image_write_png(const char *path, int width, int height, const unsigned char *rgba);
/* The PNG file's bytes, malloc'ed (free them), their count in *size; NULL
 * after one line when out of memory. */
unsigned char *image_png_bytes(int width, int height, const unsigned char *rgba, size_t *size);
/* Returns malloc'ed pixels (free them), or NULL after printing why. */
unsigned char *image_read_png(const char *path, int *width, int *height);
long image_compare(const unsigned char *a, const unsigned char *b, int width, int height, int tolerance,
                   unsigned char *diff);

#endif
