# Error against time of every accuracy configuration (tests/bench/run.sh runs this).
#   gnuplot -e "dir='build/bench'" tests/bench/accuracy.gp  ->  dir/accuracy.png
# points.dat: ms, mean abs error, label, group (0 = main grid: RGBA16F, tables, R16F detail;
# 1 = a variant: RGBA8/RGBA32F target, analytic black body/phase, R32F detail, light per
# particle, density matched to the exact model), opacity mode
# (1 planar, 2 soft, 3 spherical, 4 exact), divisor, upsampling (0 nearest-depth, 1 bilinear).
# pareto.dat: the Pareto front (no configuration is both faster and closer), by time.
# Left: everything, log-log, the front labelled. Right: the planar / soft / spherical cluster
# (their error is mostly the model's: twice the exact optical depth at the centre), labelled.
if (!exists("dir")) dir = "build/bench"
# mali-points.dat (tests/bench/run.sh, where Mesa's drm-shims are built): a third panel, the
# estimated particle + composite time on a Mali-G610 against the same error
mali = int(system("test -s ".dir."/mali-points.dat && echo 1 || echo 0"))
width = mali ? 2600 : 1800

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
    set terminal pngcairo size width,900 font "sans,10"
} else {
    set terminal png size width,900
}
set output dir."/accuracy.png"
set datafile separator whitespace
set offsets graph 0.03, graph 0.12, 0, 0

# mode -> point type and colour; filled = nearest-depth, open = bilinear
pt_of(m, u) = (m == 1 ? 9 : m == 2 ? 13 : m == 3 ? 7 : 5) - u
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
set key top right box opaque font ",9"
plot dir."/points.dat" using 1:($4 == 1 ? $2 : 1/0) with points pt 1 ps 1.2 lc rgb "#888888" \
         title "variants: RGBA8 / RGBA32F target, analytic LUTs, R32F detail, light per particle, density τ/2", \
     for [m=1:4] dir."/points.dat" using 1:($4 == 0 && $5 == m ? $2 : 1/0):(pt_of($5, $7)):(lc_of($5)) \
         with points pt variable ps 1.4 lc rgb variable notitle, \
     for [m=1:4] keyentry with points pt pt_of(m, 0) ps 1.4 lc rgb lc_of(m) \
         title (m == 1 ? "planar" : m == 2 ? "soft" : m == 3 ? "spherical" : "exact")." (filled: nearest-depth, open: bilinear)", \
     dir."/pareto.dat" using 1:2 with linespoints lw 2 pt 4 ps 2.0 lc rgb "#d62728" title "Pareto front", \
     dir."/pareto.dat" using 1:2:3 with labels offset char 0.8,-0.8 left font ",8" tc rgb "#d62728" notitle, \
     dir."/points.dat" using 1:($4 == 0 && $5 == 4 ? $2 : 1/0):3 with labels offset char 0.8,0.7 left \
         font ",8" tc rgb "#ff7f0e" notitle

set title "planar / soft / spherical, every scale and upsampling (labels: mode/divisor upsampling)"
unset logscale y
set yrange [cluster_lo - 0.02 * (cluster_hi - cluster_lo) - 0.005 : cluster_hi + 0.08 * (cluster_hi - cluster_lo) + 0.005]
set key top left box opaque font ",9"
plot for [m=1:3] dir."/points.dat" using 1:($4 == 0 && $5 == m ? $2 : 1/0):(pt_of($5, $7)):(lc_of($5)) \
         with points pt variable ps 1.4 lc rgb variable notitle, \
     for [m=1:3] keyentry with points pt pt_of(m, 0) ps 1.4 lc rgb lc_of(m) \
         title (m == 1 ? "planar" : m == 2 ? "soft" : "spherical"), \
     for [m=1:3] dir."/points.dat" using 1:($4 == 0 && $5 == m ? $2 : 1/0):3:(lc_of($5)) with labels \
         offset char 0.6,(m - 2) * 0.8 left font ",8" tc rgb variable notitle

if (mali) {
    set title "Mali-G610 (Mesa's static estimate, see summary.txt): particle + composite ms per frame"
    set xlabel "estimated ms per frame on a G610 MP4 (fragments counted on llvmpipe x cycles per fragment)"
    set ylabel "mean abs error, 8-bit levels"
    set logscale xy
    set autoscale y
    unset key
    plot dir."/mali-points.dat" using 1:2 with points pt 7 ps 1.2 lc rgb "#1f77b4", \
         dir."/mali-points.dat" using 1:2:3 with labels offset char 0.6,0.5 left font ",7" tc rgb "#555555"
}
unset multiplot
