// SPDX-License-Identifier: MIT
// setTransformation / getTransformation over float and double arrays: every row of
// Tables 7-1 and 7-2, every class of invalid input, and manual Lists 7-1 and 7-2.
#include "api/transformation_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "support/placements.h"
#include "support/test_support.h"

namespace sc::detail {
namespace {

using test::quatDistance;
using test::startState;

const double kHalfSqrt2 = std::sqrt(0.5);

const SCenum kAllTypes[] = {SC_POSITION_ORIGIN,           SC_POSITION_WORLD_CENTER,
                            SC_POSITION_LOCAL_CENTER,     SC_POSITION_NEW_WORLD_CENTER,
                            SC_POSITION_NEW_LOCAL_CENTER, SC_ORIENTATION_QUATERNION,
                            SC_ORIENTATION_MATRIX,        SC_TRANSFORMATION_MATRIX};
const SCenum kReadableTypes[] = {SC_POSITION_ORIGIN,        SC_POSITION_WORLD_CENTER,
                                 SC_POSITION_LOCAL_CENTER,  SC_ORIENTATION_QUATERNION,
                                 SC_ORIENTATION_MATRIX,     SC_TRANSFORMATION_MATRIX};
const SCenum kUnknownTypes[] = {0, -1, 0x0400, 0x0409, SC_ACTIVITY_ACTIVE, SC_DISTANCE};

/// Bit-for-bit equality of everything a Placement stores.
bool bitwiseEqual(const Placement& a, const Placement& b) {
  return std::memcmp(a.world_center.data(), b.world_center.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(a.local_center.data(), b.local_center.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(a.orientation.coeffs().data(), b.orientation.coeffs().data(),
                     4 * sizeof(double)) == 0;
}

/// A valid input array of each type, in double.
std::vector<double> validValues(SCenum type) {
  switch (type) {
    case SC_ORIENTATION_QUATERNION:
      return {0.5, 0.5, 0.5, 0.5};
    case SC_ORIENTATION_MATRIX:
      return {0, 1, 0, 0, 0, 1, 1, 0, 0};  // cyclic permutation x->y->z->x
    case SC_TRANSFORMATION_MATRIX:
      return {0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 7, -8, 9, 1};
    default:
      return {1.5, -2, 3};
  }
}

template <class Real>
class TransformationIo : public ::testing::Test {
 protected:
  static double tol(double magnitude) { return test::realTol<Real>(magnitude); }

  static SCint set(Placement& p, SCenum type, const std::vector<double>& values) {
    return setTransformation(p, type, test::convert<Real>(values).data());
  }

  /// Table 7-2 read; fails the test unless the call succeeds.
  static std::vector<double> get(const Placement& p, SCenum type) {
    std::vector<Real> out(transformationArraySize(type), Real(-12345));
    EXPECT_EQ(getTransformation(p, type, out.data()), SC_NO_ERROR) << "type " << type;
    return test::convert<double>(out);
  }

  static void expectValues(const std::vector<double>& got, const std::vector<double>& expected) {
    ASSERT_EQ(got.size(), expected.size());
    for (size_t i = 0; i < got.size(); ++i) {
      EXPECT_NEAR(got[i], expected[i], tol(expected[i])) << "index " << i;
    }
  }

  static void expectVec(const Vec3& got, const Vec3& expected) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], expected[i], tol(expected[i])) << "index " << i;
  }

