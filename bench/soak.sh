#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Soak: every stacking scene for N physics steps (default 10^6, 240 Hz: 69 minutes of
# simulated time each) in one contact model, from the headless stacking demo. Prints
# one CSV row per scene: steps, wall time, non-finite steps, the largest energy rise
# above the first step's, resident memory after 1 s and at the end, peak memory.
# Usage: bench/soak.sh [STEPS] [MODEL] [BUILD_DIR] > soak.csv
#        (defaults: 1000000, potential, build-lead). Not part of CI: it takes about
#        20 minutes per model on one core.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
steps="${1:-1000000}"
model="${2:-potential}"
build="${3:-$root/build-lead}"
demo="$build/demos/stacking"
[[ -x "$demo" ]] || { echo "soak.sh: no stacking demo at $demo" >&2; exit 1; }

field() { sed -n "s/^ *\"$1\": *\\([^,]*\\),\\{0,1\\}$/\\1/p" "$2" | tr -d '"'; }
echo "scene,model,bodies,steps,wall_s,ms_per_step,non_finite_steps,max_energy_rise_J,top_drift_m,max_penetration_m,rss_after_1s_kB,rss_end_kB,peak_rss_kB"
status=0
for scene in tower pyramid massratio meshes; do
  json="$(mktemp)"
  start=$(date +%s%N)
  "$demo" --headless --scene "$scene" --model "$model" --steps "$steps" --json "$json" >/dev/null
  ms=$(( ($(date +%s%N) - start) / 1000000 ))
  wall="$((ms / 1000)).$(printf '%03d' $((ms % 1000)))"
  row="$scene,$model,$(field bodies "$json"),$(field steps "$json"),$wall"
  for f in ms_per_step non_finite_steps max_energy_rise_J top_drift_m max_penetration_m \
           rss_after_1s_kB rss_end_kB peak_rss_kB; do
    row="$row,$(field "$f" "$json")"
  done
  echo "$row"
  [[ "$(field non_finite_steps "$json")" == 0 ]] || status=1
  rm -f "$json"
done
exit "$status"
