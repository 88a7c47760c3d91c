#!/usr/bin/env bash
# sbfx-play --display wayland under a real compositor running headless: cage 0.1.4 (wlroots'
# headless backend, pixman renderer; Mesa's EGL reaches it through wl_shm with llvmpipe), read
# back with grim (wlr-screencopy). cage refuses to run as root: as root the compositor and the
# player run as nobody (setpriv), with their own XDG_RUNTIME_DIR.
#   picture          frames grabbed from the compositor are, pixel for pixel, frames that
#                    `sbfx-play --headless` renders of the same run (--fps 30: frame i is
#                    simulated time i/30 on both), and the explosion is in them (the latest
#                    differs from the scene alone, --no-timeline, at that frame)
#   full-screen      the grab is the whole output, the player's window is that size and says
#                    "full screen"
#   frames-keep-coming  frame callbacks keep coming, and grabs show two different frames of the run
#   resize           the window starts at --size 320x180 and follows cage's configure to the output
#   sigterm          SIGTERM ends the run with status 0 and the summary
#   compositor-killed  cage killed: logged, exit status 69 (PLAYER_EXIT_DISPLAY_LOST), no crash
#   presentation     under weston (headless): presentation-time feedback reaches --stats
#   hidden           under weston's kiosk shell (headless), which sends no frame callbacks: the
#                    player logs it, renders on unshown at 10 Hz, exits 0
#   auto, no-compositor  --display auto picks wayland with WAYLAND_DISPLAY and drm without;
#                    a missing compositor is an error naming it
# Usage: tests/wayland.sh [BUILD] (default build). Prints ok / not ok / skip lines; every wait is
# bounded (WAYLAND_TEST_WAIT seconds, default 60).
set -u
cd "$(dirname "$0")/.." || exit 1
BUILD=${1:-build}
SUITE=wayland
WAIT=${WAYLAND_TEST_WAIT:-60}
FPS=30 # simulated frames per second: the explosion lasts many frames
failures=0

ok() { echo "ok - $SUITE/$1"; }
fail() {
    echo "not ok - $SUITE/$1: $2"
    failures=$((failures + 1))
}
skip() { echo "skip - $SUITE/$1: $2"; }

player=$BUILD/sbfx-play
if [ ! -x "$player" ]; then
    fail build "$player was not built"
    exit 1
fi
missing=""
for tool in cage grim setpriv compare identify timeout; do
    command -v "$tool" >/dev/null 2>&1 || missing="$missing $tool"
done
if [ -n "$missing" ]; then
    for t in picture full-screen frames-keep-coming sigterm compositor-killed; do
        skip "$t" "not installed:$missing (tools/deps.sh test: cage grim imagemagick)"
    done
    exit 0
fi

tmp=$(mktemp -d)
chmod 755 "$tmp"
pids=()
cleanup() {
    local p
    for p in "${pids[@]}"; do kill -KILL "$p" 2>/dev/null; done
    [ -n "${WAYLAND_TEST_KEEP:-}" ] && echo "# kept $tmp" || rm -rf "$tmp"
}
trap cleanup EXIT

# The player and the scene where the unprivileged user can read them (the tree may be under
# /root); sbfx-play links libsbfx statically.
mkdir -p "$tmp/bin" "$tmp/out"
cp "$player" "$tmp/bin/sbfx-play"
cp scenes/explosion.cfg "$tmp/bin/"
chmod -R a+rX "$tmp/bin"
if [ "$(id -u)" -eq 0 ]; then
    run_as=(setpriv --reuid="$(id -u nobody)" --regid="$(id -g nobody)" --clear-groups)
    chown "$(id -u nobody)" "$tmp/out"
else
    run_as=()
fi

