/* hud: lines of text over the picture (stb_easy_font), on a dark panel so
 * they stay legible over any scene, sized for a projector.
 *
 * hud_draw wraps each line at the framebuffer's width (at spaces; a word
 * wider than the whole line is broken), continuation lines indented, so
 * nothing is cut at any size; the panel grows to fit. `scale` is how many
 * pixels one font unit takes (stb_easy_font's letters are about 6 by 8
 * units on 12-unit lines); hud_scale_for picks one from the framebuffer's
 * height, so the text is as legible from the back row at 1080 lines as at
 * 720. hud_wrap is the layout alone (no GL), for tests.
 */
#ifndef HUD_H
#define HUD_H

#include <stdbool.h>
#include <stddef.h>

/* Framebuffer lines per unit of scale: 720 lines get 2 (14-pixel
 * letters), 1080 get 3. */
#define HUD_LINES_PER_SCALE 360
#define HUD_MAX_SCALE 8
#define HUD_MARGIN 4       /* font units between the panel's edge and the text */
#define HUD_LINE_UNITS 12  /* stb_easy_font's line height, in font units */
#define HUD_LETTER_UNITS 8 /* how tall its capitals are */
#define HUD_INDENT "  "    /* what a wrapped line's continuation starts with */
/* The text's grey, of 255: white, and a dimmed line's, brighter than
 * anything the panel lets through (under two fifths of the picture
 * behind it), so legible, yet nowhere as bright as white. */
#define HUD_WHITE 255
#define HUD_DIMMED_GREY 150

/* max(1, round(height / HUD_LINES_PER_SCALE)), at most HUD_MAX_SCALE. */
int hud_scale_for(int height);
/* `text` with its lines broken so that none is wider than `width` pixels
 * at `scale` (margins included), into out (NUL-terminated, truncated to
 * size). Returns the number of lines. */
int hud_wrap(const char *text, int width, int scale, char *out, size_t size);

/* `scale` (0: hud_scale_for(framebuffer_height)), less where `text`
 * wrapped at `width` would be taller than `height` pixels (down to 1). */
int hud_scale_to_fit(const char *text, int width, int height, int scale, int framebuffer_height);

/* The widest line of `text`, in font units. */
int hud_text_width(const char *text);

bool hud_init(void);
/* Draws `text` (lines separated by '\n'), wrapped, at the top-left of the
 * viewport of the given size, `scale` pixels per font unit; 0:
 * hud_scale_to_fit(text, width, height, 0, height). Its first
 * `dimmed_lines` lines are drawn HUD_DIMMED_GREY, the rest white: a
 * caption that no longer describes the picture. */
void hud_draw(const char *text, int width, int height, int scale, int dimmed_lines);
/* The dark panel hud_draw puts behind the same `text` (the same
 * arguments), in pixels from the viewport's top-left corner: the
 * rectangle the HUD hides. No GL. */
void hud_panel_size(const char *text, int width, int height, int scale, int dimmed_lines, int *panel_width,
                    int *panel_height);
void hud_destroy(void);

#endif
