# The frame budget bench (issue 11; tests/bench/run.sh runs this after bench_budget).
#   gnuplot -e "dir='build/bench'" tests/bench/budget.gp  ->  dir/budget.png
# budget_runs.dat: one block per budget (frame, ms, level, particles); budget_points.dat:
# median ms over frames with particles (budget runs: the fixed runs' time of each frame's
# chosen level, so that the load other jobs put on the machine does not move them), mean error against the CPU reference, label,
# 0 = a fixed level of the ladder / 1 = a budget run.
if (!exists("dir")) dir = "build/bench"

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
    set terminal pngcairo size 1800,1200 font "sans,10"
} else {
    set terminal png size 1800,1200
}
set output dir."/budget.png"
set termoption noenhanced
runs = system(sprintf("grep -c '^# budget' %s/budget_runs.dat", dir)) + 0
array budget[runs]
# the budgets, from the block headers
do for [i=1:runs] {
    budget[i] = system(sprintf("awk '/^# budget/{n++; if (n == %d) print $3}' %s/budget_runs.dat", i, dir)) + 0
}
colour(i) = (i == 1 ? 0x2ca02c : i == 2 ? 0x1f77b4 : i == 3 ? 0xff7f0e : i == 4 ? 0xd62728 : 0x9467bd)

set multiplot layout 2,2 title "sbfx: frame budgets — the barrage scene (24 explosions, up to about 2700 live particles), llvmpipe; the governor picks the quality level"

set title "frame time against the budget (dashed)"
set xlabel "frame (1/60 s each)"
set ylabel "sbfx_render, ms (glFinish-bracketed)"
set logscale y
set grid xtics ytics lc rgb "#dddddd"
set key top right box opaque font ",9"
plot for [i=1:runs] dir."/budget_runs.dat" index (i - 1) using 1:($4 > 0 ? $2 : 1/0) with lines lw 1.2 \
         lc rgb colour(i) title sprintf("budget %.1f ms", budget[i]), \
     for [i=1:runs] budget[i] with lines dt 2 lw 1.5 lc rgb colour(i) notitle

set title "level chosen (0 = the top: most accurate)"
unset logscale y
set ylabel "ladder level"
set ytics 1
set yrange [-0.5:*] reverse
set key top right
plot for [i=1:runs] dir."/budget_runs.dat" index (i - 1) using 1:($3 + (i - (runs + 1) / 2.0) * 0.06) with steps lw 2 \
         lc rgb colour(i) title sprintf("budget %.1f ms", budget[i])
set yrange [*:*] noreverse
set ytics autofreq

set title "live particles"
set ylabel "particles drawn before the level of detail"
unset key
plot dir."/budget_runs.dat" index 0 using 1:4 with lines lw 2 lc rgb "#555555"

set title "error of what was shown against the CPU reference, fixed levels (grey) and budgets (colour)"
set xlabel "median frame time over frames with particles, ms (budget runs: the fixed runs' time of the level chosen, frame by frame)"
set ylabel "mean abs error, 8-bit levels"
set logscale xy
set key top right box opaque
plot dir."/budget_points.dat" using 1:($4 == 0 ? $2 : 1/0) with linespoints pt 7 ps 1.3 lc rgb "#888888" title "fixed level", \
     dir."/budget_points.dat" using 1:($4 == 0 ? $2 : 1/0):3 with labels offset char 1,0.6 left font ",8" tc rgb "#555555" notitle, \
     dir."/budget_points.dat" using 1:($4 == 1 ? $2 : 1/0) with points pt 9 ps 2 lc rgb "#d62728" title "with a budget", \
     dir."/budget_points.dat" using 1:($4 == 1 ? $2 : 1/0):3 with labels offset char 1,-0.8 left font ",8" tc rgb "#d62728" notitle

unset multiplot
