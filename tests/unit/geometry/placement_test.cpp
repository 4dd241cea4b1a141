// SPDX-License-Identifier: MIT
// Placement against hand-computed rows of manual Tables 7-1 (set) and 7-2 (get),
// plus the invariants of equation (7-1).
#include "smartcollision/placement.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/placements.h"
#include "support/test_support.h"

namespace sc {
namespace {

constexpr double kTol = 1e-12;
const double kHalfSqrt2 = std::sqrt(0.5);

using test::quatDistance;
using test::startState;

/// Runs `check` on `cases` draws of one generator seeded with `seed`, each case traced.
template <class Check>
void forCases(std::uint64_t seed, int cases, Check check) {
  test::Rng rng(seed);
  for (int k = 0; k < cases; ++k) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed << ", case " << k);
    check(rng);
  }
}

/// World position of local point r_L by the first form of (7-1).
Vec3 toWorld(const Placement& p, const Vec3& r_l) {
  return p.rotation() * (r_l - p.local_center) + p.world_center;
}

Placement randomPlacement(test::Rng& rng) {
  Placement p;
  for (int i = 0; i < 3; ++i) {
    p.world_center[i] = test::uniform(rng, -50, 50);
    p.local_center[i] = test::uniform(rng, -50, 50);
  }
  p.orientation = test::randomRotation(rng);
  return p;
}

Vec3 randomPoint(test::Rng& rng) {
  return Vec3(test::uniform(rng, -50, 50), test::uniform(rng, -50, 50), test::uniform(rng, -50, 50));
}

// ---- Table 7-1 -------------------------------------------------------------------

TEST(Placement, Table71OriginSetsWorldCenterToOriginPlusRotatedLocalCenter) {
  Placement p = startState();
  p.setOrigin(Vec3(10, 20, 30));
  // r_WC = (10,20,30) + R(4,5,6) = (10,20,30) + (-5,4,6).
  EXPECT_VEC_NEAR(p.world_center, Vec3(5, 24, 36), kTol);
  EXPECT_VEC_NEAR(p.local_center, Vec3(4, 5, 6), 0.0);
  EXPECT_VEC_NEAR(p.origin(), Vec3(10, 20, 30), kTol);
  EXPECT_EQ(p.orientation.coeffs(), startState().orientation.coeffs());
}

TEST(Placement, Table71WorldCenterSetsWorldCenterOnly) {
  Placement p = startState();
  p.setWorldCenter(Vec3(7, 8, 9));
  EXPECT_VEC_NEAR(p.world_center, Vec3(7, 8, 9), 0.0);
  EXPECT_VEC_NEAR(p.local_center, Vec3(4, 5, 6), 0.0);
  // r_O = (7,8,9) - (-5,4,6).
  EXPECT_VEC_NEAR(p.origin(), Vec3(12, 4, 3), kTol);
}

TEST(Placement, Table71LocalCenterMovesWorldCenterToWhereThatLocalPointWas) {
  Placement p = startState();
  const Vec3 was = toWorld(p, Vec3(1, 1, 1));
  p.setLocalCenter(Vec3(1, 1, 1));
  // r_WC = R((1,1,1) - (4,5,6)) + (1,2,3) = R(-3,-4,-5) + (1,2,3) = (4,-3,-5) + (1,2,3).
  EXPECT_VEC_NEAR(p.world_center, Vec3(5, -1, -2), kTol);
  EXPECT_VEC_NEAR(p.world_center, was, kTol);
  EXPECT_VEC_NEAR(p.local_center, Vec3(4, 5, 6), 0.0);  // literally: only r_WC changes
  // The object moves: r_O = (5,-1,-2) - (-5,4,6).
  EXPECT_VEC_NEAR(p.origin(), Vec3(10, -5, -8), kTol);
}

TEST(Placement, Table71NewWorldCenterMovesLocalCenterAndKeepsOrigin) {
  Placement p = startState();
  p.setNewWorldCenter(Vec3(7, 8, 9));
  // r_LC = R^-1((7,8,9) - (1,2,3)) + (4,5,6) = R^-1(6,6,6) + (4,5,6) = (6,-6,6) + (4,5,6).
  EXPECT_VEC_NEAR(p.local_center, Vec3(10, -1, 12), kTol);
  EXPECT_VEC_NEAR(p.world_center, Vec3(7, 8, 9), 0.0);
  EXPECT_VEC_NEAR(p.origin(), Vec3(6, -2, -3), kTol);
}

