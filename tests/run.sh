#!/usr/bin/env bash
# The test runner of `make test` (which builds everything first, normal and ASan+UBSan).
#
# Runs, in order, and prints every line they print:
#   1. every test binary in $BUILD/tests/unit/, $BUILD/tests/gl/, $BUILD/tests/platform/ and
#      $BUILD/tests/hosts/ (the SDL2 host, docs/hosts/), the SDL2 and desktop OpenGL example
#      programs, the Qt Quick item's test and example under Xvfb (tests/hosts/qt_quick.sh)
#   2. glslangValidator on every shaders_es/*.vert and *.frag, plainly and once per line of
#      tests/shader_variants.txt ("FILE -DNAME ..." : the defines of one variant)
#   3. a check that every file in shaders_es/ begins with "#version 300 es"
#   4. the sbfx-play command-line tests (tests/cli.sh), the probe's (tests/probe.sh), what
#      libsbfx.so exports (tests/exports.sh), that it reads no data file and renders fire with
#      colord-data hidden (tests/no_data_files.sh), the CIE table generator (tests/gen_cmf.sh), the
#      kiosk's unit, udev rule and their exposure (tests/kiosk_unit.sh), sbfx-play as a Wayland
#      client of cage running headless (tests/wayland.sh), make install and the host
#      example (examples/bare-egl/)
#      built against the installed copy (tests/install.sh), a short soak and its leak
#      detection (tests/soak.sh; make soak runs hours), the documentation's links and
#      examples (tests/docs.sh)
#   5. the same binaries (and the CLI tests) from build/asan/, suite names prefixed "asan:";
#      leak detection stays on for unit tests and is off where Mesa is loaded
# Test lines are "ok - x", "not ok - x[: reason]", "skip - x[: reason]" (see tests/check.h).
# A binary that crashes, times out, fails without saying so or prints no result counts as a
# failure with that reason. Ends with "N passed, M failed[, K skipped]"; exits 1 if M > 0.
#
# Environment: BUILD (default build), ASAN_BUILD (default build/asan), TEST_TIMEOUT (seconds
# per binary, default 300), TEST_ASAN_TIMEOUT (the same for the ASan binaries, default twice
# TEST_TIMEOUT: ASan runs the GL tests about twice as slowly, and test_gl_hard_cases took 228 s
# alone and over 300 s on a loaded 2-core machine). The limits catch hangs; they time nothing.
set -u
cd "$(dirname "$0")/.." || exit 1

BUILD=${BUILD:-build}
ASAN_BUILD=${ASAN_BUILD:-build/asan}
TIMEOUT=${TEST_TIMEOUT:-300}
ASAN_TIMEOUT=${TEST_ASAN_TIMEOUT:-$((2 * TIMEOUT))}
passed=0
failed=0
skipped=0

# Prints a result line and counts it.
emit() {
    printf '%s\n' "$1"
    case "$1" in
        "ok - "*) passed=$((passed + 1)) ;;
        "not ok - "*) failed=$((failed + 1)) ;;
        "skip - "*) skipped=$((skipped + 1)) ;;
    esac
}

# run_suite PREFIX NAME COMMAND...: runs one test program under a timeout; its result lines
# are counted (names prefixed with PREFIX), everything else it prints is passed through.
run_suite() {
    local prefix=$1 name=$2
    shift 2
    local log results=0 failures=0 rc line
    log=$(mktemp)
    local start=$SECONDS
    # the group's 2>/dev/null only silences bash's own "Segmentation fault" notice
    { timeout -k 10 "$TIMEOUT" "$@" >"$log" 2>&1 </dev/null; } 2>/dev/null
    rc=$?
    while IFS= read -r line || [ -n "$line" ]; do
        case "$line" in
            "ok - "*) emit "ok - $prefix${line#ok - }"; results=$((results + 1)) ;;
            "not ok - "*) emit "not ok - $prefix${line#not ok - }"; results=$((results + 1)); failures=$((failures + 1)) ;;
            "skip - "*) emit "skip - $prefix${line#skip - }"; results=$((results + 1)) ;;
            *) printf '%s\n' "$line" ;;
        esac
    done <"$log"
    rm -f "$log"
    printf '# %s%s: %d s\n' "$prefix" "$name" $((SECONDS - start))
    if [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; then
        emit "not ok - $prefix$name: timed out after $TIMEOUT s"
    elif [ "$rc" -ge 128 ]; then
        emit "not ok - $prefix$name: crashed (signal $((rc - 128)))"
    elif [ "$rc" -ne 0 ] && [ "$failures" -eq 0 ]; then
        emit "not ok - $prefix$name: exited with status $rc without reporting a failed test"
    elif [ "$results" -eq 0 ]; then
        emit "not ok - $prefix$name: printed no test results"
    fi
}

