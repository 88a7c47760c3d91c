#!/usr/bin/env bash
# Under a real exercise's load (issue 44, docs/simulators.md "Load"): sbfx-play --dis headless at
# 30 frames a second (320x180, a 20 ms frame budget) on tests/net/range.cfg, while
# tests/net/dis_send sends 5,000 Entity State PDUs and 50 detonations a second over loopback for
# LOAD_SECONDS (60 in make test-load; make test runs 3):
#   - none lost silently: the player read every PDU sent (dis_pdus = sent), every detonation was in
#     range and set off its effect (dis_detonations = detonations sent), and every one of them was
#     started or counted refused (triggers_fired + triggers_refused + triggers_expired =
#     dis_detonations);
#   - memory flat: no heap allocation after load, by sbfx (heap_allocs_after_load 0) nor by the
#     player's own code (tests/vm/alloc_count.so: as many as a run of one detonation and a few
#     frames), and the resident set (VmRSS) grows by at most 8 MiB from the first 20 % of the run
#     to its end (what grows there is Mesa's and libpng's, reported: docs/simulators.md "Load");
#   - the frame: frames drawn, the frame times and the budget's count of frames over it are printed
#     (measured, not asserted: docs/simulators.md has the figures);
#   - the same through CIGI (tests/net/cigi_send): 50 messages a second, each an effect entity going
#     Active and 100 Entity Controls of a type that is no effect: every message read, every effect
#     entity started or counted refused, every other packet counted ignored, nothing allocated.
# Usage: tests/load.sh [BUILD] (default build). Prints ok/not ok lines.
set -u
cd "$(dirname "$0")/.." || exit 1
BUILD=${1:-build}
PLAYER=$BUILD/sbfx-play
SEND=$BUILD/tests/net/dis_send
SUITE=load
WAIT_S=${LOAD_WAIT_S:-30}
SECONDS_RUN=${LOAD_SECONDS:-60}
ES_RATE=${LOAD_ENTITY_STATES:-5000}
DET_RATE=${LOAD_DETONATIONS:-50}
SCENE=tests/net/range.cfg
ORIGIN=48.137154,11.576124,519.0
. tests/net/common.sh

ALLOC=$BUILD/tests/vm/alloc_count.so
for f in "$PLAYER" "$SEND" "$ALLOC"; do
    [ -e "$f" ] || { fail built "$f was not built (make $f)"; exit 1; }
done

rss_kib() { awk '/^VmRSS:/ { print $2 }' "/proc/$1/status" 2>/dev/null; }
program_allocs() { sed -n 's/^alloc-count: program \([0-9]*\),.*/\1/p' "$1" | tail -n 1; }
all_allocs() { sed -n 's/^alloc-count: program [0-9]*, all \([0-9]*\).*/\1/p' "$1" | tail -n 1; }

# the baseline of the player's own allocations: one detonation, a few frames
port=$(free_port udp)
out=$tmp/baseline
mkdir -p "$out"
LD_PRELOAD=$ALLOC "$PLAYER" --scene "$SCENE" --no-timeline --size 320x180 --fps 30 --frames 100000 --budget-ms 20 \
    --out "$out" --dis "127.0.0.1:$port" >"$out/log" 2>"$out/err" &
pid=$!
until_log "$out/err" 'dis: listening on' || { fail start "the player did not listen: $(head -c 300 "$out/err")"; exit 1; }
"$SEND" --port "$port" --origin "$ORIGIN" --event 1 detonation
sleep 1
kill -TERM "$pid"
wait "$pid"
pid=""
baseline=$(program_allocs "$out/err")

port=$(free_port udp)
out=$tmp/run
mkdir -p "$out"
LD_PRELOAD=$ALLOC "$PLAYER" --scene "$SCENE" --no-timeline --size 320x180 --fps 30 --frames 100000 --budget-ms 20 \
    --out "$out" --stats "$out/stats.json" --dis "127.0.0.1:$port" >"$out/log" 2>"$out/err" &
pid=$!
until_log "$out/err" 'dis: listening on' || { fail start "the player did not listen: $(head -c 300 "$out/err")"; exit 1; }
# the frames' PNGs are not what is measured: keep the folder from filling the disk
( while kill -0 "$pid" 2>/dev/null; do find "$out" -name 'frame-*.png' -mmin -1 -delete 2>/dev/null; sleep 2; done ) &
cleaner=$!
"$SEND" --port "$port" --origin "$ORIGIN" load "$SECONDS_RUN" "$ES_RATE" "$DET_RATE" >"$tmp/sent" &
sender=$!
sleep "$(awk -v s="$SECONDS_RUN" 'BEGIN { print s / 5 }')"
rss_early=$(rss_kib "$pid")
wait "$sender"
sleep 1 # what is still in flight is read, and its effects started at the next frame
rss_late=$(rss_kib "$pid")
kill -TERM "$pid"
wait "$pid" || fail exit "the player exited with an error: $(tail -c 300 "$out/err")"
pid=""
kill "$cleaner" 2>/dev/null
wait "$cleaner" 2>/dev/null

read -r _ es _ det _ <"$tmp/sent"
json() { json_number "$out/stats.json" "$1"; }
pdus=$(json dis_pdus) dets=$(json dis_detonations) ignored=$(json dis_ignored)
fired=$(json triggers_fired) refused=$(json triggers_refused) expired=$(json triggers_expired)
frames=$(json frames) over=$(json frames_over_budget) allocs=$(json heap_allocs_after_load)
echo "# sent $es entity states and $det detonations in $SECONDS_RUN s; read $pdus PDUs ($dets detonations," \
    "$ignored ignored); fired $fired, refused $refused, expired ${expired:-0}"