TEST(Placement, Table71NewLocalCenterMovesWorldCenterAndKeepsOrigin) {
  Placement p = startState();
  p.setNewLocalCenter(Vec3(1, 1, 1));
  // r_WC = R((1,1,1) - (4,5,6)) + (1,2,3) = (5,-1,-2), computed with the old r_LC.
  EXPECT_VEC_NEAR(p.world_center, Vec3(5, -1, -2), kTol);
  EXPECT_VEC_NEAR(p.local_center, Vec3(1, 1, 1), 0.0);
  EXPECT_VEC_NEAR(p.origin(), Vec3(6, -2, -3), kTol);
}

TEST(Placement, Table71QuaternionIsNormalisedAndKeepsBothCentres) {
  Placement p = startState();
  p.setOrientation(Quat(2, 2, 0, 0));  // 90 degrees about x, not unit
  EXPECT_NEAR(p.orientation.w(), kHalfSqrt2, kTol);
  EXPECT_NEAR(p.orientation.x(), kHalfSqrt2, kTol);
  EXPECT_EQ(p.orientation.y(), 0.0);
  EXPECT_EQ(p.orientation.z(), 0.0);
  EXPECT_NEAR(p.orientation.norm(), 1.0, 1e-15);
  EXPECT_VEC_NEAR(p.rotation() * Vec3(0, 1, 0), Vec3(0, 0, 1), kTol);
  EXPECT_VEC_NEAR(p.world_center, Vec3(1, 2, 3), 0.0);
  EXPECT_VEC_NEAR(p.local_center, Vec3(4, 5, 6), 0.0);
}

TEST(Placement, Table71OrientationMatrixSetsItsQuaternion) {
  Placement p = startState();
  Mat3 r_y90;  // 90 degrees about y: (x,y,z) -> (z,y,-x)
  r_y90 << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  const Result<Quat> q = rotationToQuaternion(r_y90);
  ASSERT_TRUE(q.ok());
  p.setOrientation(q.value());
  EXPECT_LE(quatDistance(p.orientation, Quat(kHalfSqrt2, 0, kHalfSqrt2, 0)), kTol);
  EXPECT_LE((p.rotation() - r_y90).norm(), kTol);
  EXPECT_VEC_NEAR(p.world_center, Vec3(1, 2, 3), 0.0);
  EXPECT_VEC_NEAR(p.local_center, Vec3(4, 5, 6), 0.0);
}

TEST(Placement, Table71OrientationMatrixOfHalfTurnGivesPureVectorQuaternion) {
  const Result<Quat> q = rotationToQuaternion(Vec3(1, -1, -1).asDiagonal());  // pi about x
  ASSERT_TRUE(q.ok());
  EXPECT_LE(quatDistance(q.value(), Quat(0, 1, 0, 0)), kTol);
}

TEST(Placement, Table71TransformationMatrixSetsWorldCenterAndOrientation) {
  Placement p = startState();
  Mat3 r_x90;  // 90 degrees about x: (x,y,z) -> (x,-z,y)
  r_x90 << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  p.setMatrix(r_x90, Vec3(1, 1, 1));
  // r_WC = M' r_LC = R'(4,5,6) + (1,1,1) = (4,-6,5) + (1,1,1).
  EXPECT_VEC_NEAR(p.world_center, Vec3(5, -5, 6), kTol);
  EXPECT_VEC_NEAR(p.local_center, Vec3(4, 5, 6), 0.0);
  EXPECT_LE(quatDistance(p.orientation, Quat(kHalfSqrt2, kHalfSqrt2, 0, 0)), kTol);
  EXPECT_VEC_NEAR(p.origin(), Vec3(1, 1, 1), kTol);
}

// ---- Table 7-2 -------------------------------------------------------------------

TEST(Placement, Table72OriginIsWorldCenterMinusRotatedLocalCenter) {
  EXPECT_VEC_NEAR(startState().origin(), Vec3(6, -2, -3), kTol);
  // The local origin is where r_L = 0 lands by (7-1).
  EXPECT_VEC_NEAR(startState().origin(), toWorld(startState(), Vec3::Zero()), kTol);
}

TEST(Placement, Table72WorldCenterIsTheStoredWorldCenter) {
  Placement p = startState();
  p.setNewWorldCenter(Vec3(7, 8, 9));
  EXPECT_VEC_NEAR(p.world_center, Vec3(7, 8, 9), 0.0);
  // r_WC is where r_LC lands.
  EXPECT_VEC_NEAR(toWorld(p, p.local_center), Vec3(7, 8, 9), 0.0);
}

