#!/usr/bin/env bash
# make bench: what accuracy costs (issue #4, docs/design.md §4).
#   tests/bench/run.sh [BUILD]      (make bench builds $BUILD/bench/bench_accuracy first)
# Writes $BUILD/bench/accuracy.csv, accuracy.md (the same as a markdown table), accuracy.png
# (gnuplot), summary.txt, reference and GPU frames as PNG, then runs the other bench programs
# that exist (lighting, scenes); prints the summary. Where Mesa's drm-shims are built (make
# mesa-shim): mali.csv (.md), mali-bench.csv, accuracy-mali.csv and the Mali columns and panel
# (docs/gpus.md); without them it says so and leaves the Mali columns out.
# BENCH_ARGS passes options to the accuracy program, e.g.
#   BENCH_ARGS="--size 640x360 --reps 3" make bench
#   BENCH_ARGS="--match 'sph/4'" make bench        (one family of configurations)
set -euo pipefail
cd "$(dirname "$0")/../.."

BUILD=${1:-build}
OUT=$BUILD/bench
BIN=$BUILD/bench/bench_accuracy
mkdir -p "$OUT"
if [ ! -x "$BIN" ]; then
    echo "bench: $BIN is missing: run 'make bench'" >&2
    exit 1
fi

start=$(date +%s)
# shellcheck disable=SC2086 # BENCH_ARGS is a list of options
eval "\"$BIN\" --out \"$OUT\" ${BENCH_ARGS:-}"

# issue 21: the same configurations on Mali — Mesa's own compilers through the drm-shims
# (tools/mesa-shim.sh, docs/gpus.md): build/bench/mali.csv (every variant the example scenes
# compile), mali-bench.csv (every variant of this bench) and accuracy-mali.csv (per
# configuration: cycles per fragment, and the G610's particle and composite passes in ms from
# the fragments counted above at MALI_CORES cores and MALI_MHZ, RK3588's G610 MP4 at 1 GHz).
MALI_CORES=${MALI_CORES:-4}
MALI_MHZ=${MALI_MHZ:-1000}
rm -f "$OUT/accuracy-mali.csv" "$OUT/mali-points.dat" "$OUT/mali.csv" "$OUT/mali.md"
if tools/mesa-shim.sh version >/dev/null 2>&1; then
    tools/shader-stats.sh -b "$BUILD" -g "g52 g57 g610 rpi4 rpi5" "$OUT/mali.csv"
    tools/mali-table.sh "$OUT/mali.csv" g52 g610 >"$OUT/mali.md"
    tools/shader-stats.sh -b "$BUILD" -g "g52 g57 g610 rpi4 rpi5" -B "$OUT/mali-bench.csv"
    awk -F, -v cores="$MALI_CORES" -v mhz="$MALI_MHZ" -f tools/mali-accuracy.awk "$OUT/mali-bench.csv" \
        "$OUT/fragments.csv" "$OUT/accuracy.csv" >"$OUT/accuracy-mali.csv"
    # ms on a G52 MP2 at 1920x1080 (the whole frame: particles, composite, depth passes,
    # refinement; the fragments counted at 960x540, x 4), mean error, label, on the G52's own
    # Pareto front (1) or not (0), by time; the front's points labelled
    awk -F, 'NR > 1 && $24 != "" && $1 != "floor" {
        n++
        ms[n] = 4 * ($24 + $25 + $26 + ($28 == "" ? 0 : $28)); err[n] = $9
        label[n] = sprintf("%.3s/%d %s%s%s%s", $1, 1 / $2, $4 == "bilinear" ? "bl" : $4 == "mixed" ? "mx" : "nd",
                           $3 == "RGBA16F" ? "" : $3 == "RGBA8" ? " 8" : " 32F", $5 == "light-per-particle" ? " lpp" : "",
                           $8 > 0 ? " lod" $8 : "")
    }
    END {
        for (i = 2; i <= n; i++) for (j = i; j > 1 && ms[j] < ms[j - 1]; j--) {
            t = ms[j]; ms[j] = ms[j - 1]; ms[j - 1] = t; t = err[j]; err[j] = err[j - 1]; err[j - 1] = t
            t = label[j]; label[j] = label[j - 1]; label[j - 1] = t
        }
        best = 1e30
        for (i = 1; i <= n; i++) {
            front = err[i] < best; if (front) best = err[i]
            printf "%.4f %s \"%s\" %d\n", ms[i], err[i], front ? label[i] : "", front
        }
    }' "$OUT/accuracy-mali.csv" >"$OUT/mali-points.dat"
    echo "mali      : Mesa $(tools/mesa-shim.sh version) drm-shims: $OUT/mali.csv, $OUT/accuracy-mali.csv (static estimates; G610 at $MALI_CORES cores x $MALI_MHZ MHz)" >>"$OUT/summary.txt"
