#!/usr/bin/env bash
# make deb: sbfx's Debian packages with dpkg-buildpackage (docs/packaging.md).
#   tools/deb.sh ARCH OUT   (ARCH: dpkg's name, amd64 or arm64; OUT: build/deb)
# The tree (without build/ and .git) is copied into OUT/ARCH/sbfx-VERSION/ with dist/debian/ as
# its debian/ and a debian/changelog of the Makefile's VERSION, so the work tree stays clean;
# dpkg-buildpackage -b builds there (-aARCH where ARCH is not this machine's: Debian's cross
# toolchain) and leaves the .deb files, .buildinfo and .changes in OUT/ARCH/. Then lintian on
# them: an error or a warning fails (LINTIAN=0 skips it). The build dependencies are checked
# by dpkg-buildpackage against debian/control (tools/deps.sh deb / deb-arm64 installs them).
set -euo pipefail
cd "$(dirname "$0")/.."
ARCH=${1:-$(dpkg --print-architecture)}
OUT=${2:-build/deb}
case $OUT in /*) ;; *) OUT=$PWD/$OUT ;; esac
VERSION=$(sed -n 's/^VERSION := //p' Makefile)
say() { printf 'deb %s: %s\n' "$ARCH" "$*" >&2; }

# The library's package is named after its soname (Debian's policy): a new major, which moves
# the soname, renames it in dist/debian/ (control, its .install and .symbols files).
SOVERSION=${VERSION%%.*}
if ! grep -qx "Package: libsbfx$SOVERSION" dist/debian/control || [ ! -f "dist/debian/libsbfx$SOVERSION.symbols" ]; then
    say "the soname is libsbfx.so.$SOVERSION (VERSION $VERSION) but dist/debian/ names another library package:"
    say "rename libsbfxN to libsbfx$SOVERSION in dist/debian/control (and libsbfx-dev's Depends), its .install and"
    say ".symbols files (the symbols file's first line and versions too), then make abi-baseline (docs/packaging.md)"
    exit 1
fi

work=$OUT/$ARCH
src=$work/sbfx-$VERSION
rm -rf --one-file-system "$work"
mkdir -p "$src"
tar -cf - --exclude=./build --exclude=./.git --exclude=./debian . | tar -xf - -C "$src"
cp -a dist/debian "$src/debian"

# The changelog: one entry, the Makefile's version, dated by the commit when there is one (the
# same commit gives the same packages), else by now.
if git rev-parse -q --verify HEAD >/dev/null 2>&1; then
    commit=$(git log -1 --format=%h)
    date=$(git log -1 --format=%aD)
    what="the project's tree at commit $commit$( [ -z "$(git status --porcelain --untracked-files=no)" ] || echo ' with changes')"
else
    date=$(date -R)
    what="the project's tree"
fi
maintainer=$(sed -n 's/^Maintainer: //p' dist/debian/control)
cat >"$src/debian/changelog" <<CHANGELOG
sbfx ($VERSION) unstable; urgency=medium

  * Packaged from $what
    (docs/packaging.md).

 -- $maintainer  $date
CHANGELOG

host=()
[ "$ARCH" = "$(dpkg --print-architecture)" ] || host=(-a"$ARCH")
# DEB_BUILD_PROFILES=pkg.sbfx.nogst: without the GStreamer element. A cross build where the
# element's arm64 build dependency cannot be installed beside the machine's own (Debian 12's
# libgstreamer-plugins-base1.0-dev is not Multi-Arch: same) says so rather than fail later.
if [ ${#host[@]} -gt 0 ] && [[ " ${DEB_BUILD_PROFILES:-} " != *" pkg.sbfx.nogst "* ]] &&
    ! dpkg-query -W -f='${Status}' "libgstreamer-plugins-base1.0-dev:$ARCH" 2>/dev/null | grep -q 'ok installed'; then
    say "libgstreamer-plugins-base1.0-dev:$ARCH is not installed: on Debian 12 it replaces the machine's own"
    say "(not Multi-Arch: same). Either install it (apt-get install libgstreamer-plugins-base1.0-dev:$ARCH,"
    say "best in a root of its own: make test-deb ARCH=$ARCH), or build without the GStreamer element:"
    say "  make deb ARCH=$ARCH DEB_BUILD_PROFILES=pkg.sbfx.nogst"
    exit 1
fi
say "dpkg-buildpackage -b ${host[*]} in $src (log: $work/build.log)"
if ! (cd "$src" && dpkg-buildpackage -b -us -uc "${host[@]}") >"$work/build.log" 2>&1; then
    tail -n 25 "$work/build.log" >&2
    say "dpkg-buildpackage failed (the whole log: $work/build.log)"
    exit 1
fi
changes=$work/sbfx_${VERSION}_$ARCH.changes
say "built: $(cd "$work" && ls -- *.deb | tr '\n' ' ')"

# Every ELF file in the packages is code for ARCH, every library in ARCH's multiarch folder.
triplet=$(dpkg-architecture -a"$ARCH" -qDEB_HOST_MULTIARCH 2>/dev/null)
case $ARCH in arm64) machine=AArch64 ;; amd64) machine='X86-64' ;; *) machine="" ;; esac
unpacked=$work/unpacked
rm -rf "$unpacked"
bad=""
elves=0
for deb in "$work"/*.deb; do
    case $deb in *-dbgsym_*) continue ;; esac
    dpkg-deb -x "$deb" "$unpacked"
done
while IFS= read -r f; do
    readelf -h "$f" >/dev/null 2>&1 || continue
    elves=$((elves + 1))
    rel=${f#"$unpacked"/}
    # every header's machine (an archive has one per member); read whole, not piped into grep -q,
    # whose early exit would fail readelf under pipefail
    machines=$(readelf -h "$f" 2>/dev/null | sed -n 's/^ *Machine: *//p' | sort -u)
    [ -z "$machine" ] || { [ -n "$machines" ] && ! grep -qv -- "$machine" <<<"$machines"; } ||
        bad="$bad $rel (not $machine: $machines)"
    case $rel in
        usr/bin/*) ;;
        usr/lib/"$triplet"/*) ;;
        *) bad="$bad $rel (not in usr/lib/$triplet/)" ;;
    esac
done < <(find "$unpacked" -type f)
rm -rf "$unpacked"
if [ -n "$bad" ] || [ "$elves" -eq 0 ]; then
    say "files that are not $ARCH's:${bad:- no ELF file at all}"
    exit 1
fi
say "$elves ELF files, each ${machine:-$ARCH} code, libraries in /usr/lib/$triplet/"
if [ "${LINTIAN:-1}" != 0 ]; then
    # --fail-on: lintian 2.116's (Debian 12) and later; an override is only taken with its reason
    if lintian --fail-on error,warning "$changes" >"$work/lintian.log" 2>&1; then
        say "lintian: no errors, no warnings ($(grep -c . "$work/lintian.log" || true) lines of info and notes)"
    else
        cat "$work/lintian.log" >&2
        say "lintian found errors or warnings ($work/lintian.log)"
        exit 1
    fi
fi
