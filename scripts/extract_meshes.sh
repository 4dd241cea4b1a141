#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Extracts the CGAL test meshes (OFF) that the tests use from libcgal-demo's data
# tarball into a directory ($1, default <repo>/.meshes; tests find it through the
# CMake cache variable SC_MESH_DIR). Idempotent: files already present are kept.
# Needs no root; only reads the tarball (SC_CGAL_DATA_TARBALL overrides its path).
set -euo pipefail

repo_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
target_dir="${1:-${repo_dir}/.meshes}"
tarball="${SC_CGAL_DATA_TARBALL:-/usr/share/doc/libcgal-dev/data.tar.gz}"

# The meshes tests/property/decomposition_invariants_test.cpp decomposes, and the
# open meshes (triangle soups) of tests/property/mesh_distance_fcl_test.cpp.
meshes=(bunny00 armadillo fandisk knot1 elephant femur cow camel
        ChineseDragon-10kv lion elephant-with-holes)

if [ ! -r "${tarball}" ]; then
  echo "extract_meshes: ${tarball} not found; install libcgal-demo via scripts/setup.sh" >&2
  exit 1
fi

mkdir -p "${target_dir}"

missing=()
for name in "${meshes[@]}"; do
  [ -s "${target_dir}/${name}.off" ] || missing+=("data/meshes/${name}.off")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "extract_meshes: all ${#meshes[@]} meshes present in ${target_dir}"
  exit 0
fi

# Extract into a scratch directory first, so an interrupted run never leaves a
# truncated mesh that a later run would take as present.
scratch="$(mktemp -d "${target_dir}/.extract.XXXXXX")"
trap 'rm -rf "${scratch}"' EXIT
if ! tar -xzf "${tarball}" -C "${scratch}" "${missing[@]}"; then
  echo "extract_meshes: could not extract ${missing[*]} from ${tarball}" >&2
  exit 1
fi
for member in "${missing[@]}"; do
  mv -f "${scratch}/${member}" "${target_dir}/$(basename "${member}")"
done
echo "extract_meshes: extracted ${#missing[@]} meshes into ${target_dir}"
