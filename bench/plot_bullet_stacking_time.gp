# SPDX-License-Identifier: MIT
# Chart of bench/bullet_stacking's CSV: thread CPU time per step of each scene under
# each contact model, one panel per rate (60, 120, 240 Hz), same process, log scale.
# Usage (from the repository root):
#   gnuplot -e "csv='docs/benchmarks/bullet_stacking.csv'; png='docs/benchmarks/bullet_stacking_time.png'" \
#           bench/plot_bullet_stacking_time.gp
if (!exists("csv")) csv = 'docs/benchmarks/bullet_stacking.csv'
if (!exists("png")) png = 'docs/benchmarks/bullet_stacking_time.png'

set terminal pngcairo size 1000,1100 font ",11"
set output png
set datafile separator ","
set logscale y
set grid ytics mytics lc rgb "#dddddd"
set xrange [-0.5:4.5]
set yrange [0.01:300]
set xtics ("10-box tower" 0, "1:100 stack" 1, "15-box pyramid" 2, "4 cows" 3, "24 tori in a bowl" 4)
set style fill solid 0.8 border -1
set boxwidth 0.15

# Columns: 1 scene, 2 scene_id, 3 hz, 4 model, 5 model_id, 6 steps, 7 mean_ms, 8 p95_ms,
# 9 cpu_mean_ms, ...
x(m) = column(2) + 0.16 * (m - 2)
sel(m, hz, c) = column(5) == m && column(3) == hz ? column(c) : NaN
colors = "#d95f02 #7570b3 #1b9e77 #e7298a #666666"
names = "'SmartCollision potential' 'SmartCollision manifold' 'btGImpactMeshShape' 'btCompoundShape of HACD parts' 'btBoxShape'"

set multiplot layout 3,1 title "CPU time per step (thread CPU, mean over 10 s), all models of a scene interleaved in one process"
do for [hz in "60 120 240"] {
  set ylabel sprintf("%s Hz: ms per step", hz)
  if (hz eq "60") { set key top left font ",10" } else { set key off }
  plot for [m=0:4] csv every ::1 using (x(m)):(sel(m, real(hz), 9)) with boxes \
           lc rgb word(colors, m + 1) title word(names, m + 1)
}
unset multiplot
