#!/usr/bin/env bash
# One world, many channels (issue 44, docs/simulators.md "The seam test"): three sbfx-play
# processes, each one third of one wide view (--frustum slices of a 60-degree view, 128x128 each:
# the 1/4 particle target's 32 texels and the 32-pixel tiles end at the seams), fed the same three
# detonations (--trigger ...#ID) in different orders, the third started 2 s later than the others
# (--world-time 2.5 rather than 0.5, two of the detonations before its first frame): at world
# times 2.5 and 3.0 their frames side by side equal the single wide render (384x128), every
# differing pixel accounted for (tests/seam/seam_check.c: at the seams within the particle
# target's texel, where the host's own picture differs, a neighbouring texel's value the
# nearest-depth upsample chose, or a difference of at most 2 of 255); a rerun writes the same
# bytes; and a channel given another identity for one detonation fails the check (it can fail);
# with --world-clock system the frames lie on k / fps of the system clock, drawn when it gets there.
# Usage: tests/seam.sh [BUILD] (default build); SEAM_SCENE=FILE: on that scene rather than the
# built-in explosion (docs/simulators.md says what other scenes leave). Prints ok/not ok lines.
set -u
cd "$(dirname "$0")/.." || exit 1
BUILD=${1:-build}
PLAYER=$BUILD/sbfx-play
CHECK=$BUILD/tests/seam/seam_check
for f in "$PLAYER" "$CHECK"; do
    [ -x "$f" ] || { echo "not ok - seam/built: $f was not built (make $f)"; exit 1; }
done
OUT=$(mktemp -d "${TMPDIR:-/tmp}/sbfx-seam.XXXXXX")
trap 'rm -rf "$OUT"' EXIT
failed=0
ok() { echo "ok - seam/$1"; }
not_ok() { echo "not ok - seam/$1: $2"; failed=1; }

# a 60 x 21.79 degree view (tan 30 deg x 1/3 = tan 10.893... deg: square pixels at 384x128) in thirds
B=10.893394649130906
WIDE="-30,30,-$B,$B"
SLICES=("-30,-$B,-$B,$B" "-$B,$B,-$B,$B" "$B,30,-$B,$B")
T1="explosion@0.5:0,0,0#101"; T2="explosion@1.2:3,0,-2#102"; T3="explosion@2.2:-4,0,1#103"
# fps 2: the frames at world times k / 2; the channels from 0.5 (frames 0..5) or 2.5 (frames 0..1)
run() { # NAME SIZE FRUSTUM WORLD_TIME FRAMES [TRIGGER...]
    local name=$1 size=$2 frustum=$3 world=$4 frames=$5
    shift 5
    local args=()
    for t in "$@"; do args+=(--trigger "$t"); done
    "$PLAYER" --headless --quiet --no-timeline --fps 2 --size "$size" --frustum="$frustum" --world-time "$world" \
        ${SEAM_SCENE:+--scene "$SEAM_SCENE"} \
        --frames "$frames" --out "$OUT/$name" "${args[@]}" >"$OUT/$name.log" 2>&1 ||
        { not_ok "$name" "sbfx-play failed: $(tail -3 "$OUT/$name.log")"; return 1; }
}
# the frame of NAME at world time W (fps 2, the run starting at START)
frame() { printf '%s/%s/frame-%04d.png' "$OUT" "$1" "$(awk -v w="$2" -v s="$3" 'BEGIN { printf "%d", (w - s) * 2 + 0.5 }')"; }

run wide 384x128 "$WIDE" 2.5 2 "$T1" "$T2" "$T3" &
run c0 128x128 "${SLICES[0]}" 0.5 6 "$T3" "$T1" "$T2" &
wait
run c1 128x128 "${SLICES[1]}" 0.5 6 "$T2" "$T3" "$T1" &
run c2 128x128 "${SLICES[2]}" 2.5 2 "$T1" "$T3" "$T2" &   # 2 s late: 101 and 102 drawn at their age
wait
run host-wide 384x128 "$WIDE" 2.5 2 & run host-c0 128x128 "${SLICES[0]}" 2.5 2 & wait
run host-c1 128x128 "${SLICES[1]}" 2.5 2 & run host-c2 128x128 "${SLICES[2]}" 2.5 2 & wait
run c1-again 128x128 "${SLICES[1]}" 0.5 6 "$T2" "$T3" "$T1" &
run c1-other 128x128 "${SLICES[1]}" 2.5 2 "explosion@1.2:3,0,-2#999" "$T3" "$T1" &
wait
[ "$failed" = 0 ] || exit 1

for w in 2.5 3.0; do
    host=(-- "$(frame host-c0 "$w" 2.5)" "$(frame host-c1 "$w" 2.5)" "$(frame host-c2 "$w" 2.5)")
    if result=$("$CHECK" 4 2 "$(frame wide "$w" 2.5)" "$(frame host-wide "$w" 2.5)" "$(frame c0 "$w" 0.5)" \
        "$(frame c1 "$w" 0.5)" "$(frame c2 "$w" 2.5)" "${host[@]}"); then
        echo "# world time $w: $result"
        ok "three_channels_equal_the_wide_view_at_$w"
    else
        not_ok "three_channels_equal_the_wide_view_at_$w" "$result"
    fi
done
same=1
for f in "$OUT"/c1/frame-*.png; do cmp -s "$f" "$OUT/c1-again/${f##*/}" || same=0; done
[ "$same" = 1 ] && ok "a_rerun_writes_the_same_bytes" || not_ok "a_rerun_writes_the_same_bytes" "c1's frames differ"
host=(-- "$(frame host-c0 2.5 2.5)" "$(frame host-c1 2.5 2.5)" "$(frame host-c2 2.5 2.5)")
if result=$("$CHECK" 4 2 "$(frame wide 2.5 2.5)" "$(frame host-wide 2.5 2.5)" "$(frame c0 2.5 0.5)" \
    "$(frame c1-other 2.5 2.5)" "$(frame c2 2.5 2.5)" "${host[@]}"); then
    not_ok "another_identity_is_another_explosion" "the check passed: $result"
else
    echo "# another identity: $result"
    ok "another_identity_is_another_explosion"
fi
# --world-clock system: frames at k / fps of the system clock, drawn when it gets there
start=$(date +%s.%N)
"$PLAYER" --headless --quiet --world-clock system --fps 4 --frames 6 --size 64x36 --out "$OUT/system" \
    --stats "$OUT/system.json" >/dev/null 2>&1
end=$(date +%s.%N)
t=$(grep -o '"world_time": [0-9.]*' "$OUT/system.json" | grep -o '[0-9.]*$')
if awk -v t="$t" -v a="$start" -v b="$end" 'BEGIN { k = t * 4; exit !(k == int(k) && t >= a + 1.0 && t <= b) }'; then
    ok "system-clock-frames-on-the-grid (the last frame at $t: on k / 4, between the run's start + 1.25 s and its end)"
else
    not_ok "system-clock-frames-on-the-grid" "world_time '$t', the run from $start to $end"
fi
exit "$failed"
