#!/usr/bin/env bash
# The command-line contract of sbfx-play (flags in platform/player/options/args.c, docs/player.md):
# --help, clear errors with exit status 1 for bad arguments, and short headless runs that
# write PNG frames, a contact sheet and a --stats JSON object.
# Usage: tests/cli.sh [PLAYER] (default build/sbfx-play). Prints "ok - cli/x" lines for
# tests/run.sh; exits 1 if a test failed.
set -u
PLAYER=${1:-build/sbfx-play}
SUITE=cli
RUN_TIMEOUT=${CLI_RUN_TIMEOUT:-120}
STATS_KEYS="programs textures framebuffers gpu_bytes passes draw_calls composite_tiles composite_pixels particles_simulated heap_allocs_after_load
    budget_ms gpu_ms frames_over_budget quality_changes"
failures=0

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

ok() { echo "ok - $SUITE/$1"; }
fail() {
    echo "not ok - $SUITE/$1: $2"
    failures=$((failures + 1))
}

# play ARGS...: runs the player; sets rc, output in $tmp/out and $tmp/err.
play() {
    timeout -k 5 "$RUN_TIMEOUT" "$PLAYER" "$@" >"$tmp/out" 2>"$tmp/err" </dev/null
    rc=$?
}

first_error_line() { head -n 1 "$tmp/err" | cut -c 1-200; }

# usage_error NAME NEEDLE ARGS...: the player must exit 1 with NEEDLE in its message.
usage_error() {
    local name=$1 needle=$2
    shift 2
    play "$@"
    if [ "$rc" -ne 1 ]; then
        fail "$name" "'$*' exited with $rc, expected 1 ($(first_error_line))"
    elif ! grep -qF -- "$needle" "$tmp/err"; then
        fail "$name" "'$*': the message does not name '$needle': $(first_error_line)"
    else
        ok "$name"
    fi
}

# goes_on NAME "TEXT|TEXT..." KEY VALUE FLAGS...: a run whose input is not there (retried while
# the run goes on) ends with status 0, its log says every TEXT, and its --stats KEY is VALUE.
goes_on() {
    local name=$1 texts=$2 key=$3 value=$4 text missing=""
    shift 4
    play "$@" --stats "$tmp/$name.json"
    if [ "$rc" -ne 0 ]; then
        fail "$name" "'$*' exited with $rc: $(first_error_line)"
        return
    fi
    IFS='|' read -ra texts <<<"$texts"
    for text in "${texts[@]}"; do grep -qF -- "$text" "$tmp/err" || missing="$missing '$text'"; done
    local got
    got=$(json_number "$tmp/$name.json" "$key")
    if [ -n "$missing" ] || [ "$got" != "$value" ]; then
        fail "$name" "the log does not say$missing, or $key is '$got', not $value: $(first_error_line)"
    else
        ok "$name"
    fi
}

# json_number FILE KEY: the value of "KEY": N in the one-object stats file.
json_number() {
    sed -n "s/.*\"$2\"[[:space:]]*:[[:space:]]*\([0-9][0-9]*\).*/\1/p" "$1"
}

is_png() {
    [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]
}

test_help() {
    play --help
    local missing="" flag
    for flag in --headless --size --frames --fps --start-time --out --contact-sheet --stats --trigger \
        --no-timeline --scale --opacity --format --upsample --tone-map --exposure --early-termination --budget-ms --seed --scene --quiet --help --version \
        --display --device --connector --mode --modeset --screenshot --board --video --gpio --dis --dis-exercise \
        --mqtt --mqtt-topic; do
        grep -qF -- "$flag" "$tmp/out" || missing="$missing $flag"
    done
    if [ "$rc" -ne 0 ]; then
        fail help "--help exited with $rc"
    elif [ -n "$missing" ]; then
        fail help "--help does not document:$missing"
    else
        ok help
    fi
}

