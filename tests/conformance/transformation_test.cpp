// SPDX-License-Identifier: MIT
// Manual section 7 through SCObject::SetTransformation / GetTransformation: every
// row of Tables 7-1 and 7-2, Lists 7-1 and 7-2, and each invalid input, in float and double.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "sc.h"
#include "support/placements.h"

namespace {

const double kH = std::sqrt(0.5);  // cos 45 degrees = sin 45 degrees

int arraySize(SCenum type) {
  switch (type) {
    case SC_ORIENTATION_QUATERNION:
      return 4;
    case SC_ORIENTATION_MATRIX:
      return 9;
    case SC_TRANSFORMATION_MATRIX:
      return 16;
    default:
      return 3;
  }
}

const SCenum kReadableTypes[] = {SC_POSITION_ORIGIN,        SC_POSITION_WORLD_CENTER,
                                 SC_POSITION_LOCAL_CENTER,  SC_ORIENTATION_QUATERNION,
                                 SC_ORIENTATION_MATRIX,     SC_TRANSFORMATION_MATRIX};
const SCenum kAllTypes[] = {SC_POSITION_ORIGIN,           SC_POSITION_WORLD_CENTER,
                            SC_POSITION_LOCAL_CENTER,     SC_POSITION_NEW_WORLD_CENTER,
                            SC_POSITION_NEW_LOCAL_CENTER, SC_ORIENTATION_QUATERNION,
                            SC_ORIENTATION_MATRIX,        SC_TRANSFORMATION_MATRIX};

/// Every readable value in double: equal snapshots mean an unchanged transformation.
std::vector<std::vector<double>> snapshot(const SCObject& o) {
  std::vector<std::vector<double>> all;
  for (SCenum type : kReadableTypes) {
    std::vector<double> v(arraySize(type));
    EXPECT_EQ(o.GetTransformation(type, v.data()), SC_NO_ERROR);
    all.push_back(v);
  }
  return all;
}

bool bitwiseEqual(const std::vector<std::vector<double>>& a,
                  const std::vector<std::vector<double>>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].size() != b[i].size() ||
        std::memcmp(a[i].data(), b[i].data(), a[i].size() * sizeof(double)) != 0) {
      return false;
    }
  }
  return true;
}

template <class Real>
class ScObjectTransformation : public ::testing::Test {
 protected:
  static double tol(double magnitude) { return sc::test::realTol<Real>(magnitude); }

  static SCint set(SCObject& o, SCenum type, const std::vector<double>& values) {
    return o.SetTransformation(type, sc::test::convert<Real>(values).data());
  }

  static std::vector<double> get(const SCObject& o, SCenum type) {
    std::vector<Real> out(arraySize(type), Real(-12345));
    EXPECT_EQ(o.GetTransformation(type, out.data()), SC_NO_ERROR) << "type " << type;
    return sc::test::convert<double>(out);
  }

  static void expectGet(const SCObject& o, SCenum type, const std::vector<double>& expected) {
    const std::vector<double> got = get(o, type);
    ASSERT_EQ(got.size(), expected.size());
    for (size_t i = 0; i < got.size(); ++i) {
      EXPECT_NEAR(got[i], expected[i], tol(expected[i])) << "type " << type << ", index " << i;
    }
  }

  /// q and -q are the same orientation.
  static void expectQuaternion(const SCObject& o, const std::vector<double>& expected) {
    const std::vector<double> q = get(o, SC_ORIENTATION_QUATERNION);
    const double sign = q[0] * expected[0] + q[1] * expected[1] + q[2] * expected[2] +
                                    q[3] * expected[3] < 0 ? -1.0 : 1.0;
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(sign * q[i], expected[i], 10 * tol(1)) << "index " << i;
  }

  /// r_WC = (1,2,3), r_LC = (4,5,6), 90 degrees about z: R(x,y,z) = (-y,x,z), so
  /// r_O = r_WC - R r_LC = (1,2,3) - (-5,4,6) = (6,-2,-3). Built through the API.
  static void makeStartState(SCObject& o) {
    ASSERT_EQ(set(o, SC_ORIENTATION_QUATERNION, {kH, 0, 0, kH}), SC_NO_ERROR);
    ASSERT_EQ(set(o, SC_POSITION_NEW_LOCAL_CENTER, {4, 5, 6}), SC_NO_ERROR);
    ASSERT_EQ(set(o, SC_POSITION_WORLD_CENTER, {1, 2, 3}), SC_NO_ERROR);
  }

