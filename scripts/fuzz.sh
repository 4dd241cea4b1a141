#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs every libFuzzer target of a SC_BUILD_FUZZERS build for a bounded time, each
# on a scratch copy of its seed corpus (the repository is never modified). Fails on
# the first crash, leak, timeout or broken invariant and prints the input's path.
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET] [BUILD_DIR]
#        (defaults: 20 and build-asan, the sanitizer build of scripts/test.sh)
#        SC_FUZZ_SEED=N fixes libFuzzer's seed (scripts/test.sh uses 1, so that the CI
#        explores the same inputs on every run; unset, each run explores new ones).
#        SC_FUZZ_TIMEOUT=N: one input running over N seconds fails (default 15).
#        SC_FUZZ_RUNS=fixed: each target runs the number of inputs tests/fuzz/ci_runs
#        gives it instead of running for a time (SECONDS then only caps a run at 5x):
#        with a fixed seed the CI then tries the same inputs on every machine.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-20}"
timeout="${SC_FUZZ_TIMEOUT:-15}"
seed_option=()
[[ -n "${SC_FUZZ_SEED:-}" ]] && seed_option=(-seed="$SC_FUZZ_SEED")
build="$(cd "${2:-$root/build-asan}" && pwd)"
corpora="$root/tests/fuzz/corpus"
artifacts="$build/fuzz-artifacts"  # crash inputs outlive the scratch directory

shopt -s nullglob
targets=("$build"/tests/fuzz/fuzz_*)
if [[ ${#targets[@]} -eq 0 ]]; then
  echo "fuzz.sh: no fuzz targets in $build/tests/fuzz (configure with -DSC_BUILD_FUZZERS=ON)" >&2
  exit 1
fi

scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
mkdir -p "$artifacts"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"

status=0
for exe in "${targets[@]}"; do
  [[ -x "$exe" && -f "$exe" ]] || continue
  name="$(basename "$exe")"
  mkdir -p "$scratch/$name" "$artifacts/$name"
  [[ -d "$corpora/$name" ]] && cp -r "$corpora/$name/." "$scratch/$name/"
  log="$scratch/$name.log"
  # A target linking an uninstrumented library may list that library's own leaks
  # (tests/fuzz/<target>.lsan.supp); leaks with our frames on top still fail.
  lsan=()
  supp="$root/tests/fuzz/$name.lsan.supp"
  [[ -f "$supp" ]] && lsan=(LSAN_OPTIONS="suppressions=$supp:print_suppressions=0")
  limit=(-max_total_time="$seconds")
  if [[ "${SC_FUZZ_RUNS:-}" == fixed ]]; then
    runs="$(awk -v n="$name" '$1 == n { print $2 }' "$root/tests/fuzz/ci_runs")"
    [[ -n "$runs" ]] || { echo "$name: no run count in tests/fuzz/ci_runs" >&2; exit 1; }
    limit=(-runs="$runs" -max_total_time="$(( 5 * seconds ))")
  fi
  # -timeout: one input taking this long is a failure (a hang or runaway loop).
  if env "${lsan[@]}" "$exe" "$scratch/$name" "${seed_option[@]}" "${limit[@]}" -timeout="$timeout" -rss_limit_mb=2560 \
       -print_final_stats=1 -artifact_prefix="$artifacts/$name/" >"$log" 2>&1; then
    runs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)"
    secs="$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log" | tail -1)"
    cov="$(grep -o 'cov: [0-9]*' "$log" | tail -1 || true)"
    rate=$(( ${runs:-0} / ( ${secs:-0} > 0 ? ${secs:-1} : 1 ) ))
    printf '%-22s ok   %8s runs in %ss (%s exec/s), %s\n' "$name" "${runs:-?}" "${secs:-?}" \
      "$rate" "${cov:-cov: ?}"
  else
    status=1
    echo "$name FAILED; last lines of its log:"
    tail -n 60 "$log"
    crash="$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$log" | tail -1)"
    echo "$name: failing input: ${crash:-(none written; see the log above)}"
    echo "$name: reproduce with: $exe ${crash:-<input>}"
  fi
done
exit "$status"
