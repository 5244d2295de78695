/* Tests of common/data/flags.c, in-process: one table parses every kind of
 * flag the programs and techniques declare, and prints their --help and markdown. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flags.h"
#include "support.h"

#define TEST_MAX_ITEMS 3

static struct {
    bool no_stencil, other_no_stencil, verbose;
    int filter, other_filter, frames, width, height, item_count, rest_count, pick_count;
    float bias;
    const char *scene, *shot, *warp;
    const char *items[TEST_MAX_ITEMS], *rest[TEST_MAX_ITEMS], *picks[TEST_MAX_ITEMS];
} v;

static const char *const filters[] = {"poisson", "none", "pcf3", NULL};
static const char *const other_filters[] = {"none", "tent", NULL};

static const flags_param params[] = {
    {NULL, NULL, 0, FLAGS_LIST, .items = v.items, .count = &v.item_count, .min = 1, .max = TEST_MAX_ITEMS,
     .what = "one to three files"},
    {"stencil", "shadows blend twice", 'S', FLAGS_TOGGLE, .disabled = &v.no_stencil},
    {"stencil", "the same flag in a second technique", 0, FLAGS_TOGGLE, .disabled = &v.other_no_stencil},
    {"filter", "what reads the map", 'F', FLAGS_CHOICE, .index = &v.filter, .choices = filters},
    {"filter", "a second technique's, with other values", 0, FLAGS_CHOICE, .index = &v.other_filter,
     .choices = other_filters},
    {"bias", "constant bias", 0, FLAGS_NUMBER, .number = &v.bias, .fallback = 1.5f, .min = 0.01f, .max = 64},
    {"frames", "frames", 0, FLAGS_INT, .integer = &v.frames, .min = 1, .max = 100, .what = "a count"},
    {"size", "size", 0, FLAGS_SIZE, .width = &v.width, .height = &v.height},
    {"scene", "scene file", 0, FLAGS_STRING, .text = &v.scene, .value_name = "PATH"},
    {"verbose", "say more\nover two lines", 0, FLAGS_SWITCH, .on = &v.verbose},
    {"pick", "one each time", 0, FLAGS_LIST, .repeat = true, .items = v.picks, .count = &v.pick_count, .min = 1,
     .max = TEST_MAX_ITEMS, .what = "names"},
    {"gallery", "the rest", 0, FLAGS_LIST, .items = v.rest, .count = &v.rest_count, .min = 2, .max = TEST_MAX_ITEMS,
     .what = "DIR then a scene"},
    {"shot", "a picture", 0, FLAGS_STRING, .text = &v.shot, .extension = ".png", .value_name = "PATH.png"},
    {.name = "help", .help = "this text", .kind = FLAGS_HELP},
};
enum { param_count = sizeof params / sizeof *params };

/* Another program's table, for an unknown flag's error. */
static const flags_param other_params[] = {
    {"warp", "how the map is placed", 0, FLAGS_STRING, .text = &v.warp},
};
static const flags_elsewhere elsewhere[] = {
    {"build/psm", other_params, 1},
    {"build/nothing", NULL, 0},
    {"build/cascades", other_params, 1},
};

/* Parses a space-separated command line (no program name), with the
 * first `others` programs of `elsewhere`. */
static int parse_among(const char *line, int others) {
    static char copy[512];
    char *words[64];
    int n = 0;
    snprintf(copy, sizeof copy, "%s", line);
    for (char *rest = copy, *word; (word = strtok_r(rest, " ", &rest));)
        words[n++] = word;
    flags_reset(params, param_count);
    return flags_parse_among("test", params, param_count, n, words, elsewhere, others);
}

static int parse(const char *line) { return parse_among(line, 0); }

static void test_every_kind(void **state) {
    (void)state;
    assert_int_equal(parse("a --no-stencil --filter pcf3 --bias=2.5 --frames 7 --size 64x36 --scene s.json "
                           "--verbose b"),
                     0);
    assert_true(v.no_stencil && v.other_no_stencil && v.verbose);
    assert_int_equal(v.filter, 2);
    assert_true(v.bias == 2.5f && flags_number(&params[5]) == 2.5f);
    assert_int_equal(v.frames, 7);
    assert_int_equal(v.width, 64);
    assert_int_equal(v.height, 36);
    assert_string_equal(v.scene, "s.json");
    assert_int_equal(v.item_count, 2);
    assert_string_equal(v.items[1], "b");
}

/* A choice two tables share sets each that has the value, leaving the
 * other as it was; a value neither has names both's. */
