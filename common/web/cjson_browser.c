/* cjson_browser: the part of cJSON's API that the suite's JSON readers use
 * (common/data/json.c, scene.c, tour.c, dump.c), for the web build only,
 * where Debian's cJSON library is not available. It compiles against
 * cJSON's own header and builds trees of its layout: siblings linked by
 * next and prev, the first child's prev at the last, object keys in the
 * file's order, valueint the double saturated to int, everything freed by
 * cJSON_Delete (malloc and free).
 *
 * The browser's JSON does the values: JSON.parse decodes every string and
 * number, JSON.stringify quotes every string cJSON_Print writes. The walk
 * over braces, brackets, colons and commas is done here in cJSON's manner,
 * so that a repeated key stays in the tree (json_check_keys still reports
 * it), keys keep their order even when they look like integers (a
 * JavaScript object would put those first), and a syntax error points
 * where cJSON's would (JSON.parse's messages differ between browsers, and
 * some give no position).
 *
 * Where it differs from cJSON: it is stricter where JSON.parse is, so a
 * number with a leading zero ("01"), a raw control character inside a
 * string or a \u escape without four hex digits is a syntax error, at the
 * token's start (cJSON reads them); invalid UTF-8 inside a string becomes
 * U+FFFD (cJSON keeps the bytes). */
#include <cJSON.h>

#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <emscripten.h>

/* JSON.parse of the string token [token, token + length), written as
 * UTF-8 into out (capacity bytes, NUL included). Returns the bytes
 * written, or -1 if the token is not a JSON string or holds a lone
 * surrogate (which has no UTF-8, and which cJSON refuses). */
EM_JS(int, cjson_browser_decode_string, (const char *token, int length, char *out, int capacity), {
    var text;
    try {
        text = JSON.parse(new TextDecoder().decode(HEAPU8.subarray(token, token + length)));
    } catch (error) {
        return -1;
    }
    var lone = new RegExp("[\\uD800-\\uDBFF](?![\\uDC00-\\uDFFF])|(?:^|[^\\uD800-\\uDBFF])[\\uDC00-\\uDFFF]");
    if (lone.test(text))
        return -1;
    return stringToUTF8(text, out, capacity);
});

/* JSON.parse of the number token [token, token + length), or NaN if the
 * token is not a JSON number. */
EM_JS(double, cjson_browser_decode_number, (const char *token, int length), {
    try {
        return JSON.parse(UTF8ToString(token, length));
    } catch (error) {
        return NaN;
    }
});

/* JSON.stringify of the UTF-8 string [string, string + length), into out
 * (capacity bytes, NUL included). */
EM_JS(void, cjson_browser_quote, (const char *string, int length, char *out, int capacity), {
    var text = new TextDecoder().decode(HEAPU8.subarray(string, string + length));
    stringToUTF8(JSON.stringify(text), out, capacity);
});

/* The text being parsed: length counts what the caller allows, a
 * terminating NUL included when it passes one. */
typedef struct {
    const unsigned char *text;
    size_t length;
    size_t offset;
    int depth;
} cjson_browser_reader;

static bool cjson_browser_parse_value(cjson_browser_reader *r, cJSON *item);

static cJSON *cjson_browser_new(int type) {
    cJSON *item = calloc(1, sizeof *item);
    if (item)
        item->type = type;
    return item;
}

static int cjson_browser_saturate(double number) {
    if (number >= INT_MAX)
        return INT_MAX;
    if (number <= (double)INT_MIN)
        return INT_MIN;
    return (int)number;
}

/* Appends item to parent's children, keeping the first child's prev at
 * the last one as cJSON does. */
static void cjson_browser_append(cJSON *parent, cJSON *item) {
    cJSON *first = parent->child;
    if (!first) {
        parent->child = item;
        item->prev = item;
        return;
    }
    first->prev->next = item;
    item->prev = first->prev;
    first->prev = item;
}

/* Whitespace as cJSON skips it: every byte up to the space. At the end
 * the offset stays on the last byte. */
static void cjson_browser_skip(cjson_browser_reader *r) {
    while (r->offset < r->length && r->text[r->offset] <= ' ')
        r->offset++;
    if (r->offset == r->length && r->offset > 0)
        r->offset--;
}

