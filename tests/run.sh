#!/usr/bin/env bash
# Runs every test program of each build directory given (build/ and, for
# the sanitizer run, build-san/) and ends with one line "N passed, N failed".
# A program that dies before cmocka's summary counts as one failure.
#
# ONLY="test_NAME ..." runs those programs alone. TEST_JOBS=N runs N at
# once (the processors by default).
#
# Two tiers. TEST_TIER=all (make test-all) is the whole matrix: every
# program of each build, sweeps whole in the plain pass. Otherwise (make
# test) the quick tier: the plain pass takes every fourth case of each
# sweep (support_sweep_stride), and the sanitizer pass runs only the
# programs tests/sanitizer_quick.list names: the tests without GL and a
# representative subset of the render tests (each technique against the
# reference, bad input, tours).
#
# References are traced once a run, under out/run/references
# (TEST_REFERENCES; support_measure), whichever program needs one first.
#
# Every (build, program) pair is a job, run by a pool of TEST_JOBS workers
# (CI has two cores; much of a test's time is one thread's: starting
# programs, compiling shaders, building the reference's BVH, writing
# dumps), the sanitizer build's first, since they take longest. Each job
# runs in its own directory out/run/BUILD/PROGRAM that links to everything
# here but has its own out/ (the tests write under out/test/, and two
# programs must not share it). Each says one line as it ends ("[3/58]
# build/tests/test_scene: ok (10 tests, 1 s)"); its log, ending with its
# time, is printed whole when every job is done, in the builds' order.
set -u
cd "$(dirname "$0")/.."

# One job: `run.sh --job BUILD PROGRAM`, from the repository root; writes
# out/run/BUILD/PROGRAM.log and, as its last line, "passed failed skipped
# seconds".
if [ "${1:-}" = --job ]; then
    build=$2 name=$3
    root=out/run/$build/$name
    export TEST_REFERENCES=$PWD/out/run/references
    rm -rf "$root" && mkdir -p "$root"
    for entry in *; do
        [ "$entry" = out ] || ln -s "$PWD/$entry" "$root/$entry"
    done
    cd "$root"
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
        export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
        # Sweeps take every Nth case here (support_sweep_stride).
        export TEST_SANITIZER=1 ;;
    *) unset TEST_PRELOAD TEST_SANITIZER ;;
    esac
    t=$build/tests/$name
    # A test that makes a GL context in its own process (not only in the
    # programs it runs) needs the same preload itself.
    run=("$t")
    if [ -n "${TEST_PRELOAD:-}" ] && grep -q 'context_create(' "tests/$name.c"; then
        run=(env LD_PRELOAD="$TEST_PRELOAD" "$t")
    fi
    started=$SECONDS
    log=$("${run[@]}" 2>&1)
    status=$?
    p=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' <<<"$log" | tail -n 1)
    f=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) test.*/\1/p' <<<"$log" | tail -n 1)
    s=$(sed -n 's/^\[  SKIPPED \] \([0-9]*\) test.*/\1/p' <<<"$log" | tail -n 1)
    {
        echo "== $t"
        printf '%s\n' "$log"
        if [ -z "$p" ] && [ -z "$f" ]; then
            echo "$t: exited with status $status before reporting its results"
            f=1
        elif [ "$status" -ne 0 ] && [ -z "$f" ]; then
            echo "$t: exited with status $status after its tests (sanitizer report above?)"
            f=1
        fi
        # Its time, for keeping make test within CI's budget (README, "Tests").
        echo "== $t: $((SECONDS - started)) s"
        echo "${p:-0} ${f:-0} ${s:-0} $((SECONDS - started))"
    } >"../$name.log"
    # One line as each job ends (the logs follow whole at the end): how
    # many have ended of how many, with this one's figures and time.
    {
        flock 9
        ended=$(($(cat ../../ended) + 1))
        echo "$ended" >../../ended
        if [ "${f:-0}" -eq 0 ]; then
            echo "[$ended/$TEST_JOB_COUNT] $t: ok (${p:-0} tests, $((SECONDS - started)) s)"
        else
            echo "[$ended/$TEST_JOB_COUNT] $t: FAILED (${f:-0} of $((${p:-0} + ${f:-0})) tests, $((SECONDS - started)) s)"
        fi
    } 9>>../../ended.lock
    exit 0
