#!/usr/bin/env bash
# Regenerates tests/golden/ from the current build, on purpose only: say in
# the commit why the pictures changed, and look at them first.
set -eu
cd "$(dirname "$0")/.."
build=${BUILD:-build}
for scene in simple bunny teapot; do
    "$build/planar" --backend egl --size 640x360 --scene "assets/scenes/$scene.json" \
        --screenshot "tests/golden/planar_$scene.png"
    echo "tests/golden/planar_$scene.png"
done