  /// `values` must be rejected and leave the placement bit-for-bit unchanged.
  static void expectRejected(SCenum type, const std::vector<Real>& values) {
    Placement p = startState();
    const Placement before = p;
    EXPECT_EQ(setTransformation(p, type, values.data()), SC_ERROR_INVALID_ARGUMENT)
        << "type " << type;
    EXPECT_TRUE(bitwiseEqual(p, before)) << "type " << type;
  }
};

TYPED_TEST_SUITE(TransformationIo, sc::test::Reals, sc::test::RealNames);

// ---- Table 7-1 through arrays ----------------------------------------------------

TYPED_TEST(TransformationIo, SetOriginMovesWorldCenter) {
  Placement p = startState();
  ASSERT_EQ(this->set(p, SC_POSITION_ORIGIN, {10, 20, 30}), SC_NO_ERROR);
  this->expectVec(p.world_center, Vec3(5, 24, 36));  // (10,20,30) + R(4,5,6)
  this->expectVec(p.local_center, Vec3(4, 5, 6));
}

TYPED_TEST(TransformationIo, SetWorldCenterStoresIt) {
  Placement p = startState();
  ASSERT_EQ(this->set(p, SC_POSITION_WORLD_CENTER, {7, 8, 9}), SC_NO_ERROR);
  this->expectVec(p.world_center, Vec3(7, 8, 9));
  this->expectVec(p.local_center, Vec3(4, 5, 6));
}

TYPED_TEST(TransformationIo, SetLocalCenterMovesOnlyWorldCenter) {
  Placement p = startState();
  ASSERT_EQ(this->set(p, SC_POSITION_LOCAL_CENTER, {1, 1, 1}), SC_NO_ERROR);
  this->expectVec(p.world_center, Vec3(5, -1, -2));  // R(-3,-4,-5) + (1,2,3)
  this->expectVec(p.local_center, Vec3(4, 5, 6));
}

TYPED_TEST(TransformationIo, SetNewWorldCenterMovesLocalCenterAndKeepsOrigin) {
  Placement p = startState();
  ASSERT_EQ(this->set(p, SC_POSITION_NEW_WORLD_CENTER, {7, 8, 9}), SC_NO_ERROR);
  this->expectVec(p.local_center, Vec3(10, -1, 12));  // R^-1(6,6,6) + (4,5,6)
  this->expectVec(p.world_center, Vec3(7, 8, 9));
  this->expectVec(p.origin(), Vec3(6, -2, -3));
}

TYPED_TEST(TransformationIo, SetNewLocalCenterMovesWorldCenterAndKeepsOrigin) {
  Placement p = startState();
  ASSERT_EQ(this->set(p, SC_POSITION_NEW_LOCAL_CENTER, {1, 1, 1}), SC_NO_ERROR);
  this->expectVec(p.local_center, Vec3(1, 1, 1));
  this->expectVec(p.world_center, Vec3(5, -1, -2));
  this->expectVec(p.origin(), Vec3(6, -2, -3));
}

TYPED_TEST(TransformationIo, SetQuaternionIsScalarFirstAndNormalised) {
  Placement p = startState();
  ASSERT_EQ(this->set(p, SC_ORIENTATION_QUATERNION, {0.707107, 0.707107, 0, 0}), SC_NO_ERROR);
  EXPECT_NEAR(p.orientation.norm(), 1.0, 1e-15);
  this->expectVec(p.rotation() * Vec3(0, 1, 0), Vec3(0, 0, 1));  // 90 degrees about x
  ASSERT_EQ(this->set(p, SC_ORIENTATION_QUATERNION, {2, 0, 0, 2}), SC_NO_ERROR);
  EXPECT_NEAR(p.orientation.w(), kHalfSqrt2, 1e-15);
  EXPECT_NEAR(p.orientation.z(), kHalfSqrt2, 1e-15);
  EXPECT_NEAR(p.orientation.norm(), 1.0, 1e-15);
  this->expectVec(p.world_center, Vec3(1, 2, 3));
  this->expectVec(p.local_center, Vec3(4, 5, 6));
}

TYPED_TEST(TransformationIo, SetOrientationMatrixIsColumnMajor) {
  Placement p = startState();
  // 90 degrees about y, (x,y,z) -> (z,y,-x); columns (0,0,-1), (0,1,0), (1,0,0).
  ASSERT_EQ(this->set(p, SC_ORIENTATION_MATRIX, {0, 0, -1, 0, 1, 0, 1, 0, 0}), SC_NO_ERROR);
  EXPECT_LE(quatDistance(p.orientation, Quat(kHalfSqrt2, 0, kHalfSqrt2, 0)), 1e-12);
  this->expectVec(p.world_center, Vec3(1, 2, 3));
  this->expectVec(p.local_center, Vec3(4, 5, 6));
}

TYPED_TEST(TransformationIo, SetTransformationMatrixTakesTranslationFromM12ToM14) {
  Placement p = startState();
  // 90 degrees about x, (x,y,z) -> (x,-z,y), translation (1,1,1).
  ASSERT_EQ(this->set(p, SC_TRANSFORMATION_MATRIX,
                      {1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 1, 1, 1, 1}),
            SC_NO_ERROR);
  this->expectVec(p.world_center, Vec3(5, -5, 6));  // R'(4,5,6) + (1,1,1)
  this->expectVec(p.local_center, Vec3(4, 5, 6));
  EXPECT_LE(quatDistance(p.orientation, Quat(kHalfSqrt2, kHalfSqrt2, 0, 0)), 1e-12);
  this->expectVec(p.origin(), Vec3(1, 1, 1));
}

TYPED_TEST(TransformationIo, AcceptsRotationsRoundedToThisPrecision) {
  const std::uint64_t seed = 11;
  test::Rng rng(seed);
  for (int k = 0; k < 100; ++k) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed << ", case " << k);
    const Quat q = test::randomRotation(rng);
    Placement p;
    p.orientation = q;
    p.world_center = Vec3(3, -4, 5);
    const std::vector<double> r = this->get(p, SC_ORIENTATION_MATRIX);
    const std::vector<double> m = this->get(p, SC_TRANSFORMATION_MATRIX);
    Placement by_r, by_m;
    ASSERT_EQ(this->set(by_r, SC_ORIENTATION_MATRIX, r), SC_NO_ERROR);
    ASSERT_EQ(this->set(by_m, SC_TRANSFORMATION_MATRIX, m), SC_NO_ERROR);
    EXPECT_LE(quatDistance(by_r.orientation, q), 10 * this->tol(0));
    EXPECT_LE(quatDistance(by_m.orientation, q), 10 * this->tol(0));
    this->expectVec(by_m.world_center, Vec3(3, -4, 5));
  }
}

