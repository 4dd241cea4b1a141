// SPDX-License-Identifier: MIT
// The scene with its AABB-tree broadphase, pair table and worker threads against
// brute-force enumeration: random scenes (up to 500 groups) under random motion,
// activities, deletions and group changes; every frame the listed pairs and every
// field of every result equal, bit for bit, those of (a) a Scene with
// Broadphase::BruteForce and (b) the independent ReferenceScene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <ostream>

#include "scene_scenario.h"

namespace sc::test {
namespace {

struct DifferentialCase {
  const char* name;
  std::uint64_t seed;
  ModelKind kind;
  int groups;
  int statics;
  int frames;  ///< halved in sanitizer and debug builds
  double max_distance;
  bool infinite_distance;
};

void PrintTo(const DifferentialCase& c, std::ostream* os) { *os << c.name; }

class SceneDifferential : public testing::TestWithParam<DifferentialCase> {};

TEST_P(SceneDifferential, TreeAndThreadsListAndComputeWhatBruteForceDoes) {
  const DifferentialCase& c = GetParam();
  SCOPED_TRACE(testing::Message() << "seed " << c.seed);
  ScenarioOptions options;
  options.seed = c.seed;
  options.kind = c.kind;
  options.groups = c.groups;
  options.statics = c.statics;
  options.max_distance = c.max_distance;
  options.infinite_distance = c.infinite_distance;
  Scenario scenario(options);

  Scene tree(c.kind);
  SceneSettings s = tree.settings();
  s.threads = 2;
  ASSERT_TRUE(tree.setSettings(s).ok());
  Scene brute(c.kind);
  s.threads = 1;
  s.broadphase = Broadphase::BruteForce;
  ASSERT_TRUE(brute.setSettings(s).ok());
  ReferenceScene reference(c.kind);

  // Successful and failed operations by kind.
  std::map<Op::Kind, int> succeeded, failed;
  auto applyAll = [&](const std::vector<Op>& ops, int frame) {
    for (size_t i = 0; i < ops.size(); ++i) {
      const bool ok = apply(reference, ops[i]);
      ASSERT_EQ(apply(tree, ops[i]), ok) << "frame " << frame << " op " << i;
      ASSERT_EQ(apply(brute, ops[i]), ok) << "frame " << frame << " op " << i;
      ++(ok ? succeeded : failed)[ops[i].kind];
    }
  };
  applyAll(scenario.populate(), -1);

  PairCounts counts;
  long max_pairs = 0;
  const int frames = slowBuild() ? c.frames / 2 : c.frames;
  for (int f = 0; f < frames; ++f) {
    const std::vector<Op> ops = scenario.frame(reference);
    applyAll(ops, f);
    if (HasFatalFailure()) return;
    reference.update();
    ASSERT_TRUE(tree.update().ok());
    ASSERT_TRUE(brute.update().ok());
    const std::string tree_diff = firstDifference(tree.pairs(), reference.pairs());
    ASSERT_TRUE(tree_diff.empty()) << "frame " << f << ", tree vs reference: " << tree_diff;
    const std::string brute_diff = firstDifference(brute.pairs(), reference.pairs());
    ASSERT_TRUE(brute_diff.empty()) << "frame " << f << ", brute force vs reference: " << brute_diff;
    count(reference.pairs(), counts);
    max_pairs = std::max(max_pairs, static_cast<long>(reference.pairs().size()));
  }
  // The scenario reached every kind of result.
  RecordProperty("listed_pairs", static_cast<int>(counts.pairs));
  EXPECT_GT(counts.pairs, 5L * frames) << "too few listed pairs";
  EXPECT_GT(counts.with_static, 0);
  EXPECT_GT(counts.apart, 0);
  EXPECT_GT(counts.penetrating, 0);
  EXPECT_GT(counts.initial_intersection, 0);
  EXPECT_GT(counts.one_way, 0);
  for (Op::Kind kind : {Op::Kind::AddObject, Op::Kind::DeleteObject, Op::Kind::AddToGroup,
                        Op::Kind::RemoveFromGroup, Op::Kind::ObjectActivity,
                        Op::Kind::GroupActivity, Op::Kind::PairActivity}) {
    EXPECT_GT(succeeded[kind], 0) << "operation kind " << static_cast<int>(kind) << " never succeeded";
  }
  EXPECT_GT(failed[Op::Kind::DeleteObject] + failed[Op::Kind::RemoveFromGroup], 0);
  int changes = 0, rejected = 0;
  for (const auto& [kind, n] : succeeded) changes += kind == Op::Kind::MoveGroup ? 0 : n;
  for (const auto& [kind, n] : failed) rejected += n;
  std::printf("[ counts   ] %s: %d frames, %ld listed pairs (max %ld per frame), %ld with static, "
              "%ld apart, %ld penetrating, %ld first seen intersecting, %ld one-way; "
              "%d changes applied, %d rejected\n",
              c.name, frames, counts.pairs, max_pairs, counts.with_static, counts.apart,
              counts.penetrating, counts.initial_intersection, counts.one_way, changes, rejected);
}

INSTANTIATE_TEST_SUITE_P(
    RandomScenes, SceneDifferential,
    testing::Values(
        DifferentialCase{"Small", 11, ModelKind::ClosedPolyhedron, 12, 4, 200, 0.6, true},
        DifferentialCase{"Medium", 12, ModelKind::ClosedPolyhedron, 100, 12, 300, 0.5, false},
        DifferentialCase{"Soup", 13, ModelKind::TriangleSoup, 60, 8, 80, 0.5, false},
        DifferentialCase{"Large", 14, ModelKind::ClosedPolyhedron, 500, 30, 100, 0.4, false}),
    [](const testing::TestParamInfo<DifferentialCase>& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace sc::test
