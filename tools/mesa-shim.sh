#!/bin/sh
# Builds Mesa 25 (Debian 13's source package) with the drm-shims of panfrost, v3d, freedreno
# and etnaviv: the real GPU drivers and compilers, loaded on a machine with no such GPU.
# Cached under build/mesa-shim/ (MESA_SHIM_DIR); when the install and its stamp exist this is
# a no-op. The archive is the one this machine's apt uses (read at run time), suite trixie,
# kept in a private apt state so the machine's own package lists stay as they are.
# Usage: tools/mesa-shim.sh [build|env NAME|prefix|version|usage]
#   build (default)  build if missing, then print how to run a program under each shim
#   env NAME         print the environment (KEY=VALUE lines) that runs a program under shim NAME
#   prefix, version  print the install prefix / the Mesa version of the cached build
# Needs tools/deps.sh mesa-shim. See docs/gpus.md.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
dir=${MESA_SHIM_DIR:-$here/build/mesa-shim}
inst=$dir/install
libdir=$inst/lib/x86_64-linux-gnu
stamp=$dir/stamp

# The shims, their target and the environment that selects the GPU model.
#   name  preload  env
shims() {
    cat <<EOF
g52 panfrost PAN_GPU_ID=7212
g57 panfrost PAN_GPU_ID=9091
g610 panfrost PAN_GPU_ID=a867
rpi4 v3d V3D_SHIM_VERSION=42
rpi5 v3d V3D_SHIM_VERSION=71
adreno618 freedreno FD_GPU_ID=618
adreno660 freedreno FD_GPU_ID=660
gc7000l etnaviv ETNA_SHIM_GPU=GC7000L
EOF
}

# the archive and the private apt state (tools/debian-archive.sh)
. "$here/tools/debian-archive.sh"
trixie_apt() { debian_private_apt "$dir/apt" "$@"; }

fetch_sources() {
    if ls "$dir"/dl/mesa_*.orig.tar.xz "$dir"/dl/meson_*.deb >/dev/null 2>&1; then return 0; fi
    mkdir -p "$dir/dl"
    debian_private_sources "$dir/apt" trixie
    (cd "$dir/dl" && trixie_apt source --download-only mesa >&2 && trixie_apt download meson/trixie >&2)
}

unpack() {
    # the .orig.tar.xz, not the .asc beside it
    orig=$(find "$dir/dl" -maxdepth 1 -name 'mesa_*.orig.tar.xz' | head -n 1)
    rm -rf "$dir/src" "$dir/meson"
    mkdir -p "$dir/src" "$dir/meson"
    tar -xJf "$orig" -C "$dir/src" --strip-components=1
    dpkg -x "$(find "$dir/dl" -maxdepth 1 -name 'meson_*.deb' | head -n 1)" "$dir/meson"
    # small changes (tools/mesa-shim.patch): Panfrost's SHADER-DB line also gives the register
    # count, the v3d shim can be a V3D 7.1 (V3D_SHIM_VERSION=71), and 25.0.7's v3d builds
    # without the shader cache (disabled here, so that every run compiles every shader)
    patch -d "$dir/src" -p1 < "$here/tools/mesa-shim.patch" >&2
}

configure_and_build() {
    # Debian's python3 (it has mako); the trixie meson first in PATH and PYTHONPATH
    PATH=$dir/meson/usr/bin:/usr/bin:/bin:$PATH
    PYTHONPATH=$dir/meson/usr/lib/python3/dist-packages
    export PATH PYTHONPATH
    rm -rf "$dir/obj"
    /usr/bin/python3 "$dir/meson/usr/bin/meson" setup "$dir/obj" "$dir/src" --prefix="$inst" \
        --buildtype=release --wrap-mode=nofallback -Dgallium-drivers=panfrost,v3d,freedreno,etnaviv -Dvulkan-drivers= \
        -Dplatforms= -Dtools=drm-shim -Dllvm=disabled -Dglx=disabled -Degl=enabled \
        -Dgles2=enabled -Dgbm=disabled -Dglvnd=disabled -Dvalgrind=disabled -Dzstd=disabled \
        -Dshader-cache=disabled -Dvideo-codecs= -Dgallium-va=disabled -Dgallium-vdpau=disabled \
        -Dgallium-xa=disabled -Dgallium-nine=false -Dgallium-opencl=disabled \
        -Dgallium-rusticl=false -Dlibunwind=disabled -Dlmsensors=disabled -Dgles1=disabled \
        -Dbuild-tests=false -Dperfetto=false >&2
    ninja -C "$dir/obj" -j"${MESA_SHIM_JOBS:-2}" install >&2
}

build() {
    if [ -f "$stamp" ] && [ -f "$libdir/libpanfrost_noop_drm_shim.so" ]; then
        return 0
    fi
    echo "mesa-shim: building Mesa (Debian 13 source) into $inst; several minutes" >&2
    fetch_sources
    unpack
    configure_and_build
    for s in panfrost_noop v3d_noop freedreno_noop etnaviv_noop; do
        [ -f "$libdir/lib${s}_drm_shim.so" ] || { echo "mesa-shim: lib${s}_drm_shim.so was not built" >&2; exit 1; }
    done
    cat "$dir/src/VERSION" > "$stamp"
}

# the Gallium driver each shim's device wants (freedreno's kernel driver is msm)
driver_of() {
    case "$1" in freedreno) echo msm ;; *) echo "$1" ;; esac
}

env_of() {
    line=$(shims | awk -v n="$1" '$1 == n')
    [ -n "$line" ] || { echo "mesa-shim: unknown shim '$1' ($(shims | awk '{printf "%s ", $1}'))" >&2; exit 2; }
    # shellcheck disable=SC2086 # the line's words: name, driver, KEY=VALUE...
    set -- $line
    echo "LD_LIBRARY_PATH=$libdir"
    echo "LD_PRELOAD=$libdir/lib$2_noop_drm_shim.so"
    echo "MESA_LOADER_DRIVER_OVERRIDE=$(driver_of "$2")"
    echo "EGL_PLATFORM=surfaceless"
    shift 2
    for kv in "$@"; do echo "$kv"; done
}

usage() {
    echo "Mesa $(cat "$stamp") with drm-shims in $inst. Run a program under a shim:"
    shims | while read -r name drv _; do
        printf '  %-10s (%s)  env %s PROGRAM ...\n' "$name" "$drv" "$(env_of "$name" | tr '\n' ' ')"
    done
    echo "  Compiler statistics: add BIFROST_MESA_DEBUG=shaderdb (panfrost), V3D_DEBUG=shaderdb,"
    echo "  FD_MESA_DEBUG=shaderdb (freedreno), ETNA_MESA_DEBUG=shaderdb (etnaviv): SHADER-DB lines on stderr."
}

case "${1:-build}" in
    build) build; usage ;;
    env) [ $# -eq 2 ] || { echo "usage: $0 env NAME" >&2; exit 2; }
         [ -f "$stamp" ] || { echo "mesa-shim: not built (run tools/mesa-shim.sh)" >&2; exit 1; }
         env_of "$2" ;;
    prefix) echo "$inst" ;;
    version) [ -f "$stamp" ] || exit 1; cat "$stamp" ;;
    usage) [ -f "$stamp" ] || { echo "mesa-shim: not built (run tools/mesa-shim.sh)" >&2; exit 1; }; usage ;;
    *) echo "usage: $0 [build|env NAME|prefix|version|usage]" >&2; exit 2 ;;
esac
