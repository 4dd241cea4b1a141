# SPDX-License-Identifier: MIT
# Chart of bench/bullet_stacking's CSV: wall time per step (mean bar, p95 whisker) of
# each stacking scene under each contact model, same process, log scale.
# Usage (from the repository root):
#   gnuplot -e "csv='docs/benchmarks/bullet_stacking.csv'; png='docs/benchmarks/bullet_stacking_time.png'" \
#           bench/plot_bullet_stacking_time.gp
if (!exists("csv")) csv = 'docs/benchmarks/bullet_stacking.csv'
if (!exists("png")) png = 'docs/benchmarks/bullet_stacking_time.png'

set terminal pngcairo size 900,600 font ",11"
set output png
set datafile separator ","
set logscale y
set grid ytics mytics lc rgb "#dddddd"
set xrange [-0.5:2.5]
set xtics ("10-box tower" 0, "15-box pyramid" 1, "4 cows (5.8k triangles)" 2)
set ylabel "wall time per step, 240 Hz [ms] (bar: mean, whisker: p95)"
set key top left
set title "Time per step after settling: SmartCollision against Bullet's GImpact and HACD compound"
set style fill solid 0.8 border -1
set boxwidth 0.18

# Columns: scene, scene_id, model, model_id, steps, mean_ms, p95_ms, ...
x(m) = column(2) + 0.2 * (m - 1.5)
sel(m, c) = column(4) == m ? column(c) : NaN
colors = "#d95f02 #7570b3 #1b9e77 #e7298a"
names = "'SmartCollision potential' 'SmartCollision manifold' 'btGImpactMeshShape' 'btCompoundShape of HACD parts'"

plot for [m=0:3] csv every ::1 using (x(m)):(sel(m, 6)) with boxes lc rgb word(colors, m + 1) \
         title word(names, m + 1), \
     for [m=0:3] csv every ::1 using (x(m)):(sel(m, 6)):(sel(m, 6)):(sel(m, 7)) \
         with yerrorbars lc rgb "black" pt -1 notitle
