#include "flags.h"

#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "typo.h"

#define FLAGS_MAX_SIZE 16384
#define FLAGS_NAME_MAX 64   /* a flag as typed, before any '=' */
#define FLAGS_LINE_MAX 1024 /* an error line; a flag's text in --help */
/* The widest flag text that keeps its help on its own line in --help;
 * wider ones (long choice lists) put the help on the next. */
#define FLAGS_HELP_WIDTH 32

const char *flags_program_name(const char *argv0) {
    const char *slash = strrchr(argv0, '/');
    return slash ? slash + 1 : argv0;
}

/* One line, written at once: "program: MESSAGE (see --help)". */
static int flags_error(const char *program, const char *format, ...) {
    char message[FLAGS_LINE_MAX];
    va_list args;
    va_start(args, format);
    vsnprintf(message, sizeof message, format, args);
    va_end(args);
    fprintf(stderr, "%s: %s (see --help)\n", program, message);
    return FLAGS_EXIT_USAGE;
}

int flags_usage_error(const char *program, const char *message, const char *value) {
    return value ? flags_error(program, "%s '%s'", message, value) : flags_error(program, "%s", message);
}

/* A whole decimal integer in [min, max]. */
static bool flags_parse_int(const char *text, int min, int max, int *out) {
    char *end;
    errno = 0;
    long v = strtol(text, &end, 10);
    if (errno || end == text || *end != '\0' || v < min || v > max)
        return false;
    *out = (int)v;
    return true;
}

/* "WxH", each 1..FLAGS_MAX_SIZE. */
static bool flags_parse_size(const char *text, int *width, int *height) {
    char w[16], h[16];
    const char *x = strchr(text, 'x');
    if (!x || x - text >= (long)sizeof w || strlen(x + 1) >= sizeof h)
        return false;
    snprintf(w, sizeof w, "%.*s", (int)(x - text), text);
    snprintf(h, sizeof h, "%s", x + 1);
    return flags_parse_int(w, 1, FLAGS_MAX_SIZE, width) && flags_parse_int(h, 1, FLAGS_MAX_SIZE, height);
}

static void flags_join(const char *const *choices, const char *separator, char *out, size_t size) {
    size_t n = 0;
    out[0] = '\0';
    for (int c = 0; choices[c] && n < size; c++)
        n += (size_t)snprintf(out + n, size - n, "%s%s", c ? separator : "", choices[c]);
}

/* Whether the typed flag names p: "--no-NAME" for a toggle, "--NAME"
 * otherwise, and -h for help. */
static bool flags_names(const flags_param *p, const char *flag) {
    if (p->kind == FLAGS_HELP && strcmp(flag, "-h") == 0)
        return true;
    if (!p->name || strncmp(flag, "--", 2) != 0)
        return false;
    flag += 2;
    if (p->kind == FLAGS_TOGGLE && strncmp(flag, "no-", 3) != 0)
        return false;
    return strcmp(p->kind == FLAGS_TOGGLE ? flag + 3 : flag, p->name) == 0;
}

/* Whether text is a name, then `ending` in any case. */
static bool flags_ends_with(const char *text, const char *ending) {
    size_t n = strlen(text), k = strlen(ending);
    return n > k && strcasecmp(text + n - k, ending) == 0;
}

static bool flags_takes_value(flags_kind kind) {
    return kind == FLAGS_CHOICE || kind == FLAGS_NUMBER || kind == FLAGS_INT || kind == FLAGS_SIZE ||
           kind == FLAGS_STRING;
}

