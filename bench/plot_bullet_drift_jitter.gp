# SPDX-License-Identifier: MIT
# Chart of bench/bullet_stacking's CSV: top drift after the run (horizontal displacement
# plus drop below the resting height) and jitter (RMS speed over the last 2 s) per
# scene and contact model, log scale; "falls" marks a scene that did not stay up.
# Usage (from the repository root):
#   gnuplot -e "csv='docs/benchmarks/bullet_stacking.csv'; png='docs/benchmarks/bullet_drift_jitter.png'" \
#           bench/plot_bullet_drift_jitter.gp
if (!exists("csv")) csv = 'docs/benchmarks/bullet_stacking.csv'
if (!exists("png")) png = 'docs/benchmarks/bullet_drift_jitter.png'

set terminal pngcairo size 1000,800 font ",11"
set output png
set datafile separator ","
set style fill solid 0.8 border -1
set boxwidth 0.18
set logscale y
set grid ytics mytics lc rgb "#dddddd"
set xrange [-0.5:2.5]
set xtics ("10-box tower" 0, "15-box pyramid" 1, "4 cows (5.8k triangles)" 2)

# Columns: ..., 12 drift_mm, 13 max_tilt_mrad, 14 jitter_mps, 15 max_penetration_mm, 16 stands.
x(m) = column(2) + 0.2 * (m - 1.5)
sel(m, c, floor) = column(4) == m ? (column(c) > floor ? column(c) : floor) : NaN
fell(m, c, floor) = column(4) == m && column(16) == 0 ? 1.6 * sel(m, c, floor) : NaN
colors = "#d95f02 #7570b3 #1b9e77 #e7298a"
names = "'SmartCollision potential' 'SmartCollision manifold' 'btGImpactMeshShape' 'btCompoundShape of HACD parts'"

set multiplot layout 2,1 title "Drift and jitter per contact model (240 Hz, 10 s, 1 kg bodies)"
set key top right font ",10"
set format y "10^{%L}"
set ylabel "top drift [mm] (floor 0.01)"
set yrange [0.05:1e6]
plot for [m=0:3] csv every ::1 using (x(m)):(sel(m, 12, 0.01)) with boxes \
         lc rgb word(colors, m + 1) title word(names, m + 1), \
     for [m=0:3] csv every ::1 using (x(m)):(fell(m, 12, 0.01)):("falls") with labels \
         font ",9" notitle
set key off
set ylabel "jitter: RMS speed, last 2 s [m/s] (floor 1e-7)"
set yrange [1e-7:1]
plot for [m=0:3] csv every ::1 using (x(m)):(sel(m, 14, 1e-7)) with boxes \
         lc rgb word(colors, m + 1) notitle, \
     for [m=0:3] csv every ::1 using (x(m)):(fell(m, 14, 1e-7)):("falls") with labels \
         font ",9" notitle
unset multiplot
