#!/usr/bin/env bash
# The test runner of `make test` (which builds everything first, normal and ASan+UBSan) and of
# `make check`. docs/testing.md says what each tier runs and how long it takes.
#
# A suite is one entry in the list below (run_suite PREFIX NAME COMMAND...): a test program or
# script that prints "ok - x", "not ok - x[: reason]" or "skip - x[: reason]" lines
# (tests/check.h). Each runs once (list_all says from which build). The list holds, in this order:
#   1. the test binaries in $BUILD/tests/hosts/ (the SDL2 host, docs/hosts/), the SDL2 and desktop
#      OpenGL example programs, the Qt Quick item's test and example under Xvfb
#      (tests/hosts/qt_quick.sh), the GStreamer element's tests in $BUILD/tests/gstreamer/ (its GL
#      state test also on OpenGL ES), its command line, installed copy and MP4 recording
#      (tests/gstreamer/gst.sh) and its display sinks under Xvfb and cage (tests/gstreamer/sinks.sh)
#   2. the shaders through glslangValidator and their "#version 300 es" line (tests/shaders.sh),
#      the rooms' one-way dependencies (tests/layers.sh)
#   3. the probe's tests (tests/probe.sh), what
#      libsbfx.so exports (tests/exports.sh), its ABI against the release's (tests/abi.sh), that
#      it reads no data file and renders fire with
#      colord-data hidden (tests/no_data_files.sh), the CIE table generator (tests/gen_cmf.sh), the
#      kiosk's unit, udev rule and their exposure (tests/kiosk_unit.sh), make install and the hosts
#      (examples/, integrations/qt/) built against the installed copy (tests/install.sh), a short
#      soak and its leak detection (tests/soak.sh; make soak runs hours), the documentation's
#      links and examples (tests/docs.sh), sbfx-play under cage and weston (tests/wayland.sh), the
#      authoring loop (tests/reload.sh), DIS, CIGI and MQTT (tests/dis.sh, tests/cigi.sh,
#      tests/mqtt.sh), the WebGL 2 page's first browser case (tests/web/run.sh --quick; make
#      test-web runs them all), the accuracy suites at GPU precision, a suite per part
#      (tests/precision.sh, "precision:"), a bounded libFuzzer run (tests/fuzz.sh)
#   4. from build/asan/, suite names prefixed "asan:", the ASan+UBSan build's: every test binary in
#      tests/unit/, tests/platform/ and tests/gl/, the GL state and host-error tests again on
#      desktop OpenGL (core and compatibility), and the sbfx-play command-line tests (tests/cli.sh);
#      leak detection stays on for unit tests and is off where Mesa is loaded. With --asan=cpu the
#      GL suites and the CLI tests run from $BUILD instead, unprefixed.
# The GL suites of each build share one folder of generated detail volumes for the run
# (SBFX_TEST_CACHE, tests/gl/support/detail_cache.c).
#
# Suites run in parallel, TEST_JOBS at a time (default: every core), the longest first (their
# times from the last run, in $BUILD/test-times.txt). Each suite's output is kept and printed
# whole, in the list's order, as soon as it and every suite before it are done, followed by
# "# NAME: W s wall, C s CPU". A suite that crashes, runs past its limit, fails without saying
# so or prints no result counts as a failure with that reason and its name. The end lists the
# 10 slowest suites, then "N passed, M failed[, K skipped]"; exits 1 if M > 0.
#
# Usage: tests/run.sh [--gl-only | --check] [--asan=cpu] [-j N] [--list] [PATTERN...]
#   --gl-only  the GL suites of $BUILD only (tests/gl/, on desktop OpenGL too), on whichever EGL
#              driver the loader finds: Mesa here, a GPU's driver where there is one
#   --check    the edit-compile tier of `make check`: unit tests, test_gl_smoke, the shaders, the
#              rooms' dependencies
#   --asan=cpu the ASan+UBSan tier without the suites that render on Mesa (make test TEST_ASAN=cpu:
#              a lighter run for a slow machine; docs/testing.md)
#   --list     print the suites' names and stop
#   PATTERN    only the suites whose name (with its "asan:" prefix) matches one of these shell
#              patterns: tests/run.sh test_gl_module 'asan:*'
# Environment: BUILD (default build), ASAN_BUILD (default build/asan), TEST_JOBS, TEST_TIMEOUT
# (seconds per suite, default 300), TEST_ASAN_TIMEOUT (the same for the ASan suites, default
# twice TEST_TIMEOUT). The limits catch hangs; they time nothing. ASAN_OPTIONS, GLIBC_TUNABLES and
# SBFX_TEST_LOAD_DRIVER, where given, replace what the runner sets for speed (below).
set -u
cd "$(dirname "$0")/.." || exit 1

