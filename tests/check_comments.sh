#!/usr/bin/env bash
# Keeps comments timeless (README's rule): a comment says what stays true
# while the code is unchanged, so it holds no measured figure (a number
# followed by a percent sign) and no tracker reference ("issue" or
# "issues" and a number, or a hash and a number). Figures belong in the
# generated reports, history in commit messages.
#
# Usage: tests/check_comments.sh [PATH...]
#   Scans the C sources and headers, GLSL (.glsl .frag .vert .geom) and
#   shell scripts under each PATH (a directory or a file; demos shaders
#   common tests by default), from the project's root. Prints one line
#   "FILE:LINE: measured figure in a comment: TEXT" or "FILE:LINE: tracker
#   number in a comment: TEXT" per hit and exits 1 if there is any.
# tests/check_comments.sh --self-test
#   Checks the check: a file with an injected figure and tracker number
#   fails, a clean one whose code prints a percent sign passes.
#
# Only comment text is read: C and GLSL block and line comments (string
# and character literals skipped, so format specifiers never count), and
# shell comments (a hash at a word's start outside quotes; here-documents
# skipped). Debian's perl does the reading.
set -u
cd "$(dirname "$0")/.."

# The scanner: perl, reading the files named on its command line.
scanner=$(cat <<'PERL'
use strict;
use warnings;

my $status = 0;

sub report {
    my ($file, $line, $text) = @_;
    $text =~ s/^\s+|\s+$//g;
    $text =~ s/\s+/ /g;
    # A number, then an optional space and a percent sign.
    if ($text =~ /(?<![A-Za-z_])\d+(?:\.\d+)?\s?%/) {
        print "$file:$line: measured figure in a comment: $text\n";
        $status = 1;
    }
    # "issue N", "issues N", "Issue #N", or "#N" on its own.
    if ($text =~ /\bissues?\s*#?\d/i || $text =~ /(?<![\w&#])#\d+\b/) {
        print "$file:$line: tracker number in a comment: $text\n";
        $status = 1;
    }
}

# C and GLSL: a character at a time; returns line => comment text.
sub c_comments {
    my ($src) = @_;
    my %text;
    my ($state, $line) = ('code', 1);
    my $n = length $src;
    for (my $i = 0; $i < $n; $i++) {
        my $c = substr($src, $i, 1);
        my $next = $i + 1 < $n ? substr($src, $i + 1, 1) : '';
        if ($c eq "\n") {
            $line++;
            # A literal does not run past its line's end (unless escaped).
            $state = 'code' if $state eq 'line'
                || (($state eq 'string' || $state eq 'char')
                    && substr($src, $i - 1, 1) ne '\\');
            next;
        }
        if ($state eq 'code') {
            if ($c eq '/' && $next eq '*') { $state = 'block'; $i++; }
            elsif ($c eq '/' && $next eq '/') { $state = 'line'; $i++; }
            elsif ($c eq '"') { $state = 'string'; }
            elsif ($c eq "'") { $state = 'char'; }
        } elsif ($state eq 'block') {
            if ($c eq '*' && $next eq '/') { $state = 'code'; $i++; }
            else { $text{$line} .= $c; }
        } elsif ($state eq 'line') {
            $text{$line} .= $c;
        } else {
            my $end = $state eq 'string' ? '"' : "'";
            if ($c eq '\\') { $i++; $line++ if $next eq "\n"; }
            elsif ($c eq $end) { $state = 'code'; }
        }
    }
    return %text;
}

# Shell: a line at a time, quotes carried across lines; a hash starts a
# comment at a word's start outside quotes; here-documents are skipped.
sub sh_comments {
    my ($src) = @_;
    my %text;
    my $quote = '';
    my @heredocs;
    my $line = 0;
    for my $l (split /\n/, $src, -1) {
        $line++;
        if (@heredocs) {
            my ($word, $tabs) = @{$heredocs[0]};
            my $t = $l;
            $t =~ s/^\t+// if $tabs;
            shift @heredocs if $t eq $word;
            next;
        }
        # The line's text before its comment, where a here-document starts.
        my $code = $l;
        my $n = length $l;
        for (my $i = 0; $i < $n; $i++) {
            my $c = substr($l, $i, 1);
            if ($quote eq "'") { $quote = '' if $c eq "'"; next; }
            if ($c eq '\\') { $i++; next; }
            if ($quote eq '"') { $quote = '' if $c eq '"'; next; }
            if ($c eq "'" || $c eq '"') { $quote = $c; next; }
            if ($c eq '#' && ($i == 0 || substr($l, $i - 1, 1) =~ /[\s;&|()]/)) {
                $text{$line} = substr($l, $i + 1);
                $code = substr($l, 0, $i);
                last;
            }
        }
        while ($code =~ /(?<!<)<<(-?)\s*(['"]?)([A-Za-z_]\w*)\2/g) {
            push @heredocs, [$3, $1 eq '-'];
        }
    }
    return %text;
}

for my $file (@ARGV) {
    open my $fh, '<', $file or die "$file: $!\n";
    local $/;
    my $src = <$fh>;
    close $fh;
    my %text = $file =~ /\.sh$/ ? sh_comments($src) : c_comments($src);
    report($file, $_, $text{$_}) for sort { $a <=> $b } keys %text;
}
exit $status;
PERL
)

# The files under the given paths that hold comments to check.
check() {
    local files
    files=$(find "$@" -type f \( -name '*.c' -o -name '*.h' -o -name '*.glsl' \
        -o -name '*.frag' -o -name '*.vert' -o -name '*.geom' -o -name '*.sh' \) | sort)
    [ -n "$files" ] || { echo "check_comments.sh: no sources under $*" >&2; return 2; }
    # shellcheck disable=SC2086
    /usr/bin/perl -e "$scanner" $files
}

if [ "${1:-}" = --self-test ]; then
    dir=$(mktemp -d)
    trap 'rm -rf "$dir"' EXIT
    mkdir "$dir/bad" "$dir/clean"
    cat >"$dir/bad/figure.c" <<'C'
/* measured: 1.5 % */
int a;
C
    cat >"$dir/bad/tracker.c" <<'C'
int b; /* see issue 12 */
C
    cat >"$dir/bad/tracker.sh" <<'SH'
true # the case of #12
SH
    cat >"$dir/clean/clean.c" <<'C'
#include <stdio.h>
/* Prints the share misclassified, in percent. */
void f(int x) { printf("%d%%", x); printf("%d %% of 7 %", x); } // ok
char c = '%';
C
    cat >"$dir/clean/clean.sh" <<'SH'
printf '%d %%\n' 50 # in percent
echo "50 % # not a comment" ${#x} $#
cat <<EOF
# 50 % here-document text, not a comment
EOF
SH
    ok=1
    for f in figure.c tracker.c tracker.sh; do
        if out=$(check "$dir/bad/$f"); then
            echo "self-test: the check passed $f, which it must fail" >&2
            ok=0
        elif [ -z "$out" ]; then
            echo "self-test: the check failed $f without naming a hit" >&2
            ok=0
        fi
    done
    grep -q 'figure.c:1: measured figure in a comment' <<<"$(check "$dir/bad/figure.c")" \
        || { echo "self-test: figure.c's hit is not reported as a figure on line 1" >&2; ok=0; }
    grep -q 'tracker.c:1: tracker number in a comment' <<<"$(check "$dir/bad/tracker.c")" \
        || { echo "self-test: tracker.c's hit is not reported as a tracker number" >&2; ok=0; }
    if ! out=$(check "$dir/clean"); then
        printf 'self-test: the check failed clean files:\n%s\n' "$out" >&2
        ok=0
    fi
    [ "$ok" = 1 ] || exit 1
    echo "check_comments.sh: self-test passed"
    exit 0
fi

case ${1:-} in
-*)
    echo "usage: tests/check_comments.sh [PATH...] | --self-test" >&2
    exit 2 ;;
esac
if [ $# -eq 0 ]; then
    set -- demos shaders common tests
fi
check "$@"
