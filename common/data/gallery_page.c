#include "gallery_page.h"

#include <errno.h>
#include <limits.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

void gallery_page_text(FILE *f, const char *text) {
    for (const char *c = text; *c; c++) {
        switch (*c) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        default: fputc(*c, f);
        }
    }
}

static void gallery_page_image(FILE *f, const char *file, const char *caption) {
    fputs("<figure><img src=\"", f);
    gallery_page_text(f, file);
    fputs("\" alt=\"", f);
    gallery_page_text(f, caption);
    fputs("\"><figcaption>", f);
    gallery_page_text(f, caption);
    fputs("</figcaption></figure>", f);
}

/* A section's anchor: its picture's file name without ".png". */
static void gallery_page_anchor(FILE *f, const gallery_page_row *r) {
    size_t n = strcspn(r->picture, ".");
    char stem[GALLERY_PAGE_NAME_MAX];
    snprintf(stem, sizeof stem, "%.*s", (int)n, r->picture);
    gallery_page_text(f, stem);
}

/* Whether rows[i] is the first of rows[0..i] whose `field` (an offset of
 * one of the row's names) is the same. */
static bool gallery_page_first(const gallery_page_row *rows, int i, size_t field) {
    for (int j = 0; j < i; j++)
        if (strcmp((const char *)&rows[j] + field, (const char *)&rows[i] + field) == 0)
            return false;
    return true;
}

/* The summary: a row per technique, a column per scene, each cell the
 * figures of the technique's measured picture of the scene with no flags,
 * linking to its section ("-" where there is none). */
static void gallery_page_summary(FILE *f, const gallery_page_row *rows, int count) {
    const size_t technique = offsetof(gallery_page_row, technique), scene = offsetof(gallery_page_row, scene);
    fputs("<table class=\"summary\"><tr><th>misclassified % / MAE</th>", f);
    for (int s = 0; s < count; s++)
        if (gallery_page_first(rows, s, scene)) {
            fputs("<th>", f);
            gallery_page_text(f, rows[s].scene);
            fputs("</th>", f);
        }
    fputs("</tr>\n", f);
    for (int t = 0; t < count; t++) {
        if (!gallery_page_first(rows, t, technique))
            continue;
        fputs("<tr><th>", f);
        gallery_page_text(f, rows[t].technique);
        fputs("</th>", f);
        for (int s = 0; s < count; s++) {
            if (!gallery_page_first(rows, s, scene))
                continue;
            const gallery_page_row *found = NULL;
            for (int i = 0; i < count && !found; i++)
                if (rows[i].measured && !rows[i].flags[0] && strcmp(rows[i].technique, rows[t].technique) == 0 &&
                    strcmp(rows[i].scene, rows[s].scene) == 0)
                    found = &rows[i];
            if (!found) {
                fputs("<td>-</td>", f);
                continue;
            }
            fputs("<td><a href=\"#", f);
            gallery_page_anchor(f, found);
            fprintf(f, "\">%.4f %% / %.5f</a></td>", found->misclassified_percent, found->mean_abs_error);
        }
        fputs("</tr>\n", f);
    }
    fputs("</table>\n", f);
}

bool gallery_page_write(const char *dir, const gallery_page_row *rows, int count, const gallery_page_key *key,
                        int key_count, const char *heatmap_note) {
    char path[PATH_MAX];
    snprintf(path, sizeof path, "%s/index.html", dir);
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "%s: cannot write: %s\n", path, strerror(errno));
        return false;
    }
    fputs("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>Shadows: the gallery</title>\n"
          "<style>body{font-family:sans-serif;background:#15171c;color:#e8e8e8;margin:1em}"
          "section{margin:0 0 2em}h2{font-size:1.1em;margin:.4em 0}"
          "figure{display:inline-block;margin:0 .5em .5em 0;vertical-align:top}"
          "img{width:32em;max-width:30vw;display:block}figcaption{font-size:.85em;color:#aaa}"
          "table.figures{border-collapse:collapse;margin:.2em 0}"
          "table.figures td{padding:0 1em 0 0;white-space:nowrap}"
          "table.summary{border-collapse:collapse;margin:0 0 1.5em}"
          "table.summary th,table.summary td{padding:.2em .8em;border:1px solid #444;text-align:left}"
          "a{color:#9cf}"
          ".key span{display:inline-block;width:1em;height:1em;border:1px solid #999;vertical-align:middle;"
          "margin:0 .3em 0 1em}</style></head>\n<body>\n<h1>Shadows: the gallery</h1>\n"
          "<p>Each technique's picture beside the ray-traced reference of the same view and shadowdiff's heat "
          "map of its errors, with its figures for light 0.</p>\n<p class=\"key\">The heat map:",
          f);
    for (int k = 0; k < key_count; k++) {
        fprintf(f, "<span style=\"background:#%02x%02x%02x\"></span>", key[k].rgb[0], key[k].rgb[1], key[k].rgb[2]);
        gallery_page_text(f, key[k].name);
    }
    if (heatmap_note) {
        fputs("; ", f);
        gallery_page_text(f, heatmap_note);
    }
    fputs("</p>\n", f);
    gallery_page_summary(f, rows, count);
    for (int i = 0; i < count; i++) {
        const gallery_page_row *r = &rows[i];
        fputs("<section id=\"", f);
        gallery_page_anchor(f, r);
        fputs("\"><h2>", f);
        gallery_page_text(f, r->technique);
        fputs(" on ", f);
        gallery_page_text(f, r->scene);
        if (r->flags[0]) {
            fputs(" <code>", f);
            gallery_page_text(f, r->flags);
            fputs("</code>", f);
        }
        fputs("</h2>\n", f);
        if (r->measured) {
            fprintf(f,
                    "<table class=\"figures\"><tr><td>misclassified %.4f %%</td><td>mean absolute error %.5f</td>"
                    "<td>%ld pixels compared</td>",
                    r->misclassified_percent, r->mean_abs_error, r->compared);
            if (r->figure_count > 0) /* the further figures on a row of their own */
                fputs("</tr><tr>", f);
            for (int k = 0; k < r->figure_count; k++) {
                fputs("<td>", f);
                gallery_page_text(f, r->figures[k]);
                fputs("</td>", f);
            }
            fputs("</tr></table>\n", f);
        } else
            fputs("<p>a lecture picture: its overlays are drawn over the decisions, so it is not measured</p>\n", f);
        gallery_page_image(f, r->picture, r->technique);
        gallery_page_image(f, r->reference, "reference (ray traced)");
        if (r->measured)
            gallery_page_image(f, r->heatmap, "heat map");
        fputs("\n</section>\n", f);
    }
    fputs("</body></html>\n", f);
    if (ferror(f) | (fclose(f) != 0)) {
        fprintf(stderr, "%s: cannot write: %s\n", path, strerror(errno));
        return false;
    }
    printf("%s\n", path);
    return true;
}
