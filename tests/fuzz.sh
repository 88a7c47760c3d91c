#!/usr/bin/env bash
# The scene parser under libFuzzer for a bounded time, the example scenes as corpus (issue #3;
# make fuzz). One result line: fuzz/scene_parse, skipped without clang.
# Usage: tests/fuzz.sh [BUILD] (default build); FUZZ_SECONDS (60) bounds the run.
set -u
cd "$(dirname "$0")/.." || exit 1
BUILD=${1:-build}
seconds=${FUZZ_SECONDS:-60}
log=$BUILD/fuzz/make.log
if ! command -v clang >/dev/null 2>&1; then
    echo "skip - fuzz/scene_parse: clang is not installed (apt-get install clang libclang-rt-14-dev)"
    exit 0
fi
mkdir -p "$BUILD/fuzz"
if make --no-print-directory BUILD="$BUILD" FUZZ_SECONDS="$seconds" fuzz >"$log" 2>&1; then
    echo "ok - fuzz/scene_parse ($(grep -o 'Done [0-9]* runs' "$BUILD/fuzz/log" | head -n 1) in ${seconds} s)"
else
    echo "not ok - fuzz/scene_parse: $(tail -n 5 "$log" | tr '\n' ' ')"
    exit 1
fi
