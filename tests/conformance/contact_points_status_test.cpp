// SPDX-License-Identifier: MIT
// The contact-points extension through sc.h: SC_SCENE_MANAGER_CONTACT_POINTS,
// SC_CONTACT_POINT_COUNT and SC_CONTACT_POINTS (10 reals per contact).
#include <gtest/gtest.h>

#include <vector>

#include "sc.h"

namespace {

// A unit cube [0,1]^3, outward winding.
const double kCube[24] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1};
const int kCubeTriangles[36] = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                                2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};

/// Cube 1 in group 1 above static cube 2, moved down into it by 0.05.
struct PressedCubes {
  SCSceneManager manager{SC_SCENE_MANAGER_CLOSED_POLYHEDRA};
  SCObject top{SC_OBJECT_TYPE_CLOSED_POLYHEDRON};
  SCObject bottom{SC_OBJECT_TYPE_CLOSED_POLYHEDRON};

  explicit PressedCubes(bool contact_points) {
    EXPECT_EQ(top.AddTriangles(kCube, 8, kCubeTriangles, 12), SC_NO_ERROR);
    EXPECT_EQ(bottom.AddTriangles(kCube, 8, kCubeTriangles, 12), SC_NO_ERROR);
    EXPECT_EQ(manager.SetAttributeInteger(SC_SCENE_MANAGER_CONTACT_POINTS, contact_points ? 1 : 0),
              SC_NO_ERROR);
    EXPECT_EQ(manager.AddObject(1, &top), SC_NO_ERROR);
    EXPECT_EQ(manager.AddObject(2, &bottom), SC_NO_ERROR);
    EXPECT_EQ(manager.AddObjectToGroup(1, 1), SC_NO_ERROR);
    const double above[3] = {0.2, 0.1, 1.01};
    EXPECT_EQ(manager.SetTransformation(1, SC_POSITION_ORIGIN, above), SC_NO_ERROR);
    EXPECT_EQ(manager.UpdateStatus(), SC_NO_ERROR);
    const double pressed[3] = {0.2, 0.1, 0.95};
    EXPECT_EQ(manager.SetTransformation(1, SC_POSITION_ORIGIN, pressed), SC_NO_ERROR);
    EXPECT_EQ(manager.UpdateStatus(), SC_NO_ERROR);
  }
};