test_bad_arguments() {
    usage_error bad-size-format --size --size 960
    usage_error bad-size-zero --size --size 0x540
    usage_error bad-size-junk --size --size 960x540px
    usage_error unknown-flag --no-such-flag --no-such-flag
    usage_error stray-argument stray stray
    usage_error frames-negative --frames --frames -1
    usage_error frames-zero --frames --frames 0
    usage_error missing-value --out --out
    usage_error fps-zero --fps --fps 0
    usage_error trigger-no-at --trigger --trigger explosion
    usage_error trigger-bad-time --trigger --trigger explosion@soon
    usage_error trigger-negative-time --trigger --trigger explosion@-1
    usage_error trigger-short-position --trigger --trigger explosion@1:1,2
    usage_error trigger-no-name --trigger --trigger @1
    usage_error trigger-id-zero --trigger --trigger explosion@1#0
    usage_error trigger-id-too-big --trigger --trigger 'explosion@1:0,0,0#9223372036854775808'
    usage_error trigger-id-junk --trigger --trigger 'explosion@1#12a'
    usage_error world-time-negative --world-time --world-time -1
    usage_error world-time-off-grid 'not on the frame grid' --world-time 0.05 --fps 12 --frames 1
    usage_error world-clock-unknown --world-clock --world-clock gps
    usage_error frustum-short --frustum --frustum=-30,30,-10
    usage_error frustum-reversed 'LEFT must be less' --frustum=30,-30,-10,10
    usage_error frustum-too-wide --frustum --frustum=-90,30,-10,10
    usage_error view-offset-junk --view-offset --view-offset=0,a,0
    usage_error bad-scale --scale --scale 3
    usage_error bad-opacity --opacity --opacity fuzzy
    usage_error bad-format --format --format rgb565
    usage_error bad-upsample --upsample --upsample cubic
    usage_error bad-seed --seed --seed -1
    usage_error scene-missing "none.cfg" --scene none.cfg
    printf 'media = { smoke = {\n  densty = 0.4; }; };\n' >"$tmp/typo.cfg"
    usage_error scene-typo "typo.cfg:2: unknown key 'densty' in media.smoke (did you mean 'density'?)" \
        --scene "$tmp/typo.cfg"
    printf 'media = { smoke = { density = -2.0; }; };\n' >"$tmp/range.cfg"
    usage_error scene-range "range.cfg:1: 'density' = -2 is out of range" --scene "$tmp/range.cfg"
    usage_error scene-trigger-unknown "(the scene's effects: plume)" --scene scenes/smoke.cfg --trigger explosion@1
    usage_error bad-tone-map "none|hue-preserving|per-channel|filmic" --tone-map aces
    usage_error bad-exposure --exposure --exposure 0
    usage_error budget-zero --budget-ms --budget-ms 0
    usage_error budget-negative --budget-ms --budget-ms -16
    usage_error budget-nan --budget-ms --budget-ms nan
    usage_error budget-garbage --budget-ms --budget-ms 16ms
    printf 'render = {\n  ladder = [ "exact/4/nd", "exact/8/fast" ]; };\n' >"$tmp/ladder.cfg"
    usage_error scene-ladder "ladder.cfg:2: 'ladder'[1]: quality \"exact/8/fast\": unknown upsample 'fast'" \
        --scene "$tmp/ladder.cfg"
    printf 'render = { budget_ms = 0.0; };\n' >"$tmp/budget.cfg"
    usage_error scene-budget "budget.cfg:1: 'budget_ms' = 0" --scene "$tmp/budget.cfg"
    printf 'media = { smoke = { density = 0.4; }; };\ncamera = {\n  fov = 200.0; };\n%s\n' \
        'effects = { puff = { steps = ( { type = "emitter"; medium = "smoke"; } ); }; };' >"$tmp/camera.cfg"
    usage_error scene-camera "camera.cfg:3: 'fov' = 200 is out of range" --scene "$tmp/camera.cfg"
}

# check_stats NAME FILE: one JSON object holding every key with a number.
check_stats() {
    local name=$1 file=$2 missing="" key
    if [ ! -s "$file" ]; then
        fail "$name" "no stats file $file"
        return
    fi
    for key in $STATS_KEYS; do
        [ -n "$(json_number "$file" "$key")" ] || missing="$missing $key"
    done
    local flat
    flat=$(tr -d ' \n\t' <"$file")
    if [ -n "$missing" ]; then
        fail "$name" "stats lack:$missing ($(head -c 200 "$file"))"
    elif [ "${flat:0:1}" != "{" ] || [ "${flat: -1}" != "}" ] || [ "$(tr -cd '{' <"$file" | wc -c)" -ne 1 ]; then
        fail "$name" "stats are not one JSON object: $(head -c 200 "$file")"
    else
        ok "$name"
    fi
}

