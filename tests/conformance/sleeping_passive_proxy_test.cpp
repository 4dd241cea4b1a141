// SPDX-License-Identifier: MIT
// Through sc.h only: a SLEEPING target keeps its penetration proxy, a PASSIVE one
// drops it, shown on a path-dependent depth (a small cube pushed deep into a big one).
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <vector>

#include "cube.h"
#include "sc.h"

namespace {

using sc_conformance::cubeVertices;
using sc_conformance::kCubeTriangles;

constexpr int kGroup = 0;
constexpr double kBig = 2.0;    // static cube [0, 2]^3
constexpr double kSmall = 0.2;  // group 0's cube, lower corner at its origin

/// Group 0's cube (x, y over the big cube's middle) pushed down through the top face
/// of a static cube, past the middle: the path-dependent depth (from the top) is far
/// larger than the global one (through the bottom).
struct DeepScene {
  SCSceneManager manager{SC_SCENE_MANAGER_CLOSED_POLYHEDRA};
  SCObject big{SC_OBJECT_TYPE_CLOSED_POLYHEDRON};
  SCObject small{SC_OBJECT_TYPE_CLOSED_POLYHEDRON};

  DeepScene() {
    const std::vector<double> vb = cubeVertices(0, 0, 0, kBig), vs = cubeVertices(0, 0, 0, kSmall);
    EXPECT_EQ(big.AddTriangles(vb.data(), 8, kCubeTriangles, 12), SC_NO_ERROR);
    EXPECT_EQ(small.AddTriangles(vs.data(), 8, kCubeTriangles, 12), SC_NO_ERROR);
    EXPECT_EQ(manager.AddObject(1, &big), SC_NO_ERROR);
    EXPECT_EQ(manager.AddObject(2, &small), SC_NO_ERROR);
    EXPECT_EQ(manager.AddObjectToGroup(kGroup, 2), SC_NO_ERROR);
  }

  void moveTo(double z) {
    const double origin[3] = {0.9, 0.9, z};
    EXPECT_EQ(manager.SetTransformation(kGroup, SC_POSITION_ORIGIN, origin), SC_NO_ERROR);
  }
  void update() { EXPECT_EQ(manager.UpdateStatus(), SC_NO_ERROR); }
  /// Frames from above the big cube down to z (the small cube's lower face).
  void pushDownTo(double z) {
    for (double at = kBig + 0.3; at > z + 1e-12; at -= 0.25) {
      moveTo(at);
      update();
    }
    moveTo(z);
    update();
  }
  void setActivity(SCenum activity) {
    EXPECT_EQ(manager.SetActivityGroup(kGroup, activity), SC_NO_ERROR);
  }
  int count() {
    SCint n = -1;
    EXPECT_EQ(manager.GetStatus(SC_STATUS_COUNT, &n), SC_NO_ERROR);
    return n;
  }
};

/// What the status list says about group 0 -> static.
struct Reading {
  SCint result = -1;
  double distance = 0.0;
  std::array<double, 3> tpdv{}, contact_position{}, normal{};
};

Reading read(DeepScene& s) {
  Reading r;
  EXPECT_EQ(s.count(), 1);
  SCint ids[2] = {-7, -7};
  EXPECT_EQ(s.manager.GetStatus(SC_GROUP_ID, ids, 0, false), SC_NO_ERROR);
  EXPECT_EQ(ids[0], kGroup);
  EXPECT_EQ(ids[1], SC_GROUP_STATIC);
  EXPECT_EQ(s.manager.GetStatus(SC_STATUS_RESULT, &r.result, 0, false), SC_NO_ERROR);
  if (r.result != SC_NO_ERROR) return r;
  EXPECT_EQ(s.manager.GetStatus(SC_DISTANCE, &r.distance, 0, false), SC_NO_ERROR);
  EXPECT_EQ(s.manager.GetStatus(SC_TPD_VECTOR, r.tpdv.data(), 0, false), SC_NO_ERROR);
  EXPECT_EQ(s.manager.GetStatus(SC_CONTACT_POSITION, r.contact_position.data(), 0, false),
            SC_NO_ERROR);
  EXPECT_EQ(s.manager.GetStatus(SC_CONTACT_NORMAL, r.normal.data(), 0, false), SC_NO_ERROR);
  return r;
}

void expectSame(const Reading& a, const Reading& b) {
  EXPECT_EQ(a.result, b.result);
  EXPECT_EQ(a.distance, b.distance);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(a.tpdv[k], b.tpdv[k]);
    EXPECT_EQ(a.contact_position[k], b.contact_position[k]);
    EXPECT_EQ(a.normal[k], b.normal[k]);
  }
}

