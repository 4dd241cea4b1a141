# SPDX-License-Identifier: MIT
# Chart of bench/bullet_stacking's stiffness sweep: the potential model's requested
# contact stiffness kT against the time step for the 10-box tower (5 s), each run
# marked by how it ended.
# Usage (from the repository root):
#   gnuplot -e "csv='docs/benchmarks/potential_stiffness_vs_dt.csv'; \
#               limits='docs/benchmarks/potential_stiffness_limits.csv'; \
#               png='docs/benchmarks/potential_stiffness_vs_dt.png'" bench/plot_bullet_stiffness.gp
if (!exists("csv")) csv = 'docs/benchmarks/potential_stiffness_vs_dt.csv'
if (!exists("limits")) limits = 'docs/benchmarks/potential_stiffness_limits.csv'
if (!exists("png")) png = 'docs/benchmarks/potential_stiffness_vs_dt.png'

set terminal pngcairo size 900,750 font ",11"
set output png
set datafile separator ","
set logscale xy
set format y "10^{%L}"
set grid xtics ytics lc rgb "#dddddd"
set xrange [0.8:20]
set yrange [5:2e8]
set xtics (1.04, 2.08, 4.17, 8.33, 16.7)
set xlabel "time step [ms] (960, 480, 240, 120, 60 Hz)"
set ylabel "requested force stiffness kT [N/m]"
set key below maxrows 4 font ",10"
set title "Potential model, 10-box tower of 0.5 m, 1 kg boxes, 5 s: where it stands, where it fails"

# Sweep columns: hz, dt_s, k_requested, k_eff_box_box, k_eff_ground, outcome, top_drop_mm, rms.
ms = 1000.0
is(name) = strcol(4) eq name ? column(3) : NaN
broke(c) = strcol(4) eq "blow_up" || strcol(4) eq "nan" ? column(c) : NaN
# Limits columns: hz, dt_s, ..., 9 clamp_k, 10 default_k.
plot csv every ::1 using ($2 * ms):(is("stable")) with points pt 7 ps 1.4 lc rgb "#1b9e77" \
         title "stands, at rest", \
     csv every ::1 using ($2 * ms):(is("restless")) with points pt 7 ps 1.4 lc rgb "#e6ab02" \
         title "stands, still moving (RMS > 0.05 m/s)", \
     csv every ::1 using ($2 * ms):(is("sank")) with points pt 11 ps 1.4 lc rgb "#7570b3" \
         title "sank (box half inside the one below)", \
     csv every ::1 using ($2 * ms):(is("toppled")) with points pt 5 ps 1.4 lc rgb "#d95f02" \
         title "toppled", \
     csv every ::1 using ($2 * ms):(broke(3)) with points pt 2 ps 1.6 \
         lc rgb "#e41a1c" title "blew up / NaN"
