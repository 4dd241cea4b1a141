// SPDX-License-Identifier: MIT
// Unit tests of buildPiece: a convex closed piece becomes one patch that keeps the
// input's indices; inside-out pieces are stored flipped; soups take anything
// finite; errors give no piece.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "preprocess/cache_file.h"
#include "preprocess/piece_data.h"
#include "query/features.h"
#include "smartcollision/model.h"
#include "support/test_support.h"

namespace sc {
namespace {

/// Unit cube [0,1]^3, outward, with an unused vertex first so that the patch's
/// compacted indices differ from the input's.
MeshData cubeWithUnusedVertex() {
  MeshData m;
  m.vertices.emplace_back(50, -20, 9);  // unused: must not reach bounds or the patch
  for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  // Input vertex 1 + (x + 2y + 4z); two triangles per face, counter-clockwise outside.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.emplace_back(1 + q[0], 1 + q[1], 1 + q[2]);
    m.triangles.emplace_back(1 + q[0], 1 + q[2], 1 + q[3]);
  }
  return m;
}

MeshData tetrahedron() {
  return {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 2, 1}, {1, 3, 0}, {0, 3, 2}, {1, 2, 3}}};
}

const detail::PieceData& data(const PiecePtr& piece) { return piece->internals(); }

TEST(BuildPiece, ConvexPieceIsOnePatchWithOriginalIndices) {
  const MeshData input = cubeWithUnusedVertex();
  const Result<PiecePtr> result = buildPiece(ModelKind::ClosedPolyhedron, input);
  ASSERT_TRUE(result.ok()) << result.status().message();
  const PiecePtr& piece = result.value();
  ASSERT_EQ(data(piece).patches.size(), 1u);
  const detail::ConvexPolytope& patch = data(piece).patches[0];

  ASSERT_EQ(patch.vertices.size(), 8u);
  ASSERT_EQ(patch.original.size(), 8u);
  for (std::size_t i = 0; i < patch.vertices.size(); ++i) {
    EXPECT_EQ(patch.original[i], static_cast<int>(i) + 1);
    EXPECT_EQ(patch.vertices[i], input.vertices[patch.original[i]]);
  }
  ASSERT_EQ(patch.faces.size(), input.triangles.size());
  ASSERT_EQ(patch.face_source.size(), input.triangles.size());
  for (std::size_t f = 0; f < patch.faces.size(); ++f) {
    EXPECT_EQ(patch.face_source[f], static_cast<int>(f));
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(patch.original[patch.faces[f][k]], input.triangles[f][k]) << "face " << f;
    }
  }
  // finalize() ran: every vertex of a cube has 3 to 6 neighbours.
  ASSERT_EQ(patch.adjacency_start.size(), 9u);
  for (int v = 0; v < 8; ++v) {
    const int degree = patch.adjacency_start[v + 1] - patch.adjacency_start[v];
    EXPECT_GE(degree, 3);
    EXPECT_LE(degree, 6);
  }
  EXPECT_VEC_NEAR(patch.bounds().min, Vec3::Zero(), 0.0);
  EXPECT_VEC_NEAR(patch.bounds().max, Vec3::Ones(), 0.0);

  EXPECT_VEC_NEAR(piece->bounds().min, Vec3::Zero(), 0.0);
  EXPECT_VEC_NEAR(piece->bounds().max, Vec3::Ones(), 0.0);
  EXPECT_EQ(piece->kind(), ModelKind::ClosedPolyhedron);
  EXPECT_EQ(piece->mesh().vertices, input.vertices);
  EXPECT_EQ(piece->mesh().triangles, input.triangles);

  const PieceStats& stats = piece->stats();
  EXPECT_EQ(stats.vertices, 9);
  EXPECT_EQ(stats.triangles, 12);
  EXPECT_FALSE(stats.flipped);
  EXPECT_TRUE(stats.convex);
  EXPECT_EQ(stats.patches, 1);
  EXPECT_EQ(stats.virtual_faces, 0);
  EXPECT_EQ(stats.hull_vertices, 8);
  EXPECT_FALSE(stats.from_cache);
  EXPECT_GE(stats.seconds, 0.0);
  EXPECT_LT(stats.seconds, 10.0);
}

TEST(BuildPiece, InsideOutPieceIsStoredFlipped) {
  MeshData inside_out = tetrahedron();
  for (Tri& t : inside_out.triangles) std::swap(t[0], t[1]);
  const Result<PiecePtr> result = buildPiece(ModelKind::ClosedPolyhedron, inside_out);
  ASSERT_TRUE(result.ok()) << result.status().message();
  const PiecePtr& piece = result.value();
  EXPECT_TRUE(piece->stats().flipped);
  EXPECT_TRUE(piece->stats().convex);
  // Every stored triangle and patch face now faces away from the centroid.
  const Vec3 centroid = Vec3::Constant(0.25);
  const auto outward = [&](const auto& p, const Tri& t) {
    const Vec3 n = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
    return n.dot(p[t[0]] - centroid) > 0.0;
  };
  for (const Tri& t : piece->mesh().triangles) EXPECT_TRUE(outward(piece->mesh().vertices, t));
  const detail::ConvexPolytope& patch = data(piece).patches.at(0);
  for (const Tri& f : patch.faces) EXPECT_TRUE(outward(patch.vertices, f));

  const Result<PiecePtr> upright = buildPiece(ModelKind::ClosedPolyhedron, tetrahedron());
  ASSERT_TRUE(upright.ok());
  EXPECT_FALSE(upright.value()->stats().flipped);
}

