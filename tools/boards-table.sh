#!/bin/sh
# The boards' frame (issue 33; docs/gpus.md, "The boards' frame"): make bench's boards.csv (the
# fragments every program of sbfx shades, frame by frame over each example scene's life, with the
# particles' tiles and as before them: tests/bench/boards/bench_boards.c) priced with Mesa's static
# Mali estimates of the same programs (mali.csv: tools/shader-stats.sh over the example scenes).
#   tools/boards-table.sh BOARDS_CSV MALI_CSV [ERRORS_CSV] > table.md
# Per frame and board: sum over programs of fragments x cycles per fragment / (cores x clock);
# the depth downsample's block is a loop Mesa counts once: its divisor^2 fetches bound it (the
# block unrolled at divisor 4 is texture-bound at exactly that on both GPUs: docs/gpus.md).
# Boards: a Mali-G52 MP2 at 800 MHz (RK3566) and a Mali-G610 MP4 at 1 GHz (RK3588); where MALI_CSV
# has the v3d shims' rows (tools/shader-stats.sh -g "... rpi4 rpi5"), a Raspberry Pi 4 (V3D 4.2,
# 8 QPUs at 500 MHz) and a Pi 5 (V3D 7.1, 16 QPUs at 960 MHz): a V3D row's cycles are one QPU's per
# fragment, (instructions + stalls) / 4 (docs/gpus.md, "V3D"), so the divisor is QPUs x clock. Per scene and
# output size: the mean and the worst frame over the scene's life, before (the composite and the
# depth passes over the whole screen, whole particle rectangles) and after, and what the after
# leaves of a 60 Hz frame (16.67 ms) to the host: shader throughput only, no bandwidth, blending,
# tiling or vertex work. Then, per scene and size, the composite's and the depth passes'
# fragments against the pixels of the tiles' union (their ratio over the life). Then each scene's
# worst frame on the G52 (after) pass by pass: the depth passes (downsample, low-res corners), the
# particles per medium (fire, heat, the scattering media), early termination's marks
# (terminate_mark.frag: render/terminate.c), mixed resolution's refinement (its mark
# and the particles it shades again: boards.csv's refined column), the composite, the post chain.
# The velocity blur's gather (motion_blur.frag) is a loop of SAMPLES - 1 samples that Mesa
# unrolls only up to 7 on the Malis and 3 on V3D, and counts once beyond: it is priced per sample
# (docs/gpus.md, "The post chain"): base + (SAMPLES - 1) x sample, the two measured from the
# unrolled builds at SAMPLES 3, 5 and 7 (tools/shader-stats.sh -s over scenes/post.cfg with
# `samples` 3, 5 and 7; V3D unrolls only 3: its sample is 3's less the loop counted once; per
# fragment: G52 3.875 + 2.25, G610 1.234 + 0.6875, V3D 4.2 12 + 39, V3D 7.1 14.25 + 30.75; its
# FAST variant G52 3.0 + 1.75, G610 1.047 + 0.578, V3D 4.2 32 + 18, V3D 7.1 29.25 + 16.5, V3D from 3
# and 5); measure them again when motion_blur.frag changes. Then, for the scenes with a post chain, its
# programs in the worst frame on the G52: fragments, cycles per fragment as priced, ms.
# With ERRORS_CSV (bench_boards --error), a last table: each scene's error against its own
# full-resolution RGBA32F render (mean |difference| in 8-bit levels over the pixels either image
# changes), the mean over its life and the worst frame.
set -eu
[ $# -eq 2 ] || [ $# -eq 3 ] || { echo "usage: $0 BOARDS_CSV MALI_CSV [ERRORS_CSV]" >&2; exit 2; }
[ -r "$1" ] || { echo "boards-table: $1 is missing (make bench)" >&2; exit 1; }
[ -r "$2" ] || { echo "boards-table: $2 is missing (tools/shader-stats.sh)" >&2; exit 1; }
awk -F, '
function key_of(g, scene, shader, variant) { return g SUBSEP scene SUBSEP shader SUBSEP variant }
# the pass a program belongs to (the per-pass table)
function pass_of(shader, variant) {
    if (shader == "depth_downsample.frag" || shader == "low_corners.frag") return "depth"
    if (shader == "particle.frag") return variant ~ /MEDIUM_EMITS/ ? "fire" : variant ~ /MEDIUM_HEAT/ ? "heat" : "scatter"
    if (shader == "refine_mark.frag") return "refine"
    if (shader == "terminate_mark.frag") return "stop" # early termination of the particles (render/terminate.c)
    if (shader == "composite.frag") return "composite"
    return "post"
}
function left(ms) { return ms >= 16.667 ? "none" : sprintf("%.0f %%", 100 * (16.667 - ms) / 16.667) }
BEGIN {
    gather_base["g52", "full"] = 3.875; gather_sample["g52", "full"] = 2.25
    gather_base["g610", "full"] = 1.2344; gather_sample["g610", "full"] = 0.6875
    gather_base["rpi4", "full"] = 12; gather_sample["rpi4", "full"] = 39
    gather_base["rpi5", "full"] = 14.25; gather_sample["rpi5", "full"] = 30.75
    gather_base["g52", "fast"] = 3.0; gather_sample["g52", "fast"] = 1.75
    gather_base["g610", "fast"] = 1.0469; gather_sample["g610", "fast"] = 0.5781
    gather_base["rpi4", "fast"] = 32; gather_sample["rpi4", "fast"] = 18
    gather_base["rpi5", "fast"] = 29.25; gather_sample["rpi5", "fast"] = 16.5
}
FNR == 1 { file++; next }
file == 1 && $6 == "fragment" { cycles[key_of($1, $3, $4, $5)] = $8; texture[key_of($1, $3, $4, $5)] = $10; has[$1] = 1; next }
file == 2 {
    scene = $1; size = $2 "x" $3; frame = scene SUBSEP size SUBSEP $5; mode = ($6 == "full") ? "before" : "after"
    if ($6 != "full" && $6 != "tiles") next
    if (!((scene, size) in seen)) { seen[scene, size] = 1; order[++n] = scene SUBSEP size }
    frames[frame] = 1
    split("g52 g610 rpi4 rpi5", gpus, " ")
    for (i = 1; i <= 4; i++) {
        if (i > 2 && !has[gpus[i]]) continue
        k = key_of(gpus[i], scene, $7, $8)
        c = cycles[k]
        if (c == "") { if (!warned[k]++) printf "boards-table: no %s cycles for %s %s %s\n", gpus[i], scene, $7, $8 > "/dev/stderr"; missing = 1; continue }
        # the downsample'"'"'s block: its divisor^2 fetches bound it (Mesa counts the loop once); V3D
        # counts the loop once too: its body divisor^2 times
        block = $7 == "depth_downsample.frag" && $8 !~ /SINGLE_TEXEL/ # not mixed resolution'"'"'s full-res depth
        if (block && texture[k] * $4 * $4 > c) c = texture[k] * $4 * $4
        if (block && i > 2) c *= $4 * $4
        if ($7 == "motion_blur.frag" && match($8, /SAMPLES=[0-9]+/)) {
            samples = substr($8, RSTART + 8, RLENGTH - 8) + 0
            fast = $8 ~ /FAST/ ? "fast" : "full"
            priced = gather_base[gpus[i], fast] + (samples - 1) * gather_sample[gpus[i], fast]
            if (priced > c) c = priced
        }
        work[gpus[i], frame, mode] += $9 * c
        if (i == 1 && mode == "after") {
            refined = NF >= 14 ? $14 + 0 : 0
            p = pass_of($7, $8)
            part[frame, p] += ($9 - refined) * c
            part[frame, "refine"] += refined * c
            if (p == "post") {
                prog = $7 ($8 == "-" ? "" : " " $8)
                if (!((frame, prog) in post_frags)) post_progs[frame] = post_progs[frame] SUBSEP prog
                post_frags[frame, prog] += $9; post_cycles[frame, prog] = c
            }
        }
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
    if (has["rpi4"] || has["rpi5"]) {
        clock["rpi4"] = 8 * 500e3; clock["rpi5"] = 16 * 960e3 # QPUs x kHz
        print ""
        print "| scene | output | Raspberry Pi 4 (V3D 4.2): mean / worst (ms) | left to the host (mean / worst) | Raspberry Pi 5 (V3D 7.1): mean / worst (ms) | left (mean / worst) |"
        print "| --- | --- | ---: | ---: | ---: | ---: |"
        for (k = 1; k <= n; k++) {
            split(order[k], sk, SUBSEP)
            line = sprintf("| %s | %s |", sk[1], sk[2])
            for (i = 3; i <= 4; i++) {
                g = i == 3 ? "rpi4" : "rpi5"
                if (!has[g]) { line = line " – | – |"; continue }
                sum = 0; worst = 0; count = 0
                for (f in frames) {
                    split(f, fk, SUBSEP)
                    if (fk[1] != sk[1] || fk[2] != sk[2]) continue
                    ms = work[g, f, "after"] / clock[g]; sum += ms; count++; if (ms > worst) worst = ms
                }
                line = line sprintf(" %.2f / %.2f | %s / %s |", sum / count, worst, left(sum / count), left(worst))
            }
            print line
        }
    }
    print ""
    print "| scene | output | worst frame on the G52 MP2 (t) | depth passes | fire | heat | smoke, dust | termination marks | refinement | composite | post | total (ms) |"
    print "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    split("depth fire heat scatter stop refine composite post", passes, " ")
    for (k = 1; k <= n; k++) {
        split(order[k], sk, SUBSEP)
        worst = -1; wf = ""
        for (f in frames) {
            split(f, fk, SUBSEP)
            if (fk[1] != sk[1] || fk[2] != sk[2]) continue
            if (work["g52", f, "after"] > worst) { worst = work["g52", f, "after"]; wf = f }
        }
        worst_frame[order[k]] = wf
        split(wf, fk, SUBSEP)
        line = sprintf("| %s | %s | %.1f s |", sk[1], sk[2], fk[3])
        for (p = 1; p <= 8; p++) line = line sprintf(" %.2f |", part[wf, passes[p]] / clock["g52"])
        print line sprintf(" %.2f |", worst / clock["g52"])
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
    header = 0
    for (k = 1; k <= n; k++) {
        split(order[k], sk, SUBSEP)
        wf = worst_frame[order[k]]
        if (post_progs[wf] == "") continue
        if (!header++) {
            print ""
            print "| scene | output | worst frame (t) | post program | fragments | G52 cycles per fragment | G52 MP2 ms |"
            print "| --- | --- | ---: | --- | ---: | ---: | ---: |"
        }
        split(wf, fk, SUBSEP)
        np = split(substr(post_progs[wf], 2), progs, SUBSEP)
        total = 0
        for (q = 1; q <= np; q++) {
            ms = post_frags[wf, progs[q]] * post_cycles[wf, progs[q]] / clock["g52"]; total += ms
            printf "| %s | %s | %.1f s | `%s` | %.0f | %.2f | %.2f |\n", sk[1], sk[2], fk[3], progs[q], post_frags[wf, progs[q]], post_cycles[wf, progs[q]], ms
        }
        printf "| %s | %s | %.1f s | the post chain | | | %.2f |\n", sk[1], sk[2], fk[3], total
    }
}' "$2" "$1"
if [ $# -eq 3 ]; then
    [ -r "$3" ] || { echo "boards-table: $3 is missing (bench_boards --error)" >&2; exit 1; }
    awk -F, 'NR > 1 {
        k = $1 " | " $2 "x" $3 " | `" $5 "`"
        if (!(k in n)) order[++m] = k
        n[k]++; sum[k] += $7; if ($7 > worst[k]) worst[k] = $7
    }
    END {
        print ""
        print "| scene | output | level | error against its own full resolution, RGBA32F: mean over the life / worst frame (8-bit levels) |"
        print "| --- | --- | --- | ---: |"
        for (i = 1; i <= m; i++) printf "| %s | %.2f / %.2f |\n", order[i], sum[order[i]] / n[order[i]], worst[order[i]]
    }' "$3"
fi
