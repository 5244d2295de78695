#!/usr/bin/env bash
# Every link of README.md lands: a link to "#ANCHOR" names a heading of
# the file (GitHub's anchor: the heading's text in lower case, spaces as
# hyphens, other punctuation dropped), and a link to a relative path names
# a file of the repository. Prints one line "README.md: link TARGET lands
# nowhere" for each that does not and exits 1.
#
# tests/check_links.sh --self-test
#   Checks the check: a file with a broken anchor and a missing file fails,
#   the README's own headings pass.
set -u
cd "$(dirname "$0")/.."

# check FILE: the links of FILE, against its headings and the tree.
check() {
    local file=$1 status=0 target
    local anchors
    anchors=$(sed -n 's/^#\{1,6\} \(.*\)$/\1/p' "$file" | tr 'A-Z' 'a-z' | sed 's/[^a-z0-9 _-]//g; s/ /-/g')
    while read -r target; do
        [ -n "$target" ] || continue
        case $target in
        http://* | https://* | mailto:*) continue ;;
        \#*)
            grep -qxF "${target#\#}" <<<"$anchors" || { echo "$file: link $target lands nowhere"; status=1; } ;;
        *)
            [ -e "${target%%#*}" ] || { echo "$file: link $target lands nowhere"; status=1; } ;;
        esac
    done < <(grep -o '](\([^)]*\))' "$file" | sed 's/^](\(.*\))$/\1/' | sort -u)
    return $status
}

if [ "${1:-}" = --self-test ]; then
    dir=$(mktemp -d) || exit 1
    trap 'rm -rf "$dir"' EXIT
    printf '# Title\n\n## Keys and flags\n\nSee [keys](#keys-and-flags) and [a](README.md).\n' >"$dir/good.md"
    printf '# Title\n\nSee [x](#no-such-heading) and [y](no/such/file.png).\n' >"$dir/bad.md"
    check "$dir/good.md" >/dev/null || { echo "check_links.sh: self-test: a good file failed"; exit 1; }
    [ "$(check "$dir/bad.md" | wc -l)" -eq 2 ] || { echo "check_links.sh: self-test: a broken file passed"; exit 1; }
    echo "check_links.sh: self-test passed"
    exit 0
fi
check README.md