echo "# $frames frames ($(awk -v f="$frames" -v s="$SECONDS_RUN" 'BEGIN { printf "%.1f", f / (s + 1) }') a second)," \
    "$over over the 20 ms budget; $(grep -o 'sbfx update+render+glFinish: [^(]*' "$out/log" | head -n 1)"
echo "# resident set: $rss_early KiB after $(awk -v s="$SECONDS_RUN" 'BEGIN { print s / 5 }') s, $rss_late KiB at the end"
if [ "$pdus" = $((es + det)) ]; then ok "every-pdu-read ($pdus)"
else
    drops=$(awk '/^Udp:/ { if (h) print $0; h = 1 }' /proc/net/snmp)
    fail every-pdu-read "read $pdus of $((es + det)) (the kernel's UDP counters: $drops)"
fi
[ "$dets" = "$det" ] && ok "every-detonation-in-range-set-off-its-effect ($dets)" ||
    fail every-detonation-in-range-set-off-its-effect "$dets of $det"
if [ $((fired + refused + ${expired:-0})) = "$dets" ]; then
    ok "every-detonation-fired-or-counted-refused (fired $fired + refused $refused + expired ${expired:-0})"
else
    fail every-detonation-fired-or-counted-refused "fired $fired + refused $refused + expired ${expired:-0} != $dets"
fi
program=$(program_allocs "$out/err") everything=$(all_allocs "$out/err")
echo "# allocations: the player's own code $program (a run of one detonation: $baseline), all $everything"
if [ "$allocs" = 0 ] && [ -n "$baseline" ] && [ "$program" = "$baseline" ] && [ -n "$rss_early" ] &&
    [ -n "$rss_late" ] && [ $((rss_late - rss_early)) -le 8192 ]; then
    ok "memory-flat (no allocation by sbfx or the player after load; resident set $rss_early -> $rss_late KiB)"
else
    fail memory-flat "heap_allocs_after_load $allocs, the player's own $program (baseline $baseline), resident" \
        "set $rss_early -> $rss_late KiB"
fi

# ---- the same through CIGI: 50 messages a second, each an effect entity going Active and 100
# entities of a type that is no effect (5,000 Entity Controls a second) ---------------------------
port=$(free_port udp)
out=$tmp/cigi
mkdir -p "$out"
"$PLAYER" --scene tests/net/cigi-range.cfg --no-timeline --size 320x180 --fps 30 --frames 100000 --budget-ms 20 \
    --out "$out" --stats "$out/stats.json" --cigi "127.0.0.1:$port" >"$out/log" 2>"$out/err" &
pid=$!
until_log "$out/err" 'cigi: listening on' || { fail cigi-start "the player did not listen: $(head -c 300 "$out/err")"; exit 1; }
( while kill -0 "$pid" 2>/dev/null; do find "$out" -name 'frame-*.png' -mmin -1 -delete 2>/dev/null; sleep 2; done ) &
cleaner=$!
messages=$(awk -v s="$SECONDS_RUN" -v r="$DET_RATE" 'BEGIN { printf "%d", s * r }')
packets=("entity=1,1001,1,2@0,0,0")
for k in $(seq 0 $((ES_RATE / DET_RATE - 1))); do packets+=("entity=$((10000 + k)),4242,1,0@$((k % 10 * 20)),$((k / 10 * 20)),0"); done
cigi_sent=$(date +%s%N)
"$BUILD/tests/net/cigi_send" --port "$port" --origin "$ORIGIN" --count "$messages" --id-step 1 \
    --interval-ms $((1000 / DET_RATE)) "${packets[@]}" >/dev/null
cigi_took=$(awk -v a="$cigi_sent" -v b="$(date +%s%N)" 'BEGIN { printf "%.1f", (b - a) / 1e9 }')
sleep 1
kill -TERM "$pid"
wait "$pid" || fail cigi-exit "the player exited with an error: $(tail -c 300 "$out/err")"
pid=""
kill "$cleaner" 2>/dev/null
wait "$cleaner" 2>/dev/null
cm=$(json cigi_messages) ce=$(json cigi_entities) ci=$(json cigi_ignored) cb=$(json cigi_malformed)
fired=$(json triggers_fired) refused=$(json triggers_refused) frames=$(json frames) over=$(json frames_over_budget)
echo "# cigi: $messages messages in $cigi_took s, each one effect entity and $((ES_RATE / DET_RATE)) others; read $cm" \
    "($ce effects started, $ci packets ignored, $cb malformed); fired $fired, refused $refused; $frames frames," \
    "$over over the budget; $(grep -o 'sbfx update+render+glFinish: [^(]*' "$out/log" | head -n 1)"
if [ "$cm" = "$messages" ] && [ "$ce" = "$messages" ] && [ "$ci" = $((messages * ES_RATE / DET_RATE)) ] &&
    [ $((fired + refused)) = "$ce" ]; then
    ok "cigi-every-entity-started-or-counted-refused ($ce)"
else
    fail cigi-every-entity-started-or-counted-refused "messages $cm of $messages, entities $ce, ignored $ci," \
        "fired $fired + refused $refused"
fi
[ "$(json heap_allocs_after_load)" = 0 ] && ok cigi-no-allocation-after-load ||
    fail cigi-no-allocation-after-load "heap_allocs_after_load $(json heap_allocs_after_load)"
[ "$failures" = 0 ]