test_headless_run() {
    local dir="$tmp/run"
    play --headless --size 160x90 --frames 4 --out "$dir" --contact-sheet --stats "$tmp/run.json" --quiet
    if [ "$rc" -ne 0 ]; then
        fail run "a 4-frame headless run exited with $rc: $(first_error_line)"
        return
    fi
    ok run
    local frames bad=""
    frames=$(find "$dir" -maxdepth 1 -name 'frame-*.png' | wc -l)
    for f in frame-0000 frame-0001 frame-0002 frame-0003; do
        [ -f "$dir/$f.png" ] && is_png "$dir/$f.png" || bad="$bad $f.png"
    done
    if [ "$frames" -ne 4 ] || [ -n "$bad" ]; then
        fail run-frames "expected frame-0000..0003.png, found $frames frames, bad or missing:$bad"
    else
        ok run-frames
    fi
    if [ -f "$dir/contact-sheet.png" ] && is_png "$dir/contact-sheet.png"; then
        ok run-contact-sheet
    else
        fail run-contact-sheet "no valid $dir/contact-sheet.png"
    fi
    check_stats run-stats "$tmp/run.json"
}

test_idle_run() {
    play --no-timeline --size 160x90 --frames 3 --out "$tmp/idle" --stats "$tmp/idle.json" --quiet
    if [ "$rc" -ne 0 ]; then
        fail idle "a --no-timeline run exited with $rc: $(first_error_line)"
        return
    fi
    check_stats idle-stats "$tmp/idle.json"
    local passes simulated tiles
    passes=$(json_number "$tmp/idle.json" passes)
    simulated=$(json_number "$tmp/idle.json" particles_simulated)
    tiles=$(json_number "$tmp/idle.json" composite_tiles)
    if [ "$passes" = 0 ] && [ "$simulated" = 0 ] && [ "$tiles" = 0 ]; then
        ok idle-no-passes
    else
        fail idle-no-passes "--no-timeline: passes=$passes particles_simulated=$simulated composite_tiles=$tiles," \
            "expected 0, 0 and 0"
    fi
}

# A smoke-only scene plans one particle program (+ depth downsample and composite).
test_scene_run() {
    play --scene scenes/smoke.cfg --size 160x90 --frames 6 --out "$tmp/smoke" --stats "$tmp/smoke.json" --quiet
    if [ "$rc" -ne 0 ]; then
        fail scene-run "--scene scenes/smoke.cfg exited with $rc: $(first_error_line)"
        return
    fi
    local programs passes
    programs=$(json_number "$tmp/smoke.json" programs)
    passes=$(json_number "$tmp/smoke.json" passes)
    # smoke, depth, composite and their passes, + the low-res corners' program and pass where
    # RGBA32F renders (src/render/passes.c), + the shadow map's program (render.host_shadows), whose
    # pass is sbfx_render_shadow_map's, not sbfx_render's
    if { [ "$programs" = 4 ] || [ "$programs" = 5 ]; } && [ "${passes:-0}" = "$((programs - 1))" ]; then
        ok scene-run
    else
        fail scene-run "smoke scene: programs=$programs passes=$passes, expected 4 and 3 (5 and 4 with RGBA32F)"
    fi
    # the composite covered the column's tiles: some of the 160 x 90 frame, not all of it (issue 33)
    local tiles pixels
    tiles=$(json_number "$tmp/smoke.json" composite_tiles)
    pixels=$(json_number "$tmp/smoke.json" composite_pixels)
    if [ "${tiles:-0}" -gt 0 ] && [ "${pixels:-0}" -gt 0 ] && [ "${pixels:-0}" -lt $((160 * 90)) ]; then
        ok scene-run-tiles
    else
        fail scene-run-tiles "smoke scene: composite_tiles=$tiles composite_pixels=$pixels, expected some of 14400"
    fi
}

test_trigger_run() {
    play --no-timeline --trigger explosion@0.1:0.5,0,-0.5 --size 160x90 --frames 4 \
        --out "$tmp/trig" --stats "$tmp/trig.json" --quiet
    if [ "$rc" -ne 0 ]; then
        fail trigger-run "exited with $rc: $(first_error_line)"
        return
    fi
    local passes simulated
    passes=$(json_number "$tmp/trig.json" passes)
    simulated=$(json_number "$tmp/trig.json" particles_simulated)
    if [ "${passes:-0}" -gt 0 ] && [ "${simulated:-0}" -gt 0 ]; then
        ok trigger-run
    else
        fail trigger-run "a --trigger after --no-timeline left passes=$passes particles_simulated=$simulated"
    fi
    usage_error trigger-unknown-effect "(the scene's effects: explosion)" --no-timeline --trigger nosuch@0 --size 160x90 \
        --frames 1 --out "$tmp/unknown" --quiet
}

