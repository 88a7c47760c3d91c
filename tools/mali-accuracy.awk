# make bench's Mali columns (tests/bench/run.sh): what each accuracy configuration costs on
# the Mali GPUs, from Mesa's static per-fragment estimates (tools/shader-stats.sh -B) and the
# fragments the configuration shades (fragments.csv, counted on llvmpipe by the bench).
#   awk -F, -v cores=4 -v mhz=1000 -f tools/mali-accuracy.awk mali-bench.csv fragments.csv accuracy.csv
# Per configuration and GPU: the particle pass's cycles per fragment (the mean of its variants,
# weighted by the fragments each shades), the composite's, and on the G610 the particle and
# composite passes per frame in ms: fragments x cycles / (cores x clock). An estimate of shader
# throughput only: no bandwidth, blending, tiling or vertex work.
FNR == 1 { file++; if (file == 3) header(); next }
file == 1 && $6 == "fragment" { cycles[$1 SUBSEP $4 SUBSEP $5] = $8; gpus[$1] = 1; next }
file == 2 {
    key = $1 FS $2 FS $3 FS $4 FS $5 FS $6 FS $7 FS $8
    n = split("g52 g57 g610", list, " ")
    if ($9 == "composite.frag") comp_frags[key] = $11
    else part_frags[key] += $11
    for (i = 1; i <= n; i++) {
        g = list[i]
        c = cycles[g SUBSEP $9 SUBSEP $10]
        if (c == "") { missing[key, g] = 1; continue }
        if ($9 == "composite.frag") comp[key, g] = c
        else part[key, g] += $11 * c
    }
    next
}
file == 3 {
    if ($30 == "float") next # the error at GPU precision: the gpu row (issue 25)
    key = $1 FS $2 FS $3 FS $4 FS $5 FS $6 FS $22 FS $23
    if (!(key in part_frags)) next
    printf "%s,%s,%.0f,%.0f", key, $15, part_frags[key], comp_frags[key]
    n = split("g52 g57 g610", list, " ")
    for (i = 1; i <= n; i++) {
        g = list[i]
        if ((key, g) in missing || !(g in gpus)) { printf ",,"; continue }
        printf ",%.3f,%.3f", part[key, g] / part_frags[key], comp[key, g]
    }
    if ((key, "g610") in missing || !("g610" in gpus)) printf ",,\n"
    else printf ",%.3f,%.3f\n", part[key, "g610"] / (cores * mhz * 1000), comp_frags[key] * comp[key, "g610"] / (cores * mhz * 1000)
}
function header() {
    print "mode,scale,format,upsample,lut,detail,density,lod,mean_abs_err,particle_fragments,composite_fragments," \
          "g52_particle_cycles,g52_composite_cycles,g57_particle_cycles,g57_composite_cycles," \
          "g610_particle_cycles,g610_composite_cycles,g610_particle_ms,g610_composite_ms"
}
