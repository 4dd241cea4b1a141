// SPDX-License-Identifier: MIT
// Fuzzes the OFF reader of tests/support (parseOff) and hands every mesh it
// accepts to buildPiece, as a closed polyhedron and as a triangle soup.
#include <cmath>
#include <cstdint>
#include <string>

#include "fuzz_common.h"
#include "smartcollision/model.h"
#include "support/off_reader.h"

namespace {

/// Preprocessing is superlinear in the worst case; bigger meshes only cost time.
constexpr std::size_t kMaxTriangles = 512;

void checkPiece(const sc::Result<sc::PiecePtr>& piece, const sc::MeshData& mesh) {
  if (!piece.hasValue()) {
    const sc::ErrorCode code = piece.status().code();
    if (code != sc::ErrorCode::InvalidArgument && code != sc::ErrorCode::InvalidGeometry)
      sc::fuzz::fail("buildPiece failed with an undocumented code", static_cast<int>(code));
    return;
  }
  const sc::Piece& p = *piece.value();
  if (p.mesh().triangles.size() != mesh.triangles.size())
    sc::fuzz::fail("piece lost triangles");
  const sc::Aabb& b = p.bounds();
  const double corners[6] = {b.min.x(), b.min.y(), b.min.z(), b.max.x(), b.max.y(), b.max.z()};
  if (!mesh.triangles.empty()) sc::fuzz::requireFinite(corners, 6, "piece bounds not finite");
  if (p.stats().patches < 0 || p.stats().tree_depth < 0) sc::fuzz::fail("negative statistics");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  sc::Result<sc::MeshData> mesh = sc::test::parseOff(text);
  if (!mesh.hasValue()) {
    if (mesh.status().code() != sc::ErrorCode::InvalidArgument)
      sc::fuzz::fail("parseOff failed with a code other than InvalidArgument");
    return 0;
  }
  const sc::MeshData& m = mesh.value();
  for (const sc::Vec3& v : m.vertices) sc::fuzz::requireFinite(v.data(), 3, "OFF vertex not finite");
  for (const sc::Tri& t : m.triangles)
    for (int i = 0; i < 3; ++i)
      if (t[i] < 0 || static_cast<std::size_t>(t[i]) >= m.vertices.size())
        sc::fuzz::fail("OFF index out of range accepted", t[i]);
  if (m.triangles.size() > kMaxTriangles) return 0;
  checkPiece(sc::buildPiece(sc::ModelKind::ClosedPolyhedron, m), m);
  checkPiece(sc::buildPiece(sc::ModelKind::TriangleSoup, m), m);
  return 0;
}
