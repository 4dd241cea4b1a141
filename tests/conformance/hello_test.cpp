// SPDX-License-Identifier: MIT
// Manual 10.2 (HelloSmartCollision, List 10-1) through sc.h only: the distance and
// the dynamic penetration depth of two unit-corner tetrahedra, and the contact data.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sc.h"

namespace {

// List 10-1: the unit-corner tetrahedron, outward winding.
const double kVertices[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
const int kTriangles[12] = {0, 2, 1, 1, 3, 0, 0, 3, 2, 1, 2, 3};
constexpr int kControlledGroup = 0;

double norm3(const double* v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

/// The scene of List 10-1: object 1000 in the controlled group, 2000 static.
struct HelloScene {
  SCSceneManager manager{SC_SCENE_MANAGER_CLOSED_POLYHEDRA};
  SCObject object1{SC_OBJECT_TYPE_CLOSED_POLYHEDRON};
  SCObject object2{SC_OBJECT_TYPE_CLOSED_POLYHEDRON};

  HelloScene() {
    EXPECT_EQ(object1.AddTriangles(kVertices, 4, kTriangles, 4), SC_NO_ERROR);
    EXPECT_EQ(object2.AddTriangles(kVertices, 4, kTriangles, 4), SC_NO_ERROR);
    EXPECT_EQ(manager.SetAttributeDouble(SC_SCENE_MANAGER_MAX_DISTANCE, 10.0), SC_NO_ERROR);
    EXPECT_EQ(manager.SetAttributeDouble(SC_SCENE_MANAGER_TOLERANCE, 0.1), SC_NO_ERROR);
    EXPECT_EQ(manager.SetAttributeInteger(SC_SCENE_MANAGER_MAX_ITERATION, 10), SC_NO_ERROR);
    EXPECT_EQ(manager.AddObject(1000, &object1), SC_NO_ERROR);
    EXPECT_EQ(manager.AddObject(2000, &object2), SC_NO_ERROR);
    EXPECT_EQ(manager.AddObjectToGroup(kControlledGroup, 1000), SC_NO_ERROR);
  }

  void moveTo(SCenum type, const double* position) {
    ASSERT_EQ(manager.SetTransformation(kControlledGroup, type, position), SC_NO_ERROR);
    ASSERT_EQ(manager.UpdateStatus(), SC_NO_ERROR);
  }

  /// The only pair, read with the controlled group as target (List 10-1's loop).
  bool controlledDirection(int& index, bool& reverse) {
    SCint count = -1;
    EXPECT_EQ(manager.GetStatus(SC_STATUS_COUNT, &count), SC_NO_ERROR);
    EXPECT_EQ(count, 1);
    if (count != 1) return false;
    SCint gids[2] = {-7, -7};
    EXPECT_EQ(manager.GetStatus(SC_GROUP_ID, gids, 0, false), SC_NO_ERROR);
    // The static group is never first when reverseFlag is false (manual 8.10).
    EXPECT_EQ(gids[0], kControlledGroup);
    EXPECT_EQ(gids[1], SC_GROUP_STATIC);
    index = 0;
    reverse = gids[0] != kControlledGroup;
    return true;
  }

  /// List 10-1's path: apart at origin (1, 1, 1), then pressed in at (0, 0, 0.5).
  void pressIn() {
    const double position1[3] = {1.0, 1.0, 1.0};
    const double position2[3] = {0.0, 0.0, 0.5};
    moveTo(SC_POSITION_ORIGIN, position1);
    moveTo(SC_POSITION_ORIGIN, position2);
  }

  /// Reads `field` of the controlled direction into `out` (double or float).
  template <class Value>
  void read(SCenum field, Value* out) {
    int index = 0;
    bool reverse = false;
    ASSERT_TRUE(controlledDirection(index, reverse));
    ASSERT_EQ(manager.GetStatus(field, out, index, reverse), SC_NO_ERROR);
  }

  /// The controlled direction's distance; NaN, with a failure, unless its result is Ok.
  double controlledDistance() {
    int index = 0;
    bool reverse = false;
    if (!controlledDirection(index, reverse)) return std::nan("");
    SCint result = -1;
    EXPECT_EQ(manager.GetStatus(SC_STATUS_RESULT, &result, index, reverse), SC_NO_ERROR);
    EXPECT_EQ(result, SC_NO_ERROR);
    double distance = std::nan("");
    EXPECT_EQ(manager.GetStatus(SC_DISTANCE, &distance, index, reverse), SC_NO_ERROR);
    return result == SC_NO_ERROR ? distance : std::nan("");
  }
};

TEST(HelloSmartCollision, DistanceAtOneOneOneIsSqrtFourThirds) {
  HelloScene hello;
  const double position1[3] = {1.0, 1.0, 1.0};
  hello.moveTo(SC_POSITION_ORIGIN, position1);
  EXPECT_NEAR(hello.controlledDistance(), std::sqrt(4.0 / 3.0), 1e-9);
  // The closest points: the controlled tetrahedron's corner {1,1,1} and the centre
  // {1/3,1/3,1/3} of the static tetrahedron's slanted face.
  double on_target[3], on_opponent[3], normal[3];
  hello.read(SC_POINT_ON_TARGET, on_target);
  hello.read(SC_POINT_ON_OPPONENT, on_opponent);
  hello.read(SC_CONTACT_NORMAL, normal);
  const double k = 1.0 / std::sqrt(3.0);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(on_target[i], 1.0, 1e-9);
    EXPECT_NEAR(on_opponent[i], 1.0 / 3.0, 1e-9);
    EXPECT_NEAR(normal[i], k, 1e-9);
  }
  // The float overload reads the same result.
  float distance_f = 0.0f;
  hello.read(SC_DISTANCE, &distance_f);
  EXPECT_NEAR(distance_f, std::sqrt(4.0 / 3.0), 1e-6);
}

TEST(HelloSmartCollision, PenetrationDepthAtHalfZIsSqrtOneTwelfth) {
  HelloScene hello;
  hello.pressIn();
  EXPECT_NEAR(hello.controlledDistance(), -std::sqrt(1.0 / 12.0), 1e-9);
}

TEST(HelloSmartCollision, ContactDataOfThePenetrationIsConsistent) {
  HelloScene hello;
  hello.pressIn();
  double normal[3], tpdv[3], contact[3], center[3];
  hello.read(SC_CONTACT_NORMAL, normal);
  hello.read(SC_TPD_VECTOR, tpdv);
  hello.read(SC_CONTACT_POSITION, contact);
  ASSERT_EQ(hello.manager.GetTransformation(kControlledGroup, SC_POSITION_WORLD_CENTER, center),
            SC_NO_ERROR);
  EXPECT_NEAR(norm3(normal), 1.0, 1e-12);
  EXPECT_NEAR(norm3(tpdv), std::sqrt(1.0 / 12.0), 1e-9);
  // The unique shortest way out is along the static tetrahedron's slanted face normal:
  // the contact normal is (1,1,1)/sqrt(3) and the TPDV its opposite times the depth.
  const double k = 1.0 / std::sqrt(3.0);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(normal[i], k, 1e-9);
    EXPECT_NEAR(tpdv[i], -1.0 / 6.0, 1e-9);
    EXPECT_NEAR(contact[i], center[i] - tpdv[i], 1e-12);
  }
  // RPDV vanishes: the rotation mode INPUT follows the (unchanged) input orientation.
  double rpdv[3];
  hello.read(SC_RPD_VECTOR, rpdv);
  EXPECT_LE(norm3(rpdv), 1e-12);
}

TEST(HelloSmartCollision, TargetPlacedAtContactPositionTouchesWithinTolerance) {
  HelloScene hello;
  hello.pressIn();
  double contact[3], normal[3];
  hello.read(SC_CONTACT_POSITION, contact);
  hello.read(SC_CONTACT_NORMAL, normal);

  // A fresh scene approaches the contact position from outside along the normal, so
  // the pair is tracked and a slight overlap would show as a small negative depth.
  HelloScene fresh;
  const double apart[3] = {contact[0] + normal[0], contact[1] + normal[1],
                           contact[2] + normal[2]};
  fresh.moveTo(SC_POSITION_WORLD_CENTER, apart);
  fresh.moveTo(SC_POSITION_WORLD_CENTER, contact);
  const double distance = fresh.controlledDistance();
  const double tolerance = 0.1;  // set by List 10-1
  EXPECT_LE(std::abs(distance), tolerance);
  RecordProperty("distance_at_contact", std::to_string(distance));
}

}  // namespace
