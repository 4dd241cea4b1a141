// SPDX-License-Identifier: MIT
// Fuzzes the mesh import of sc-preprocess (tools/sc_preprocess/mesh_import.h, the
// strict readers of mesh_formats.h): the first byte modulo 4 picks the format (0 OBJ,
// 1 STL ASCII or binary, 2 OFF, 3 PLY ASCII or binary), the rest is the file. Every
// mesh it accepts goes to buildPiece as a closed polyhedron and as a triangle soup.
// Built only when assimp is found.
#include <cstdint>

#include "fuzz_piece.h"
#include "mesh_import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const kFormats[4] = {"obj", "stl", "off", "ply"};
  const char* format = kFormats[data[0] % 4];
  sc::Result<sc::tools::ImportedMesh> imported =
      sc::tools::importMeshMemory(data + 1, size - 1, format);
  if (!imported.hasValue()) {
    if (imported.status().code() != sc::ErrorCode::InvalidArgument ||
        imported.status().message().empty())
      sc::fuzz::fail("mesh import refused a file without InvalidArgument and a message");
    return 0;
  }
  const sc::MeshData& mesh = imported.value().mesh;
  if (mesh.triangles.empty()) sc::fuzz::fail("mesh import accepted a file without triangles");
  sc::fuzz::checkMesh(mesh, "imported vertex not finite");
  sc::fuzz::checkBothKinds(mesh);
  return 0;
}