static bool cjson_browser_at(const cjson_browser_reader *r, char c) {
    return r->offset < r->length && r->text[r->offset] == (unsigned char)c;
}

/* The string token at the offset into *out. On failure the offset is one
 * byte past where the token starts, as cJSON leaves it (a missing key's
 * error points past the offending byte). */
static bool cjson_browser_parse_string(cjson_browser_reader *r, char **out) {
    size_t start = r->offset, end = start + 1;
    r->offset = start + 1;
    if (start >= r->length || r->text[start] != '"')
        return false;
    while (end < r->length && r->text[end] != '"')
        end += r->text[end] == '\\' ? 2 : 1;
    if (end >= r->length)
        return false;
    int length = (int)(end + 1 - start);
    /* A byte of the token becomes at most three of UTF-8 (U+FFFD). */
    char *string = malloc(3 * (size_t)length + 1);
    if (!string)
        return false;
    int written = cjson_browser_decode_string((const char *)r->text + start, length, string, 3 * length + 1);
    if (written < 0) {
        free(string);
        return false;
    }
    char *shrunk = realloc(string, (size_t)written + 1);
    *out = shrunk ? shrunk : string;
    r->offset = end + 1;
    return true;
}

/* The number token at the offset: the bytes cJSON hands to strtod. */
static bool cjson_browser_parse_number(cjson_browser_reader *r, cJSON *item) {
    size_t end = r->offset;
    while (end < r->length && r->text[end] && strchr("0123456789+-.eE", r->text[end]))
        end++;
    double number = cjson_browser_decode_number((const char *)r->text + r->offset, (int)(end - r->offset));
    if (isnan(number))
        return false;
    item->type = cJSON_Number;
    item->valuedouble = number;
    item->valueint = cjson_browser_saturate(number);
    r->offset = end;
    return true;
}

/* An array or an object (close ']' or '}') at the offset. On failure the
 * offset is where cJSON stops: on the offending byte. */
static bool cjson_browser_parse_children(cjson_browser_reader *r, cJSON *item, char close) {
    if (r->depth >= CJSON_NESTING_LIMIT)
        return false;
    r->depth++;
    item->type = close == ']' ? cJSON_Array : cJSON_Object;
    r->offset++;
    cjson_browser_skip(r);
    if (cjson_browser_at(r, close)) {
        r->offset++;
        r->depth--;
        return true;
    }
    for (;;) {
        cJSON *child = cjson_browser_new(cJSON_NULL);
        if (!child)
            return false;
        cjson_browser_append(item, child);
        if (close == '}') {
            if (!cjson_browser_parse_string(r, &child->string))
                return false;
            cjson_browser_skip(r);
            if (!cjson_browser_at(r, ':'))
                return false;
            r->offset++;
            cjson_browser_skip(r);
        }
        if (!cjson_browser_parse_value(r, child))
            return false;
        cjson_browser_skip(r);
        if (!cjson_browser_at(r, ','))
            break;
        r->offset++;
        cjson_browser_skip(r);
    }
    if (!cjson_browser_at(r, close))
        return false;
    r->offset++;
    r->depth--;
    return true;
}

static bool cjson_browser_parse_value(cjson_browser_reader *r, cJSON *item) {
    static const struct {
        const char *word;
        int type;
    } words[] = {{"null", cJSON_NULL}, {"false", cJSON_False}, {"true", cJSON_True}};
    for (size_t i = 0; i < sizeof words / sizeof *words; i++) {
        size_t size = strlen(words[i].word);
        if (r->offset + size <= r->length && memcmp(r->text + r->offset, words[i].word, size) == 0) {
            item->type = words[i].type;
            item->valueint = words[i].type == cJSON_True;
            r->offset += size;
            return true;
        }
    }
    if (r->offset >= r->length)
        return false;
    unsigned char c = r->text[r->offset];
    if (c == '"') {
        item->type = cJSON_String;
        return cjson_browser_parse_string(r, &item->valuestring);
    }
    if (c == '-' || (c >= '0' && c <= '9'))
        return cjson_browser_parse_number(r, item);
    if (c == '[')
        return cjson_browser_parse_children(r, item, ']');
    if (c == '{')
        return cjson_browser_parse_children(r, item, '}');
    return false;
}

