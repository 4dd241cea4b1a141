#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs what is needed, builds everything, and runs every test: the whole suite
# in Release, then again under AddressSanitizer + UndefinedBehaviorSanitizer.
# Usage: scripts/test.sh            (from anywhere; no input needed)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
jobs="${SC_JOBS:-$(nproc)}"

"$root/scripts/setup.sh"

build() {  # build <dir> <extra cmake args...>
  local dir="$1"; shift
  cmake -S "$root" -B "$dir" -G Ninja -DSC_WARNINGS_AS_ERRORS=ON "$@"
  cmake --build "$dir" -j "$jobs"
}

echo "== Release build and tests"
build "$root/build" -DCMAKE_BUILD_TYPE=Release
ctest --test-dir "$root/build" -j "$jobs" --output-on-failure --timeout 1200

echo "== AddressSanitizer + UndefinedBehaviorSanitizer build and tests"
build "$root/build-asan" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSC_SANITIZE=ON \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
  -DSC_BUILD_DEMOS=OFF -DSC_BUILD_BENCH=OFF
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir "$root/build-asan" -j "$jobs" --output-on-failure --timeout 1800
echo "== all tests passed"
