#!/usr/bin/env bash
# README's "Adding a technique", followed word for word on a copy of this
# tree, with NAME the throwaway technique beside this script
# (recipe_probe.c, and test_recipe_probe.c its accuracy cases):
#   1. step 1's file into demos/, step 3's two lines into
#      demos/registry.c, step 4's test into tests/;
#   2. each `make ...` command of the recipe, in order, but `make test`
#      (the whole suite, which runs this script);
#   3. every path the recipe names exists, NAME read as recipe_probe.
# Usage: tests/recipe/follow.sh BUILD SCRATCH (the tree is this script's
# checkout, BUILD a build directory of it, both copied to SCRATCH with
# their times, so that only what the steps change is built).
# Says each step; exits non-zero at the first that fails.
set -euo pipefail
build=$1 scratch=$2
name=recipe_probe
here=$(dirname "$(readlink -f "$0")")
root=$(git -C "$here" rev-parse --show-toplevel)

recipe=$(awk '/^## Adding a technique$/ { on = 1; next } /^## / { on = 0 } on' "$root/README.md")
[ -n "$recipe" ] || { echo "README.md has no section \"Adding a technique\""; exit 1; }

# The copy: the tracked files (a clean clone's), and BUILD.
rm -rf "$scratch" && mkdir -p "$scratch/$build"
git -C "$root" ls-files -z | tar -C "$root" --null -T - -cf - | tar -xf - -C "$scratch"
cp -a "$(readlink -f "$build")/." "$scratch/$build/"
cd "$scratch"
# Sub-makes of the suite's own make must not reach its job server.
unset MAKEFLAGS MFLAGS MAKELEVEL

# Its files.
cp "$here/$name.c" "demos/$name.c"
cp "$here/test_$name.c" "tests/test_$name.c"
awk -v extern="extern const technique ${name}_technique;" -v entry="    &${name}_technique," '
    /^extern const technique / { last_extern = NR }
    { lines[NR] = $0 }
    END {
        for (i = 1; i <= NR; i++) {
            if (lines[i] ~ /^};/ && in_table) { print entry; in_table = 0 }
            print lines[i]
            if (i == last_extern) print extern
            if (lines[i] ~ /registry_techniques\[\] = \{/) in_table = 1
        }
    }' demos/registry.c >demos/registry.c.new
mv demos/registry.c.new demos/registry.c
grep -q "&${name}_technique" demos/registry.c || { echo "demos/registry.c: no table to add $name to"; exit 1; }
echo "recipe: demos/$name.c, tests/test_$name.c and demos/registry.c written"

# Its commands, in order.
grep -o '`make [^`]*`' <<<"$recipe" | tr -d '`' | sed "s/NAME/$name/g" | while read -r command; do
    if [ "$command" = "make test" ]; then
        echo "recipe: $command (left to the suite that runs this script)"
        continue
    fi
    echo "recipe: $command"
    BUILD=$build $command </dev/null || { echo "recipe: $command failed"; exit 1; }
done

# Every path it names is there, NAME's files written and built.
missing=0
for path in $(grep -o '`[a-zA-Z_./]*/[a-zA-Z_./]*`' <<<"$recipe" | tr -d '`' | sed "s/NAME/$name/g" | sort -u); do
    [ -e "$path" ] || { echo "README.md, \"Adding a technique\": $path does not exist"; missing=1; }
done
[ "$missing" = 0 ]
echo "recipe: every path it names exists"