# --start-time (docs/kiosk-and-devices.md "Kiosk months"): a clock started a year in (a whole number of the 4 s
# detail loop and of lit-smoke's 4 s orbit) gives the frames a start at 0 gives; a start of 1 s
# does not (the flag reaches the module); bad values name the flag.
test_start_time() {
    usage_error start-time-negative --start-time --start-time -1
    usage_error start-time-nan --start-time --start-time nan
    usage_error start-time-junk --start-time --start-time 1year
    usage_error start-time-huge --start-time --start-time 1e11
    local s bad="" same=0 f
    for s in 0 31536000 1; do
        play --scene scenes/lit-smoke.cfg --start-time "$s" --size 160x90 --frames 4 --fps 2 --out "$tmp/start-$s" --quiet
        if [ "$rc" -ne 0 ]; then
            fail start-time-year "--start-time $s exited with $rc: $(first_error_line)"
            return
        fi
    done
    for f in frame-0000 frame-0001 frame-0002 frame-0003; do
        cmp -s "$tmp/start-0/$f.png" "$tmp/start-31536000/$f.png" || bad="$bad $f"
        cmp -s "$tmp/start-0/$f.png" "$tmp/start-1/$f.png" && same=$((same + 1))
    done
    if [ -n "$bad" ]; then
        fail start-time-year "--start-time 31536000 differs from 0 in:$bad"
    elif [ "$same" -eq 4 ]; then
        fail start-time-year "--start-time 1 renders what 0 renders: the flag does not reach the clock"
    else
        ok start-time-year
    fi
}

# The platform flags (docs/kiosk-and-devices.md): bad values, missing devices
# and files exit 1 naming them; a missing camera is not fatal. Never opens a real display: the
# DRM device named here does not exist.
test_platform_arguments() {
    usage_error display-bad --display --display kms
    usage_error drm-missing-device /nonexistent/dri/card9 --display drm --device /nonexistent/dri/card9
    usage_error drm-size-conflict --size --display drm --size 640x480 --device /nonexistent/dri/card9
    usage_error headless-device-conflict --device --device /dev/dri/card0
    usage_error drm-bad-mode --mode --display drm --mode 640x480p
    usage_error drm-bad-modeset --modeset --display drm --modeset fast
    usage_error drm-bad-connector --connector --display drm --connector "HDMI A"
    usage_error gpio-no-equals --gpio --gpio gpiochip0:17
    usage_error gpio-no-chip --gpio --gpio :17=explosion
    usage_error gpio-bad-line --gpio --gpio gpiochip0:seventeen=explosion
    usage_error gpio-bad-position --gpio --gpio gpiochip0:17=explosion@1,2
    # a chip that is not there is not fatal (docs/gpio.md): logged naming it, retried, the run goes on
    goes_on gpio-missing-chip "sbfx-no-such-chip|until it appears" gpio_absent 1 \
        --gpio sbfx-no-such-chip:3=explosion --size 160x90 --frames 2 --out "$tmp/gpio" --quiet
    usage_error gpio-unknown-effect "its effects: explosion" --gpio sbfx-no-such-chip:3=nosuch \
        --size 160x90 --frames 1 --out "$tmp/gpio"
    # network trigger sources (docs/triggers.md): a DIS address that is not this machine's stops
    # the run, naming it; a broker that is not there is retried while the run goes on
    usage_error dis-unbindable "--dis 192.0.2.1:3000: binding 192.0.2.1:3000: " --scene tests/net/range.cfg \
        --dis 192.0.2.1:3000 --size 160x90 --frames 1 --out "$tmp/dis"
    goes_on mqtt-missing-broker "cannot reach the broker at 127.0.0.1:1|retrying" mqtt_messages 0 \
        --mqtt 127.0.0.1:1 --size 160x90 --frames 2 --out "$tmp/mqtt" --quiet
    usage_error board-missing "none-board.cfg" --board "$tmp/none-board.cfg"
    printf 'board = "t";\ndisplay = {\n  conector = "HDMI-A-1"; };\n' >"$tmp/typo-board.cfg"
    usage_error board-typo "typo-board.cfg:3: unknown key 'conector' in display" --board "$tmp/typo-board.cfg"
    sed 's/strength = [0-9.]*;/strength = 0.0;/' scenes/smoke.cfg >"$tmp/no-detail.cfg"
    usage_error video-no-detail-volume "/nonexistent/video9: cannot feed the detail volume" \
        --scene "$tmp/no-detail.cfg" --video /nonexistent/video9 --size 160x90 --frames 1 --out "$tmp/video"
    play --video /nonexistent/video9 --size 160x90 --frames 2 --out "$tmp/video" --quiet
    if [ "$rc" -ne 0 ]; then
        fail video-missing-not-fatal "a run with a missing camera exited with $rc: $(first_error_line)"
    elif ! grep -qF "/nonexistent/video9" "$tmp/err" || ! grep -qF "procedural detail" "$tmp/err"; then
        fail video-missing-not-fatal "the message does not name the device and the fallback: $(first_error_line)"
    else
        ok video-missing-not-fatal
    fi
    play --board boards/rk3588.cfg --size 160x90 --frames 1 --out "$tmp/board" --quiet
    if [ "$rc" -eq 0 ] && { [ -e /dev/gpiochip3 ] || grep -qF "gpiochip3" "$tmp/err"; }; then
        ok board-run # on a machine without the board's GPIO chip: logged naming it, retried
    else
        fail board-run "--board boards/rk3588.cfg exited with $rc: $(first_error_line)"
    fi
}

