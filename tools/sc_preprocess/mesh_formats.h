// SPDX-License-Identifier: MIT
// Strict readers of the simple mesh formats (OFF, PLY ASCII and binary, STL ASCII
// and binary, OBJ), used by the mesh import instead of assimp: every count is
// bounded by the bytes present, every number must parse whole and be finite, every
// index must name a vertex, and a file that ends early is refused. assimp's readers
// clamp bad indices, read "nan" as 0 and abort or spin on some truncated files.
#pragma once

#include <cstddef>
#include <string>

#include "smartcollision/model.h"

namespace sc::tools {

struct ImportedMesh {
  sc::MeshData mesh;
  int skipped = 0;  ///< points and lines, which a piece cannot hold
};

/// True when `extension` (lower case, without the dot) has a strict reader here.
bool hasStrictReader(const std::string& extension);

/// Reads `size` bytes as the format of `extension` (hasStrictReader must hold):
/// polygons fanned into triangles, equal positions welded, unreferenced vertices
/// dropped. InvalidArgument with a one-line message naming `source` and the problem.
sc::Result<ImportedMesh> parseStrict(const char* data, std::size_t size,
                                     const std::string& extension, const std::string& source);

}  // namespace sc::tools
