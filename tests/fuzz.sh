#!/usr/bin/env bash
# The scene parser under libFuzzer for a bounded time, the example scenes as corpus (issue #3),
# then the DIS parser and receiver, valid v6 and v7 PDUs as corpus (issue 35; make fuzz). Two
# result lines, fuzz/scene_parse and fuzz/dis_parse, skipped without clang.
# Usage: tests/fuzz.sh [BUILD] (default build); FUZZ_SECONDS (60) and FUZZ_DIS_SECONDS (15) bound
# the runs.
set -u
cd "$(dirname "$0")/.." || exit 1
BUILD=${1:-build}
seconds=${FUZZ_SECONDS:-60}
log=$BUILD/fuzz/make.log
if ! command -v clang >/dev/null 2>&1; then
    echo "skip - fuzz/scene_parse: clang is not installed (apt-get install clang libclang-rt-14-dev)"
    echo "skip - fuzz/dis_parse: clang is not installed (apt-get install clang libclang-rt-14-dev)"
    exit 0
fi
mkdir -p "$BUILD/fuzz"
dis_seconds=${FUZZ_DIS_SECONDS:-15}
rm -f "$BUILD/fuzz/log" "$BUILD/fuzz/dis.log"
make --no-print-directory BUILD="$BUILD" FUZZ_SECONDS="$seconds" FUZZ_DIS_SECONDS="$dis_seconds" fuzz >"$log" 2>&1
failed=0
# result NAME LOG SECONDS: ok when LOG says libFuzzer finished its runs
result() {
    if grep -q 'Done [0-9]* runs' "$2" 2>/dev/null; then
        echo "ok - fuzz/$1 ($(grep -o 'Done [0-9]* runs' "$2" | head -n 1) in $3 s)"
    else
        echo "not ok - fuzz/$1: $(tail -n 5 "$log" | tr '\n' ' ')"
        failed=1
    fi
}
result scene_parse "$BUILD/fuzz/log" "$seconds"
result dis_parse "$BUILD/fuzz/dis.log" "$dis_seconds"
exit $failed