/* Sets a flag that takes no value or one value; 0 or the usage error. */
static int flags_set(const char *program, const flags_param *p, const char *value) {
    char *end;
    switch (p->kind) {
    case FLAGS_TOGGLE: *p->disabled = true; return 0;
    case FLAGS_SWITCH: *p->on = true; return 0;
    case FLAGS_STRING:
        if (p->extension && !flags_ends_with(value, p->extension))
            return flags_error(program, "--%s: expected a file name ending in %s, got '%s'", p->name, p->extension,
                               value);
        *p->text = value;
        return 0;
    case FLAGS_NUMBER: {
        float v = strtof(value, &end);
        if (end != value && *end == '\0' && v >= p->min && v <= p->max) {
            *p->number = v;
            return 0;
        }
        return flags_error(program, "--%s: expected a number in %g..%g, got '%s'", p->name, p->min, p->max, value);
    }
    case FLAGS_INT:
        if (flags_parse_int(value, (int)p->min, (int)p->max, p->integer))
            return 0;
        return flags_error(program, "--%s: expected %s %d..%d, got '%s'", p->name,
                           p->what ? p->what : "a whole number", (int)p->min, (int)p->max, value);
    case FLAGS_SIZE:
        if (flags_parse_size(value, p->width, p->height))
            return 0;
        return flags_error(program, "--%s: expected WxH, each 1..%d, got '%s'", p->name, FLAGS_MAX_SIZE, value);
    case FLAGS_CHOICE: /* flags_set_choice, which sees every table's */
    case FLAGS_LIST:   /* flags_parse fills lists itself */
    case FLAGS_HELP: break;
    }
    return 0;
}

/* "--NAME: " for a named list, "" for the positional arguments. */
static void flags_list_prefix(const flags_param *p, char *out, size_t size) {
    if (p->name)
        snprintf(out, size, "--%s: ", p->name);
    else
        out[0] = '\0';
}

static int flags_add(const char *program, const flags_param *p, const char *item) {
    char prefix[FLAGS_NAME_MAX + 4];
    flags_list_prefix(p, prefix, sizeof prefix);
    if (*p->count >= (int)p->max)
        return flags_error(program, "%sexpected %s, got also '%s'", prefix, p->what, item);
    p->items[(*p->count)++] = item;
    return 0;
}

static int flags_check_list(const char *program, const flags_param *p) {
    char prefix[FLAGS_NAME_MAX + 4];
    flags_list_prefix(p, prefix, sizeof prefix);
    return *p->count < (int)p->min ? flags_error(program, "%sexpected %s", prefix, p->what) : 0;
}

static const flags_param *flags_find(const flags_param *params, int count, const char *flag) {
    for (int k = 0; k < count; k++)
        if (flag ? flags_names(&params[k], flag) : !params[k].name && params[k].kind == FLAGS_LIST)
            return &params[k];
    return NULL;
}

/* The table's flag nearest the unknown `flag`, as it is typed, into out;
 * false when none is a near miss. A toggle is near as --no-NAME and as
 * --NAME, what it turns off. */
static bool flags_suggest(const flags_param *params, int count, const char *flag, char *out, size_t size) {
    int letters = (int)strlen(flag + strspn(flag, "-")), best = TYPO_MAX_EDITS + 1;
    for (const flags_param *p = params; p < params + count; p++) {
        if (!p->name)
            continue;
        char typed[FLAGS_NAME_MAX], plain[FLAGS_NAME_MAX];
        snprintf(typed, sizeof typed, "--%s%s", p->kind == FLAGS_TOGGLE ? "no-" : "", p->name);
        snprintf(plain, sizeof plain, "--%s", p->name);
        int distance = typo_distance(flag, typed), to_plain = typo_distance(flag, plain);
        distance = to_plain < distance ? to_plain : distance;
        if (distance < best && typo_near(distance, letters)) {
            best = distance;
            snprintf(out, size, "%s", typed);
        }
    }
    return best <= TYPO_MAX_EDITS;
}

/* "unknown flag '--warpp', did you mean --warp?", then the other programs
 * that have it: "; build/psm has it", "; A, B and C have it". */
