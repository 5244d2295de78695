/* README's "Adding a technique", followed word for word on a copy of the
 * tree (tests/recipe/follow.sh) with a throwaway technique: its files
 * written where the steps say, each `make` command of the recipe run in
 * order (its goldens recorded, its flags written into the README, its
 * own checks passed), each path the recipe names there. In the plain
 * pass alone: the sanitizer build adds nothing to a recipe's words. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "support.h"

#define RECIPE_SCRATCH "out/test/recipe"
#define RECIPE_LOG "out/test/recipe.log"

static void test_recipe_adds_a_technique(void **state) {
    (void)state;
    if (getenv("TEST_SANITIZER")) {
        printf("recipe: the plain pass follows it\n");
        skip();
    }
    if (!support_have_command("git") || system("git rev-parse --show-toplevel >/dev/null 2>&1") != 0) {
        printf("recipe: not a git checkout, whose tracked files the copy takes\n");
        skip();
    }
    const char *build = getenv("BUILD") ? getenv("BUILD") : "build";
    char command[512], err[4096];
    snprintf(command, sizeof command, "(tests/recipe/follow.sh %s " RECIPE_SCRATCH " >" RECIPE_LOG " 2>&1)", build);
    int status = support_run(command, err, sizeof err);
    char *said = NULL;
    FILE *log = fopen(RECIPE_LOG, "r");
    assert_non_null(log);
    size_t size = 0;
    assert_true(getdelim(&said, &size, '\0', log) >= 0);
    fclose(log);
    printf("%s", said);
    assert_int_equal(status, 0);
    /* Each step said, and what it made there. */
    assert_non_null(strstr(said, "recipe: make update-golden ONLY=recipe_probe\n"));
    assert_non_null(strstr(said, "recipe: make test-technique ONLY=recipe_probe\n"));
    assert_non_null(strstr(said, "recipe: every path it names exists\n"));
    assert_int_equal(access(RECIPE_SCRATCH "/tests/golden/recipe_probe_simple.png", R_OK), 0);
    assert_int_equal(system("grep -q -- '--no-lights' " RECIPE_SCRATCH "/README.md"), 0);
    free(said);
    assert_int_equal(system("rm -rf " RECIPE_SCRATCH), 0);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_recipe_adds_a_technique),
    };
    return cmocka_run_group_tests_name("the recipe for a technique", tests, NULL, NULL);
}
