# Error against time of every accuracy configuration (tests/bench/run.sh runs this).
#   gnuplot -e "dir='build/bench'" tests/bench/accuracy.gp  ->  dir/accuracy.png
# points.dat: ms, mean abs error, label, group (0 = main grid: RGBA16F, tables, R16F detail;
# 1 = a variant: RGBA8/RGBA32F target, analytic black body/phase, R32F detail, light per
# particle, density matched to the exact model), opacity mode
# (1 planar, 2 soft, 3 spherical, 4 exact), divisor, upsampling (0 nearest-depth, 1 bilinear,
# 2 mixed).
# pareto.dat: the Pareto front (no configuration is both faster and closer), by time.
# Left: everything, log-log, the front labelled (one label a point). Middle: the planar / soft /
# spherical cluster (their error is mostly the model's: twice the exact optical depth at the
# centre), the front's points among them labelled. The keys sit under the panels, off the data.
if (!exists("dir")) dir = "build/bench"
# mali-points.dat (tests/bench/run.sh, where Mesa's drm-shims are built): a third panel, the
# estimated whole-frame time on a Mali-G52 MP2 at 1920x1080 against the same error, its own
# Pareto front labelled
mali = int(system("test -s ".dir."/mali-points.dat && echo 1 || echo 0"))
width = mali ? 2600 : 1800

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
    set terminal pngcairo size width,1000 font "sans,10"
} else {
    set terminal png size width,1000
}
set output dir."/accuracy.png"
set datafile separator whitespace
set offsets graph 0.03, graph 0.12, 0, 0

# a front's labels alternate above and below their points (neighbours along the front do not
# print over each other); the offsets are factors, the axes logarithmic
above(row) = int(row) % 2 == 1
# mode -> point type and colour; filled = nearest-depth, open = bilinear, asterisk = mixed
pt_of(m, u) = u == 2 ? 3 : (m == 1 ? 9 : m == 2 ? 13 : m == 3 ? 7 : 5) - u
lc_of(m) = (m == 1 ? 0x2ca02c : m == 2 ? 0x9467bd : m == 3 ? 0x1f77b4 : 0xff7f0e)

stats dir."/points.dat" using ($5 < 4 && $4 == 0 ? $2 : NaN) nooutput
cluster_lo = STATS_min
cluster_hi = STATS_max

set multiplot layout 1,(mali ? 3 : 2) title "sbfx: what accuracy costs — built-in explosion over the test scene, 3 frames, mean |GPU − exact CPU reference|"

set title "all configurations (red: Pareto front)"
set xlabel "time per frame, ms (median; depth downsample + particles + composite)"
set ylabel "mean abs error, 8-bit levels of the RGBA8 output"
set logscale xy
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set key below box font ",9" maxrows 3
plot dir."/points.dat" using 1:($4 == 1 ? $2 : 1/0) with points pt 1 ps 1.2 lc rgb "#888888" \
         title "variants: RGBA8 / RGBA32F target, analytic LUTs, R32F detail, light per particle, density τ/2", \
     for [m=1:4] dir."/points.dat" using 1:($4 == 0 && $5 == m ? $2 : 1/0):(pt_of($5, $7)):(lc_of($5)) \
         with points pt variable ps 1.4 lc rgb variable notitle, \
     for [m=1:4] keyentry with points pt pt_of(m, 0) ps 1.4 lc rgb lc_of(m) \
         title (m == 1 ? "planar" : m == 2 ? "soft" : m == 3 ? "spherical" : "exact")." (filled: nearest-depth, open: bilinear, asterisk: mixed)", \
     dir."/pareto.dat" using 1:2 with linespoints lw 2 pt 4 ps 2.0 lc rgb "#d62728" title "Pareto front", \
     dir."/pareto.dat" using ($1 * 1.12):(above($0) ? $2 * 1.22 : $2 / 1.22):3 with labels left font ",8" \
         tc rgb "#d62728" notitle

set title "planar / soft / spherical, every scale and upsampling (labels: mode/divisor upsampling)"
unset logscale y
set yrange [cluster_lo - 0.02 * (cluster_hi - cluster_lo) - 0.005 : cluster_hi + 0.08 * (cluster_hi - cluster_lo) + 0.005]
set key below box font ",9"
plot for [m=1:3] dir."/points.dat" using 1:($4 == 0 && $5 == m ? $2 : 1/0):(pt_of($5, $7)):(lc_of($5)) \
         with points pt variable ps 1.4 lc rgb variable notitle, \
     for [m=1:3] keyentry with points pt pt_of(m, 0) ps 1.4 lc rgb lc_of(m) \
         title (m == 1 ? "planar" : m == 2 ? "soft" : "spherical"), \
     dir."/pareto.dat" using 1:($2 >= cluster_lo && $2 <= cluster_hi ? $2 : 1/0):3 with labels \
         offset char 0.8,-0.8 left font ",8" tc rgb "#d62728" notitle

# the n-th point of the G52's front (mali-points.dat is sorted by time): counts as it is read
front_n = 0
front_row(on) = on == 1 ? (front_n = front_n + 1) : front_n
if (mali) {
    set title "Mali-G52 MP2 at 800 MHz, 1920x1080 (Mesa's static estimate): sbfx's whole frame"
    set xlabel "estimated ms per frame on a G52 MP2 (fragments counted at 960x540 x 4, x cycles per fragment)"
    set ylabel "mean abs error, 8-bit levels"
    set logscale xy
    set autoscale y
    set key below box font ",9"
    plot dir."/mali-points.dat" using 1:2 with points pt 7 ps 1.2 lc rgb "#1f77b4" title "configuration", \
         dir."/mali-points.dat" using 1:($4 == 1 ? $2 : 1/0) with linespoints lw 2 pt 4 ps 2.0 lc rgb "#d62728" title "Pareto front (G52)", \
         dir."/mali-points.dat" using ($1 * 1.06):($4 == 1 ? (above(front_row($4)) ? $2 * 1.15 : $2 / 1.15) : 1/0):3 \
             with labels left font ",8" tc rgb "#d62728" notitle
}
unset multiplot