TEST(Placement, Table72LocalCenterIsTheStoredLocalCenter) {
  Placement p = startState();
  p.setNewLocalCenter(Vec3(-2, 0, 5));
  EXPECT_VEC_NEAR(p.local_center, Vec3(-2, 0, 5), 0.0);
}

TEST(Placement, Table72QuaternionIsTheStoredUnitQuaternion) {
  Placement p;
  p.setOrientation(Quat(1, 2, 3, 4));
  const double n = std::sqrt(30.0);
  EXPECT_LE((p.orientation.coeffs() - Eigen::Vector4d(2, 3, 4, 1) / n).norm(), kTol);  // x y z w
}

TEST(Placement, Table72RotationFollowsTheManualsQuaternionFormula) {
  Mat3 r_z90;
  r_z90 << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  EXPECT_LE((startState().rotation() - r_z90).norm(), kTol);

  // The matrix R of (7-1) written out in s, vx, vy, vz.
  test::Rng rng(71);
  for (int k = 0; k < 20; ++k) {
    const Quat q = test::randomRotation(rng);
    const double s = q.w(), x = q.x(), y = q.y(), z = q.z();
    Mat3 manual;
    manual << 1 - 2 * (y * y + z * z), 2 * (x * y - s * z), 2 * (x * z + s * y),
        2 * (x * y + s * z), 1 - 2 * (z * z + x * x), 2 * (y * z - s * x),
        2 * (x * z - s * y), 2 * (y * z + s * x), 1 - 2 * (x * x + y * y);
    Placement p;
    p.orientation = q;
    EXPECT_LE((p.rotation() - manual).norm(), kTol) << "rng seed 71, case " << k;
  }
}

TEST(Placement, Table72MatrixIsTwcTimesRTimesTlcInverse) {
  const Placement p = startState();
  Eigen::Matrix4d expected;
  expected << 0, -1, 0, 6,  //
      1, 0, 0, -2,          //
      0, 0, 1, -3,          //
      0, 0, 0, 1;
  EXPECT_LE((p.matrix() - expected).norm(), kTol);
  // Column-major storage puts the translation at m12, m13, m14.
  EXPECT_NEAR(p.matrix().data()[12], 6, kTol);
  EXPECT_NEAR(p.matrix().data()[13], -2, kTol);
  EXPECT_NEAR(p.matrix().data()[14], -3, kTol);

  // T_LC^-1 is the translation by -r_LC (written out: clang's vectorised 4x4
  // inverse raises a trapped FP flag on this input).
  Eigen::Matrix4d t_wc = Eigen::Matrix4d::Identity(), t_lc_inv = Eigen::Matrix4d::Identity(),
                  r4 = Eigen::Matrix4d::Identity();
  t_wc.topRightCorner<3, 1>() = p.world_center;
  t_lc_inv.topRightCorner<3, 1>() = -p.local_center;
  r4.topLeftCorner<3, 3>() = p.rotation();
  EXPECT_LE((p.matrix() - t_wc * r4 * t_lc_inv).norm(), kTol);

  const Vec3 r_l(0.5, -7, 2);
  const Eigen::Vector4d h = p.matrix() * r_l.homogeneous();
  EXPECT_VEC_NEAR(h.head<3>(), toWorld(p, r_l), kTol);
  EXPECT_EQ(h[3], 1.0);
}

// ---- Invariants ------------------------------------------------------------------

TEST(Placement, NewCentersKeepOriginAndEveryPointOfTheObject) {
  forCases(20240701, 200, [](test::Rng& rng) {
    const Placement before = randomPlacement(rng);
    const Vec3 point = randomPoint(rng);
    Placement by_world = before, by_local = before;
    by_world.setNewWorldCenter(randomPoint(rng));
    by_local.setNewLocalCenter(randomPoint(rng));
    for (const Placement* p : {&by_world, &by_local}) {
      EXPECT_VEC_NEAR(p->origin(), before.origin(), 1e-11);
      EXPECT_VEC_NEAR(toWorld(*p, point), toWorld(before, point), 1e-11);
      EXPECT_EQ(p->orientation.coeffs(), before.orientation.coeffs());
    }
  });
}

