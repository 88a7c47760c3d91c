#!/usr/bin/env bash
# One-way dependencies (issue 37; docs/hacking.md), a suite of make check and make test:
#   layers/src                 src/'s rooms (src/rooms.txt): no include of, or call into, a room
#                              listed after a file's own; no circle of files; every file in a room
#   layers/player              platform/player/'s rooms (platform/player/rooms.txt), the same
#   layers/net                 platform/net/'s rooms (platform/net/rooms.txt), the same
#   layers/planted-include     a copy of src/ whose base/alloc.c includes render/render.h: the check
#                              fails, naming that include
#   layers/planted-call        a copy whose base/ has an object that calls sbfx_create (the top): the
#                              check fails, naming that call (read from the object's symbols)
#   layers/planted-circle      two files of sim/ that call each other: the check fails, naming both
#   layers/planted-unplaced    a file in a folder that is no room: the check fails, naming it
#   layers/planted-net         a copy of platform/net/ whose common/geodesy.c includes a protocol's
#                              header (dis/dis_pdu.h): the check fails, naming that include
# The planted copies are made in a temporary folder; the tree and its objects are not touched.
# Usage: tests/layers.sh [BUILD] (default build; make check builds the objects it reads).
set -u
cd "$(dirname "$0")/.." || exit 1
BUILD=${1:-build}
failed=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# tree NAME ROOT OBJDIR [INCDIR]: the check on a real tree passes and read its objects.
tree() {
    local name=$1 root=$2 objdir=$3 incdir=${4:-$2} out
    if [ ! -d "$objdir" ]; then
        echo "not ok - layers/$name: $objdir is missing (make lib, make check)"
        failed=1
        return
    fi
    if out=$(tools/layers.sh -I "$incdir" "$root" "$objdir" 2>&1) && ! grep -q 'not built' <<<"$out"; then
        out=$(tail -n1 <<<"$out")
        echo "ok - layers/$name (${out#layers: $root: })"
    else
        echo "not ok - layers/$name: $(tr '\n' ';' <<<"$out")"
        failed=1
    fi
}

# planted NAME EXPECTED...: the check on the planted copy fails, with a line that says every
# EXPECTED (a circle's files come in no particular order).
planted() {
    local name=$1 out line e
    shift
    if out=$(tools/layers.sh -I "$tmp/src" "$tmp/src" "$tmp/obj" 2>&1); then
        echo "not ok - layers/$name: the check passed: $(tail -n1 <<<"$out")"
        failed=1
        return
    fi
    while IFS= read -r line; do
        for e in "$@"; do [[ $line == *"$e"* ]] || continue 2; done
        echo "ok - layers/$name ($line)"
        return
    done <<<"$out"
    echo "not ok - layers/$name: failed without a line saying '$*': $(tr '\n' ';' <<<"$out")"
    failed=1
}

# fresh_copy: src/ and its objects into $tmp, as they are.
fresh_copy() {
    rm -rf "$tmp/src" "$tmp/obj"
    cp -r src "$tmp/src" && cp -r "$BUILD/obj/src" "$tmp/obj"
}

# compile_planted FILE: FILE (under $tmp/src) into its object under $tmp/obj.
compile_planted() {
    local file=$1
    mkdir -p "$(dirname "$tmp/obj/${file%.c}.o")"
    cc -std=c11 -c -Iinclude -Isrc -o "$tmp/obj/${file%.c}.o" "$tmp/src/$file"
}

tree src src "$BUILD/obj/src"
[ -f platform/player/rooms.txt ] && tree player platform/player "$BUILD/obj/platform/player" platform
[ -f platform/net/rooms.txt ] && tree net platform/net "$BUILD/obj/platform/net" platform

if [ -d "$BUILD/obj/src" ]; then
    fresh_copy
    echo '#include "render/render.h" /* planted: the ground floor reaching up */' >>"$tmp/src/base/alloc.c"
    planted planted-include "upward include: base/alloc.c (base) -> render/render.h (render)"

    fresh_copy
    printf '#include "sbfx.h"\nvoid sbfx_planted(void);\nvoid sbfx_planted(void) { sbfx_create(NULL, NULL); }\n' \
        >"$tmp/src/base/planted.c"
    compile_planted base/planted.c && planted planted-call "upward call: base/planted.c (base) -> sbfx.c (top): sbfx_create"

    fresh_copy
    printf 'void sbfx_planted_a(int n);\nvoid sbfx_planted_b(int n);\nvoid sbfx_planted_a(int n) { if (n) sbfx_planted_b(n - 1); }\n' \
        >"$tmp/src/sim/planted_a.c"
    printf 'void sbfx_planted_a(int n);\nvoid sbfx_planted_b(int n);\nvoid sbfx_planted_b(int n) { if (n) sbfx_planted_a(n - 1); }\n' \
        >"$tmp/src/sim/planted_b.c"
    compile_planted sim/planted_a.c && compile_planted sim/planted_b.c &&
        planted planted-circle "circle:" sim/planted_a.c sim/planted_b.c

    fresh_copy
    mkdir -p "$tmp/src/misc" && echo 'int sbfx_planted_nowhere;' >"$tmp/src/misc/nowhere.c"
    planted planted-unplaced "not in a room: misc/nowhere.c"
fi

# platform/net/'s rooms: what the protocols share may not reach into one of them
if [ -d "$BUILD/obj/platform/net" ]; then
    rm -rf "$tmp/platform" "$tmp/obj"
    mkdir -p "$tmp/platform" && cp -r platform/net "$tmp/platform/net" && cp -r "$BUILD/obj/platform/net" "$tmp/obj"
    echo '#include "net/dis/dis_pdu.h" /* planted: the shared floor reaching into DIS */' \
        >>"$tmp/platform/net/common/geodesy.c"
    if out=$(tools/layers.sh -I "$tmp/platform" "$tmp/platform/net" "$tmp/obj" 2>&1); then
        echo "not ok - layers/planted-net: the check passed: $(tail -n1 <<<"$out")"
        failed=1
    elif line=$(grep -F "upward include: common/geodesy.c (common) -> dis/dis_pdu.h (dis)" <<<"$out"); then
        echo "ok - layers/planted-net ($line)"
    else
        echo "not ok - layers/planted-net: failed without naming the include: $(tr '\n' ';' <<<"$out")"
        failed=1
    fi
fi
exit "$failed"
