// SPDX-License-Identifier: MIT
#include "support/meshes.h"

#include <gtest/gtest.h>

#include <fstream>

#include "sc_support/off_mesh.h"

#ifndef SC_MESH_DIR
#error "SC_MESH_DIR must be defined by tests/CMakeLists.txt"
#endif

namespace sc::test {

std::string testMeshPath(const std::string& name) {
  return std::string(SC_MESH_DIR) + "/" + name + ".off";
}

MeshData loadTestMesh(const std::string& name) {
  const std::string path = testMeshPath(name);
  if (!std::ifstream(path).good()) {
    // FAIL() needs a void function; the lambda makes this a fatal failure.
    [&] {
      FAIL() << "test mesh " << path << " is missing: install libcgal-demo with "
             << "scripts/setup.sh, then run scripts/extract_meshes.sh (or configure "
             << "with -DSC_MESH_DIR=<dir holding the CGAL data/meshes/*.off files>)";
    }();
    return {};
  }
  Result<MeshData> mesh = support::readOff(path);
  if (!mesh.ok()) {
    [&] { FAIL() << "cannot load test mesh " << path << ": " << mesh.status().message(); }();
    return {};
  }
  return std::move(mesh.value());
}

}  // namespace sc::test