BUILD=${BUILD:-build}
ASAN_BUILD=${ASAN_BUILD:-build/asan}
TIMEOUT=${TEST_TIMEOUT:-300}
ASAN_TIMEOUT=${TEST_ASAN_TIMEOUT:-$((2 * TIMEOUT))}
JOBS=${TEST_JOBS:-$(nproc 2>/dev/null || echo 2)}
TIMES=$BUILD/test-times.txt

mode=all
asan=full
list_only=0
patterns=()
while [ $# -gt 0 ]; do
    case $1 in
        --gl-only) mode=gl ;;
        --check) mode=check ;;
        --asan=full | --asan=cpu) asan=${1#--asan=} ;;
        --list) list_only=1 ;;
        -j) JOBS=$2; shift ;;
        -j*) JOBS=${1#-j} ;;
        -h | --help) sed -n '2,/^set -u/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0 ;;
        -*) echo "tests/run.sh: unknown option $1 (--help)" >&2; exit 2 ;;
        *) patterns+=("$1") ;;
    esac
    shift
done

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

# ---- the list ---------------------------------------------------------------------------
# Each suite: its prefix, name, command (shell-quoted), time limit and the seconds it is
# expected to take when $TIMES does not know it yet (WEIGHT when it was added).
prefixes=() names=() commands=() limits=() weights=()
WEIGHT=5

selected() {
    local name=$1 p
    [ ${#patterns[@]} -eq 0 ] && return 0
    for p in "${patterns[@]}"; do
        # shellcheck disable=SC2053 # a pattern, on purpose
        [[ $name == $p ]] && return 0
    done
    return 1
}

# run_suite PREFIX NAME COMMAND...: adds one suite to the list (run later, in parallel); its
# result lines are counted with their names prefixed with PREFIX. Run with `env VAR=VALUE`
# first for an environment of its own.
run_suite() {
    local prefix=$1 name=$2
    shift 2
    selected "$prefix$name" || return 0
    local command
    printf -v command '%q ' "$@"
    prefixes+=("$prefix")
    names+=("$name")
    commands+=("$command")
    limits+=("$TIMEOUT")
    weights+=("$WEIGHT")
}

# run_dir PREFIX DIR [VAR=VALUE...]: every executable in DIR, with that environment.
run_dir() {
    local prefix=$1 dir=$2 bin
    shift 2
    [ -d "$dir" ] || return 0
    for bin in "$dir"/*; do
        [ -f "$bin" ] && [ -x "$bin" ] || continue
        run_suite "$prefix" "${bin##*/}" env "$@" "$bin"
    done
}

# A test source whose binary is missing means the build skipped it: say so, not nothing.
check_built() {
    local prefix=$1 kind=$2 build=$3 src bin
    for src in tests/"$kind"/*.c; do
        [ -f "$src" ] || continue
        src=${src##*/}
        bin="$build/tests/$kind/${src%.c}"
        selected "$prefix${bin##*/}" || continue
        [ -x "$bin" ] || emit "not ok - $prefix${bin##*/}: $bin was not built (make test-$kind)"
    done
}

# The GL tests' detail volumes, generated once per run and build (tests/gl/support/detail_cache.c):
# a folder per build, made here, removed at the end of the run.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# (detail_cache NAME sets $cache_env; no subshell: on the development VM a fork costs milliseconds)
detail_cache() {
    mkdir -p "$tmp/cache/$1"
    cache_env="SBFX_TEST_CACHE=$tmp/cache/$1"
}

# the GL suites of BUILD, also on desktop OpenGL 4.5, core and compatibility profile (issue 18)
gl_suites() {
    local prefix=$1 build=$2 t
    shift 2
    local tag=${prefix%:}
    detail_cache "${tag:-normal}"
    set -- "$@" "$cache_env"
    check_built "$prefix" gl "$build"
    run_dir "$prefix" "$build/tests/gl" "$@"
    for t in test_gl_state test_gl_host_errors; do
        [ -x "$build/tests/gl/$t" ] || continue
        run_suite "${prefix}desktop-core:" "$t" env "$@" SBFX_TEST_GL_API=core "$build/tests/gl/$t"
        run_suite "${prefix}desktop-compat:" "$t" env "$@" SBFX_TEST_GL_API=compat "$build/tests/gl/$t"
    done
}