# same_frames DIR_A DIR_B FIRST LAST: the PNGs of frames FIRST..LAST are byte-identical.
same_frames() {
    local i f
    for ((i = $3; i <= $4; i++)); do
        printf -v f 'frame-%04d.png' "$i"
        cmp -s "$1/$f" "$2/$f" || return 1
    done
}

# A GPU reset injected before frame 5 (SBFX_PLAY_INJECT_GPU_RESET, platform/egl/gl_reset.h): the run
# goes on with a new context, GL objects and sbfx. Frames 0-4 are those of a run without the
# reset; from frame 5 the explosion in flight is gone (lost with the old module) and the frames
# are exactly the scene of a run without timeline at the same times (the player's clock went
# on); a --trigger due after the reset fires on the new module.
test_gpu_reset_run() {
    local common=(--headless --size 160x90 --frames 12 --fps 12 --quiet)
    play "${common[@]}" --out "$tmp/reset-normal"
    local normal=$rc
    play "${common[@]}" --out "$tmp/reset-scene" --no-timeline
    local scene=$rc
    SBFX_PLAY_INJECT_GPU_RESET=5 play "${common[@]}" --out "$tmp/reset" --stats "$tmp/reset.json"
    local resets
    resets=$(json_number "$tmp/reset.json" gpu_resets)
    if [ "$rc" -ne 0 ] || [ "$normal" -ne 0 ] || [ "$scene" -ne 0 ]; then
        fail gpu-reset-recovers "exit $rc (reference runs $normal, $scene): $(first_error_line)"
    elif [ "$(grep -c 'GPU reset before frame 5' "$tmp/err")" -ne 1 ] || ! grep -q 'recovered at' "$tmp/err" ||
        [ "${resets:-0}" -ne 1 ] || [ ! -f "$tmp/reset/frame-0011.png" ]; then
        fail gpu-reset-recovers "gpu_resets=$resets, 12 frames: $(ls "$tmp/reset" | wc -l); log: $(head -c 300 "$tmp/err")"
    else
        ok gpu-reset-recovers
    fi
    if ! same_frames "$tmp/reset" "$tmp/reset-normal" 0 4; then
        fail gpu-reset-frames "frames 0-4 (before the reset) differ from a run without it"
    elif same_frames "$tmp/reset" "$tmp/reset-normal" 5 5; then
        fail gpu-reset-frames "frame 5 still shows the explosion of the lost module"
    elif ! same_frames "$tmp/reset" "$tmp/reset-scene" 5 11; then
        fail gpu-reset-frames "frames 5-11 after the reset are not the scene at the same times"
    else
        ok gpu-reset-frames
    fi
    SBFX_PLAY_INJECT_GPU_RESET=3 play "${common[@]}" --out "$tmp/reset-trigger" --no-timeline \
        --trigger explosion@0.5 --stats "$tmp/reset-trigger.json"
    local fired
    fired=$(json_number "$tmp/reset-trigger.json" particles_simulated)
    if [ "$rc" -eq 0 ] && [ "${fired:-0}" -gt 0 ] && same_frames "$tmp/reset-trigger" "$tmp/reset-scene" 0 5 &&
        ! same_frames "$tmp/reset-trigger" "$tmp/reset-scene" 11 11; then
        ok gpu-reset-trigger-after
    else
        fail gpu-reset-trigger-after "exit $rc, particles_simulated=$fired in the last frame (expected the --trigger at 0.5 s to fire on the module made at frame 3)"
    fi
}

