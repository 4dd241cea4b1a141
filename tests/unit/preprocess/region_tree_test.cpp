// SPDX-License-Identifier: MIT
// The decomposition's tree of a region's reach: it holds every triangle whose box
// meets the region's widened box (brute force over the mesh), a walk visits the
// same triangles as a brute-force box test, and with the patch counted it skips
// exactly the patch's triangles, however the patch grew and shrank.
#include "preprocess/region_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include "sc_support/sample_meshes.h"

namespace sc::detail {
namespace {

bool overlap(const Aabb& a, const Aabb& b) {
  return !(a.min.array() > b.max.array()).any() && !(a.max.array() < b.min.array()).any();
}

struct RegionTreeTest : ::testing::Test {
  // 20k triangles: three regions of at most kRegionTriangles.
  MeshData mesh = samples::torusMesh(1.0, 0.3, 100, 100);
  SharedMesh shared{mesh};
  void SetUp() override { ASSERT_TRUE(shared.prepare().ok()); }

  Aabb regionBox(int region, double margin) const {
    Aabb box;
    for (int i = shared.region_start[region]; i < shared.region_start[region + 1]; ++i) {
      box.extend(shared.tree.box(shared.region_order[i]));
    }
    box.min -= Vec3::Constant(margin);
    box.max += Vec3::Constant(margin);
    return box;
  }
  std::set<int> walk(const RegionTree& tree, bool skip, const Aabb& query) const {
    std::set<int> seen;
    tree.query(
        skip, [&](const Aabb& box) { return overlap(box, query); },
        [&](int t) {
          if (overlap(shared.tree.box(t), query)) seen.insert(t);
          return true;
        });
    return seen;
  }
};

TEST_F(RegionTreeTest, HoldsEveryTriangleThatMeetsTheWidenedRegion) {
  ASSERT_GT(shared.regionCount(), 1);
  RegionTree tree(shared);
  const double margin = 0.05;
  for (int r = 0; r < shared.regionCount(); ++r) {
    tree.build(r, margin);
    const Aabb reach = regionBox(r, margin);
    std::set<int> expected;
    for (int t = 0; t < shared.tree.size(); ++t) {
      if (overlap(shared.tree.box(t), reach)) expected.insert(t);
    }
    EXPECT_EQ(walk(tree, false, reach), expected) << "region " << r;
    EXPECT_LT(expected.size(), mesh.triangles.size()) << "the reach is local";
  }
}

TEST_F(RegionTreeTest, CountedPatchIsSkippedAndNothingElse) {
  RegionTree tree(shared);
  tree.build(0, 0.0);
  const Aabb reach = regionBox(0, 0.0);
  const std::vector<int> region(shared.region_order.begin() + shared.region_start[0],
                                shared.region_order.begin() + shared.region_start[1]);
  std::mt19937 rng(7);
  std::set<int> patch;
  // A compact patch (the 600 region triangles nearest one) grown, shrunk and grown
  // again.
  auto centre = [&](int t) { return shared.tree.box(t).min + shared.tree.box(t).max; };
  for (int round = 0; round < 3; ++round) {
    const Vec3 seed = centre(region[rng() % region.size()]);
    std::vector<int> near = region;
    std::sort(near.begin(), near.end(), [&](int a, int b) {
      return (centre(a) - seed).squaredNorm() < (centre(b) - seed).squaredNorm();
    });
    for (int i = 0; i < 600; ++i) {
      if (patch.insert(near[i]).second) tree.markPatch(near[i], 1);
    }
    std::vector<int> drop(patch.begin(), patch.end());
    std::shuffle(drop.begin(), drop.end(), rng);
    drop.resize(drop.size() / 3);
    for (int t : drop) {
      patch.erase(t);
      tree.markPatch(t, -1);
    }
    std::set<int> expected;
    for (int t : walk(tree, false, reach)) {
      if (!patch.count(t)) expected.insert(t);
    }
    std::set<int> seen;
    for (int t : walk(tree, true, reach)) {
      if (!patch.count(t)) seen.insert(t);
    }
    EXPECT_EQ(seen, expected) << "round " << round;
    EXPECT_LT(walk(tree, true, reach).size(), walk(tree, false, reach).size());
  }
}

}  // namespace
}  // namespace sc::detail