# as_user XDG COMMAND...: COMMAND as the unprivileged user in a clean environment. It execs:
# called in a subshell, "( as_user ... ) &", $! is COMMAND's own pid.
as_user() {
    local xdg=$1
    shift
    exec "${run_as[@]}" env -i PATH=/usr/bin:/bin HOME="$tmp/out" XDG_RUNTIME_DIR="$xdg" \
        WLR_BACKENDS=headless WLR_RENDERER=pixman WLR_LIBINPUT_NO_DEVICES=1 \
        ${ASAN_OPTIONS:+ASAN_OPTIONS=$ASAN_OPTIONS} ${UBSAN_OPTIONS:+UBSAN_OPTIONS=$UBSAN_OPTIONS} "$@"
}

# wait_for SECONDS COMMAND...: polls COMMAND every 0.1 s until it succeeds; 1 on timeout.
wait_for() {
    local deadline=$((SECONDS + $1))
    shift
    until "$@"; do
        [ "$SECONDS" -ge "$deadline" ] && return 1
        sleep 0.1
    done
}

# cage rotates its output by 180 degrees (-r -r) so that it composites every frame instead of
# scanning the player's buffer out directly. Direct scan-out (cage 0.1.4 does it for a full-screen
# surface of the output's size and transform, i.e. here after the resize) leaves a stale picture
# for grim: each grab locks out scan-out for one frame, and cage composites that frame into the
# render buffer it used last (buffer age 1) with only the damage since the last output commit,
# because wlr_output_damage (wlroots 0.15) files the damage committed while scanning out under
# previous[] and adds previous[] only for buffers older than 1. A grab then shows the last frame
# composited, i.e. the last grab's frame or the 320x180 one before the resize, for as long as no
# new buffer happens to arrive during a grab: seconds when the player draws a few frames a
# second, as it does on a loaded 2-core machine. Composited every frame, the render buffers age
# normally and every grab is the newest buffer; 180 degrees keeps the output 1280x720 and maps
# pixels one to one (grim turns the picture back), so grabs still equal headless frames.
# cage 0.2 (Debian 13: wlroots 0.18, which accounts for that damage since wlroots MR 3883) has
# no -r and composites what it must: the flags only where `cage -h` offers rotation.
CAGE_FLAGS=()
if cage -h 2>&1 | grep -q '^ *-r'; then CAGE_FLAGS=(-r -r); fi

# start_cage NAME: a cage of its own (XDG_RUNTIME_DIR $tmp/NAME) holding a placeholder client;
# sets cage_pid and xdg. The player joins it as a second client.
start_cage() {
    xdg=$tmp/$1
    mkdir -p "$xdg"
    [ "${#run_as[@]}" -gt 0 ] && chown "$(id -u nobody)" "$xdg"
    chmod 700 "$xdg"
    (as_user "$xdg" cage "${CAGE_FLAGS[@]}" -- sleep $((WAIT * 3))) >"$tmp/out/$1-cage.log" 2>&1 &
    cage_pid=$!
    pids+=("$cage_pid")
    compositor_up "$cage_pid" "$xdg" "$tmp/out/$1-cage.log"
}

# compositor_up PID XDG LOG: waits (20 s at most) for the compositor's socket; returns at once,
# with why_not set to the reason, when the compositor exits first (a compositor that cannot
# start: waiting would only add 20 s to a failure).
compositor_up() {
    why_not=""
    wait_for 20 socket_or_gone "$1" "$2/wayland-0" || why_not="it did not start within 20 s"
    if [ -z "$why_not" ] && ! [ -S "$2/wayland-0" ]; then
        why_not="it exited before its socket appeared: $(tail -n 3 "$3" | tr '\n' ' ')"
        # cage 0.1.4 (Debian 12) cannot start without Xwayland, which it only recommends
        if grep -q "Cannot find Xwayland binary" "$3"; then
            why_not="it needs Xwayland: install xwayland (tools/deps.sh test). $why_not"
        fi
    fi
    [ -z "$why_not" ]
}
socket_or_gone() { [ -S "$2" ] || ! kill -0 "$1" 2>/dev/null; }

# children_of PID: the processes whose parent is PID (from /proc: procps may be absent)
children_of() {
    local stat
    for stat in /proc/[0-9]*/stat; do
        awk -v p="$1" '$4 == p { print $1 }' "$stat" 2>/dev/null
    done
}

