#!/bin/sh
# The boards' frame (issue 33; docs/gpus.md, "The boards' frame"): make bench's boards.csv (the
# fragments every program of sbfx shades, frame by frame over each example scene's life, with the
# particles' tiles and as before them: tests/bench/boards/bench_boards.c) priced with Mesa's static
# Mali estimates of the same programs (mali.csv: tools/shader-stats.sh over the example scenes).
#   tools/boards-table.sh BOARDS_CSV MALI_CSV > table.md
# Per frame and board: sum over programs of fragments x cycles per fragment / (cores x clock);
# the depth downsample's block is a loop Mesa counts once: its divisor^2 fetches bound it (the
# block unrolled at divisor 4 is texture-bound at exactly that on both GPUs: docs/gpus.md).
# Boards: a Mali-G52 MP2 at 800 MHz (RK3566) and a Mali-G610 MP4 at 1 GHz (RK3588). Per scene and
# output size: the mean and the worst frame over the scene's life, before (the composite and the
# depth passes over the whole screen, whole particle rectangles) and after, and what the after
# leaves of a 60 Hz frame (16.67 ms) to the host: shader throughput only, no bandwidth, blending,
# tiling or vertex work. Then, per scene and size, the composite's and the depth passes'
# fragments against the pixels of the tiles' union (their ratio over the life).
set -eu
[ $# -eq 2 ] || { echo "usage: $0 BOARDS_CSV MALI_CSV" >&2; exit 2; }
[ -r "$1" ] || { echo "boards-table: $1 is missing (make bench)" >&2; exit 1; }
[ -r "$2" ] || { echo "boards-table: $2 is missing (tools/shader-stats.sh)" >&2; exit 1; }
awk -F, '
function key_of(g, scene, shader, variant) { return g SUBSEP scene SUBSEP shader SUBSEP variant }
function left(ms) { return ms >= 16.667 ? "none" : sprintf("%.0f %%", 100 * (16.667 - ms) / 16.667) }
FNR == 1 { file++; next }
file == 1 && $6 == "fragment" { cycles[key_of($1, $3, $4, $5)] = $8; texture[key_of($1, $3, $4, $5)] = $10; next }
file == 2 {
    scene = $1; size = $2 "x" $3; frame = scene SUBSEP size SUBSEP $5; mode = ($6 == "full") ? "before" : "after"
    if ($6 != "full" && $6 != "tiles") next
    if (!((scene, size) in seen)) { seen[scene, size] = 1; order[++n] = scene SUBSEP size }
    frames[frame] = 1
    split("g52 g610", gpus, " ")
    for (i = 1; i <= 2; i++) {
        k = key_of(gpus[i], scene, $7, $8)
        c = cycles[k]
        if (c == "") { if (!warned[k]++) printf "boards-table: no %s cycles for %s %s %s\n", gpus[i], scene, $7, $8 > "/dev/stderr"; missing = 1; continue }
        # the downsample'"'"'s block: its divisor^2 fetches bound it (Mesa counts the loop once)
        if ($7 == "depth_downsample.frag" && texture[k] * $4 * $4 > c) c = texture[k] * $4 * $4
        work[gpus[i], frame, mode] += $9 * c
    }
    if (mode == "after") {
        pixels[frame] = $11
        if ($7 == "composite.frag" && $8 !~ /SCENE_ONLY/ || $7 == "depth_downsample.frag" || $7 == "low_corners.frag")
            drawn[frame] += $9
    }
    next
}
END {
    if (missing) exit 1
    clock["g52"] = 2 * 800e3; clock["g610"] = 4 * 1000e3 # cores x kHz: cycles -> ms
    print "| scene | output | frames | G52 MP2 before: mean / worst (ms) | after: mean / worst | 60 Hz frame left to the host (mean / worst) | G610 MP4 before | after | left (mean / worst) |"
    print "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    for (k = 1; k <= n; k++) {
        split(order[k], sk, SUBSEP)
        line = sprintf("| %s | %s |", sk[1], sk[2])
        count = 0
        for (f in frames) { split(f, fk, SUBSEP); if (fk[1] == sk[1] && fk[2] == sk[2]) count++ }
        line = line sprintf(" %d |", count)
        for (i = 1; i <= 2; i++) {
            g = i == 1 ? "g52" : "g610"
            for (m = 1; m <= 2; m++) {
                mode = m == 1 ? "before" : "after"
                sum = 0; worst = 0
                for (f in frames) {
                    split(f, fk, SUBSEP)
                    if (fk[1] != sk[1] || fk[2] != sk[2]) continue
                    ms = work[g, f, mode] / clock[g]
                    sum += ms; if (ms > worst) worst = ms
                }
                mean[mode] = sum / count; worst_of[mode] = worst
                line = line sprintf(" %.2f / %.2f |", mean[mode], worst)
            }
            line = line sprintf(" %s / %s |", left(mean["after"]), left(worst_of["after"]))
        }
        print line
    }
    print ""
    print "| scene | output | composite + depth passes fragments / pixels of the tiles (over the life) | tiles covered (mean share of the screen) |"
    print "| --- | --- | ---: | ---: |"
    for (k = 1; k <= n; k++) {
        split(order[k], sk, SUBSEP); split(sk[2], wh, "x")
        d = 0; p = 0; share = 0; count = 0
        for (f in frames) {
            split(f, fk, SUBSEP)
            if (fk[1] != sk[1] || fk[2] != sk[2]) continue
            d += drawn[f]; p += pixels[f]; share += pixels[f] / (wh[1] * wh[2]); count++
        }
        printf "| %s | %s | %s | %.0f %% |\n", sk[1], sk[2], (p > 0 ? sprintf("%.3f", d / p) : "–"), 100 * share / count
    }
}' "$2" "$1"
