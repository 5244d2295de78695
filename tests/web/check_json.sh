#!/usr/bin/env bash
# Checks the web build's cJSON (common/web/cjson_browser.c) against
# Debian's: builds tests/web/json_tree.c natively with -lcjson and with
# emcc and the adapter, runs both on every JSON file the suite reads or
# tests with (assets/scenes, assets/tours, tests/data and below, with
# tests/data/json's malformed files and edge cases), embedded in the web
# build as the page embeds its files, and fails on any difference between
# the two listings: same trees, same json_load lines for the files that
# do not parse. Skips, saying so, without emcc, node or cc.
#
# Usage: tests/web/check_json.sh
set -u
cd "$(dirname "$0")/../.."

for tool in emcc node cc; do
    if ! command -v "$tool" >/dev/null; then
        echo "check_json: $tool not found: skipped"
        exit 0
    fi
done
# Debian's emcc wants its own python first and node's acorn.
export PATH="/usr/bin:$PATH" NODE_PATH="${NODE_PATH:-/usr/share/nodejs}"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The header both ways, as the web build finds it: <cjson/cJSON.h> and
# <cJSON.h>.
mkdir -p "$work/include/cjson"
ln -s /usr/include/cjson/cJSON.h "$work/include/cjson/cJSON.h"
ln -s /usr/include/cjson/cJSON.h "$work/include/cJSON.h"
flags=(-std=c11 -Wall -Wextra -Werror -D_XOPEN_SOURCE=700 -I"$work/include")

mapfile -t files < <({ ls assets/scenes/*.json assets/tours/*.json; find tests/data -name '*.json'; } | sort)
embeds=()
for f in "${files[@]}"; do
    embeds+=(--embed-file "$f@/$f")
done

cc -O1 "${flags[@]}" tests/web/json_tree.c -lcjson -o "$work/native" || exit 1
emcc -O2 "${flags[@]}" -sALLOW_MEMORY_GROWTH=1 tests/web/json_tree.c common/web/cjson_browser.c \
    "${embeds[@]}" -o "$work/web.js" || exit 1

"$work/native" "${files[@]}" >"$work/native.txt" || exit 1
# Node's fetch cannot load the wasm file by path; the file system can.
node --no-experimental-fetch "$work/web.js" "${files[@]}" >"$work/web.txt" || exit 1

parsed=$(grep -c ': parsed, end at ' "$work/native.txt")
refused=$(grep -c ': JSON syntax error ' "$work/native.txt")
if ! cmp -s "$work/native.txt" "$work/web.txt"; then
    diff -u "$work/native.txt" "$work/web.txt" | head -n 60
    echo "check_json: the adapter differs from cJSON (above: - native, + web)"
    exit 1
fi
echo "check_json: ${#files[@]} files ($parsed parsed, $refused syntax errors) and the built tree: the adapter lists the same as cJSON"