stop_cage() {
    local child
    for child in $(children_of "$cage_pid"); do kill -KILL "$child" 2>/dev/null; done # its placeholder
    kill -KILL "$cage_pid" 2>/dev/null
    wait "$cage_pid" 2>/dev/null
}

# play NAME ARGS...: sbfx-play --display wayland in the current cage, in the background;
# player_pid, its stdout and stderr in $tmp/out/NAME.out and .err.
play() {
    local name=$1
    shift
    (as_user "$xdg" env WAYLAND_DISPLAY=wayland-0 "$tmp/bin/sbfx-play" --display wayland "$@") \
        >"$tmp/out/$name.out" 2>"$tmp/out/$name.err" &
    player_pid=$!
    pids+=("$player_pid")
}

# stats_lines NAME N: the player printed at least N once-a-second lines
stats_lines() {
    local count
    count=$(grep -c ' fps, frame ' "$tmp/out/$1.out" 2>/dev/null)
    [ "${count:-0}" -ge "$2" ]
}

# finish_player SECONDS: waits for the player (bounded); sets player_rc (124: it did not end).
finish_player() {
    if wait_for "$1" bash -c "! kill -0 $player_pid 2>/dev/null"; then
        wait "$player_pid"
        player_rc=$?
    else
        kill -KILL "$player_pid" 2>/dev/null
        wait "$player_pid" 2>/dev/null
        player_rc=124
    fi
}

grab() { (as_user "$xdg" env WAYLAND_DISPLAY=wayland-0 timeout 20 grim "$1") 2>>"$tmp/out/grim.err"; }
json_number() { sed -n "s/.*\"$2\"[[:space:]]*:[[:space:]]*\([0-9][0-9]*\).*/\1/p" "$1"; }
# differing A B: how many pixels differ (-1: a file is missing or the sizes differ)
differing() {
    local n
    n=$(compare -metric AE "$1" "$2" null: 2>&1 | cut -d' ' -f1)
    [[ "$n" =~ ^[0-9]+$ ]] && echo "$n" || echo -1
}

# ---- the picture, full screen, frames, SIGTERM -----------------------------------------------
# raw_hash PNG: a digest of its RGB pixels (the same picture from grim and from the player's PNG
# writer hashes the same)
raw_hash() { convert "$1" -alpha off rgb:- 2>/dev/null | md5sum | cut -d' ' -f1; }

# Grabs every half second until three show different pictures or GRAB_SECONDS pass: on a loaded
# machine the player may draw fewer frames a second than there are grabs (each grab is the newest
# buffer the player committed, CAGE_FLAGS says why), so a fixed pair of grabs could catch one frame.
GRAB_SECONDS=${WAYLAND_TEST_GRAB_SECONDS:-20}
grab_until_two() {
    local deadline=$((SECONDS + GRAB_SECONDS)) i=0
    declare -A seen=()
    # three different pictures: the first frame, at the size before the compositor's, may be one
    while [ "$SECONDS" -lt "$deadline" ] && [ "${#seen[@]}" -lt 3 ] && kill -0 "$player_pid" 2>/dev/null; do
        grab "$tmp/out/grab-$i.png" || break
        seen[$(raw_hash "$tmp/out/grab-$i.png")]=1
        i=$((i + 1))
        sleep 0.5
    done
    grabs=$i
}

test_picture() {
    if ! start_cage picture; then
        fail picture "cage: $why_not"
        return
    fi
    # --size: the first buffer is 320x180, cage then configures the output's size: a resize
    play run --scene "$tmp/bin/explosion.cfg" --fps "$FPS" --frames 100000 --size 320x180 --stats "$tmp/out/run.json"
    if ! wait_for "$WAIT" stats_lines run 1; then
        fail picture "no stats line within $WAIT s: $(head -c 300 "$tmp/out/run.err")"
        stop_cage
        return
    fi
    grab_until_two
    kill -TERM "$player_pid"
    finish_player 20
    stop_cage
    check_sigterm
    check_picture
    check_frames
}