run_cli() {
    local prefix=$1 player=$2
    shift 2
    if [ ! -x "$player" ]; then
        selected "${prefix}cli" && emit "not ok - ${prefix}cli: $player was not built"
        return 0
    fi
    run_suite "$prefix" cli env "$@" tests/cli.sh "$player"
}

export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# ASan's quarantine (freed memory kept poisoned, to catch a use after free) at 16 MB rather than
# 256, and allocation stacks of 8 frames rather than 30: the ASan tier in two thirds of the time
# (docs/testing.md "Where the time goes": page faults and unwinding in Mesa's allocations). What
# is checked is the same; a report's allocation stack is shorter (ASAN_OPTIONS= tests/run.sh
# NAME reruns a suite with ASan's defaults). ASAN_OPTIONS given by the caller wins.
export ASAN_OPTIONS=${ASAN_OPTIONS-quarantine_size_mb=16:malloc_context_size=8}
# glibc's malloc on transparent huge pages where the kernel offers them (madvise): a page fault
# costs some 12 us on the development VM (tools' measurement in docs/testing.md), and a GL case
# touches tens of megabytes of heap in Mesa and sbfx; a quarter of a plain GL suite's time. Not
# for the soak, whose leak check watches the resident memory grow (in 2 MB steps it would not
# see what it must). GLIBC_TUNABLES given by the caller wins.
caller_tunables=${GLIBC_TUNABLES-}
export GLIBC_TUNABLES=${GLIBC_TUNABLES-glibc.malloc.hugetlb=1}
# The GL suites' parent process loads Mesa's driver once before it forks the tests
# (tests/gl/gl_fixture.h); not in --gl-only, which runs on whichever driver a machine has.
[ "$mode" = gl ] || export SBFX_TEST_LOAD_DRIVER=${SBFX_TEST_LOAD_DRIVER:-1}
# Mesa's drivers keep allocations until exit that LeakSanitizer would report as ours.
NO_LEAKS=ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0

# The GStreamer element's suites (tests/gstreamer/), headless through GstGL's EGL device.
gstreamer_suites() {
    local t
    check_built "" gstreamer "$BUILD"
    [ -x "$BUILD/tests/gstreamer/test_gst_units" ] && run_suite "" test_gst_units "$BUILD/tests/gstreamer/test_gst_units"
    for t in test_gst_sbfx test_gst_gl_state; do
        [ -x "$BUILD/tests/gstreamer/$t" ] || continue
        run_suite "" "$t" tests/gstreamer/with_plugin.sh "$BUILD" "$BUILD/tests/gstreamer/$t"
    done
    [ -x "$BUILD/tests/gstreamer/test_gst_gl_state" ] &&
        run_suite "gles:" test_gst_gl_state env GST_GL_API=gles2 tests/gstreamer/with_plugin.sh "$BUILD" \
            "$BUILD/tests/gstreamer/test_gst_gl_state"
    run_suite "" gstreamer tests/gstreamer/gst.sh "$BUILD"
    run_suite "" gstreamer-sinks tests/gstreamer/sinks.sh "$BUILD"
}

list_check() {
    WEIGHT=2
    check_built "" unit "$BUILD"
    run_dir "" "$BUILD/tests/unit"
    WEIGHT=10
    if [ -x "$BUILD/tests/gl/test_gl_smoke" ]; then
        detail_cache normal
        run_suite "" test_gl_smoke env "$cache_env" "$BUILD/tests/gl/test_gl_smoke"
    else
        emit "not ok - test_gl_smoke: $BUILD/tests/gl/test_gl_smoke was not built (make check)"
    fi
    WEIGHT=3
    run_suite "" shaders tests/shaders.sh "$BUILD"
    run_suite "" layers tests/layers.sh "$BUILD"
}

