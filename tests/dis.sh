#!/usr/bin/env bash
# DIS detonations into sbfx-play (issue 35, docs/triggers.md): `sbfx-play --dis 127.0.0.1:PORT`
# headless on tests/net/range.cfg, fed by tests/net/dis_send (PDUs encoded from the standard's
# layout, sent over loopback):
#   - placement: detonations 100 m east, 100 m north and 50 m up of dis.origin (reached by the
#     sender's own geodesy) land within 1 cm of (100, 0, 0), (0, 0, -100), (0, 50, 0);
#   - the effect table: a rule with a result, one without, the default; versions 6 and 7;
#   - the exercise filter, a repeated event within a second (one detonation), the same event
#     after it (a second one), a detonation beyond dis.range (ignored, logged with where it was);
#   - another PDU type ignored; truncated, wrong-version and wrong-length PDUs counted as
#     malformed and logged;
#   - the next frame: a PDU sent while frame K+1 is being made starts its effect at the first
#     step after frame K or K+1 (trigger_log's time), never later;
#   - a storm of 10,000 PDUs, a tenth malformed: every counter exact, frames go on meanwhile, and
#     the player's own code allocates nothing per PDU, nor per frame (tests/vm/alloc_count.so: the
#     same count as a run of one PDU and fewer frames);
#   - a reloaded scene (--watch) brings its dis group: its effects and exercise take over (a
#     dis.exercise dropped: any exercise again); a dis group naming an effect the scene lacks is
#     logged and the one before goes on;
#   - --dis-exercise overrides dis.exercise; --dis without a dis group is refused, naming it.
# Every wait is bounded. Usage: tests/dis.sh [BUILD] (default build). Prints ok/not ok lines.
set -u
cd "$(dirname "$0")/.." || exit 1
BUILD=${1:-build}
PLAYER=$BUILD/sbfx-play
SEND=$BUILD/tests/net/dis_send
ALLOC=$BUILD/tests/vm/alloc_count.so
SUITE=dis
WAIT_S=${DIS_WAIT_S:-30}
SCENE=tests/net/range.cfg
ORIGIN=48.137154,11.576124,519.0
. tests/net/common.sh

for f in "$PLAYER" "$SEND" "$ALLOC"; do
    [ -e "$f" ] || { fail built "$f was not built (make test-platform)"; exit 1; }
done

# start NAME [FLAGS...]: sbfx-play --dis on a free port in the background, until it listens; FPS
# frames a second (headless with --dis, frames come at --fps in real time).
start() {
    local name=$1
    shift
    port=$(free_port udp)
    out=$tmp/$name
    mkdir -p "$out"
    env ${PRELOAD:+LD_PRELOAD=$PRELOAD} "$PLAYER" --scene "$SCENE" --no-timeline --size 64x36 --fps "$FPS" \
        --frames 100000 --out "$out" --stats "$out/stats.json" --dis "127.0.0.1:$port" "$@" \
        >"$out/log" 2>"$out/err" &
    pid=$!
    until_log "$out/err" 'dis: listening on' && return 0
    fail "$name" "the player did not start listening: $(head -c 300 "$out/err")"
    return 1
}

send() { "$SEND" --port "$port" --origin "$ORIGIN" "$@"; }

