#!/usr/bin/env bash
# The shaders, without a GL context (a suite of tests/run.sh and of make check):
#   glslang/FILE             glslangValidator accepts every shaders_es/*.vert and *.frag as written
#   glslang-variant/FILE -D. and once per line of tests/shader_variants.txt ("FILE -DNAME ...": the
#                            defines of one variant)
#   shader-header/FILE       every file in shaders_es/ begins with "#version 300 es"
# Usage: tests/shaders.sh. Prints ok/not ok/skip lines (tests/check.h style); exits 1 if one failed.
set -u
cd "$(dirname "$0")/.." || exit 1
failed=0

# validate NAME GLSLANG-ARGS...: one validation as one test line.
validate() {
    local name=$1 out reason
    shift
    if out=$(glslangValidator "$@" 2>&1); then
        echo "ok - $name"
    else
        reason=$(printf '%s\n' "$out" | grep -m1 -i 'error' || printf '%s\n' "$out" | tail -n1)
        echo "not ok - $name: $reason"
        failed=1
    fi
}

validate_shaders() {
    local f line file words
    local shaders=(shaders_es/*.vert shaders_es/*.frag)
    if ! command -v glslangValidator >/dev/null 2>&1; then
        for f in "${shaders[@]}"; do
            [ -f "$f" ] && echo "skip - glslang/$(basename "$f"): glslangValidator not installed (tools/deps.sh test)"
        done
        return 0
    fi
    for f in "${shaders[@]}"; do
        [ -f "$f" ] && validate "glslang/$(basename "$f")" "$f"
    done
    [ -f tests/shader_variants.txt ] || return 0
    while IFS= read -r line || [ -n "$line" ]; do
        line=${line%$'\r'}
        case "$line" in "" | "#"*) continue ;; esac
        read -r -a words <<<"$line"
        file=${words[0]}
        [ -f "$file" ] || file="shaders_es/$file"
        if [ ! -f "$file" ]; then
            echo "not ok - glslang-variant/$line: no such shader"
            failed=1
            continue
        fi
        # glslangValidator takes -D only when linking (-l); one stage links on its own
        validate "glslang-variant/$(basename "$file") ${words[*]:1}" -l "${words[@]:1}" "$file"
    done <tests/shader_variants.txt
}

check_version_lines() {
    local f first
    for f in shaders_es/*; do
        [ -f "$f" ] || continue
        first=""
        IFS= read -r first <"$f"
        if [[ "$first" =~ ^"#version 300 es"[[:space:]]*$ ]]; then
            echo "ok - shader-header/$(basename "$f")"
        else
            echo "not ok - shader-header/$(basename "$f"): first line is '$first', not '#version 300 es'"
            failed=1
        fi
    done
}

validate_shaders
check_version_lines
exit "$failed"