if [ ! -x "$PLAYER" ]; then
    fail player "$PLAYER is not built"
    exit 1
fi
# With --budget-ms the stats say the budget and the level (a string); a budget nothing meets
# moves below the top level given by the quality flags.
test_budget_run() {
    play --size 160x90 --frames 12 --out "$tmp/budget" --scale 2 --budget-ms 0.001 --stats "$tmp/budget.json" --quiet
    local quality budget changes
    quality=$(sed -n 's/.*"quality": "\([^"]*\)".*/\1/p' "$tmp/budget.json" 2>/dev/null)
    budget=$(sed -n 's/.*"budget_ms": \([0-9.e-]*\).*/\1/p' "$tmp/budget.json" 2>/dev/null)
    changes=$(json_number "$tmp/budget.json" quality_changes)
    if [ "$rc" -ne 0 ]; then
        fail budget-run "a run with --budget-ms exited with $rc: $(first_error_line)"
    elif [ "$budget" != 0.001 ] || [ -z "$quality" ] || [ "$quality" = exact/2/nd ] || [ "${changes:-0}" -lt 1 ]; then
        fail budget-run "budget_ms=$budget quality=$quality changes=$changes: expected 0.001, a level below exact/2/nd"
    else
        ok budget-run
    fi
    check_stats budget-stats "$tmp/budget.json"
    play --size 160x90 --frames 2 --out "$tmp/nobudget" --stats "$tmp/nobudget.json" --quiet
    quality=$(sed -n 's/.*"quality": "\([^"]*\)".*/\1/p' "$tmp/nobudget.json" 2>/dev/null)
    if [ "$rc" -eq 0 ] && [ "$quality" = exact/4/nd ] && [ "$(json_number "$tmp/nobudget.json" budget_ms)" = 0 ]; then
        ok budget-none-stats
    else
        fail budget-none-stats "without a budget: rc $rc, quality '$quality' ($(head -c 300 "$tmp/nobudget.json"))"
    fi
}

# --version: the Makefile's VERSION.
test_version() {
    local want
    want=$(sed -n 's/^VERSION := //p' Makefile)
    play --version
    if [ "$rc" -eq 0 ] && grep -qx "sbfx-play $want (libsbfx $want)" "$tmp/out"; then
        ok version
    else
        fail version "--version: rc $rc, '$(head -n 1 "$tmp/out")', expected 'sbfx-play $want (libsbfx $want)'"
    fi
}

# The --stats keys --help lists (one table in platform/player/outputs/stats.c makes both): its
# every-run group must be exactly the keys of a headless run's JSON, in order; the man page
# must list every key --help lists, and every flag.
MAN_PAGE=platform/player/sbfx-play.1
help_keys() { sed -n '/^--stats keys/,/^$/p' "$1" | sed -n 's/^    \([a-z_0-9]*\) .*/\1/p'; }
help_keys_every_run() {
    sed -n '/^--stats keys/,/^$/p' "$1" | awk '/^  [^ ]/ { g++ } g == 1 && /^    [a-z]/ { print $1 }'
}
man_keys() { sed -n '/^\.SH STATS KEYS/,/^\.SH /p' "$MAN_PAGE" | sed -n 's/^\.B \([a-z_0-9]*\)$/\1/p'; }
help_flags() { grep -o -- '^  --[a-z-]*' "$1" | sed 's/^  //' | sort -u; }
man_flags() {
    sed -n '/^\.SH OPTIONS/,/^\.SH STATS/p' "$MAN_PAGE" | grep -o '^\.B[IR]* \\-\\-[a-z\\-]*' |
        sed 's/^\.B[IR]* //; s/\\-/-/g' | sort -u
}

