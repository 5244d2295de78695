#include "image.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stb_image.h>
#include <stb_image_write.h>

bool image_write_png(const char *path, int width, int height, const unsigned char *rgba) {
    if (!stbi_write_png(path, width, height, 4, rgba, width * 4)) {
        fprintf(stderr, "%s: cannot write PNG: %s\n", path, errno ? strerror(errno) : "stb_image_write failed");
        return false;
    }
    return true;
}

/* stb_image_write's output, gathered. */
typedef struct image_bytes {
    unsigned char *data;
    size_t size;
    bool out_of_memory;
} image_bytes;

static void image_append(void *context, void *data, int size) {
    image_bytes *b = context;
    unsigned char *grown = b->out_of_memory ? NULL : realloc(b->data, b->size + (size_t)size);
    if (!grown) {
        b->out_of_memory = true;
        return;
    }
    memcpy(grown + b->size, data, (size_t)size);
    b->data = grown;
    b->size += (size_t)size;
}

unsigned char *image_png_bytes(int width, int height, const unsigned char *rgba, size_t *size) {
    image_bytes b = {0};
    if (!stbi_write_png_to_func(image_append, &b, width, height, 4, rgba, width * 4) || b.out_of_memory) {
        fprintf(stderr, "image: out of memory for a %dx%d PNG\n", width, height);
        free(b.data);
        return NULL;
    }
    *size = b.size;
    return b.data;
}

unsigned char *image_read_png(const char *path, int *width, int *height) {
    int channels;
    unsigned char *rgba = stbi_load(path, width, height, &channels, 4);
    if (!rgba)
        fprintf(stderr, "%s: cannot read image: %s\n", path, stbi_failure_reason());
    return rgba;
}

long image_compare(const unsigned char *a, const unsigned char *b, int width, int height, int tolerance,
                   unsigned char *diff) {
    long over = 0;
    for (long i = 0; i < (long)width * height; i++) {
        int worst = 0;
        for (int c = 0; c < 3; c++) {
            int d = abs(a[i * 4 + c] - b[i * 4 + c]);
            worst = d > worst ? d : worst;
        }
        over += worst > tolerance;
        if (diff) {
            unsigned char grey = (unsigned char)((a[i * 4] + a[i * 4 + 1] + a[i * 4 + 2]) / 12 + 32);
            bool bad = worst > tolerance;
            diff[i * 4 + 0] = bad ? (unsigned char)(128 + worst / 2) : grey;
            diff[i * 4 + 1] = bad ? 0 : grey;
            diff[i * 4 + 2] = bad ? 0 : grey;
            diff[i * 4 + 3] = 255;
        }
    }
    return over;
}