static int flags_unknown(const char *program, const flags_param *params, int count, const char *flag,
                         const flags_elsewhere *elsewhere, int elsewhere_count) {
    char near[FLAGS_NAME_MAX], suggestion[FLAGS_NAME_MAX + 32] = "", there[FLAGS_LINE_MAX] = "";
    if (flags_suggest(params, count, flag, near, sizeof near))
        snprintf(suggestion, sizeof suggestion, ", did you mean %s?", near);
    int found = 0, n = 0;
    for (int e = 0; e < elsewhere_count; e++)
        found += flags_find(elsewhere[e].params, elsewhere[e].count, flag) != NULL;
    for (int e = 0, k = 0; e < elsewhere_count && n < (int)sizeof there; e++) {
        if (!flags_find(elsewhere[e].params, elsewhere[e].count, flag))
            continue;
        const char *separator = ++k == 1 ? (suggestion[0] ? "; " : ": ") : k == found ? " and " : ", ";
        n += snprintf(there + n, sizeof there - (size_t)n, "%s%s", separator, elsewhere[e].program);
    }
    if (found && n < (int)sizeof there)
        snprintf(there + n, sizeof there - (size_t)n, " %s it", found == 1 ? "has" : "have");
    return flags_error(program, "unknown flag '%s'%s%s", flag, suggestion, there);
}

/* The index of `value` among p's choices, or -1. */
static int flags_choice_index(const flags_param *p, const char *value) {
    for (int c = 0; p->choices[c]; c++)
        if (strcmp(value, p->choices[c]) == 0)
            return c;
    return -1;
}

/* Sets the choice `flag` in every table from `first` on that has it. One
 * that several tables share (build/shadows' --overlay, each technique's
 * own) sets each of them that has the value, and is an error only where
 * none has it, which names every value any of them takes. */
static int flags_set_choice(const char *program, const flags_param *first, const flags_param *end, const char *flag,
                            const char *value) {
    bool taken = false;
    char list[FLAGS_LINE_MAX] = "";
    size_t used = 0;
    for (const flags_param *p = first; p < end; p++) {
        if (!flags_names(p, flag))
            continue;
        int index = flags_choice_index(p, value);
        if (index >= 0) {
            *p->index = index;
            taken = true;
        }
        for (int c = 0; p->choices[c]; c++) {
            bool listed = false;
            for (const flags_param *q = first; q < p && !listed; q++)
                listed = flags_names(q, flag) && flags_choice_index(q, p->choices[c]) >= 0;
            if (!listed && used < sizeof list)
                used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", used ? ", " : "", p->choices[c]);
        }
    }
    return taken ? 0
                 : flags_error(program, "--%s: unknown %s '%s', expected one of %s", first->name, first->name, value,
                               list);
}

/* flags_parse_among, with what each entry's flag was first given (NULL:
 * not yet), for a second to be refused. */
