#!/usr/bin/env bash
# CIGI 3.3 into sbfx-play (issue 44, docs/simulators.md): `sbfx-play --cigi 127.0.0.1:PORT`
# headless on tests/net/cigi-range.cfg, fed by tests/net/cigi_send (a host encoding from the
# standard's layout on its own) over loopback:
#   - an Entity Control of an effect type that goes Active starts its effect 100 m east of
#     dis.origin (trigger_log source "cigi", within 1 cm of (100, 0, 0)), another 100 m north at
#     (0, 0, -100); an entity type the scene does not name is ignored; Destroyed ends one
#     (cigi_stopped); a message with a bad byte-swap magic is malformed; the counts
#     (cigi_messages, cigi_entities, cigi_ignored, cigi_malformed) exact;
#   - Start of Frame comes back to the sender of IG Control after each frame (cigi_send reads it:
#     version 3, the host's last frame number), and cigi_start_of_frame counts one per frame;
#   - View Definition and View Control make the channel: the frame after them is byte for byte
#     the frame of a run given the same --frustum and --view-offset;
#   - entity 0 is the eyepoint: placed 30 m south and 2 m up within 1 cm, its yaw, pitch and roll
#     as sent, and the frames after it differ from the scene camera's (those before do not);
#   - --cigi without a scene, and --cigi-host without --cigi, are refused naming what is missing.
# Every wait is bounded. Usage: tests/cigi_play.sh [BUILD] (default build). Prints ok/not ok lines.
set -u
cd "$(dirname "$0")/.." || exit 1
BUILD=${1:-build}
PLAYER=$BUILD/sbfx-play
SEND=$BUILD/tests/net/cigi_send
SUITE=cigi-play
WAIT_S=${CIGI_WAIT_S:-30}
SCENE=tests/net/cigi-range.cfg
ORIGIN=48.137154,11.576124,519.0
. tests/net/common.sh

for f in "$PLAYER" "$SEND"; do
    [ -e "$f" ] || { fail built "$f was not built (make $f)"; exit 1; }
done

# start NAME [FLAGS...]: sbfx-play --cigi on a free port in the background, until it listens.
start() {
    local name=$1
    shift
    port=$(free_port udp)
    out=$tmp/$name
    mkdir -p "$out"
    "$PLAYER" --scene "$SCENE" --no-timeline --size 64x36 --fps 4 --out "$out" --stats "$out/stats.json" \
        --cigi "127.0.0.1:$port" "$@" >"$out/log" 2>"$out/err" &
    pid=$!
    until_log "$out/err" 'cigi: listening on' && return 0
    fail "$name" "the player did not start listening: $(head -c 300 "$out/err")"
    return 1
}

send() { "$SEND" --port "$port" --origin "$ORIGIN" "$@"; }
json() { json_number "$out/stats.json" "$1"; }
cigi_entries() {
    grep -o '{"source": "cigi", "effect": "[^"]*", "at": \[[^]]*\]' "$out/stats.json" |
        sed 's/{"source": "cigi", "effect": "\([^"]*\)", "at": \[\([^,]*\), \([^,]*\), \([^]]*\)\]/\1 \2 \3 \4/'
}

test_entities() {
    start entities --frames 100000 || return
    local sof
    sof=$(send --frame 10 --sof-wait 3000 'entity=5,1001,1,2@100,0,0')
    send --frame 11 'entity=6,1002,1,2@0,100,0'
    send --frame 12 'entity=7,4242,1,2@0,0,0'
    send --frame 13 --magic 0x1234 'entity=8,1001,1,2@0,0,0'
    send --frame 14 'entity=6,1002,2,2@0,100,0'
    sleep 1
    stop || { fail entities "the player exited with an error: $(tail -c 300 "$out/err")"; return; }
    case "$sof" in
    *"sof version=3"*"last_host_frame=10"*) ok "start-of-frame-to-the-sender ($sof)" ;;
    *) fail start-of-frame-to-the-sender "cigi_send read '$sof'" ;;
    esac
    local blast airburst
    blast=$(cigi_entries | grep '^blast ' | head -n 1) airburst=$(cigi_entries | grep '^airburst ' | head -n 1)
    # shellcheck disable=SC2086
    if [ -n "$blast" ] && near3 ${blast#blast } 100 0 0 && [ -n "$airburst" ] && near3 ${airburst#airburst } 0 0 -100; then
        ok "placed-through-dis-origin (blast at ${blast#blast }, airburst at ${airburst#airburst })"
    else
        fail placed-through-dis-origin "trigger_log's cigi entries: $(cigi_entries | tr '\n' ';')"
    fi
    local m e i b s f frames
    m=$(json cigi_messages) e=$(json cigi_entities) i=$(json cigi_ignored) b=$(json cigi_malformed)
    s=$(json cigi_stopped) f=$(json cigi_start_of_frame) frames=$(json frames)
    if [ "$m" = 5 ] && [ "$e" = 2 ] && [ "${i:-0}" -ge 1 ] && [ "${b:-0}" -ge 1 ] && [ "$s" = 1 ]; then
        ok "counts (messages $m, entities $e, ignored $i, malformed $b, stopped $s)"
    else
        fail counts "messages $m (5), entities $e (2), ignored $i (>= 1), malformed $b (>= 1), stopped $s (1)"
    fi
    if [ -n "$f" ] && [ -n "$frames" ] && [ "$f" -ge 1 ] && [ "$f" -le "$frames" ] && [ "$frames" -le $((f + 2)) ]; then
        ok "start-of-frame-each-frame ($f for $frames frames; none before the host was heard)"
    else
        fail start-of-frame-each-frame "$f Start of Frame for $frames frames"
    fi
}

