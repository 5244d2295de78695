/* legend: the key to a picture's colours, for lectures: lines of text,
 * each with its colour swatch at the left (none for a title or a figure;
 * two side by side for a ramp's two ends), on a dark panel.
 *
 *   legend_line lines[] = {{.text = "count"}, {"1", 1, {{0.2f, 0.4f, 1}}}};
 *   legend_draw_corner(lines, 2);       over a technique's picture, or
 *   legend_draw(lines, 2, x, y, scale); at a place of the caller's
 *
 * The text is the HUD's (hud.h: the frame's owner has called hud_init),
 * the swatches scissored clears framed in grey (so that a dark colour
 * shows on the dark panel): no program of its own. Sizes are in the HUD's
 * font units, so a legend grows with the text on a projector, and a
 * swatch faces its line at any scale (the text is never wrapped: a
 * legend too wide for its place is drawn at a smaller scale, or cut).
 */
#ifndef LEGEND_H
#define LEGEND_H

#define LEGEND_TEXT_MAX 128
/* Font units of the swatch column left of the text, and of the gap
 * between them. */
#define LEGEND_SWATCH_UNITS 10
#define LEGEND_SWATCH_GAP_UNITS 2

typedef struct legend_line {
    char text[LEGEND_TEXT_MAX];
    int swatches;    /* 0, 1 or 2 (rgb[0] on the left half, rgb[1] on the right) */
    float rgb[2][3]; /* 0..1 */
} legend_line;

/* The panel's colour, for a caller that fills a larger place with it. */
extern const float legend_panel_color[3];

/* The legend's size in font units (its height: `count` lines). */
int legend_width_units(const legend_line *lines, int count);
int legend_height_units(int count);
/* The largest scale, at most hud_scale_for(framebuffer_height), at which
 * the legend fits width x height pixels; 0 if it fits at none. */
int legend_scale_to_fit(const legend_line *lines, int count, int width, int height, int framebuffer_height);

/* Draws the legend with its top-left corner at (x, y), pixels from the
 * top-left of the bound framebuffer's viewport, `scale` pixels per font
 * unit. Leaves blending, scissor and the depth and stencil tests off and
 * the viewport as it found it. */
void legend_draw(const legend_line *lines, int count, int x, int y, int scale);
/* In the viewport's bottom-right corner, at the HUD's scale for its
 * height (less where that would not fit; at 1, cut, where nothing does). */
void legend_draw_corner(const legend_line *lines, int count);

#endif
