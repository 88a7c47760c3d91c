# tools/shader-stats.sh: one CSV row per SHADER-DB line printed while sbfx built a program.
#   sbfx: info: shader build begin: VERT FRAG | DEFINE DEFINE=VALUE ...
#   SHADER-DB: MESA_SHADER_FRAGMENT shader: 671 inst, ..., 20.4 cycles, 5.0 arith, ... 35 regs
#   sbfx: info: shader build end: program N linked
# Bifrost names its units arith, texture, vary, ldst; Valhall fma, cvt, sfu, v, t, ls.
# V3D (the v3d shim, V3D_DEBUG=shaderdb) prints "SHADER-DB-NAME - STAGE shader: N inst, T threads,
# L loops, U uniforms, M max-temps, S:F spills:fills, X sfu-stalls, Y inst-and-stalls, Z nops":
# its row's cycles are a QPU's cycles per fragment, (inst + stalls) / 4 (a QPU issues one
# instruction a cycle for 4 of a thread's 16 lanes; docs/gpus.md, "V3D"), its arith the same,
# registers the max-temps, threads as printed (1, 2 or 4).
/shader build begin: / {
    s = $0
    sub(/.*shader build begin: /, "", s)
    split(s, halves, / \| /)
    split(halves[1], files, " ")
    shader = files[2]
    variant = halves[2] == "" ? "-" : halves[2]
    inside = 1
    next
}
/shader build end: / { inside = 0; next }
inside && /SHADER-DB-[^ ]* - / {
    s = $0
    sub(/.*SHADER-DB-[^ ]* - /, "", s)
    stage = tolower(shaderdb_fields(s))
    stage = stage ~ /frag|fs/ ? "fragment" : stage ~ /vert|vs/ ? "vertex" : stage
    c = v["inst-and-stalls"] / 4
    printf "%s,%s,%s,%s,%s,%s,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%s,%d,%d,%d\n", gpu, id, scene, shader,
        variant, stage, v["inst"], c, c, 0, 0, 0, v["max-temps"], v["threads"], sf[1], sf[2]
    next
}
inside && /SHADER-DB: / {
    s = $0
    sub(/.*SHADER-DB: /, "", s)
    stage = shaderdb_fields(s)
    sub(/^MESA_SHADER_/, "", stage)
    stage = tolower(stage)
    arith = "arith" in v ? v["arith"] : max3(v["fma"], v["cvt"], v["sfu"])
    tex = "texture" in v ? v["texture"] : v["t"]
    vary = "vary" in v ? v["vary"] : v["v"]
    ldst = "ldst" in v ? v["ldst"] : v["ls"]
    printf "%s,%s,%s,%s,%s,%s,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%s,%d,%d,%d\n", gpu, id, scene, shader,
        variant, stage, v["inst"], v["cycles"], arith, tex, vary, ldst,
        "regs" in v ? v["regs"] : "", v["threads"], sf[1], sf[2]
}
# "STAGE shader: 671 inst, 20.4 cycles, 0:0 spills:fills, ...": the fields into v (name ->
# value) and spills:fills into sf; returns STAGE as printed.
function shaderdb_fields(s,    stage, parts, kv, n, i) {
    stage = s
    sub(/ shader:.*/, "", stage)
    sub(/^[^:]*shader: /, "", s)
    delete v
    n = split(s, parts, /, /)
    for (i = 1; i <= n; i++) {
        split(parts[i], kv, " ")
        v[kv[2]] = kv[1]
    }
    split(v["spills:fills"], sf, ":")
    return stage
}
function max3(a, b, c) { a += 0; b += 0; c += 0; return a > b ? (a > c ? a : c) : (b > c ? b : c) }