test_view() {
    start view --frames 12 || return
    send --frame 1 'view-def=0,0,-20,25,-10,15,0.1,200' 'view-ctrl=0,0,0,0,0,0,10,5,0'
    wait "$pid"
    pid=""
    local ref=$tmp/view-ref
    "$PLAYER" --scene "$SCENE" --no-timeline --size 64x36 --fps 4 --frames 12 --out "$ref" \
        --frustum=-20,25,-10,15 --view-offset 10,5,0 >/dev/null 2>&1
    if cmp -s "$out/frame-0011.png" "$ref/frame-0011.png"; then
        ok "view-definition-and-control-make-the-channel (frame 11 = --frustum -20,25,-10,15 --view-offset 10,5,0)"
    else
        fail view-definition-and-control-make-the-channel "frame 11 differs from the flags' run"
    fi
}

test_ownship() {
    start ownship --frames 100000 || return
    wait_frames_cigi 1
    local before=$newest_frame
    send --frame 1 'entity=0,0,1,0@0,-30,2/20,5,-3'
    sleep 0.6
    stop || true
    local line last
    line=$(grep -o 'cigi: the eyepoint rides on entity 0 at .*' "$out/err" | head -n 1)
    if awk -v l="$line" 'BEGIN { split(l, w, /[ ,()]+/); x = w[9]; y = w[10]; z = w[11]; h = w[13]; p = w[15]; r = w[17];
        d = sqrt(x * x + (y - 2) ^ 2 + (z - 30) ^ 2);
        exit !(d < 0.01 && (h - 20) ^ 2 < 1e-6 && (p - 5) ^ 2 < 1e-6 && (r + 3) ^ 2 < 1e-6) }'; then
        ok "ownship-is-the-eyepoint ($line)"
    else
        fail ownship-is-the-eyepoint "'$line' (want 0, 2, 30, yaw 20, pitch 5, roll -3)"
    fi
    last=$(ls "$out" | grep -o 'frame-[0-9]*' | sort | tail -n 1)
    last=$((10#${last#frame-}))
    "$PLAYER" --scene "$SCENE" --no-timeline --size 64x36 --fps 4 --frames $((last + 1)) --quiet \
        --out "$tmp/scene-camera" >/dev/null 2>&1
    local a b c d
    printf -v a '%s/frame-%04d.png' "$out" "$last"
    printf -v b '%s/scene-camera/frame-%04d.png' "$tmp" "$last"
    printf -v c '%s/frame-%04d.png' "$out" "$before"
    printf -v d '%s/scene-camera/frame-%04d.png' "$tmp" "$before"
    if [ -e "$a" ] && ! cmp -s "$a" "$b" && cmp -s "$c" "$d"; then
        ok "ownship-moves-the-view (frame $last differs from the scene camera's; frame $before, before, does not)"
    else
        fail ownship-moves-the-view "frame $last against $b, frame $before against $d"
    fi
}

# wait_frames_cigi N: until frame N is written (newest_frame: the newest then).
wait_frames_cigi() {
    local deadline=$(($(now_ms) + WAIT_S * 1000)) name
    printf -v name '%s/frame-%04d.png' "$out" "$1"
    until [ -e "$name" ]; do
        [ "$(now_ms)" -gt "$deadline" ] && break
        sleep 0.01
    done
    newest_frame=$(ls "$out" | grep -o 'frame-[0-9]*' | sort | tail -n 1)
    newest_frame=$((10#${newest_frame#frame-}))
}

test_refusals() {
    local err
    err=$("$PLAYER" --cigi 4000 --frames 1 --out "$tmp/r1" 2>&1 >/dev/null)
    case "$err" in *"--cigi needs --scene"*) ok refused-without-scene ;; *) fail refused-without-scene "$err" ;; esac
    err=$("$PLAYER" --cigi-host 127.0.0.1:4000 --frames 1 --out "$tmp/r2" 2>&1 >/dev/null)
    case "$err" in *"--cigi-host needs --cigi"*) ok refused-host-without-cigi ;; *) fail refused-host-without-cigi "$err" ;; esac
}

test_entities
test_view
test_ownship
test_refusals
[ "$failures" = 0 ]
