#!/usr/bin/env bash
# The library's ABI against the last release's (issue 46; docs/packaging.md "The ABI"):
# libabigail's abidiff compares the built libsbfx.so, its types read from its DWARF and limited to
# what include/sbfx.h publishes, with the committed baseline dist/abi/libsbfx.so.SOVERSION.abi
# (abidw's XML of the release; `make abi-baseline` writes it). Functions added are compatible
# (the minor grows); a function or variable removed or changed (its parameters, return type or a
# public struct it reaches: a field added, moved, resized) is not, and fails unless the SONAME
# moved (the Makefile's major grew): then the new baseline is due.
# The check is shown to catch what it must on planted builds: the library linked again with
# src/sbfx.c compiled against a copy of the header with one field added at the top of
# sbfx_desc (a layout change), with sbfx_elapsed returning float (a signature change) and with a
# value added in the middle of an enum (its later values move); these must fail the comparison;
# the unchanged library, one with a function added and one with an enum value added before the
# enum's *_COUNT sentinel must pass.
# Usage: tests/abi.sh [BUILD] (default build). Prints ok/not ok lines (tests/check.h style).
set -u
cd "$(dirname "$0")/.." || exit 1
BUILD=${1:-build}
VERSION=$(sed -n 's/^VERSION := //p' Makefile)
SOVERSION=${VERSION%%.*}
so=$BUILD/libsbfx.so.$VERSION
baseline=dist/abi/libsbfx.so.$SOVERSION.abi
# what is not an incompatible change although abidiff reports it, each with its reason
suppressions=dist/abi/sbfx.abignore

failed=0
ok() { echo "ok - abi/$1"; }
not_ok() { echo "not ok - abi/$1: $2"; failed=1; }
skip() { echo "skip - abi/$1: $2"; }

if ! command -v abidiff >/dev/null || ! command -v abidw >/dev/null; then
    skip all "no abidiff/abidw (apt-get install abigail-tools; tools/deps.sh test installs it)"
    exit 0
fi
[ -f "$so" ] || { not_ok built "$so is missing (make lib)"; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

soname_of() { readelf -d "$1" | sed -n 's/.*(SONAME).*\[\(.*\)\]/\1/p'; }

# abi_verdict LIB [REFERENCE]: compares LIB with REFERENCE (the baseline; the plants: this build's
# ABI, so that they test the check whatever this build is); prints "compatible: ..." or
# "incompatible: ..." (the summary of what changed), the report in $tmp/report.
abi_verdict() {
    local lib=$1 reference=${2:-$baseline} rc removed changed added syms_removed
    abidiff --suppressions "$suppressions" --headers-dir2 include --drop-private-types "$reference" "$lib" \
        >"$tmp/report" 2>&1
    rc=$?
    if [ $((rc & 3)) -ne 0 ]; then
        echo "error: abidiff exit status $rc: $(head -n 3 "$tmp/report" | tr '\n' ' ')"
        return
    fi
    # "Functions changes summary: R Removed, C Changed (F filtered out), A Added functions"
    read -r removed changed added < <(sed -n 's/^Functions changes summary: \([0-9]*\) Removed, \([0-9]*\) Changed.*, \([0-9]*\) Added.*/\1 \2 \3/p' "$tmp/report")
    read -r vremoved vchanged < <(sed -n 's/^Variables changes summary: \([0-9]*\) Removed, \([0-9]*\) Changed.*/\1 \2/p' "$tmp/report")
    syms_removed=$(sed -n 's/^Function symbols changes summary: \([0-9]*\) Removed.*/\1/p' "$tmp/report")
    local what="${removed:-0} removed, ${changed:-0} changed, ${added:-0} added functions; ${vremoved:-0} removed, ${vchanged:-0} changed variables; ${syms_removed:-0} symbols removed"
    if [ "${removed:-0}" -gt 0 ] || [ "${changed:-0}" -gt 0 ] || [ "${vremoved:-0}" -gt 0 ] ||
        [ "${vchanged:-0}" -gt 0 ] || [ "${syms_removed:-0}" -gt 0 ] || [ $((rc & 8)) -ne 0 ]; then
        echo "incompatible: $what"
    else
        echo "compatible: $what"
    fi
}

# what changed, in a line: the report's function and type names
changed_names() {
    grep -E "^  \[C\]|^  \[D\]|type size changed|offset changed|1 data member insertion|return type changed" "$tmp/report" |
        sed 's/^ *//' | head -n 4 | tr '\n' ';' | sed 's/;$//'
}

if [ ! -f "$baseline" ]; then
    not_ok baseline "$baseline is missing: a new SONAME's first release writes it (make abi-baseline)"
    exit 1
fi
base_soname=$(sed -n "s/^<abi-corpus [^>]*soname='\([^']*\)'.*/\1/p" "$baseline" | head -n 1)
soname=$(soname_of "$so")

# 1. this build against the release
verdict=$(abi_verdict "$so")
case $verdict in
    compatible:*) ok "this-build ($so against $baseline: ${verdict#compatible: })" ;;
    incompatible:*)
        if [ "$soname" != "$base_soname" ]; then
            ok "this-build (SONAME moved $base_soname -> $soname, so incompatible changes are allowed: ${verdict#incompatible: }; make abi-baseline at the release)"
        else
            not_ok this-build "an incompatible change under the same SONAME $soname (${verdict#incompatible: }): $(changed_names). Keep the ABI, or grow the Makefile's major (a new SONAME, and the library's package renamed: docs/packaging.md) and run make abi-baseline; abidiff's report: abidiff --suppressions $suppressions --headers-dir2 include $baseline $so"
        fi
        ;;
    *) not_ok this-build "$verdict" ;;
