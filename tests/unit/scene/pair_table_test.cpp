// SPDX-License-Identifier: MIT
// PairTable: listing order and slots, trackers kept across syncs, the sleeping rule
// for unlisted pairs, and forgetting or dropping the pairs of one group.
#include "scene/pair_table.h"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "support/shapes.h"

namespace sc::detail {
namespace {

/// Two unit boxes 3 apart; updating a tracker on them makes it track both directions.
struct TwoBoxes {
  ModelPtr model;
  Part part;
  GroupView a, b;

  TwoBoxes() {
    auto piece = buildPiece(ModelKind::ClosedPolyhedron, test::boxMesh(Vec3::Constant(0.5)));
    model = std::make_shared<const Model>(ModelKind::ClosedPolyhedron,
                                          std::vector<PiecePtr>{piece.value()});
    part.model = model.get();
    a.parts = &part;
    a.part_count = 1;
    b = a;
    b.placement.world_center = Vec3(3, 0, 0);
  }

  void track(PairTracker& t) const {
    DirectedResult out[2];
    t.update(a, b, Directions{}, SceneSettings(), out);
    ASSERT_EQ(out[0].code, ErrorCode::Ok);
    ASSERT_TRUE(t.tracking(0) && t.tracking(1));
  }
};

std::vector<PairKey> keysOf(const PairTable& table) {
  std::vector<PairKey> keys;
  for (const auto& e : table.entries()) keys.push_back(e.key);
  return keys;
}

/// Per entry, in order: whether direction 0 and direction 1 track a state.
using Tracking = std::vector<std::pair<bool, bool>>;
Tracking trackingOf(const PairTable& table) {
  Tracking t;
  for (const auto& e : table.entries())
    t.emplace_back(e.tracker.tracking(0), e.tracker.tracking(1));
  return t;
}

auto noneSleeps = [](int) { return false; };

TEST(PairTable, KeysOrderByIdWithTheStaticGroupSecond) {
  EXPECT_EQ(pairKeyOf(4, 2), (PairKey{2, 4}));
  const PairKey with_static = pairKeyOf(3, kStaticGroup);
  EXPECT_EQ(firstGroup(with_static), 3);
  EXPECT_EQ(secondGroup(with_static), kStaticGroup);
  EXPECT_EQ(targetOf(with_static, 0), 3);
  EXPECT_EQ(targetOf(PairKey{2, 4}, 1), 4);
  EXPECT_TRUE(pairKeyOf(9, kStaticGroup) < pairKeyOf(0, 1));
}

TEST(PairTable, SyncKeepsTheTrackersOfListedPairsAndAssignsSlotsInOrder) {
  const TwoBoxes boxes;
  PairTable table;
  std::vector<int> slots;
  table.sync(std::vector<PairKey>{{kStaticGroup, 3}, {1, 2}, {1, 5}}, noneSleeps, slots);
  EXPECT_EQ(slots, (std::vector<int>{0, 1, 2}));
  boxes.track(table.entries()[1].tracker);

  // (1, 2) stays listed and keeps its state; (-1, 3) and (1, 5) track nothing: gone.
  table.sync(std::vector<PairKey>{{0, 1}, {1, 2}}, noneSleeps, slots);
  EXPECT_EQ(keysOf(table), (std::vector<PairKey>{{0, 1}, {1, 2}}));
  EXPECT_EQ(slots, (std::vector<int>{0, 1}));
  EXPECT_TRUE(table.entries()[1].tracker.tracking(0));
  EXPECT_FALSE(table.entries()[0].tracker.tracking(0));
}

/// A table listing `keys` (none sleeping), every pair tracking both directions.
struct TrackedTable {
  TwoBoxes boxes;
  PairTable table;
  std::vector<int> slots;

  explicit TrackedTable(const std::vector<PairKey>& keys) {
    table.sync(keys, noneSleeps, slots);
    for (auto& e : table.entries()) boxes.track(e.tracker);
  }
};

TEST(PairTable, UnlistedPairsKeepOnlyTheDirectionsOfSleepingTargets) {
  TrackedTable t({{kStaticGroup, 4}, {1, 2}, {2, 3}});
  PairTable& table = t.table;
  std::vector<int>& slots = t.slots;

  // Group 2 and group 4 sleep; nothing is listed.
  auto sleeping = [](int gid) { return gid == 2 || gid == 4; };
  table.sync({}, sleeping, slots);
  EXPECT_TRUE(slots.empty());
  ASSERT_EQ(keysOf(table), (std::vector<PairKey>{{kStaticGroup, 4}, {1, 2}, {2, 3}}));
  // The sleeping targets' directions: 4 -> static, 2 -> 1, 2 -> 3.
  EXPECT_EQ(trackingOf(table), (Tracking{{true, false}, {false, true}, {true, false}}));

  // Once awake and still unlisted, the state goes.
  table.sync({}, noneSleeps, slots);
  EXPECT_TRUE(table.entries().empty());
}

TEST(PairTable, ForgetAndDropTouchOnlyTheNamedGroup) {
  TrackedTable t({{kStaticGroup, 2}, {1, 2}, {3, 4}});
  PairTable& table = t.table;

  // Group 2 as target: 2 -> static and 2 -> 1 forgotten, (3, 4) untouched.
  table.forgetTarget(2);
  EXPECT_EQ(trackingOf(table), (Tracking{{false, true}, {true, false}, {true, true}}));

  // Group 1 either way: 1 -> 2 too.
  table.forgetGroup(1);
  EXPECT_EQ(trackingOf(table), (Tracking{{false, true}, {false, false}, {true, true}}));

  table.dropGroup(2);
  EXPECT_EQ(keysOf(table), (std::vector<PairKey>{{3, 4}}));
  EXPECT_TRUE(table.entries()[0].tracker.tracking(0));
}

}  // namespace
}  // namespace sc::detail
