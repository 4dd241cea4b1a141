# SPDX-License-Identifier: MIT
# Chart of bench/scene_scaling's CSV: UpdateStatus CPU time per frame against the
# number of groups, tree and brute-force broadphase, log-log, with a line of slope 1.
# Usage (from the repository root):
#   gnuplot -e "csv='docs/benchmarks/scene_scaling.csv'; png='docs/benchmarks/scene_scaling.png'" \
#           bench/plot_scene_scaling.gp
if (!exists("csv")) csv = 'docs/benchmarks/scene_scaling.csv'
if (!exists("png")) png = 'docs/benchmarks/scene_scaling.png'

set terminal pngcairo size 900,600 font ",11"
set output png
set datafile separator ","
set logscale xy
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set xlabel "groups (one object each; constant density, random walk)"
set ylabel "UpdateStatus CPU time per frame [ms]"
set key top left
set title "Scene scaling: dynamic AABB tree against brute-force enumeration"

# Columns: scene, broadphase, threads, groups, wall_ms, cpu_ms, pairs, cpu_us_per_group, frames.
is(scene, name, threads) = (strcol(1) eq scene && strcol(2) eq name && column(3) == threads)
# Slope-1 guide through the serial tree time at 1,000 groups.
stats csv every ::1 using (is("dense", "tree", 1) && column(4) == 1000 ? column(6) : NaN) nooutput
t1000 = STATS_max
linear(x) = t1000 * x / 1000.0

plot csv every ::1 using 4:(is("dense", "tree", 1) ? column(6) : NaN) \
         with linespoints lw 2 pt 7 title "tree, 1 thread", \
     csv every ::1 using 4:(is("dense", "brute_force", 1) ? column(6) : NaN) \
         with linespoints lw 2 pt 9 title "brute force, 1 thread", \
     csv every ::1 using 4:(is("sparse", "tree", 1) ? column(6) : NaN) \
         with linespoints lw 1 pt 6 title "tree, sparse scene (finding pairs only)", \
     [10:10000] linear(x) with lines dt 2 lc rgb "#888888" title "proportional to groups"