esac

# 2. planted builds: the library linked again with one object made differently, each compared
# with this build's own ABI (abidw, as make abi-baseline writes it)
abidw --headers-dir include --drop-private-types --no-comp-dir-path --no-corpus-path --no-elf-needed \
    --out-file "$tmp/this.abi" "$so" 2>"$tmp/abidw.log" || { not_ok abidw "$(head -n 2 "$tmp/abidw.log")"; exit 1; }
pkg_cflags=$(pkg-config --cflags glesv2 libconfig)
pkg_libs=$(pkg-config --libs glesv2 libconfig)
objects=$(find "$BUILD/obj/src" -name '*.o' ! -path '*/sbfx.o' | sort)
objects="$objects $BUILD/obj/gen/shaders_es.o $BUILD/obj/gen/cie1931_2deg.o"
# planted NAME HEADER-SED [SOURCE-SED]: src/sbfx.c compiled with the header (and the file) so
# changed, linked with the build's other objects into $tmp/NAME/libsbfx.so
planted() {
    local name=$1 header_sed=$2 source_sed=${3:-} dir=$tmp/$1
    mkdir -p "$dir/include"
    sed "$header_sed" include/sbfx.h >"$dir/include/sbfx.h"
    sed "${source_sed:-s/^//}" src/sbfx.c >"$dir/sbfx.c"
    cmp -s include/sbfx.h "$dir/include/sbfx.h" && { echo "the plant did not change include/sbfx.h" >"$dir/log"; return 1; }
    # shellcheck disable=SC2086
    cc -std=c11 -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE -O1 -g -fPIC -fvisibility=hidden \
        -ffunction-sections -fdata-sections $pkg_cflags -I"$dir/include" -Iinclude -Isrc \
        -c -o "$dir/sbfx.o" "$dir/sbfx.c" >"$dir/log" 2>&1 &&
        cc -shared -Wl,-soname,"$soname" -Wl,--gc-sections -o "$dir/libsbfx.so" "$dir/sbfx.o" $objects \
            $pkg_libs -lm >>"$dir/log" 2>&1
}
check_plant() {
    local name=$1 label=$2 verdict
    shift 2
    if ! planted "$name" "$@"; then
        not_ok "planted-$name" "the planted build failed: $(tail -n 3 "$tmp/$name/log" | tr '\n' ' ')"
        return
    fi
    verdict=$(abi_verdict "$tmp/$name/libsbfx.so" "$tmp/this.abi")
    case $verdict in
        incompatible:*) ok "planted-$name-fails ($label: ${verdict#incompatible: }; $(changed_names))" ;;
        *) not_ok "planted-$name-fails" "$label was not found incompatible: $verdict" ;;
    esac
}
check_plant layout "a field added at the top of sbfx_desc" \
    '0,/^    int target_divisor; /s//    int planted_field;\n    int target_divisor; /'
check_plant signature "sbfx_elapsed returns float" \
    's/^SBFX_API double sbfx_elapsed(/SBFX_API float sbfx_elapsed(/' 's/^double sbfx_elapsed(/float sbfx_elapsed(/'
# an enum: a value added before its *_COUNT sentinel is compatible (dist/abi/sbfx.abignore says
# why); one added before an existing value moves that value, and is not
check_plant enum-moved "a value added before SBFX_UPSAMPLE_BILINEAR" \
    's/^    SBFX_UPSAMPLE_BILINEAR,/    SBFX_UPSAMPLE_PLANTED,\n&/'
if planted enum-appended 's/^    SBFX_UPSAMPLE_COUNT/    SBFX_UPSAMPLE_PLANTED,\n&/'; then
    verdict=$(abi_verdict "$tmp/enum-appended/libsbfx.so" "$tmp/this.abi")
    case $verdict in
        compatible:*) ok "planted-enum-appended-passes (a value added before SBFX_UPSAMPLE_COUNT)" ;;
        *) not_ok planted-enum-appended-passes "a value added before the sentinel was not found compatible: $verdict" ;;
    esac
else
    not_ok planted-enum-appended-passes "the planted build failed: $(tail -n 3 "$tmp/enum-appended/log" | tr '\n' ' ')"
fi
# and an addition, which is compatible: a new function passes (with a note that the minor grows)
if planted added 's/^SBFX_API double sbfx_elapsed(/SBFX_API int sbfx_planted_added(void);\n&/' \
    '$a int sbfx_planted_added(void) { return 1; }'; then
    verdict=$(abi_verdict "$tmp/added/libsbfx.so" "$tmp/this.abi")
    case $verdict in
        compatible:*) ok "planted-added-passes (a function added: ${verdict#compatible: })" ;;
        *) not_ok planted-added-passes "an added function was not found compatible: $verdict" ;;
    esac
else
    not_ok planted-added-passes "the planted build failed: $(tail -n 3 "$tmp/added/log" | tr '\n' ' ')"
fi
exit "$failed"
