#!/usr/bin/env bash
# The scene parser under libFuzzer for a bounded time, the example scenes as corpus (issue #3),
# then the DIS parser and receiver, valid v6 and v7 PDUs as corpus (issue 35), then the CIGI
# parser and receiver, messages in both byte orders as corpus (issue 44; make fuzz). Three result
# lines, fuzz/scene_parse, fuzz/dis_parse and fuzz/cigi_parse, skipped without clang.
# Usage: tests/fuzz.sh [BUILD] (default build); FUZZ_SECONDS (60), FUZZ_DIS_SECONDS (15) and
# FUZZ_CIGI_SECONDS (15) bound the runs.
set -u
cd "$(dirname "$0")/.." || exit 1
BUILD=${1:-build}
seconds=${FUZZ_SECONDS:-60}
log=$BUILD/fuzz/make.log
if ! command -v clang >/dev/null 2>&1; then
    echo "skip - fuzz/scene_parse: clang is not installed (apt-get install clang libclang-rt-14-dev)"
    echo "skip - fuzz/dis_parse: clang is not installed (apt-get install clang libclang-rt-14-dev)"
    echo "skip - fuzz/cigi_parse: clang is not installed (apt-get install clang libclang-rt-14-dev)"
    exit 0
fi
mkdir -p "$BUILD/fuzz"
dis_seconds=${FUZZ_DIS_SECONDS:-15}
cigi_seconds=${FUZZ_CIGI_SECONDS:-15}
rm -f "$BUILD/fuzz/log" "$BUILD/fuzz/dis.log" "$BUILD/fuzz/cigi.log"
make --no-print-directory BUILD="$BUILD" FUZZ_SECONDS="$seconds" FUZZ_DIS_SECONDS="$dis_seconds" \
    FUZZ_CIGI_SECONDS="$cigi_seconds" fuzz >"$log" 2>&1
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
result cigi_parse "$BUILD/fuzz/cigi.log" "$cigi_seconds"
exit $failed
