// SPDX-License-Identifier: MIT
// Mesh import through assimp (OFF, OBJ, STL, PLY, ...) into one sc::MeshData: every
// mesh of the file, node transforms applied, coincident positions welded. Used by
// sc-preprocess and by the fuzz target tests/fuzz/fuzz_mesh_import.cpp.
#pragma once

#include <cstddef>
#include <string>

#include "smartcollision/model.h"

namespace sc::tools {

struct ImportedMesh {
  sc::MeshData mesh;
  int skipped = 0;  ///< points and lines, which a piece cannot hold
};

/// Reads a mesh file; the format follows from its contents and extension.
/// InvalidArgument with a message naming the file when assimp cannot read it, when
/// the result is inconsistent (an index or mesh reference out of range), a position
/// is not finite, or there are no triangles.
sc::Result<ImportedMesh> importMeshFile(const std::string& path);

/// The same for a file's bytes in memory, read as `format` only: an extension
/// without the dot ("obj", "stl"); InvalidArgument when assimp has no such reader.
sc::Result<ImportedMesh> importMeshMemory(const void* data, std::size_t size,
                                          const char* format);

}  // namespace sc::tools
