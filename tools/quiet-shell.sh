#!/bin/sh
# make's SHELL for quiet builds (the Makefile sets it unless V=1, with .SILENT): before a recipe
# line that compiles, links, archives, links a file or installs, one short line in the kernel's
# kbuild style ("  CC      build/obj/src/sim.o"); then the line itself runs in this /bin/sh,
# unchanged. Other lines (tests, scripts, $(shell ...) queries) print only what they print.
# QUIET_LINES=0 in the environment leaves out the short lines too (make demo's build).
# Called by make as: tools/quiet-shell.sh -c 'RECIPE LINE'
[ "$1" = -c ] && shift
line=$1
set -f
# shellcheck disable=SC2086 # the recipe line's words, to find the program and its -o
set -- $line
# "mkdir -p DIR" before each compile: nothing to do when DIR is there (most of a build's
# 360 of them), without starting a shell and mkdir for it (some 15 ms each on the development VM)
[ $# -eq 3 ] && [ "$1" = mkdir ] && [ "$2" = -p ] && [ -d "$3" ] && exit 0
[ "$1" = ccache ] && shift
tag=""
case "${1##*/}" in
    cc | gcc | clang | c99 | emcc | *-gcc | *-cc | gcc-[0-9]* | clang-[0-9]*)
        case " $line " in
            *" -c "*) tag=CC ;;
            *) tag=LD ;;
        esac
        ;;
    c++ | g++ | *-g++ | clang++ | g++-[0-9]* | clang++-[0-9]*)
        case " $line " in
            *" -c "*) tag=CXX ;;
            *) tag=LD ;;
        esac
        ;;
    ar | *-ar | gcc-ar*) tag=AR ;;
    ln) tag=LN ;;
    install) case " $line " in *" -d "*) ;; *) tag=INSTALL ;; esac ;;
    embed_shaders) tag=GEN ;;
esac
[ "${QUIET_LINES:-1}" = 0 ] && tag=""
if [ -n "$tag" ]; then
    out=""
    prev=""
    for word; do
        [ "$prev" = -o ] && out=$word
        prev=$word
    done
    case "$tag" in
        AR) out=$3 ;;
        GEN) out=$2; [ "$2" = --join ] && out=$4 ;;
        LN | INSTALL) out=$word ;;
    esac
    printf '  %-7s %s\n' "$tag" "$out"
fi
# The line runs in this shell, as `sh -c` would run it (globbing back on, no positional
# parameters, none of this script's variables): one shell started per line, not two.
set +f
set --
unset tag out prev word
eval "$line"
