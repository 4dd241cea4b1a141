// SPDX-License-Identifier: MIT
// A small OFF reader for the mesh benches (the tests' reader is not theirs to use),
// and the unit-size normalisation the benches share.
#pragma once

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "smartcollision/smartcollision.h"

namespace sc_bench {

#ifdef SC_BENCH_MESH_DIR
inline const char* kMeshDir = SC_BENCH_MESH_DIR;
#else
inline const char* kMeshDir = ".meshes";
#endif

/// The next token of an OFF stream, skipping '#' comments.
inline bool nextToken(std::istream& in, std::string& token) {
  while (in >> token) {
    if (token[0] != '#') return true;
    std::string rest;
    std::getline(in, rest);
  }
  return false;
}

/// Reads <kMeshDir>/<name>.off; polygons are fanned into triangles. Empty on failure
/// (with a message): the caller skips what needs the mesh.
inline sc::MeshData loadOff(const std::string& name) {
  const std::string path = std::string(kMeshDir) + "/" + name + ".off";
  std::ifstream in(path);
  sc::MeshData mesh;
  std::string token;
  long nv = 0, nf = 0, ne = 0;
  try {
    if (!nextToken(in, token) || token != "OFF") throw 0;
    if (!nextToken(in, token)) throw 0;
    nv = std::stol(token);
    if (!nextToken(in, token)) throw 0;
    nf = std::stol(token);
    if (!nextToken(in, token)) throw 0;
    ne = std::stol(token);
    (void)ne;
    for (long i = 0; i < nv; ++i) {
      double c[3];
      for (double& x : c) {
        if (!nextToken(in, token)) throw 0;
        x = std::stod(token);
      }
      mesh.vertices.emplace_back(c[0], c[1], c[2]);
    }
    for (long f = 0; f < nf; ++f) {
      if (!nextToken(in, token)) throw 0;
      const long k = std::stol(token);
      std::vector<int> ids;
      for (long j = 0; j < k; ++j) {
        if (!nextToken(in, token)) throw 0;
        ids.push_back(std::stoi(token));
      }
      // Anything after the indices on the line (colours) is not ours.
      std::string rest;
      std::getline(in, rest);
      for (size_t j = 1; j + 1 < ids.size(); ++j)
        mesh.triangles.emplace_back(ids[0], ids[j], ids[j + 1]);
    }
  } catch (...) {
    std::fprintf(stderr, "bench: cannot read %s (set SC_MESH_DIR, see scripts/extract_meshes.sh)\n",
                 path.c_str());
    return {};
  }
  return mesh;
}

/// Centred on its box and scaled to a largest box side of 1, so tolerances and
/// steps read the same for every mesh.
inline sc::MeshData unitSize(sc::MeshData mesh) {
  sc::Aabb box;
  for (const sc::Vec3& v : mesh.vertices) box.extend(v);
  const sc::Vec3 centre = 0.5 * (box.min + box.max);
  const double scale = 1.0 / (box.max - box.min).maxCoeff();
  for (sc::Vec3& v : mesh.vertices) v = (v - centre) * scale;
  return mesh;
}

}  // namespace sc_bench