static void test_shared_choice(void **state) {
    (void)state;
    assert_int_equal(parse("a --filter none"), 0);
    assert_int_equal(v.filter, 1);
    assert_int_equal(v.other_filter, 0);
    assert_int_equal(parse("a --filter tent"), 0);
    assert_int_equal(v.filter, 0);
    assert_int_equal(v.other_filter, 1);
    assert_int_equal(parse("a --filter pcf3"), 0);
    assert_int_equal(v.filter, 2);
    support_capture_stderr();
    int status = parse("a --filter box");
    const char *text = support_release_stderr();
    assert_int_equal(status, FLAGS_EXIT_USAGE);
    assert_non_null(strstr(text, "unknown filter 'box', expected one of poisson, none, pcf3, tent"));
}

static void test_reset_gives_defaults(void **state) {
    (void)state;
    assert_int_equal(parse("a"), 0);
    assert_false(v.no_stencil || v.verbose);
    assert_int_equal(v.filter, 0);
    assert_true(flags_number(&params[5]) == 1.5f);
    assert_null(v.scene);
}

/* A named list takes the arguments up to the next flag, which is parsed
 * as a flag: a misplaced one leaves the list short, a usage error. */
static void test_list_stops_at_a_flag(void **state) {
    (void)state;
    assert_int_equal(parse("a --gallery out x y --verbose"), 0);
    assert_true(v.verbose);
    assert_int_equal(v.rest_count, 3);
    assert_string_equal(v.rest[2], "y");
    assert_int_equal(parse("a --gallery out --verbose x"), FLAGS_EXIT_USAGE);
    assert_int_equal(parse("a --gallery out"), FLAGS_EXIT_USAGE);
    assert_int_equal(parse("a --gallery=out x y z"), FLAGS_EXIT_USAGE);
}

/* A repeated list takes one argument each time, and flags go on after it. */
static void test_list_repeats(void **state) {
    (void)state;
    assert_int_equal(parse("a --pick x --verbose --pick=y b"), 0);
    assert_true(v.verbose);
    assert_int_equal(v.pick_count, 2);
    assert_string_equal(v.picks[0], "x");
    assert_string_equal(v.picks[1], "y");
    assert_int_equal(v.item_count, 2);
    assert_int_equal(parse("a --pick"), FLAGS_EXIT_USAGE);
    assert_int_equal(parse("a --pick 1 --pick 2 --pick 3 --pick 4"), FLAGS_EXIT_USAGE); /* over max */
}

