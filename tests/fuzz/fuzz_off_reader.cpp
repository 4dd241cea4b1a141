// SPDX-License-Identifier: MIT
// Fuzzes the OFF reader of support/ (parseOff) and hands every mesh it
// accepts to buildPiece, as a closed polyhedron and as a triangle soup.
#include <cstdint>
#include <string>

#include "fuzz_piece.h"
#include "sc_support/off_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  sc::Result<sc::MeshData> mesh = sc::support::parseOff(text);
  if (!mesh.hasValue()) {
    if (mesh.status().code() != sc::ErrorCode::InvalidArgument)
      sc::fuzz::fail("parseOff failed with a code other than InvalidArgument");
    return 0;
  }
  sc::fuzz::checkMesh(mesh.value(), "OFF vertex not finite");
  sc::fuzz::checkBothKinds(mesh.value());
  return 0;
}
