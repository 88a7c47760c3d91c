#!/usr/bin/env bash
# The build step that compiles the CIE 1931 tables into the library (tools/gen_cmf.c): with a
# missing, unreadable or malformed colour-matching file it exits 1, names the file, the reason
# and the Debian package (colord-data), and writes no output; with colord's file it writes C
# whose every number is the file's as lcms2 read it (compared number by number).
# Usage: tests/gen_cmf.sh [BUILD] (default build). Prints ok/not ok lines.
set -u
cd "$(dirname "$0")/.." || exit 1
BUILD=${1:-build}
gen=$BUILD/tools/gen_cmf
CMF=/usr/share/colord/cmf/CIE1931-2deg-XYZ.cmf

tmp=$(mktemp -d)
trap 'chmod -R u+rwx "$tmp"; rm -rf "$tmp"' EXIT
failed=0
ok() { echo "ok - gen-cmf/$1"; }
not_ok() { echo "not ok - gen-cmf/$1: $2"; failed=1; }

if [ ! -x "$gen" ]; then
    not_ok built "$gen was not built (make lib)"
    exit 1
fi

# refuses NAME FILE [REASON]: gen_cmf FILE fails with a message naming FILE, colord-data and REASON.
refuses() {
    local name=$1 file=$2 reason=${3:-} out=$tmp/out.c msg rc
    rm -f "$out"
    msg=$("$gen" "$file" "$out" 2>&1)
    rc=$?
    if [ "$rc" -ne 1 ]; then not_ok "$name" "exit status $rc, not 1 ($msg)"
    elif [ -e "$out" ]; then not_ok "$name" "wrote $out anyway"
    elif [[ "$msg" != *"$file"* || "$msg" != *"apt-get install colord-data"* || "$msg" != *"CIE 1931"* ]]; then
        not_ok "$name" "message lacks the file or the package: $msg"
    elif [ -n "$reason" ] && [[ "$msg" != *"$reason"* ]]; then not_ok "$name" "no reason '$reason' in: $msg"
    else ok "$name"; echo "# $msg"; fi
}

refuses missing "$tmp/nonexistent/CIE1931-2deg-XYZ.cmf" "No such file or directory"
mkdir "$tmp/dir.cmf"
refuses directory "$tmp/dir.cmf" "Is a directory"
: >"$tmp/empty.cmf"
refuses empty "$tmp/empty.cmf" "empty"
printf '\001\002 this is not a colour-matching function table\n' >"$tmp/garbage.cmf"
refuses garbage "$tmp/garbage.cmf" "not a CGATS/IT8 file"
printf 'CMF\nNUMBER_OF_FIELDS 2\nBEGIN_DATA_FORMAT\nSPEC_360 SPEC_365\nEND_DATA_FORMAT\nNUMBER_OF_SETS 3\nBEGIN_DATA\n1 2\n3 4\n5 6\nEND_DATA\n' >"$tmp/noheader.cmf"
refuses no-spectral-header "$tmp/noheader.cmf" "SPECTRAL_START_NM"
printf 'CMF\nSPECTRAL_START_NM 360.0\nSPECTRAL_END_NM 365.0\nSPECTRAL_BANDS 2\nNUMBER_OF_FIELDS 2\nBEGIN_DATA_FORMAT\nSPEC_360 SPEC_365\nEND_DATA_FORMAT\nNUMBER_OF_SETS 2\nBEGIN_DATA\n1 2\n3 4\nEND_DATA\n' >"$tmp/tworows.cmf"
refuses two-rows "$tmp/tworows.cmf" "data row 2"

# colord's file: the generated rows hold the file's numbers, in order.
if [ ! -r "$CMF" ]; then
    not_ok colord-file "$CMF is not readable (tools/deps.sh installs colord-data)"
elif ! "$gen" "$CMF" "$tmp/cie.c" 2>"$tmp/err"; then
    not_ok colord-file "$(cat "$tmp/err")"
else
    # the file's three data rows vs the generated arrays, compared as numbers (lcms2's own
    # number parser is not correctly rounded: it may differ from strtod's by an ulp)
    want=$(sed -n '/^BEGIN_DATA$/,/^END_DATA$/p' "$CMF" | sed '1d;$d' | tr -s ' \t' '\n' | grep -v '^$')
    got=$(sed -n '/^static const double/,/^};/p' "$tmp/cie.c" | grep -v '^static\|^}' | tr -s ' ,' '\n' | grep -v '^$')
    bad=$(paste <(echo "$want") <(echo "$got") | awk 'function abs(x) { return x < 0 ? -x : x }
        NF != 2 || abs($1 - $2) > 4e-16 * abs($1) {n++} END {print n + 0}')
    count=$(echo "$got" | wc -l)
    if [ "$count" -ne 285 ]; then not_ok colord-file "$count numbers generated, not 3 x 95"
    elif [ "$bad" -ne 0 ]; then not_ok colord-file "$bad numbers differ from the file's"
    else ok "colord-file (3 x 95 numbers, each the file's)"; fi
fi
exit "$failed"
