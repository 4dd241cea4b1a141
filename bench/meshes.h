// SPDX-License-Identifier: MIT
// Where the mesh benches find CGAL's meshes (reading and scaling: sc_support).
#pragma once

#include <cstdio>
#include <string>

#include "sc_support/off_mesh.h"

namespace sc_bench {

#ifdef SC_BENCH_MESH_DIR
inline const char* kMeshDir = SC_BENCH_MESH_DIR;
#else
inline const char* kMeshDir = ".meshes";
#endif

/// <kMeshDir>/<name>.off; empty when it cannot be read (with the reason and the hint
/// on stderr): the caller skips what needs the mesh.
inline sc::MeshData loadOff(const std::string& name) {
  sc::MeshData mesh = sc::support::readOffOrEmpty(std::string(kMeshDir) + "/" + name + ".off");
  if (mesh.vertices.empty())
    std::fprintf(stderr, "bench: set SC_MESH_DIR, see scripts/extract_meshes.sh\n");
  return mesh;
}

}  // namespace sc_bench
