/* csv: a comma-separated table with a header row, read whole (the
 * bench's results.csv). A field may be quoted ("a, b"; "" inside is one
 * quote); lines end in \n or \r\n; a last line without \n counts.
 *
 * csv_read fails, after printing one line "PATH: problem" or "PATH:LINE:
 * problem" (unreadable, empty, an unterminated quote, a row with another
 * field count than the header), and leaves nothing to free.
 */
#ifndef CSV_H
#define CSV_H

#include <stdbool.h>
#include <stddef.h>

/* The largest file and the most fields a row csv_read takes. */
#define CSV_MAX_BYTES (16 << 20)
#define CSV_MAX_COLUMNS 64

typedef struct csv_table {
    char *text;        /* the file, split in place into the cells */
    char **cells;      /* row r's column c: cells[r * columns + c]; row 0 the header */
    int columns, rows; /* rows without the header */
} csv_table;

bool csv_read(const char *path, csv_table *table);
/* The index of the header's column `name`, or -1. */
int csv_column(const csv_table *table, const char *name);
/* Row r's (0: the first after the header) cell in `column`. */
const char *csv_cell(const csv_table *table, int row, int column);
void csv_free(csv_table *table);

#endif
