// SPDX-License-Identifier: MIT
// Manual 8.4 and 8.10 through sc.h only: Table 8-1 cell by cell, the static group,
// List 8-10, pair and object activities, tracking across SLEEPING/PASSIVE, and the
// GetStatus conventions (id order, reverseFlag, signs, maximum distance).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <memory>
#include <set>
#include <utility>
#include <vector>

#include "cube.h"
#include "sc.h"

namespace {

using sc_conformance::cubeVertices;
using sc_conformance::kCubeTriangles;

// List 10-1: the unit-corner tetrahedron.
const double kTetraVertices[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
const int kTetraTriangles[12] = {0, 2, 1, 1, 3, 0, 0, 3, 2, 1, 2, 3};

const double kSqrt4Over3 = std::sqrt(4.0 / 3.0);
const double kSqrt1Over12 = std::sqrt(1.0 / 12.0);

/// A closed-polyhedra scene that owns its objects. Objects are destroyed first
/// (declared last), so each leaves the scene on its own.
struct TestScene {
  SCSceneManager manager{SC_SCENE_MANAGER_CLOSED_POLYHEDRA};
  std::vector<std::unique_ptr<SCObject>> objects;

  SCObject& newObject() {
    objects.push_back(std::make_unique<SCObject>(SC_OBJECT_TYPE_CLOSED_POLYHEDRON));
    return *objects.back();
  }

  void place(int id, int gid, SCObject& o) {
    EXPECT_EQ(manager.AddObject(id, &o), SC_NO_ERROR);
    if (gid != SC_GROUP_STATIC) {
      EXPECT_EQ(manager.AddObjectToGroup(gid, id), SC_NO_ERROR);
    }
  }

  /// Object `id`: a cube (lower corner x, y, z) in group `gid` (or SC_GROUP_STATIC).
  SCObject& addCube(int id, int gid, double x, double y = 0.0, double z = 0.0,
                    double size = 1.0) {
    SCObject& o = newObject();
    const std::vector<double> v = cubeVertices(x, y, z, size);
    EXPECT_EQ(o.AddTriangles(v.data(), 8, kCubeTriangles, 12), SC_NO_ERROR);
    place(id, gid, o);
    return o;
  }

  /// Object `id`: the List 10-1 tetrahedron with its local origin at `origin`.
  SCObject& addTetra(int id, int gid, double x, double y, double z) {
    SCObject& o = newObject();
    EXPECT_EQ(o.AddTriangles(kTetraVertices, 4, kTetraTriangles, 4), SC_NO_ERROR);
    const double origin[3] = {x, y, z};
    EXPECT_EQ(o.SetTransformation(SC_POSITION_ORIGIN, origin), SC_NO_ERROR);
    place(id, gid, o);
    return o;
  }

  void moveGroup(int gid, double x, double y, double z) {
    const double origin[3] = {x, y, z};
    EXPECT_EQ(manager.SetTransformation(gid, SC_POSITION_ORIGIN, origin), SC_NO_ERROR);
  }

  void setGroup(int gid, SCenum activity) {
    EXPECT_EQ(manager.SetActivityGroup(gid, activity), SC_NO_ERROR);
  }
  void setPair(int first, int second, SCenum activity) {
    EXPECT_EQ(manager.SetActivityPair(first, second, activity), SC_NO_ERROR);
  }
  void setObject(int id, SCenum activity) {
    EXPECT_EQ(manager.SetActivityObject(id, activity), SC_NO_ERROR);
  }

  void update() { EXPECT_EQ(manager.UpdateStatus(), SC_NO_ERROR); }

  int count() {
    SCint n = -1;
    EXPECT_EQ(manager.GetStatus(SC_STATUS_COUNT, &n), SC_NO_ERROR);
    return n;
  }
};

/// Cubes 1 and 2 in groups `ga` and `gb`, gap 1 along x.
struct TwoCubes : TestScene {
  TwoCubes(int ga, int gb) {
    addCube(1, ga, 0.0);
    addCube(2, gb, 2.0);
  }
};

/// Cubes 1 and 2 in groups 1 and 2, and cube 3 in the static group: three pairs.
struct ThreeCubes : TwoCubes {
  ThreeCubes() : TwoCubes(1, 2) { addCube(3, SC_GROUP_STATIC, 0.0, 3.0); }
};

/// Where the direction target -> opponent is in the status list.
struct Slot {
  bool listed = false;
  int index = -1;
  bool reverse = false;
};

Slot find(SCSceneManager& m, int target, int opponent) {
  SCint count = 0;
  EXPECT_EQ(m.GetStatus(SC_STATUS_COUNT, &count), SC_NO_ERROR);
  for (int i = 0; i < count; ++i) {
    for (bool reverse : {false, true}) {
      SCint g[2] = {-77, -77};
      EXPECT_EQ(m.GetStatus(SC_GROUP_ID, g, i, reverse), SC_NO_ERROR);
      if (g[0] == target && g[1] == opponent) return {true, i, reverse};
    }
  }
  return {};
}

/// The two ids of `field` (SC_OBJECT_ID or SC_PIECE_ID) at `slot`, target first.
void expectIds(SCSceneManager& m, const Slot& slot, SCenum field, std::pair<int, int> ids) {
  SCint got[2] = {-1, -1};
  EXPECT_EQ(m.GetStatus(field, got, slot.index, slot.reverse), SC_NO_ERROR);
  EXPECT_EQ(std::make_pair(int(got[0]), int(got[1])), ids) << "field " << field;
}

constexpr int kNotListed = -1000;

/// SC_STATUS_RESULT of target -> opponent, or kNotListed when the pair is not listed.
int resultOf(SCSceneManager& m, int target, int opponent) {
  const Slot s = find(m, target, opponent);
  if (!s.listed) return kNotListed;
  SCint r = -1;
  EXPECT_EQ(m.GetStatus(SC_STATUS_RESULT, &r, s.index, s.reverse), SC_NO_ERROR);
  return r;
}

double distanceOf(SCSceneManager& m, int target, int opponent) {
  const Slot s = find(m, target, opponent);
  double d = 1e300;
  EXPECT_TRUE(s.listed);
  if (s.listed) {
    EXPECT_EQ(m.GetStatus(SC_DISTANCE, &d, s.index, s.reverse), SC_NO_ERROR);
  }
  return d;
}

/// Which directions of a pair are computed; a pair with none is not listed.
enum class Way { None, AToB, BToA, Both };

const char* name(Way w) {
  switch (w) {
    case Way::None: return "none";
    case Way::AToB: return "A->B";
    case Way::BToA: return "B->A";
    case Way::Both: return "A<->B";
  }
  return "?";
}

void expectWay(SCSceneManager& m, int a, int b, Way w) {
  SCOPED_TRACE(testing::Message() << "groups " << a << ", " << b << ": expected " << name(w));
  const int ab = resultOf(m, a, b);
  const int ba = resultOf(m, b, a);
  if (w == Way::None) {
    EXPECT_EQ(ab, kNotListed);
    EXPECT_EQ(ba, kNotListed);
    return;
  }
  EXPECT_EQ(ab, w == Way::AToB || w == Way::Both ? SC_NO_ERROR : SC_ERROR_NO_RESULT);
  EXPECT_EQ(ba, w == Way::BToA || w == Way::Both ? SC_NO_ERROR : SC_ERROR_NO_RESULT);
}

const SCenum kActivities[4] = {SC_ACTIVITY_ACTIVE, SC_ACTIVITY_SLEEPING, SC_ACTIVITY_PASSIVE,
                               SC_ACTIVITY_INACTIVE};

// Table 8-1 as printed in the manual: row = group A, column = group B.
const Way kTable81[4][4] = {
    {Way::Both, Way::AToB, Way::AToB, Way::None},  // A ACTIVE
    {Way::BToA, Way::None, Way::None, Way::None},  // A SLEEPING
    {Way::BToA, Way::None, Way::None, Way::None},  // A PASSIVE
    {Way::None, Way::None, Way::None, Way::None},  // A INACTIVE
};

/// One cell of Table 8-1, with group A's id below and above group B's id, so the
/// result does not hang on the listing order. Computed directions give distance 1.
void checkCell(int row, int column) {
  for (const auto& [ga, gb] : {std::pair<int, int>{3, 8}, std::pair<int, int>{8, 3}}) {
    SCOPED_TRACE(testing::Message() << "row " << row << " column " << column << ", A=" << ga
                                    << " B=" << gb);
    TestScene s;
    s.addCube(1, ga, 0.0);
    s.addCube(2, gb, 2.0);
    s.setGroup(ga, kActivities[row]);
    s.setGroup(gb, kActivities[column]);
    s.update();
    const Way w = kTable81[row][column];
    EXPECT_EQ(s.count(), w == Way::None ? 0 : 1);
    expectWay(s.manager, ga, gb, w);
    if (w == Way::AToB || w == Way::Both) {
      EXPECT_NEAR(distanceOf(s.manager, ga, gb), 1.0, 1e-9);
    }
    if (w == Way::BToA || w == Way::Both) {
      EXPECT_NEAR(distanceOf(s.manager, gb, ga), 1.0, 1e-9);
    }
  }
}

constexpr int kActive = 0, kSleeping = 1, kPassive = 2, kInactive = 3;

TEST(Table81, TwoActiveGroupsAreComputedBothWays) { checkCell(kActive, kActive); }

TEST(Table81, ActiveAgainstSleepingOrPassiveIsComputedWithTheActiveGroupAsTarget) {
  checkCell(kActive, kSleeping);
  checkCell(kActive, kPassive);
  checkCell(kSleeping, kActive);
  checkCell(kPassive, kActive);
}

TEST(Table81, SleepingAndPassiveGroupsAmongThemselvesAreNotListed) {
  for (int row : {kSleeping, kPassive})
    for (int column : {kSleeping, kPassive}) checkCell(row, column);
}

TEST(Table81, AnInactiveGroupTakesPartInNoPair) {
  for (int other = 0; other < 4; ++other) {
    checkCell(kInactive, other);
    checkCell(other, kInactive);
  }
}

TEST(StaticGroup, ActiveGroupAgainstStaticIsComputedOneWayWithTheGroupAsTarget) {
  TestScene s;
  s.addCube(1, SC_GROUP_STATIC, 0.0);
  s.addCube(2, 4, 2.0);
  s.update();
  ASSERT_EQ(s.count(), 1);
  SCint g[2];
  ASSERT_EQ(s.manager.GetStatus(SC_GROUP_ID, g, 0, false), SC_NO_ERROR);
  EXPECT_EQ(g[0], 4);
  EXPECT_EQ(g[1], SC_GROUP_STATIC);
  ASSERT_EQ(s.manager.GetStatus(SC_GROUP_ID, g, 0, true), SC_NO_ERROR);
  EXPECT_EQ(g[0], SC_GROUP_STATIC);
  EXPECT_EQ(g[1], 4);
  SCint r = -1;
  ASSERT_EQ(s.manager.GetStatus(SC_STATUS_RESULT, &r, 0, false), SC_NO_ERROR);
  EXPECT_EQ(r, SC_NO_ERROR);
  ASSERT_EQ(s.manager.GetStatus(SC_STATUS_RESULT, &r, 0, true), SC_NO_ERROR);
  EXPECT_EQ(r, SC_ERROR_NO_RESULT);  // the static group is passive: never a target
  EXPECT_NEAR(distanceOf(s.manager, 4, SC_GROUP_STATIC), 1.0, 1e-9);
}

TEST(StaticGroup, SleepingPassiveOrInactiveGroupAgainstStaticIsNotListed) {
  for (SCenum activity : {SC_ACTIVITY_SLEEPING, SC_ACTIVITY_PASSIVE, SC_ACTIVITY_INACTIVE}) {
    TestScene s;
    s.addCube(1, SC_GROUP_STATIC, 0.0);
    s.addCube(2, 4, 2.0);
    s.setGroup(4, activity);
    s.update();
    EXPECT_EQ(s.count(), 0) << "activity " << activity;
  }
}

TEST(StaticGroup, ObjectsOutsideGroupsNeverFormPairsAmongThemselves) {
  TestScene s;
  s.addCube(1, SC_GROUP_STATIC, 0.0);
  s.addCube(2, SC_GROUP_STATIC, 2.0);
  s.update();
  EXPECT_EQ(s.count(), 0);
}

TEST(List810, SevenGroupsGiveThePairsOfFigure82) {
  TestScene s;
  // One cube per group on a circle of radius 4, none touching; max distance is +inf.
  const double kPi = std::acos(-1.0);
  for (int g = 0; g < 7; ++g) {
    const double a = 2.0 * kPi * g / 7.0;
    s.addCube(100 + g, g, 4.0 * std::cos(a), 4.0 * std::sin(a));
  }
  const SCenum activity[7] = {SC_ACTIVITY_ACTIVE,   SC_ACTIVITY_PASSIVE, SC_ACTIVITY_INACTIVE,
                              SC_ACTIVITY_SLEEPING, SC_ACTIVITY_ACTIVE,  SC_ACTIVITY_SLEEPING,
                              SC_ACTIVITY_PASSIVE};
  for (int g = 0; g < 7; ++g) s.setGroup(g, activity[g]);
  s.update();
  // Figure 8-2 (from Table 8-1): the two active groups 0 and 4 both ways, and each of
  // them as target against the sleeping (3, 5) and passive (1, 6) groups.
  const std::set<std::pair<int, int>> expected = {{0, 4}, {4, 0}, {0, 1}, {0, 3}, {0, 5},
                                                  {0, 6}, {4, 1}, {4, 3}, {4, 5}, {4, 6}};
  EXPECT_EQ(s.count(), 9);
  std::set<std::pair<int, int>> computed;
  for (int i = 0; i < s.count(); ++i) {
    for (bool reverse : {false, true}) {
      SCint g[2], r = -1;
      ASSERT_EQ(s.manager.GetStatus(SC_GROUP_ID, g, i, reverse), SC_NO_ERROR);
      ASSERT_EQ(s.manager.GetStatus(SC_STATUS_RESULT, &r, i, reverse), SC_NO_ERROR);
      if (r == SC_NO_ERROR)
        computed.insert({g[0], g[1]});
      else
        EXPECT_EQ(r, SC_ERROR_NO_RESULT) << g[0] << " -> " << g[1];
    }
  }
  EXPECT_EQ(computed, expected);
}

/// One SetActivityPair call, then the directions of the pair under test after update.
struct PairStep {
  int first, second;
  SCenum activity;
  Way way;
};

/// Applies `steps` in order, checking the directions of groups a, b after each.
void runPairSteps(TestScene& s, int a, int b, std::initializer_list<PairStep> steps) {
  for (const PairStep& step : steps) {
    SCOPED_TRACE(testing::Message() << "SetActivityPair(" << step.first << ", " << step.second
                                    << ", " << step.activity << ")");
    s.setPair(step.first, step.second, step.activity);
    s.update();
    expectWay(s.manager, a, b, step.way);
  }
}

TEST(PairActivity, ActiveOnTwoSleepingGroupsComputesBothDirections) {
  TwoCubes s(1, 2);
  s.setGroup(1, SC_ACTIVITY_SLEEPING);
  s.setGroup(2, SC_ACTIVITY_SLEEPING);
  s.update();
  expectWay(s.manager, 1, 2, Way::None);
  runPairSteps(s, 1, 2, {{1, 2, SC_ACTIVITY_ACTIVE, Way::Both}});
}

TEST(PairActivity, InactiveOnTwoActiveGroupsRemovesThePair) {
  TwoCubes s(1, 2);
  s.addCube(3, 3, 0.0, 3.0);
  s.update();
  EXPECT_EQ(s.count(), 3);
  runPairSteps(s, 1, 2, {{2, 1, SC_ACTIVITY_INACTIVE, Way::None}});
  EXPECT_EQ(s.count(), 2);
  expectWay(s.manager, 1, 3, Way::Both);
  expectWay(s.manager, 2, 3, Way::Both);
}

TEST(PairActivity, OneWayActiveSetsOnlyTheFirstGroupAsTarget) {
  {  // Two sleeping groups: nothing before, only 5 -> 2 after (5 > 2: not id order).
    TwoCubes s(2, 5);
    s.setGroup(2, SC_ACTIVITY_SLEEPING);
    s.setGroup(5, SC_ACTIVITY_SLEEPING);
    runPairSteps(s, 5, 2, {{5, 2, SC_ACTIVITY_ONE_WAY_ACTIVE, Way::AToB}});
  }
  {  // Sleeping 2, active 5: Table 8-1 gives 5 -> 2, the setting adds 2 -> 5.
    TwoCubes s(2, 5);
    s.setGroup(2, SC_ACTIVITY_SLEEPING);
    s.update();
    expectWay(s.manager, 5, 2, Way::AToB);
    runPairSteps(s, 2, 5, {{2, 5, SC_ACTIVITY_ONE_WAY_ACTIVE, Way::Both}});
  }
  {  // Pair set inactive first: the other direction stays inactive.
    TwoCubes s(2, 5);
    s.setPair(2, 5, SC_ACTIVITY_INACTIVE);
    runPairSteps(s, 2, 5, {{2, 5, SC_ACTIVITY_ONE_WAY_ACTIVE, Way::AToB}});
  }
}

TEST(PairActivity, OneWayInactiveClearsOnlyTheFirstGroupAsTarget) {
  {  // Two active groups: 5 -> 2 off, 2 -> 5 kept from Table 8-1.
    TwoCubes s(2, 5);
    runPairSteps(s, 2, 5, {{5, 2, SC_ACTIVITY_ONE_WAY_INACTIVE, Way::AToB}});
  }
  {  // Two sleeping groups made active by the pair setting: 2 -> 5 off, 5 -> 2 kept.
    TwoCubes s(2, 5);
    s.setGroup(2, SC_ACTIVITY_SLEEPING);
    s.setGroup(5, SC_ACTIVITY_SLEEPING);
    s.setPair(2, 5, SC_ACTIVITY_ACTIVE);
    runPairSteps(s, 5, 2, {{2, 5, SC_ACTIVITY_ONE_WAY_INACTIVE, Way::AToB}});
  }
}

TEST(PairActivity, LaterSettingReplacesEarlierOneForTheDirectionsItSets) {
  TwoCubes s(1, 2);
  runPairSteps(s, 1, 2,
               {{1, 2, SC_ACTIVITY_INACTIVE, Way::None},
                {2, 1, SC_ACTIVITY_ONE_WAY_ACTIVE, Way::BToA},
                {1, 2, SC_ACTIVITY_ACTIVE, Way::Both},
                {2, 1, SC_ACTIVITY_ONE_WAY_INACTIVE, Way::AToB},
                {2, 1, SC_ACTIVITY_INACTIVE, Way::None}});
}

TEST(PairActivity, PairSettingOverridesGroupActivityOfTable81) {
  TwoCubes s(1, 2);
  s.setGroup(1, SC_ACTIVITY_INACTIVE);
  s.update();
  expectWay(s.manager, 1, 2, Way::None);
  runPairSteps(s, 1, 2, {{1, 2, SC_ACTIVITY_ACTIVE, Way::Both}});
}

TEST(PairActivity, GroupWithoutActiveObjectTakesPartInNoPairEvenWhenSetActive) {
  ThreeCubes s;
  s.setPair(1, 2, SC_ACTIVITY_ACTIVE);
  s.setObject(1, SC_ACTIVITY_INACTIVE);
  s.update();
  EXPECT_EQ(s.count(), 1);  // only 2 -> static
  expectWay(s.manager, 1, 2, Way::None);
  expectWay(s.manager, 1, SC_GROUP_STATIC, Way::None);
  expectWay(s.manager, 2, SC_GROUP_STATIC, Way::AToB);
}

TEST(ObjectActivity, InactiveObjectIsIgnoredByCollisionDetection) {
  TestScene s;
  // Group 1 holds a near cube (object 1, gap 1) and a far one (object 4, gap 5).
  s.addCube(1, 1, 0.0);
  s.addCube(4, 1, -5.0);
  s.addCube(2, 2, 2.0);
  s.update();
  EXPECT_NEAR(distanceOf(s.manager, 2, 1), 1.0, 1e-9);
  s.setObject(1, SC_ACTIVITY_INACTIVE);
  s.update();
  EXPECT_NEAR(distanceOf(s.manager, 2, 1), 6.0, 1e-9);
  const Slot slot = find(s.manager, 2, 1);
  ASSERT_TRUE(slot.listed);
  expectIds(s.manager, slot, SC_OBJECT_ID, {2, 4});
  s.setObject(1, SC_ACTIVITY_ACTIVE);
  s.update();
  EXPECT_NEAR(distanceOf(s.manager, 2, 1), 1.0, 1e-9);
}

TEST(ObjectActivity, GroupWhoseOnlyObjectIsInactiveTakesPartInNoPair) {
  ThreeCubes s;
  s.update();
  EXPECT_EQ(s.count(), 3);
  s.setObject(2, SC_ACTIVITY_INACTIVE);
  s.update();
  EXPECT_EQ(s.count(), 1);
  expectWay(s.manager, 1, SC_GROUP_STATIC, Way::AToB);
  expectWay(s.manager, 1, 2, Way::None);
  expectWay(s.manager, 2, SC_GROUP_STATIC, Way::None);
}

// --- Dynamic penetration depth across activities (manual 8.4, 8.6) -----------------

/// The List 10-1 scene: group 0 (object 1) moves, object 2 is static. Group 0 also
/// holds a far cube (object 3) that never comes near.
struct TrackedScene : TestScene {
  TrackedScene() {
    addTetra(1, 0, 1.0, 1.0, 1.0);
    addTetra(2, SC_GROUP_STATIC, 0.0, 0.0, 0.0);
    addCube(3, 0, 20.0, 20.0, 20.0);
  }
  /// Apart (distance sqrt(4/3)), then penetrating (depth sqrt(1/12)).
  void enterContact() {
    moveGroup(0, 1.0, 1.0, 1.0);
    update();
    EXPECT_NEAR(distanceOf(manager, 0, SC_GROUP_STATIC), kSqrt4Over3, 1e-9);
    moveGroup(0, 0.0, 0.0, 0.5);
    update();
    EXPECT_NEAR(distanceOf(manager, 0, SC_GROUP_STATIC), -kSqrt1Over12, 1e-9);
  }
  /// In contact, group 0 is set to `activity` (its pair leaves the list) for one
  /// update, then active again.
  void pauseInContact(SCenum activity) {
    enterContact();
    setGroup(0, activity);
    update();
    EXPECT_EQ(count(), 0);
    setGroup(0, SC_ACTIVITY_ACTIVE);
    update();
  }
  int result() { return resultOf(manager, 0, SC_GROUP_STATIC); }
};

TEST(Tracking, SleepingGroupKeepsItsPenetrationState) {
  TrackedScene s;
  s.pauseInContact(SC_ACTIVITY_SLEEPING);
  ASSERT_EQ(s.result(), SC_NO_ERROR);
  const double d = distanceOf(s.manager, 0, SC_GROUP_STATIC);
  EXPECT_LT(d, 0.0);
  EXPECT_NEAR(d, -kSqrt1Over12, 1e-9);
}

TEST(Tracking, PassiveGroupDropsItsPenetrationState) {
  TrackedScene s;
  s.pauseInContact(SC_ACTIVITY_PASSIVE);
  EXPECT_EQ(s.result(), SC_ERROR_INVALID_INITIAL_TRANSFORMATION);
}

TEST(Tracking, PairFirstSeenIntersectingIsInvalidUntilSeenApart) {
  TrackedScene s;
  s.moveGroup(0, 0.0, 0.0, 0.5);
  s.update();
  EXPECT_EQ(s.result(), SC_ERROR_INVALID_INITIAL_TRANSFORMATION);
  s.update();  // still never seen apart
  EXPECT_EQ(s.result(), SC_ERROR_INVALID_INITIAL_TRANSFORMATION);
  s.enterContact();
  EXPECT_EQ(s.result(), SC_NO_ERROR);
}

TEST(Tracking, ChangingAnObjectActivityInTheGroupDropsTheState) {
  TrackedScene s;
  s.enterContact();
  // Setting the activity an object already has changes nothing.
  s.setObject(3, SC_ACTIVITY_ACTIVE);
  s.update();
  EXPECT_EQ(s.result(), SC_NO_ERROR);
  s.setObject(3, SC_ACTIVITY_INACTIVE);
  s.update();
  EXPECT_EQ(s.result(), SC_ERROR_INVALID_INITIAL_TRANSFORMATION);
}

TEST(Tracking, ChangingGroupMembershipDropsTheState) {
  TrackedScene s;
  s.enterContact();
  ASSERT_EQ(s.manager.DeleteObjectFromGroup(0, 3), SC_NO_ERROR);
  s.update();
  EXPECT_EQ(s.result(), SC_ERROR_INVALID_INITIAL_TRANSFORMATION);
}

// --- GetStatus conventions (manual 8.10) -------------------------------------------

TEST(StatusConventions, GroupIdsSwapWithReverseFlag) {
  ThreeCubes s;
  s.update();
  ASSERT_EQ(s.count(), 3);
  for (int i = 0; i < 3; ++i) {
    SCint forward[2], backward[2];
    ASSERT_EQ(s.manager.GetStatus(SC_GROUP_ID, forward, i, false), SC_NO_ERROR);
    ASSERT_EQ(s.manager.GetStatus(SC_GROUP_ID, backward, i, true), SC_NO_ERROR);
    EXPECT_EQ(forward[0], backward[1]);
    EXPECT_EQ(forward[1], backward[0]);
    EXPECT_NE(forward[0], SC_GROUP_STATIC);  // the static group is never first
  }
}

TEST(StatusConventions, PairsAreListedByGroupIdWithTheStaticGroupSecond) {
  TestScene s;
  s.addCube(1, 2, 0.0);
  s.addCube(2, 0, 2.0);
  s.addCube(3, 1, 0.0, 2.0);
  s.addCube(4, SC_GROUP_STATIC, 2.0, 2.0);
  s.update();
  ASSERT_EQ(s.count(), 6);
  std::vector<std::pair<int, int>> keys;
  for (int i = 0; i < 6; ++i) {
    SCint g[2];
    ASSERT_EQ(s.manager.GetStatus(SC_GROUP_ID, g, i, false), SC_NO_ERROR);
    EXPECT_NE(g[0], SC_GROUP_STATIC);
    keys.emplace_back(std::min(g[0], g[1]), std::max(g[0], g[1]));
  }
  const std::vector<std::pair<int, int>> expected = {{SC_GROUP_STATIC, 0}, {SC_GROUP_STATIC, 1},
                                                     {SC_GROUP_STATIC, 2}, {0, 1},
                                                     {0, 2},               {1, 2}};
  EXPECT_EQ(keys, expected);
}

TEST(StatusConventions, ObjectAndPieceIdsSwapWithReverseFlag) {
  TestScene s;
  s.addCube(10, 0, 0.0);
  // Object 20: piece 0 far away, piece 1 at gap 1 from object 10.
  SCObject& o = s.newObject();
  const std::vector<double> far = cubeVertices(10.0, 0.0, 0.0, 1.0);
  const std::vector<double> near = cubeVertices(2.0, 0.0, 0.0, 1.0);
  ASSERT_EQ(o.AddTriangles(far.data(), 8, kCubeTriangles, 12), SC_NO_ERROR);
  ASSERT_EQ(o.AddTriangles(near.data(), 8, kCubeTriangles, 12), SC_NO_ERROR);
  s.place(20, 1, o);
  s.update();
  const Slot a = find(s.manager, 0, 1);
  const Slot b = find(s.manager, 1, 0);
  ASSERT_TRUE(a.listed && b.listed);
  EXPECT_EQ(a.index, b.index);
  EXPECT_NE(a.reverse, b.reverse);
  // Target first: object 10's piece 0 against object 20's piece 1, and back.
  expectIds(s.manager, a, SC_OBJECT_ID, {10, 20});
  expectIds(s.manager, a, SC_PIECE_ID, {0, 1});
  expectIds(s.manager, b, SC_OBJECT_ID, {20, 10});
  expectIds(s.manager, b, SC_PIECE_ID, {1, 0});
}

TEST(StatusConventions, SeparatedDirectionsReportPositiveDistanceNormalAndPoints) {
  TestScene s;
  s.addCube(1, 0, 0.0);
  s.addCube(2, 1, 2.5);  // gap 1.5 along x
  s.update();
  for (const auto& [target, sign] : {std::pair<int, double>{0, -1.0}, {1, 1.0}}) {
    const Slot slot = find(s.manager, target, 1 - target);
    ASSERT_TRUE(slot.listed);
    double d, n[3], pt[3], po[3];
    ASSERT_EQ(s.manager.GetStatus(SC_DISTANCE, &d, slot.index, slot.reverse), SC_NO_ERROR);
    ASSERT_EQ(s.manager.GetStatus(SC_CONTACT_NORMAL, n, slot.index, slot.reverse), SC_NO_ERROR);
    ASSERT_EQ(s.manager.GetStatus(SC_POINT_ON_TARGET, pt, slot.index, slot.reverse),
              SC_NO_ERROR);
    ASSERT_EQ(s.manager.GetStatus(SC_POINT_ON_OPPONENT, po, slot.index, slot.reverse),
              SC_NO_ERROR);
    EXPECT_NEAR(d, 1.5, 1e-9);
    // The normal points from the opponent towards the target.
    EXPECT_NEAR(n[0], sign, 1e-9);
    EXPECT_NEAR(n[1], 0.0, 1e-9);
    EXPECT_NEAR(n[2], 0.0, 1e-9);
    EXPECT_NEAR(pt[0], target == 0 ? 1.0 : 2.5, 1e-9);
    EXPECT_NEAR(po[0], target == 0 ? 2.5 : 1.0, 1e-9);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(pt[i] - po[i], d * n[i], 1e-9);
  }
}

TEST(StatusConventions, PenetratingDirectionReportsNegativeDistanceOfTpdvNorm) {
  TrackedScene s;
  s.enterContact();
  const Slot slot = find(s.manager, 0, SC_GROUP_STATIC);
  ASSERT_TRUE(slot.listed);
  double d, tpdv[3];
  ASSERT_EQ(s.manager.GetStatus(SC_DISTANCE, &d, slot.index, slot.reverse), SC_NO_ERROR);
  ASSERT_EQ(s.manager.GetStatus(SC_TPD_VECTOR, tpdv, slot.index, slot.reverse), SC_NO_ERROR);
  EXPECT_LT(d, 0.0);
  EXPECT_NEAR(d, -std::sqrt(tpdv[0] * tpdv[0] + tpdv[1] * tpdv[1] + tpdv[2] * tpdv[2]), 1e-12);
}

TEST(StatusConventions, DirectionBeyondMaximumDistanceReportsNoResult) {
  TestScene s;
  s.addTetra(1, 0, 0.0, 0.0, 0.0);
  // The same tetrahedron turned 180 degrees about (1,-1,0)/sqrt(2), corner at {1,1,1}:
  // slanted faces parallel and facing, 1/sqrt(3) apart, bounding boxes overlapping.
  SCObject& o = s.newObject();
  ASSERT_EQ(o.AddTriangles(kTetraVertices, 4, kTetraTriangles, 4), SC_NO_ERROR);
  const double h = std::sqrt(0.5);
  const double q[4] = {0.0, h, -h, 0.0};
  const double origin[3] = {1.0, 1.0, 1.0};
  ASSERT_EQ(o.SetTransformation(SC_ORIENTATION_QUATERNION, q), SC_NO_ERROR);
  ASSERT_EQ(o.SetTransformation(SC_POSITION_ORIGIN, origin), SC_NO_ERROR);
  s.place(2, 1, o);
  const double gap = 1.0 / std::sqrt(3.0);

  ASSERT_EQ(s.manager.SetAttributeDouble(SC_SCENE_MANAGER_MAX_DISTANCE, 1.0), SC_NO_ERROR);
  s.update();
  EXPECT_NEAR(distanceOf(s.manager, 0, 1), gap, 1e-9);
  EXPECT_NEAR(distanceOf(s.manager, 1, 0), gap, 1e-9);

  ASSERT_EQ(s.manager.SetAttributeDouble(SC_SCENE_MANAGER_MAX_DISTANCE, 0.5), SC_NO_ERROR);
  s.update();
  // Listed or not is up to the scene; if listed, both directions have no result.
  if (s.count() > 0) {
    EXPECT_EQ(resultOf(s.manager, 0, 1), SC_ERROR_NO_RESULT);
    EXPECT_EQ(resultOf(s.manager, 1, 0), SC_ERROR_NO_RESULT);
  }

  // Far beyond: the pair may be omitted; if listed it has no result either.
  s.moveGroup(1, 50.0, 0.0, 0.0);
  s.update();
  if (s.count() > 0) {
    EXPECT_EQ(resultOf(s.manager, 0, 1), SC_ERROR_NO_RESULT);
  }
}

TEST(StatusConventions, FieldOfADirectionWithoutResultReturnsItsCodeAndWritesNothing) {
  TestScene s;
  s.addCube(1, 0, 0.0);
  s.addCube(2, SC_GROUP_STATIC, 2.0);
  s.update();
  const Slot none = find(s.manager, SC_GROUP_STATIC, 0);
  ASSERT_TRUE(none.listed);
  double d = 123.0, v[4] = {5, 6, 7, 8};
  float f = 9.0f;
  SCint ids[3] = {-5, -6, -7};
  EXPECT_EQ(s.manager.GetStatus(SC_DISTANCE, &d, none.index, none.reverse), SC_ERROR_NO_RESULT);
  EXPECT_EQ(s.manager.GetStatus(SC_DISTANCE, &f, none.index, none.reverse), SC_ERROR_NO_RESULT);
  EXPECT_EQ(s.manager.GetStatus(SC_CONTACT_ORIENTATION, v, none.index, none.reverse),
            SC_ERROR_NO_RESULT);
  EXPECT_EQ(s.manager.GetStatus(SC_OBJECT_ID, ids, none.index, none.reverse),
            SC_ERROR_NO_RESULT);
  EXPECT_EQ(s.manager.GetStatus(SC_FEATURE_ON_TARGET, ids, none.index, none.reverse),
            SC_ERROR_NO_RESULT);
  EXPECT_EQ(d, 123.0);
  EXPECT_EQ(f, 9.0f);
  EXPECT_EQ(v[0], 5.0);
  EXPECT_EQ(v[3], 8.0);
  EXPECT_EQ(ids[0], -5);
  EXPECT_EQ(ids[2], -7);

  TrackedScene t;
  t.moveGroup(0, 0.0, 0.0, 0.5);
  t.update();
  const Slot invalid = find(t.manager, 0, SC_GROUP_STATIC);
  ASSERT_TRUE(invalid.listed);
  EXPECT_EQ(t.manager.GetStatus(SC_TPD_VECTOR, v, invalid.index, invalid.reverse),
            SC_ERROR_INVALID_INITIAL_TRANSFORMATION);
  EXPECT_EQ(t.manager.GetStatus(SC_PIECE_ID, ids, invalid.index, invalid.reverse),
            SC_ERROR_INVALID_INITIAL_TRANSFORMATION);
  EXPECT_EQ(v[0], 5.0);
  EXPECT_EQ(ids[0], -5);
}

}  // namespace