test_help_stats_keys() {
    play --help
    cp "$tmp/out" "$tmp/help"
    play --size 64x36 --frames 2 --out "$tmp/keys" --stats "$tmp/keys.json" --quiet
    local json help
    json=$(grep -o '"[a-z_0-9]*":' "$tmp/keys.json" | tr -d '":' | tr '\n' ' ')
    help=$(help_keys_every_run "$tmp/help" | tr '\n' ' ')
    if [ "$rc" -ne 0 ] || [ -z "$json" ]; then
        fail help-stats-keys "the run for its --stats failed (rc $rc)"
    elif [ "$json" != "$help" ]; then
        fail help-stats-keys "--help lists '$help', the JSON has '$json'"
    elif ! grep -q '^Examples:' "$tmp/help"; then
        fail help-stats-keys "--help has no examples"
    else
        ok "help-stats-keys ($(help_keys "$tmp/help" | wc -l) keys, $(echo "$json" | wc -w) in a headless run)"
    fi
}

test_man_page() {
    if [ ! -f "$MAN_PAGE" ]; then
        fail man-page "$MAN_PAGE is missing"
        return
    fi
    local hk mk hf mf warnings
    hk=$(help_keys "$tmp/help" | tr '\n' ' ')
    mk=$(man_keys | tr '\n' ' ')
    hf=$(help_flags "$tmp/help" | tr '\n' ' ')
    mf=$(man_flags | tr '\n' ' ')
    if [ "$hk" != "$mk" ]; then
        fail man-page-stats-keys "$MAN_PAGE lists '$mk', --help '$hk'"
    else
        ok man-page-stats-keys
    fi
    local k undocumented=""
    for k in $hk; do grep -q "^    $k " docs/player.md || undocumented="$undocumented $k"; done
    if [ -n "$undocumented" ]; then
        fail docs-stats-keys "docs/player.md does not list:$undocumented"
    else
        ok docs-stats-keys
    fi
    if [ "$hf" != "$mf" ]; then
        fail man-page-flags "$MAN_PAGE documents '$mf', --help '$hf'"
    else
        ok man-page-flags
    fi
    if command -v man >/dev/null 2>&1 && man --help 2>&1 | grep -q -- --warnings; then
        warnings=$(LC_ALL=C.UTF-8 MANROFFSEQ='' man --warnings -l "$MAN_PAGE" 2>&1 >/dev/null)
    elif command -v groff >/dev/null 2>&1; then
        warnings=$(groff -man -ww -z "$MAN_PAGE" 2>&1)
    else
        echo "skip - $SUITE/man-page-lint: neither man (man-db) nor groff is installed"
        return
    fi
    if [ -n "$warnings" ]; then
        fail man-page-lint "$(echo "$warnings" | head -n 3 | tr '\n' ' ')"
    else
        ok man-page-lint
    fi
}

# A scene whose detail is a clip beside it (docs/detail-clips.md): played, and said so; a
# missing clip stops the player with a message naming the file.
test_clip_run() {
    if ! command -v ffmpeg >/dev/null 2>&1; then
        echo "skip - $SUITE/clip-run: the ffmpeg command is not installed (tools/deps.sh test)"
        return
    fi
    mkdir -p "$tmp/clipscene/clips"
    ffmpeg -hide_banner -loglevel error -nostdin -y -f lavfi -i "mandelbrot=size=64x64:rate=25" \
        -frames:v 40 -c:v ffv1 "$tmp/clipscene/clips/m.mkv"
    sed 's|source = "procedural"|source = "clips/m.mkv"|' scenes/smoke.cfg >"$tmp/clipscene/clip.cfg"
    sed 's|source = "procedural"|source = "clips/none.mp4"|' scenes/smoke.cfg >"$tmp/clipscene/none.cfg"
    play --scene "$tmp/clipscene/clip.cfg" --size 160x90 --frames 2 --out "$tmp/clip"
    if [ "$rc" -eq 0 ] && grep -q "m.mkv: ffv1 in matroska" "$tmp/err" && is_png "$tmp/clip/frame-0001.png"; then
        ok clip-run
    else
        fail clip-run "a clip scene: rc $rc: $(first_error_line)"
    fi
    usage_error clip-missing "$tmp/clipscene/clips/none.mp4" --scene "$tmp/clipscene/none.cfg" --size 160x90 \
        --frames 2 --out "$tmp/clip-none"
}

test_help
test_version
test_help_stats_keys
test_man_page
test_bad_arguments
test_clip_run
test_budget_run
test_headless_run
test_idle_run
test_scene_run
test_trigger_run
test_start_time
test_platform_arguments
test_gpu_reset_run
[ "$failures" -eq 0 ]