# run_dir PREFIX DIR: every executable in DIR.
run_dir() {
    local prefix=$1 dir=$2 bin
    [ -d "$dir" ] || return 0
    for bin in "$dir"/*; do
        [ -f "$bin" ] && [ -x "$bin" ] || continue
        run_suite "$prefix" "$(basename "$bin")" "$bin"
    done
}

# A test source whose binary is missing means the build skipped it: say so, not nothing.
check_built() {
    local prefix=$1 kind=$2 build=$3 src
    for src in tests/"$kind"/*.c; do
        [ -f "$src" ] || continue
        local bin="$build/tests/$kind/$(basename "$src" .c)"
        [ -x "$bin" ] || emit "not ok - $prefix$(basename "$bin"): $bin was not built (make test-$kind)"
    done
}

# validate NAME GLSLANG-ARGS...: one shader validation as one test line.
validate() {
    local name=$1 out reason
    shift
    if out=$(glslangValidator "$@" 2>&1); then
        emit "ok - $name"
    else
        reason=$(printf '%s\n' "$out" | grep -m1 -i 'error' || printf '%s\n' "$out" | tail -n1)
        emit "not ok - $name: $reason"
    fi
}

validate_shaders() {
    local f line file words
    local shaders=(shaders_es/*.vert shaders_es/*.frag)
    if ! command -v glslangValidator >/dev/null 2>&1; then
        for f in "${shaders[@]}"; do
            [ -f "$f" ] && emit "skip - glslang/$(basename "$f"): glslangValidator not installed (tools/deps.sh test)"
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
            emit "not ok - glslang-variant/$line: no such shader"
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
            emit "ok - shader-header/$(basename "$f")"
        else
            emit "not ok - shader-header/$(basename "$f"): first line is '$first', not '#version 300 es'"
        fi
    done
}

run_cli() {
    local prefix=$1 player=$2
    if [ ! -x "$player" ]; then
        emit "not ok - ${prefix}cli: $player was not built"
        return 0
    fi
    run_suite "$prefix" cli tests/cli.sh "$player"
}

export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

check_built "" unit "$BUILD"
run_dir "" "$BUILD/tests/unit"
check_built "" gl "$BUILD"
run_dir "" "$BUILD/tests/gl"
check_built "" platform "$BUILD"
run_dir "" "$BUILD/tests/platform"
# the host contract and the host's pending errors on desktop OpenGL 4.5, core and compatibility
# profile (issue 18)
for t in test_gl_state test_gl_host_errors; do
    [ -x "$BUILD/tests/gl/$t" ] || continue
    SBFX_TEST_GL_API=core run_suite "desktop-core:" "$t" "$BUILD/tests/gl/$t"
    SBFX_TEST_GL_API=compat run_suite "desktop-compat:" "$t" "$BUILD/tests/gl/$t"
done
check_built "" hosts "$BUILD"
run_dir "" "$BUILD/tests/hosts"
run_suite "" sdl2-example tests/hosts/sdl2_example.sh "$BUILD"
run_suite "" desktop-gl-example tests/hosts/desktop_gl_example.sh "$BUILD"
# the Qt Quick item's test and example under Xvfb (skipped, with the reason, without Qt 6)
run_suite "" qt-quick tests/hosts/qt_quick.sh "$BUILD"
validate_shaders
check_version_lines
run_cli "" "$BUILD/sbfx-play"
run_suite "" probe tests/probe.sh "$BUILD/sbfx-probe"
TIMEOUT=$((4 * TIMEOUT)) run_suite "precision:" precision tests/precision.sh "$BUILD"
run_suite "" exports tests/exports.sh "$BUILD"
run_suite "" no-data-files tests/no_data_files.sh "$BUILD"
run_suite "" gen-cmf tests/gen_cmf.sh "$BUILD"
run_suite "" kiosk-unit tests/kiosk_unit.sh "$BUILD"
run_suite "" wayland tests/wayland.sh "$BUILD"
run_suite "" reload tests/reload.sh "$BUILD/sbfx-play"
run_suite "" install tests/install.sh "$BUILD"
run_suite "" docs tests/docs.sh
run_suite "" soak tests/soak.sh "$BUILD"

if [ -d "$ASAN_BUILD" ]; then
    TIMEOUT=$ASAN_TIMEOUT
    check_built "asan:" unit "$ASAN_BUILD"
    run_dir "asan:" "$ASAN_BUILD/tests/unit"
    # Mesa's drivers keep allocations until exit that LeakSanitizer would report as ours.
    check_built "asan:" platform "$ASAN_BUILD"
    run_dir "asan:" "$ASAN_BUILD/tests/platform"
    check_built "asan:" gl "$ASAN_BUILD"
    ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0 run_dir "asan:" "$ASAN_BUILD/tests/gl"
    ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0 run_cli "asan:" "$ASAN_BUILD/sbfx-play"
else
    emit "not ok - asan: $ASAN_BUILD is missing (make test builds it)"
fi

# The scene parser under libFuzzer for a bounded time, the example scenes as corpus (issue #3).
run_fuzz() {
    local seconds=${FUZZ_SECONDS:-60} log="$BUILD/fuzz/make.log"
    if ! command -v clang >/dev/null 2>&1; then
        emit "skip - fuzz/scene_parse: clang is not installed (apt-get install clang libclang-rt-14-dev)"
        return
    fi
    mkdir -p "$BUILD/fuzz"
    if make --no-print-directory BUILD="$BUILD" FUZZ_SECONDS="$seconds" fuzz >"$log" 2>&1; then
        emit "ok - fuzz/scene_parse ($(grep -o 'Done [0-9]* runs' "$BUILD/fuzz/log" | head -n 1) in ${seconds} s)"
    else
        emit "not ok - fuzz/scene_parse: $(tail -n 5 "$log" | tr '\n' ' ')"
    fi
}
run_fuzz

if [ "$skipped" -gt 0 ]; then
    echo "$passed passed, $failed failed, $skipped skipped"
else
    echo "$passed passed, $failed failed"
fi
[ "$failed" -eq 0 ]
