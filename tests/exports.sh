#!/usr/bin/env bash
# What libsbfx.so shows the world (issue 10, docs/design.md §5 "Library surface"): exactly the
# functions include/sbfx.h declares, under a versioned soname with the usual links, needing only
# what src/ may use (GLESv2, libconfig, libc, libm).
#
# The header's functions come from the compiler, not from reading the text: GCC's -aux-info
# writes one prototype per function declared in a translation unit, with the file it came from.
# Usage: tests/exports.sh [BUILD] (default build). Prints ok/not ok lines (tests/check.h style).
set -u
cd "$(dirname "$0")/.." || exit 1
BUILD=${1:-build}
VERSION=$(sed -n 's/^VERSION := //p' Makefile)
SOVERSION=${VERSION%%.*}
so=$BUILD/libsbfx.so

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

failed=0
ok() { echo "ok - exports/$1"; }
not_ok() { echo "not ok - exports/$1: $2"; failed=1; }

# header_functions: the functions include/sbfx.h declares (not static inline ones), one a line.
# "NAME (" with no "*" after the parenthesis is the function's own name, even for one that
# returns a function pointer ("void (*name (int)) (void)").
header_functions() {
    echo '#include "sbfx.h"' >"$tmp/header.c"
    gcc -std=c11 -Iinclude -fsyntax-only -aux-info "$tmp/header.aux" "$tmp/header.c" || return 1
    grep -F '/* include/sbfx.h:' "$tmp/header.aux" | grep -v ' static ' | sed 's|^/\*[^*]*\*/ *||' |
        grep -oE '[A-Za-z_][A-Za-z0-9_]* \([^*]' | sed 's/ (.$//' | sort -u
}

# library_symbols: the functions and data the .so defines for others. The symbols the linker
# adds to every shared object (_edata, _end, __bss_start, and more on some targets) have no
# type and are left out.
library_symbols() {
    readelf --dyn-syms -W "$so" |
        awk '$7 != "UND" && $4 ~ /^(FUNC|OBJECT|TLS|IFUNC|COMMON)$/ { sub(/@.*/, "", $8); print $8 }' |
        sort -u
}

if [ ! -f "$so" ]; then
    not_ok built "$so is missing (make lib)"
    exit 1
fi

header_functions >"$tmp/header" || { not_ok header "gcc -aux-info could not read include/sbfx.h"; exit 1; }
library_symbols >"$tmp/library"
count=$(wc -l <"$tmp/header")
if [ "$count" -gt 0 ]; then
    ok "header: include/sbfx.h declares $count functions"
else
    not_ok header "no function found in include/sbfx.h"
fi

missing=$(comm -23 "$tmp/header" "$tmp/library" | tr '\n' ' ' | sed 's/ $//')
extra=$(comm -13 "$tmp/header" "$tmp/library" | tr '\n' ' ' | sed 's/ $//')
if [ -z "$missing" ]; then
    ok "every-declared-function-exported"
else
    not_ok every-declared-function-exported "declared in include/sbfx.h, not exported (SBFX_API?): $missing"
fi
if [ -z "$extra" ]; then
    ok "nothing-else-exported ($(wc -l <"$tmp/library") symbols)"
else
    not_ok nothing-else-exported "exported, not declared in include/sbfx.h (static, or not SBFX_API): $extra"
fi

# include/ publishes the one public header; src/'s headers stay private (issue 46)
published=$(cd include && find . -mindepth 1 | sed 's|^\./||' | sort | tr '\n' ' ' | sed 's/ $//')
if [ "$published" = sbfx.h ]; then
    ok "include-holds-only-sbfx.h"
else
    not_ok include-holds-only-sbfx.h "include/ holds: $published (only the public header belongs there)"
fi

soname=$(readelf -d "$so" | sed -n 's/.*(SONAME).*\[\(.*\)\]/\1/p')
if [ "$soname" = "libsbfx.so.$SOVERSION" ]; then
    ok "soname ($soname)"
else
    not_ok soname "'$soname', expected libsbfx.so.$SOVERSION"
fi

# libsbfx.so -> libsbfx.so.1 -> libsbfx.so.1.0.0, the last a real file
real=$BUILD/libsbfx.so.$VERSION
if [ -L "$so" ] && [ "$(readlink "$so")" = "libsbfx.so.$SOVERSION" ] &&
    [ -L "$BUILD/libsbfx.so.$SOVERSION" ] &&
    [ "$(readlink "$BUILD/libsbfx.so.$SOVERSION")" = "libsbfx.so.$VERSION" ] &&
    [ -f "$real" ] && [ ! -L "$real" ]; then
    ok "links (libsbfx.so -> libsbfx.so.$SOVERSION -> libsbfx.so.$VERSION)"
else
    not_ok links "$(ls -l "$BUILD"/libsbfx.so* 2>&1 | awk '{print $9, $10, $11}' | tr '\n' ';')"
fi

# src/ knows only GLES 3.0 and libc (+ libconfig): no EGL, DRM, GBM, libpng, libgpiod, and no
# lcms2 since the CIE tables are compiled in (tests/no_data_files.sh)
needed=$(readelf -d "$so" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | tr '\n' ' ' | sed 's/ $//')
# (and the dynamic loader, part of libc: AArch64's glibc keeps the stack protector's guard there,
# so a build with -fstack-protector, as Debian's packages, needs ld-linux-aarch64.so.1)
unexpected=$(printf '%s\n' $needed | grep -vE '^(lib(GLESv2|config|m|c)|ld-linux[-a-z0-9_]*)\.so\.[0-9]+$' | tr '\n' ' ')
if [ -z "$unexpected" ]; then
    ok "needed-libraries ($needed)"
else
    not_ok needed-libraries "needs $unexpected (src/ may use GLESv2, libconfig, libc, libm)"
fi
exit "$failed"
