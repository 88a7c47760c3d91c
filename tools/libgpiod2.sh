#!/bin/sh
# Builds libgpiod 2.x from Debian 13 (trixie)'s source package, for the GPIO backend's second
# build (platform/gpio/gpio_gpiod2.c; docs/gpio.md). Usage: tools/libgpiod2.sh [DIR] (build/libgpiod2).
# Prints the pkg-config folder to use (PKG_CONFIG_PATH=...) on its last line.
#
# Debian 13's sources come from the archive this machine's apt already uses (its URI is read from
# /etc/apt/sources.list.d/debian.sources or /etc/apt/sources.list at run time) through a private
# apt state under DIR/apt: the machine's own lists are not touched. apt-get checks the source
# package against the archive's signed index. Built static only (libgpiod.a, no tools): a program
# linked against it runs without libgpiod.so.3 installed. Cached: a second run builds nothing.
# Needs gcc, make and xz-utils; autoconf/automake/libtool/autoconf-archive only if the upstream
# tarball came without a configure script.
set -eu
DIR=${1:-build/libgpiod2}
case $DIR in /*) ;; *) DIR=$PWD/$DIR ;; esac
INST=$DIR/inst
PC=$INST/lib/pkgconfig

if [ -f "$PC/libgpiod.pc" ] && [ -f "$INST/lib/libgpiod.a" ]; then
    echo "$PC"
    exit 0
fi

# The archive's URI: the first "URIs:" of a deb822 source that serves the main suite (not
# security), else the first plain "deb" line.
archive_uri() {
    f=/etc/apt/sources.list.d/debian.sources
    if [ -r "$f" ]; then
        awk '/^URIs:/ { uri = $2 } /^Suites:/ && uri != "" && $0 !~ /-security/ { print uri; exit }
             /^$/ { uri = "" }' "$f"
    fi
    if [ -r /etc/apt/sources.list ]; then
        awk '$1 == "deb" && $0 !~ /security/ { for (i = 2; i <= NF; i++) if ($i ~ /^[a-z]+:\/\//) { print $i; exit } }' \
            /etc/apt/sources.list
    fi
}
URI=$(archive_uri | head -n 1)
[ -n "$URI" ] || { echo "libgpiod2.sh: no Debian archive in the machine's apt sources" >&2; exit 1; }
KEYRING=/usr/share/keyrings/debian-archive-keyring.gpg
[ -r "$KEYRING" ] || { echo "libgpiod2.sh: $KEYRING missing (debian-archive-keyring)" >&2; exit 1; }

APT=$DIR/apt
mkdir -p "$APT/lists/partial" "$APT/cache/archives/partial" "$DIR/src"
printf 'deb-src [signed-by=%s] %s trixie main\n' "$KEYRING" "$URI" >"$APT/sources.list"
apt_private() {
    apt-get -q -o Dir::Etc::SourceList="$APT/sources.list" -o Dir::Etc::SourceParts=/dev/null \
        -o Dir::State::Lists="$APT/lists" -o Dir::Cache="$APT/cache" \
        -o APT::Sandbox::User=root "$@"
}

if ! ls "$DIR"/src/libgpiod_2.*.orig.tar.* >/dev/null 2>&1; then
    echo "libgpiod2.sh: fetching libgpiod's source package from trixie" >&2
    apt_private update >"$DIR/apt.log" 2>&1 || {
        tail -n 3 "$DIR/apt.log" >&2
        exit 1
    }
    # apt checks every file it fetches against the signed index's hashes; only the upstream
    # tarball is used, so a missing .dsc on the mirror is not fatal
    (cd "$DIR/src" && apt_private source --download-only libgpiod/trixie) >>"$DIR/apt.log" 2>&1 ||
        echo "libgpiod2.sh: apt-get source: $(grep -m1 '^E:' "$DIR/apt.log")" >&2
fi
TARBALL=$(ls "$DIR"/src/libgpiod_2.*.orig.tar.* 2>/dev/null | grep -v '\.asc$' | head -n 1)
[ -n "$TARBALL" ] || { echo "libgpiod2.sh: trixie's libgpiod is not 2.x" >&2; exit 1; }

rm -rf "$DIR/build" && mkdir -p "$DIR/build"
tar -xf "$TARBALL" -C "$DIR/build" --strip-components=1
cd "$DIR/build"
if [ ! -x configure ]; then
    ./autogen.sh --no-configure >"$DIR/autogen.log" 2>&1 || {
        echo "libgpiod2.sh: autogen.sh failed (autoconf automake libtool autoconf-archive): $DIR/autogen.log" >&2
        exit 1
    }
fi
echo "libgpiod2.sh: building $(basename "$TARBALL") into $INST" >&2
./configure --prefix="$INST" --enable-static --disable-shared --disable-tools \
    --disable-bindings-cxx --disable-bindings-python >"$DIR/configure.log" 2>&1 || {
    tail -n 5 "$DIR/configure.log" >&2
    exit 1
}
make -j"$(nproc)" >"$DIR/make.log" 2>&1 && make install >>"$DIR/make.log" 2>&1 || {
    tail -n 5 "$DIR/make.log" >&2
    exit 1
}
echo "$PC"
