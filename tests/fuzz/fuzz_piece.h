// SPDX-License-Identifier: MIT
// Shared by the fuzz targets that build pieces from parsed meshes (OFF, OBJ, STL):
// what a mesh reader may hand over, and what buildPiece may make of it.
#pragma once

#include <cstddef>

#include "fuzz_common.h"
#include "smartcollision/model.h"

namespace sc::fuzz {

/// Preprocessing is superlinear in the worst case; bigger meshes only cost time.
constexpr std::size_t kMaxPieceTriangles = 512;

/// Finite vertices, every index in range.
inline void checkMesh(const MeshData& m, const char* reader) {
  for (const Vec3& v : m.vertices) requireFinite(v.data(), 3, reader);
  for (const Tri& t : m.triangles)
    for (int i = 0; i < 3; ++i)
      if (t[i] < 0 || static_cast<std::size_t>(t[i]) >= m.vertices.size())
        fail("mesh index out of range accepted", t[i]);
}

/// Only InvalidArgument or InvalidGeometry may refuse a mesh; an accepted piece
/// keeps every triangle and has finite bounds.
inline void checkPiece(const Result<PiecePtr>& piece, const MeshData& mesh) {
  if (!piece.hasValue()) {
    const ErrorCode code = piece.status().code();
    if (code != ErrorCode::InvalidArgument && code != ErrorCode::InvalidGeometry)
      fail("buildPiece failed with an undocumented code", static_cast<int>(code));
    return;
  }
  const Piece& p = *piece.value();
  if (p.mesh().triangles.size() != mesh.triangles.size()) fail("piece lost triangles");
  const Aabb& b = p.bounds();
  const double corners[6] = {b.min.x(), b.min.y(), b.min.z(), b.max.x(), b.max.y(), b.max.z()};
  if (!mesh.triangles.empty()) requireFinite(corners, 6, "piece bounds not finite");
  if (p.stats().patches < 0 || p.stats().tree_depth < 0) fail("negative statistics");
}

/// Both model kinds, for a mesh small enough.
inline void checkBothKinds(const MeshData& m) {
  if (m.triangles.size() > kMaxPieceTriangles) return;
  checkPiece(buildPiece(ModelKind::ClosedPolyhedron, m), m);
  checkPiece(buildPiece(ModelKind::TriangleSoup, m), m);
}

}  // namespace sc::fuzz