else
    echo "mali      : skipped: no Mesa drm-shim build (make mesa-shim; docs/gpus.md): no mali.csv, no Mali columns" | tee -a "$OUT/summary.txt" >&2
fi

# The table as markdown (for docs/accuracy-and-benchmarks.md); Mali columns where measured.
awk -F, -v mali="$OUT/accuracy-mali.csv" '
# the detail kept (issue 17): band energies relative to the reference, and beta over 4-16 px
function kept(v) { return (v == "" || v == "nan") ? "–" : sprintf("%.2f", v) }
BEGIN {
    while ((getline line < mali) > 0) {
        n = split(line, a, ",")
        k = a[1] FS a[2] FS a[3] FS a[4] FS a[5] FS a[6] FS a[7] FS a[8]
        m[k] = sprintf(" %s / %s | %s / %s | %s |", a[12], a[13], a[16], a[17], a[18] == "" ? "" : sprintf("%.2f", a[18]))
        have = 1
    }
}
NR == 1 {
    for (i = 1; i <= NF; i++) col[$i] = i
    print "| mode | scale | target | upsample | LUT | detail | density | particles | precision | ms (min–max) | particle pass ms | mean err | max err | PSNR dB | edge mean | edge PSNR dB | Pareto | detail kept 2–8 px | 8–32 px | β 4–16 px |" \
        (have ? " G52 cycles/fragment particle / composite | G610 cycles/fragment particle / composite | G610 particle pass ms (est.) |" : "")
    print "| --- | ---: | --- | --- | --- | --- | --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | :---: | ---: | ---: | ---: |" (have ? " ---: | ---: | ---: |" : "")
    next
}
{
    k = $col["mode"] FS $col["scale"] FS $col["format"] FS $col["upsample"] FS $col["lut"] FS $col["detail"] FS $col["density"] FS $col["lod"]
    tail = have ? (k in m ? m[k] : " | | |") : ""
    printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %.1f (%.1f–%.1f) | %.1f | %.3f | %.0f | %.1f | %.2f | %.1f | %s | %s | %s | %s |%s\n",
        $col["mode"], $col["scale"], $col["format"], $col["upsample"], $col["lut"], $col["detail"],
        $col["density"] == "matched" ? "τ/2" : "scene", ("lod" in col && $col["lod"] > 0) ? "lod" $col["lod"] : "all",
        ("precision" in col) ? $col["precision"] : "float",
        $col["ms"], $col["ms_min"], $col["ms_max"], $col["particle_ms"], $col["mean_abs_err"],
        $col["max_abs_err"], $col["psnr"], $col["edge_mean_abs_err"], $col["edge_psnr"],
        $col["pareto"] == 1 ? "★" : "", kept($col["band_2_8"]), kept($col["band_8_32"]), kept($col["beta_4_16"]), tail
}' "$OUT/accuracy.csv" >"$OUT/accuracy.md"

# issue 11: the quality ladder this run's front proposes (make ladder commits it to src/)
tools/ladder.sh "$OUT/accuracy.csv" "$OUT/ladder_default.h" || true

if command -v gnuplot >/dev/null 2>&1; then
    gnuplot -e "dir='$OUT'" tests/bench/accuracy.gp
else
    echo "bench: gnuplot is not installed (apt-get install gnuplot-nox): no $OUT/accuracy.png" >&2
fi

# Other benches built by the Makefile's bench targets run after the accuracy bench
# (issue #7's lighting bench writes $OUT/lighting.csv).
if [ -x "$BUILD/bench/bench_lighting" ]; then
    "$BUILD/bench/bench_lighting" --out "$OUT"
fi
# issue 12: what each tone map does to the particles' light on an 8-bit display
if [ -x "$BUILD/bench/bench_tonemap" ]; then
    "$BUILD/bench/bench_tonemap" --out "$OUT" >/dev/null
    cat "$OUT/tonemap.txt" >>"$OUT/summary.txt"
fi
# issue 17 item 2: fire's luminance against the sky behind it (look-fire.csv)
if [ -x "$BUILD/bench/bench_look_fire" ]; then
    "$BUILD/bench/bench_look_fire" --out "$OUT" | tee "$OUT/look-fire.txt"
fi
# issues #3 and #6: simulation throughput, load time and GPU bytes per scene, post effects
if [ -x "$BUILD/bench/bench_scenes" ]; then
    "$BUILD/bench/bench_scenes" --out "$OUT" | tee "$OUT/scenes.txt"
fi

