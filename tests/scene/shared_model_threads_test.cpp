// SPDX-License-Identifier: MIT
// The thread-safety contract of docs/reliability.md: Models are immutable and may
// be shared by scenes running on different threads at once. Two threads each run
// their own Scene (with its own worker pool) over the same Models; every frame
// equals a serial run bit for bit. Runs under ThreadSanitizer in CI.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <thread>
#include <vector>

#include "scene_scenario.h"
#include "smartcollision/scene.h"
#include "support/test_support.h"

namespace sc::test {
namespace {

constexpr int kGroups = 24;
constexpr int kStatics = 4;
constexpr int kFrames = 12;

/// FNV-1a of every number of a pair list.
std::uint64_t hashPairs(const std::vector<PairStatus>& pairs) {
  std::uint64_t h = 14695981039346656037ull;
  auto add = [&h](const void* data, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  };
  for (const PairStatus& p : pairs) {
    add(p.groups, sizeof p.groups);
    for (const DirectedResult& r : p.results) {
      add(&r.code, sizeof r.code);
      add(&r.target_object, sizeof r.target_object);
      add(&r.opponent_object, sizeof r.opponent_object);
      add(&r.distance, sizeof r.distance);
      add(r.normal.data(), 3 * sizeof(double));
      add(r.tpdv.data(), 3 * sizeof(double));
      add(r.rpdv.data(), 3 * sizeof(double));
      add(r.contact_orientation.coeffs().data(), 4 * sizeof(double));
    }
  }
  return h;
}

Placement randomPlacement(Rng& rng, double extent) {
  Placement p;
  p.world_center = Vec3(uniform(rng, -extent, extent), uniform(rng, -extent, extent),
                        uniform(rng, -extent, extent));
  p.orientation = randomRotation(rng);
  return p;
}

/// Runs one scene over the shared models for kFrames random-walk frames; returns
/// the hash of each frame's pair list (and how many pairs were listed in all).
std::vector<std::uint64_t> runScene(const std::vector<ModelPtr>& models, std::uint64_t seed,
                                    int threads, long* listed) {
  Rng rng(seed);
  Scene scene(ModelKind::ClosedPolyhedron);
  SceneSettings settings;
  settings.threads = threads;
  settings.max_distance = 1.0;
  EXPECT_TRUE(scene.setSettings(settings).ok());
  const double extent = 2.0;
  for (int i = 0; i < kGroups + kStatics; ++i) {
    const ModelPtr& model = models[static_cast<std::size_t>(i) % models.size()];
    EXPECT_TRUE(scene.addObject(i, model, randomPlacement(rng, extent)).ok());
    if (i < kGroups) {
      EXPECT_TRUE(scene.addObjectToGroup(100 + i, i).ok());
    }
  }
  std::vector<std::uint64_t> hashes;
  for (int frame = 0; frame < kFrames; ++frame) {
    for (int g = 0; g < kGroups; ++g) {
      Result<Placement> p = scene.groupPlacement(100 + g);
      EXPECT_TRUE(p.hasValue());
      if (!p.hasValue()) continue;
      Placement next = p.value();
      next.world_center += 0.05 * randomDirection(rng);
      next.orientation = (next.orientation * Quat(Eigen::AngleAxisd(0.05, randomDirection(rng))))
                             .normalized();
      EXPECT_TRUE(scene.setGroupPlacement(100 + g, next).ok());
    }
    EXPECT_TRUE(scene.update().ok());
    hashes.push_back(hashPairs(scene.pairs()));
    if (listed != nullptr) *listed += static_cast<long>(scene.pairs().size());
  }
  return hashes;
}

TEST(SharedModelThreads, ConcurrentScenesOverSharedModelsMatchSerialRuns) {
  const std::vector<ModelPtr> models = {
      modelOf(ModelKind::ClosedPolyhedron, sceneBoxMesh(Vec3(0.5, 0.3, 0.4))),
      modelOf(ModelKind::ClosedPolyhedron, lPrismMesh(1.0)),
      modelOf(ModelKind::ClosedPolyhedron, sceneBoxMesh(Vec3(0.2, 0.6, 0.3))),
  };
  constexpr std::uint64_t kSeeds[2] = {11, 12};

  long listed = 0;
  const std::vector<std::uint64_t> serial[2] = {runScene(models, kSeeds[0], 1, &listed),
                                                runScene(models, kSeeds[1], 1, &listed)};
  // Enough pairs per frame that the scenes' worker pools take part (the scene
  // runs fewer than 16 on the calling thread).
  EXPECT_GE(listed, 2 * kFrames * 16) << "the scenario lists too few pairs";

  // Same seeds on two threads at once, each scene with two threads of its own.
  std::vector<std::uint64_t> concurrent[2];
  std::thread a([&] { concurrent[0] = runScene(models, kSeeds[0], 2, nullptr); });
  std::thread b([&] { concurrent[1] = runScene(models, kSeeds[1], 2, nullptr); });
  a.join();
  b.join();
  EXPECT_EQ(concurrent[0], serial[0]);
  EXPECT_EQ(concurrent[1], serial[1]);
}

}  // namespace
}  // namespace sc::test