static int flags_walk(const char *program, const flags_param *params, int count, int argc, char *const *argv,
                      const flags_elsewhere *elsewhere, int elsewhere_count, const char **given) {
    const flags_param *positional = flags_find(params, count, NULL);
    int status = 0;
    for (int i = 0; i < argc && !status;) {
        const char *arg = argv[i++];
        if (arg[0] != '-') {
            status = positional ? flags_add(program, positional, arg)
                                : flags_usage_error(program, "unexpected argument", arg);
            continue;
        }
        const char *eq = strncmp(arg, "--", 2) == 0 ? strchr(arg, '=') : NULL;
        char flag[FLAGS_NAME_MAX];
        snprintf(flag, sizeof flag, "%.*s", eq ? (int)(eq - arg) : (int)strlen(arg), arg);
        const flags_param *first = flags_find(params, count, flag);
        if (!first)
            return flags_unknown(program, params, count, flag, elsewhere, elsewhere_count);
        if (first->kind == FLAGS_LIST) {
            if (eq)
                status = flags_add(program, first, eq + 1);
            else if (first->repeat && i == argc)
                return flags_usage_error(program, "missing value after", flag);
            else if (first->repeat)
                status = flags_add(program, first, argv[i++]);
            while (!first->repeat && i < argc && argv[i][0] != '-' && !status)
                status = flags_add(program, first, argv[i++]);
            status = status ? status : flags_check_list(program, first);
            continue;
        }
        const char *value = NULL;
        if (flags_takes_value(first->kind) && eq)
            value = eq + 1;
        else if (flags_takes_value(first->kind) && i < argc)
            value = argv[i++];
        else if (flags_takes_value(first->kind))
            return flags_usage_error(program, "missing value after", flag);
        else if (eq)
            return flags_usage_error(program, "flag takes no value:", arg);
        if (first->kind == FLAGS_HELP)
            return FLAGS_HELP_ASKED;
        const char **earlier = &given[first - params];
        if (value && *earlier)
            return flags_error(program, "%s given twice, '%s' then '%s': give it once", flag, *earlier, value);
        *earlier = value;
        if (first->kind == FLAGS_CHOICE) {
            status = flags_set_choice(program, first, params + count, flag, value);
            continue;
        }
        for (const flags_param *p = first; p < params + count && !status; p++)
            if (flags_names(p, flag))
                status = flags_set(program, p, value);
    }
    return status || !positional ? status : flags_check_list(program, positional);
}

int flags_parse(const char *program, const flags_param *params, int count, int argc, char *const *argv) {
    return flags_parse_among(program, params, count, argc, argv, NULL, 0);
}

int flags_parse_among(const char *program, const flags_param *params, int count, int argc, char *const *argv,
                      const flags_elsewhere *elsewhere, int elsewhere_count) {
    const char **given = calloc((size_t)count + 1, sizeof *given); /* + 1: a table may be empty */
    if (!given)
        return flags_error(program, "out of memory for %d flags", count);
    int status = flags_walk(program, params, count, argc, argv, elsewhere, elsewhere_count, given);
    free(given);
    return status;
}

void flags_reset(const flags_param *params, int count) {
    for (const flags_param *p = params; p < params + count; p++) {
        switch (p->kind) {
        case FLAGS_TOGGLE: *p->disabled = false; break;
        case FLAGS_CHOICE: *p->index = 0; break;
        case FLAGS_NUMBER: *p->number = 0; break;
        case FLAGS_SWITCH: *p->on = false; break;
        case FLAGS_INT: *p->integer = 0; break;
        case FLAGS_SIZE: *p->width = *p->height = 0; break;
        case FLAGS_STRING: *p->text = NULL; break;
        case FLAGS_LIST: *p->count = 0; break;
        case FLAGS_HELP: break;
        }
    }
}

float flags_number(const flags_param *p) { return *p->number != 0 ? *p->number : p->fallback; }

/* The flag as --help shows it: "--no-stencil", "--size WxH", "--depth 24|32f"
 * (with `choices` false, a choice's values left to another column:
 * "--depth"). */
static int flags_usage_text(const flags_param *p, bool choices, char *out, size_t size) {
    static const char *const value_names[FLAGS_HELP + 1] = {
        [FLAGS_NUMBER] = "X",    [FLAGS_INT] = "N",       [FLAGS_SIZE] = "WxH",
        [FLAGS_STRING] = "TEXT", [FLAGS_LIST] = "ARG...",
    };
    int n = snprintf(out, size, "--%s%s", p->kind == FLAGS_TOGGLE ? "no-" : "", p->name);
    if (p->kind == FLAGS_CHOICE && choices && n + 1 < (int)size) {
        out[n++] = ' ';
        flags_join(p->choices, "|", out + n, size - (size_t)n);
    } else if (p->value_name || value_names[p->kind]) {
        const char *value = p->value_name ? p->value_name : p->repeat ? "ARG" : value_names[p->kind];
        snprintf(out + n, size - (size_t)n, " %s", value);
    }
    return (int)strlen(out);
}

