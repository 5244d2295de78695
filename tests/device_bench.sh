#!/bin/bash
# The benchmark's GPU figures, on a machine that has a GPU but not the
# build's packages (a lent GPU server): run from the repository's root
# there, with out/device/ (make device-bundle, on the build machine)
# beside the checkout. Unpacks build/bench and its libraries, points
# GLVND's EGL at the NVIDIA driver where one is installed, and runs four
# short benchmarks through the EGL device platform: the hard scenes
# (shadowmap, and hybrid with its rays off and everywhere), the soft
# scenes, and lamps_64 still and with one lamp moving (light 27). Each
# run's report.md and results.csv go to DIR (the first argument, else
# $OUT, else out/device-results), eight files in all. DEVICE_BENCH_FLAGS
# adds bench flags to every run (--quick: a smoke test of the script).
set -euo pipefail

bundle=out/device/bench.tar.xz
results=${1:-${OUT:-out/device-results}}
[ -f "$bundle" ] || {
    echo "device_bench: $bundle: missing (make device-bundle, on the build machine)" >&2
    exit 1
}
# A folder of the checkout's root: the programs find shaders/ and assets/
# beside the folder they run from.
unpacked=build-device
rm -rf "$unpacked" && mkdir -p "$unpacked"
tar -xJf "$bundle" -C "$unpacked"
export LD_LIBRARY_PATH="$PWD/$unpacked/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
nvidia=/usr/local/nvidia
if [ -f "$nvidia/share/glvnd/egl_vendor.d/10_nvidia.json" ]; then
    export __EGL_VENDOR_LIBRARY_FILENAMES="$nvidia/share/glvnd/egl_vendor.d/10_nvidia.json"
    export LD_LIBRARY_PATH="$LD_LIBRARY_PATH:$nvidia/lib64:$nvidia/lib"
fi

bench() {
    local name=$1
    shift
    # shellcheck disable=SC2086 # the flags split into words
    "$unpacked/bench" --verbose ${DEVICE_BENCH_FLAGS:-} --out "out/device-bench/$name" "$@"
    mkdir -p "$results/$name"
    cp "out/device-bench/$name/report.md" "out/device-bench/$name/results.csv" "$results/$name/"
}

hard_and_soft=(--technique shadowmap --technique hybrid --configs-with rays --motion static)
bench hard "${hard_and_soft[@]}"
bench soft "${hard_and_soft[@]}" assets/scenes/soft_table.json assets/scenes/soft_sun.json \
    assets/scenes/flat_boxes.json
lamps=(--light 27 --technique shadowmap --technique hybrid --configs defaults assets/scenes/lamps_64.json)
bench lamps --motion static "${lamps[@]}"
bench lamps-lamp --motion lamp "${lamps[@]}"