fi

# The quick tier's sanitizer pass: the programs tests/sanitizer_quick.list
# names.
SANITIZER_QUICK=$(grep -v '^#' tests/sanitizer_quick.list | tr '\n' ' ')
export TEST_TIER=${TEST_TIER:-quick}
# The quick tier's longest tests, longest first: they start first, so
# that the cores end together (longest processing time first) rather
# than one waiting on the last long test alone.
LONGEST_FIRST="test_web test_lights test_moments test_skip test_hybrid test_shadowmap test_render \
    test_volumes_skips test_volumes test_glsl_es"

# The jobs: the sanitizer builds' programs first, then the others', the
# longest of those first.
jobs=()
for build in $(printf '%s\n' "$@" | grep san) $(printf '%s\n' "$@" | grep -v san); do
    tests=()
    for name in $LONGEST_FIRST; do
        [ -x "$build/tests/$name" ] && tests+=("$build/tests/$name")
    done
    for t in "$build"/tests/test_*; do
        [[ " $LONGEST_FIRST " == *" $(basename "$t") "* ]] || tests+=("$t")
    done
    for t in "${tests[@]}"; do
        [ -x "$t" ] || continue
        name=$(basename "$t")
        # ONLY="test_a test_b": those programs alone (a quick check).
        [ -z "${ONLY:-}" ] || [[ " $ONLY " == *" $name "* ]] || continue
        if [[ $build == *san* && $TEST_TIER != all && -z "${ONLY:-}" ]]; then
            [[ " $SANITIZER_QUICK " == *" $name "* ]] || continue
        fi
        jobs+=("$build $name")
    done
done
for build in "$@"; do
    mkdir -p "out/run/$build"
    rm -f "out/run/$build"/test_*.log
done
rm -rf out/run/references
echo 0 >out/run/ended
export TEST_JOB_COUNT=${#jobs[@]}
printf '%s\n' "${jobs[@]}" | xargs -P "${TEST_JOBS:-$(nproc)}" -L 1 bash tests/run.sh --job

passed=0 failed=0 skipped=0
times=()
for build in "$@"; do
    for job in "${jobs[@]}"; do
        read -r job_build name <<<"$job"
        [ "$job_build" = "$build" ] || continue
        log=out/run/$build/$name.log
        if [ ! -f "$log" ]; then
            echo "$build/tests/$name: no log (the job did not run)"
            failed=$((failed + 1))
            continue
        fi
        sed '$d' "$log"
        read -r p f s seconds < <(tail -n 1 "$log")
        passed=$((passed + p)) failed=$((failed + f)) skipped=$((skipped + s))
        times+=("$seconds $build/tests/$name")
    done
done
echo "== each test's time (tier $TEST_TIER), in seconds:"
printf '%s\n' "${times[@]}" | awk '{ printf "%6d %s\n", $1, $2 }'
echo "== the slowest ten:"
printf '%s\n' "${times[@]}" | sort -rn | head -n 10 | awk '{ printf "%6d %s\n", $1, $2 }'
# The failures again, last, where a log that keeps only the output's tail
# (CI's) still shows them: each failed program with cmocka's lines that
# name the failed assertion and the few lines its test printed before.
if [ "$failed" -gt 0 ]; then
    echo "== what failed:"
    for build in "$@"; do
        for job in "${jobs[@]}"; do
            read -r job_build name <<<"$job"
            log=out/run/$build/$name.log
            [ "$job_build" = "$build" ] && [ -f "$log" ] || continue
            read -r p f s seconds < <(tail -n 1 "$log")
            [ "$f" -gt 0 ] || continue
            echo "-- $build/tests/$name"
            grep -B 3 -E '^\[ +(ERROR|LINE|FAILED) +\]|exited with status' "$log" | grep -v -E '^--$|^\[ +(OK|PASSED) +\]|^\[=+\]' | head -n 40
        done
    done
fi
if [ "$skipped" -gt 0 ]; then
    echo "$passed passed, $failed failed, $skipped skipped"
else
    echo "$passed passed, $failed failed"
fi
[ "$failed" -eq 0 ]
