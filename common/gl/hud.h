/* hud: lines of text over the picture (stb_easy_font), on a dark panel so
 * they stay legible over any scene. Shown in the window only: headless
 * screenshots carry no text, since frame times would make them differ.
 */
#ifndef HUD_H
#define HUD_H

#include <stdbool.h>

bool hud_init(void);
/* Draws `text` (lines separated by '\n') at the top-left of the bound
 * framebuffer of the given size. */
void hud_draw(const char *text, int width, int height);
void hud_destroy(void);

#endif
