// SPDX-License-Identifier: MIT
// Misuse of the sc.h scene API (docs/sc-api.md, SCSceneManager): one test per kind of
// misuse, each checking the returned code and that the scene is unchanged afterwards.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "cube.h"
#include "sc.h"

namespace {

using sc_conformance::cubeVertices;
using sc_conformance::kCubeTriangles;

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();
constexpr SCenum kBogusEnum = 0x7777;

std::unique_ptr<SCObject> makeCube(double x, double y, double z,
                                   SCenum type = SC_OBJECT_TYPE_CLOSED_POLYHEDRON) {
  auto o = std::make_unique<SCObject>(type);
  const std::vector<double> v = cubeVertices(x, y, z);
  EXPECT_EQ(o->AddTriangles(v.data(), 8, kCubeTriangles, 12), SC_NO_ERROR);
  return o;
}

/// Everything observable about a scene after an UpdateStatus, as one flat list:
/// attributes, group transformations, and every listed pair's ids and results.
std::vector<double> snapshot(SCSceneManager& m) {
  std::vector<double> s;
  EXPECT_EQ(m.UpdateStatus(), SC_NO_ERROR);
  for (SCenum a : {SC_SCENE_MANAGER_MAX_DISTANCE, SC_SCENE_MANAGER_TOLERANCE,
                   SC_SCENE_MANAGER_SAFETY_COEFFICIENT, SC_SCENE_MANAGER_FORCE_STIFFNESS,
                   SC_SCENE_MANAGER_TORQUE_STIFFNESS}) {
    double v = kNaN;
    EXPECT_EQ(m.GetAttributeDouble(a, &v), SC_NO_ERROR);
    s.push_back(v);
  }
  SCint iterations = -1, mode = -1;
  EXPECT_EQ(m.GetAttributeInteger(SC_SCENE_MANAGER_MAX_ITERATION, &iterations), SC_NO_ERROR);
  EXPECT_EQ(m.GetAttributeEnum(SC_SCENE_MANAGER_ROTATION_MODE, &mode), SC_NO_ERROR);
  s.push_back(iterations);
  s.push_back(mode);
  for (SCint gid : {0, 1}) {
    double m16[16];
    const SCint rc = m.GetTransformation(gid, SC_TRANSFORMATION_MATRIX, m16);
    s.push_back(rc);
    if (rc == SC_NO_ERROR) s.insert(s.end(), m16, m16 + 16);
  }
  SCint count = -1;
  EXPECT_EQ(m.GetStatus(SC_STATUS_COUNT, &count), SC_NO_ERROR);
  s.push_back(count);
  for (int i = 0; i < count; ++i) {
    for (bool reverse : {false, true}) {
      SCint g[2], r, o[2], p[2];
      EXPECT_EQ(m.GetStatus(SC_GROUP_ID, g, i, reverse), SC_NO_ERROR);
      EXPECT_EQ(m.GetStatus(SC_STATUS_RESULT, &r, i, reverse), SC_NO_ERROR);
      s.insert(s.end(), {double(g[0]), double(g[1]), double(r)});
      if (r != SC_NO_ERROR) continue;
      double d, n[3];
      EXPECT_EQ(m.GetStatus(SC_OBJECT_ID, o, i, reverse), SC_NO_ERROR);
      EXPECT_EQ(m.GetStatus(SC_PIECE_ID, p, i, reverse), SC_NO_ERROR);
      EXPECT_EQ(m.GetStatus(SC_DISTANCE, &d, i, reverse), SC_NO_ERROR);
      EXPECT_EQ(m.GetStatus(SC_CONTACT_NORMAL, n, i, reverse), SC_NO_ERROR);
      s.insert(s.end(), {double(o[0]), double(o[1]), double(p[0]), double(p[1]), d, n[0], n[1],
                         n[2]});
    }
  }
  return s;
}

/// Outputs of calls that must fail: each keeps its -3 (they write nothing on error).
struct Outputs {
  SCint i = -3;
  SCenum e = -3;
  float f = -3.0f;
  double d = -3.0;
  void expectUntouched() const {
    EXPECT_EQ(i, -3);
    EXPECT_EQ(e, -3);
    EXPECT_EQ(f, -3.0f);
    EXPECT_EQ(d, -3.0);
  }
};

/// Group 0 (object 1) and group 1 (object 2) one apart along x, object 3 static
/// above group 0: three pairs, (0,1) both ways, each group -> static.
struct Baseline {
  SCSceneManager manager{SC_SCENE_MANAGER_CLOSED_POLYHEDRA};
  std::unique_ptr<SCObject> o1 = makeCube(0.0, 0.0, 0.0);
  std::unique_ptr<SCObject> o2 = makeCube(2.0, 0.0, 0.0);
  std::unique_ptr<SCObject> o3 = makeCube(0.0, 3.0, 0.0);
  std::vector<double> before;