// ---- Table 7-2 through arrays ----------------------------------------------------

TYPED_TEST(TransformationIo, GetOriginIsWorldCenterMinusRotatedLocalCenter) {
  this->expectValues(this->get(startState(), SC_POSITION_ORIGIN), {6, -2, -3});
}

TYPED_TEST(TransformationIo, GetWorldCenter) {
  this->expectValues(this->get(startState(), SC_POSITION_WORLD_CENTER), {1, 2, 3});
}

TYPED_TEST(TransformationIo, GetLocalCenter) {
  this->expectValues(this->get(startState(), SC_POSITION_LOCAL_CENTER), {4, 5, 6});
}

TYPED_TEST(TransformationIo, GetQuaternionIsScalarFirst) {
  this->expectValues(this->get(startState(), SC_ORIENTATION_QUATERNION),
                     {kHalfSqrt2, 0, 0, kHalfSqrt2});
}

TYPED_TEST(TransformationIo, GetOrientationMatrixIsColumnMajor) {
  // R = [0 -1 0; 1 0 0; 0 0 1]: columns (0,1,0), (-1,0,0), (0,0,1).
  this->expectValues(this->get(startState(), SC_ORIENTATION_MATRIX), {0, 1, 0, -1, 0, 0, 0, 0, 1});
}

TYPED_TEST(TransformationIo, GetTransformationMatrixIsColumnMajorWithOriginAtM12) {
  this->expectValues(this->get(startState(), SC_TRANSFORMATION_MATRIX),
                     {0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 6, -2, -3, 1});
}

