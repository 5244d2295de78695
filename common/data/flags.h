/* flags: every program's command line and every technique's parameters,
 * declared once as a table of flags_param and walked by one parser, so that
 * a flag's value, its error and its --help line come from the same entry
 * ("--size 640by480" fails alike everywhere).
 *
 * Kinds, each with the fields it uses (zero means the default, as in the
 * settings structs the fields point into):
 *   FLAGS_TOGGLE  a feature, on by default: --no-NAME sets *disabled;
 *   FLAGS_CHOICE  --NAME VALUE: *index into choices (NULL-terminated, the
 *                 default first);
 *   FLAGS_NUMBER  --NAME X: *number in [min, max], 0 meaning fallback;
 *   FLAGS_SWITCH  --NAME sets *on;
 *   FLAGS_INT     --NAME N: *integer, a whole number in [min, max], which
 *                 errors call `what` ("a count");
 *   FLAGS_SIZE    --NAME WxH: *width and *height, each 1..16384;
 *   FLAGS_STRING  --NAME TEXT: *text (a path, a directory, a name), which
 *                 must end in `extension` where one is given (".png", in
 *                 any case: what the program writes there);
 *   FLAGS_LIST    arguments into items, *count of them, at least min and at
 *                 most max, which errors call `what`: with a name, --NAME
 *                 takes the arguments after it up to the next flag
 *                 (--gallery DIR SCENE...; a scene named "-x" is "./-x"),
 *                 or with `repeat` one argument each time it is given
 *                 (--technique A --technique B); without a name (name
 *                 NULL), the positional arguments;
 *   FLAGS_HELP    --NAME or -h: flags_parse returns FLAGS_HELP_ASKED and the
 *                 program prints its usage.
 * A flag takes its value as "--name=value" or as the next argument. Several
 * entries may have one name (the multi-technique program's --no-offset):
 * the flag sets each of them. A flag that takes a value is given once: a
 * second value would silently win over the first, so it is an error;
 * lists collect what each time gives, and a switch or toggle given twice
 * says the same thing twice.
 *
 * An unknown flag's error names the program's own flag it is closest to,
 * when few edits away (a typo: "did you mean --size?"), and the other
 * programs of the suite that have it (flags_elsewhere: "build/psm has
 * it").
 *
 * Every error is one line on stderr, "program: --flag: expected ..., got
 * 'value' (see --help)", and flags_parse returns FLAGS_EXIT_USAGE, the
 * program's exit status for a bad command line.
 */
#ifndef FLAGS_H
#define FLAGS_H

#include <stdbool.h>
#include <stdio.h>

#define FLAGS_EXIT_USAGE 2
#define FLAGS_HELP_ASKED (-1)

/* A numeric constant as text, for a help line ("1.." FLAGS_TEXT(MAX)). */
#define FLAGS_TEXT(x) FLAGS_TEXT_(x)
#define FLAGS_TEXT_(x) #x

typedef enum flags_kind {
    FLAGS_TOGGLE,
    FLAGS_CHOICE,
    FLAGS_NUMBER,
    FLAGS_SWITCH,
    FLAGS_INT,
    FLAGS_SIZE,
    FLAGS_STRING,
    FLAGS_LIST,
    FLAGS_HELP,
} flags_kind;

typedef struct flags_param {
    const char *name; /* the flag without "--" (toggles: "--no-" NAME) */
    const char *help; /* toggles: what turning it off shows; may hold '\n' */
    int key;          /* the window's key for it (GLFW_KEY_*), or 0 */
    flags_kind kind;
    bool *disabled;             /* TOGGLE */
    const bool *available;      /* TOGGLE: NULL, or false where this GL lacks the feature (the HUD says so) */
    int *index;                 /* CHOICE */
    const char *const *choices; /* CHOICE: NULL-terminated */
    float *number;              /* NUMBER */
    float fallback;             /* NUMBER */
    double min, max;            /* NUMBER, INT; LIST: how many items */
    bool *on;                   /* SWITCH */
    int *integer;               /* INT */
    int *width, *height;        /* SIZE */
    const char **text;          /* STRING */
    const char *extension;      /* STRING: the value's ending, any case; NULL: any */
    const char **items;         /* LIST: room for max */
    int *count;                 /* LIST */
    bool repeat;                /* LIST: one argument per --NAME, which repeats */
    const char *what;           /* INT, LIST: what errors call the value */
    const char *value_name;     /* --help: "PATH", "K" (default by kind) */
} flags_param;

/* Another program's flags, for the error of an unknown flag: a flag that
 * one of them has is named with it ("build/psm has it"). */
typedef struct flags_elsewhere {
    const char *program; /* how the error names it: "build/psm" */
    const flags_param *params;
    int count;
} flags_elsewhere;

/* argv[0] without its directory: what errors begin with. */
const char *flags_program_name(const char *argv0);
/* Walks the arguments (argv[0] is the first argument, not the program)
 * through the table. Returns 0, FLAGS_HELP_ASKED, or FLAGS_EXIT_USAGE after
 * printing the one-line error. */
int flags_parse(const char *program, const flags_param *params, int count, int argc, char *const *argv);
/* The same, an unknown flag's error also naming those of `elsewhere`
 * (elsewhere_count of them) that have it. */
int flags_parse_among(const char *program, const flags_param *params, int count, int argc, char *const *argv,
                      const flags_elsewhere *elsewhere, int elsewhere_count);
/* Every value back to zero, its default. */
void flags_reset(const flags_param *params, int count);
/* A NUMBER's value: its fallback while the field is 0. */
float flags_number(const flags_param *p);
/* The window's key press: flips each toggle and steps each choice that
 * has the key; false if none has it. */
bool flags_press_key(const flags_param *params, int count, int key);
/* One --help line per flag, `indent` spaces in: the flag, its value
 * (a choice's values as a|b|c), "key K: " and the help, which starts
 * after a column `width` wide (0: as wide as the table's flags need). */
void flags_print_help(FILE *out, const flags_param *params, int count, int indent, int width);
/* The same table as markdown (the README's "Keys and flags"): a header,
 * then one row per flag: the flag and its value's name, its key, its
 * values (a choice's, the default first; a number's range and default),
 * and the help on one line. */
void flags_print_markdown(FILE *out, const flags_param *params, int count);
/* Prints "program: message 'value' (see --help)" (value may be NULL) and
 * returns FLAGS_EXIT_USAGE: for checks after parsing. */
int flags_usage_error(const char *program, const char *message, const char *value);

#endif
