// SPDX-License-Identifier: MIT
// Result invariants: hand-made results that keep the contract pass, each single
// violation fails, and every result of real tracked sequences (all rotation modes)
// passes both checks.
#include "penetration/result_invariants.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "geometry/math_util.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::detail {
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

Placement placementAt(const Vec3& center, const Quat& q = Quat::Identity()) {
  Placement p;
  p.world_center = center;
  p.orientation = q;
  return p;
}

/// Unit cube target centred at (3, 0, 0) one unit from a unit cube opponent at the
/// origin, as the tracker reports it apart.
struct ApartCase {
  Placement target = placementAt(Vec3(3, 0, 0));
  Placement opponent = placementAt(Vec3::Zero());
  DirectedResult r;
  ApartCase() {
    r.code = ErrorCode::Ok;
    r.target_object = 7;
    r.opponent_object = -3;  // ids are the caller's and may be negative
    r.target_piece = 0;
    r.opponent_piece = 0;
    r.distance = 1.0;
    r.normal = Vec3::UnitX();
    r.point_on_target = Vec3(2.5, 0.1, 0.2);
    r.point_on_opponent = Vec3(1.5, 0.1, 0.2);
    r.target_feature.type = FeatureType::Face;
    r.target_feature.vertices[0] = 0;
    r.target_feature.vertices[1] = 2;
    r.target_feature.vertices[2] = 4;
    r.opponent_feature.type = FeatureType::Edge;
    r.opponent_feature.vertices[0] = 1;
    r.opponent_feature.vertices[1] = 3;
    r.contact_position = target.world_center;
    r.contact_orientation = target.orientation;
  }
};

/// Target at (1.7, 0, 0) turned by 0.3 rad about z, penetrating by TPDV (-0.3, 0, 0)
/// and RPDV (0, 0, 0.1) from its contact configuration.
struct PenetratingCase {
  Placement target = placementAt(Vec3(1.7, 0, 0), Quat(Eigen::AngleAxisd(0.3, Vec3::UnitZ())));
  Placement opponent = placementAt(Vec3::Zero());
  DirectedResult r;
  PenetratingCase() {
    r.code = ErrorCode::Ok;
    r.target_piece = 1;
    r.opponent_piece = 0;
    r.tpdv = Vec3(-0.3, 0, 0);
    r.rpdv = Vec3(0, 0, 0.1);
    r.distance = -0.3;
    r.normal = Vec3::UnitX();
    r.point_on_target = Vec3(1.0, 0, 0);
    r.point_on_opponent = Vec3(1.0, 0, 0);
    r.contact_position = target.world_center - r.tpdv;
    r.contact_orientation = Quat(Eigen::AngleAxisd(0.2, Vec3::UnitZ()));
    r.target_feature.type = FeatureType::Vertex;
    r.target_feature.vertices[0] = 5;
    r.opponent_feature.type = FeatureType::Face;
    r.opponent_feature.vertices[0] = 0;
    r.opponent_feature.vertices[1] = 1;
    r.opponent_feature.vertices[2] = 2;
  }
};

TEST(ResultInvariants, ConsistentApartAndPenetratingResultsPass) {
  const ApartCase a;
  EXPECT_TRUE(checkResult(a.r).ok()) << checkResult(a.r).message();
  EXPECT_TRUE(checkResult(a.r, a.target, a.opponent).ok())
      << checkResult(a.r, a.target, a.opponent).message();
  const PenetratingCase p;
  EXPECT_TRUE(checkResult(p.r).ok()) << checkResult(p.r).message();
  EXPECT_TRUE(checkResult(p.r, p.target, p.opponent).ok())
      << checkResult(p.r, p.target, p.opponent).message();
}

TEST(ResultInvariants, NonOkCodesPassWhateverTheirUndefinedFields) {
  for (ErrorCode code : {ErrorCode::NoResult, ErrorCode::InvalidInitialTransformation}) {
    DirectedResult r;
    r.code = code;
    r.distance = kNaN;
    r.normal.setZero();
    EXPECT_TRUE(checkResult(r).ok());
    EXPECT_TRUE(checkResult(r, Placement(), Placement()).ok());
  }
}

