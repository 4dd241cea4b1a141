// SPDX-License-Identifier: MIT
// Mesh import into one sc::MeshData: OFF, PLY, STL and OBJ through the strict readers
// of mesh_formats.h, other formats through assimp (every mesh of the file, node
// transforms applied); coincident positions welded. Used by sc-preprocess and by the
// fuzz target tests/fuzz/fuzz_mesh_import.cpp.
#pragma once

#include <cstddef>
#include <string>

#include "mesh_formats.h"
#include "smartcollision/model.h"

namespace sc::tools {

/// Reads a mesh file; OFF, PLY, STL and OBJ (by the extension, any case) strictly,
/// other formats through assimp. InvalidArgument with a one-line message naming the
/// file when it is not a regular file (a FIFO or device is refused before it is
/// read), cannot be read, is malformed (a count the data does not hold, a number
/// that does not parse or is not finite, an index out of range), or has no triangles.
sc::Result<ImportedMesh> importMeshFile(const std::string& path);

/// The same for a file's bytes in memory, read as `format` only: an extension
/// without the dot ("obj", "stl"); InvalidArgument when there is no such reader.
sc::Result<ImportedMesh> importMeshMemory(const void* data, std::size_t size, const char* format);

}  // namespace sc::tools