TEST(ContactPointsStatus, AttributeTakesZeroOrOneOnly) {
  SCSceneManager manager{SC_SCENE_MANAGER_CLOSED_POLYHEDRA};
  SCint value = -1;
  ASSERT_EQ(manager.GetAttributeInteger(SC_SCENE_MANAGER_CONTACT_POINTS, &value), SC_NO_ERROR);
  EXPECT_EQ(value, 0);
  EXPECT_EQ(manager.SetAttributeInteger(SC_SCENE_MANAGER_CONTACT_POINTS, 2),
            SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(manager.SetAttributeInteger(SC_SCENE_MANAGER_CONTACT_POINTS, 1), SC_NO_ERROR);
  ASSERT_EQ(manager.GetAttributeInteger(SC_SCENE_MANAGER_CONTACT_POINTS, &value), SC_NO_ERROR);
  EXPECT_EQ(value, 1);
  EXPECT_EQ(manager.SetAttributeInteger(SC_SCENE_MANAGER_RESOLVE_INITIAL_INTERSECTION, -1),
            SC_ERROR_INVALID_ARGUMENT);
}

TEST(ContactPointsStatus, OffListsNoContact) {
  PressedCubes s(false);
  SCint count = -1;
  ASSERT_EQ(s.manager.GetStatus(SC_CONTACT_POINT_COUNT, &count, 0, false), SC_NO_ERROR);
  EXPECT_EQ(count, 0);
}

TEST(ContactPointsStatus, OnListsTheContactOfBothDirections) {
  PressedCubes s(true);
  for (bool reverse : {false, true}) {
    SCint count = -1;
    ASSERT_EQ(s.manager.GetStatus(SC_CONTACT_POINT_COUNT, &count, 0, reverse), SC_NO_ERROR);
    // The static group is no target (Table 8-1): only group 1's direction has points.
    if (reverse) {
      EXPECT_EQ(count, 0);
      continue;
    }
    ASSERT_EQ(count, 1);  // two convex cubes: one leaf pair
    double distance = 0.0, normal[3];
    ASSERT_EQ(s.manager.GetStatus(SC_DISTANCE, &distance, 0, reverse), SC_NO_ERROR);
    ASSERT_EQ(s.manager.GetStatus(SC_CONTACT_NORMAL, normal, 0, reverse), SC_NO_ERROR);
    EXPECT_NEAR(distance, -0.05, 1e-3);
    std::vector<double> points(10 * count);
    ASSERT_EQ(s.manager.GetStatus(SC_CONTACT_POINTS, points.data(), 0, reverse), SC_NO_ERROR);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(points[6 + i], normal[i], 1e-9);
    EXPECT_NEAR(points[9], distance, 1e-3);          // separation at the current pose
    EXPECT_NEAR(points[2], 0.95, 1e-3);              // on the top cube's bottom face
    EXPECT_NEAR(points[5], 1.0, 1e-3);               // on the bottom cube's top face
    std::vector<float> points_f(10 * count);
    ASSERT_EQ(s.manager.GetStatus(SC_CONTACT_POINTS, points_f.data(), 0, reverse), SC_NO_ERROR);
    EXPECT_NEAR(points_f[9], distance, 1e-3);
  }
}

// Set down exactly flush (distance 0, SC_DIRECTION_TOUCHING), first seen or followed
// there: the contact of the two faces, on the bottom cube's top face.
TEST(ContactPointsStatus, TouchingAtDistanceZeroListsItsContact) {
  for (const bool followed : {false, true}) {
    SCOPED_TRACE(followed ? "followed from above" : "first seen");
    PressedCubes s(true);
    const double above[3] = {0.2, 0.1, 1.5}, flush[3] = {0.2, 0.1, 1.0};
    ASSERT_EQ(s.manager.SetTransformation(1, SC_POSITION_ORIGIN, above), SC_NO_ERROR);
    ASSERT_EQ(s.manager.UpdateStatus(), SC_NO_ERROR);
    // INACTIVE, moved, ACTIVE: a teleport, the pair is first seen flush.
    if (!followed) {
      ASSERT_EQ(s.manager.SetActivityGroup(1, SC_ACTIVITY_INACTIVE), SC_NO_ERROR);
    }
    ASSERT_EQ(s.manager.SetTransformation(1, SC_POSITION_ORIGIN, flush), SC_NO_ERROR);
    if (!followed) {
      ASSERT_EQ(s.manager.SetActivityGroup(1, SC_ACTIVITY_ACTIVE), SC_NO_ERROR);
    }
    ASSERT_EQ(s.manager.UpdateStatus(), SC_NO_ERROR);
    SCint status = -1, count = -1;
    ASSERT_EQ(s.manager.GetStatus(SC_DIRECTION_STATUS, &status, 0, false), SC_NO_ERROR);
    // Followed, the proxy may stop a rounding short of flush: a depth of ~1e-13.
    if (followed) {
      EXPECT_TRUE(status == SC_DIRECTION_TOUCHING || status == SC_DIRECTION_PENETRATING);
    } else {
      EXPECT_EQ(status, SC_DIRECTION_TOUCHING);
    }
    ASSERT_EQ(s.manager.GetStatus(SC_CONTACT_POINT_COUNT, &count, 0, false), SC_NO_ERROR);
    ASSERT_EQ(count, 1);
    double distance = -1.0, p[10];
    ASSERT_EQ(s.manager.GetStatus(SC_DISTANCE, &distance, 0, false), SC_NO_ERROR);
    EXPECT_NEAR(distance, 0.0, 1e-9);
    ASSERT_EQ(s.manager.GetStatus(SC_CONTACT_POINTS, p, 0, false), SC_NO_ERROR);
    EXPECT_NEAR(p[2], 1.0, 1e-9);  // on the top cube's bottom face
    EXPECT_NEAR(p[5], 1.0, 1e-9);  // on the bottom cube's top face
    EXPECT_NEAR(p[8], 1.0, 1e-9);  // normal +z
    EXPECT_NEAR(p[9], 0.0, 1e-9);  // separation
    EXPECT_TRUE(p[3] >= 0.2 - 1e-9 && p[3] <= 1.0 + 1e-9 && p[4] >= 0.1 - 1e-9 &&
                p[4] <= 1.0 + 1e-9);
  }
}

// SC_DIRECTION_STATUS (extension): the pressed cube penetrates; above the other cube
// it is separated; set down within the tolerance (1e-3) of it, it touches; the static
// group's direction is not computed. (Exactly flush, distance 0 and no depth: the
// unit test of DirectedResult::status.)
TEST(DirectionStatus, TellsTouchingFromPenetrating) {
  PressedCubes s(false);
  SCint status = -1;
  ASSERT_EQ(s.manager.GetStatus(SC_DIRECTION_STATUS, &status, 0, false), SC_NO_ERROR);
  EXPECT_EQ(status, SC_DIRECTION_PENETRATING);
  const double above[3] = {0.2, 0.1, 1.5};
  ASSERT_EQ(s.manager.SetTransformation(1, SC_POSITION_ORIGIN, above), SC_NO_ERROR);
  ASSERT_EQ(s.manager.UpdateStatus(), SC_NO_ERROR);
  ASSERT_EQ(s.manager.GetStatus(SC_DIRECTION_STATUS, &status, 0, false), SC_NO_ERROR);
  EXPECT_EQ(status, SC_DIRECTION_SEPARATED);
  const double resting[3] = {0.2, 0.1, 1.0002};
  ASSERT_EQ(s.manager.SetTransformation(1, SC_POSITION_ORIGIN, resting), SC_NO_ERROR);
  ASSERT_EQ(s.manager.UpdateStatus(), SC_NO_ERROR);
  ASSERT_EQ(s.manager.GetStatus(SC_DIRECTION_STATUS, &status, 0, false), SC_NO_ERROR);
  EXPECT_EQ(status, SC_DIRECTION_TOUCHING);
  double distance = 1.0;
  ASSERT_EQ(s.manager.GetStatus(SC_DISTANCE, &distance, 0, false), SC_NO_ERROR);
  EXPECT_NEAR(distance, 2e-4, 1e-9);
  ASSERT_EQ(s.manager.GetStatus(SC_DIRECTION_STATUS, &status, 0, true), SC_NO_ERROR);
  EXPECT_EQ(status, SC_DIRECTION_NOT_COMPUTED);
  float wrong = 0;
  EXPECT_EQ(s.manager.GetStatus(SC_DIRECTION_STATUS, &wrong, 0, false), SC_ERROR_INVALID_ARGUMENT);
}

}  // namespace
