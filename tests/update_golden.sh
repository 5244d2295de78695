#!/usr/bin/env bash
# Regenerates tests/golden/ from the current build, on purpose only: say in
# the commit why the pictures changed, and look at them first.
set -eu
cd "$(dirname "$0")/.."
build=${BUILD:-build}
golden() { # NAME TECHNIQUE SCENE [FLAGS...]
    local name=$1 technique=$2 scene=$3
    shift 3
    "$build/$technique" --backend egl --size 640x360 --scene "assets/scenes/$scene.json" "$@" \
        --screenshot "tests/golden/$name.png"
    echo "tests/golden/$name.png"
}
for technique in planar shadowmap psm volumes; do
    for scene in simple bunny teapot; do
        golden "${technique}_$scene" "$technique" "$scene"
    done
done
# Lecture overlays (tests/test_render.c): a 2D map and a cube map.
for scene in simple bunny; do
    golden "shadowmap-overlay_$scene" shadowmap "$scene" --overlay all
done
# Perspective shadow maps where they matter: a light in front of the
# viewer and one behind; the lecture's post-perspective view.
for scene in long_view long_view_behind; do
    golden "psm_$scene" psm "$scene"
done
golden "psm-overlay_long_view" psm long_view --overlay post-perspective
