#!/usr/bin/env bash
# Regenerates tests/golden/ from the current build, on purpose only: say in
# the commit why the pictures changed, and look at them first.
set -eu
cd "$(dirname "$0")/.."
build=${BUILD:-build}
for technique in planar shadowmap; do
    for scene in simple bunny teapot; do
        "$build/$technique" --backend egl --size 640x360 --scene "assets/scenes/$scene.json" \
            --screenshot "tests/golden/${technique}_$scene.png"
        echo "tests/golden/${technique}_$scene.png"
    done
done
