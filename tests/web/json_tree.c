/* json_tree: prints what cJSON makes of each file named on the command
 * line, then of a tree built with cJSON's Create and Add functions and of
 * cJSON_Print's text of it, in a canonical listing: one line per item
 * (path, type, number as %.17g and valueint, string bytes), key order as
 * stored, each link checked. Built once against Debian's cJSON and once
 * with emcc against common/web/cjson_browser.c, its two outputs must be
 * the same (tests/web/check_json.sh). A file that does not parse gives
 * json_load's line (common/data/json.c): "FILE:LINE: JSON syntax error
 * ...". */
#include <cJSON.h>

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void json_tree_print_string(const char *string) {
    putchar('"');
    for (const unsigned char *c = (const unsigned char *)string; *c; c++) {
        if (*c < ' ' || *c >= 0x7f || *c == '"' || *c == '\\')
            printf("\\x%02x", *c);
        else
            putchar(*c);
    }
    putchar('"');
}

static const char *json_tree_type(const cJSON *item) {
    if (cJSON_IsNumber(item))
        return "number";
    if (cJSON_IsString(item))
        return "string";
    if (cJSON_IsArray(item))
        return "array";
    if (cJSON_IsObject(item))
        return "object";
    if (cJSON_IsBool(item))
        return cJSON_IsTrue(item) ? "true" : "false";
    return "null";
}

/* One line for item at path, then its children's. */
static void json_tree_list(const cJSON *item, const char *path) {
    printf("%s %s type=%d", path, json_tree_type(item), item->type);
    if (cJSON_IsNumber(item))
        printf(" %.17g valueint=%d", item->valuedouble, item->valueint);
    if (cJSON_IsString(item)) {
        putchar(' ');
        json_tree_print_string(item->valuestring);
    }
    if (cJSON_IsArray(item) || cJSON_IsObject(item))
        printf(" size=%d", cJSON_GetArraySize(item));
    putchar('\n');
    const cJSON *child, *previous = NULL;
    int index = 0;
    cJSON_ArrayForEach(child, item) {
        size_t size = strlen(path) + (child->string ? strlen(child->string) * 4 : 0) + 32;
        char *inner = malloc(size);
        if (!inner)
            exit(1);
        if (cJSON_IsObject(item)) {
            int used = snprintf(inner, size, "%s.", path);
            for (const unsigned char *c = (const unsigned char *)child->string; *c; c++)
                used += snprintf(inner + used, size - (size_t)used, isgraph(*c) ? "%c" : "\\x%02x", *c);
            if (cJSON_GetObjectItemCaseSensitive(item, child->string) != child)
                printf("%s: repeated key\n", inner);
        } else {
            snprintf(inner, size, "%s[%d]", path, index);
        }
        if (cJSON_GetArrayItem(item, index) != child)
            printf("%s: cJSON_GetArrayItem(%d) is another item\n", inner, index);
        if (child->prev != (previous ? previous : cJSON_GetArrayItem(item, cJSON_GetArraySize(item) - 1)))
            printf("%s: wrong prev link\n", inner);
        json_tree_list(child, inner);
        free(inner);
        previous = child;
        index++;
    }
}

/* The file's tree, or json_load's message for it. */
static void json_tree_file(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) {
        printf("%s: cannot open\n", path);
        return;
    }
    size_t capacity = 1 << 16, length = 0, got;
    char *text = malloc(capacity);
    while (text && (got = fread(text + length, 1, capacity - length, f)) > 0) {
        length += got;
        if (length == capacity)
            text = realloc(text, capacity *= 2);
    }
    fclose(f);
    if (!text)
        exit(1);
    text[length] = '\0';
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithLengthOpts(text, length + 1, &end, 1);
    if (root) {
        printf("%s: parsed, end at %ld of %zu\n", path, (long)(end - text), length);
        json_tree_list(root, "$");
        cJSON_Delete(root);
    } else {
        int line = 1;
        for (const char *c = text; c < end; c++)
            line += *c == '\n';
        if (end >= text + length)
            printf("%s:%d: JSON syntax error at the end of the file\n", path, line);
        else if (isgraph((unsigned char)*end))
            printf("%s:%d: JSON syntax error near '%c'\n", path, line, *end);
        else
            printf("%s:%d: JSON syntax error near byte 0x%02x\n", path, line, (unsigned char)*end);
    }
    free(text);
}

/* What dump.c's meta.json needs, and the numbers and strings that test
 * the printer: tiny, huge, negative zero, past int, floats, escapes. */
static void json_tree_built(void) {
    cJSON *root = cJSON_CreateObject();
    const double numbers[] = {0.1, 1e-7, 123456789, -0.0, 3, -2.5, 1e300, 2147483648.0, -3e9, 1.0 / 3, 1e21, 5e-324};
    for (int i = 0; i < (int)(sizeof numbers / sizeof *numbers); i++) {
        char key[16];
        snprintf(key, sizeof key, "%d", 9 - i);
        cJSON_AddNumberToObject(root, key, numbers[i]);
    }
    const float floats[] = {0.1f, 1e-7f, 3.4e38f, -0.0f, 16777217.0f, 0.3f, 640, 1.5f};
    cJSON_AddItemToObject(root, "floats", cJSON_CreateFloatArray(floats, sizeof floats / sizeof *floats));
    cJSON *names = cJSON_AddArrayToObject(root, "names");
    const char *strings[] = {"plain", "quote \" backslash \\ slash /", "tab\tnewline\nreturn\r\b\f\x01\x1f",
                             "caf\xc3\xa9 \xe2\x9c\x93 \xf0\x9f\x98\x80", ""};
    for (size_t i = 0; i < sizeof strings / sizeof *strings; i++)
        cJSON_AddItemToArray(names, cJSON_CreateString(strings[i]));
    cJSON *nested = cJSON_AddObjectToObject(root, "nested");
    cJSON_AddObjectToObject(nested, "empty object");
    cJSON_AddArrayToObject(nested, "empty array");
    cJSON *objects = cJSON_AddArrayToObject(nested, "objects");
    cJSON *inner = cJSON_CreateObject();
    cJSON_AddNumberToObject(inner, "x", 1);
    cJSON_AddItemToArray(objects, inner);
    cJSON_AddItemToArray(objects, cJSON_CreateObject());
    cJSON_AddNumberToObject(nested, "infinity", 1e308 * 10);
    printf("built:\n");
    json_tree_list(root, "$");
    char *text = cJSON_Print(root);
    cJSON_Delete(root);
    printf("printed:\n%s\n", text);
    cJSON *again = cJSON_Parse(text);
    free(text);
    printf("read back:\n");
    if (again)
        json_tree_list(again, "$");
    /* What dump.c reads back from its meta.json: floats. */
    const cJSON *read_floats = cJSON_GetObjectItemCaseSensitive(again, "floats");
    int same = 0;
    for (int i = 0; i < (int)(sizeof floats / sizeof *floats); i++) {
        const cJSON *number = cJSON_GetArrayItem(read_floats, i);
        same += number && (float)number->valuedouble == floats[i];
    }
    printf("floats read back as the same float: %d of %d\n", same, (int)(sizeof floats / sizeof *floats));
    cJSON_Delete(again);
    cJSON *garbage = cJSON_Parse("{\"a\": 1} trailing");
    printf("cJSON_Parse with trailing text: %s\n", garbage ? "parsed" : "refused");
    cJSON_Delete(garbage);
}

int main(int argc, char **argv) {
    for (int i = 1; i < argc; i++)
        json_tree_file(argv[i]);
    json_tree_built();
    return 0;
}
