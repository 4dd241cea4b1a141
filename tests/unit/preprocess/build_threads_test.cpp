// SPDX-License-Identifier: MIT
// BuildOptions::threads: a piece built on one thread and on two is the same piece
// (the same cache file, byte for byte, and the same distances), for a closed mesh
// large enough to be decomposed in two regions and for a soup; bad counts are
// refused.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "sc_support/sample_meshes.h"
#include "smartcollision/collision.h"
#include "support/temp_files.h"
#include "support/test_support.h"

namespace sc {
namespace {

/// Builds `mesh` on `threads` threads, writing its cache file; returns the piece
/// and the file's bytes.
PiecePtr buildWith(ModelKind kind, const MeshData& mesh, int threads, std::string& bytes) {
  BuildOptions options;
  options.threads = threads;
  options.cache_file = test::tempPath("sc_threads_test", std::to_string(threads) + ".bvh");
  std::remove(options.cache_file.c_str());
  const Result<PiecePtr> built = buildPiece(kind, mesh, options);
  bytes = test::readBytes<std::string>(options.cache_file);
  std::remove(options.cache_file.c_str());
  EXPECT_TRUE(built.ok()) << built.status().message();
  EXPECT_FALSE(built.value()->stats().from_cache);
  return built.value();
}

/// Distance from `target` at random poses around `opponent`, through PairTracker.
std::vector<double> distances(const PiecePtr& target, const PiecePtr& opponent) {
  const Model model_a(target->kind(), {target});
  const Model model_b(opponent->kind(), {opponent});
  const Part part_a{&model_a, Rigid(), 1};
  const Part part_b{&model_b, Rigid(), 2};
  test::Rng rng(5);
  PairTracker tracker;
  std::vector<double> out;
  for (int pose = 0; pose < 40; ++pose) {
    GroupView a{&part_a, 1, Placement()};
    a.placement.orientation = test::randomRotation(rng);
    a.placement.world_center = test::uniform(rng, 2.9, 4.0) * test::randomDirection(rng);
    const GroupView b{&part_b, 1, Placement()};
    DirectedResult result[2];
    tracker.forget(0);
    tracker.update(a, b, Directions{true, false}, SceneSettings(), result);
    EXPECT_EQ(result[0].code, ErrorCode::Ok);
    out.push_back(result[0].distance);
  }
  return out;
}

void expectSamePiece(ModelKind kind, const MeshData& mesh) {
  std::string one, two;
  const PiecePtr a = buildWith(kind, mesh, 1, one);
  const PiecePtr b = buildWith(kind, mesh, 2, two);
  ASSERT_FALSE(one.empty());
  EXPECT_TRUE(one == two) << "cache files differ: " << one.size() << " and " << two.size()
                          << " bytes";
  EXPECT_EQ(a->stats().patches, b->stats().patches);
  const std::vector<double> da = distances(a, a), db = distances(b, a);
  for (std::size_t i = 0; i < da.size(); ++i) {
    EXPECT_NEAR(da[i], db[i], 1e-12 * da[i]) << "pose " << i;
  }
}

TEST(BuildThreads, ClosedMeshOfSeveralRegionsIsTheSameOnOneAndTwoThreads) {
  // 10,000 triangles: more than one region of the decomposition.
  const MeshData torus = samples::torusMesh(1.0, 0.3, 100, 50);
  expectSamePiece(ModelKind::ClosedPolyhedron, torus);
}

TEST(BuildThreads, SoupIsTheSameOnOneAndTwoThreads) {
  const MeshData torus = samples::torusMesh(1.0, 0.3, 60, 40);
  expectSamePiece(ModelKind::TriangleSoup, torus);
}

TEST(BuildThreads, CountOutsideTheRangeIsRefused) {
  for (const int threads : {-1, kMaxBuildThreads + 1}) {
    BuildOptions options;
    options.threads = threads;
    const Result<PiecePtr> built =
        buildPiece(ModelKind::ClosedPolyhedron, samples::torusMesh(1.0, 0.3, 8, 6), options);
    ASSERT_FALSE(built.hasValue());
    EXPECT_EQ(built.status().code(), ErrorCode::InvalidArgument);
  }
}

}  // namespace
}  // namespace sc
