#!/usr/bin/env bash
# make ladder: the default quality ladder (docs/design.md §6, issue 11) from the accuracy bench's CSV.
#   tools/ladder.sh ACCURACY_CSV [MORE_CSV...] OUT_HEADER
# The qualities the module offers (opacity model, scale, upsampling, target format, light per
# particle; the default's tables, half-float detail, the scene's density) are walked from the least mean error
# up; a quality becomes the next rung if its whole-frame time (median) is at least SAVING (10 %)
# below the rung above it — the Pareto front of error against time, thinned so that every rung
# pays for its error with a saving larger than the noise of a shared machine (every rung kept is
# on the front: nothing more accurate is as cheap). Below the cheapest rung come its particle
# levels of detail (the bench's `lod` rows: at most N particles, src/sim/lod.h), fewest last. Errors
# are the `gpu` precision rows' (mediump as written, 8-bit filter weights: what GPUs compute).
# Several runs' CSVs (the same configurations, in the same order): each configuration's time is the
# least of its runs' medians (a shared machine's noise only ever adds time; one run's medians moved
# by a third between quiet runs), its errors must agree. LADDER_CSV=PATH keeps the CSV the ladder
# was made from (docs/ladder-accuracy.csv).
# Level names: <opacity>/<divisor>/<nd|bl|mx>[/rgba8|/rgba32f][/lpp][/lodN].
set -euo pipefail
usage="usage: tools/ladder.sh ACCURACY_CSV [MORE_CSV...] OUT_HEADER"
[ $# -ge 2 ] || { echo "$usage" >&2; exit 2; }
runs=("${@:1:$#-1}")
out=${!#}
for csv in "${runs[@]}"; do
    [ -r "$csv" ] || { echo "ladder: $csv is missing: run the accuracy bench (make bench)" >&2; exit 1; }
done
SAVING=${LADDER_SAVING:-0.10}
tmp=$(mktemp)
merged=$(mktemp)
trap 'rm -f "$tmp" "$merged"' EXIT

# the runs as one CSV: the first run's rows, each "ms" the least of the runs'
awk -F, -v OFS=, '
function fail(why) { print "ladder: " FILENAME ": " why > "/dev/stderr"; bad = 1; exit 1 }
FNR == 1 {
    if (++files == 1) {
        header = $0
        for (c = 1; c <= NF; c++) col[$c] = c
        split("mode scale format upsample lut detail density lod precision mean_abs_err", names, " ")
        for (k in names) if (names[k] in col) key[names[k]] = col[names[k]]
    } else {
        if ($0 != header) fail("other columns than the first run")
        if (files > 2 && seen != rows) fail("the run before has " seen " rows, the first " rows)
    }
    seen = 0
    next
}
files == 1 { rows++; line[rows] = $0; ms[rows] = $col["ms"] + 0; next }
{
    seen++
    split(line[seen], first, ",")
    for (k in key) if ($key[k] != first[key[k]]) fail("row " FNR ": " k " " $key[k] ", the first run: " first[key[k]])
    if ($col["ms"] + 0 < ms[seen]) ms[seen] = $col["ms"] + 0
}
END {
    if (bad) exit 1
    if (files > 1 && seen != rows) { print "ladder: the last run has " seen " rows, the first " rows > "/dev/stderr"; exit 1 }
    print header
    for (r = 1; r <= rows; r++) {
        n = split(line[r], f, ",")
        f[col["ms"]] = sprintf("%.3f", ms[r])
        s = f[1]
        for (c = 2; c <= n; c++) s = s "," f[c]
        print s
    }
}' "${runs[@]}" >"$merged"
csv=$merged
src=$(basename "${runs[0]}")
[ ${#runs[@]} -gt 1 ] && src="${#runs[@]} runs ($(for r in "${runs[@]}"; do basename "$r"; done | paste -sd' '))"
[ -n "${LADDER_CSV:-}" ] && cp "$merged" "$LADDER_CSV"

# the default level's tables, the lut most rows have: the black body's table and the analytic
# phase since issue 43 ("analytic-phase"); a CSV from before it has both tables ("table")
default_lut=$(awk -F, 'NR == 1 { for (c = 1; c <= NF; c++) if ($c == "lut") l = c; next }
    $l != "light-per-particle" { n[$l]++ } END { for (k in n) if (n[k] > best) { best = n[k]; v = k } print v }' "$csv")
awk -F, -v saving="$SAVING" -v src="$src" -v default_lut="$default_lut" '
function divisor(scale) { return scale == 1 ? 1 : scale == 0.5 ? 2 : scale == 0.25 ? 4 : 8 }
function name(i,   s) {
    s = mode[i] "/" divisor(scale[i]) "/" (ups[i] == "bilinear" ? "bl" : ups[i] == "mixed" ? "mx" : "nd")
    if (fmt[i] == "RGBA8") s = s "/rgba8"
    if (fmt[i] == "RGBA32F") s = s "/rgba32f"
    if (lut[i] == "light-per-particle") s = s "/lpp"
    if (lod[i] > 0) s = s "/lod" lod[i]
    return s
}
NR == 1 { for (c = 1; c <= NF; c++) col[$c] = c; next }
{
    n++
    mode[n] = $col["mode"]; scale[n] = $col["scale"] + 0; fmt[n] = $col["format"]
    ups[n] = $col["upsample"]; lut[n] = $col["lut"]; ms[n] = $col["ms"] + 0
    err[n] = $col["mean_abs_err"] + 0; edge[n] = $col["edge_mean_abs_err"] + 0
    lod[n] = ("lod" in col) ? $col["lod"] + 0 : 0
    # chosen at GPU precision (issue 25): the gpu rows, where the bench wrote both
    quality[n] = mode[n] != "floor" && $col["density"] == "scene" && $col["detail"] == "R16F" &&
                 (lut[n] == default_lut || lut[n] == "light-per-particle") &&
                 (!("precision" in col) || $col["precision"] == "gpu")
}
END {
    m = 0
    for (i = 1; i <= n; i++) if (quality[i] && lod[i] == 0) cand[++m] = i
    for (a = 2; a <= m; a++) # insertion sort: error, then time
        for (b = a; b > 1 && (err[cand[b]] < err[cand[b-1]] || (err[cand[b]] == err[cand[b-1]] && ms[cand[b]] < ms[cand[b-1]])); b--) {
            t = cand[b]; cand[b] = cand[b-1]; cand[b-1] = t
        }
    k = 0
    for (a = 1; a <= m; a++) {
        i = cand[a]
        if (k == 0 || ms[i] < ms[rung[k]] * (1 - saving)) rung[++k] = i
    }
    if (k == 0) { print "ladder: no quality rows in " src > "/dev/stderr"; exit 1 }
    last = rung[k]; pareto = k
    for (N = 1e9; ; ) { # the cheapest rung with at most N particles, N falling
        best = 0
        for (i = 1; i <= n; i++)
            if (quality[i] && lod[i] > 0 && lod[i] < N && mode[i] == mode[last] && scale[i] == scale[last] &&
                ups[i] == ups[last] && fmt[i] == fmt[last] && lut[i] == lut[last] && (!best || lod[i] > lod[best]))
                best = i
        if (!best) break
        rung[++k] = best; N = lod[best]
    }
    if (k == pareto) { print "ladder: no lod rows for " name(last) " in " src ": run the full accuracy bench" > "/dev/stderr"; exit 1 }
    for (a = 1; a <= k; a++) {
        i = rung[a]
        printf "%s %.3f %.4f %.3f %s\n", name(i), ms[i], err[i], edge[i], a <= pareto ? "front" : "lod"
    }
}' "$csv" >"$tmp"

{
    echo "/* Generated by tools/ladder.sh (make ladder): do not edit. From the accuracy bench's"
    if [ ${#runs[@]} -gt 1 ]; then
        echo " * $src, each time the least of the runs' medians."
    else
        echo " * $src."
    fi
    echo " * The default quality ladder (docs/design.md §6), most accurate first: the Pareto front of"
    echo " * mean error against whole-frame time, each rung at least $(awk -v s="$SAVING" 'BEGIN{printf "%g", s*100}') % cheaper than the one"
    echo " * above it, then the cheapest rung's particle levels of detail (src/sim/lod.h). Errors in 8-bit"
    echo " * levels against the CPU reference (docs/accuracy-and-benchmarks.md), times the GPU's median"
    echo " * for the built-in explosion over the test scene; provenance: docs/quality-and-budgets.md \"Frame budgets\"."
    echo " * Regenerate: make bench (or bench_accuracy alone), then make ladder. */"
    echo "#ifndef SBFX_LADDER_DEFAULT_H"
    echo "#define SBFX_LADDER_DEFAULT_H"
    echo ""
    echo "static const char *const sbfx_ladder_default[] = {"
    awk '{ printf "    %-24s /* mean error %6.3f (near silhouettes %6.3f), %8.2f ms%s */\n", "\"" $1 "\",", $3, $4, $2, $5 == "lod" ? ", level of detail" : "" }' "$tmp"
    echo "};"
    echo ""
    echo "/* The bench's whole-frame time of each rung (ms): the governor's prior of relative costs. */"
    echo "static const double sbfx_ladder_default_ms[] = {"
    awk '{ printf "    %.3f,\n", $2 }' "$tmp"
    echo "};"
    echo ""
    echo "/* The bench's mean error of each rung against the CPU reference (8-bit levels). */"
    echo "static const double sbfx_ladder_default_error[] = {"
    awk '{ printf "    %.4f,\n", $3 }' "$tmp"
    echo "};"
    echo ""
    echo "#define SBFX_LADDER_DEFAULT_COUNT $(wc -l <"$tmp")"
    echo ""
    echo "#endif"
} >"$out"
echo "ladder: $out: $(wc -l <"$tmp") levels from $src"