cJSON *cJSON_ParseWithLengthOpts(const char *value, size_t buffer_length, const char **return_parse_end,
                                 cJSON_bool require_null_terminated) {
    if (!value)
        return NULL;
    cjson_browser_reader r = {(const unsigned char *)value, buffer_length, 0, 0};
    cJSON *item = buffer_length ? cjson_browser_new(cJSON_NULL) : NULL;
    bool ok = item != NULL;
    if (ok && buffer_length > 4 && memcmp(value, "\xEF\xBB\xBF", 3) == 0)
        r.offset = 3;
    if (ok) {
        cjson_browser_skip(&r);
        ok = cjson_browser_parse_value(&r, item);
    }
    if (ok && require_null_terminated) {
        cjson_browser_skip(&r);
        ok = r.offset < r.length && r.text[r.offset] == '\0';
    }
    if (!ok) {
        cJSON_Delete(item);
        item = NULL;
        if (r.offset >= r.length && r.length > 0)
            r.offset = r.length - 1;
    }
    if (return_parse_end)
        *return_parse_end = value + r.offset;
    return item;
}

cJSON *cJSON_Parse(const char *value) {
    return value ? cJSON_ParseWithLengthOpts(value, strlen(value) + 1, NULL, false) : NULL;
}

void cJSON_Delete(cJSON *item) {
    while (item) {
        cJSON *next = item->next;
        if (!(item->type & cJSON_IsReference)) {
            cJSON_Delete(item->child);
            free(item->valuestring);
        }
        if (!(item->type & cJSON_StringIsConst))
            free(item->string);
        free(item);
        item = next;
    }
}

int cJSON_GetArraySize(const cJSON *array) {
    int size = 0;
    for (const cJSON *child = array ? array->child : NULL; child; child = child->next)
        size++;
    return size;
}

cJSON *cJSON_GetArrayItem(const cJSON *array, int index) {
    cJSON *child = array && index >= 0 ? array->child : NULL;
    while (child && index-- > 0)
        child = child->next;
    return child;
}

cJSON *cJSON_GetObjectItemCaseSensitive(const cJSON *const object, const char *const string) {
    cJSON *child = object && string ? object->child : NULL;
    while (child && child->string && strcmp(child->string, string) != 0)
        child = child->next;
    return child && child->string ? child : NULL;
}

cJSON_bool cJSON_IsBool(const cJSON *const item) { return item && (item->type & (cJSON_True | cJSON_False)); }
cJSON_bool cJSON_IsTrue(const cJSON *const item) { return item && (item->type & 0xFF) == cJSON_True; }
cJSON_bool cJSON_IsNumber(const cJSON *const item) { return item && (item->type & 0xFF) == cJSON_Number; }
cJSON_bool cJSON_IsString(const cJSON *const item) { return item && (item->type & 0xFF) == cJSON_String; }
cJSON_bool cJSON_IsArray(const cJSON *const item) { return item && (item->type & 0xFF) == cJSON_Array; }
cJSON_bool cJSON_IsObject(const cJSON *const item) { return item && (item->type & 0xFF) == cJSON_Object; }

cJSON *cJSON_CreateObject(void) { return cjson_browser_new(cJSON_Object); }

cJSON *cJSON_CreateString(const char *string) {
    cJSON *item = string ? cjson_browser_new(cJSON_String) : NULL;
    if (item && !(item->valuestring = strdup(string))) {
        free(item);
        return NULL;
    }
    return item;
}

static cJSON *cjson_browser_number(double number) {
    cJSON *item = cjson_browser_new(cJSON_Number);
    if (item) {
        item->valuedouble = number;
        item->valueint = cjson_browser_saturate(number);
    }
    return item;
}

cJSON *cJSON_CreateFloatArray(const float *numbers, int count) {
    if (!numbers || count < 0)
        return NULL;
    cJSON *array = cjson_browser_new(cJSON_Array);
    for (int i = 0; array && i < count; i++) {
        cJSON *number = cjson_browser_number(numbers[i]);
        if (!number) {
            cJSON_Delete(array);
            return NULL;
        }
        cjson_browser_append(array, number);
    }
    return array;
}