# Each suite runs once. The unit and platform suites, and the GL suites and CLI tests, run from the
# ASan+UBSan build, the same sources and assertions with more checked; the normal build (what
# ships) runs everything else: the precision suites' GL tests, the hosts, GStreamer, the player
# under compositors, reloading, the network, install, docs, the soak. With --asan=cpu the GL
# suites and CLI tests run from the normal build instead (the ASan tier leaves them out).
list_all() {
    WEIGHT=5
    if [ "$asan" = cpu ]; then
        gl_suites "" "$BUILD"
    fi
    WEIGHT=2
    check_built "" hosts "$BUILD"
    run_dir "" "$BUILD/tests/hosts"
    WEIGHT=10
    run_suite "" sdl2-example tests/hosts/sdl2_example.sh "$BUILD"
    run_suite "" desktop-gl-example tests/hosts/desktop_gl_example.sh "$BUILD"
    # the Qt Quick item's test and example under Xvfb (skipped, with the reason, without Qt 6)
    run_suite "" qt-quick tests/hosts/qt_quick.sh "$BUILD"
    # the GStreamer element (issue 34): its C tests on desktop OpenGL (the GL state also on
    # OpenGL ES), the command line and the installed copy, the display sinks
    gstreamer_suites
    run_suite "" shaders tests/shaders.sh "$BUILD"
    run_suite "" layers tests/layers.sh "$BUILD"
    [ "$asan" = cpu ] && run_cli "" "$BUILD/sbfx-play"
    run_suite "" probe tests/probe.sh "$BUILD/sbfx-probe"
    run_suite "" exports tests/exports.sh "$BUILD"
    # the ABI against the release's (dist/abi/, libabigail; issue 46)
    run_suite "" abi tests/abi.sh "$BUILD"
    run_suite "" no-data-files tests/no_data_files.sh "$BUILD"
    run_suite "" gen-cmf tests/gen_cmf.sh "$BUILD"
    run_suite "" kiosk-unit tests/kiosk_unit.sh "$BUILD"
    # sbfx-play as a client of cage and weston, headless, as a plain user (issue 28)
    WEIGHT=60
    run_suite "" wayland tests/wayland.sh "$BUILD"
    # the authoring loop: sbfx-play --headless --watch edited the ways editors save (issue 29)
    WEIGHT=30
    run_suite "" reload tests/reload.sh "$BUILD/sbfx-play"
    # triggers from the network: DIS over loopback, MQTT through a broker of its own (issue 35)
    WEIGHT=15
    run_suite "" dis tests/dis.sh "$BUILD"
    # CIGI 3.3 over loopback: a host of its own against the receiver, read by Wireshark (issue 44)
    WEIGHT=5
    run_suite "" cigi tests/cigi.sh "$BUILD"
    WEIGHT=15
    run_suite "" mqtt tests/mqtt.sh "$BUILD"
    # one world, many channels: three sbfx-play processes against one wide view, CIGI into the
    # player (issue 44)
    run_suite "" seam tests/seam.sh "$BUILD"
    run_suite "" cigi-play tests/cigi_play.sh "$BUILD"
    # a real exercise's load, 3 s of it (make test-load: 60 s)
    run_suite "" load env LOAD_SECONDS="${LOAD_SECONDS:-3}" tests/load.sh "$BUILD"
    WEIGHT=10
    run_suite "" install tests/install.sh "$BUILD"
    run_suite "" docs tests/docs.sh
    # the authoring page in headless Chromium, its first case (make test-web runs them all)
    run_suite "" web tests/web/run.sh "$BUILD/web" --quick
    run_suite "" soak env GLIBC_TUNABLES="$caller_tunables" tests/soak.sh "$BUILD"
    # the accuracy suites at the precision GPUs compute at (issue 25, tests/precision.sh, make
    # test-precision), each part a suite of its own
    WEIGHT=20
    local part
    detail_cache normal
    for part in $(tests/precision.sh --parts); do
        run_suite "precision:" "$part" env "$cache_env" tests/precision.sh "$BUILD" "$part"
    done
    # the scene parser under libFuzzer for FUZZ_SECONDS, the example scenes as corpus; the DIS
    # parser for FUZZ_DIS_SECONDS, the CIGI parser for FUZZ_CIGI_SECONDS: 15, 5 and 5 s here, of
    # make test's CPU (make fuzz: 60, 15 and 15, which CI runs too)
    local fuzz_s=${FUZZ_SECONDS:-15} fuzz_dis_s=${FUZZ_DIS_SECONDS:-5} fuzz_cigi_s=${FUZZ_CIGI_SECONDS:-5}
    WEIGHT=$((fuzz_s + fuzz_dis_s + fuzz_cigi_s + 30))
    run_suite "" fuzz env FUZZ_SECONDS="$fuzz_s" FUZZ_DIS_SECONDS="$fuzz_dis_s" FUZZ_CIGI_SECONDS="$fuzz_cigi_s" \
        tests/fuzz.sh "$BUILD"

    if [ -d "$ASAN_BUILD" ]; then
        local timeout=$TIMEOUT
        TIMEOUT=$ASAN_TIMEOUT
        WEIGHT=4
        check_built "asan:" unit "$ASAN_BUILD"
        run_dir "asan:" "$ASAN_BUILD/tests/unit"
        check_built "asan:" platform "$ASAN_BUILD"
        run_dir "asan:" "$ASAN_BUILD/tests/platform"
        if [ "$asan" = full ]; then
            WEIGHT=8
            gl_suites "asan:" "$ASAN_BUILD" "$NO_LEAKS"
            WEIGHT=15 # its player runs take the detail volume from the run's cache (Makefile: PLAYER_TEST_WRAP)
            detail_cache asan
            run_cli "asan:" "$ASAN_BUILD/sbfx-play" "$NO_LEAKS" "$cache_env"
        else
            echo "# --asan=cpu: the ASan+UBSan tier runs the unit and platform suites only"
        fi
        TIMEOUT=$timeout
    else
        emit "not ok - asan: $ASAN_BUILD is missing (make test builds it)"
    fi
}

