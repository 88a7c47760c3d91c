#!/bin/sh
# Makes sure the Debian packages sbfx needs are installed.
# As root: installs what is missing (apt-get, non-interactive). Otherwise: prints the exact
# apt-get line and exits 1. Usage: tools/deps.sh [build|test|vm|cross-arm64]
set -eu
set_of="${1:-test}"

build_pkgs="make gcc pkg-config libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri libpng-dev liblcms2-dev libconfig-dev libdrm-dev libgbm-dev libgpiod-dev colord-data"
test_pkgs="$build_pkgs glslang-tools gnuplot-nox clang libclang-rt-14-dev"

case "$set_of" in
    build) want="$build_pkgs" ;;
    test) want="$test_pkgs" ;;
    *) echo "deps.sh: unknown package set '$set_of' (build|test)" >&2; exit 2 ;;
esac

missing=""
for p in $want; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing="$missing $p"
    fi
done
[ -z "$missing" ] && exit 0

line="apt-get install -y --no-install-recommends$missing"
if [ "$(id -u)" -ne 0 ]; then
    echo "sbfx needs Debian packages that are not installed. As root, run:" >&2
    echo "  apt-get update && $line" >&2
    exit 1
fi
echo "deps.sh: installing:$missing" >&2
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
# shellcheck disable=SC2086
apt-get install -y -qq --no-install-recommends $missing >&2
