/* gallery_page: the gallery's index.html: a summary table (a row per
 * technique, a column per scene: each measured picture's misclassified %
 * and MAE, linking to its section), then one section per picture: what made
 * it (technique, flags, scene), its figures against the ray-traced
 * reference (shadowdiff's: misclassified %, mean absolute error, pixels
 * compared, then the caller's further figures as text: each class's MAE
 * and pixels), and the picture beside the reference's and the heat map,
 * under a key to the heat map's colours (the caller's: shadowdiff's one
 * definition, which this data layer does not see). Pictures are named relative to the
 * page, which lives in the same directory. Plain HTML and CSS: it opens
 * from the file system in any browser, nothing loaded from elsewhere.
 */
#ifndef GALLERY_PAGE_H
#define GALLERY_PAGE_H

#include <stdbool.h>
#include <stdio.h>

#define GALLERY_PAGE_NAME_MAX 256
/* Further figures of a row: how many at most, and room for each one's
 * text. */
#define GALLERY_PAGE_MAX_FIGURES 4
#define GALLERY_PAGE_FIGURE_MAX 64

typedef struct gallery_page_row {
    char technique[GALLERY_PAGE_NAME_MAX], flags[GALLERY_PAGE_NAME_MAX], scene[GALLERY_PAGE_NAME_MAX];
    char picture[GALLERY_PAGE_NAME_MAX], reference[GALLERY_PAGE_NAME_MAX], heatmap[GALLERY_PAGE_NAME_MAX];
    bool measured; /* else the figures and the heat map are left out (a lecture picture's overlays) */
    double misclassified_percent, mean_abs_error;
    long compared;
    char figures[GALLERY_PAGE_MAX_FIGURES][GALLERY_PAGE_FIGURE_MAX]; /* each a cell, on a row below those */
    int figure_count;
} gallery_page_row;

/* A line of the heat map's key: what a colour means. */
typedef struct gallery_page_key {
    const char *name;
    unsigned char rgb[3];
} gallery_page_key;

/* text with &, <, > and " escaped, as HTML wants in content and
 * attributes (the report's page writes with it too). */
void gallery_page_text(FILE *f, const char *text);

/* Writes DIR/index.html, the key followed by `heatmap_note` (how the
 * heat maps are drawn; may be NULL); false after printing why. */
bool gallery_page_write(const char *dir, const gallery_page_row *rows, int count, const gallery_page_key *key,
                        int key_count, const char *heatmap_note);

#endif
