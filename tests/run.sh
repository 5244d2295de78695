#!/usr/bin/env bash
# Runs every test program of each build directory given (build/ and, for
# the sanitizer run, build-san/) and ends with one line "N passed, N failed".
# A program that dies before cmocka's summary counts as one failure.
#
# ONLY="test_NAME ..." runs those programs alone.
#
# Given several builds (make test: plain and sanitizer), it runs them at
# once, each in its own directory out/run/BUILD that links to everything
# here but has its own out/ (the tests write under out/test/): CI has two
# cores, and much of a test's time is one thread's (starting programs,
# compiling shaders, building the reference's BVH, writing dumps). Each
# build's log is printed whole when both are done.
set -u
cd "$(dirname "$0")/.."

# The last line, "N passed, N failed[, N skipped]", and the exit status.
summarize() {
    if [ "$skipped" -gt 0 ]; then
        echo "$passed passed, $failed failed, $skipped skipped"
    else
        echo "$passed passed, $failed failed"
    fi
    [ "$failed" -eq 0 ]
    exit
}
if [ $# -gt 1 ]; then
    mkdir -p out/run
    for build in "$@"; do
        root=out/run/$build
        rm -rf "$root" && mkdir -p "$root"
        for entry in *; do
            [ "$entry" = out ] || ln -s "$PWD/$entry" "$root/$entry"
        done
        (cd "$root" && bash tests/run.sh "$build") >"out/run/$build.log" 2>&1 &
    done
    wait
    passed=0 failed=0 skipped=0
    for build in "$@"; do
        cat "out/run/$build.log"
        summary=$(sed -n 's/^\([0-9]*\) passed, \([0-9]*\) failed\(, \([0-9]*\) skipped\)\{0,1\}$/\1 \2 \4/p' \
            "out/run/$build.log" | tail -n 1)
        read -r p f s <<<"$summary"
        [ -n "${p:-}" ] || { echo "$build: the run ended without its summary line"; f=1; }
        passed=$((passed + ${p:-0})) failed=$((failed + ${f:-0})) skipped=$((skipped + ${s:-0}))
    done
    summarize
fi
passed=0 failed=0 skipped=0
for build in "$@"; do
    export BUILD=$build
    case $build in
    *san*)
        # Mesa unloads its drivers (dlclose) at eglTerminate; the driver's
        # globals then vanish and LeakSanitizer calls everything they held
        # a leak in an "<unknown module>". Programs under test therefore
        # start with the drivers preloaded (after the ASan runtime, which
        # must come first), so they stay mapped and nothing is hidden.
        preload=$(readlink -f "$(${CC:-cc} -print-file-name=libasan.so)")
        for lib in libEGL_mesa.so.0 libGLX_mesa.so.0 libOSMesa.so.8 dri/swrast_dri.so; do
            path=/usr/lib/$(${CC:-cc} -print-multiarch)/$lib
            [ -e "$path" ] && preload="$preload $path"
        done
        export TEST_PRELOAD=$preload
        export ASAN_OPTIONS=detect_leaks=1
        export LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp:print_suppressions=0
        export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ;;
    *) unset TEST_PRELOAD ;;
    esac
    for t in "$build"/tests/test_*; do
        [ -x "$t" ] || continue
        # ONLY="test_a test_b": those programs alone (a quick check).
        [ -z "${ONLY:-}" ] || [[ " $ONLY " == *" $(basename "$t") "* ]] || continue
        echo "== $t"
        # A test that makes a GL context in its own process (not only in
        # the programs it runs) needs the same preload itself.
        run=("$t")
        if [ -n "${TEST_PRELOAD:-}" ] && grep -q 'context_create(' "tests/$(basename "$t").c"; then
            run=(env LD_PRELOAD="$TEST_PRELOAD" "$t")
        fi
        started=$SECONDS
        log=$("${run[@]}" 2>&1)
        status=$?
        printf '%s\n' "$log"
        # Its time, for keeping make test within CI's budget (the README's
        # "Tests" says how long a run takes).
        echo "== $t: $((SECONDS - started)) s"
        p=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' <<<"$log" | tail -n 1)
        f=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) test.*/\1/p' <<<"$log" | tail -n 1)
        s=$(sed -n 's/^\[  SKIPPED \] \([0-9]*\) test.*/\1/p' <<<"$log" | tail -n 1)
        if [ -z "$p" ] && [ -z "$f" ]; then
            echo "$t: exited with status $status before reporting its results"
            f=1
        elif [ "$status" -ne 0 ] && [ -z "$f" ]; then
            echo "$t: exited with status $status after its tests (sanitizer report above?)"
            f=1
        fi
        passed=$((passed + ${p:-0})) failed=$((failed + ${f:-0})) skipped=$((skipped + ${s:-0}))
    done
done
summarize
