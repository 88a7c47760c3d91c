#!/bin/sh
# What Mesa's Mali (and V3D: the rpi4 and rpi5 shims) compiler makes of every shader variant the example scenes compile: runs the
# real sbfx-play under the panfrost drm-shim (tools/mesa-shim.sh) once per scene and GPU with
# BIFROST_MESA_DEBUG=shaderdb and SBFX_SHADER_LOG=1, and names each SHADER-DB line after the
# variant sbfx was building when the driver printed it (the log brackets every program build).
# Usage: tools/shader-stats.sh [-b BUILD] [-g "g52 g57 g610 rpi4 rpi5"] [-s "scenes/a.cfg ..."] [-q QUALITY]
#                              [-B] OUT.csv
#   QUALITY: extra sbfx-play flags (e.g. "--opacity spherical"), default none (the scene's own)
#   -B: instead of the scenes, every configuration of the accuracy bench (bench_accuracy
#       --shaders; scene column "bench")
# Columns: gpu, gpu_id, scene, shader, variant, stage, instructions, cycles, arith_cycles,
# texture_cycles, varying_cycles, ldst_cycles, registers, threads, spills, fills.
# cycles is Mesa's bound, the largest of the unit columns; on Valhall arith is the largest of
# its fma, cvt and sfu. threads 2: full occupancy (<= 32 registers), 1: half. The numbers are the
# compiler's static estimates per fragment (every unrolled loop iteration counted), not timings.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
build=build
gpus="g52 g57 g610"
scenes=""
quality=""
bench=0
while getopts b:g:s:q:B opt; do
    case "$opt" in
        b) build=$OPTARG ;;
        g) gpus=$OPTARG ;;
        s) scenes=$OPTARG ;;
        q) quality=$OPTARG ;;
        B) bench=1 ;;
        *) exit 2 ;;
    esac
done
shift $((OPTIND - 1))
[ $# -eq 1 ] || { echo "usage: $0 [-b BUILD] [-g GPUS] [-s SCENES] [-q FLAGS] OUT.csv" >&2; exit 2; }
out=$1
cd "$here"
[ -n "$scenes" ] || scenes=$(ls scenes/*.cfg)
[ "$bench" -eq 0 ] || scenes=bench
play=$build/sbfx-play
[ -x "$play" ] || { echo "shader-stats: $play is missing (make)" >&2; exit 1; }
tools/mesa-shim.sh version >/dev/null 2>&1 || { echo "shader-stats: no Mesa drm-shim build (tools/mesa-shim.sh)" >&2; exit 1; }
logs=$(dirname "$out")/shader-stats
mkdir -p "$logs"

echo "gpu,gpu_id,scene,shader,variant,stage,instructions,cycles,arith_cycles,texture_cycles,varying_cycles,ldst_cycles,registers,threads,spills,fills" >"$out.tmp"
for gpu in $gpus; do
    id=$(tools/mesa-shim.sh env "$gpu" | sed -n 's/^PAN_GPU_ID=//p;s/^V3D_SHIM_VERSION=/v3d/p')
    [ -n "$id" ] || { echo "shader-stats: $gpu is not a panfrost or v3d shim" >&2; exit 2; }
    for scene in $scenes; do
        name=$(basename "$scene" .cfg)
        log=$logs/$gpu-$name.log
        if [ "$scene" = bench ]; then
            set -- "$build/bench/bench_accuracy" --shaders --out "$logs/frames"
        else
            # shellcheck disable=SC2086 # the quality flags are a list
            set -- "$play" --scene "$scene" --frames 3 --size 320x180 $quality --out "$logs/frames"
        fi
        # shellcheck disable=SC2046 # the shim's KEY=VALUE lines
        if ! env $(tools/mesa-shim.sh env "$gpu") SBFX_SHADER_LOG=1 BIFROST_MESA_DEBUG=shaderdb V3D_DEBUG=shaderdb,precompile \
            mesa_glthread=false "$@" >"$log" 2>&1; then
            echo "shader-stats: sbfx-play failed on $gpu with $scene (see $log)" >&2
            exit 1
        fi
        awk -v gpu="$gpu" -v id="$id" -v scene="$name" -f tools/shader-stats.awk "$log" >>"$out.tmp"
    done
done
# one row per (gpu, scene, variant, stage): two media with the same defines are one shader
awk -F, 'NR == 1 || !seen[$1 FS $3 FS $4 FS $5 FS $6]++' "$out.tmp" >"$out"
rm -f "$out.tmp"
echo "shader-stats: $(($(wc -l <"$out") - 1)) shader rows in $out (Mesa $(tools/mesa-shim.sh version))"
