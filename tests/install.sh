#!/usr/bin/env bash
# make install as a packager does it (PREFIX=/usr into a temporary DESTDIR), then the host
# example examples/bare-egl/host.c (the code docs/hosts/bare-egl.md, docs/embedding.md and the README show;
# tests/docs.sh checks that they show this file) built as a user does it, with pkg-config
# against the installed copy: once against the installed libsbfx.so, once against libsbfx.a
# with pkg-config --static. Both must run headless and see the explosion over their own scene.
# Then the other examples and the Qt integration, each built from its own files against the
# installed copy only (below).
# Usage: tests/install.sh [BUILD] (default build). Prints ok/not ok lines (tests/check.h style).
set -u
cd "$(dirname "$0")/.." || exit 1
BUILD=${1:-build}
VERSION=$(sed -n 's/^VERSION := //p' Makefile)
SOVERSION=${VERSION%%.*}
CC=${CC:-cc}

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
root=$tmp/root
lib=$root/usr/lib

failed=0
ok() { echo "ok - install/$1"; }
not_ok() { echo "not ok - install/$1: $2"; failed=1; }
# the last lines of a log, on one line
tail_of() { tail -n "${2:-5}" "$1" | tr '\n' ' ' | sed 's/ $//'; }

# pkg-config for the staged copy: sbfx.pc says prefix=/usr, the sysroot puts it under $root
pkg_sbfx() {
    PKG_CONFIG_PATH=$lib/pkgconfig PKG_CONFIG_SYSROOT_DIR=$root pkg-config "$@" sbfx
}

# build_and_run NAME LINK-FLAGS...: compiles host.c, runs it; ok/not ok lines for both.
build_and_run() {
    local name=$1
    shift
    # shellcheck disable=SC2046 # word splitting of pkg-config output is intended
    if ! $CC -std=c11 -Wall -Wextra -Werror -o "$tmp/$name" "$tmp/host.c" $(pkg_sbfx --cflags) \
        $(pkg-config --cflags egl glesv2) "$@" $(pkg-config --libs egl glesv2) >"$tmp/$name.log" 2>&1; then
        not_ok "$name/builds" "$(tail_of "$tmp/$name.log")"
        return 1
    fi
    ok "$name/builds"
    if LD_LIBRARY_PATH=$lib timeout 120 "$tmp/$name" >"$tmp/$name.run" 2>&1; then
        ok "$name/runs ($(tail_of "$tmp/$name.run" 1))"
    else
        not_ok "$name/runs" "exit status $?: $(tail_of "$tmp/$name.run")"
    fi
}

if make --no-print-directory BUILD="$BUILD" PREFIX=/usr DESTDIR="$root" install >"$tmp/make.log" 2>&1; then
    ok "make-install (PREFIX=/usr DESTDIR=\$tmp)"
else
    not_ok make-install "$(tail_of "$tmp/make.log")"
    exit 1
fi

# what is installed, and nothing of the reference or of the private headers
want="usr/include/sbfx.h usr/lib/libsbfx.a usr/lib/libsbfx.so.$VERSION usr/lib/pkgconfig/sbfx.pc
usr/bin/sbfx-play usr/bin/sbfx-probe usr/share/man/man1/sbfx-play.1 usr/share/man/man1/sbfx-probe.1"
absent=""
for f in $want; do [ -f "$root/$f" ] || absent="$absent $f"; done
stray=$(cd "$root" && find . \( -name '*ref*' -o -name 'internal.h' -o -name 'tables.h' \) | tr '\n' ' ')
if [ -z "$absent" ] && [ -z "$stray" ]; then
    ok files
else
    not_ok files "missing:${absent:- none}; not for installing: ${stray:-none}"
fi

if [ "$(readlink "$lib/libsbfx.so")" = "libsbfx.so.$SOVERSION" ] &&
    [ "$(readlink "$lib/libsbfx.so.$SOVERSION")" = "libsbfx.so.$VERSION" ] &&
    readelf -d "$lib/libsbfx.so.$VERSION" | grep -q "(SONAME).*\[libsbfx.so.$SOVERSION\]"; then
    ok "links (libsbfx.so -> libsbfx.so.$SOVERSION -> libsbfx.so.$VERSION, soname libsbfx.so.$SOVERSION)"
else
    not_ok links "$(ls -l "$lib"/libsbfx.so* | awk '{print $9, $10, $11}' | tr '\n' ';')"
fi

flags=$(pkg_sbfx --cflags --libs 2>&1 | sed 's/ *$//')
if [ "$flags" = "-I$root/usr/include -L$lib -lsbfx" ] && [ "$(pkg_sbfx --modversion)" = "$VERSION" ]; then
    ok "pkg-config (sbfx $VERSION: -I\$root/usr/include -L\$root/usr/lib -lsbfx)"
else
    not_ok pkg-config "pkg-config --cflags --libs sbfx gives '$flags'"
