#!/bin/sh
# Makes sure the Debian packages sbfx needs are installed.
# As root: installs what is missing (apt-get, non-interactive). Otherwise: prints the exact
# apt-get line and exits 1. Usage: tools/deps.sh [build|test|vm|cross-arm64]
set -eu
set_of="${1:-test}"

# gcc only recommends libc6-dev, which --no-install-recommends leaves out: named here
host_tools="make gcc libc6-dev pkg-config"
build_pkgs="$host_tools libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri libpng-dev liblcms2-dev libconfig-dev libdrm-dev libgbm-dev libgpiod-dev colord-data"
# make test also builds the hosts (docs/hosts/): the SDL2 example, libOpenGL for desktop OpenGL
test_pkgs="$build_pkgs glslang-tools gnuplot-nox clang libclang-rt-14-dev libsdl2-dev libopengl-dev"
# make test-vm: qemu (TCG), the guest's modprobe through the shared root, and what tests/vm/run.sh
# needs to fetch and unpack Debian's kernel packages and build vkms and gpio-sim out of tree
vm_pkgs="$build_pkgs qemu-system-x86 kmod xz-utils patch gcc-12 make libelf1"
# make BOARD=<an arm64 board> and make cross-check: Debian's aarch64 toolchain and the arm64
# multiarch -dev packages, with the host's make, pkg-config and compiler (build/tools/ runs here)
cross_arm64_pkgs="$host_tools gcc-aarch64-linux-gnu libc6-dev:arm64 libegl-dev:arm64 libgles-dev:arm64 libdrm-dev:arm64 libgbm-dev:arm64 libgpiod-dev:arm64 libpng-dev:arm64 liblcms2-dev:arm64 libconfig-dev:arm64"

case "$set_of" in
    build) want="$build_pkgs" ;;
    test) want="$test_pkgs" ;;
    vm) want="$vm_pkgs" ;;
    cross-arm64) want="$cross_arm64_pkgs" ;;
    *) echo "deps.sh: unknown package set '$set_of' (build|test|vm|cross-arm64)" >&2; exit 2 ;;
esac

# arm64 packages need the architecture enabled first (dpkg --add-architecture arm64)
add_arch=""
if [ "$set_of" = cross-arm64 ] && ! dpkg --print-foreign-architectures | grep -qx arm64; then
    add_arch="dpkg --add-architecture arm64 && "
fi

missing=""
for p in $want; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing="$missing $p"
    fi
done
[ -z "$missing" ] && [ -z "$add_arch" ] && exit 0

line="apt-get install -y --no-install-recommends$missing"
if [ "$(id -u)" -ne 0 ]; then
    echo "sbfx needs Debian packages that are not installed. As root, run:" >&2
    echo "  ${add_arch}apt-get update && $line" >&2
    exit 1
fi
echo "deps.sh: installing:$missing" >&2
export DEBIAN_FRONTEND=noninteractive
[ -n "$add_arch" ] && dpkg --add-architecture arm64
apt-get update -qq
# shellcheck disable=SC2086
apt-get install -y -qq --no-install-recommends $missing >&2
