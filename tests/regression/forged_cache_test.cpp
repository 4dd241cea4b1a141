// SPDX-License-Identifier: MIT
// A cache file's checksum finds damage, not forgery: a file whose hulls were scaled
// x10 and whose checksum was recomputed was trusted, and the pair distances came
// out of the forged hulls. Loading now checks what is cheap to check against the
// input mesh (every hull vertex is the input vertex it names, real faces are input
// triangles covering the surface, every inner hull's box contains its children's):
// such a file is refused with ErrorCode::File (SC_ERROR_FILE), the piece is rebuilt
// as if there were no file, and the file is rewritten.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "preprocess/cache_file.h"
#include "sc.h"
#include "support/sc_results.h"
#include "support/shapes.h"
#include "support/temp_files.h"

namespace sc::test {
namespace {

class ForgedCache : public ::testing::Test {
 protected:
  void SetUp() override {
    std::remove(path_.c_str());
    const Result<PiecePtr> fresh = buildPiece(ModelKind::ClosedPolyhedron, mesh_);
    ASSERT_TRUE(fresh.ok()) << fresh.status().message();
    fresh_ = fresh.value();
    ASSERT_GT(fresh_->internals().patches.size(), 2u) << "the torus should be non-convex";
    key_ = detail::pieceInputHash(ModelKind::ClosedPolyhedron, mesh_);
    valid_ = detail::encodePieceCache(key_, fresh_->internals());
  }
  void TearDown() override { std::remove(path_.c_str()); }

  /// Writes the fresh preprocessing changed by `forge`, re-signed: a file that
  /// passes every header and checksum test.
  void writeForged(const std::function<void(detail::PieceData&)>& forge) {
    detail::PieceData data;
    data.kind = ModelKind::ClosedPolyhedron;
    data.mesh = fresh_->internals().mesh;
    ASSERT_TRUE(detail::decodePieceCache(valid_, key_, data));
    forge(data);
    writeBytes(path_, detail::encodePieceCache(key_, data));
  }

  /// The forged file is refused with File, the piece equals a fresh build, and the
  /// file is rewritten with the valid preprocessing (so the next build loads it).
  void expectRefused() {
    BuildOptions options;
    options.cache_file = path_;
    const Result<PiecePtr> piece = buildPiece(ModelKind::ClosedPolyhedron, mesh_, options);
    ASSERT_TRUE(piece.hasValue());
    EXPECT_EQ(piece.status().code(), ErrorCode::File);
    EXPECT_NE(piece.status().message().find(path_), std::string::npos) << piece.status().message();
    EXPECT_FALSE(piece.value()->stats().from_cache);
    EXPECT_EQ(detail::encodePieceCache(key_, piece.value()->internals()), valid_);
    EXPECT_EQ(readBytes(path_), valid_);
    const Result<PiecePtr> again = buildPiece(ModelKind::ClosedPolyhedron, mesh_, options);
    ASSERT_TRUE(again.ok()) << again.status().message();
    EXPECT_TRUE(again.value()->stats().from_cache);
  }

  MeshData mesh_ = torusMesh(1.0, 0.3, 16, 8);
  std::string path_ = tempPath("sc_forged_cache", "torus.scc");
  PiecePtr fresh_;
  std::uint64_t key_ = 0;
  std::vector<std::uint8_t> valid_;
};

/// Every hull ten times larger: still bounding, no longer the input's.
void scaleHulls(detail::PieceData& data) {
  for (detail::ConvexPolytope& p : data.patches)
    for (Vec3& v : p.vertices) v *= 10.0;
  for (detail::ConvexPolytope& p : data.hierarchy.hulls)
    for (Vec3& v : p.vertices) v *= 10.0;
}

TEST_F(ForgedCache, ScaledHullsWithARecomputedChecksumAreRefused) {
  ASSERT_NO_FATAL_FAILURE(writeForged(scaleHulls));
  ASSERT_NO_FATAL_FAILURE(expectRefused());
}

TEST_F(ForgedCache, OneMovedHullVertexIsRefused) {
  ASSERT_NO_FATAL_FAILURE(writeForged(
      [](detail::PieceData& data) { data.patches[1].vertices[0] += Vec3(0, 0, 1e-9); }));
  ASSERT_NO_FATAL_FAILURE(expectRefused());
}

TEST_F(ForgedCache, AnInnerHullNotContainingItsChildrenIsRefused) {
  // The root's hull replaced by one leaf patch: every vertex is a real input
  // vertex, but the root no longer bounds the piece, so traversals would cull.
  ASSERT_NO_FATAL_FAILURE(writeForged([](detail::PieceData& data) {
    const int root = data.hierarchy.nodes[0].polytope;
    data.hierarchy.hulls[static_cast<std::size_t>(root)] = data.patches[0];
  }));
  ASSERT_NO_FATAL_FAILURE(expectRefused());
}

TEST_F(ForgedCache, AFaceNamingAnotherTriangleIsRefused) {
  ASSERT_NO_FATAL_FAILURE(writeForged([](detail::PieceData& data) {
    for (int& source : data.patches[0].face_source) {
      if (source >= 0) {
        source = (source + 1) % static_cast<int>(data.mesh.triangles.size());
        break;
      }
    }
  }));
  ASSERT_NO_FATAL_FAILURE(expectRefused());
}

TEST_F(ForgedCache, ThroughScApiTheForgedFileGivesScErrorFileAndTheRightDistance) {
  ASSERT_NO_FATAL_FAILURE(writeForged(scaleHulls));
  SCObject torus(SC_OBJECT_TYPE_CLOSED_POLYHEDRON), probe(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  EXPECT_EQ(addPiece(torus, mesh_, path_.c_str()), SC_ERROR_FILE);
  ASSERT_EQ(addPiece(probe, boxMesh(Vec3(0.5, 0.5, 0.5))), SC_NO_ERROR);
  // The torus (outer radius 1.3) in the static group, the box 3 units from its axis.
  const double at[3] = {4.8, 0, 0};
  ASSERT_EQ(probe.SetTransformation(SC_POSITION_ORIGIN, at), SC_NO_ERROR);
  PairScene scene(probe, torus);
  // The torus's outermost vertices lie at 1.3 on the x axis: the box's face at 4.3.
  EXPECT_NEAR(scene.distance(), 3.0, 1e-9);
}

}  // namespace
}  // namespace sc::test