TEST(SleepingPassiveProxy, PathDependentDepthFollowsThePushFromTheTop) {
  DeepScene s;
  s.pushDownTo(0.3);
  const Reading r = read(s);
  ASSERT_EQ(r.result, SC_NO_ERROR);
  // Pushed out through the top face (z = 2): depth 1.7, not the global 0.5.
  EXPECT_NEAR(r.distance, -(kBig - 0.3), 1e-9);
  EXPECT_NEAR(r.contact_position[2], kBig, 1e-9);
  EXPECT_NEAR(r.normal[2], 1.0, 1e-9);
}

TEST(SleepingPassiveProxy, SleepingKeepsTheContactConfiguration) {
  DeepScene reference;  // stays ACTIVE throughout
  reference.pushDownTo(0.3);
  reference.moveTo(0.2);
  reference.update();
  const Reading expected = read(reference);
  ASSERT_EQ(expected.result, SC_NO_ERROR);
  EXPECT_NEAR(expected.distance, -(kBig - 0.2), 1e-9);

  DeepScene s;
  s.pushDownTo(0.3);
  s.setActivity(SC_ACTIVITY_SLEEPING);
  s.update();
  EXPECT_EQ(s.count(), 0);  // a sleeping target against the static group: not computed
  s.moveTo(0.2);            // moved while asleep
  s.update();
  EXPECT_EQ(s.count(), 0);
  s.setActivity(SC_ACTIVITY_ACTIVE);
  s.update();
  const Reading r = read(s);
  ASSERT_EQ(r.result, SC_NO_ERROR);
  // The same contact as if it had never slept: still pushed out through the top.
  expectSame(r, expected);
  EXPECT_NEAR(r.contact_position[2], kBig, 1e-9);
}

TEST(SleepingPassiveProxy, PassiveDropsTheProxyAndTrackingRestarts) {
  DeepScene s;
  s.pushDownTo(0.3);
  s.setActivity(SC_ACTIVITY_PASSIVE);
  s.update();
  EXPECT_EQ(s.count(), 0);
  s.moveTo(0.2);
  s.update();
  s.setActivity(SC_ACTIVITY_ACTIVE);
  s.update();
  // No proxy: first seen intersecting.
  EXPECT_EQ(read(s).result, SC_ERROR_INVALID_INITIAL_TRANSFORMATION);
  // Seen apart below the big cube, then back at the same pose in one frame: the
  // depth now comes from the bottom (0.4), the push from the top is forgotten.
  s.moveTo(-0.5);
  s.update();
  Reading r = read(s);
  ASSERT_EQ(r.result, SC_NO_ERROR);
  EXPECT_NEAR(r.distance, 0.5 - kSmall, 1e-9);
  s.moveTo(0.2);
  s.update();
  r = read(s);
  ASSERT_EQ(r.result, SC_NO_ERROR);
  EXPECT_NEAR(r.distance, -(0.2 + kSmall), 1e-9);
  EXPECT_NEAR(r.contact_position[2], -kSmall, 1e-9);
  EXPECT_NEAR(r.normal[2], -1.0, 1e-9);
}

}  // namespace