check_sigterm() {
    if [ "$player_rc" -eq 0 ] && grep -q "frames in .* on Wayland" "$tmp/out/run.out" && [ -s "$tmp/out/run.json" ]; then
        ok "sigterm (exit 0, summary, --stats written)"
    else
        fail sigterm "exit status $player_rc: $(tail -n 2 "$tmp/out/run.err" | tr '\n' ' ')"
    fi
}

# Every grab against every frame the headless player renders of the same run, pixel for pixel:
# matched holds the frame index of each grab that is one ("-": none, e.g. the first frame,
# drawn at the default size before the compositor said the output's).
check_picture() {
    local frames size i f h
    frames=$(json_number "$tmp/out/run.json" frames)
    size=$(identify -format '%wx%h' "$tmp/out/grab-0.png" 2>/dev/null)
    if [ -z "$frames" ] || [ -z "$size" ] || [ "$grabs" -eq 0 ]; then
        fail picture "no frame count ($frames) or no grab ($size): $(head -c 200 "$tmp/out/grim.err")"
        return
    fi
    "$player" --headless --scene scenes/explosion.cfg --fps "$FPS" --frames "$frames" --size "$size" \
        --out "$tmp/headless" --quiet || { fail picture "the headless render failed"; return; }
    declare -A frame_of=()
    for ((i = 0; i < frames; i++)); do
        printf -v f '%s/headless/frame-%04d.png' "$tmp" "$i"
        frame_of[$(raw_hash "$f")]=$i
    done
    matched=()
    for ((i = 0; i < grabs; i++)); do
        h=$(raw_hash "$tmp/out/grab-$i.png")
        matched+=("${frame_of[$h]:--}")
    done
    local last=-1 m # the earliest grabbed frame after frame 0 (the explosion starts at frame 1)
    for m in "${matched[@]}"; do [ "$m" != - ] && [ "$m" -ge 1 ] && { [ "$last" -lt 0 ] || [ "$m" -lt "$last" ]; } && last=$m; done
    if [ "$last" -lt 1 ]; then
        fail picture "no grab is a headless frame with particles (grabs: ${matched[*]} of $frames frames)"
        return
    fi
    "$player" --headless --no-timeline --scene scenes/explosion.cfg --fps "$FPS" --frames $((last + 1)) \
        --size "$size" --out "$tmp/scene" --quiet
    local explosion
    printf -v f '%s/scene/frame-%04d.png' "$tmp" "$last"
    explosion=$(differing "$tmp/headless/$(basename "$f")" "$f")
    if [ "${explosion:-0}" -lt 1000 ]; then
        fail picture "the grab is headless frame $last, but the scene alone differs in only $explosion pixels"
    else
        ok "picture (grabs are headless frames ${matched[*]} of $frames pixel for pixel, $size; the explosion covers $explosion pixels)"
    fi
    if grep -q "on Wayland wayland-0 $size full screen" "$tmp/out/run.out"; then
        ok "full-screen ($size, the output's size)"
    else
        fail full-screen "the summary does not say '$size full screen': $(grep 'frames in' "$tmp/out/run.out")"
    fi
    # cage 0.1.4 configures the window's size after its first buffer (a resize from --size);
    # cage 0.2 in its first configure, before any buffer: the window starts at the output's size
    if grep -q "Wayland wayland-0 320x180" "$tmp/out/run.out" && grep -q "wayland: the window is $size now" "$tmp/out/run.err"; then
        ok "resize (320x180 -> $size by the compositor's configure; the frames after it are the headless ones)"
    elif grep -q "Wayland wayland-0 $size full screen" "$tmp/out/run.out"; then
        ok "resize (--size 320x180, and the compositor's first configure, before any buffer, made it $size)"
    else
        fail resize "no resize from 320x180 to $size logged: $(grep -m1 'sbfx-play: .*Wayland' "$tmp/out/run.out")"
    fi
}