TEST(BuildPiece, ProgressIsReportedFromZeroToOne) {
  std::vector<double> fractions;
  BuildOptions options;
  options.progress = [&](double fraction, const char* stage) {
    EXPECT_NE(stage, nullptr);
    fractions.push_back(fraction);
  };
  ASSERT_TRUE(buildPiece(ModelKind::ClosedPolyhedron, tetrahedron(), options).ok());
  ASSERT_GE(fractions.size(), 2u);
  EXPECT_EQ(fractions.front(), 0.0);
  EXPECT_EQ(fractions.back(), 1.0);
  ASSERT_TRUE(buildPiece(ModelKind::TriangleSoup, tetrahedron()).ok());  // no callback: fine
}

// Soup leaves keep no vertex-face lists: the readers' scan of their two faces
// finds the same features (every seed, every point near the triangle) as the
// lists would; built and loaded alike.
TEST(BuildPiece, SoupLeavesWithoutVertexFaceListsGiveTheSameFeatures) {
  test::Rng rng(21);
  MeshData soup;
  for (int t = 0; t < 40; ++t) {
    const Vec3 c = test::randomDirection(rng);
    for (int k = 0; k < 3; ++k) soup.vertices.push_back(c + 0.3 * test::randomDirection(rng));
    soup.triangles.emplace_back(3 * t, 3 * t + 1, 3 * t + 2);
  }
  const Result<PiecePtr> piece = buildPiece(ModelKind::TriangleSoup, soup);
  ASSERT_TRUE(piece.ok());
  const detail::PieceData& built = piece.value()->internals();
  detail::PieceData loaded;
  loaded.kind = built.kind;
  loaded.mesh = built.mesh;
  ASSERT_TRUE(detail::decodePieceCache(detail::encodePieceCache(3, built), 3, loaded));
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    const detail::ConvexPolytope& leaf = built.patches[t];
    EXPECT_TRUE(leaf.vertex_face_start.empty() && leaf.vertex_faces.empty());
    EXPECT_TRUE(loaded.patches[t].vertex_face_start.empty());
    const detail::ConvexPolytope listed = detail::ConvexPolytope::build(leaf.parts());
    ASSERT_EQ(listed.vertex_face_start.size(), 4u);
    const double tolerance = detail::featureTolerance(leaf);
    for (int k = 0; k < 30; ++k) {
      // Points on the triangle, its edges and corners, and off it.
      Vec3 w(test::uniform(rng, 0, 1), test::uniform(rng, 0, 1), test::uniform(rng, 0, 1));
      if (k % 3 == 0) w[k % 2] = 0.0;
      if (k % 5 == 0) w = Vec3::Unit(k % 3);
      const Vec3 p =
          (w[0] * leaf.vertices[0] + w[1] * leaf.vertices[1] + w[2] * leaf.vertices[2]) / w.sum() +
          (k % 4 == 0 ? Vec3(0.01 * test::randomDirection(rng)) : Vec3::Zero());
      const int seeds[3] = {k % 3, (k + 1) % 3, (k + 2) % 3};
      const int count = 1 + k % 3;
      const Feature a = detail::closestFeature(leaf, p, seeds, count, tolerance);
      const Feature b = detail::closestFeature(listed, p, seeds, count, tolerance);
      EXPECT_EQ(a.type, b.type);
      EXPECT_EQ(a.is_virtual, b.is_virtual);
      for (int i = 0; i < 3; ++i) EXPECT_EQ(a.vertices[i], b.vertices[i]);
    }
  }
}

