#!/usr/bin/env bash
# sbfx-probe's line protocol (issue #2): every query answered on its own line, CPU next to a real
# GPU render, malformed lines reported on stderr with their line number while later lines are
# still answered, exit status 1 when any line was malformed.
# Usage: tests/probe.sh [PROBE]. Prints "ok - probe/x" / "not ok - probe/x: why" lines.
set -u
PROBE=${1:-build/sbfx-probe}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
ok() { echo "ok - probe/$1"; }
fail() { echo "not ok - probe/$1: $2"; failures=$((failures + 1)); }

# close A B TOL: |A - B| <= TOL (awk: the shell has no floats)
close() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t) }'; }

cat >"$tmp/in" <<'QUERIES'
opacity spherical 0 1 5 100 0.1 0.4
opacity exact 0 1 5 100 0.1 0.4
opacity planar 0.5 1 5 100 0.1 0.4
opacity soft 0.5 1 5 5.5 0.1 0.4
opacity spherical 0.5 1 0.3 100 0.1 0.4
opacity exact 0.999999 1 5 100 0.1 0.4
opacity spherical 0.3 1 5 100 0.1 1e6
opacity spherical 0.01 0.05 10000 1e9 0.1 0.4
this line is malformed
blackbody 1500
blackbody 3000
blackbody 6500
phase 1 0.5
phase -1 0.5
phase 0 0
opacity spherical 1 2
opacity spherical 0 0.05 3000 3000.01 0.1 0.4
opacity exact 0 0.05 3000 3000.01 0.1 0.4
opacity soft 0.01 0.05 3000 3000.01 0.1 0.4
opacity spherical 0.03 0.05 3000 3000.01 0.1 0.4
blackbody 500
blackbody 20000
phase 1 0.95
phase -1 -0.95
phase 0.31 0.95
phase 0.999 -0.9
QUERIES
timeout 120 "$PROBE" <"$tmp/in" >"$tmp/out" 2>"$tmp/err"
rc=$?
[ "$rc" -eq 1 ] && ok exit-status || fail exit-status "exit $rc, expected 1 (two malformed lines)"
grep -q "line 9:" "$tmp/err" && grep -q "line 16:" "$tmp/err" && ok malformed-lines-named ||
    fail malformed-lines-named "stderr does not name lines 9 and 16: $(head -c 300 "$tmp/err")"
lines=$(wc -l <"$tmp/out")
[ "$lines" -eq 24 ] && ok answers-per-line || fail answers-per-line "$lines answers to 24 good queries"

n=0 bad=""
while read -r cpu gpu rest; do
    n=$((n + 1))
    [ "$n" -gt 8 ] && break
    [ -z "$rest" ] || { bad="$bad line$n(extra fields)"; continue; }
    close "$cpu" "$gpu" 2e-4 || bad="$bad line$n($cpu vs $gpu)"
done <"$tmp/out"
[ "$n" -ge 8 ] || bad="$bad only $n opacity answers"
[ -z "$bad" ] && ok opacity-cpu-matches-gpu || fail opacity-cpu-matches-gpu "$bad"

# the model difference is shown, not hidden: spherical through the centre 1-e^-0.8, exact 1-e^-0.4
read -r sph _ < <(sed -n 1p "$tmp/out")
read -r ex _ < <(sed -n 2p "$tmp/out")
close "$sph" 0.550671 1e-5 && close "$ex" 0.329680 1e-5 && ok centre-2tau-r-vs-tau-r ||
    fail centre-2tau-r-vs-tau-r "spherical $sph exact $ex"

# the black body from 500 to 20000 K (lines 9-11, 19-20): the GPU within 1e-3 of Planck x CIE in
# double, relative to the colour's largest channel
bad=""
for i in 9 10 11 19 20; do
    set -- $(sed -n "${i}p" "$tmp/out")
    [ $# -eq 6 ] || { bad="$bad line$i($# fields)"; continue; }
    awk -v r="$1" -v g="$2" -v b="$3" -v R="$4" -v G="$5" -v B="$6" 'function abs(x) { return x < 0 ? -x : x }
        BEGIN { m = r; if (g > m) m = g; if (b > m) m = b
                e = abs(R - r); if (abs(G - g) > e) e = abs(G - g); if (abs(B - b) > e) e = abs(B - b)
                exit !(m > 0 && e <= 1e-3 * m) }' || bad="$bad line$i($*)"
done
[ -z "$bad" ] && ok blackbody-gpu-matches-planck || fail blackbody-gpu-matches-planck "$bad"

read -r fwd _ < <(sed -n 12p "$tmp/out")
read -r back _ < <(sed -n 13p "$tmp/out")
read -r iso_cpu iso_gpu < <(sed -n 14p "$tmp/out")
awk -v f="$fwd" -v b="$back" 'BEGIN { exit !(f > 10 * b) }' && ok phase-forward-peak ||
    fail phase-forward-peak "P(1, 0.5) = $fwd is not well above P(-1, 0.5) = $back"
close "$iso_cpu" 0.0596831 1e-6 && close "$iso_gpu" "$iso_cpu" 6e-5 && ok phase-isotropic ||
    fail phase-isotropic "P(0, 0) cpu $iso_cpu gpu $iso_gpu, want 3/(16 pi)"
# The far field (issue 10): r = 5 cm at 3000 m, the surface 1 cm behind the centre, near 0.1.
# With reversed-Z float depth the probe's host depth resolves 0.2 mm there: within 4e-3 of the
# reference. Standard depth cannot (metres at 3 km): then the answers are only reported.
depth=$(sed -n 's/^sbfx-probe: host depth: //p' "$tmp/err")
echo "# probe host depth: ${depth:-not reported}"
bad=""
for i in 15 16 17 18; do
    read -r cpu gpu < <(sed -n "${i}p" "$tmp/out")
    echo "# far field, answer $i: CPU $cpu GPU $gpu"
    close "$cpu" "$gpu" 4e-3 || bad="$bad line$i($cpu vs $gpu)"
done
case "$depth" in
    reversed-Z*) [ -z "$bad" ] && ok far-field-reversed-z || fail far-field-reversed-z "$bad" ;;
    *) echo "skip - probe/far-field-reversed-z: GL_EXT_clip_control missing, standard depth cannot resolve 1 cm at 3 km" ;;
esac
# |g| = 0.95 at the peak, the back and between, g = -0.9 just off its peak: within 1e-3 relative
bad=""
for i in 12 13 14 21 22 23 24; do
    read -r cpu gpu < <(sed -n "${i}p" "$tmp/out")
    awk -v c="$cpu" -v g="$gpu" 'BEGIN { d = c - g; if (d < 0) d = -d; exit !(c > 0 && d <= 1e-3 * c) }' ||
        bad="$bad line$i($cpu vs $gpu)"
done
[ -z "$bad" ] && ok phase-gpu-matches-function || fail phase-gpu-matches-function "$bad"
[ "$failures" -eq 0 ]
