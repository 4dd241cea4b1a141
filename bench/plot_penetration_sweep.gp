# SPDX-License-Identifier: MIT
# Chart of bench/penetration_depth's convex sweep: relative |TPDV| error (90th
# percentile over the cases) against the median time per query, log-log; ours per
# iteration count over the tolerance sweep, libccd and Bullet as reference points.
# Usage (from the repository root):
#   gnuplot -e "csv='docs/benchmarks/penetration_sweep.csv'; png='docs/benchmarks/penetration_sweep.png'" \
#           bench/plot_penetration_sweep.gp
if (!exists("csv")) csv = 'docs/benchmarks/penetration_sweep.csv'
if (!exists("png")) png = 'docs/benchmarks/penetration_sweep.png'

set terminal pngcairo size 1400,600 font ",11"
set output png
set datafile separator ","
set logscale xy
set format y "10^{%L}"
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set xlabel "median time per query [us]"
set ylabel "relative |TPDV| error, 90th percentile (floored at 1e-16)"
set key top right font ",9"
set yrange [1e-16:3]

# Columns: method, shapes, tolerance, iterations, cases, failures, median_us,
# median_err, p90_err, max_err, parameters.
err(c) = (column(c) > 1e-16 ? column(c) : 1e-16)
ours(shapes, it) = (strcol(1) eq "smartcollision" && strcol(2) eq shapes && column(4) == it)
peer(name, shapes) = (strcol(1) eq name && strcol(2) eq shapes)

set multiplot layout 1,2
do for [shapes in "boxes hulls"] {
  set title sprintf("Convex %s, shallow penetration entered from a free pose", shapes)
  plot for [it in "1 2 4 8 30"] csv every ::1 using 7:(ours(shapes, int(it)) ? err(9) : NaN) \
           with points pt 7 ps 1.2 title sprintf("SmartCollision, %s iterations (tolerance 1e-2..1e-6)", it), \
       csv every ::1 using 7:(peer("libccd_epa", shapes) ? err(9) : NaN) \
           with points pt 5 ps 1.5 title "libccd EPA (epa tolerance 1e-2..1e-8)", \
       csv every ::1 using 7:(peer("libccd_mpr", shapes) ? err(9) : NaN) \
           with points pt 9 ps 1.5 title "libccd MPR (mpr tolerance 1e-2..1e-8)", \
       csv every ::1 using 7:(peer("bullet_gjk_epa", shapes) ? err(9) : NaN) \
           with points pt 13 ps 2 title "Bullet GJK-EPA"
}
unset multiplot