TEST(ResultInvariants, CodesThatNoDirectionReportsFail) {
  for (ErrorCode code : {ErrorCode::InvalidGeometry, ErrorCode::InvalidArgument,
                         ErrorCode::InvalidId, ErrorCode::InvalidOperation, ErrorCode::File}) {
    DirectedResult r;
    r.code = code;
    EXPECT_FALSE(checkResult(r).ok()) << static_cast<int>(code);
  }
}

struct Violation {
  const char* name;
  std::function<void(DirectedResult&)> apply;
};

TEST(ResultInvariants, EachSingleViolationOfAnApartResultFails) {
  const std::vector<Violation> violations = {
      {"NaN distance", [](DirectedResult& r) { r.distance = kNaN; }},
      {"infinite distance",
       [](DirectedResult& r) { r.distance = std::numeric_limits<double>::infinity(); }},
      {"NaN point", [](DirectedResult& r) { r.point_on_opponent.y() = kNaN; }},
      {"NaN contact position", [](DirectedResult& r) { r.contact_position.z() = kNaN; }},
      {"NaN quaternion", [](DirectedResult& r) { r.contact_orientation.w() = kNaN; }},
      {"long normal", [](DirectedResult& r) { r.normal *= 1.0 + 1e-8; }},
      {"zero normal", [](DirectedResult& r) { r.normal.setZero(); }},
      {"short quaternion",
       [](DirectedResult& r) { r.contact_orientation.coeffs() *= 1.0 - 1e-8; }},
      {"TPDV while apart", [](DirectedResult& r) { r.tpdv.x() = 1e-300; }},
      {"RPDV while apart", [](DirectedResult& r) { r.rpdv.z() = 1e-300; }},
      {"negative piece", [](DirectedResult& r) { r.target_piece = -1; }},
      {"face with two vertices", [](DirectedResult& r) { r.target_feature.vertices[2] = -1; }},
      {"edge with three vertices", [](DirectedResult& r) { r.opponent_feature.vertices[2] = 5; }},
      {"bad feature type",
       [](DirectedResult& r) { r.opponent_feature.type = static_cast<FeatureType>(3); }},
  };
  for (const Violation& v : violations) {
    ApartCase a;
    v.apply(a.r);
    EXPECT_FALSE(checkResult(a.r).ok()) << v.name;
    EXPECT_FALSE(checkResult(a.r, a.target, a.opponent).ok()) << v.name;
  }
}

TEST(ResultInvariants, ApartGeometryIsCheckedAgainstThePlacements) {
  const std::vector<Violation> violations = {
      {"points not distance apart", [](DirectedResult& r) { r.distance = 1.0 + 1e-6; }},
      {"normal not along the points",
       [](DirectedResult& r) { r.normal = Vec3(1, 1e-6, 0).normalized(); }},
      {"contact position elsewhere", [](DirectedResult& r) { r.contact_position.y() += 1e-6; }},
      {"contact orientation turned",
       [](DirectedResult& r) {
         r.contact_orientation = Quat(Eigen::AngleAxisd(1e-6, Vec3::UnitY()));
       }},
  };
  for (const Violation& v : violations) {
    ApartCase a;
    v.apply(a.r);
    EXPECT_TRUE(checkResult(a.r).ok()) << v.name << ": not visible without placements";
    EXPECT_FALSE(checkResult(a.r, a.target, a.opponent).ok()) << v.name;
  }
}

TEST(ResultInvariants, PenetratingDistanceMustBeMinusTpdvLengthWithin1e12Relative) {
  PenetratingCase p;
  p.r.distance = -0.3 * (1.0 + 2e-13);
  EXPECT_TRUE(checkResult(p.r).ok()) << checkResult(p.r).message();
  p.r.distance = -0.3 * (1.0 + 2e-12);
  EXPECT_FALSE(checkResult(p.r).ok());
  p.r.distance = -0.3 * (1.0 - 2e-12);
  EXPECT_FALSE(checkResult(p.r).ok());
  // A pure rotational depth: TPDV zero, distance exactly zero.
  p.r.tpdv.setZero();
  p.r.distance = 0.0;
  EXPECT_TRUE(checkResult(p.r).ok());
  p.r.distance = -1e-300;
  EXPECT_FALSE(checkResult(p.r).ok());
}