  /// `values` must be rejected with SC_ERROR_INVALID_ARGUMENT, changing nothing.
  static void expectRejected(SCenum type, const std::vector<Real>& values) {
    SCObject o(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
    makeStartState(o);
    const auto before = snapshot(o);
    EXPECT_EQ(o.SetTransformation(type, values.data()), SC_ERROR_INVALID_ARGUMENT)
        << "type " << type;
    EXPECT_TRUE(bitwiseEqual(snapshot(o), before)) << "type " << type;
  }
};

TYPED_TEST_SUITE(ScObjectTransformation, sc::test::Reals, sc::test::RealNames);

TYPED_TEST(ScObjectTransformation, NewObjectIsAtTheWorldOriginUnrotated) {
  SCObject o(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  this->expectGet(o, SC_POSITION_ORIGIN, {0, 0, 0});
  this->expectGet(o, SC_POSITION_WORLD_CENTER, {0, 0, 0});
  this->expectGet(o, SC_POSITION_LOCAL_CENTER, {0, 0, 0});
  this->expectGet(o, SC_ORIENTATION_QUATERNION, {1, 0, 0, 0});
  this->expectGet(o, SC_TRANSFORMATION_MATRIX, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});
}

TYPED_TEST(ScObjectTransformation, StartStateIsAsBuilt) {
  SCObject o(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  this->makeStartState(o);
  this->expectGet(o, SC_POSITION_WORLD_CENTER, {1, 2, 3});
  this->expectGet(o, SC_POSITION_LOCAL_CENTER, {4, 5, 6});
}

// ---- Table 7-1 -------------------------------------------------------------------

/// Rows 1-5 of Table 7-1: a position set on the start state, and the world centre,
/// local centre and origin read back after it (the orientation stays).
struct PositionRow {
  int row;
  SCenum type;
  std::vector<double> value, world_center, local_center, origin;
};

const PositionRow kPositionRows[] = {
    // The origin sets the world centre: (10,20,30) + R(4,5,6).
    {1, SC_POSITION_ORIGIN, {10, 20, 30}, {5, 24, 36}, {4, 5, 6}, {10, 20, 30}},
    // The world centre: origin (7,8,9) - (-5,4,6).
    {2, SC_POSITION_WORLD_CENTER, {7, 8, 9}, {7, 8, 9}, {4, 5, 6}, {12, 4, 3}},
    // The local centre moves the world centre only: R((1,1,1) - (4,5,6)) + (1,2,3).
    {3, SC_POSITION_LOCAL_CENTER, {1, 1, 1}, {5, -1, -2}, {4, 5, 6}, {10, -5, -8}},
    // A new world centre moves the local centre, keeps the origin:
    // R^-1((7,8,9) - (1,2,3)) + (4,5,6) = (6,-6,6) + (4,5,6).
    {4, SC_POSITION_NEW_WORLD_CENTER, {7, 8, 9}, {7, 8, 9}, {10, -1, 12}, {6, -2, -3}},
    // A new local centre moves the world centre, keeps the origin.
    {5, SC_POSITION_NEW_LOCAL_CENTER, {1, 1, 1}, {5, -1, -2}, {1, 1, 1}, {6, -2, -3}},
};

TYPED_TEST(ScObjectTransformation, Table71PositionRows) {
  for (const PositionRow& r : kPositionRows) {
    SCOPED_TRACE(testing::Message() << "Table 7-1 row " << r.row);
    SCObject o(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
    this->makeStartState(o);
    ASSERT_EQ(this->set(o, r.type, r.value), SC_NO_ERROR);
    this->expectGet(o, SC_POSITION_WORLD_CENTER, r.world_center);
    this->expectGet(o, SC_POSITION_LOCAL_CENTER, r.local_center);
    this->expectGet(o, SC_POSITION_ORIGIN, r.origin);
    this->expectQuaternion(o, {kH, 0, 0, kH});
  }
}

TYPED_TEST(ScObjectTransformation, Table71Row6QuaternionIsScalarFirstAndNormalised) {
  SCObject o(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  this->makeStartState(o);
  ASSERT_EQ(this->set(o, SC_ORIENTATION_QUATERNION, {3, 3, 0, 0}), SC_NO_ERROR);
  this->expectGet(o, SC_ORIENTATION_QUATERNION, {kH, kH, 0, 0});
  // 90 degrees about x: columns (1,0,0), (0,0,1), (0,-1,0).
  this->expectGet(o, SC_ORIENTATION_MATRIX, {1, 0, 0, 0, 0, 1, 0, -1, 0});
  this->expectGet(o, SC_POSITION_WORLD_CENTER, {1, 2, 3});
  this->expectGet(o, SC_POSITION_LOCAL_CENTER, {4, 5, 6});
}

TYPED_TEST(ScObjectTransformation, Table71Row7OrientationMatrixIsColumnMajor) {
  SCObject o(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  this->makeStartState(o);
  // 90 degrees about y, (x,y,z) -> (z,y,-x): columns (0,0,-1), (0,1,0), (1,0,0).
  ASSERT_EQ(this->set(o, SC_ORIENTATION_MATRIX, {0, 0, -1, 0, 1, 0, 1, 0, 0}), SC_NO_ERROR);
  this->expectQuaternion(o, {kH, 0, kH, 0});
  this->expectGet(o, SC_ORIENTATION_MATRIX, {0, 0, -1, 0, 1, 0, 1, 0, 0});
  this->expectGet(o, SC_POSITION_WORLD_CENTER, {1, 2, 3});
  this->expectGet(o, SC_POSITION_LOCAL_CENTER, {4, 5, 6});
}

TYPED_TEST(ScObjectTransformation, Table71Row8TransformationMatrixSetsWorldCenterAndOrientation) {
  SCObject o(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  this->makeStartState(o);
  // 90 degrees about x, (x,y,z) -> (x,-z,y), translation (1,1,1) at m12..m14.
  ASSERT_EQ(this->set(o, SC_TRANSFORMATION_MATRIX, {1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 1, 1, 1, 1}),
            SC_NO_ERROR);
  this->expectGet(o, SC_POSITION_WORLD_CENTER, {5, -5, 6});  // R'(4,5,6) + (1,1,1)
  this->expectGet(o, SC_POSITION_LOCAL_CENTER, {4, 5, 6});
  this->expectGet(o, SC_POSITION_ORIGIN, {1, 1, 1});
  this->expectQuaternion(o, {kH, kH, 0, 0});
  this->expectGet(o, SC_TRANSFORMATION_MATRIX, {1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 1, 1, 1, 1});
}

// ---- Table 7-2 -------------------------------------------------------------------

TYPED_TEST(ScObjectTransformation, Table72Row1OriginIsWorldCenterMinusRotatedLocalCenter) {
  SCObject o(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  this->makeStartState(o);
  this->expectGet(o, SC_POSITION_ORIGIN, {6, -2, -3});
}

TYPED_TEST(ScObjectTransformation, Table72Row2WorldCenter) {
  SCObject o(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  this->makeStartState(o);
  ASSERT_EQ(this->set(o, SC_POSITION_NEW_WORLD_CENTER, {-7, 0.5, 2}), SC_NO_ERROR);
  this->expectGet(o, SC_POSITION_WORLD_CENTER, {-7, 0.5, 2});
}

TYPED_TEST(ScObjectTransformation, Table72Row3LocalCenter) {
  SCObject o(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  this->makeStartState(o);
  ASSERT_EQ(this->set(o, SC_POSITION_NEW_LOCAL_CENTER, {-2, 0, 5}), SC_NO_ERROR);
  this->expectGet(o, SC_POSITION_LOCAL_CENTER, {-2, 0, 5});
}

TYPED_TEST(ScObjectTransformation, Table72Row4QuaternionIsScalarFirstUnit) {
  SCObject o(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  this->makeStartState(o);
  this->expectGet(o, SC_ORIENTATION_QUATERNION, {kH, 0, 0, kH});
  ASSERT_EQ(this->set(o, SC_ORIENTATION_QUATERNION, {1, 2, 3, 4}), SC_NO_ERROR);
  const double n = std::sqrt(30.0);
  this->expectGet(o, SC_ORIENTATION_QUATERNION, {1 / n, 2 / n, 3 / n, 4 / n});
}

TYPED_TEST(ScObjectTransformation, Table72Row5OrientationMatrixIsColumnMajor) {
  SCObject o(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  this->makeStartState(o);
  // R = [0 -1 0; 1 0 0; 0 0 1]: columns (0,1,0), (-1,0,0), (0,0,1).
  this->expectGet(o, SC_ORIENTATION_MATRIX, {0, 1, 0, -1, 0, 0, 0, 0, 1});
}

TYPED_TEST(ScObjectTransformation, Table72Row6TransformationMatrixIsTwcRTlcInverse) {
  SCObject o(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  this->makeStartState(o);
  this->expectGet(o, SC_TRANSFORMATION_MATRIX, {0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 6, -2, -3, 1});
}

TYPED_TEST(ScObjectTransformation, NewCentersAreSetOnlyAndCannotBeRead) {
  SCObject o(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  this->makeStartState(o);
  for (SCenum type : {SC_POSITION_NEW_WORLD_CENTER, SC_POSITION_NEW_LOCAL_CENTER}) {
    TypeParam out[3] = {7, 7, 7};
    EXPECT_EQ(o.GetTransformation(type, out), SC_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(out[0], 7);
    EXPECT_EQ(out[2], 7);
  }
}

// ---- Lists 7-1 and 7-2 -----------------------------------------------------------

TYPED_TEST(ScObjectTransformation, List71AndList72GiveTheSameTransformation) {
  // List 7-2, verbatim.
  SCObject list72(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  ASSERT_EQ(this->set(list72, SC_POSITION_ORIGIN, {-3, 61, 29}), SC_NO_ERROR);
  ASSERT_EQ(this->set(list72, SC_ORIENTATION_QUATERNION, {0.707107, 0.707107, 0, 0}), SC_NO_ERROR);
  ASSERT_EQ(this->set(list72, SC_POSITION_NEW_WORLD_CENTER, {10, 50, 35}), SC_NO_ERROR);

  // List 7-1 is an image missing from the manual's text, described as reaching the
  // same transformation by another sequence. Reconstructed: the local centre where
  // List 7-2 ends, R^-1((10,50,35) - (-3,61,29)) = (13,6,11), then the orientation,
  // then the world centre.
  SCObject list71(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  ASSERT_EQ(this->set(list71, SC_POSITION_NEW_LOCAL_CENTER, {13, 6, 11}), SC_NO_ERROR);
  ASSERT_EQ(this->set(list71, SC_ORIENTATION_QUATERNION, {0.707107, 0.707107, 0, 0}), SC_NO_ERROR);
  ASSERT_EQ(this->set(list71, SC_POSITION_WORLD_CENTER, {10, 50, 35}), SC_NO_ERROR);

  for (const SCObject* o : {&list72, &list71}) {
    this->expectGet(*o, SC_POSITION_WORLD_CENTER, {10, 50, 35});
    this->expectGet(*o, SC_POSITION_LOCAL_CENTER, {13, 6, 11});
    this->expectGet(*o, SC_POSITION_ORIGIN, {-3, 61, 29});
    this->expectGet(*o, SC_ORIENTATION_QUATERNION, {kH, kH, 0, 0});
    this->expectGet(*o, SC_TRANSFORMATION_MATRIX,
                    {1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, -3, 61, 29, 1});
  }
  for (SCenum type : kReadableTypes) this->expectGet(list71, type, this->get(list72, type));
}

// ---- Invalid input: SC_ERROR_INVALID_ARGUMENT and nothing changes -----------------

TYPED_TEST(ScObjectTransformation, NullPointerIsInvalidArgument) {
  SCObject o(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  this->makeStartState(o);
  const auto before = snapshot(o);
  for (SCenum type : kAllTypes) {
    EXPECT_EQ(o.SetTransformation(type, static_cast<const TypeParam*>(nullptr)),
              SC_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(o.GetTransformation(type, static_cast<TypeParam*>(nullptr)), SC_ERROR_INVALID_ARGUMENT);
  }
  EXPECT_TRUE(bitwiseEqual(snapshot(o), before));
}

TYPED_TEST(ScObjectTransformation, UnknownTypeIsInvalidArgument) {
  for (SCenum type : {0, -1, 0x0400, 0x0409, SC_ACTIVITY_ACTIVE}) {
    this->expectRejected(type, std::vector<TypeParam>(16, TypeParam(1)));
    SCObject o(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
    std::vector<TypeParam> out(16, TypeParam(7));
    EXPECT_EQ(o.GetTransformation(type, out.data()), SC_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(out, std::vector<TypeParam>(16, TypeParam(7)));
  }
}

TYPED_TEST(ScObjectTransformation, NaNOrInfinityAnywhereIsInvalidArgument) {
  const std::vector<TypeParam> bad = sc::test::nonFinite<TypeParam>();
  for (SCenum type : kAllTypes) {
    std::vector<TypeParam> valid;
    switch (type) {
      case SC_ORIENTATION_QUATERNION:
        valid = {0.5, 0.5, 0.5, 0.5};
        break;
      case SC_ORIENTATION_MATRIX:
        valid = {0, 1, 0, 0, 0, 1, 1, 0, 0};
        break;
      case SC_TRANSFORMATION_MATRIX:
        valid = {0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 7, -8, 9, 1};
        break;
      default:
        valid = {1.5, -2, 3};
    }
    SCObject check(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
    ASSERT_EQ(check.SetTransformation(type, valid.data()), SC_NO_ERROR) << "type " << type;
    for (size_t i = 0; i < valid.size(); ++i) {
      for (TypeParam b : bad) {
        SCOPED_TRACE(::testing::Message() << "index " << i << ", value " << b);
        std::vector<TypeParam> values = valid;
        values[i] = b;
        this->expectRejected(type, values);
      }
    }
  }
}

TYPED_TEST(ScObjectTransformation, ZeroQuaternionIsInvalidArgument) {
  this->expectRejected(SC_ORIENTATION_QUATERNION, {0, 0, 0, 0});
}

TYPED_TEST(ScObjectTransformation, NonRotationMatrixIsInvalidArgument) {
  const std::vector<std::vector<TypeParam>> not_rotations = {
      {2, 0, 0, 0, 2, 0, 0, 0, 2},      // scale
      {1, 0, 0, 0, 1, 0, 0, 0, -1},     // reflection
      {1, 0, 0, 0.01f, 1, 0, 0, 0, 1},  // shear
      {0, 0, 0, 0, 0, 0, 0, 0, 0},      // zero
  };
  for (const std::vector<TypeParam>& r : not_rotations) {
    this->expectRejected(SC_ORIENTATION_MATRIX, r);
    this->expectRejected(SC_TRANSFORMATION_MATRIX, {r[0], r[1], r[2], 0, r[3], r[4], r[5], 0,
                                                    r[6], r[7], r[8], 0, 1, 2, 3, 1});
  }
}

TYPED_TEST(ScObjectTransformation, TransformationMatrixWithBadLastRowIsInvalidArgument) {
  for (int index : {3, 7, 11, 15}) {
    std::vector<TypeParam> m = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 2, 3, 1};
    m[index] += TypeParam(0.5);
    this->expectRejected(SC_TRANSFORMATION_MATRIX, m);
  }
}

// ---- Precisions mix --------------------------------------------------------------

TEST(ScObjectTransformationPrecision, SetInDoubleReadsBackInFloat) {
  SCObject o(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  const double origin[3] = {-3, 61, 29};
  ASSERT_EQ(o.SetTransformation(SC_POSITION_ORIGIN, origin), SC_NO_ERROR);
  float got[3];
  ASSERT_EQ(o.GetTransformation(SC_POSITION_ORIGIN, got), SC_NO_ERROR);
  EXPECT_EQ(got[0], -3.0f);
  EXPECT_EQ(got[1], 61.0f);
  EXPECT_EQ(got[2], 29.0f);
}

}  // namespace