/* Text into a --help column (`column` >= 0: each '\n' starts a line
 * indented that far) or into a markdown table's cell (column < 0: '\n'
 * is a space, '|' escaped). */
static void flags_print_text(FILE *out, const char *text, int column) {
    for (const char *c = text; *c; c++) {
        if (*c == '\n' && column >= 0)
            fprintf(out, "\n%*s", column, "");
        else if (*c == '\n')
            fputc(' ', out);
        else if (*c == '|' && column < 0)
            fputs("\\|", out);
        else
            fputc(*c, out);
    }
}

void flags_print_help(FILE *out, const flags_param *params, int count, int indent, int width) {
    char text[FLAGS_LINE_MAX];
    bool fit = width == 0;
    for (const flags_param *p = params; p < params + count && fit; p++) {
        int n = p->name ? flags_usage_text(p, true, text, sizeof text) : 0;
        width = n > width && n <= FLAGS_HELP_WIDTH ? n : width;
    }
    /* Two spaces between the flag and its help, which continues there. */
    int column = indent + width + 2;
    for (const flags_param *p = params; p < params + count; p++) {
        if (!p->name)
            continue;
        int n = flags_usage_text(p, true, text, sizeof text);
        fprintf(out, "%*s%s", indent, "", text);
        if (n > width)
            fprintf(out, "\n%*s", column, "");
        else
            fprintf(out, "%*s", width - n + 2, "");
        if (p->key)
            fprintf(out, "key %c: ", p->key);
        flags_print_text(out, p->help ? p->help : "", column);
        fputc('\n', out);
    }
}

/* A markdown table's values cell: a choice's values, the default first;
 * a number's range and default; a count's range; what a list takes. */
static void flags_print_values(FILE *out, const flags_param *p) {
    switch (p->kind) {
    case FLAGS_TOGGLE: fputs("on (the flag: off)", out); break;
    case FLAGS_SWITCH: fputs("off (the flag: on)", out); break;
    case FLAGS_CHOICE:
        for (int c = 0; p->choices[c]; c++)
            fprintf(out, "%s`%s`%s", c ? ", " : "", p->choices[c], c ? "" : " (default)");
        break;
    case FLAGS_NUMBER: fprintf(out, "%g..%g, default %g", p->min, p->max, p->fallback); break;
    case FLAGS_INT: fprintf(out, "%d..%d", (int)p->min, (int)p->max); break;
    case FLAGS_SIZE: fprintf(out, "each 1..%d", FLAGS_MAX_SIZE); break;
    case FLAGS_LIST: flags_print_text(out, p->what ? p->what : "", -1); break;
    case FLAGS_STRING:
    case FLAGS_HELP: break;
    }
}

void flags_print_markdown(FILE *out, const flags_param *params, int count) {
    char text[FLAGS_LINE_MAX];
    fputs("| flag | key | values | what it does |\n|---|---|---|---|\n", out);
    for (const flags_param *p = params; p < params + count; p++) {
        if (!p->name)
            continue;
        flags_usage_text(p, false, text, sizeof text);
        fprintf(out, "| `%s` | ", text);
        if (p->key)
            fprintf(out, "%c", p->key);
        fputs(" | ", out);
        flags_print_values(out, p);
        fputs(" | ", out);
        flags_print_text(out, p->help ? p->help : "", -1);
        fputs(" |\n", out);
    }
}

bool flags_press_key(const flags_param *params, int count, int key) {
    bool found = false;
    for (int k = 0; k < count; k++) {
        const flags_param *p = &params[k];
        if (p->key != key || key == 0)
            continue;
        found = true;
        if (p->kind == FLAGS_TOGGLE)
            *p->disabled ^= true;
        else if (p->kind == FLAGS_CHOICE)
            *p->index = p->choices[*p->index + 1] ? *p->index + 1 : 0;
    }
    return found;
}