TEST(BuildPiece, SoupAcceptsDegenerateAndOpenTriangles) {
  MeshData soup;
  soup.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {-7, 3, 3}};
  soup.triangles = {{0, 1, 2}, {0, 0, 0}, {1, 1, 3}, {0, 1, 3}, {0, 1, 3}};  // collinear, point, ...
  const Result<PiecePtr> result = buildPiece(ModelKind::TriangleSoup, soup);
  ASSERT_TRUE(result.ok()) << result.status().message();
  const PiecePtr& piece = result.value();
  EXPECT_EQ(piece->kind(), ModelKind::TriangleSoup);
  EXPECT_EQ(piece->mesh().triangles, soup.triangles);
  EXPECT_EQ(piece->stats().patches, 5);
  EXPECT_EQ(piece->stats().triangles, 5);
  EXPECT_EQ(piece->stats().vertices, 5);
  EXPECT_FALSE(piece->stats().convex);
  EXPECT_FALSE(piece->stats().flipped);
  // One two-sided leaf per triangle, degenerate ones included.
  ASSERT_EQ(data(piece).patches.size(), 5u);
  for (size_t t = 0; t < soup.triangles.size(); ++t) {
    const auto& leaf = data(piece).patches[t];
    EXPECT_EQ(leaf.faces.size(), 2u);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(leaf.original[k], soup.triangles[t][k]);
  }
  EXPECT_VEC_NEAR(piece->bounds().min, Vec3(0, 0, 0), 0.0);  // vertex 4 is unused
  EXPECT_VEC_NEAR(piece->bounds().max, Vec3(2, 1, 0), 0.0);
}

TEST(BuildPiece, SoupIsNotFlippedOrValidatedAsClosed) {
  MeshData inside_out = tetrahedron();
  for (Tri& t : inside_out.triangles) std::swap(t[1], t[2]);
  const Result<PiecePtr> result = buildPiece(ModelKind::TriangleSoup, inside_out);
  ASSERT_TRUE(result.ok());
  EXPECT_FALSE(result.value()->stats().flipped);
  EXPECT_EQ(result.value()->mesh().triangles, inside_out.triangles);
}

TEST(BuildPiece, ClosedRuleBreakGivesInvalidGeometryAndNoPiece) {
  MeshData open = tetrahedron();
  open.triangles.pop_back();
  const Result<PiecePtr> result = buildPiece(ModelKind::ClosedPolyhedron, open);
  EXPECT_EQ(result.status().code(), ErrorCode::InvalidGeometry);
  EXPECT_FALSE(result.hasValue());
  EXPECT_FALSE(result.ok());
  EXPECT_EQ(result.value(), nullptr);
  EXPECT_FALSE(result.status().message().empty());
}

TEST(BuildPiece, BadArraysGiveInvalidArgumentAndNoPiece) {
  for (const ModelKind kind : {ModelKind::ClosedPolyhedron, ModelKind::TriangleSoup}) {
    MeshData nan = tetrahedron();
    nan.vertices[1].x() = std::numeric_limits<double>::quiet_NaN();
    MeshData inf = tetrahedron();
    inf.vertices[0].y() = -kInfinity;
    MeshData out_of_range = tetrahedron();
    out_of_range.triangles[2][1] = 4;
    MeshData negative = tetrahedron();
    negative.triangles[0][0] = -3;
    MeshData empty = tetrahedron();
    empty.triangles.clear();
    for (const MeshData& bad : {nan, inf, out_of_range, negative, empty}) {
      const Result<PiecePtr> result = buildPiece(kind, bad);
      EXPECT_EQ(result.status().code(), ErrorCode::InvalidArgument) << result.status().message();
      EXPECT_FALSE(result.hasValue());
      EXPECT_EQ(result.value(), nullptr);
    }
  }
}

TEST(BuildPiece, NonConvexPieceIsDecomposed) {
  // An L of three unit cubes, 2 triangles per boundary square.
  MeshData m;
  const std::vector<Vec3> corners = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  // Extrude the L outline (counter-clockwise seen from +z) to z in [0, 1].
  for (const Vec3& c : corners) m.vertices.push_back(c);
  for (const Vec3& c : corners) m.vertices.push_back(c + Vec3::UnitZ());
  const int n = 6;
  // Bottom and top: the L split at the reflex corner 3 into two convex quads.
  m.triangles = {{0, 3, 1}, {1, 3, 2}, {0, 5, 3}, {3, 5, 4}};
  for (int i = 0; i < 4; ++i) {
    const Tri& b = m.triangles[i];
    m.triangles.emplace_back(b[0] + n, b[2] + n, b[1] + n);
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.emplace_back(i, j, j + n);
    m.triangles.emplace_back(i, j + n, i + n);
  }
  const Result<PiecePtr> result = buildPiece(ModelKind::ClosedPolyhedron, m);
  ASSERT_TRUE(result.ok()) << result.status().message();
  const PieceStats& stats = result.value()->stats();
  EXPECT_FALSE(stats.convex);
  EXPECT_FALSE(stats.flipped);
  EXPECT_GE(stats.patches, 2);
  EXPECT_EQ(stats.patches, static_cast<int>(data(result.value()).patches.size()));
  int hull_vertices = 0;
  for (const auto& patch : data(result.value()).patches) hull_vertices += static_cast<int>(patch.vertices.size());
  EXPECT_EQ(stats.hull_vertices, hull_vertices);
  EXPECT_VEC_NEAR(result.value()->bounds().max, Vec3(2, 2, 1), 0.0);
}

}  // namespace
}  // namespace sc