TYPED_TEST(TransformationIo, GetNewCentersIsInvalidAndWritesNothing) {
  for (SCenum type : {SC_POSITION_NEW_WORLD_CENTER, SC_POSITION_NEW_LOCAL_CENTER}) {
    TypeParam out[3] = {7, 7, 7};
    EXPECT_EQ(getTransformation(startState(), type, out), SC_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(out[0], 7);
    EXPECT_EQ(out[1], 7);
    EXPECT_EQ(out[2], 7);
  }
}

TYPED_TEST(TransformationIo, EveryReadableTypeRoundTripsThroughSet) {
  const std::uint64_t seed = 12;
  test::Rng rng(seed);
  Placement source;
  source.world_center = Vec3(test::uniform(rng, -9, 9), test::uniform(rng, -9, 9), 2);
  source.local_center = Vec3(test::uniform(rng, -9, 9), -1, test::uniform(rng, -9, 9));
  source.orientation = test::randomRotation(rng);
  for (SCenum type : kReadableTypes) {
    SCOPED_TRACE(::testing::Message() << "type " << type << ", seed " << seed);
    const std::vector<double> values = this->get(source, type);
    Placement target = source;
    ASSERT_EQ(this->set(target, type, values), SC_NO_ERROR);
    // LOCAL_CENTER re-applied at its own value and the rest leave M unchanged.
    const Eigen::Matrix4d diff = target.matrix() - source.matrix();
    EXPECT_LE(diff.norm(), 10 * this->tol(10));
  }
}

// ---- Invalid input: rejected, placement unchanged --------------------------------

TYPED_TEST(TransformationIo, NullPointerIsInvalid) {
  for (SCenum type : kAllTypes) {
    Placement p = startState();
    EXPECT_EQ(setTransformation(p, type, static_cast<const TypeParam*>(nullptr)),
              SC_ERROR_INVALID_ARGUMENT);
    EXPECT_TRUE(bitwiseEqual(p, startState()));
    EXPECT_EQ(getTransformation(p, type, static_cast<TypeParam*>(nullptr)), SC_ERROR_INVALID_ARGUMENT);
  }
}

TYPED_TEST(TransformationIo, UnknownTypeIsInvalid) {
  for (SCenum type : kUnknownTypes) {
    EXPECT_EQ(transformationArraySize(type), 0);
    std::vector<TypeParam> values(16, TypeParam(1));
    this->expectRejected(type, values);
    std::vector<TypeParam> out(16, TypeParam(7));
    EXPECT_EQ(getTransformation(startState(), type, out.data()), SC_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(out, std::vector<TypeParam>(16, TypeParam(7)));
  }
}

TYPED_TEST(TransformationIo, NonFiniteValueAnywhereIsInvalid) {
  const std::vector<TypeParam> bad = test::nonFinite<TypeParam>();
  for (SCenum type : kAllTypes) {
    const std::vector<double> valid = validValues(type);
    ASSERT_EQ(static_cast<int>(valid.size()), transformationArraySize(type));
    Placement check = startState();
    ASSERT_EQ(this->set(check, type, valid), SC_NO_ERROR) << "type " << type;
    for (size_t i = 0; i < valid.size(); ++i) {
      for (TypeParam b : bad) {
        SCOPED_TRACE(::testing::Message() << "index " << i << ", value " << b);
        std::vector<TypeParam> values(valid.begin(), valid.end());
        values[i] = b;
        this->expectRejected(type, values);
      }
    }
  }
}

TYPED_TEST(TransformationIo, ZeroQuaternionIsInvalid) {
  this->expectRejected(SC_ORIENTATION_QUATERNION, {0, 0, 0, 0});
  this->expectRejected(SC_ORIENTATION_QUATERNION, {-0.0f, 0, -0.0f, 0});
  // The smallest non-zero one is still a direction.
  Placement p;
  const TypeParam tiny = std::numeric_limits<TypeParam>::denorm_min();
  const std::vector<TypeParam> values = {0, 0, tiny, 0};
  ASSERT_EQ(setTransformation(p, SC_ORIENTATION_QUATERNION, values.data()), SC_NO_ERROR);
  EXPECT_EQ(p.orientation.y(), 1.0);
}

TYPED_TEST(TransformationIo, NonRotationMatrixIsInvalid) {
  const std::vector<std::vector<TypeParam>> not_rotations = {
      {2, 0, 0, 0, 2, 0, 0, 0, 2},         // scale
      {1, 0, 0, 0, 1, 0, 0, 0, -1},        // reflection
      {-1, 0, 0, 0, -1, 0, 0, 0, -1},      // point reflection
      {1, 0, 0, 0.01f, 1, 0, 0, 0, 1},     // shear
      {0, 0, 0, 0, 0, 0, 0, 0, 0},         // zero
      {1.001f, 0, 0, 0, 1, 0, 0, 0, 1},    // 2e-3 off, beyond the tolerance
  };
  for (const std::vector<TypeParam>& r : not_rotations) {
    this->expectRejected(SC_ORIENTATION_MATRIX, r);
    std::vector<TypeParam> m = {r[0], r[1], r[2], 0, r[3], r[4], r[5], 0,
                                r[6], r[7], r[8], 0, 1,    2,    3,    1};
    this->expectRejected(SC_TRANSFORMATION_MATRIX, m);
  }
}

TYPED_TEST(TransformationIo, TransformationMatrixWithBadLastRowIsInvalid) {
  const std::vector<double> valid = validValues(SC_TRANSFORMATION_MATRIX);
  for (int index : {3, 7, 11, 15}) {
    for (double delta : {1e-2, -1e-3, 1.0}) {
      SCOPED_TRACE(::testing::Message() << "m" << index << " + " << delta);
      std::vector<TypeParam> values(valid.begin(), valid.end());
      values[index] = static_cast<TypeParam>(values[index] + delta);
      this->expectRejected(SC_TRANSFORMATION_MATRIX, values);
    }
  }
  // Rounding noise in the last row is accepted.
  std::vector<TypeParam> noisy(valid.begin(), valid.end());
  noisy[3] = static_cast<TypeParam>(1e-6);
  noisy[15] = static_cast<TypeParam>(1 - 1e-6);
  Placement p;
  EXPECT_EQ(setTransformation(p, SC_TRANSFORMATION_MATRIX, noisy.data()), SC_NO_ERROR);
}

// ---- Manual Lists 7-1 and 7-2 ----------------------------------------------------

TYPED_TEST(TransformationIo, List71AndList72EndWithTheSamePlacement) {
  // List 7-2: origin, then orientation, then a new world centre (which keeps r_O).
  Placement list72;
  ASSERT_EQ(this->set(list72, SC_POSITION_ORIGIN, {-3, 61, 29}), SC_NO_ERROR);
  ASSERT_EQ(this->set(list72, SC_ORIENTATION_QUATERNION, {0.707107, 0.707107, 0, 0}), SC_NO_ERROR);
  ASSERT_EQ(this->set(list72, SC_POSITION_NEW_WORLD_CENTER, {10, 50, 35}), SC_NO_ERROR);

  // List 7-1 is an image missing from the text; the manual only says it reaches the
  // same transformation by another sequence. Reconstructed: put the local centre
  // where List 7-2 ends, R^-1((10,50,35) - (-3,61,29)) = R^-1(13,-11,6) = (13,6,11),
  // then rotate about it, then move it to the world centre.
  Placement list71;
  ASSERT_EQ(this->set(list71, SC_POSITION_NEW_LOCAL_CENTER, {13, 6, 11}), SC_NO_ERROR);
  ASSERT_EQ(this->set(list71, SC_ORIENTATION_QUATERNION, {0.707107, 0.707107, 0, 0}), SC_NO_ERROR);
  ASSERT_EQ(this->set(list71, SC_POSITION_WORLD_CENTER, {10, 50, 35}), SC_NO_ERROR);

  for (const Placement* p : {&list72, &list71}) {
    this->expectValues(this->get(*p, SC_POSITION_WORLD_CENTER), {10, 50, 35});
    this->expectValues(this->get(*p, SC_POSITION_LOCAL_CENTER), {13, 6, 11});
    this->expectValues(this->get(*p, SC_POSITION_ORIGIN), {-3, 61, 29});
    this->expectValues(this->get(*p, SC_ORIENTATION_QUATERNION), {kHalfSqrt2, kHalfSqrt2, 0, 0});
  }
  for (SCenum type : kReadableTypes) {
    SCOPED_TRACE(::testing::Message() << "type " << type);
    this->expectValues(this->get(list71, type), this->get(list72, type));
  }
}

// ---- Magnitude limits (double only: float cannot express them) -------------------

TEST(TransformationIoLimits, HugeFiniteInputIsInvalidSoNothingOverflows) {
  Placement p = startState();
  const double huge[] = {1e301, 0, 0};
  EXPECT_EQ(setTransformation(p, SC_POSITION_WORLD_CENTER, huge), SC_ERROR_INVALID_ARGUMENT);
  // Centres are held to the vertex limit, 1e100: beyond it distances and motions
  // between placed models could overflow.
  const double beyond[] = {0, -1.01e100, 0};
  EXPECT_EQ(setTransformation(p, SC_POSITION_WORLD_CENTER, beyond), SC_ERROR_INVALID_ARGUMENT);
  // Each accepted step is bounded, but stacking them is refused.
  const double big[] = {9e99, -9e99, 9e99};
  EXPECT_EQ(setTransformation(p, SC_POSITION_WORLD_CENTER, big), SC_NO_ERROR);
  const Placement before = p;
  EXPECT_EQ(setTransformation(p, SC_POSITION_LOCAL_CENTER, big), SC_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(bitwiseEqual(p, before));
}

TEST(TransformationIoLimits, ValueBeyondFloatRangeIsNotReadAsFloat) {
  Placement p;
  p.world_center = Vec3(1e100, 0, 0);
  float out[3] = {7, 7, 7};
  EXPECT_EQ(getTransformation(p, SC_POSITION_WORLD_CENTER, out), SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(out[0], 7.0f);
  double out_d[3];
  EXPECT_EQ(getTransformation(p, SC_POSITION_WORLD_CENTER, out_d), SC_NO_ERROR);
  EXPECT_EQ(out_d[0], 1e100);
}

}  // namespace
}  // namespace sc::detail