# issue #10: what the host contract costs (glGet calls, save + restore time; with Mesa's
# threaded dispatch too, where every glGet waits for the driver thread) and far-field depth
if [ -x "$BUILD/bench/bench_state" ]; then
    "$BUILD/bench/bench_state" --out "$OUT" | tee "$OUT/state.txt"
    mesa_glthread=true "$BUILD/bench/bench_state" --out "$OUT" --label glthread --append | tee -a "$OUT/state.txt"
fi

# issue 27: the host's shadow map, per size: ms per sbfx_render_shadow_map, bytes (shadow.csv)
if [ -x "$BUILD/bench/bench_shadow" ]; then
    "$BUILD/bench/bench_shadow" --out "$OUT" | tee "$OUT/shadow.txt"
    cat "$OUT/shadow.txt" >>"$OUT/summary.txt"
fi

# issue 17: the look — beta and band energies per scene, view, time and scale (look.csv), the
# detail's cost (look.txt); docs/look.md. LOOK_ARGS passes options (e.g. "--quick").
if [ -x "$BUILD/bench/bench_look" ]; then
    # shellcheck disable=SC2086 # LOOK_ARGS is a list of options
    "$BUILD/bench/bench_look" --out "$OUT" ${LOOK_ARGS:-} | tee "$OUT/look.log"
    cat "$OUT/look.txt" >>"$OUT/summary.txt"
fi

# issue 11: the frame budget — the barrage at every fixed level and at several budgets
if [ -x "$BUILD/bench/bench_budget" ]; then
    "$BUILD/bench/bench_budget" --out "$OUT" | tee "$OUT/budget.log"
    if command -v gnuplot >/dev/null 2>&1; then gnuplot -e "dir='$OUT'" tests/bench/budget.gp; fi
    cat "$OUT/budget.txt" >>"$OUT/summary.txt"
fi

# issue 33: the boards' frame — every example scene over its life at 1280x720 and 1920x1080 (its
# own camera; the explosion also from the accuracy bench's orbit), fragments per program with the
# particles' tiles and as before them, priced on a G52 MP2 and a G610 MP4 (docs/gpus.md)
if [ -x "$BUILD/bench/bench_boards" ]; then
    "$BUILD/bench/bench_boards" --out "$OUT"
    cp "$OUT/boards.csv" "$OUT/boards-scenes.csv"
    "$BUILD/bench/bench_boards" --out "$OUT" --scenes explosion --camera orbit
    mv "$OUT/boards.csv" "$OUT/boards-orbit.csv"
    # issue 43: each scene's error against its own full-resolution RGBA32F render (errors.csv), and
    # the scenes with mixed resolution (boards-mixed.csv, errors-mixed.csv), at 1280x720
    mkdir -p "$OUT/boards-mixed"
    "$BUILD/bench/bench_boards" --out "$OUT/boards-mixed" --sizes 1280x720 --step 0.5 --error
    mv "$OUT/boards-mixed/errors.csv" "$OUT/errors.csv"
    "$BUILD/bench/bench_boards" --out "$OUT/boards-mixed" --sizes 1280x720 --step 0.5 --quality mixed --error
    mv "$OUT/boards-mixed/boards.csv" "$OUT/boards-mixed.csv"
    mv "$OUT/boards-mixed/errors.csv" "$OUT/errors-mixed.csv"
    mv "$OUT/boards-scenes.csv" "$OUT/boards.csv"
    if [ -r "$OUT/mali.csv" ]; then
        tools/shader-stats.sh -b "$BUILD" -g "g52 g610 rpi4 rpi5" -q "--upsample mixed" "$OUT/mali-mixed.csv"
        { tools/boards-table.sh "$OUT/boards.csv" "$OUT/mali.csv" "$OUT/errors.csv"
          echo; echo "The explosion from the accuracy bench's orbit camera:"; echo
          tools/boards-table.sh "$OUT/boards-orbit.csv" "$OUT/mali.csv"
          echo; echo "Every scene at its own level with mixed resolution (upsample = \"mixed\"), 1280x720:"; echo
          tools/boards-table.sh "$OUT/boards-mixed.csv" "$OUT/mali-mixed.csv" "$OUT/errors-mixed.csv"; } >"$OUT/boards.md"
        echo "boards    : $OUT/boards.md (the boards' frame, docs/gpus.md)" >>"$OUT/summary.txt"
    else
        echo "boards    : $OUT/boards.csv counted; no Mali prices without the drm-shims (make mesa-shim)" >>"$OUT/summary.txt"
    fi
fi

echo "time      : make bench took $(($(date +%s) - start)) s" >>"$OUT/summary.txt"
echo
cat "$OUT/summary.txt"
echo
echo "bench: $OUT/accuracy.csv (.md), $OUT/accuracy.png, $OUT/summary.txt, $OUT/budget.csv, $OUT/budget.png"
