#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# One command for the evidence: installs what is needed (scripts/setup.sh), builds the
# benchmarks in Release, runs every one, and regenerates every CSV and chart of
# docs/benchmarks/ (the figures docs/benchmarks.md quotes).
# Usage: bench/run_all.sh [OUT_DIR]     (default docs/benchmarks; no input needed)
#        SC_BENCH_SOAK=1 also runs bench/soak.sh (about 20 minutes more).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(mkdir -p "${1:-$root/docs/benchmarks}" && cd "${1:-$root/docs/benchmarks}" && pwd)"
build="$root/build-bench"
jobs="${SC_JOBS:-$(nproc)}"

"$root/scripts/setup.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSC_BUILD_TESTS=OFF \
  -DSC_BUILD_TOOLS=OFF
cmake --build "$build" -j "$jobs"

run() {  # run <name> <command...>: timed, output kept next to the CSVs
  local name="$1"; shift
  local start=$SECONDS
  echo "== $name"
  "$@" > "$out/$name.log" 2>&1 || { echo "$name failed; see $out/$name.log" >&2; exit 1; }
  echo "   $((SECONDS - start)) s"
}
run mesh_distance "$build/bench/mesh_distance" --csv="$out/mesh_distance.csv"
run penetration_depth "$build/bench/penetration_depth" --csv-dir="$out"
run scene_scaling "$build/bench/scene_scaling" --csv="$out/scene_scaling.csv"
run bullet_stacking "$build/bench/bullet_stacking" --csv-dir="$out"
run pile_rotation_modes "$build/bench/pile_rotation_modes"
run bullet_terrain "$build/bench/bullet_terrain"
# The stability matrix writes its CSV next to the others and its page docs/stability.md.
run stability_matrix "$build/bench/stability_matrix" --csv="$out/stability.csv" \
  --md="$root/docs/stability.md"
# Up to 400k triangles: knot1's next level (410k) alone would preprocess for minutes.
run triangle_scaling "$build/bench/triangle_scaling" --csv "$out/triangle_scaling.csv" \
  --max-triangles 400000
# The haptic coupling demo with the 75k-triangle bunny: on the three threads (rates,
# periods; docs/benchmarks.md) and lock-step (force continuity on simulated time).
cavity=(--scene cavity --headless --device "script:$root/demos/haptic_coupling/cavity_push.txt")
run haptic_cavity "$build/demos/haptic_coupling" "${cavity[@]}" --seconds 12 \
  --json "$out/haptic_cavity.json"
# The timing targets over ten such runs (one CSV row each; fails when a run misses).
run haptic_periods bash -c '"$0" 10 "$1" > "$2"' "$root/bench/haptic_periods.sh" "$build" \
  "$out/haptic_periods.csv"
run haptic_cavity_lockstep "$build/demos/haptic_coupling" "${cavity[@]}" --lockstep \
  --json "$out/haptic_cavity_lockstep.json"
# The Python binding's overhead per call (when the module is built), its table in the log.
python="$(sed -n 's/^Python3_EXECUTABLE:FILEPATH=//p' "$build/CMakeCache.txt")"
if [[ -n "$python" && -f "$build/bench/python_overhead.so" ]]; then
  run python_overhead env PYTHONPATH="$build/python" "$python" "$root/bench/python_overhead.py" \
    "$build/bench/python_overhead.so" --check
fi
if [[ "${SC_BENCH_SOAK:-0}" == 1 ]]; then
  echo "== soak"
  "$root/bench/soak.sh" 1000000 potential "$build" > "$out/soak.csv"
fi

echo "== charts"
cd "$root"
gnuplot -e "csv='$out/penetration_haptic_steps.csv'; png='$out/penetration_haptic.png'" \
  bench/plot_penetration_haptic.gp
gnuplot -e "csv='$out/penetration_sweep.csv'; png='$out/penetration_sweep.png'" \
  bench/plot_penetration_sweep.gp
gnuplot -e "csv='$out/scene_scaling.csv'; png='$out/scene_scaling.png'" \
  bench/plot_scene_scaling.gp
gnuplot -e "csv='$out/bullet_stacking.csv'; png='$out/bullet_stacking_time.png'" \
  bench/plot_bullet_stacking_time.gp
gnuplot -e "csv='$out/bullet_stacking.csv'; png='$out/bullet_drift_jitter.png'" \
  bench/plot_bullet_drift_jitter.gp
gnuplot -e "csv='$out/potential_stiffness_vs_dt.csv'; limits='$out/potential_stiffness_limits.csv'; \
  png='$out/potential_stiffness_vs_dt.png'" bench/plot_bullet_stiffness.gp
gnuplot -e "csv='$out/triangle_scaling.csv'; png='$out/triangle_scaling.png'" \
  bench/plot_triangle_scaling.gp
echo "== done: $out"
