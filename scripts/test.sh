#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs what is needed, builds everything, and runs every test: the whole suite
# in Release; again under AddressSanitizer + UndefinedBehaviorSanitizer (clang), whose
# build also makes the libFuzzer targets, each then fuzzed for a short time; and the
# scene tests and the haptic demo's threads under ThreadSanitizer.
# Usage: scripts/test.sh            (from anywhere; no input needed)
#        SC_FUZZ_SECONDS=N scripts/test.sh   caps each fuzz target at 5N s (default 20)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="${SC_JOBS:-$(nproc)}"
fuzz_seconds="${SC_FUZZ_SECONDS:-20}"

"$root/scripts/setup.sh"

configure() {  # configure <dir> <extra cmake args...>
  local dir="$1"; shift
  cmake -S "$root" -B "$dir" -G Ninja -DSC_WARNINGS_AS_ERRORS=ON "$@"
}
build() {  # build <dir> <extra cmake args...>
  configure "$@"
  cmake --build "$1" -j "$jobs"
}
# A build directory configured with another compiler cannot be switched in place.
use_clang() {  # use_clang <dir>
  if [[ -f "$1/CMakeCache.txt" ]] &&
     ! grep -q '^CMAKE_CXX_COMPILER:[A-Z]*=.*clang++' "$1/CMakeCache.txt"; then
    rm -rf "$1"
  fi
  export CC=clang CXX=clang++
}

echo "== Release build and tests"
build "$root/build" -DCMAKE_BUILD_TYPE=Release
ctest --test-dir "$root/build" -j "$jobs" --output-on-failure --timeout 1200

# Sanitized passes: clang, -O1, without demos and benchmarks.
sanitized=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"
           -DSC_BUILD_DEMOS=OFF -DSC_BUILD_BENCH=OFF -DSC_BUILD_PYTHON=OFF)

echo "== AddressSanitizer + UndefinedBehaviorSanitizer build (clang, with fuzz targets) and tests"
(
  use_clang "$root/build-asan"
  build "$root/build-asan" "${sanitized[@]}" -DSC_SANITIZE=ON -DSC_BUILD_FUZZERS=ON
)
# The Large differential scene only repeats the Medium one's code paths at five
# times the cost (also under TSan below).
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir "$root/build-asan" -E '/Large' -j "$jobs" --output-on-failure --timeout 1800

echo "== Fuzzing: every target for the fixed inputs of tests/fuzz/ci_runs, seed 1 (longer, new inputs: scripts/fuzz.sh 600)"
SC_FUZZ_RUNS=fixed SC_FUZZ_SEED="${SC_FUZZ_SEED:-1}" "$root/scripts/fuzz.sh" "$fuzz_seconds" "$root/build-asan"

echo "== ThreadSanitizer build of the scene tests and the haptic demo, and their runs"
(
  use_clang "$root/build-tsan"
  # Without precompiled headers: also checks that core and scene test files include
  # what they use. The plugin and the demos are configured for haptic_coupling only
  # (the later -D options win over those of "sanitized").
  configure "$root/build-tsan" "${sanitized[@]}" -DSC_SANITIZE_THREAD=ON \
    -DSC_BUILD_TOOLS=OFF -DSC_PRECOMPILED_HEADERS=OFF -DSC_BUILD_BULLET_PLUGIN=ON \
    -DSC_BUILD_DEMOS=ON
  cmake --build "$root/build-tsan" -j "$jobs" --target sc_scene_tests haptic_coupling
)
export TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1
ctest --test-dir "$root/build-tsan" -L scene -E '/Large' -j "$jobs" --output-on-failure \
  --timeout 1800
# The demo's haptic, physics and main threads for the recorded peg insertion (5 s,
# headless: no display, so its real-time metrics are not checked here; the Release
# ctest haptic_demo_headless does that). Bullet itself is not instrumented: while the
# loops run only the physics thread touches it.
"$root/build-tsan/demos/haptic_coupling" --scene peg --headless \
  --device "script:$root/demos/haptic_coupling/peg_insertion.txt" >/dev/null
unset TSAN_OPTIONS
echo "== all tests passed"
