#!/usr/bin/env bash
# make web-bench: the page's frame time in headless Chromium on
# SwiftShader (a CPU rasterizer: a laptop GPU is far faster), each
# technique on the simple scene at 1280x720, and how long the page takes
# to show its first frame. Writes out/web/bench.md.
#
# A run is one Chromium process that loads the page and stops after F
# window frames (index.html's &frames=F); its wall time, median of RUNS,
# includes the browser's start. A frame's time is the difference between
# runs of FRAMES+1 and 1 frames over FRAMES; the ratio is to the
# unshadowed technique's, measured in the same run of this script.
set -euo pipefail
cd "$(dirname "$0")/../.."
FRAMES=${FRAMES:-30}
RUNS=${RUNS:-3}
page="file://$PWD/out/web/index.html"
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT

# The median wall time in seconds of RUNS loads of the page with `query`.
median_seconds() {
    local times=()
    for _ in $(seq "$RUNS"); do
        local start end
        start=$(date +%s.%N)
        timeout 600 chromium --headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader \
            --virtual-time-budget=600000 --user-data-dir="$profile" --dump-dom "$page?$1" > "$profile/dom.html" \
            2>/dev/null
        end=$(date +%s.%N)
        grep -q '<pre id="status">frames ' "$profile/dom.html" || {
            echo "page_bench: $1: the page did not finish:" >&2
            sed -n 's/.*<pre id="console">\([^<]*\).*/\1/p' "$profile/dom.html" >&2
            exit 1
        }
        times+=("$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }')")
    done
    printf '%s\n' "${times[@]}" | sort -g | sed -n "$(((RUNS + 1) / 2))p"
}

start=$(date +%s.%N)
chromium --headless --no-sandbox --user-data-dir="$profile" --dump-dom "data:text/html,<p>" > /dev/null 2>&1
blank=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
out=out/web/bench.md
{
    echo "# The page in headless Chromium (SwiftShader), simple at 1280x720"
    echo
    echo "$(date -u +%Y-%m-%d) on $(nproc) cores; medians of $RUNS runs, $FRAMES frames each."
    echo
    echo "| technique | first frame, s (browser start included) | frame, ms | × unshadowed |"
    echo "|---|---|---|---|"
} > "$out"
declare -A frame_ms first_s
techniques=$(build/shadows --help | sed -n 's/^  [0-9] \([a-z]*\) .*/\1/p')
for t in $techniques; do
    # At a fixed size: without --size the canvas follows the window's.
    args="args=--technique%20$t%20--size%201280x720"
    one=$(median_seconds "$args&frames=1")
    many=$(median_seconds "$args&frames=$((FRAMES + 1))")
    first_s[$t]=$one
    frame_ms[$t]=$(awk -v a="$one" -v b="$many" -v n="$FRAMES" 'BEGIN { print (b - a) * 1000 / n }')
done
for t in $techniques; do
    printf '| %s | %.2f | %.1f | %.2f |\n' "$t" "${first_s[$t]}" "${frame_ms[$t]}" \
        "$(awk -v a="${frame_ms[$t]}" -v b="${frame_ms[unshadowed]}" 'BEGIN { print a / b }')" >> "$out"
done
printf '\nA blank page takes %.2f s in the same browser.\n' "$blank" >> "$out"
cat "$out"
