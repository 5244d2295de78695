#!/usr/bin/env bash
# Drives build/shadows in a real window with X input events (xdotool), as
# a lecturer's hands would, under the X server xvfb-run started; run by
# tests/test_window.c, which checks what it leaves in DIR:
#   F12                 screenshot-planar-2.png (DIR holds a -1 already: never overwritten)
#   drag 150 px down    the camera orbits (above the ground)
#   F12                 screenshot-planar-3.png
#   0                   camera and light reset
#   F12                 screenshot-planar-4.png (the same picture as -2)
#   3                   the third technique, shadowmap
#   F12                 screenshot-shadowmap-1.png
#   Escape              the window closes, exit 0
# all with --no-hud (clean pictures to compare); then, with the HUD, on
# SCENE2 (whose directory's next scene is broken) and --verbose:
#   F12                 screenshot-planar-5.png: the same view, HUD included
#   Page Down           the broken scene does not load: the HUD says why
#   Escape              exit 0, the HUD's last text on stderr2.txt
# then TOUR (tests/support.h, SUPPORT_CAPTION_TOUR), with the HUD and
# --verbose, each F12 printing the HUD's text on stderr3.txt:
#   Space x3            the step of SUPPORT_CAPTION_STEP, shadowmap
#   F12                 screenshot-shadowmap-2.png: its caption
#   6                   volumes: the caption no longer says what is shown
#   F12                 screenshot-volumes-1.png
#   3                   shadowmap again, as the step sets it
#   F12                 screenshot-shadowmap-3.png
#   C                   its constant bias off
#   F12                 screenshot-shadowmap-4.png
#   Escape              exit 0
# then with --fullscreen and --no-hud, on SCENE:
#   F12                 screenshot-planar-6.png: the whole screen
#   F11, F12            screenshot-planar-7.png: the window as it was (the same picture as -2)
#   F11, F12            screenshot-planar-8.png: the whole screen again
#   Escape              exit 0
# F12 saves the frame drawn after it, with every key sent before it
# applied (the app reads events in order, between frames): each F12
# waits for its picture on disk, so that the keys after it come after
# that frame, and no other step waits. Only what the window system does
# on its own time waits SETTLE seconds: the window's first frames, F11's
# new size, the broken scene's note before the app quits.
# Usage: tests/window_input.sh PROGRAM SCENE SCENE2 TOUR SIZE DIR, from
# the project's root (the scenes and the tour relative to it; SIZE the
# tour's window);
# PROGRAM is a command (tests/support.h's support_program: it may start
# with env LD_PRELOAD=...) whose build directory DIR links to, since the
# app runs in DIR (where F12 writes).
set -eu
program=$1 scene=$PWD/$2 scene2=$PWD/$3 tour=$PWD/$4 tour_size=$5 dir=$6
SETTLE=2
for build in build build-san; do
    [ ! -e "$build" ] || ln -sfn "$PWD/$build" "$dir/$build"
done
cd "$dir"
# A failed step says whether the app was still running, or how it ended.
report_app() {
    if kill -0 "$app" 2>/dev/null; then
        echo "window_input.sh: the app was still running" >&2
    else
        wait "$app" && status=0 || status=$?
        echo "window_input.sh: the app had ended, status $status" >&2
    fi
}
trap 'echo "window_input.sh: line $LINENO failed on display $DISPLAY: $BASH_COMMAND" >&2; report_app' ERR
# The app with ARGS, its outputs to stdoutN.txt and stderrN.txt (N: the
# run's suffix), once its window is there; its size SIZE (640x360).
start() {
    eval "$program $1 --size ${3:-640x360} >stdout$2.txt 2>stderr$2.txt &"
    app=$!
    window=$(timeout 60 xdotool search --sync --name '^shadows$' | head -1)
    sleep "$SETTLE"
}
press() {
    xdotool key --window "$window" "$1"
}
# F12, and its picture on disk.
shoot() {
    local saved
    saved=$(find . -maxdepth 1 -name 'screenshot-*.png' | wc -l)
    press F12
    timeout 30 bash -c "while [ \$(find . -maxdepth 1 -name 'screenshot-*.png' | wc -l) -le $saved ]; do sleep 0.05; done"
}
# Escape pressed only: the app closes its window on the press, so a
# release sent after it would find no window. The server may list the
# closed window a moment longer: the next start must not find it.
quit() {
    xdotool keydown --window "$window" Escape
    wait "$app"
    timeout 30 bash -c "while xdotool search --name '^shadows\$' >/dev/null; do sleep 0.2; done"
}
start "--scene '$scene' --no-hud" ""
shoot
xdotool mousemove --window "$window" 320 100 mousedown 1 mousemove --window "$window" 320 180 \
    mousemove --window "$window" 320 250 mouseup 1
shoot
press 0
shoot
press 3
shoot
quit

start "--scene '$scene2' --verbose" 2
shoot
press Next
sleep "$SETTLE"
quit

start "--tour '$tour' --verbose" 3 "$tour_size"
for key in space space space F12 6 F12 3 F12 c F12; do
    if [ "$key" = F12 ]; then shoot; else press "$key"; fi
done
quit

start "--scene '$scene' --no-hud --fullscreen" 4
shoot
press F11
sleep "$SETTLE"
shoot
press F11
sleep "$SETTLE"
shoot
quit
