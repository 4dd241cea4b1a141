# SPDX-License-Identifier: MIT
# Chart of bench/penetration_depth's haptic path (fandisk against armadillo, INPUT):
# time per update along the path (thread CPU and wall clock) and |TPDV|.
# Usage (from the repository root):
#   gnuplot -e "csv='docs/benchmarks/penetration_haptic_steps.csv'; png='docs/benchmarks/penetration_haptic.png'" \
#           bench/plot_penetration_haptic.gp
if (!exists("csv")) csv = 'docs/benchmarks/penetration_haptic_steps.csv'
if (!exists("png")) png = 'docs/benchmarks/penetration_haptic.png'

set terminal pngcairo size 1000,600 font ",11"
set output png
set datafile separator ","
set logscale y
set grid xtics ytics lc rgb "#dddddd"
set xlabel "step (2000 updates, one per haptic frame)"
set ylabel "time per update [us]"
set y2label "|TPDV| (model units, unit-size models)"
set y2tics
set ytics nomirror
set key outside bottom center horizontal
set title "Dynamic penetration depth under haptic-like motion: fandisk (13k triangles) against armadillo (52k)"

# Columns: step, wall_us, cpu_us, tpdv.
plot csv every ::1 using 1:2 with points pt 7 ps 0.3 lc rgb "#bbbbbb" title "wall clock", \
     csv every ::1 using 1:3 with points pt 7 ps 0.3 lc rgb "#1f77b4" title "thread CPU time", \
     1000 with lines dt 2 lc rgb "#d62728" title "1 ms (1 kHz loop)", \
     csv every ::1 using 1:4 axes x1y2 with lines lw 2 lc rgb "#2ca02c" title "|TPDV|"