  Baseline() {
    EXPECT_EQ(manager.AddObject(1, o1.get()), SC_NO_ERROR);
    EXPECT_EQ(manager.AddObject(2, o2.get()), SC_NO_ERROR);
    EXPECT_EQ(manager.AddObject(3, o3.get()), SC_NO_ERROR);
    EXPECT_EQ(manager.AddObjectToGroup(0, 1), SC_NO_ERROR);
    EXPECT_EQ(manager.AddObjectToGroup(1, 2), SC_NO_ERROR);
    before = snapshot(manager);
    SCint count = -1;
    EXPECT_EQ(manager.GetStatus(SC_STATUS_COUNT, &count), SC_NO_ERROR);
    EXPECT_EQ(count, 3);
  }

  void expectUnchanged() { EXPECT_EQ(snapshot(manager), before); }
};

TEST(SceneMisuse, DuplicateObjectIdIsInvalidId) {
  Baseline b;
  auto other = makeCube(1.2, 0.0, 0.0);  // would change every distance if added
  EXPECT_EQ(b.manager.AddObject(1, other.get()), SC_ERROR_INVALID_ID);
  EXPECT_EQ(b.manager.AddObject(3, other.get()), SC_ERROR_INVALID_ID);
  b.expectUnchanged();
  // `other` is in no scene: its own transformation can still be set.
  const double origin[3] = {0.0, 0.0, 0.0};
  EXPECT_EQ(other->SetTransformation(SC_POSITION_ORIGIN, origin), SC_NO_ERROR);
}

TEST(SceneMisuse, UnknownObjectIdIsInvalidId) {
  Baseline b;
  EXPECT_EQ(b.manager.DeleteObject(99), SC_ERROR_INVALID_ID);
  EXPECT_EQ(b.manager.AddObjectToGroup(0, 99), SC_ERROR_INVALID_ID);
  EXPECT_EQ(b.manager.AddObjectToGroup(5, 99), SC_ERROR_INVALID_ID);
  EXPECT_EQ(b.manager.SetActivityObject(99, SC_ACTIVITY_INACTIVE), SC_ERROR_INVALID_ID);
  EXPECT_EQ(b.manager.DeleteObjectFromGroup(0, 99), SC_ERROR_INVALID_ID);
  b.expectUnchanged();
  // A failed AddObjectToGroup(5, ...) must not have created group 5.
  EXPECT_EQ(b.manager.SetActivityGroup(5, SC_ACTIVITY_ACTIVE), SC_ERROR_INVALID_ID);
}

TEST(SceneMisuse, UnknownGroupIdIsInvalidId) {
  Baseline b;
  const double pos[3] = {9.0, 9.0, 9.0};
  const float pos_f[3] = {9.0f, 9.0f, 9.0f};
  double got[3] = {-1.0, -2.0, -3.0};
  float got_f[3] = {-1.0f, -2.0f, -3.0f};
  EXPECT_EQ(b.manager.SetTransformation(7, SC_POSITION_ORIGIN, pos), SC_ERROR_INVALID_ID);
  EXPECT_EQ(b.manager.SetTransformation(7, SC_POSITION_ORIGIN, pos_f), SC_ERROR_INVALID_ID);
  EXPECT_EQ(b.manager.GetTransformation(7, SC_POSITION_ORIGIN, got), SC_ERROR_INVALID_ID);
  EXPECT_EQ(b.manager.GetTransformation(7, SC_POSITION_ORIGIN, got_f), SC_ERROR_INVALID_ID);
  EXPECT_EQ(got[0], -1.0);
  EXPECT_EQ(got_f[2], -3.0f);
  EXPECT_EQ(b.manager.SetActivityGroup(7, SC_ACTIVITY_ACTIVE), SC_ERROR_INVALID_ID);
  EXPECT_EQ(b.manager.SetActivityPair(0, 7, SC_ACTIVITY_INACTIVE), SC_ERROR_INVALID_ID);
  EXPECT_EQ(b.manager.SetActivityPair(7, 0, SC_ACTIVITY_INACTIVE), SC_ERROR_INVALID_ID);
  EXPECT_EQ(b.manager.SetActivityPair(7, 8, SC_ACTIVITY_ONE_WAY_ACTIVE), SC_ERROR_INVALID_ID);
  b.expectUnchanged();
}

TEST(SceneMisuse, GroupWhoseLastObjectLeftIsUnknown) {
  Baseline b;
  ASSERT_EQ(b.manager.DeleteObjectFromGroup(1, 2), SC_NO_ERROR);
  const std::vector<double> after_removal = snapshot(b.manager);
  const double pos[3] = {9.0, 9.0, 9.0};
  double got[3] = {-1.0, -2.0, -3.0};
  EXPECT_EQ(b.manager.SetTransformation(1, SC_POSITION_ORIGIN, pos), SC_ERROR_INVALID_ID);
  EXPECT_EQ(b.manager.GetTransformation(1, SC_POSITION_ORIGIN, got), SC_ERROR_INVALID_ID);
  EXPECT_EQ(b.manager.SetActivityGroup(1, SC_ACTIVITY_ACTIVE), SC_ERROR_INVALID_ID);
  EXPECT_EQ(b.manager.SetActivityPair(0, 1, SC_ACTIVITY_ACTIVE), SC_ERROR_INVALID_ID);
  EXPECT_EQ(got[0], -1.0);
  EXPECT_EQ(snapshot(b.manager), after_removal);
}

TEST(SceneMisuse, RemovingAnObjectFromAGroupItIsNotInIsInvalidId) {
  Baseline b;
  EXPECT_EQ(b.manager.DeleteObjectFromGroup(1, 1), SC_ERROR_INVALID_ID);  // 1 is in group 0
  EXPECT_EQ(b.manager.DeleteFromGroup(1, 1), SC_ERROR_INVALID_ID);
  EXPECT_EQ(b.manager.DeleteObjectFromGroup(0, 3), SC_ERROR_INVALID_ID);  // 3 is static
  EXPECT_EQ(b.manager.DeleteObjectFromGroup(9, 1), SC_ERROR_INVALID_ID);  // no group 9
  b.expectUnchanged();
}

TEST(SceneMisuse, AddingTheSameObjectTwiceFails) {
  Baseline b;
  EXPECT_NE(b.manager.AddObject(50, b.o1.get()), SC_NO_ERROR);
  b.expectUnchanged();
  EXPECT_EQ(b.manager.DeleteObject(50), SC_ERROR_INVALID_ID);  // 50 was never added
  // Nor can an object be in two scenes.
  SCSceneManager second(SC_SCENE_MANAGER_CLOSED_POLYHEDRA);
  EXPECT_NE(second.AddObject(1, b.o1.get()), SC_NO_ERROR);
  b.expectUnchanged();
}

TEST(SceneMisuse, ObjectOfAnotherTypeThanTheSceneIsInvalidOperation) {
  Baseline b;
  auto soup = makeCube(1.2, 0.0, 0.0, SC_OBJECT_TYPE_TRIANGLE_SOUP);
  EXPECT_EQ(b.manager.AddObject(60, soup.get()), SC_ERROR_INVALID_OPERATION);
  EXPECT_NE(b.manager.AddObject(61, nullptr), SC_NO_ERROR);
  b.expectUnchanged();

  SCSceneManager soup_scene(SC_SCENE_MANAGER_TRIANGLE_SOUP);
  auto closed = makeCube(0.0, 0.0, 0.0);
  EXPECT_EQ(soup_scene.AddObject(1, closed.get()), SC_ERROR_INVALID_OPERATION);
  EXPECT_EQ(soup_scene.AddObject(2, soup.get()), SC_NO_ERROR);
}

TEST(SceneMisuse, NegativeOrStaticGroupIdInAddObjectToGroupFails) {
  Baseline b;
  EXPECT_NE(b.manager.AddObjectToGroup(-5, 1), SC_NO_ERROR);
  EXPECT_NE(b.manager.AddObjectToGroup(SC_GROUP_STATIC, 1), SC_NO_ERROR);
  EXPECT_NE(b.manager.AddObjectToGroup(SC_GROUP_STATIC, 3), SC_NO_ERROR);
  b.expectUnchanged();
}

TEST(SceneMisuse, UnknownEnumValuesFail) {
  Baseline b;
  const double v[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 5, 5, 1};
  const float v_f[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 5, 5, 1};
  double out[16];
  EXPECT_NE(b.manager.SetActivityObject(1, kBogusEnum), SC_NO_ERROR);
  EXPECT_NE(b.manager.SetActivityGroup(0, kBogusEnum), SC_NO_ERROR);
  EXPECT_NE(b.manager.SetActivityGroup(0, SC_ACTIVITY_ONE_WAY_INACTIVE), SC_NO_ERROR);
  EXPECT_NE(b.manager.SetActivityPair(0, 1, kBogusEnum), SC_NO_ERROR);
  EXPECT_NE(b.manager.SetActivityPair(0, 1, SC_ACTIVITY_SLEEPING), SC_NO_ERROR);
  EXPECT_NE(b.manager.SetTransformation(0, kBogusEnum, v), SC_NO_ERROR);
  EXPECT_NE(b.manager.SetTransformation(0, kBogusEnum, v_f), SC_NO_ERROR);
  EXPECT_NE(b.manager.SetTransformation(0, SC_STATUS_RESULT, v), SC_NO_ERROR);
  EXPECT_NE(b.manager.GetTransformation(0, kBogusEnum, out), SC_NO_ERROR);
  EXPECT_NE(b.manager.SetAttributeDouble(kBogusEnum, 1.0), SC_NO_ERROR);
  EXPECT_NE(b.manager.SetAttributeInteger(kBogusEnum, 1), SC_NO_ERROR);
  EXPECT_NE(b.manager.SetAttributeEnum(kBogusEnum, SC_ROTATION_MODE_NONE), SC_NO_ERROR);
  EXPECT_NE(b.manager.SetAttributeEnum(SC_SCENE_MANAGER_ROTATION_MODE, kBogusEnum), SC_NO_ERROR);
  EXPECT_NE(b.manager.SetAttributeEnum(SC_SCENE_MANAGER_ROTATION_MODE, SC_ACTIVITY_ACTIVE),
            SC_NO_ERROR);
  Outputs kept;
  EXPECT_EQ(b.manager.GetStatus(kBogusEnum, &kept.i), SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(b.manager.GetStatus(kBogusEnum, &kept.i, 0, false), SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(b.manager.GetStatus(kBogusEnum, &kept.d, 0, false), SC_ERROR_INVALID_ARGUMENT);
  kept.expectUntouched();
  b.expectUnchanged();
  // A new object of an unknown type accepts no geometry and joins no scene.
  SCObject bogus(kBogusEnum);
  const std::vector<double> cube = cubeVertices(0.0, 0.0, 0.0);
  EXPECT_NE(bogus.AddTriangles(cube.data(), 8, kCubeTriangles, 12), SC_NO_ERROR);
  EXPECT_NE(b.manager.AddObject(70, &bogus), SC_NO_ERROR);
  b.expectUnchanged();
}

TEST(SceneMisuse, SleepingOrPassiveObjectActivityFails) {
  Baseline b;
  EXPECT_NE(b.manager.SetActivityObject(1, SC_ACTIVITY_SLEEPING), SC_NO_ERROR);
  EXPECT_NE(b.manager.SetActivityObject(1, SC_ACTIVITY_PASSIVE), SC_NO_ERROR);
  EXPECT_NE(b.manager.SetActivityObject(3, SC_ACTIVITY_ONE_WAY_ACTIVE), SC_NO_ERROR);
  b.expectUnchanged();
}

TEST(SceneMisuse, WronglyTypedAttributeSetterIsInvalidArgument) {
  Baseline b;
  // List 8-13 passes the double safety coefficient 0.49 to SetAttributeInteger...
  EXPECT_EQ(b.manager.SetAttributeInteger(SC_SCENE_MANAGER_SAFETY_COEFFICIENT,
                                          static_cast<SCint>(0.49)),
            SC_ERROR_INVALID_ARGUMENT);
  // ... and List 8-15 the double stiffnesses 0.6 and 150 to SetAttributeEnum.
  EXPECT_EQ(b.manager.SetAttributeEnum(SC_SCENE_MANAGER_FORCE_STIFFNESS, static_cast<SCenum>(0.6)),
            SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(b.manager.SetAttributeEnum(SC_SCENE_MANAGER_TORQUE_STIFFNESS, 150),
            SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(b.manager.SetAttributeInteger(SC_SCENE_MANAGER_TOLERANCE, 1),
            SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(b.manager.SetAttributeDouble(SC_SCENE_MANAGER_MAX_ITERATION, 10.0),
            SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(b.manager.SetAttributeDouble(SC_SCENE_MANAGER_ROTATION_MODE, SC_ROTATION_MODE_NONE),
            SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(b.manager.SetAttributeInteger(SC_SCENE_MANAGER_ROTATION_MODE, SC_ROTATION_MODE_NONE),
            SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(b.manager.SetAttributeEnum(SC_SCENE_MANAGER_MAX_ITERATION, 10),
            SC_ERROR_INVALID_ARGUMENT);
  // The getters are typed the same way and write nothing on error.
  Outputs out;
  EXPECT_EQ(b.manager.GetAttributeInteger(SC_SCENE_MANAGER_SAFETY_COEFFICIENT, &out.i),
            SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(b.manager.GetAttributeEnum(SC_SCENE_MANAGER_FORCE_STIFFNESS, &out.e),
            SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(b.manager.GetAttributeDouble(SC_SCENE_MANAGER_MAX_ITERATION, &out.d),
            SC_ERROR_INVALID_ARGUMENT);
  out.expectUntouched();
  b.expectUnchanged();
}

TEST(SceneMisuse, InvalidAttributeValuesAreInvalidArgument) {
  Baseline b;
  for (double bad : {-0.1, 0.0, kNaN, kInf, -kInf}) {
    EXPECT_EQ(b.manager.SetAttributeDouble(SC_SCENE_MANAGER_TOLERANCE, bad),
              SC_ERROR_INVALID_ARGUMENT)
        << bad;
  }
  for (double bad : {-1.0, kNaN, -kInf}) {
    EXPECT_EQ(b.manager.SetAttributeDouble(SC_SCENE_MANAGER_MAX_DISTANCE, bad),
              SC_ERROR_INVALID_ARGUMENT)
        << bad;
  }
  for (double bad : {0.0, 1.0, -0.49, kNaN}) {
    EXPECT_EQ(b.manager.SetAttributeDouble(SC_SCENE_MANAGER_SAFETY_COEFFICIENT, bad),
              SC_ERROR_INVALID_ARGUMENT)
        << bad;
  }
  for (double bad : {0.0, -0.6, kNaN, kInf}) {
    EXPECT_EQ(b.manager.SetAttributeDouble(SC_SCENE_MANAGER_FORCE_STIFFNESS, bad),
              SC_ERROR_INVALID_ARGUMENT)
        << bad;
    EXPECT_EQ(b.manager.SetAttributeDouble(SC_SCENE_MANAGER_TORQUE_STIFFNESS, bad),
              SC_ERROR_INVALID_ARGUMENT)
        << bad;
  }
  for (SCint bad : {0, -1, std::numeric_limits<SCint>::min()}) {
    EXPECT_EQ(b.manager.SetAttributeInteger(SC_SCENE_MANAGER_MAX_ITERATION, bad),
              SC_ERROR_INVALID_ARGUMENT)
        << bad;
  }
  b.expectUnchanged();
}

TEST(SceneMisuse, EveryRotationModeIsAcceptedAndAnUnknownOneChangesNothing) {
  Baseline b;
  for (SCenum m : {SC_ROTATION_MODE_NONE, SC_ROTATION_MODE_FREE, SC_ROTATION_MODE_MIX,
                   SC_ROTATION_MODE_INPUT}) {
    EXPECT_EQ(b.manager.SetAttributeEnum(SC_SCENE_MANAGER_ROTATION_MODE, m), SC_NO_ERROR);
    SCenum mode = -1;
    EXPECT_EQ(b.manager.GetAttributeEnum(SC_SCENE_MANAGER_ROTATION_MODE, &mode), SC_NO_ERROR);
    EXPECT_EQ(mode, m);
  }
  EXPECT_EQ(b.manager.SetAttributeEnum(SC_SCENE_MANAGER_ROTATION_MODE, SC_FEATURE_VERTEX),
            SC_ERROR_INVALID_ARGUMENT);
  SCenum mode = -1;
  EXPECT_EQ(b.manager.GetAttributeEnum(SC_SCENE_MANAGER_ROTATION_MODE, &mode), SC_NO_ERROR);
  EXPECT_EQ(mode, SC_ROTATION_MODE_INPUT);  // the last valid one, kept
  b.expectUnchanged();
}

TEST(SceneMisuse, ObjectSetTransformationInASceneIsInvalidOperation) {
  Baseline b;
  double before[16], after[16];
  ASSERT_EQ(b.o1->GetTransformation(SC_TRANSFORMATION_MATRIX, before), SC_NO_ERROR);
  const double pos[3] = {0.5, 0.0, 0.0};
  const float pos_f[3] = {0.5f, 0.0f, 0.0f};
  EXPECT_EQ(b.o1->SetTransformation(SC_POSITION_ORIGIN, pos), SC_ERROR_INVALID_OPERATION);
  EXPECT_EQ(b.o1->SetTransformation(SC_POSITION_ORIGIN, pos_f), SC_ERROR_INVALID_OPERATION);
  EXPECT_EQ(b.o3->SetTransformation(SC_POSITION_WORLD_CENTER, pos), SC_ERROR_INVALID_OPERATION);
  ASSERT_EQ(b.o1->GetTransformation(SC_TRANSFORMATION_MATRIX, after), SC_NO_ERROR);
  EXPECT_EQ(std::memcmp(before, after, sizeof before), 0);
  b.expectUnchanged();
}

TEST(SceneMisuse, AddTrianglesInASceneIsInvalidOperation) {
  Baseline b;
  // A piece that would touch group 0 if it were added to static object 3.
  const std::vector<double> near = cubeVertices(0.0, 1.5, 0.0);
  std::vector<float> near_f(near.begin(), near.end());
  EXPECT_EQ(b.o3->AddTriangles(near.data(), 8, kCubeTriangles, 12), SC_ERROR_INVALID_OPERATION);
  EXPECT_EQ(b.o3->AddTriangles(near_f.data(), 8, kCubeTriangles, 12),
            SC_ERROR_INVALID_OPERATION);
  EXPECT_EQ(b.o1->AddTriangles(near.data(), 8, kCubeTriangles, 12), SC_ERROR_INVALID_OPERATION);
  b.expectUnchanged();
}

TEST(SceneMisuse, GetStatusOutOfRangeNullOrWrongTypeIsInvalidArgument) {
  Baseline b;
  Outputs out;
  for (SCint index : {-1, 3, 1000}) {
    EXPECT_EQ(b.manager.GetStatus(SC_STATUS_RESULT, &out.i, index, false),
              SC_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(b.manager.GetStatus(SC_GROUP_ID, &out.i, index, true), SC_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(b.manager.GetStatus(SC_DISTANCE, &out.f, index, false), SC_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(b.manager.GetStatus(SC_DISTANCE, &out.d, index, true), SC_ERROR_INVALID_ARGUMENT);
  }
  EXPECT_EQ(b.manager.GetStatus(SC_STATUS_COUNT, static_cast<SCint*>(nullptr)),
            SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(b.manager.GetStatus(SC_STATUS_RESULT, static_cast<SCint*>(nullptr), 0, false),
            SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(b.manager.GetStatus(SC_DISTANCE, static_cast<SCfloat*>(nullptr), 0, false),
            SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(b.manager.GetStatus(SC_DISTANCE, static_cast<SCdouble*>(nullptr), 0, false),
            SC_ERROR_INVALID_ARGUMENT);
  // Value type not matching the status type.
  EXPECT_EQ(b.manager.GetStatus(SC_DISTANCE, &out.i, 0, false), SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(b.manager.GetStatus(SC_DISTANCE, &out.i), SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(b.manager.GetStatus(SC_GROUP_ID, &out.d, 0, false), SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(b.manager.GetStatus(SC_STATUS_RESULT, &out.f, 0, false), SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(b.manager.GetStatus(SC_STATUS_COUNT, &out.d, 0, false), SC_ERROR_INVALID_ARGUMENT);
  out.expectUntouched();
  b.expectUnchanged();
}

TEST(SceneMisuse, StaticGroupCannotBeMovedNorReactivated) {
  Baseline b;
  const double pos[3] = {0.0, 5.0, 0.0};
  const float pos_f[3] = {0.0f, 5.0f, 0.0f};
  EXPECT_EQ(b.manager.SetTransformation(SC_GROUP_STATIC, SC_POSITION_ORIGIN, pos),
            SC_ERROR_INVALID_OPERATION);
  EXPECT_EQ(b.manager.SetTransformation(SC_GROUP_STATIC, SC_POSITION_ORIGIN, pos_f),
            SC_ERROR_INVALID_OPERATION);
  EXPECT_EQ(b.manager.SetActivityGroup(SC_GROUP_STATIC, SC_ACTIVITY_ACTIVE),
            SC_ERROR_INVALID_OPERATION);
  EXPECT_EQ(b.manager.SetActivityGroup(SC_GROUP_STATIC, SC_ACTIVITY_PASSIVE),
            SC_ERROR_INVALID_OPERATION);
  EXPECT_EQ(b.manager.SetActivityPair(0, 0, SC_ACTIVITY_ACTIVE), SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(b.manager.SetActivityPair(SC_GROUP_STATIC, SC_GROUP_STATIC, SC_ACTIVITY_ACTIVE),
            SC_ERROR_INVALID_ARGUMENT);
  b.expectUnchanged();
  // Its transformation reads as the identity.
  double m[16];
  ASSERT_EQ(b.manager.GetTransformation(SC_GROUP_STATIC, SC_TRANSFORMATION_MATRIX, m),
            SC_NO_ERROR);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_EQ(m[4 * c + r], r == c ? 1.0 : 0.0) << r << "," << c;
  double q[4];
  ASSERT_EQ(b.manager.GetTransformation(SC_GROUP_STATIC, SC_ORIENTATION_QUATERNION, q),
            SC_NO_ERROR);
  EXPECT_EQ(std::abs(q[0]), 1.0);
  float origin[3] = {-1.0f, -1.0f, -1.0f};
  ASSERT_EQ(b.manager.GetTransformation(SC_GROUP_STATIC, SC_POSITION_ORIGIN, origin),
            SC_NO_ERROR);
  EXPECT_EQ(origin[0], 0.0f);
  EXPECT_EQ(origin[1], 0.0f);
  EXPECT_EQ(origin[2], 0.0f);
}

TEST(SceneMisuse, DestroyingAnObjectStillInASceneRemovesIt) {
  Baseline b;
  b.o2.reset();  // object 2, the only member of group 1
  ASSERT_EQ(b.manager.UpdateStatus(), SC_NO_ERROR);
  SCint count = -1;
  ASSERT_EQ(b.manager.GetStatus(SC_STATUS_COUNT, &count), SC_NO_ERROR);
  EXPECT_EQ(count, 1);  // only group 0 -> static is left
  SCint g[2];
  ASSERT_EQ(b.manager.GetStatus(SC_GROUP_ID, g, 0, false), SC_NO_ERROR);
  EXPECT_EQ(g[0], 0);
  EXPECT_EQ(g[1], SC_GROUP_STATIC);
  EXPECT_EQ(b.manager.DeleteObject(2), SC_ERROR_INVALID_ID);
  EXPECT_EQ(b.manager.SetActivityGroup(1, SC_ACTIVITY_ACTIVE), SC_ERROR_INVALID_ID);
  // The id is free again.
  auto again = makeCube(2.0, 0.0, 0.0);
  EXPECT_EQ(b.manager.AddObject(2, again.get()), SC_NO_ERROR);
  EXPECT_EQ(b.manager.AddObjectToGroup(1, 2), SC_NO_ERROR);
  EXPECT_EQ(snapshot(b.manager), b.before);
}

TEST(SceneMisuse, DestroyingTheSceneFirstLeavesItsObjectsUsable) {
  auto o1 = makeCube(0.0, 0.0, 0.0);
  auto o2 = makeCube(2.0, 0.0, 0.0);
  {
    SCSceneManager scene(SC_SCENE_MANAGER_CLOSED_POLYHEDRA);
    ASSERT_EQ(scene.AddObject(1, o1.get()), SC_NO_ERROR);
    ASSERT_EQ(scene.AddObject(2, o2.get()), SC_NO_ERROR);
    ASSERT_EQ(scene.AddObjectToGroup(0, 1), SC_NO_ERROR);
    const double origin[3] = {0.0, 5.0, 0.0};
    ASSERT_EQ(scene.SetTransformation(0, SC_POSITION_ORIGIN, origin), SC_NO_ERROR);
    ASSERT_EQ(scene.UpdateStatus(), SC_NO_ERROR);
  }
  // Like DeleteObject, releasing keeps the pose the object had in the scene.
  double origin[3] = {-1.0, -1.0, -1.0};
  ASSERT_EQ(o1->GetTransformation(SC_POSITION_ORIGIN, origin), SC_NO_ERROR);
  EXPECT_EQ(origin[0], 0.0);
  EXPECT_EQ(origin[1], 5.0);
  EXPECT_EQ(origin[2], 0.0);
  // Out of any scene: the objects take transformations and geometry again...
  const double back[3] = {0.0, 0.0, 0.0};
  EXPECT_EQ(o1->SetTransformation(SC_POSITION_ORIGIN, back), SC_NO_ERROR);
  const std::vector<double> extra = cubeVertices(10.0, 0.0, 0.0);
  EXPECT_EQ(o2->AddTriangles(extra.data(), 8, kCubeTriangles, 12), SC_NO_ERROR);
  // ... and work in a new scene.
  SCSceneManager scene(SC_SCENE_MANAGER_CLOSED_POLYHEDRA);
  ASSERT_EQ(scene.AddObject(1, o1.get()), SC_NO_ERROR);
  ASSERT_EQ(scene.AddObject(2, o2.get()), SC_NO_ERROR);
  ASSERT_EQ(scene.AddObjectToGroup(0, 1), SC_NO_ERROR);
  ASSERT_EQ(scene.UpdateStatus(), SC_NO_ERROR);
  double d = -1.0;
  ASSERT_EQ(scene.GetStatus(SC_DISTANCE, &d, 0, false), SC_NO_ERROR);
  EXPECT_NEAR(d, 1.0, 1e-9);
}

TEST(SceneMisuse, EveryResultCodeHasADistinctNonEmptyMessage) {
  const SCint codes[] = {SC_NO_ERROR,
                         SC_ERROR_NO_RESULT,
                         SC_ERROR_INVALID_INITIAL_TRANSFORMATION,
                         SC_ERROR_INVALID_LICENSE,
                         SC_ERROR_INVALID_GEOMETRY,
                         SC_ERROR_INVALID_ARGUMENT,
                         SC_ERROR_INVALID_ID,
                         SC_ERROR_INVALID_OPERATION,
                         SC_ERROR_FILE,
                         -1,
                         12345};  // the last two are unknown codes
  std::set<std::string> messages;
  for (SCint code : codes) {
    const char* m = SCGetErrorString(code);
    ASSERT_NE(m, nullptr) << code;
    EXPECT_GT(std::strlen(m), 0u) << code;
    messages.insert(m);
  }
  // Every known code distinct; both unknown codes share one "unknown" message.
  EXPECT_EQ(messages.size(), 10u);
  EXPECT_STREQ(SCGetErrorString(-1), SCGetErrorString(12345));
  // The aliases are the same codes.
  EXPECT_EQ(SC_ERROR_UNKNOWN_DISTANCE, SC_ERROR_NO_RESULT);
  EXPECT_EQ(SC_ERROR_INVALID_INTIAL_TRANSFORMATION, SC_ERROR_INVALID_INITIAL_TRANSFORMATION);
}

}  // namespace