# The compositor asked for frames all along (frame callbacks), and two grabs showed two
# different frames of the run.
check_frames() {
    local flips lines distinct
    flips=$(json_number "$tmp/out/run.json" flips)
    lines=$(grep ' fps, frame ' "$tmp/out/run.out" | grep -vc 'flips 0,')
    distinct=$(printf '%s\n' "${matched[@]}" | grep -v '^-$' | sort -u | wc -l)
    if [ "${flips:-0}" -ge 3 ] && [ "$lines" -ge 1 ] && [ "$distinct" -ge 2 ]; then
        ok "frames-keep-coming ($flips frame callbacks; grabs showed $distinct different frames)"
    else
        fail frames-keep-coming "frame callbacks $flips, stats lines with callbacks $lines, distinct frames grabbed $distinct (${matched[*]})"
    fi
}

# ---- the compositor going away --------------------------------------------------------------
test_compositor_killed() {
    if ! start_cage killed; then
        fail compositor-killed "cage: $why_not"
        return
    fi
    play killed --scene "$tmp/bin/explosion.cfg"
    if ! wait_for "$WAIT" stats_lines killed 1; then
        fail compositor-killed "no stats line within $WAIT s: $(head -c 300 "$tmp/out/killed.err")"
        stop_cage
        return
    fi
    stop_cage
    finish_player 20
    if [ "$player_rc" -eq 69 ] && grep -q "the compositor went away" "$tmp/out/killed.err"; then
        ok "compositor-killed (logged, exit status 69)"
    elif [ "$player_rc" -ge 124 ]; then
        fail compositor-killed "the player did not end or crashed (status $player_rc)"
    else
        fail compositor-killed "exit status $player_rc, expected 69: $(tail -n 1 "$tmp/out/killed.err")"
    fi
}

# start_weston NAME SHELL: weston headless (pixman, 640x360) with SHELL, XDG_RUNTIME_DIR
# $tmp/NAME; sets weston_pid and xdg.
start_weston() {
    xdg=$tmp/$1
    mkdir -p "$xdg"
    [ "${#run_as[@]}" -gt 0 ] && chown "$(id -u nobody)" "$xdg"
    chmod 700 "$xdg"
    (as_user "$xdg" weston --backend=headless-backend.so --shell="$2" --use-pixman \
        --socket=wayland-0 --width=640 --height=360 --idle-time=0) >"$tmp/out/weston-$1.log" 2>&1 &
    weston_pid=$!
    pids+=("$weston_pid")
    compositor_up "$weston_pid" "$xdg" "$tmp/out/weston-$1.log"
}

# ---- presentation-time feedback: weston (headless, pixman, desktop shell) ----------------------
# cage 0.1.4 offers no wp_presentation; weston 10 does. (Its kiosk shell on the headless backend
# sends no frame callbacks to any client, weston-simple-egl's included: the desktop shell here.)
test_presentation() {
    if ! command -v weston >/dev/null 2>&1; then
        skip presentation "weston is not installed (tools/deps.sh test)"
        return
    fi
    if ! start_weston weston desktop-shell.so; then
        fail presentation "weston: $why_not"
        return
    fi
    play weston --scene "$tmp/bin/explosion.cfg" --frames 40 --stats "$tmp/out/weston.json"
    finish_player "$WAIT"
    kill -TERM "$weston_pid" 2>/dev/null
    wait "$weston_pid" 2>/dev/null
    local j=$tmp/out/weston.json presented latency frames
    presented=$(json_number "$j" presented_frames)
    latency=$(sed -n 's/.*"latency_ms_mean": \([0-9.]*\).*/\1/p' "$j")
    frames=$(json_number "$j" frames)
    if [ "$player_rc" -ne 0 ]; then
        fail presentation "exit status $player_rc: $(tail -n 1 "$tmp/out/weston.err")"
    elif [ "${frames:-0}" -ne 40 ] || [ "${presented:-0}" -lt 1 ] || ! awk -v l="${latency:-0}" 'BEGIN { exit !(l > 0) }'; then
        fail presentation "frames $frames, presented_frames $presented, latency_ms_mean $latency"
    elif ! grep -q "640x360 full screen, presentation-time feedback" "$tmp/out/weston.out"; then
        fail presentation "not full screen with feedback: $(grep 'frames in' "$tmp/out/weston.out")"
    else
        ok "presentation (weston: $presented of $frames frames presented, latency mean $latency ms; $(grep 'frames in' "$tmp/out/weston.out" | grep -o 'missed vblanks [0-9]*'))"
    fi
}

