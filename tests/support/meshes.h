// SPDX-License-Identifier: MIT
// The CGAL sample meshes the tests use, found through SC_MESH_DIR (filled by
// scripts/extract_meshes.sh).
#pragma once

#include <string>

#include "smartcollision/model.h"

namespace sc::test {

/// Path of ${SC_MESH_DIR}/<name>.off.
std::string testMeshPath(const std::string& name);

/// Reads ${SC_MESH_DIR}/<name>.off. When it is missing or unreadable, records a
/// fatal test failure naming scripts/setup.sh and scripts/extract_meshes.sh and
/// returns an empty mesh: call as `ASSERT_NO_FATAL_FAILURE(mesh = loadTestMesh(..))`
/// or check `mesh.triangles.empty()`.
MeshData loadTestMesh(const std::string& name);

}  // namespace sc::test
