#include "csv.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "path.h"

/* Splits the line at *cursor into fields, unquoting in place, and moves
 * *cursor past the line's end; returns the field count, or -1 for an
 * unterminated quote. At most CSV_MAX_COLUMNS fields are stored; more
 * are counted. */
static int csv_split_line(char **cursor, char **fields) {
    char *read = *cursor, *write = *cursor;
    int count = 0;
    for (;;) {
        if (count < CSV_MAX_COLUMNS)
            fields[count] = write;
        count++;
        if (*read == '"') {
            for (read++;; read++) {
                if (*read == '\0')
                    return -1;
                if (*read == '"' && read[1] != '"')
                    break;
                read += *read == '"';
                *write++ = *read;
            }
            read++;
        }
        while (*read && *read != ',' && *read != '\n')
            *write++ = *read++;
        char end = *read;
        if (write > *cursor && write[-1] == '\r' && end != ',')
            write--;
        *write++ = '\0';
        read += end != '\0';
        if (end != ',') {
            *cursor = read;
            return count;
        }
    }
}

bool csv_read(const char *path, csv_table *table) {
    *table = (csv_table){0};
    size_t length;
    char *text = path_read_text(path, CSV_MAX_BYTES, &length);
    if (!text)
        return false;
    int lines = 0;
    for (const char *p = text; *p; p++)
        lines += *p == '\n';
    lines += length > 0 && text[length - 1] != '\n';
    if (lines == 0) {
        fprintf(stderr, "%s: empty: expected a header line\n", path);
        free(text);
        return false;
    }
    char **cells = malloc((size_t)lines * CSV_MAX_COLUMNS * sizeof *cells);
    if (!cells) {
        fprintf(stderr, "%s: out of memory\n", path);
        free(text);
        return false;
    }
    char *cursor = text;
    int columns = 0, rows = 0;
    for (int line = 1; *cursor; line++) {
        char *fields[CSV_MAX_COLUMNS];
        int count = csv_split_line(&cursor, fields);
        const char *problem = count < 0                      ? "a quote is not closed"
                              : count > CSV_MAX_COLUMNS      ? "more fields than the most a row may have"
                              : line > 1 && count != columns ? "another field count than the header's"
                                                             : NULL;
        if (problem) {
            fprintf(stderr, "%s:%d: %s (%d fields, the header %d)\n", path, line, problem, count, columns);
            free(cells);
            free(text);
            return false;
        }
        columns = line == 1 ? count : columns;
        memcpy(cells + (size_t)rows * (size_t)columns, fields, (size_t)count * sizeof *fields);
        rows++;
    }
    *table = (csv_table){.text = text, .cells = cells, .columns = columns, .rows = rows - 1};
    return true;
}

int csv_column(const csv_table *table, const char *name) {
    for (int c = 0; c < table->columns; c++)
        if (strcmp(table->cells[c], name) == 0)
            return c;
    return -1;
}

const char *csv_cell(const csv_table *table, int row, int column) {
    return table->cells[(size_t)(row + 1) * (size_t)table->columns + (size_t)column];
}

void csv_free(csv_table *table) {
    free(table->cells);
    free(table->text);
    *table = (csv_table){0};
}
