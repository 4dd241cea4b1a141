#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Haptic soak: the haptic coupling demo headless with its recorded script played back
# and forth (--loop) for SECONDS of real time (default 600: 10 minutes of simulated
# time, since the loops run in real time), per scene. Prints one CSV row per scene:
# haptic samples and physics steps, wall time, non-finite physics steps and haptic
# samples, the largest energy the coupling generated (CouplingEnergyMonitor, running
# maximum), the tool's largest kinetic energy, missed deadlines, resident memory after
# 1 s, after 60 s and at the end, peak memory. Fails on a non-finite state or more than
# 1 mJ generated (the bound haptic_demo_headless uses).
# Usage: bench/soak_haptic.sh [SECONDS] [BUILD_DIR] [SCENES...] > soak_haptic.csv
#        (defaults: 600, build-lead, "peg cavity"). Not part of CI.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-600}"
build="${2:-$root/build-lead}"
shift $(( $# < 2 ? $# : 2 ))
scenes=("$@")
[[ ${#scenes[@]} -gt 0 ]] || scenes=(peg cavity)
demo="$build/demos/haptic_coupling"
[[ -x "$demo" ]] || { echo "soak_haptic.sh: no haptic demo at $demo" >&2; exit 1; }

field() { sed -n "s/^ *\"$1\": *\\([^,]*\\),\\{0,1\\}$/\\1/p" "$2" | tr -d '"'; }
fields=(haptic_samples physics_steps haptic_rate_hz physics_rate_hz non_finite_steps
        non_finite_samples energy_generated_max_J energy_generated_J max_kinetic_energy_J
        max_penetration_m samples_after_missed_deadline haptic_period_max_ms
        rss_after_1s_kB rss_after_60s_kB rss_end_kB peak_rss_kB)
header="scene,seconds,wall_s"
for f in "${fields[@]}"; do header="$header,$f"; done
echo "$header"
status=0
for scene in "${scenes[@]}"; do
  script="$root/demos/haptic_coupling/peg_insertion.txt"
  [[ "$scene" == cavity ]] && script="$root/demos/haptic_coupling/cavity_push.txt"
  json="$(mktemp)"
  start=$(date +%s%N)
  "$demo" --headless --loop --scene "$scene" --device "script:$script" --seconds "$seconds" \
    --json "$json" >/dev/null
  ms=$(( ($(date +%s%N) - start) / 1000000 ))
  row="$scene,$seconds,$((ms / 1000)).$(printf '%03d' $((ms % 1000)))"
  for f in "${fields[@]}"; do row="$row,$(field "$f" "$json")"; done
  echo "$row"
  [[ "$(field non_finite_steps "$json")" == 0 && "$(field non_finite_samples "$json")" == 0 ]] ||
    status=1
  awk -v e="$(field energy_generated_max_J "$json")" 'BEGIN { exit !(e <= 1e-3) }' || status=1
  rm -f "$json"
done
exit "$status"
