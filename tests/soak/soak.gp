# The soak record (make soak): gnuplot -e "dir='build/soak'" tests/soak/soak.gp -> dir/soak.png
# soak.csv columns: 1 sim_hours, 2 frames, 3 wall_seconds, 4 rss_kib, 5 rss_anon_kib,
# 6 rss_file_kib, 7 heap_bytes, 8 programs, 9 textures, 10 framebuffers, 11 gpu_bytes,
# 12 heap_allocs_after_load, 13 gl_textures, 14 gl_framebuffers, 15 gl_buffers,
# 16 particles_alive, 17 triggers_fired, 18 triggers_refused
if (!exists("dir")) dir = "build/soak"

if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {
    set terminal pngcairo size 1500,1000 font "sans,10"
} else {
    set terminal png size 1500,1000
}
set output dir."/soak.png"
set datafile separator ","
set key autotitle columnhead noenhanced
set termoption noenhanced
set grid
set xlabel "simulated hours"

set multiplot layout 2,2 title "sbfx-soak: the kiosk loop, effects triggered every 0.2 s (build/soak/soak.csv)"

set title "process memory"
set ylabel "MiB"
plot dir."/soak.csv" using 1:($4/1024) with lines lw 2 title "resident (RSS)", \
     "" using 1:($5/1024) with lines lw 2 title "resident, anonymous (checked)", \
     "" using 1:($6/1024) with lines lw 2 title "resident, file-backed (library code)", \
     "" using 1:($7/1048576) with lines lw 2 title "malloc'ed (heap, checked)"

set title "GL objects (sbfx's counters, and alive in the context)"
set ylabel "count"
plot dir."/soak.csv" using 1:8 with steps lw 2 title "sbfx programs", \
     "" using 1:9 with steps lw 2 title "sbfx textures", \
     "" using 1:10 with steps lw 2 title "sbfx framebuffers", \
     "" using 1:13 with steps lw 2 dt 2 title "context textures", \
     "" using 1:14 with steps lw 2 dt 2 title "context framebuffers", \
     "" using 1:15 with steps lw 2 dt 2 title "context buffers", \
     "" using 1:12 with steps lw 2 title "sbfx heap allocations after load"

set title "GPU bytes sbfx holds"
set ylabel "MiB"
plot dir."/soak.csv" using 1:($11/1048576) with steps lw 2 title "gpu bytes"

set title "effects"
set ylabel "particles alive"
set y2label "triggers"
set y2tics
plot dir."/soak.csv" using 1:16 with lines title "particles alive", \
     "" using 1:17 axes x1y2 with lines lw 2 title "triggers fired", \
     "" using 1:18 axes x1y2 with lines lw 2 title "triggers refused"
unset multiplot