static void test_bad_command_lines(void **state) {
    (void)state;
    static const char *const bad[] = {
        "a --bogus",  "a --filter blur", "a --bias 0",    "a --bias x",       "a --frames 101",
        "a --size 3", "a --frames",      "a --verbose=1", "a --no-stencil=1", "",
        "a b c d",    "a --stencil",     "a --no-filter",
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
        assert_int_equal(parse(bad[i]), FLAGS_EXIT_USAGE);
    assert_int_equal(parse("a --help --bogus"), FLAGS_HELP_ASKED);
    assert_int_equal(parse("-h"), FLAGS_HELP_ASKED);
}

/* Bad command lines whose one line names the problem: a value given
 * twice (a list collects, a switch or toggle given again says the same
 * again), a name without the extension, an unknown flag (the nearest of
 * the table's when few edits away, a toggle as --no-NAME; the first
 * `others` programs of `elsewhere` that have it). */
static const struct {
    const char *line;
    int others;
    const char *expected;
} named_errors[] = {
    {"a --scene s.json --scene t.json", 0, "test: --scene given twice, 's.json' then 't.json'"},
    {"a --frames=3 --frames 3", 0, "--frames given twice"},
    {"a --filter pcf3 --no-stencil --filter none", 0, "--filter given twice"},
    {"a --size 64x36 --size=64x36", 0, "--size given twice"},
    {"a --bias 2 --bias 3", 0, "--bias given twice"},
    {"a --shot x.jpg", 0, "test: --shot: expected a file name ending in .png, got 'x.jpg'"},
    {"a --shot .png", 0, "ending in .png"},
    {"a --shot png", 0, "ending in .png"},
    {"a --frame 3", 0, "test: unknown flag '--frame', did you mean --frames? (see --help)"},
    {"a --verbsoe", 0, "did you mean --verbose?"},
    {"a --scne x", 0, "did you mean --scene?"},
    {"a -scene x", 0, "did you mean --scene?"},
    {"a --stencil", 0, "unknown flag '--stencil', did you mean --no-stencil?"},
    {"a --no-filtre", 0, "unknown flag '--no-filtre' (see --help)"},
    {"a --sz", 0, "unknown flag '--sz' (see --help)"},
    {"a --bogus", 0, "unknown flag '--bogus' (see --help)"},
    {"a --warp psm", 1, "test: unknown flag '--warp': build/psm has it (see --help)"},
    {"a --warp psm", 3, "unknown flag '--warp': build/psm and build/cascades have it (see --help)"},
    {"a --frame 3", 3, "did you mean --frames? (see --help)"},
};

static void test_errors_name_the_problem(void **state) {
    (void)state;
    for (size_t i = 0; i < sizeof named_errors / sizeof *named_errors; i++) {
        support_capture_stderr();
        int status = parse_among(named_errors[i].line, named_errors[i].others);
        const char *text = support_release_stderr();
        if (status != FLAGS_EXIT_USAGE || support_count_lines(text) != 1 || !strstr(text, named_errors[i].expected))
            fail_msg("%s: status %d, said \"%s\", expected one line with \"%s\"", named_errors[i].line, status, text,
                     named_errors[i].expected);
    }
}

/* What the errors above refuse, the good cases of it: switches, toggles
 * and lists given again; a name with the extension in any case. */
static void test_repeats_and_extensions_that_pass(void **state) {
    (void)state;
    assert_int_equal(parse("a --no-stencil --verbose --no-stencil --verbose --pick x --pick y"), 0);
    assert_true(v.no_stencil && v.other_no_stencil && v.verbose);
    assert_int_equal(parse("a --scene s.json b"), 0); /* the reset forgets what was given */
    assert_int_equal(parse("a --scene s.json b"), 0);
    assert_int_equal(parse("a --shot out/x.png"), 0);
    assert_string_equal(v.shot, "out/x.png");
    assert_int_equal(parse("a --shot X.PNG"), 0);
}

static void test_help_lists_every_flag(void **state) {
    (void)state;
    char *text = NULL;
    size_t size = 0;
    FILE *out = open_memstream(&text, &size);
    assert_non_null(out);
    flags_print_help(out, params, param_count, 2, 0);
    fclose(out);
    static const char *const lines[] = {
        "  --no-stencil                key S: shadows blend twice\n",
        "  --filter poisson|none|pcf3  key F: what reads the map\n",
        "  --bias X                    constant bias\n",
        "  --scene PATH                scene file\n",
        "  --verbose                   say more\n                              over two lines\n",
        "  --pick ARG                  one each time\n",
        "  --gallery ARG...            the rest\n",
        "  --help                      this text\n",
    };
    for (size_t i = 0; i < sizeof lines / sizeof *lines; i++)
        assert_non_null(strstr(text, lines[i]));
    free(text);
}

static void test_markdown_lists_every_flag(void **state) {
    (void)state;
    char *text = NULL;
    size_t size = 0;
    FILE *out = open_memstream(&text, &size);
    assert_non_null(out);
    flags_print_markdown(out, params, param_count);
    static const flags_param piped[] = {
        {"mode", "a|b\nover two lines", 0, FLAGS_STRING, .text = &v.scene, .value_name = "M"},
    };
    flags_print_markdown(out, piped, 1);
    fclose(out);
    static const char *const lines[] = {
        "| flag | key | values | what it does |\n|---|---|---|---|\n| `--no-stencil` | S |",
        "| `--no-stencil` | S | on (the flag: off) | shadows blend twice |\n",
        "| `--filter` | F | `poisson` (default), `none`, `pcf3` | what reads the map |\n",
        "| `--bias X` |  | 0.01..64, default 1.5 | constant bias |\n",
        "| `--frames N` |  | 1..100 | frames |\n",
        "| `--size WxH` |  | each 1..16384 | size |\n",
        "| `--verbose` |  | off (the flag: on) | say more over two lines |\n",
        "| `--gallery ARG...` |  | DIR then a scene | the rest |\n",
        "| `--mode M` |  |  | a\\|b over two lines |\n",
    };
    for (size_t i = 0; i < sizeof lines / sizeof *lines; i++)
        assert_non_null(strstr(text, lines[i]));
    assert_null(strstr(text, "one to three files")); /* the positional arguments have no row */
    free(text);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_kind),
        cmocka_unit_test(test_shared_choice),
        cmocka_unit_test(test_reset_gives_defaults),
        cmocka_unit_test(test_list_stops_at_a_flag),
        cmocka_unit_test(test_list_repeats),
        cmocka_unit_test(test_bad_command_lines),
        cmocka_unit_test(test_errors_name_the_problem),
        cmocka_unit_test(test_repeats_and_extensions_that_pass),
        cmocka_unit_test(test_help_lists_every_flag),
        cmocka_unit_test(test_markdown_lists_every_flag),
    };
    return cmocka_run_group_tests_name("flags", tests, NULL, NULL);
}
