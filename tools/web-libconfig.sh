#!/bin/sh
# libconfig's C source for the WebGL 2 build (make web): Debian's source package of the
# machine's own release (apt-get source through the archive this machine's apt uses, with a
# deb-src entry in a private apt state: tools/debian-archive.sh), unpacked with Debian's
# patches into DIR/src. Cached: a no-op when DIR/src/lib/libconfig.c exists.
# Usage: tools/web-libconfig.sh DIR     (prints the source folder)
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
. "$here/tools/debian-archive.sh"
dir=${1:?usage: tools/web-libconfig.sh DIR}
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
if [ -f "$dir/src/lib/libconfig.c" ]; then echo "$dir/src"; exit 0; fi
echo "web-libconfig: libconfig's source from Debian's archive ($(debian_codename)) into $dir/src" >&2
rm -rf "$dir/dl" "$dir/src"
mkdir -p "$dir/dl"
debian_private_sources "$dir/apt" "$(debian_codename)"
(cd "$dir/dl" && debian_private_apt "$dir/apt" source --download-only libconfig >&2) || true
# dpkg-source unpacks and applies Debian's patches (dpkg-dev, tools/deps.sh web)
dsc=$(find "$dir/dl" -maxdepth 1 -name 'libconfig_*.dsc' | head -n 1)
orig=$(find "$dir/dl" -maxdepth 1 -name 'libconfig_*.orig.tar.*' | head -n 1)
if [ -n "$dsc" ]; then
    dpkg-source --no-check -x "$dsc" "$dir/src" >&2
elif [ -n "$orig" ]; then
    # A mirror that serves the upstream tarball but not the .dsc and Debian's patches (seen on a
    # partial Debian 13 mirror): the same upstream release, its hash checked by apt against the
    # archive's Sources index, unpacked without Debian's patches (packaging; lib/ builds as is).
    echo "web-libconfig: no .dsc from the archive; $(basename "$orig") (hash checked by apt) without Debian's patches" >&2
    mkdir -p "$dir/src"
    tar -xf "$orig" -C "$dir/src" --strip-components=1
else
    echo "web-libconfig: apt-get source libconfig brought neither a .dsc nor the upstream tarball" >&2
    exit 1
fi
[ -f "$dir/src/lib/libconfig.c" ] || { echo "web-libconfig: no lib/libconfig.c in $dir/src" >&2; exit 1; }
echo "$dir/src"