# newest: the number of the newest frame written (-1: none).
newest() {
    local f
    f=$(ls "$out" | grep -o 'frame-[0-9]*' | sort | tail -n 1)
    [ -n "$f" ] && echo $((10#${f#frame-})) || echo -1
}

# written N: frame N is there (builtins only: no process to wait for).
written() {
    local name
    printf -v name '%s/frame-%04d.png' "$out" "$1"
    [ -e "$name" ]
}

# wait_frames N: until frame N is written.
wait_frames() {
    local deadline=$(($(now_ms) + WAIT_S * 1000))
    until written "$1"; do
        [ "$(now_ms)" -gt "$deadline" ] && return 1
        sleep 0.01
    done
}

# json KEY: a number of the stats file.
json() { json_number "$out/stats.json" "$1"; }

# log_entries: trigger_log's objects, one a line: "source effect x y z time".
log_entries() {
    grep -o '{"source": "[a-z]*", "effect": "[^"]*", "at": \[[^]]*\], "time": [0-9.e+-]*}' "$out/stats.json" |
        sed 's/{"source": "\([a-z]*\)", "effect": "\([^"]*\)", "at": \[\([^,]*\), \([^,]*\), \([^]]*\)\], "time": \(.*\)}/\1 \2 \3 \4 \5 \6/'
}

# ---- one run: placement, mapping, filters, malformed PDUs, the next frame -----------------------
test_detonations() {
    FPS=4 start detonations || return # a frame each 250 ms: time to send between two
    send --version 7 --event 11 --enu 100,0,0 detonation                 # 155 mm HE, result 5: blast
    send --version 6 --event 12 --enu 0,100,0 --result 7 detonation      # air burst: airburst
    send --version 7 --event 13 --enu 0,0,50 --munition 3.1.1.1.1.1.1 detonation # no rule: dust
    send --version 7 --event 14 --exercise 2 detonation                  # another exercise
    send --version 7 --event 15 --enu 10,0,0 --count 2 detonation        # twice: one detonation
    send --version 7 --event 16 --enu 30000,0,0 detonation               # 30 km east: out of range
    send --version 7 entity-state                                        # another PDU type
    send --version 7 --event 17 --cut 50 detonation                      # truncated
    send --version 5 --event 18 detonation                               # DIS 1995
    send --version 7 --event 19 --vp 1 --announce 0 detonation           # 120 bytes saying 104: wrong length
    sleep 1.1
    send --version 6 --event 15 --enu -10,0,0 detonation                 # event 15 again, a second on
    # the next frame: sent right after frame K is written, before frame K+1 is
    local k=-1 try y=0 nexts=0 next
    next=$(($(newest) + 1))
    for try in 1 2 3 4 5 6 7 8; do
        wait_frames "$next" || break
        k=$next next=$((next + 1))
        while written "$next"; do k=$next next=$((next + 1)); done
        send --version 7 --event $((20 + try)) --enu 0,0,$((-5 - try)) detonation
        nexts=$try
        if ! written "$next"; then
            y=$((-5 - try))
            break
        fi
        k=-1
    done
    sleep 0.3
    stop || fail detonations-exit "the player exited with $? on SIGTERM: $(tail -n 3 "$out/err")"

    log_entries >"$tmp/entries"
    local blast air dust
    blast=$(awk '$2 == "blast" && $3 > 50' "$tmp/entries")
    air=$(awk '$2 == "airburst"' "$tmp/entries")
    dust=$(grep -c ' dust ' "$tmp/entries")
    # shellcheck disable=SC2086
    if [ -n "$blast" ] && near3 $(echo "$blast" | awk '{print $3, $4, $5}') 100 0 0 &&
        [ -n "$air" ] && near3 $(echo "$air" | awk '{print $3, $4, $5}') 0 0 -100 &&
        grep -q '^dis dust ' "$tmp/entries" &&
        near3 $(awk '$2 == "dust" && $4 > 25 {print $3, $4, $5}' "$tmp/entries") 0 50 0; then
        ok "placement (100 m east, north, up: within 1 cm of (100,0,0), (0,0,-100), (0,50,0); v6 and v7)"
    else
        fail placement "trigger_log: $(tr '\n' ';' <"$tmp/entries")"
    fi
    if [ -n "$air" ] && [ -n "$blast" ] && [ "$dust" -ge 1 ]; then
        ok "effect-table (result 7: airburst; any result: blast; no rule: the default, dust)"
    else
        fail effect-table "trigger_log: $(tr '\n' ';' <"$tmp/entries")"
    fi
    local tens
    tens=$(awk '$2 == "blast" && ($3 > 9 && $3 < 11 || $3 > -11 && $3 < -9)' "$tmp/entries" | wc -l)
    if [ "$tens" -eq 2 ]; then
        ok "repeats (an event sent twice: one detonation; the same event a second later: another)"
    else
        fail repeats "$tens blasts at +-10 m, want 2: $(tr '\n' ';' <"$tmp/entries")"
    fi
    local pdus det ign mal
    pdus=$(json dis_pdus) det=$(json dis_detonations) ign=$(json dis_ignored) mal=$(json dis_malformed)
    # sent: 12 PDUs and the next frame's; detonations: events 11, 12, 13, 15, 15 a second on and
    # the next frame's; ignored: exercise 2, the repeat of 15, 30 km, the entity state; malformed:
    # 17, 18, 19
    if [ "$pdus" = $((12 + nexts)) ] && [ "$det" = $((5 + nexts)) ] && [ "$ign" = 4 ] && [ "$mal" = 3 ]; then
        ok "counters (dis_pdus $pdus = $det detonations + 4 ignored + 3 malformed)"
    else
        fail counters "dis_pdus $pdus detonations $det ignored $ign malformed $mal (want $((12 + nexts)), $((5 + nexts)), 4, 3)"
    fi
    if grep -q 'is 30.0 km from dis.origin, beyond dis.range (20.0 km): ignored' "$out/err" &&
        grep -q 'malformed PDU dropped (truncated)' "$out/err" &&
        grep -q 'malformed PDU dropped (not protocol version 6 or 7)' "$out/err" &&
        grep -q 'malformed PDU dropped (wrong length)' "$out/err"; then
        ok "logged (out of range with its place; truncated, wrong version, wrong length)"
    else
        fail logged "$(grep 'dis:' "$out/err" | tr '\n' ';' | cut -c 1-400)"
    fi
    local t
    t=$(awk -v y="$y" '$2 == "blast" && $4 > y - 0.5 && $4 < y + 0.5 {print $6}' "$tmp/entries")
    if [ "$k" -lt 0 ] || [ -z "$t" ]; then
        fail next-frame "no frame to send between (k $k) or no trigger_log entry ($t)"
    elif awk -v t="$t" -v k="$k" -v f=4 'BEGIN { exit !(t >= k / f - 1 / 120 - 1e-6 && t <= (k + 1) / f + 1e-6) }'; then
        ok "next-frame (sent after frame $k was written: started at t=$t s, the first step after frame $k or $((k + 1)))"
    else
        fail next-frame "sent after frame $k, before frame $((k + 1)): started at $t s, want $(awk -v k="$k" -v f=4 'BEGIN { print k / f }')..$(awk -v k="$k" -v f=4 'BEGIN { print (k + 1) / f }')"
    fi
}

# ---- a storm: 10,000 PDUs, counters exact, frames go on, nothing allocated per PDU -----------
# The player's own allocations (tests/vm/alloc_count.so): none per frame (the headless PNG
# writer's row table is made at setup, platform/image/png_io.h), none per PDU.
program_allocs() {
    sed -n 's/^alloc-count: program \([0-9]*\),.*/\1/p' "$out/err" | tail -n 1
}

test_storm() {
    # the baseline: one detonation (the first render of particles makes what it makes once)
    FPS=20 PRELOAD=$ALLOC start one-pdu || return
    send --event 1 detonation
    wait_frames 6
    stop || true
    local baseline
    baseline=$(program_allocs)
    FPS=20 PRELOAD=$ALLOC start storm --dis-exercise 3 || return
    wait_frames 2
    local before
    before=$(newest)
    send --exercise 1 --event 1 detonation # exercise 1: --dis-exercise 3 says no
    local sent
    sent=$(send --exercise 3 storm 10000)
    local during
    during=$(newest)
    sleep 0.5
    stop || fail storm-exit "the player exited with $? on SIGTERM: $(tail -n 3 "$out/err")"
    local allocs d i m
    allocs=$(program_allocs)
    read -r _ _ _ d _ i _ m <<<"$sent"
    i=$((i + 1)) # the exercise 1 detonation
    local pdus det ign mal
    pdus=$(json dis_pdus) det=$(json dis_detonations) ign=$(json dis_ignored) mal=$(json dis_malformed)
    if [ "$pdus" = 10001 ] && [ "$det" = "$d" ] && [ "$ign" = "$i" ] && [ "$mal" = "$m" ]; then
        ok "storm-counters (10,001 PDUs: $det detonations, $ign ignored, $mal malformed, as sent)"
    else
        fail storm-counters "dis_pdus $pdus detonations $det ignored $ign malformed $mal; the sender: $sent (+1 ignored)"
    fi
    if [ "$during" -gt "$before" ]; then
        ok "storm-frames (frames $before to $during written while the storm came in)"
    else
        fail storm-frames "no frame written during the storm (newest $before before, $during after)"
    fi
    if [ -n "$baseline" ] && [ "$allocs" = "$baseline" ]; then
        ok "storm-allocations (the player's own code: $allocs allocations with 10,001 PDUs and $(json frames) frames, as with one PDU and fewer)"
    else
        fail storm-allocations "the player's own code allocated $allocs times with the storm, $baseline with one PDU"
    fi
}

# ---- a reloaded scene's dis group -------------------------------------------------------------
# replace_scene SED: the watched copy edited (a new file renamed over it, as editors save), then
# until the player says it reloaded it (the Nth time).
replace_scene() {
    sed "$1" "$SCENE" >"$tmp/watched/.range.cfg.new" && mv "$tmp/watched/.range.cfg.new" "$tmp/watched/range.cfg"
    local deadline=$(($(now_ms) + WAIT_S * 1000))
    until [ "$(grep -c 'scene reloaded: ' "$out/err")" -ge "$2" ]; do
        [ "$(now_ms)" -gt "$deadline" ] && return 1
        sleep 0.05
    done
}

test_reload() {
    mkdir -p "$tmp/watched"
    cp "$SCENE" "$tmp/watched/range.cfg"
    FPS=10 SCENE=$tmp/watched/range.cfg start reload --watch || return
    send --event 1 --enu 1,0,0 detonation                         # 155 mm HE: blast
    wait_frames $(($(newest) + 2))
    # the 155 mm rule sets off dust now, and dis.exercise is gone: exercise 2 counts
    if ! replace_scene 's/effect = "blast"; },/effect = "dust"; },/; /exercise = 1;/d' 1; then
        stop
        fail reload "no reload logged: $(tail -n 3 "$out/err" | tr '\n' ';')"
        return
    fi
    send --event 2 --exercise 2 --enu 2,0,0 detonation            # now: dust
    wait_frames $(($(newest) + 2))
    replace_scene 's/default = "dust";/default = "nosuch";/' 2     # refused: the one before goes on
    send --event 3 --exercise 2 --enu 3,0,0 detonation            # still dust
    wait_frames $(($(newest) + 2))
    stop || fail reload-exit "the player exited with $? on SIGTERM: $(tail -n 3 "$out/err")"
    log_entries >"$tmp/entries"
    local got
    got=$(awk '{printf "%s@%g ", $2, $3}' "$tmp/entries")
    if [ "$got" = "blast@1 dust@2 dust@3 " ] &&
        grep -q "dis: the reloaded scene's dis group is not taken: .*dis.default sets off 'nosuch'" "$out/err"; then
        ok "reload (the edited dis group takes over, exercise any again; a bad one is logged, the one before goes on)"
    else
        fail reload "trigger_log: $got; $(grep 'dis:' "$out/err" | tail -n 2 | tr '\n' ';')"
    fi
}

# ---- refused setups --------------------------------------------------------------------------
test_refused() {
    "$PLAYER" --scene scenes/smoke.cfg --dis 3000 --size 64x36 --frames 1 --out "$tmp/refused" >/dev/null 2>"$tmp/err"
    local rc=$?
    if [ $rc -eq 1 ] && grep -q 'has no dis.origin: DIS places detonations relative to it' "$tmp/err"; then
        ok "no-dis-group (refused, naming dis.origin)"
    else
        fail no-dis-group "rc $rc: $(head -c 300 "$tmp/err")"
    fi
    sed 's/effect = "blast"; },/effect = "nosuch"; },/' "$SCENE" >"$tmp/bad.cfg"
    "$PLAYER" --scene "$tmp/bad.cfg" --dis 3000 --size 64x36 --frames 1 --out "$tmp/refused" >/dev/null 2>"$tmp/err"
    rc=$?
    if [ $rc -eq 1 ] && grep -q "dis.effects sets off 'nosuch', but the scene has no effect of that name (its effects: blast, airburst, dust)" "$tmp/err"; then
        ok "unknown-effect (refused, naming the effects there are)"
    else
        fail unknown-effect "rc $rc: $(head -c 300 "$tmp/err")"
    fi
}

# ---- --world-clock dis: the exercise's absolute timestamps are the world clock ----------------------
test_world_clock() {
    # now, past the hour, by the system clock (as the exercise's senders have it): x 2^31 / 3600,
    # shifted over the absolute bit
    local past=$(($(date +%s) % 3600))
    local ts=$(((past * 2147483648 / 3600) << 1 | 1))
    FPS=10 start world-clock --world-clock dis || return
    send --timestamp "$ts" entity-state
    send --timestamp "$ts" --event 77 --enu 10,0,0 detonation
    sleep 1
    stop || true
    local t s
    t=$(grep -o '"world_time": [0-9.e+]*' "$out/stats.json" | grep -o '[0-9.e+]*$')
    s=$(log_entries | awk '$1 == "dis" { print $6; exit }')
    # the hour is the system clock's: $past s past it, a few seconds later at the last frame
    if awk -v t="$t" -v s="$s" -v p="$past" 'BEGIN { a = t % 3600; d = s % 3600;
        exit !(a >= p && a < p + 10 && d > p - 0.001 && d < p + 0.001) }'; then
        ok "world-clock-from-timestamps (world time $t s: $past s past the hour + the run; the detonation started at $s)"
    else
        fail world-clock-from-timestamps "world_time '$t', the detonation's start '$s' (want $past s past the hour)"
    fi
}

# ---- --follow: a DIS entity as the eyepoint ------------------------------------------------------
test_follow() {
    FPS=10 start follow --follow 1:3:42 || return
    wait_frames 1
    local before
    before=$(newest)
    send --site 1 --app 3 --entity 41 --enu 0,-100,5 --attitude 90,0,0 entity-state  # another entity
    send --site 1 --app 3 --entity 42 --enu 0,-30,2 --attitude 20,5,-3 entity-state
    sleep 0.6
    stop || true
    local line
    line=$(grep -o 'dis: following 1:3:42 at .*' "$out/err" | head -n 1)
    # 30 m south, 2 m up: (0, 2, 30) within 1 cm; its attitude within 0.01 degrees (the sender's own
    # conversion at its place, the player's at dis.origin's: 30 m apart, 0.0003 degrees)
    if awk -v l="$line" 'BEGIN { n = split(l, w, /[ ,()]+/); x = w[5]; y = w[6]; z = w[7]; h = w[9]; p = w[11]; r = w[13];
        d = sqrt(x * x + (y - 2) ^ 2 + (z - 30) ^ 2);
        exit !(d < 0.01 && (h - 20) ^ 2 < 1e-4 && (p - 5) ^ 2 < 1e-4 && (r + 3) ^ 2 < 1e-4) }'; then
        ok "follow-an-entity ($line)"
    else
        fail follow-an-entity "'$line' (want 0, 2, 30, heading 20, pitch 5, roll -3)"
    fi
    # the last frame against the same frame without --follow (the scene's camera at the same time)
    local last a b
    last=$(newest)
    "$PLAYER" --scene "$SCENE" --no-timeline --size 64x36 --fps 10 --frames $((last + 1)) --quiet \
        --out "$tmp/unfollowed" >/dev/null 2>&1
    printf -v a '%s/frame-%04d.png' "$out" "$last"
    printf -v b '%s/unfollowed/frame-%04d.png' "$tmp" "$last"
    printf -v c '%s/frame-%04d.png' "$out" "$before"
    printf -v d '%s/unfollowed/frame-%04d.png' "$tmp" "$before"
    if [ -e "$a" ] && [ -e "$b" ] && ! cmp -s "$a" "$b" && cmp -s "$c" "$d"; then
        ok "follow-moves-the-eyepoint (frame $last differs from the scene camera's; frame $before, before, does not)"
    else
        fail follow-moves-the-eyepoint "frame $last against $b, frame $before against $d"
    fi
}

test_detonations
test_storm
test_reload
test_refused
test_world_clock
test_follow
exit $((failures > 0))
