# make bench's Mali columns (tests/bench/run.sh): what each accuracy configuration costs on
# the Mali GPUs, from Mesa's static per-fragment estimates (tools/shader-stats.sh -B) and the
# fragments each of the configuration's programs shades (fragments.csv, counted on llvmpipe by
# the bench: tests/bench/bench_fragments.h).
#   awk -F, -v cores=4 -v mhz=1000 -v g52_cores=2 -v g52_mhz=800 -f tools/mali-accuracy.awk \
#       mali-bench.csv fragments.csv accuracy.csv
# Per configuration and GPU, the cycles per fragment (the mean over a pass's programs, weighted by
# the fragments each shades) of three parts: the particle pass; the composite; the depth passes
# (the depth downsample and the low-res corners). The depth downsample's block is a loop, which
# Mesa's estimate counts once: its divisor^2 fetches bound it (texture cycles x divisor^2, where
# that is more than the estimate; as tools/boards-table.sh, docs/gpus.md). Then each part
# per frame in ms on a G610 MP4 at 1 GHz (cores, mhz) and a G52 MP2 at 800 MHz (g52_cores,
# g52_mhz): fragments x cycles / (cores x clock). An estimate of shader throughput only: no
# bandwidth, blending, tiling or vertex work.
# Mixed resolution (upsample "mixed"): its mark (refine_mark.frag) is a fourth part, "refine"; the
# particles it shades again are in the particle part (fragments.csv counts them with the coarse
# ones), its full-resolution depth in the depth part. Last, where mali-bench.csv has the v3d
# shims' rows: the whole frame (the four parts) in ms on a Raspberry Pi 4 (V3D 4.2, 8 QPUs at
# 500 MHz) and 5 (V3D 7.1, 16 QPUs at 960 MHz), a V3D row's cycles being one QPU's per fragment
# (tools/shader-stats.awk; docs/gpus.md, "V3D"); the downsample's loop counted divisor^2 times.
BEGIN { if (g52_cores == "") g52_cores = 2; if (g52_mhz == "") g52_mhz = 800 }
FNR == 1 { file++; if (file == 3) header(); next }
file == 1 && $6 == "fragment" { cycles[$1 SUBSEP $4 SUBSEP $5] = $8; texture[$1 SUBSEP $4 SUBSEP $5] = $10; gpus[$1] = 1; next }
file == 2 {
    key = $1 FS $2 FS $3 FS $4 FS $5 FS $6 FS $7 FS $8
    part = part_of($9)
    if (part == "") next
    frags[part, key] += $11
    # divisor^2 (scale = 1 / divisor); mixed resolution's full-resolution depth (SINGLE_TEXEL) has no block
    fetches = $9 == "depth_downsample.frag" && $10 !~ /SINGLE_TEXEL/ ? 1 / ($2 * $2) : 0
    n = split("g52 g57 g610 rpi4 rpi5", list, " ")
    for (i = 1; i <= n; i++) {
        g = list[i]
        c = cycles[g SUBSEP $9 SUBSEP $10]
        if (c == "") { missing[key, g] = 1; continue }
        if (texture[g SUBSEP $9 SUBSEP $10] * fetches > c) c = texture[g SUBSEP $9 SUBSEP $10] * fetches
        if (g ~ /^rpi/ && fetches > 0) c *= fetches
        work[part, key, g] += $11 * c
    }
    next
}
file == 3 {
    if ($30 == "float") next # the error at GPU precision: the gpu row (issue 25)
    key = $1 FS $2 FS $3 FS $4 FS $5 FS $6 FS $22 FS $23
    if (!(("particle", key) in frags)) next
    printf "%s,%s,%.0f,%.0f", key, $15, frags["particle", key], frags["composite", key]
    n = split("g52 g57 g610", list, " ")
    for (i = 1; i <= n; i++) {
        g = list[i]
        if (!usable(key, g)) { printf ",,"; continue }
        printf ",%.3f,%.3f", per_fragment("particle", key, g), per_fragment("composite", key, g)
    }
    if (!usable(key, "g610")) printf ",,"
    else printf ",%.3f,%.3f", ms("particle", key, "g610", cores, mhz), ms("composite", key, "g610", cores, mhz)
    printf ",%.0f", frags["depth", key]
    if (!usable(key, "g52") || !usable(key, "g610")) { printf ",,,,,,,,,,,\n"; next }
    printf ",%.3f,%.3f,%.3f", per_fragment("depth", key, "g52"), per_fragment("depth", key, "g610"),
        ms("depth", key, "g610", cores, mhz)
    printf ",%.3f,%.3f,%.3f", ms("particle", key, "g52", g52_cores, g52_mhz),
        ms("composite", key, "g52", g52_cores, g52_mhz), ms("depth", key, "g52", g52_cores, g52_mhz)
    printf ",%.0f,%.3f,%.3f", frags["refine", key], ms("refine", key, "g52", g52_cores, g52_mhz),
        ms("refine", key, "g610", cores, mhz)
    printf ",%s,%s\n", frame_ms(key, "rpi4", 8, 500), frame_ms(key, "rpi5", 16, 960)
}
function part_of(shader) {
    if (shader == "particle.frag" || shader == "terminate_mark.frag") return "particle" # its early termination's marks too
    if (shader == "composite.frag") return "composite"
    if (shader == "depth_downsample.frag" || shader == "low_corners.frag") return "depth"
    if (shader == "refine_mark.frag") return "refine"
    return ""
}
# the whole frame's four parts on a V3D board (QPUs x MHz), or empty without its rows
function frame_ms(key, g, qpus, clock) {
    if (!usable(key, g)) return ""
    t = ms("particle", key, g, qpus, clock) + ms("composite", key, g, qpus, clock)
    t += ms("depth", key, g, qpus, clock) + ms("refine", key, g, qpus, clock)
    return sprintf("%.3f", t)
}
function usable(key, g) { return !((key, g) in missing) && (g in gpus) }
function per_fragment(part, key, g) { return frags[part, key] > 0 ? work[part, key, g] / frags[part, key] : 0 }
function ms(part, key, g, n, clock) { return work[part, key, g] / (n * clock * 1000) }
function header() {
    print "mode,scale,format,upsample,lut,detail,density,lod,mean_abs_err,particle_fragments,composite_fragments," \
          "g52_particle_cycles,g52_composite_cycles,g57_particle_cycles,g57_composite_cycles," \
          "g610_particle_cycles,g610_composite_cycles,g610_particle_ms,g610_composite_ms," \
          "depth_fragments,g52_depth_cycles,g610_depth_cycles,g610_depth_ms," \
          "g52_particle_ms,g52_composite_ms,g52_depth_ms,refine_fragments,g52_refine_ms,g610_refine_ms,rpi4_ms,rpi5_ms"
}
