# SPDX-License-Identifier: MIT
# Query time and preprocessing time against the triangle count (bench/triangle_scaling).
# Usage: gnuplot -e "csv='docs/benchmarks/triangle_scaling.csv'; png='docs/benchmarks/triangle_scaling.png'" bench/plot_triangle_scaling.gp
if (!exists("csv")) csv = 'docs/benchmarks/triangle_scaling.csv'
if (!exists("png")) png = 'docs/benchmarks/triangle_scaling.png'
set terminal pngcairo size 1400,560 font ",11"
set output png
set datafile separator ","
set logscale xy
set grid
set key top left
set xlabel "triangles per model (each model against a copy of itself)"
sphere = "icosphere (convex)"
knot = "knot1 subdivided (non-convex)"
cgal = "CGAL models"
pick(s, col) = (strcol(1) eq s ? column(col) : NaN)
set multiplot layout 1,2
set key bottom right
set title "Time per query, median (us)"
set ylabel "us"
plot csv every ::1 using 3:(pick(sphere, 6)) with linespoints lw 2 pt 7 lc rgb "#1f77b4" title "ours, distance, icosphere", \
     csv every ::1 using 3:(pick(sphere, 8)) with linespoints lw 2 pt 6 dt 2 lc rgb "#1f77b4" title "FCL, distance, icosphere", \
     csv every ::1 using 3:(pick(knot, 6)) with linespoints lw 2 pt 5 lc rgb "#d62728" title "ours, distance, knot1", \
     csv every ::1 using 3:(pick(knot, 8)) with linespoints lw 2 pt 4 dt 2 lc rgb "#d62728" title "FCL, distance, knot1", \
     csv every ::1 using 3:(pick(cgal, 6)) with points pt 9 ps 1.5 lc rgb "#2ca02c" title "ours, distance, CGAL models", \
     csv every ::1 using 3:(pick(cgal, 8)) with points pt 8 ps 1.5 lc rgb "#2ca02c" title "FCL, distance, CGAL models", \
     csv every ::1 using 3:(pick(sphere, 10)) with linespoints lw 1 pt 7 dt 3 lc rgb "#9467bd" title "ours, penetration depth, icosphere", \
     csv every ::1 using 3:(pick(knot, 10)) with linespoints lw 1 pt 5 dt 3 lc rgb "#ff7f0e" title "ours, penetration depth, knot1"
set key top left
set title "Preprocessing (s): our decomposition + hull hierarchy vs FCL's OBBRSS tree"
set ylabel "s"
plot csv every ::1 using 3:(pick(sphere, 4)) with linespoints lw 2 pt 7 lc rgb "#1f77b4" title "ours, icosphere", \
     csv every ::1 using 3:(pick(sphere, 5)) with linespoints lw 2 pt 6 dt 2 lc rgb "#1f77b4" title "FCL, icosphere", \
     csv every ::1 using 3:(pick(knot, 4)) with linespoints lw 2 pt 5 lc rgb "#d62728" title "ours, knot1", \
     csv every ::1 using 3:(pick(knot, 5)) with linespoints lw 2 pt 4 dt 2 lc rgb "#d62728" title "FCL, knot1", \
     csv every ::1 using 3:(pick(cgal, 4)) with points pt 9 ps 1.5 lc rgb "#2ca02c" title "ours, CGAL models", \
     csv every ::1 using 3:(pick(cgal, 5)) with points pt 8 ps 1.5 lc rgb "#2ca02c" title "FCL, CGAL models"
unset multiplot

# Preprocessing alone against the triangle count (triangle_scaling --preprocess-csv):
# time (ours wall and CPU, FCL's BVH build) and peak resident memory per process;
# prep_before (if readable) is an earlier run, drawn thin for comparison.
if (!exists("prep_csv")) prep_csv = 'docs/benchmarks/triangle_scaling_preprocess.csv'
if (!exists("prep_png")) prep_png = 'docs/benchmarks/triangle_scaling_preprocess.png'
if (!exists("prep_before")) prep_before = 'docs/benchmarks/triangle_scaling_preprocess_round2.csv'
if (!exists("before_label")) before_label = "before Quickhull"
set output prep_png
set xlabel "triangles"
set xrange [5000:4e6]
closed = "torus (closed)"
soup = "torus (soup)"
set multiplot layout 1,2
set key top left
set title "Preprocessing time against the triangle count"
set ylabel "s"
plot prep_csv every ::1 using 3:(pick(closed, 4)) with linespoints lw 2 pt 7 lc rgb "#d62728" title "ours, closed torus, wall", \
     prep_csv every ::1 using 3:(pick(closed, 5)) with linespoints lw 2 pt 6 dt 3 lc rgb "#d62728" title "ours, closed torus, CPU", \
     prep_before every ::1 using 3:(pick(closed, 5)) with lines lw 1.5 dt 4 lc rgb "#f08080" title "closed torus, CPU, ".before_label, \
     prep_csv every ::1 using 3:(pick(soup, 4)) with linespoints lw 2 pt 5 lc rgb "#1f77b4" title "ours, soup, wall", \
     prep_csv every ::1 using 3:(pick(soup, 5)) with linespoints lw 2 pt 4 dt 3 lc rgb "#1f77b4" title "ours, soup, CPU", \
     prep_before every ::1 using 3:(pick(soup, 5)) with lines lw 1.5 dt 4 lc rgb "#6fa8dc" title "soup, CPU, ".before_label, \
     prep_csv every ::1 using 3:(pick(closed, 6)) with linespoints lw 2 pt 9 dt 2 lc rgb "#7f7f7f" title "FCL BVH build", \
     prep_csv every ::1 using 3:(pick(cgal, 5)) with points pt 13 ps 1.5 lc rgb "#2ca02c" title "ours, bunny00, CPU"
set title "Peak resident memory of the process (MB)"
set ylabel "MB"
plot prep_csv every ::1 using 3:(pick(closed, 8) / 1024) with linespoints lw 2 pt 7 lc rgb "#d62728" title "closed torus", \
     prep_before every ::1 using 3:(pick(closed, 8) / 1024) with lines lw 1.5 dt 4 lc rgb "#f08080" title "closed torus, ".before_label, \
     prep_csv every ::1 using 3:(pick(soup, 8) / 1024) with linespoints lw 2 pt 5 lc rgb "#1f77b4" title "soup", \
     prep_before every ::1 using 3:(pick(soup, 8) / 1024) with lines lw 1.5 dt 4 lc rgb "#6fa8dc" title "soup, ".before_label, \
     prep_csv every ::1 using 3:(pick(soup, 3) / 1024) with lines lw 1 dt 2 lc rgb "#000000" title "1 KB per triangle", \
     prep_csv every ::1 using 3:(pick(cgal, 8) / 1024) with points pt 13 ps 1.5 lc rgb "#2ca02c" title "bunny00"
unset multiplot