case $mode in
    all) list_all ;;
    check) list_check ;;
    gl) gl_suites "" "$BUILD" ;;
esac
count=${#names[@]}

if [ "$list_only" -eq 1 ]; then
    for ((i = 0; i < count; i++)); do printf '%s%s\n' "${prefixes[i]}" "${names[i]}"; done
    exit 0
fi
if [ "$count" -eq 0 ] && [ ${#patterns[@]} -gt 0 ]; then
    echo "tests/run.sh: no suite matches ${patterns[*]} (tests/run.sh --list)" >&2
    exit 2
fi

# ---- running them -----------------------------------------------------------------------
stop_all() {
    local f
    for f in "$tmp"/*.pid; do [ -f "$f" ] && kill -TERM "$(cat "$f")" 2>/dev/null; done
}
trap 'stop_all; rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM

# Seconds as "12.3" from microseconds, into the variable named first (no subshell).
seconds() { printf -v "$1" '%d.%d' $(($2 / 1000000)) $(($2 % 1000000 / 100000)); }
# bash's `times` value (1m2.345s) in microseconds
times_us() {
    [[ $1 =~ ^([0-9]+)m([0-9]+)\.([0-9]+)s$ ]] || { echo 0; return; }
    local frac=${BASH_REMATCH[3]}000000
    echo $(((BASH_REMATCH[1] * 60 + 10#${BASH_REMATCH[2]}) * 1000000 + 10#${frac:0:6}))
}

# start_suite I: runs suite I in the background under its limit; its output goes to $tmp/I.log,
# then "STATUS WALL_US CPU_US" to $tmp/I.end (CPU: user + system of the suite and its children).
start_suite() {
    local i=$1
    {
        local t0=${EPOCHREALTIME/./} rc u s
        eval "exec timeout -k 10 ${limits[i]} ${commands[i]}" >"$tmp/$i.log" 2>&1 </dev/null &
        echo $! >"$tmp/$i.pid"
        wait $!
        rc=$?
        rm -f "$tmp/$i.pid"
        times >"$tmp/$i.times" # in this shell: the suite's processes are its children
        read -r _ _ u s < <(tr '\n' ' ' <"$tmp/$i.times")
        echo "$rc $((${EPOCHREALTIME/./} - t0)) $(($(times_us "$u") + $(times_us "$s")))" >"$tmp/$i.end"
    } 2>/dev/null & # the 2>/dev/null only silences bash's own "Segmentation fault" notice
}

# print_suite I: suite I's output whole, its results counted, its time, and the failure its
# exit says when its lines do not.
print_suite() {
    local i=$1
    local prefix=${prefixes[i]} name=${names[i]} limit=${limits[i]} results=0 failures=0 line rc wall cpu
    while IFS= read -r line || [ -n "$line" ]; do
        case "$line" in
            "ok - "*) emit "ok - $prefix${line#ok - }"; results=$((results + 1)) ;;
            "not ok - "*) emit "not ok - $prefix${line#not ok - }"; results=$((results + 1)); failures=$((failures + 1)) ;;
            "skip - "*) emit "skip - $prefix${line#skip - }"; results=$((results + 1)) ;;
            *) printf '%s\n' "$line" ;;
        esac
    done <"$tmp/$i.log"
    read -r rc wall cpu <"$tmp/$i.end"
    local wall_s cpu_s
    seconds wall_s "$wall"
    seconds cpu_s "$cpu"
    printf '# %s%s: %s s wall, %s s CPU\n' "$prefix" "$name" "$wall_s" "$cpu_s"
    printf '%s %s %s%s\n' "$wall" "$cpu" "$prefix" "$name" >>"$tmp/times"
    if [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; then
        emit "not ok - $prefix$name: timed out after $limit s"
    elif [ "$rc" -ge 128 ]; then
        emit "not ok - $prefix$name: crashed (signal $((rc - 128)))"
    elif [ "$rc" -ne 0 ] && [ "$failures" -eq 0 ]; then
        emit "not ok - $prefix$name: exited with status $rc without reporting a failed test"
    elif [ "$results" -eq 0 ]; then
        emit "not ok - $prefix$name: printed no test results"
    fi
}

# The order to start them in: longest first, by the last run's wall time, else by weight.
declare -A known=()
if [ -f "$TIMES" ]; then
    while read -r wall _ full; do known[$full]=$wall; done <"$TIMES"
fi
order=()
while read -r _ i; do order+=("$i"); done < <(
    for ((i = 0; i < count; i++)); do
        printf '%s %d\n' "${known[${prefixes[i]}${names[i]}]:-$((weights[i] * 1000000))}" "$i"
    done | sort -k1,1nr -k2,2n)

declare -A running=()
done_=()
next=0 shown=0 t0=${EPOCHREALTIME/./}
while [ "$shown" -lt "$count" ]; do
    while [ "$next" -lt "$count" ] && [ ${#running[@]} -lt "$JOBS" ]; do
        start_suite "${order[next]}"
        running[$!]=${order[next]}
        next=$((next + 1))
    done
    finished=""
    wait -n -p finished "${!running[@]}"
    [ -n "${finished:-}" ] || continue
    done_[${running[$finished]}]=1
    unset "running[$finished]"
    finished_count=$((${finished_count:-0} + 1))
    # on a terminal, how far it is (the suites print in order, so output can wait for a long one)
    [ -t 2 ] && printf '\r\033[K# %d of %d suites done\r' "$finished_count" "$count" >&2
    while [ "$shown" -lt "$count" ] && [ -n "${done_[shown]:-}" ]; do
        [ -t 2 ] && printf '\r\033[K' >&2
        print_suite "$shown"
        shown=$((shown + 1))
    done
done
total_wall=$((${EPOCHREALTIME/./} - t0))

if [ "$count" -gt 0 ]; then
    cpu_sum=0
    while read -r _ cpu _; do cpu_sum=$((cpu_sum + cpu)); done <"$tmp/times"
    echo "# the 10 slowest suites (wall, CPU):"
    sort -k1,1nr "$tmp/times" | head -n 10 | while read -r wall cpu full; do
        seconds wall "$wall"
        seconds cpu "$cpu"
        printf '#   %7s s %7s s  %s\n' "$wall" "$cpu" "$full"
    done
    seconds total_wall "$total_wall"
    seconds cpu_sum "$cpu_sum"
    printf '# %d suites in %s s wall, %d at a time (%s s CPU)\n' "$count" "$total_wall" "$JOBS" "$cpu_sum"
    # this run's times replace the last run's, suite by suite
    declare -A ran=()
    while read -r _ _ full; do ran[$full]=1; done <"$tmp/times"
    for full in "${!known[@]}"; do
        [ -n "${ran[$full]:-}" ] || printf '%s 0 %s\n' "${known[$full]}" "$full" >>"$tmp/times"
    done
    mkdir -p "$BUILD" && cp "$tmp/times" "$TIMES" 2>/dev/null
fi

if [ "$skipped" -gt 0 ]; then
    echo "$passed passed, $failed failed, $skipped skipped"
else
    echo "$passed passed, $failed failed"
fi
[ "$failed" -eq 0 ]
