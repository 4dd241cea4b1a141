// SPDX-License-Identifier: MIT
// What the broadphase lists: static objects bound themselves (a big static world
// does not make every group a candidate), thousands of sparse groups list only
// their close pairs, and switching broadphase mid-run changes no result.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scene_scenario.h"

namespace sc::test {
namespace {

Placement at(const Vec3& p) {
  Placement pl;
  pl.world_center = p;
  return pl;
}

std::vector<std::pair<int, int>> listedGroups(const Scene& scene) {
  std::vector<std::pair<int, int>> out;
  for (const PairStatus& p : scene.pairs()) out.emplace_back(p.groups[0], p.groups[1]);
  return out;
}

using Pairs = std::vector<std::pair<int, int>>;

class SceneBroadphase : public testing::TestWithParam<Broadphase> {
 protected:
  Scene scene{ModelKind::ClosedPolyhedron};
  ModelPtr cube = modelOf(ModelKind::ClosedPolyhedron, sceneBoxMesh(Vec3::Constant(0.5)));

  void SetUp() override {
    SceneSettings s;
    s.max_distance = 1.0;
    s.broadphase = GetParam();
    ASSERT_TRUE(scene.setSettings(s).ok());
  }
};

TEST_P(SceneBroadphase, StaticObjectsBoundThemselvesNotTheirUnion) {
  ASSERT_TRUE(scene.addObject(100, cube, at(Vec3(0, 0, 0))).ok());
  ASSERT_TRUE(scene.addObject(101, cube, at(Vec3(100, 0, 0))).ok());
  ASSERT_TRUE(scene.addObject(1, cube, at(Vec3(50, 0, 0))).ok());
  ASSERT_TRUE(scene.addObjectToGroup(7, 1).ok());
  ASSERT_TRUE(scene.update().ok());
  // Inside the box spanning both static cubes, but 48.5 from each.
  EXPECT_EQ(listedGroups(scene), Pairs{});

  Placement p = scene.groupPlacement(7).value();
  p.world_center = Vec3(98.5, 0, 0);  // gap 0.5 to the cube at x = 100
  ASSERT_TRUE(scene.setGroupPlacement(7, p).ok());
  ASSERT_TRUE(scene.update().ok());
  ASSERT_EQ(listedGroups(scene), (Pairs{{7, kStaticGroup}}));
  EXPECT_EQ(scene.pairs()[0].results[0].code, ErrorCode::Ok);
  EXPECT_NEAR(scene.pairs()[0].results[0].distance, 0.5, 1e-9);
  EXPECT_EQ(scene.pairs()[0].results[0].opponent_object, 101);

  // Deleting that static object unlists the pair at once.
  ASSERT_TRUE(scene.deleteObject(101).ok());
  ASSERT_TRUE(scene.update().ok());
  EXPECT_EQ(listedGroups(scene), Pairs{});
}

TEST_P(SceneBroadphase, ThousandsOfSparseGroupsListOnlyTheirClosePairs) {
  // 20 x 20 x 8 unit cubes on a grid of spacing 3: gaps of 2, beyond max distance 1.
  int id = 0;
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 20; ++j) {
      for (int k = 0; k < 8; ++k, ++id) {
        ASSERT_TRUE(scene.addObject(id, cube, at(Vec3(3.0 * i, 3.0 * j, 3.0 * k))).ok());
        ASSERT_TRUE(scene.addObjectToGroup(id, id).ok());
      }
    }
  }
  ASSERT_TRUE(scene.update().ok());
  EXPECT_EQ(listedGroups(scene), Pairs{});

  // Group 0 (at the origin) moves next to group 8 (at y = 3): one pair, ids in order.
  Placement p = scene.groupPlacement(0).value();
  p.world_center = Vec3(0, 1.6, 0);
  ASSERT_TRUE(scene.setGroupPlacement(0, p).ok());
  ASSERT_TRUE(scene.update().ok());
  ASSERT_EQ(listedGroups(scene), (Pairs{{0, 8}}));
  EXPECT_NEAR(scene.pairs()[0].results[0].distance, 0.4, 1e-9);
  EXPECT_NEAR(scene.pairs()[0].results[1].distance, 0.4, 1e-9);

  // A sleeping pair of groups is not listed; a sleeping group near an active one is.
  ASSERT_TRUE(scene.setGroupActivity(0, Activity::Sleeping).ok());
  ASSERT_TRUE(scene.setGroupActivity(8, Activity::Sleeping).ok());
  ASSERT_TRUE(scene.update().ok());
  EXPECT_EQ(listedGroups(scene), Pairs{});
  ASSERT_TRUE(scene.setGroupActivity(8, Activity::Active).ok());
  ASSERT_TRUE(scene.update().ok());
  ASSERT_EQ(listedGroups(scene), (Pairs{{0, 8}}));
  EXPECT_EQ(scene.pairs()[0].results[0].code, ErrorCode::NoResult);
  EXPECT_EQ(scene.pairs()[0].results[1].code, ErrorCode::Ok);

  // Deleting group 8's object removes the group and its pair.
  ASSERT_TRUE(scene.deleteObject(8).ok());
  ASSERT_TRUE(scene.update().ok());
  EXPECT_EQ(listedGroups(scene), Pairs{});
  EXPECT_FALSE(scene.hasGroup(8));
}

INSTANTIATE_TEST_SUITE_P(Both, SceneBroadphase,
                         testing::Values(Broadphase::Tree, Broadphase::BruteForce),
                         [](const testing::TestParamInfo<Broadphase>& p) {
                           return std::string(p.param == Broadphase::Tree ? "Tree" : "BruteForce");
                         });

TEST(SceneBroadphaseSwitch, SwitchingBroadphaseMidRunChangesNoResult) {
  ScenarioOptions options;
  options.seed = 5;
  options.groups = 80;
  options.statics = 10;
  Scenario scenario(options);
  ReferenceScene reference(options.kind);
  Scene scene(options.kind);
  for (const Op& op : scenario.populate()) ASSERT_EQ(apply(scene, op), apply(reference, op));
  const int frames = slowBuild() ? 30 : 60;
  for (int f = 0; f < frames; ++f) {
    for (const Op& op : scenario.frame(reference)) ASSERT_EQ(apply(scene, op), apply(reference, op));
    if (f % 7 == 3) {
      SceneSettings s = scene.settings();
      s.broadphase = s.broadphase == Broadphase::Tree ? Broadphase::BruteForce : Broadphase::Tree;
      ASSERT_TRUE(scene.setSettings(s).ok());
    }
    reference.update();
    ASSERT_TRUE(scene.update().ok());
    ASSERT_EQ(firstDifference(scene.pairs(), reference.pairs()), "") << "frame " << f;
  }
}

}  // namespace
}  // namespace sc::test