TEST(Placement, SetMatrixRoundTripsThroughMatrix) {
  forCases(77, 200, [](test::Rng& rng) {
    const Placement source = randomPlacement(rng);
    const Eigen::Matrix4d m = source.matrix();
    Placement target = randomPlacement(rng);
    const Vec3 local_center = target.local_center;
    target.setMatrix(m.topLeftCorner<3, 3>(), m.topRightCorner<3, 1>());
    EXPECT_LE((target.matrix() - m).norm(), 1e-12);
    EXPECT_LE(quatDistance(target.orientation, source.orientation), 1e-12);
    EXPECT_VEC_NEAR(target.local_center, local_center, 0.0);  // r_LC is kept
    EXPECT_NEAR(target.orientation.norm(), 1.0, 1e-15);
  });
}

TEST(Placement, ZeroQuaternionKeepsTheCurrentOrientation) {
  Placement p = startState();
  p.setOrientation(Quat(0, 0, 0, 0));
  EXPECT_EQ(p.orientation.coeffs(), startState().orientation.coeffs());
}

TEST(Placement, TinyAndHugeQuaternionsNormaliseWithoutUnderflowOrOverflow) {
  Placement p;
  p.setOrientation(Quat(3e-170, 4e-170, 0, 0));
  EXPECT_LE((p.orientation.coeffs() - Eigen::Vector4d(0.8, 0, 0, 0.6)).norm(), kTol);
  p.setOrientation(Quat(4e200, 0, -3e200, 0));
  EXPECT_LE((p.orientation.coeffs() - Eigen::Vector4d(0, -0.6, 0, 0.8)).norm(), kTol);
}

// ---- rotationToQuaternion --------------------------------------------------------

TEST(RotationToQuaternion, RoundTripsRandomRotationsUpToSign) {
  forCases(5, 500, [](test::Rng& rng) {
    const Quat q = test::randomRotation(rng);
    const Result<Quat> back = rotationToQuaternion(q.toRotationMatrix());
    ASSERT_TRUE(back.ok());
    EXPECT_LE(quatDistance(back.value(), q), 1e-12);
    EXPECT_NEAR(back.value().norm(), 1.0, 1e-15);
  });
}

TEST(RotationToQuaternion, AcceptsRotationsRoundedToFloat) {
  forCases(6, 200, [](test::Rng& rng) {
    const Quat q = test::randomRotation(rng);
    const Mat3 rounded = q.toRotationMatrix().cast<float>().cast<double>();
    const Result<Quat> back = rotationToQuaternion(rounded);
    ASSERT_TRUE(back.ok());
    EXPECT_LE(quatDistance(back.value(), q), 1e-6);
  });
}

TEST(RotationToQuaternion, RejectsReflections) {
  const std::uint64_t seed = 7;
  test::Rng rng(seed);
  const Mat3 mirror = Vec3(1, 1, -1).asDiagonal();
  for (const Mat3& r : {Mat3(mirror), Mat3(-Mat3::Identity()),
                        Mat3(test::randomRotation(rng).toRotationMatrix() * mirror)}) {
    const Result<Quat> q = rotationToQuaternion(r);
    EXPECT_FALSE(q.ok());
    EXPECT_EQ(q.status().code(), ErrorCode::InvalidArgument);
  }
}

TEST(RotationToQuaternion, RejectsNonOrthonormalMatrices) {
  Mat3 shear = Mat3::Identity();
  shear(0, 1) = 0.01;
  Mat3 huge = Mat3::Identity();
  huge(0, 0) = 1e200;
  huge(0, 1) = -1e200;  // R^T R would be inf - inf without the entry bound
  Mat3 nan_entry = Mat3::Identity(), inf_entry = Mat3::Identity();
  nan_entry(2, 1) = std::numeric_limits<double>::quiet_NaN();
  inf_entry(1, 2) = -kInfinity;
  for (const Mat3& r : {Mat3(1.01 * Mat3::Identity()), shear, Mat3(Mat3::Zero()), huge,
                        nan_entry, inf_entry}) {
    const Result<Quat> q = rotationToQuaternion(r);
    EXPECT_FALSE(q.ok()) << r;
    EXPECT_EQ(q.status().code(), ErrorCode::InvalidArgument);
  }
  // The tolerance is what decides: 1e-3 off passes a 1e-2 tolerance, not 1e-4.
  const Mat3 slightly = (1.0 + 5e-4) * Mat3::Identity();  // |R^T R - I| = 1.73e-3
  EXPECT_FALSE(rotationToQuaternion(slightly).ok());
  EXPECT_TRUE(rotationToQuaternion(slightly, 1e-2).ok());
}

}  // namespace
}  // namespace sc
