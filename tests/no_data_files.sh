#!/usr/bin/env bash
# The runtime library needs no data file (issue 20, docs/distributions.md): the CIE 1931
# colour-matching functions are compiled in. Checks that libsbfx.so
#   - does not need lcms2 and names no colord path or .cmf file in its strings,
#   - imports no function that opens a file by name (fopen, open, openat),
#   - renders a fire scene identically with colord-data's directory hidden: sbfx-play runs in
#     a private mount namespace (unshare -m as root, unshare -rm otherwise) with an empty
#     tmpfs over /usr/share/colord, and its PNGs are compared byte for byte with a normal run.
# Usage: tests/no_data_files.sh [BUILD] (default build). Prints ok/not ok/skip lines.
set -u
cd "$(dirname "$0")/.." || exit 1
BUILD=${1:-build}
so=$BUILD/libsbfx.so
play=$BUILD/sbfx-play
CMF_DIR=/usr/share/colord

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failed=0
ok() { echo "ok - no-data-files/$1"; }
not_ok() { echo "not ok - no-data-files/$1: $2"; failed=1; }
skip() { echo "skip - no-data-files/$1: $2"; }

needed=$(readelf -d "$so" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | tr '\n' ' ')
case "$needed" in
    *lcms2*) not_ok no-lcms2 "libsbfx.so still needs lcms2 ($needed)" ;;
    "") not_ok no-lcms2 "readelf found no NEEDED entry in $so" ;;
    *) ok "no-lcms2 ($needed)" ;;
esac

paths=$(strings -a "$so" | grep -E 'colord|\.cmf|/usr/share' || true)
if [ -z "$paths" ]; then ok "no-data-path"; else not_ok no-data-path "strings names: $(echo "$paths" | head -n 3 | tr '\n' ' ')"; fi

opens=$(nm -D --undefined-only "$so" | awk '{print $NF}' | sed 's/@.*//' |
    grep -xE 'fopen|fopen64|open|open64|openat|openat64|freopen|opendir' | tr '\n' ' ')
if [ -z "$opens" ]; then ok "no-file-open"; else not_ok no-file-open "libsbfx.so imports $opens"; fi

# render OUT_DIR [HIDE]: two frames of the explosion (fire) at 160x90; HIDE hides CMF_DIR.
render() {
    local out=$1 hide=${2:-} args
    args=(--headless --quiet --scene scenes/explosion.cfg --size 160x90 --frames 2 --fps 3 --out "$out")
    if [ -z "$hide" ]; then
        "$play" "${args[@]}"
        return
    fi
    local ns=(unshare -m)
    [ "$(id -u)" -eq 0 ] || ns=(unshare -rm)
    "${ns[@]}" sh -c 'mount -t tmpfs sbfx-hidden "$1" && shift && [ ! -e "$1" ] && shift && exec "$@"' \
        sh "$CMF_DIR" "$CMF_DIR/cmf/CIE1931-2deg-XYZ.cmf" "$play" "${args[@]}"
}

if [ ! -x "$play" ]; then
    not_ok fire-without-colord "$play was not built"
elif ! command -v unshare >/dev/null 2>&1 ||
    ! { [ "$(id -u)" -eq 0 ] && unshare -m true 2>/dev/null || unshare -rm true 2>/dev/null; }; then
    skip fire-without-colord "no private mount namespace here (unshare -m / -rm refused)"
elif [ ! -d "$CMF_DIR" ]; then
    # nothing to hide: the fire renders on a machine without colord-data, which is the point
    if render "$tmp/hidden" >"$tmp/log" 2>&1; then ok "fire-without-colord ($CMF_DIR absent)"
    else not_ok fire-without-colord "$(head -n 1 "$tmp/log")"; fi
elif ! render "$tmp/normal" >"$tmp/log" 2>&1; then
    not_ok fire-without-colord "the normal run failed: $(head -n 1 "$tmp/log")"
elif ! render "$tmp/hidden" hide >"$tmp/log" 2>&1; then
    not_ok fire-without-colord "with $CMF_DIR hidden: $(head -n 1 "$tmp/log")"
else
    differ=""
    for f in "$tmp"/normal/*.png; do
        cmp -s "$f" "$tmp/hidden/$(basename "$f")" || differ="$differ $(basename "$f")"
    done
    count=$(ls "$tmp"/normal/*.png 2>/dev/null | wc -l)
    if [ "$count" -eq 0 ]; then not_ok fire-without-colord "the run wrote no PNG"
    elif [ -n "$differ" ]; then not_ok fire-without-colord "frames differ with $CMF_DIR hidden:$differ"
    else ok "fire-without-colord ($count PNGs identical with $CMF_DIR hidden)"; fi
fi
exit "$failed"
