#!/usr/bin/env bash
# The short soak of `make test` (docs/kiosk-and-devices.md "Kiosk months"; `make soak` runs hours):
#   soak/flat          9 simulated minutes of the five default scenes, triggers every 0.2 s:
#                      exit 0, "flat after warm-up", a CSV with a header and every sample
#   soak/catches-*     the same check must fail (exit 2) and name what grew when the soak
#                      leaks on purpose: a 64x64 GL texture (the context's live textures) or
#                      256 KiB of heap (malloc) every 20 frames (5 simulated seconds)
#   soak/bad-argument  a bad value names the flag, exit 1
# Usage: tests/soak.sh [BUILD] (default build). Prints ok/not ok lines (tests/check.h style).
set -u
cd "$(dirname "$0")/.." || exit 1
BUILD=${1:-build}
SOAK=$BUILD/sbfx-soak
failed=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

ok() { echo "ok - soak/$1"; }
not_ok() { echo "not ok - soak/$1: $2"; failed=1; }

if [ ! -x "$SOAK" ]; then
    not_ok built "$SOAK was not built (make all)"
    exit 1
fi

# soak NAME ARGS...: runs it; rc, $tmp/NAME.out, $tmp/NAME.err
soak() {
    local name=$1
    shift
    timeout -k 5 120 "$SOAK" --quiet --out "$tmp/$name" "$@" >"$tmp/$name.out" 2>"$tmp/$name.err" </dev/null
    rc=$?
}

soak flat --hours 0.15 --rss-tolerance 8192
samples=$(($(wc -l <"$tmp/flat/soak.csv" 2>/dev/null || echo 1) - 1))
if [ "$rc" -ne 0 ]; then
    not_ok flat "exit $rc: $(grep -m 3 . "$tmp/flat.err" | tr '\n' ' ')"
elif ! grep -q "flat after warm-up" "$tmp/flat.out" || [ "$samples" -lt 100 ] ||
    ! head -n 1 "$tmp/flat/soak.csv" | grep -q '^sim_hours,frames,.*rss_anon_kib.*gl_textures'; then
    not_ok flat "no verdict or no record ($samples samples): $(tail -n 3 "$tmp/flat.out" | tr '\n' ' ')"
else
    ok "flat (9 simulated minutes, $samples samples: $(grep -m 1 'rss_anon_kib' "$tmp/flat.out" | sed 's/^sbfx-soak: //'))"
fi

# catches KIND NEEDLE: a leak of KIND must fail the check with NEEDLE on stderr.
catches() {
    local kind=$1 needle=$2
    soak "leak-$kind" --hours 0.05 --scene history-blur --render-every 2 --leak-every 20 --inject-leak "$kind"
    if [ "$rc" -ne 2 ]; then
        not_ok "catches-$kind" "a leaking soak exited with $rc, expected 2: $(grep -m 3 . "$tmp/leak-$kind.err" | tr '\n' ' ')"
    elif ! grep -q -- "$needle" "$tmp/leak-$kind.err"; then
        not_ok "catches-$kind" "the failure does not name '$needle': $(grep -m 3 . "$tmp/leak-$kind.err" | tr '\n' ' ')"
    else
        ok "catches-$kind ($(grep -m 1 -- "$needle" "$tmp/leak-$kind.err" | sed 's/^sbfx-soak: not flat: //' | cut -c 1-80))"
    fi
}
catches texture "gl_textures grew"
catches malloc "heap_bytes grew"

soak bad --dt 1
if [ "$rc" -eq 1 ] && grep -q -- "--dt" "$tmp/bad.err"; then
    ok bad-argument
else
    not_ok bad-argument "--dt 1 exited with $rc: $(head -n 1 "$tmp/bad.err")"
fi
[ "$failed" -eq 0 ]