cJSON_bool cJSON_AddItemToArray(cJSON *array, cJSON *item) {
    if (!array || !item || array == item)
        return false;
    cjson_browser_append(array, item);
    return true;
}

cJSON_bool cJSON_AddItemToObject(cJSON *object, const char *string, cJSON *item) {
    if (!object || !string || !item || object == item)
        return false;
    char *key = strdup(string);
    if (!key)
        return false;
    if (!(item->type & cJSON_StringIsConst))
        free(item->string);
    item->string = key;
    item->type &= ~cJSON_StringIsConst;
    cjson_browser_append(object, item);
    return true;
}

/* Adds item under name, or deletes it and returns NULL. */
static cJSON *cjson_browser_add(cJSON *object, const char *name, cJSON *item) {
    if (cJSON_AddItemToObject(object, name, item))
        return item;
    cJSON_Delete(item);
    return NULL;
}

cJSON *cJSON_AddNumberToObject(cJSON *const object, const char *const name, const double number) {
    return cjson_browser_add(object, name, cjson_browser_number(number));
}

cJSON *cJSON_AddArrayToObject(cJSON *const object, const char *const name) {
    return cjson_browser_add(object, name, cjson_browser_new(cJSON_Array));
}

cJSON *cJSON_AddObjectToObject(cJSON *const object, const char *const name) {
    return cjson_browser_add(object, name, cjson_browser_new(cJSON_Object));
}

static void cjson_browser_print_string(FILE *out, const char *string) {
    size_t length = strlen(string);
    /* A byte becomes at most six ("\u001f"); two quotes and the NUL. */
    char *quoted = malloc(6 * length + 3);
    if (!quoted) {
        fputs("\"\"", out);
        return;
    }
    cjson_browser_quote(string, (int)length, quoted, (int)(6 * length + 3));
    fputs(quoted, out);
    free(quoted);
}

/* A number as cJSON prints it, so that a dump's meta.json is the same
 * text natively and on the web: fifteen digits when they read back within
 * a rounding step of the double, else seventeen; null for an infinity or
 * NaN. */
static void cjson_browser_print_number(FILE *out, const cJSON *item) {
    double number = item->valuedouble;
    if (!isfinite(number)) {
        fputs("null", out);
        return;
    }
    char text[32];
    snprintf(text, sizeof text, "%1.15g", number);
    double back = strtod(text, NULL);
    if (fabs(back - number) > fmax(fabs(back), fabs(number)) * DBL_EPSILON)
        snprintf(text, sizeof text, "%1.17g", number);
    fputs(text, out);
}

/* cJSON's formatted layout: an object's members one per line, indented by
 * tabs, "key":<tab>value; an array's elements on one line, ", " apart. */
static void cjson_browser_print_value(FILE *out, const cJSON *item, int depth) {
    switch (item->type & 0xFF) {
    case cJSON_False: fputs("false", out); break;
    case cJSON_True: fputs("true", out); break;
    case cJSON_Number: cjson_browser_print_number(out, item); break;
    case cJSON_String: cjson_browser_print_string(out, item->valuestring ? item->valuestring : ""); break;
    case cJSON_Array:
        fputc('[', out);
        for (const cJSON *child = item->child; child; child = child->next) {
            cjson_browser_print_value(out, child, depth + 1);
            if (child->next)
                fputs(", ", out);
        }
        fputc(']', out);
        break;
    case cJSON_Object:
        fputs("{\n", out);
        for (const cJSON *child = item->child; child; child = child->next) {
            for (int i = 0; i <= depth; i++)
                fputc('\t', out);
            cjson_browser_print_string(out, child->string ? child->string : "");
            fputs(":\t", out);
            cjson_browser_print_value(out, child, depth + 1);
            fputs(child->next ? ",\n" : "\n", out);
        }
        for (int i = 0; i < depth; i++)
            fputc('\t', out);
        fputc('}', out);
        break;
    default: fputs("null", out); break;
    }
}

char *cJSON_Print(const cJSON *item) {
    if (!item)
        return NULL;
    char *text = NULL;
    size_t size = 0;
    FILE *out = open_memstream(&text, &size);
    if (!out)
        return NULL;
    cjson_browser_print_value(out, item, 0);
    if (fclose(out) != 0) {
        free(text);
        return NULL;
    }
    return text;
}
