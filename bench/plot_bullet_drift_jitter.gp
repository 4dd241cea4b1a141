# SPDX-License-Identifier: MIT
# Chart of bench/bullet_stacking's CSV at one rate (default 60 Hz): the largest overlap
# (impacts included), the overlap over the last second, and the RMS speed over the
# last second, per scene and contact model, log scale; "X" marks a scene that fell or
# a pile that escaped its bowl.
# Usage (from the repository root):
#   gnuplot -e "csv='docs/benchmarks/bullet_stacking.csv'; png='docs/benchmarks/bullet_drift_jitter.png'; hz=60" \
#           bench/plot_bullet_drift_jitter.gp
if (!exists("csv")) csv = 'docs/benchmarks/bullet_stacking.csv'
if (!exists("png")) png = 'docs/benchmarks/bullet_drift_jitter.png'
if (!exists("hz")) hz = 60

set terminal pngcairo size 1000,1100 font ",11"
set output png
set datafile separator ","
set style fill solid 0.8 border -1
set boxwidth 0.15
set logscale y
set format y "10^{%L}"
set grid ytics mytics lc rgb "#dddddd"
set xrange [-0.5:4.5]
set xtics ("10-box tower" 0, "1:100 stack" 1, "15-box pyramid" 2, "4 cows" 3, "24 tori in a bowl" 4)

# Columns: 2 scene_id, 3 hz, 5 model_id, 11 max_overlap_mm, 12 settled_overlap_mm,
# 13 rest_rms_mps, 16 stands.
x(m) = column(2) + 0.16 * (m - 2)
sel(m, c, floor) = column(5) == m && column(3) == hz ? (column(c) > floor ? column(c) : floor) : NaN
fell(m, c, floor) = column(5) == m && column(3) == hz && column(16) == 0 ? 1.6 * sel(m, c, floor) : NaN
colors = "#d95f02 #7570b3 #1b9e77 #e7298a #666666"
names = "'SmartCollision potential' 'SmartCollision manifold' 'btGImpactMeshShape' 'btCompoundShape of HACD parts' 'btBoxShape'"

set multiplot layout 3,1 title sprintf("Overlap and rest per contact model (%d Hz, 10 s; overlaps measured geometrically)", hz)
set key top left font ",10"
set ylabel "largest overlap, impacts included [mm]"
set yrange [0.01:1e4]
plot for [m=0:4] csv every ::1 using (x(m)):(sel(m, 11, 0.01)) with boxes \
         lc rgb word(colors, m + 1) title word(names, m + 1), \
     for [m=0:4] csv every ::1 using (x(m)):(fell(m, 11, 0.01)):("X") with labels notitle
set key off
set ylabel "largest overlap, last second [mm]"
plot for [m=0:4] csv every ::1 using (x(m)):(sel(m, 12, 0.01)) with boxes \
         lc rgb word(colors, m + 1) notitle, \
     for [m=0:4] csv every ::1 using (x(m)):(fell(m, 12, 0.01)):("X") with labels notitle
set ylabel "RMS speed, last second [m/s]"
set yrange [1e-7:10]
plot for [m=0:4] csv every ::1 using (x(m)):(sel(m, 13, 1e-7)) with boxes \
         lc rgb word(colors, m + 1) notitle, \
     for [m=0:4] csv every ::1 using (x(m)):(fell(m, 13, 1e-7)):("X") with labels notitle
unset multiplot