TEST(ResultInvariants, EachSingleViolationOfAPenetratingResultFails) {
  const std::vector<Violation> violations = {
      {"RPDV beyond pi", [](DirectedResult& r) { r.rpdv = Vec3(0, 0, 3.2); }},
      {"contact position not centre - TPDV",
       [](DirectedResult& r) { r.contact_position.x() += 1e-6; }},
      {"RPDV not the rotation from contact", [](DirectedResult& r) { r.rpdv.z() += 1e-6; }},
      {"contact orientation turned",
       [](DirectedResult& r) {
         r.contact_orientation = Quat(Eigen::AngleAxisd(0.2 + 1e-6, Vec3::UnitZ()));
       }},
  };
  for (const Violation& v : violations) {
    PenetratingCase p;
    v.apply(p.r);
    EXPECT_FALSE(checkResult(p.r, p.target, p.opponent).ok()) << v.name;
  }
}

TEST(ResultInvariants, HugeFiniteFieldsAreJudgedWithoutOverflow) {
  // |tpdv| overflows a naive norm; the check still compares it with the distance.
  PenetratingCase p;
  p.r.tpdv = Vec3(-1e200, -1e200, 0);
  p.r.distance = -std::sqrt(2.0) * 1e200;
  p.r.contact_position = p.target.world_center - p.r.tpdv;
  EXPECT_TRUE(checkResult(p.r).ok()) << checkResult(p.r).message();
  EXPECT_TRUE(checkResult(p.r, p.target, p.opponent).ok())
      << checkResult(p.r, p.target, p.opponent).message();
}

TEST(ResultInvariants, EnforceAbortsInDebugAndIsSilentInRelease) {
  ApartCase a;
  enforceResultInvariants(a.r, a.target, a.opponent);  // valid: never aborts
  a.r.normal *= 2.0;
  if constexpr (kCheckResultInvariants) {
    EXPECT_DEATH(enforceResultInvariants(a.r), "normal is not unit");
  } else {
    enforceResultInvariants(a.r);
    SUCCEED() << "NDEBUG build: the check is compiled out";
  }
}

// Real results: every update of tracked pairs, in every rotation mode, keeps both
// checks. Ground truth is the contract itself (docs/api.md, "Results").
TEST(ResultInvariants, TrackedSequencesInEveryRotationModeKeepThem) {
  const std::uint64_t seed = 9090901;
  SCOPED_TRACE(testing::Message() << "seed " << seed);
  test::Rng rng(seed);
  const ModelPtr box = test::closedModel(test::boxMesh(Vec3(0.5, 0.4, 0.3)));
  const ModelPtr tet = test::closedModel(test::regularTetrahedronMesh(0.8));
  const Part part_a{box.get(), Rigid(), 1}, part_b{tet.get(), Rigid(), 2};
  int apart = 0, penetrating = 0;
  for (RotationMode mode :
       {RotationMode::None, RotationMode::Input, RotationMode::Free, RotationMode::Mix}) {
    for (int run = 0; run < 20; ++run) {
      PairSettings settings;
      settings.rotation_mode = mode;
      PairTracker tracker;
      Placement pb = placementAt(Vec3::Zero(), test::randomRotation(rng));
      pb.local_center = 0.1 * test::randomDirection(rng);
      const Vec3 dir = test::randomDirection(rng);
      const Quat q0 = test::randomRotation(rng);
      const Vec3 spin = 0.05 * test::randomDirection(rng);
      // From 3 units away straight through the opponent, turning as it goes.
      for (int step = 0; step <= 40; ++step) {
        Placement pa = placementAt(dir * (3.0 - 0.1 * step),
                                   Quat(rotationFromVector(spin * step)) * q0);
        pa.local_center = Vec3(0.05, -0.02, 0.01);
        DirectedResult out[2];
        tracker.update({&part_a, 1, pa}, {&part_b, 1, pb}, {true, true}, settings, out);
        for (int d = 0; d < 2; ++d) {
          const Placement& target = d == 0 ? pa : pb;
          const Placement& opponent = d == 0 ? pb : pa;
          const Status s = checkResult(out[d], target, opponent);
          ASSERT_TRUE(s.ok()) << s.message() << " mode " << static_cast<int>(mode) << " run "
                              << run << " step " << step << " direction " << d;
          if (out[d].code != ErrorCode::Ok) continue;
          ++(out[d].distance > 0.0 ? apart : penetrating);
        }
      }
    }
  }
  // The sample covers both branches substantially.
  EXPECT_GT(apart, 500);
  EXPECT_GT(penetrating, 500);
}

}  // namespace
}  // namespace sc::detail
