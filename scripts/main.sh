#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs what is needed, builds, and runs the main demo: Bullet rigid bodies
# stacked with SmartCollision contacts. With an X display it opens a window;
# without one it runs headless under xvfb-run and writes build/stacking.png and
# build/stacking.json, then prints the metrics.
# Usage: scripts/main.sh [stacking options, e.g. --scene pyramid --model manifold]
#        Without options: 24 non-convex bodies piled into a box at 60 Hz, the rate of
#        most Bullet applications (--scene pile --hz 60).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/setup.sh"
cmake -S "$root" -B "$root/build" -G Ninja -DCMAKE_BUILD_TYPE=Release
targets=(hello_smartcollision stacking)
# The Python package too, when configured (pybind11 found).
if grep -q '^SC_BUILD_PYTHON:BOOL=ON' "$root/build/CMakeCache.txt"; then targets+=(sc_python); fi
cmake --build "$root/build" -j "${SC_JOBS:-$(nproc)}" --target "${targets[@]}"
if [[ $# -eq 0 ]]; then set -- --scene pile --hz 60; fi
"$root/build/demos/hello_smartcollision"
if [[ -n "${DISPLAY:-}" ]]; then
  exec "$root/build/demos/stacking" "$@"
fi
if ! command -v xvfb-run >/dev/null; then
  echo "no DISPLAY and no xvfb-run: running the physics only" >&2
  exec "$root/build/demos/stacking" --headless --seconds 10 --json "$root/build/stacking.json" "$@"
fi
xvfb-run -a "$root/build/demos/stacking" --headless --seconds 10 \
  --png "$root/build/stacking.png" --json "$root/build/stacking.json" "$@" >/dev/null
echo "metrics (build/stacking.json), image build/stacking.png:"
cat "$root/build/stacking.json"