fi

EXAMPLE=examples/bare-egl/host.c
if ! cp "$EXAMPLE" "$tmp/host.c" 2>/dev/null; then
    not_ok example "$EXAMPLE is missing"
    exit 1
fi
ok "example ($EXAMPLE, $(wc -l <"$tmp/host.c") lines)"

# shellcheck disable=SC2046
if build_and_run shared $(pkg_sbfx --libs); then
    loaded=$(LD_LIBRARY_PATH=$lib ldd "$tmp/shared" | awk '/libsbfx/ {print $3}')
    if [ "$loaded" = "$lib/libsbfx.so.$SOVERSION" ]; then
        ok "shared/uses-installed-library"
    else
        not_ok shared/uses-installed-library "loads '$loaded', not $lib/libsbfx.so.$SOVERSION"
    fi
fi

# Static: the archive instead of the .so, and whatever pkg-config --static adds for it
# (Requires.private, Libs.private); the program must then need no libsbfx.so at all.
static_libs=$(pkg_sbfx --static --libs | sed 's/-lsbfx/-l:libsbfx.a/')
# shellcheck disable=SC2086
if build_and_run static $static_libs; then
    if readelf -d "$tmp/static" | grep -q 'NEEDED.*libsbfx'; then
        not_ok static/no-libsbfx-so "links libsbfx.so although given the archive"
    else
        ok "static/no-libsbfx-so"
    fi
fi

# The other hosts a user builds outside the tree, each from its own files only, with the
# installed header and library through pkg-config and nothing of src/ or include/ of this tree:
# the SDL2 example (run with SDL's offscreen driver, 3 frames) and the desktop OpenGL host
# (linked), where their -dev packages are, in the compiler's own C dialect as a user's cc has it
# (and -lm, which the SDL2 example calls itself); the Qt Quick item and its example compiled
# (-fsyntax-only: moc and the link are the in-tree build's) where Qt 6 Quick is.
# host_build NAME PKGS -- SOURCES...: compiles and links SOURCES into $tmp/NAME.
host_build() {
    local name=$1 pkgs=$2
    shift 3
    # shellcheck disable=SC2046,SC2086
    if $CC -Wall -Wextra -Werror -o "$tmp/$name" "$@" $(pkg_sbfx --cflags) \
        $(pkg-config --cflags $pkgs) $(pkg_sbfx --libs) $(pkg-config --libs $pkgs) -lm >"$tmp/$name.log" 2>&1; then
        ok "$name/builds (pkg-config --cflags --libs sbfx $pkgs)"
    else
        not_ok "$name/builds" "$(tail_of "$tmp/$name.log")"
        return 1
    fi
}
if pkg-config --exists sdl2 && host_build sdl2 "sdl2 glesv2" -- examples/sdl2/main.c examples/sdl2/sdl2_host.c; then
    if SDL_VIDEODRIVER=offscreen LD_LIBRARY_PATH=$lib timeout 120 "$tmp/sdl2" --frames 3 >"$tmp/sdl2.run" 2>&1; then
        ok "sdl2/runs (3 frames, offscreen)"
    else
        not_ok sdl2/runs "exit status $?: $(tail_of "$tmp/sdl2.run")"
    fi
elif ! pkg-config --exists sdl2; then
    echo "skip - install/sdl2: no libsdl2-dev (tools/deps.sh test installs it)"
fi
if pkg-config --exists opengl egl; then
    host_build desktop-gl "opengl egl" -- examples/desktop-gl/host.c
else
    echo "skip - install/desktop-gl: no libopengl-dev / libegl-dev"
fi
qt_pkgs="Qt6Quick Qt6Qml Qt6Gui"
# shellcheck disable=SC2086
if pkg-config --exists $qt_pkgs && command -v "${CXX:-c++}" >/dev/null; then
    qt_failed=""
    for f in integrations/qt/sbfx_render_node.cpp integrations/qt/sbfx_item.cpp examples/qt-quick/main.cpp; do
        # shellcheck disable=SC2046,SC2086
        "${CXX:-c++}" -std=c++17 -fsyntax-only -Wall -Wextra -Werror -Wno-unused-parameter -Iintegrations/qt \
            $(pkg_sbfx --cflags) $(pkg-config --cflags $qt_pkgs) "$f" >>"$tmp/qt.log" 2>&1 || qt_failed="$qt_failed $f"
    done
    if [ -z "$qt_failed" ]; then
        ok "qt-quick/compiles (integrations/qt, examples/qt-quick; pkg-config --cflags sbfx $qt_pkgs)"
    else
        not_ok qt-quick/compiles "$qt_failed: $(tail_of "$tmp/qt.log")"
    fi
else
    echo "skip - install/qt-quick: no Qt 6 Quick -dev packages (tools/deps.sh test installs them)"
fi
exit "$failed"
