#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs every Debian 12 package SmartCollision needs to build, test, run
# its demos and benchmarks, then extracts the CGAL test meshes into .meshes/. Non-interactive and idempotent: packages already
# present are left alone, and `apt-get update` runs only when something is
# missing. Needs root (or sudo).
set -euo pipefail

packages=(
  build-essential cmake pkg-config ninja-build git
  libeigen3-dev libccd-dev libbullet-dev libbullet-extras-dev
  libgtest-dev libgmock-dev libbenchmark-dev libfcl-dev
  freeglut3-dev libgl-dev libglu1-mesa-dev libpng-dev libspnav-dev
  libassimp-dev libqhull-dev
  xvfb xauth
  libcgal-demo
  clang libclang-rt-14-dev
  gnuplot-nox
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed"; then
    missing+=("$p")
  fi
done

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  "$root/scripts/extract_meshes.sh" "$root/.meshes"
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: run as root (missing: ${missing[*]})" >&2; exit 1; }
  sudo_cmd=(sudo)
fi

echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q </dev/null
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}" </dev/null
"$root/scripts/extract_meshes.sh" "$root/.meshes"
