#!/bin/sh
# make test-gpus: every example scene under the drm-shims of Mesa's drivers for the GPUs sbfx
# targets (tools/mesa-shim.sh builds them): Mali-G52 and G610 (panfrost), V3D 4.2 and 7.1
# (Raspberry Pi 4 and 5, v3d), Adreno 618 (freedreno) and Vivante GC7000L (etnaviv). The real
# drivers compile and link every shader sbfx builds; nothing is drawn (the shims execute no
# command stream), so this checks compilation, not pictures.
# Each scene runs at its own quality and at a second level that compiles the other variants
# (spherical opacity, bilinear upsampling, per-channel tone map, RGBA8 target), three scenes
# with mixed resolution (issue 43: its own programs) and one with early termination (its mark,
# terminate_mark.frag, and the particle target's depth renderbuffer). A run passes when
# every program links, or when sbfx refuses at create with a message naming what the GPU lacks
# (no GLES 3.0, a missing format); a shader compile or link error is a failure. The etnaviv
# driver of Mesa 25 offers no OpenGL ES 3.0 context on a GC7000L: there the check is that the
# run stops with that message (docs/gpus.md).
# Usage: tests/gpus/run.sh [BUILD]   (TEST_GPUS="g52 rpi4" picks shims)
set -u
cd "$(dirname "$0")/../.." || exit 1
build=${1:-build}
play=$build/sbfx-play
gpus=${TEST_GPUS:-g52 g610 rpi4 rpi5 adreno618 gc7000l}
out=$build/test-gpus
mkdir -p "$out"
pass=0 fail=0

ok() { echo "ok - $1"; pass=$((pass + 1)); }
not_ok() { echo "not ok - $1: $2"; fail=$((fail + 1)); }

# stat var, gallium driver of a shim, for the driver's own statistics lines
debug_env() {
    case "$1" in
        g*[0-9]) echo BIFROST_MESA_DEBUG=shaderdb ;;
        rpi*) echo V3D_DEBUG=shaderdb ;;
        adreno*) echo FD_MESA_DEBUG=shaderdb ;;
        gc*) echo ETNA_MESA_DEBUG=shaderdb ;;
    esac
}

# one run: $1 shim, $2 scene, $3 label, rest: sbfx-play flags
run_one() {
    gpu=$1 scene=$2 label=$3
    shift 3
    name=$(basename "$scene" .cfg)
    log=$out/$gpu-$name-$label.log
    # shellcheck disable=SC2046 # the shim's KEY=VALUE lines
    timeout 300 env $(tools/mesa-shim.sh env "$gpu") $(debug_env "$gpu") SBFX_SHADER_LOG=1 mesa_glthread=false \
        "$play" --scene "$scene" --frames 3 --size 320x180 --out "$out/frames" "$@" >"$log" 2>&1
    rc=$?
    linked=$(grep -c "shader build end: program [1-9][0-9]* linked" "$log")
    failed=$(grep -m1 -E "compiling .* failed|linking .* failed|shader build end: program 0" "$log")
    what="$gpu $name $label"
    if [ -n "$failed" ]; then
        not_ok "$what" "$(echo "$failed" | cut -c1-300)"
    elif [ "$rc" -eq 0 ] && [ "$linked" -gt 0 ]; then
        ok "$what: $linked programs linked"
    elif [ "$rc" -ne 0 ] && grep -q -E "sbfx: error: .*(needs|lacks|not supported|no .*renderable|OpenGL ES 3)" "$log"; then
        ok "$what: refused at create: $(grep -m1 "sbfx: error:" "$log" | cut -c1-200)"
    elif [ "$rc" -ne 0 ] && [ "$linked" -eq 0 ] && grep -q "offers no GLES 3.0 context" "$log"; then
        # the driver has no OpenGL ES 3.0 for this GPU: nothing of sbfx can run there
        ok "$what: refused: the driver offers no OpenGL ES 3.0 context"
    elif [ "$rc" -eq 124 ]; then
        not_ok "$what" "timed out after 300 s (see $log)"
    else
        not_ok "$what" "exit status $rc, $linked programs linked (see $log)"
    fi
}

if ! tools/mesa-shim.sh version >/dev/null 2>&1; then
    echo "test-gpus: no Mesa drm-shim build: run tools/mesa-shim.sh (tools/deps.sh mesa-shim first)" >&2
    exit 1
fi
[ -x "$play" ] || { echo "test-gpus: $play is missing (make)" >&2; exit 1; }
echo "# Mesa $(tools/mesa-shim.sh version) drm-shims: $gpus"
for gpu in $gpus; do
    for scene in scenes/*.cfg; do
        run_one "$gpu" "$scene" default
        run_one "$gpu" "$scene" other --opacity spherical --upsample bilinear --tone-map per-channel --format rgba8
    done
    # mixed resolution's programs (the mark, the one-texel depth, the refined composite): a scene
    # over the host's picture, one with post effects (its own scene), one at a 1/2 target
    for scene in scenes/explosion.cfg scenes/post.cfg scenes/campfire.cfg; do
        run_one "$gpu" "$scene" mixed --upsample mixed
    done
    run_one "$gpu" scenes/barrage.cfg termination --early-termination on
done
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
