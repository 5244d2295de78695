/* json: what the JSON file readers share (json.h). */
#include "json.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "path.h"
#include "typo.h"

/* Reports "FILE: WHERE.KEY: problem"; where may be "" and key NULL. */
bool json_fail(const char *file, const char *where, const char *key, const char *format, ...) {
    char problem[512];
    va_list args;
    va_start(args, format);
    vsnprintf(problem, sizeof problem, format, args);
    va_end(args);
    char location[256];
    snprintf(location, sizeof location, "%s%s%s", where, where[0] && key ? "." : "", key ? key : "");
    fprintf(stderr, "%s: %s%s%s\n", file, location, location[0] ? ": " : "", problem);
    return false;
}

const char *json_kind(const cJSON *item) {
    if (cJSON_IsNumber(item))
        return "a number";
    if (cJSON_IsString(item))
        return "a string";
    if (cJSON_IsArray(item))
        return "an array";
    if (cJSON_IsObject(item))
        return "an object";
    if (cJSON_IsBool(item))
        return "a boolean";
    return "null";
}

/* "a, b, c or d" */
void json_join_names(const char *const names[], char *out, size_t size) {
    size_t count = 0, used = 0;
    while (names[count])
        count++;
    out[0] = '\0';
    for (size_t i = 0; i < count && used < size; i++) {
        const char *separator = i == 0 ? "" : i + 1 == count ? " or " : ", ";
        used += (size_t)snprintf(out + used, size - used, "%s%s", separator, names[i]);
    }
}

bool json_lookup(const char *file, const cJSON *object, const char *where, const char *key, bool required,
                 const cJSON **item) {
    *item = cJSON_GetObjectItemCaseSensitive(object, key);
    if (!*item && required)
        return json_fail(file, where, key, "missing required field");
    return true;
}

/* Unknown keys are usually typos, and a repeated key hides one value. */
bool json_check_keys(const char *file, const cJSON *object, const char *where, const char *const allowed[]) {
    const cJSON *item;
    cJSON_ArrayForEach(item, object) {
        bool known = false;
        for (int i = 0; allowed[i] && !known; i++)
            known = strcmp(allowed[i], item->string) == 0;
        if (!known) {
            char expected[256], suggestion[TYPO_NAME_MAX + 32] = "";
            json_join_names(allowed, expected, sizeof expected);
            const char *near = typo_nearest(item->string, allowed);
            if (near)
                snprintf(suggestion, sizeof suggestion, ", did you mean \"%s\"?", near);
            return json_fail(file, where, NULL, "unknown key \"%s\" (expected %s)%s", item->string, expected,
                             suggestion);
        }
        if (cJSON_GetObjectItemCaseSensitive(object, item->string) != item) {
            return json_fail(file, where, item->string, "duplicate key");
        }
    }
    return true;
}

bool json_read_int(const char *file, const cJSON *object, const char *where, const char *key, int *out) {
    const cJSON *item;
    if (!json_lookup(file, object, where, key, false, &item))
        return false;
    if (!item)
        return true;
    if (!cJSON_IsNumber(item) || item->valuedouble != floor(item->valuedouble) || fabs(item->valuedouble) > INT_MAX) {
        return json_fail(file, where, key, "expected a whole number");
    }
    *out = (int)item->valuedouble;
    return true;
}

bool json_read_numbers(const char *file, const cJSON *object, const char *where, const char *key, double *out,
                       int count) {
    const cJSON *item;
    if (!json_lookup(file, object, where, key, true, &item))
        return false;
    if (!cJSON_IsArray(item) || cJSON_GetArraySize(item) != count) {
        return json_fail(file, where, key, "expected an array of %d numbers", count);
    }
    for (int i = 0; i < count; i++) {
        const cJSON *number = cJSON_GetArrayItem(item, i);
        char element[80];
        snprintf(element, sizeof element, "%s[%d]", key, i);
        if (!cJSON_IsNumber(number)) {
            return json_fail(file, where, element, "expected a number, got %s", json_kind(number));
        }
        /* cJSON turns 1e999 into infinity. */
        if (!isfinite(number->valuedouble)) {
            return json_fail(file, where, element, "must be a finite number (got %g)", number->valuedouble);
        }
        out[i] = number->valuedouble;
    }
    return true;
}

bool json_read_bool(const char *file, const cJSON *object, const char *where, const char *key, bool *out) {
    const cJSON *item;
    if (!json_lookup(file, object, where, key, false, &item))
        return false;
    if (!item)
        return true;
    if (!cJSON_IsBool(item)) {
        return json_fail(file, where, key, "expected true or false, got %s", json_kind(item));
    }
    *out = cJSON_IsTrue(item);
    return true;
}

bool json_read_string(const char *file, const cJSON *object, const char *where, const char *key, bool required,
                      const char **out) {
    const cJSON *item;
    if (!json_lookup(file, object, where, key, required, &item))
        return false;
    if (!item)
        return true;
    if (!cJSON_IsString(item) || !item->valuestring) {
        return json_fail(file, where, key, "expected a string, got %s", json_kind(item));
    }
    *out = item->valuestring;
    return true;
}

bool json_read_object(const char *file, const cJSON *object, const char *where, const char *key, const cJSON **out) {
    if (!json_lookup(file, object, where, key, true, out))
        return false;
    if (!cJSON_IsObject(*out)) {
        return json_fail(file, where, key, "expected an object, got %s", json_kind(*out));
    }
    return true;
}

static cJSON *json_parse(const char *file, const char *text, size_t length) {
    const char *error = NULL;
    /* The length counts the terminating NUL: cJSON wants it to tell the end
     * of the document from trailing garbage. */
    cJSON *root = cJSON_ParseWithLengthOpts(text, length + 1, &error, true);
    if (root)
        return root;
    if (!error)
        error = text;
    int line = 1;
    for (const char *c = text; c < error; c++)
        line += *c == '\n';
    if (error >= text + length) {
        fprintf(stderr, "%s:%d: JSON syntax error at the end of the file\n", file, line);
    } else if (isgraph((unsigned char)*error)) {
        fprintf(stderr, "%s:%d: JSON syntax error near '%c'\n", file, line, *error);
    } else {
        fprintf(stderr, "%s:%d: JSON syntax error near byte 0x%02x\n", file, line, (unsigned char)*error);
    }
    return NULL;
}

bool json_save(cJSON *root, const char *path) {
    char *text = cJSON_Print(root);
    cJSON_Delete(root);
    FILE *f = text ? fopen(path, "w") : NULL;
    bool ok = f && fputs(text, f) >= 0;
    ok = (f && fclose(f) == 0) && ok;
    if (!ok)
        fprintf(stderr, "%s: cannot write: %s\n", path, text ? strerror(errno) : "out of memory");
    free(text);
    return ok;
}

cJSON *json_load(const char *path, size_t max_size) {
    size_t length;
    char *text = path_read_text(path, max_size, &length);
    if (!text)
        return NULL;
    cJSON *root = json_parse(path, text, length);
    free(text);
    return root;
}