# ---- a window the compositor does not draw: weston's kiosk shell, headless -------------------
# It maps the window full screen but sends no frame callback (to any client): after a second
# the player logs it and goes on at 10 Hz without showing frames, and ends normally.
test_hidden() {
    if ! command -v weston >/dev/null 2>&1; then
        skip hidden "weston is not installed (tools/deps.sh test)"
        return
    fi
    if ! start_weston kiosk kiosk-shell.so; then
        fail hidden "weston: $why_not"
        return
    fi
    play hidden --scene "$tmp/bin/explosion.cfg" --frames 20 --stats "$tmp/out/hidden.json"
    finish_player "$WAIT"
    kill -TERM "$weston_pid" 2>/dev/null
    wait "$weston_pid" 2>/dev/null
    local paused flips
    paused=$(json_number "$tmp/out/hidden.json" display_paused_frames)
    flips=$(json_number "$tmp/out/hidden.json" flips)
    if [ "$player_rc" -ne 0 ]; then
        fail hidden "exit status $player_rc: $(tail -n 1 "$tmp/out/hidden.err")"
    elif [ "${flips:-1}" -ne 0 ]; then
        skip hidden "this weston sent $flips frame callbacks: the window was drawn, nothing to test"
    elif ! grep -q "no frame callback for a second" "$tmp/out/hidden.err" || [ "${paused:-0}" -lt 1 ]; then
        fail hidden "not logged, or no paused frames ($paused): $(tail -n 1 "$tmp/out/hidden.err")"
    else
        ok "hidden (no frame callbacks: logged, $paused of 20 frames rendered unshown at 10 Hz, exit 0)"
    fi
}

