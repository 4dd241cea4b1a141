// SPDX-License-Identifier: MIT
// Cancelling buildPiece: the build stops where it is asked to, fails without a
// piece, and leaves the cache file as it was (absent or untouched).
#include <gtest/gtest.h>

#include <dirent.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "sc_support/sample_meshes.h"
#include "smartcollision/model.h"
#include "support/temp_files.h"

namespace sc {
namespace {

using test::readBytes;
using test::TempFile;

bool exists(const std::string& path) { return std::ifstream(path).good(); }

/// Files beside `path` whose names start with its name and are not it: temporaries
/// of a cache file write (path + ".tmp...").
std::vector<std::string> leftovers(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  const std::string dir = path.substr(0, slash), name = path.substr(slash + 1);
  std::vector<std::string> found;
  DIR* d = ::opendir(dir.c_str());
  if (d == nullptr) return found;
  while (const dirent* entry = ::readdir(d)) {
    const std::string other = entry->d_name;
    if (other != name && other.compare(0, name.size(), name) == 0) found.push_back(other);
  }
  ::closedir(d);
  return found;
}

/// Non-convex: decomposed into some forty patches.
MeshData torus() { return samples::torusMesh(1.0, 0.3, 40, 20); }

/// Options that cancel once the progress passes `at`; `highest` records the
/// furthest progress reported.
BuildOptions cancelAt(double at, const std::string& cache, double& highest) {
  BuildOptions options;
  options.cache_file = cache;
  auto stop = std::make_shared<bool>(false);
  options.progress = [stop, at, &highest](double fraction, const char*) {
    highest = std::max(highest, fraction);
    if (fraction >= at) *stop = true;
  };
  options.cancel = [stop] { return *stop; };
  return options;
}

TEST(BuildCancel, UncancelledBuildWritesTheCacheFile) {
  const TempFile file("sc_cancel_test", "whole.bvh");
  double highest = 0.0;
  const Result<PiecePtr> built =
      buildPiece(ModelKind::ClosedPolyhedron, torus(), cancelAt(2.0, file.path, highest));
  ASSERT_TRUE(built.ok()) << built.status().message();
  EXPECT_GT(built.value()->stats().patches, 1);
  EXPECT_EQ(highest, 1.0);
  EXPECT_TRUE(exists(file.path));
  EXPECT_TRUE(leftovers(file.path).empty());
}

/// Builds `mesh` with `options` (made by cancelAt) and expects it cancelled: no piece,
/// InvalidOperation, and neither the cache file nor a temporary of it written.
void expectCancelled(ModelKind kind, const MeshData& mesh, const BuildOptions& options) {
  const Result<PiecePtr> built = buildPiece(kind, mesh, options);
  ASSERT_FALSE(built.hasValue());
  EXPECT_EQ(built.status().code(), ErrorCode::InvalidOperation);
  EXPECT_FALSE(exists(options.cache_file));
  EXPECT_TRUE(leftovers(options.cache_file).empty());
}

TEST(BuildCancel, CancelDuringTheDecompositionStopsThereAndWritesNothing) {
  const TempFile file("sc_cancel_test", "mid.bvh");
  double highest = 0.0;
  expectCancelled(ModelKind::ClosedPolyhedron, torus(), cancelAt(0.3, file.path, highest));
  // The decomposition maps to [0.05, 0.85] of the whole: it stopped before its end.
  EXPECT_GE(highest, 0.3);
  EXPECT_LT(highest, 0.85);
}

TEST(BuildCancel, CancelOnTwoThreadsStopsTheWorkersAndWritesNothing) {
  const TempFile file("sc_cancel_test", "threads.bvh");
  double highest = 0.0;
  BuildOptions options = cancelAt(0.3, file.path, highest);
  options.threads = 2;
  // Two regions, so both threads have work when the cancel comes.
  expectCancelled(ModelKind::ClosedPolyhedron, samples::torusMesh(1.0, 0.3, 100, 50), options);
  EXPECT_LT(highest, 0.85);
}

TEST(BuildCancel, CancelDuringTheHierarchyWritesNothing) {
  const TempFile file("sc_cancel_test", "late.bvh");
  double highest = 0.0;
  expectCancelled(ModelKind::ClosedPolyhedron, torus(), cancelAt(0.9, file.path, highest));
  EXPECT_GE(highest, 0.9);
}

TEST(BuildCancel, CancelBeforeTheWorkFailsForEveryKind) {
  for (const ModelKind kind : {ModelKind::ClosedPolyhedron, ModelKind::TriangleSoup}) {
    const TempFile file("sc_cancel_test", "early.bvh");
    double highest = 0.0;
    expectCancelled(kind, torus(), cancelAt(0.0, file.path, highest));
    EXPECT_EQ(highest, 0.0);
  }
}

TEST(BuildCancel, ExistingCacheFileIsLeftAsItWas) {
  const TempFile file("sc_cancel_test", "stale.bvh");
  const std::string stale = "not a cache file";
  std::ofstream(file.path, std::ios::binary) << stale;
  double highest = 0.0;
  const Result<PiecePtr> built =
      buildPiece(ModelKind::ClosedPolyhedron, torus(), cancelAt(0.5, file.path, highest));
  ASSERT_FALSE(built.hasValue());
  EXPECT_EQ(readBytes<std::string>(file.path), stale);
  EXPECT_TRUE(leftovers(file.path).empty());
}

}  // namespace
}  // namespace sc
