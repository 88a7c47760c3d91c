#!/usr/bin/env bash
# The shaders, without a GL context (a suite of tests/run.sh and of make check):
#   glslang/FILE             glslangValidator accepts every shaders_es/*.vert and *.frag as written, and
#                            every shader joined from parts ($BUILD/gen/shaders_es/, e.g. particle.frag)
#   glslang-variant/FILE -D. and once per line of tests/shader_variants.txt ("FILE -DNAME ...": the
#                            defines of one variant; FILE a joined shader where it has parts)
#   shader-header/FILE       every file in shaders_es/, parts included, begins with "#version 300 es"
#   parts/DIR/joined         a shader in parts (shaders_es/NAME.STAGE.parts/, tools/embed_shaders.c): the
#                            build's joined file is what its parts join to, and without its "#line"
#                            lines it is the parts' text from their line 3, in order
#   parts/DIR/message-N      an error planted at the end of part N (the first, a middle one, the last)
#                            is reported by glslangValidator as N:LINE, that part's own line
#   parts/DIR/refused        a part without its "#version 300 es" line is refused by the join, named
# Usage: tests/shaders.sh [BUILD] (default build: the joined shaders and the join tool are built
# by make lib). Prints ok/not ok/skip lines (tests/check.h style); exits 1 if one failed.
set -u
cd "$(dirname "$0")/.." || exit 1
BUILD=${1:-build}
JOINED=$BUILD/gen/shaders_es
EMBED=$BUILD/tools/embed_shaders
failed=0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

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
    local dir
    for dir in shaders_es/*.parts; do
        [ -d "$dir" ] || continue
        shaders+=("$JOINED/$(basename "$dir" .parts)")
        if [ ! -f "$JOINED/$(basename "$dir" .parts)" ]; then
            echo "not ok - glslang/$(basename "$dir" .parts): $JOINED/$(basename "$dir" .parts) is not built (make lib)"
            failed=1
        fi
    done
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
        [ -f "$file" ] || [ ! -d "shaders_es/${words[0]}.parts" ] || file="$JOINED/${words[0]}"
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
    while IFS= read -r f; do
        first=""
        IFS= read -r first <"$f"
        if [[ "$first" =~ ^"#version 300 es"[[:space:]]*$ ]]; then
            echo "ok - shader-header/${f#shaders_es/}"
        else
            echo "not ok - shader-header/${f#shaders_es/}: first line is '$first', not '#version 300 es'"
            failed=1
        fi
    done < <(find shaders_es -type f | sort)
}

# check_parts DIR: a shader in parts (tools/embed_shaders.c says how they join).
check_parts() {
    local dir=$1 name part n last lines out
    name=$(basename "$dir" .parts)
    if [ ! -x "$EMBED" ] || [ ! -f "$JOINED/$name" ]; then
        echo "not ok - parts/$name.parts: $EMBED or $JOINED/$name is not built (make lib)"
        failed=1
        return
    fi
    # the parts' own text from line 3, in order, after the one #version line
    { echo "#version 300 es"; for part in $(ls "$dir"/*.glsl | sort -t/ -k3 -n); do tail -n +3 "$part"; done; } >"$tmp/expected"
    if "$EMBED" --join "$dir" "$tmp/$name" && cmp -s "$tmp/$name" "$JOINED/$name" &&
        grep -v '^#line ' "$JOINED/$name" | cmp -s - "$tmp/expected"; then
        echo "ok - parts/$name.parts/joined ($(ls "$dir"/*.glsl | wc -l) parts, $(grep -c '^#line ' "$JOINED/$name") #line lines)"
    else
        echo "not ok - parts/$name.parts/joined: $JOINED/$name is not the parts of $dir joined (make lib), or differs from their text"
        failed=1
    fi
    command -v glslangValidator >/dev/null 2>&1 || {
        echo "skip - parts/$name.parts/messages: glslangValidator not installed (tools/deps.sh test)"
        return 0
    }
    last=$(ls "$dir"/*.glsl | wc -l)
    for n in 1 $(((last + 1) / 2)) "$last"; do
        rm -rf "$tmp/planted.parts" && cp -r "$dir" "$tmp/planted.parts"
        part=$(ls "$tmp/planted.parts/$n"-*.glsl)
        echo "float planted_in_part_$n = no_such_name;" >>"$part"
        lines=$(wc -l <"$part")
        out=""
        mkdir -p "$tmp/planted" && "$EMBED" --join "$tmp/planted.parts" "$tmp/planted/$name" &&
            out=$(glslangValidator "$tmp/planted/$name" 2>&1)
        if grep -q "ERROR: $n:$lines: 'no_such_name' : undeclared identifier" <<<"$out"; then
            echo "ok - parts/$name.parts/message-$n (an error on line $lines of $(basename "$part") is reported at $n:$lines)"
        else
            echo "not ok - parts/$name.parts/message-$n: expected ERROR: $n:$lines, got: $(grep -m1 ERROR <<<"$out")"
            failed=1
        fi
    done
    rm -rf "$tmp/planted.parts" && cp -r "$dir" "$tmp/planted.parts"
    part=$(ls "$tmp/planted.parts"/*.glsl | head -n1)
    sed -i 1d "$part"
    if out=$("$EMBED" --join "$tmp/planted.parts" "$tmp/refused" 2>&1); then
        echo "not ok - parts/$name.parts/refused: a part without its #version line was joined"
        failed=1
    elif grep -q "$(basename "$part"):1: a part begins \"#version 300 es\"" <<<"$out"; then
        echo "ok - parts/$name.parts/refused ($out)"
    else
        echo "not ok - parts/$name.parts/refused: refused without naming $(basename "$part"):1: $out"
        failed=1
    fi
}

validate_shaders
check_version_lines
for d in shaders_es/*.parts; do [ -d "$d" ] && check_parts "$d"; done
exit "$failed"