# ---- the user unit, started by a user manager in a weston session ---------------------------
# dist/systemd/user/sbfx-kiosk-wayland.service.in as `make install` writes it, started by a real
# `systemd --user` of the unprivileged user in a weston (desktop shell) session: it must become
# active (READY=1 after its first frame) with its sandbox in force, and stop with status 0. Its
# files and the session's XDG_RUNTIME_DIR live under /run: the unit's PrivateTmp= hides /tmp.
# A user manager needs a cgroup subtree of its own (made here, as logind's user@.service would
# delegate it) and /run/systemd/system (present where systemd booted the machine, made in a
# private mount namespace otherwise).
cgroup_for_manager() {
    local h
    for h in /sys/fs/cgroup/unified /sys/fs/cgroup/systemd /sys/fs/cgroup; do
        if [ -f "$h/cgroup.procs" ] && [ -w "$h" ]; then echo "$h"; fi
    done
}
test_user_unit() {
    local name=user-unit
    if [ "$(id -u)" -ne 0 ]; then skip $name "needs root (a cgroup subtree delegated to a user manager)"; return; fi
    if ! command -v weston >/dev/null 2>&1 || ! [ -x /lib/systemd/systemd ] || ! command -v unshare >/dev/null 2>&1; then
        skip $name "weston, systemd or unshare is not installed (tools/deps.sh test)"
        return
    fi
    local hier
    hier=$(cgroup_for_manager)
    if [ -z "$hier" ]; then skip $name "no writable cgroup hierarchy under /sys/fs/cgroup for a user manager"; return; fi
    local run cg=() h uid gid
    run=$(mktemp -d -p /run sbfx-user-unit.XXXXXX)
    chmod 755 "$run"
    uid=$(id -u nobody) gid=$(id -g nobody)
    mkdir -p "$run/bin" "$run/share/sbfx/scenes" "$run/xdg" "$run/home/.config/systemd/user/sbfx-kiosk-wayland.service.d"
    cp "$player" "$run/bin/sbfx-play"
    cp scenes/explosion.cfg "$run/share/sbfx/scenes/"
    sed -e "s|@BINDIR@|$run/bin|g" -e "s|@DATADIR@|$run/share|g" dist/systemd/user/sbfx-kiosk-wayland.service.in \
        >"$run/home/.config/systemd/user/sbfx-kiosk-wayland.service"
    # the test reads the player's log (no journal here): where its output goes, nothing else
    printf '[Service]\nStandardOutput=file:%s\nStandardError=file:%s\n' "$run/home/unit.log" "$run/home/unit.log" \
        >"$run/home/.config/systemd/user/sbfx-kiosk-wayland.service.d/log.conf"
    chown -R "$uid:$gid" "$run/xdg" "$run/home"
    chmod 700 "$run/xdg"
    for h in $hier; do mkdir "$h/sbfx-user-unit.$$" && chown -R "$uid:$gid" "$h/sbfx-user-unit.$$" && cg+=("$h/sbfx-user-unit.$$"); done
    local sess=(setpriv --reuid="$uid" --regid="$gid" --clear-groups env -i PATH=/usr/bin:/bin HOME="$run/home"
        XDG_RUNTIME_DIR="$run/xdg" XDG_CONFIG_HOME="$run/home/.config")
    (exec "${sess[@]}" weston --backend=headless-backend.so --shell=desktop-shell.so --use-pixman --socket=wayland-0 \
        --width=640 --height=360 --idle-time=0) >"$tmp/out/user-unit-weston.log" 2>&1 &
    local weston=$!
    pids+=("$weston")
    if ! compositor_up "$weston" "$run/xdg" "$tmp/out/user-unit-weston.log"; then
        fail $name "weston: $why_not"
        user_unit_cleanup "$run" "$weston" "" "${cg[@]}"
        return
    fi
    # the user manager, in the cgroup subtree delegated to it
    CGROUPS="${cg[*]}" unshare -m --propagation private sh -c '
        [ -d /run/systemd/system ] || { mkdir -p /run/systemd && mount -t tmpfs tmpfs /run/systemd && mkdir /run/systemd/system; } || exit 1
        for c in $CGROUPS; do echo $$ >"$c/cgroup.procs" || exit 1; done
        exec "$@" /lib/systemd/systemd --user' sh "${sess[@]}" >>"$tmp/out/user-unit-manager.log" 2>&1 &
    local manager=$!
    pids+=("$manager")
    local ctl=("${sess[@]}" systemctl --user)
    if ! wait_for 20 test -S "$run/xdg/systemd/private"; then
        skip $name "cannot start a user manager here: $(tail -n 2 "$tmp/out/user-unit-manager.log" | tr '\n' ' ')"
        user_unit_cleanup "$run" "$weston" "$manager" "${cg[@]}"
        return
    fi
    "${ctl[@]}" set-environment WAYLAND_DISPLAY=wayland-0
    local rc=0 state pid
    timeout "$WAIT" "${ctl[@]}" start sbfx-kiosk-wayland.service >"$tmp/out/user-unit-start.log" 2>&1 || rc=$?
    [ "$rc" -eq 0 ] || echo "its main process: $("${ctl[@]}" show -P ExecMainStatus sbfx-kiosk-wayland.service)" \
        "(systemd.exec(5), PROCESS EXIT CODES)" >>"$tmp/out/user-unit-start.log"
    sleep 2 # frames go on: the watchdog and the sandbox's system call filter let it run
    state=$("${ctl[@]}" show -P ActiveState sbfx-kiosk-wayland.service)/$("${ctl[@]}" show -P NRestarts sbfx-kiosk-wayland.service)
    pid=$("${ctl[@]}" show -P MainPID sbfx-kiosk-wayland.service)
    local sandbox=""
    if [ "${pid:-0}" -gt 0 ] && [ -r "/proc/$pid/status" ]; then
        grep -q '^NoNewPrivs:[[:space:]]*1' "/proc/$pid/status" && sandbox+="no-new-privileges "
        grep -q '^Seccomp:[[:space:]]*2' "/proc/$pid/status" && sandbox+="seccomp "
        grep -q '^CapBnd:[[:space:]]*0*$' "/proc/$pid/status" && sandbox+="no-capabilities "
        local ns
        for ns in user mnt; do
            [ "$(readlink "/proc/$pid/ns/$ns")" != "$(readlink "/proc/$$/ns/$ns")" ] && sandbox+="$ns-namespace "
        done
    fi
    "${ctl[@]}" stop sbfx-kiosk-wayland.service >/dev/null 2>&1
    local status
    status=$("${ctl[@]}" show -P ExecMainStatus sbfx-kiosk-wayland.service)
    user_unit_cleanup "$run" "$weston" "$manager" "${cg[@]}"
    local want="no-new-privileges seccomp no-capabilities user-namespace mnt-namespace "
    if [ "$rc" -ne 0 ] || [ "$state" != active/0 ]; then
        fail $name "start exit status $rc, state $state: $(tail -n 3 "$tmp/out/user-unit-start.log" | tr '\n' ' ') $(tail -n 3 "$tmp/out/user-unit.log" 2>/dev/null | tr '\n' ' ')"
    elif [ "$sandbox" != "$want" ]; then
        fail $name "the sandbox is not in force: has '$sandbox', wants '$want'"
    elif [ "$status" != 0 ]; then
        fail $name "stopped with status $status, expected 0"
    else
        ok "$name (systemd --user started it in a weston session: active after its first frame, sandboxed (${sandbox% }), stopped with status 0)"
    fi
}
# user_unit_cleanup RUN WESTON MANAGER CGROUP...
user_unit_cleanup() {
    local run=$1 p c
    cp "$run/home/unit.log" "$tmp/out/user-unit.log" 2>/dev/null
    for p in "$3" "$2"; do
        [ -n "$p" ] || continue
        kill -TERM "$p" 2>/dev/null
        wait_for 10 bash -c "! kill -0 $p 2>/dev/null" || kill -KILL "$p" 2>/dev/null
        wait "$p" 2>/dev/null
    done
    shift 3
    for c in "$@"; do
        [ -d "$c" ] || continue
        # what is left in it goes back to the parent, then the subtree goes (deepest first)
        find "$c" -depth -type d | while read -r d; do
            while read -r p; do echo "$p" >"$(dirname "$c")/cgroup.procs" 2>/dev/null; done <"$d/cgroup.procs"
            rmdir "$d" 2>/dev/null
        done
    done
    rm -rf "$run"
}

# ---- --display auto, no compositor ------------------------------------------------------------
test_auto() {
    local err rc
    err=$(env -u WAYLAND_DISPLAY timeout 30 "$player" --display auto --device /nonexistent/dri/card9 2>&1 >/dev/null)
    rc=$?
    if [ "$rc" -eq 1 ] && grep -q -- "--display drm" <<<"$err"; then
        ok "auto-drm (no WAYLAND_DISPLAY: drm)"
    else
        fail auto-drm "status $rc: $err"
    fi
    err=$(WAYLAND_DISPLAY=sbfx-no-such-compositor XDG_RUNTIME_DIR=$tmp timeout 30 "$player" --display auto 2>&1 >/dev/null)
    rc=$?
    if [ "$rc" -eq 1 ] && grep -q "cannot connect to the Wayland compositor $tmp/sbfx-no-such-compositor" <<<"$err"; then
        ok "no-compositor (auto chose wayland; the error names the socket)"
    else
        fail no-compositor "status $rc: $err"
    fi
}

test_auto
test_picture
test_compositor_killed
test_presentation
test_hidden
test_user_unit
[ "$failures" -eq 0 ]
