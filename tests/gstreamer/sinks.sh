#!/usr/bin/env bash
# The docs' display pipelines on real display servers, headless (issue 34; docs/hosts/gstreamer.md):
#   glimagesink      examples/gstreamer/desktop.sh in an X server (Xvfb, GstGL's own choice of
#                    window system and platform): its window, grabbed from the screen, shows
#                    smoke over a white test pattern
#   waylandsink      examples/gstreamer/camera-wayland.sh as a client of cage (wlroots' headless
#                    backend; as nobody when run as root, cage refuses root), grabbed with grim:
#                    the output shows smoke over the white pattern (the scene: the explosion
#                    every second)
# The camera is videotestsrc here (CAMERA=...): the VM tier runs v4l2src from vivid (tests/vm/).
# Usage: tests/gstreamer/sinks.sh [BUILD] (default build). Every wait is bounded (SINKS_WAIT, 30 s).
set -u
cd "$(dirname "$0")/../.." || exit 1
BUILD=${1:-build}
case $BUILD in /*) ;; *) BUILD=$PWD/$BUILD ;; esac
SUITE=gstreamer-sinks
WAIT=${SINKS_WAIT:-30}
failures=0
ok() { echo "ok - $SUITE/$1"; }
fail() {
    echo "not ok - $SUITE/$1: $2"
    failures=$((failures + 1))
}
skip() { echo "skip - $SUITE/$1: $2"; }

if [ ! -f "$BUILD/gstreamer/libgstsbfx.so" ]; then
    fail build "$BUILD/gstreamer/libgstsbfx.so was not built (make gstreamer)"
    exit 1
fi
tmp=$(mktemp -d)
chmod 755 "$tmp"
pids=()
cleanup() {
    local p
    for p in "${pids[@]}"; do kill -KILL "$p" 2>/dev/null; done
    [ -n "${SINKS_KEEP:-}" ] && echo "# kept $tmp" || rm -rf "$tmp"
}
trap cleanup EXIT
# a white picture at 5 fps for the whole wait: the smoke is what is dark in it. The sinks show
# frames at their time and drop late ones (on a loaded machine, at 15 fps, waylandsink dropped
# nearly all), and a grab takes seconds there: the stream goes on until a grab shows smoke, then
# stops. The scene is the explosion again every second, from 0.5 s.
CAMERA="videotestsrc pattern=white num-buffers=$((WAIT * 5)) ! video/x-raw,width=160,height=120,framerate=5/1"
sed '/^triggers = {/,$d' scenes/explosion.cfg >"$tmp/again.cfg"
{
    echo 'triggers = { timeline = ('
    for ((t = 0; t < WAIT - 1; t++)); do echo "  { effect = \"explosion\"; time = $t.5; position = [0.0, 0.0, 0.0]; },"; done
    echo "  { effect = \"explosion\"; time = $((WAIT - 1)).5; position = [0.0, 0.0, 0.0]; } ); };"
} >>"$tmp/again.cfg"
chmod a+r "$tmp/again.cfg"

# below PNG CROP LEVEL: pixels of CROP darker than LEVEL
below() {
    convert "$1" -crop "$2" +repage -colorspace gray -threshold "$3" -negate -format '%[fx:round(mean*w*h)]' info: \
        2>/dev/null || echo 0
}

# dark_pixels PNG CROP: grey pixels, between 4 % and 70 % (the smoke over the white video; the
# screen around the video, and before it shows, is black)
dark_pixels() { echo $(($(below "$1" "$2" 70%) - $(below "$1" "$2" 4%))); }

# grab_until COMMAND CROP: grabs with COMMAND FILE every 0.3 s until one shows over 300 dark
# pixels in CROP, or WAIT seconds; sets dark (the most seen)
grab_until() {
    local deadline=$((SECONDS + WAIT)) n
    dark=0
    while [ "$SECONDS" -lt "$deadline" ]; do
        "$1" "$tmp/grab.png" 2>/dev/null && n=$(dark_pixels "$tmp/grab.png" "$2") && [ "$n" -gt "$dark" ] && dark=$n
        [ "$dark" -gt 300 ] && return 0
        sleep 0.3
    done
    return 1
}

# ---- glimagesink in an X server ----------------------------------------------------------------
x_grab() { DISPLAY=:$display import -window root "$1"; }
test_glimagesink() {
    if ! command -v Xvfb >/dev/null || ! command -v import >/dev/null; then
        skip glimagesink "Xvfb or ImageMagick's import is not installed (tools/deps.sh test)"
        return
    fi
    Xvfb -displayfd 3 -screen 0 640x480x24 -nolisten tcp 3>"$tmp/display" >"$tmp/xvfb.log" 2>&1 &
    pids+=($!)
    disown # killed at the end: no "Killed" notice
    local i
    for ((i = 0; i < 100; i++)); do [ -s "$tmp/display" ] && break; sleep 0.1; done
    display=$(head -n 1 "$tmp/display")
    if [ -z "$display" ]; then
        fail glimagesink "Xvfb did not start: $(tail -n 2 "$tmp/xvfb.log")"
        return
    fi
    tests/gstreamer/with_plugin.sh "$BUILD" env -u GST_GL_PLATFORM -u GST_GL_WINDOW DISPLAY=":$display" \
        CAMERA="$CAMERA" SCENE="$tmp/again.cfg" timeout $((WAIT * 2)) examples/gstreamer/desktop.sh >"$tmp/gl.log" 2>&1 &
    local player=$! # timeout's (with_plugin.sh and env exec it): it passes a SIGTERM on to the pipeline
    pids+=("$player")
    # the window opens at the video's size in the top left corner (no window manager)
    if grab_until x_grab 160x120+0+0; then
        ok "glimagesink (its window shows $dark dark pixels of smoke over the white video)"
    else
        fail glimagesink "no smoke in the window within $WAIT s ($dark dark pixels): $(tail -n 3 "$tmp/gl.log" | tr '\n' ' ')"
    fi
    kill "$player" 2>/dev/null
    wait "$player" 2>/dev/null
}

# ---- waylandsink in cage -------------------------------------------------------------------------
# user_command COMMAND...: sets ucmd to COMMAND as nobody when root (cage refuses root), in a
# clean environment; "${ucmd[@]}" & then gives the command's own id (what a function run in the
# background would not), for kill
user_command() {
    ucmd=()
    [ "$(id -u)" -eq 0 ] && ucmd=(setpriv --reuid="$(id -u nobody)" --regid="$(id -g nobody)" --clear-groups)
    ucmd+=(env -i PATH=/usr/bin:/bin HOME="$tmp/home" XDG_RUNTIME_DIR="$tmp/xdg" WLR_BACKENDS=headless
        WLR_RENDERER=pixman WLR_LIBINPUT_NO_DEVICES=1 "$@")
}
as_user() {
    local ucmd
    user_command "$@"
    "${ucmd[@]}"
}
w_grab() { as_user env WAYLAND_DISPLAY=wayland-0 timeout 20 grim "$tmp/home/grab.png" && cp "$tmp/home/grab.png" "$1"; }
test_waylandsink() {
    local missing="" tool
    for tool in cage grim Xwayland setpriv; do command -v "$tool" >/dev/null || missing="$missing $tool"; done
    if [ -n "$missing" ]; then
        skip waylandsink "not installed:$missing (tools/deps.sh test: cage grim xwayland)"
        return
    fi
    mkdir -p "$tmp/xdg" "$tmp/home"
    [ "$(id -u)" -eq 0 ] && chown "$(id -u nobody)" "$tmp/xdg" "$tmp/home"
    chmod 700 "$tmp/xdg"
    # the output keeps being composited (not scanned out directly: tests/wayland.sh says why)
    local flags=()
    cage -h 2>&1 | grep -q '^ *-r' && flags=(-r -r)
    local ucmd
    user_command cage "${flags[@]}" -- sleep $((WAIT * 2))
    "${ucmd[@]}" >"$tmp/cage.log" 2>&1 &
    pids+=($!)
    disown
    local i
    for ((i = 0; i < 200; i++)); do [ -S "$tmp/xdg/wayland-0" ] && break; sleep 0.1; done
    if [ ! -S "$tmp/xdg/wayland-0" ]; then
        fail waylandsink "cage did not start: $(tail -n 3 "$tmp/cage.log" | tr '\n' ' ')"
        return
    fi
    # nobody's own copy of the plugin and the library: the build may lie where nobody cannot go
    # (a clone in root's home, mode 700, as on a fresh machine)
    mkdir -p "$tmp/home/plugin"
    cp "$BUILD/gstreamer/libgstsbfx.so" "$tmp/home/plugin/"
    cp -L "$BUILD/libsbfx.so.1" "$tmp/home/plugin/"
    chmod -R a+rX "$tmp/home/plugin"
    user_command env WAYLAND_DISPLAY=wayland-0 GST_PLUGIN_PATH="$tmp/home/plugin" LD_LIBRARY_PATH="$tmp/home/plugin" \
        GST_REGISTRY="$tmp/home/registry.bin" CAMERA="$CAMERA" SCENE="$tmp/again.cfg" \
        timeout $((WAIT * 2)) examples/gstreamer/camera-wayland.sh
    "${ucmd[@]}" >"$tmp/wl.log" 2>&1 &
    local player=$! # timeout's: it passes a SIGTERM on to the pipeline
    pids+=("$player")
    # cage's headless output is 1280x720; the video in its middle (no wp_viewporter to scale)
    if grab_until w_grab 1280x720+0+0; then
        ok "waylandsink (cage's output shows $dark dark pixels of smoke over the white video)"
    else
        fail waylandsink "no smoke on cage's output within $WAIT s ($dark dark pixels): $(grep -v '^$' "$tmp/wl.log" |
            tail -n 3 | tr '\n' ' ')"
    fi
    kill "$player" 2>/dev/null
    wait "$player" 2>/dev/null
}

test_glimagesink
test_waylandsink
[ "$failures" -eq 0 ]
