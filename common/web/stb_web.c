/* The web build's stb_image and stb_image_write: natively Debian's libstb
 * links them; for the page their implementations are compiled here from
 * Debian's same headers. */
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
