// SPDX-License-Identifier: MIT
// Bi-directional penetration depth (manual 5.10): with both groups moving and both
// directions requested, each direction is present and valid about its own centre of
// rotation, and swapping which group is A changes nothing but the labels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "penetration/result_invariants.h"
#include "sc_support/off_mesh.h"
#include "smartcollision/collision.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::test {
namespace {

constexpr int kCases = caseCount(300, 30);
constexpr int kSteps = 16;

/// The same result up to rounding: every field within 1e-12 (relative to 1).
void expectSame(const DirectedResult& x, const DirectedResult& y) {
  EXPECT_EQ(x.code, y.code);
  if (x.code != ErrorCode::Ok || y.code != ErrorCode::Ok) return;
  EXPECT_EQ(x.target_object, y.target_object);
  EXPECT_EQ(x.opponent_object, y.opponent_object);
  EXPECT_EQ(x.target_piece, y.target_piece);
  EXPECT_EQ(x.opponent_piece, y.opponent_piece);
  EXPECT_NEAR(x.distance, y.distance, 1e-12);
  EXPECT_VEC_NEAR(x.normal, y.normal, 1e-12);
  EXPECT_VEC_NEAR(x.point_on_target, y.point_on_target, 1e-12);
  EXPECT_VEC_NEAR(x.point_on_opponent, y.point_on_opponent, 1e-12);
  EXPECT_VEC_NEAR(x.tpdv, y.tpdv, 1e-12);
  EXPECT_VEC_NEAR(x.rpdv, y.rpdv, 1e-12);
  EXPECT_VEC_NEAR(x.contact_position, y.contact_position, 1e-12);
  EXPECT_LE(x.contact_orientation.angularDistance(y.contact_orientation), 1e-12);
  EXPECT_EQ(x.target_feature.type, y.target_feature.type);
  EXPECT_EQ(x.opponent_feature.type, y.opponent_feature.type);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(x.target_feature.vertices[k], y.target_feature.vertices[k]);
    EXPECT_EQ(x.opponent_feature.vertices[k], y.opponent_feature.vertices[k]);
  }
}

/// Every field equal, bit for bit.
bool identical(const DirectedResult& x, const DirectedResult& y) {
  const auto same_feature = [](const Feature& f, const Feature& g) {
    return f.type == g.type && f.vertices[0] == g.vertices[0] && f.vertices[1] == g.vertices[1] &&
           f.vertices[2] == g.vertices[2];
  };
  return x.code == y.code && x.target_object == y.target_object &&
         x.opponent_object == y.opponent_object && x.target_piece == y.target_piece &&
         x.opponent_piece == y.opponent_piece && x.distance == y.distance &&
         x.normal == y.normal && x.point_on_target == y.point_on_target &&
         x.point_on_opponent == y.point_on_opponent && x.tpdv == y.tpdv && x.rpdv == y.rpdv &&
         x.contact_position == y.contact_position &&
         x.contact_orientation.coeffs() == y.contact_orientation.coeffs() &&
         same_feature(x.target_feature, y.target_feature) &&
         same_feature(x.opponent_feature, y.opponent_feature);
}

Placement placementAt(const Vec3& local_center, const Quat& q, const Vec3& world_center) {
  Placement p;
  p.local_center = local_center;
  p.orientation = q;
  p.world_center = world_center;
  return p;
}

TEST(Bidirectional, BothDirectionsValidAndSwapOnlyRelabels) {
  const std::uint64_t seed = 510;
  SCOPED_TRACE(testing::Message() << "seed " << seed);
  Rng rng(seed);
  Result<MeshData> l_prism = support::readOff(std::string(SC_TEST_DATA_DIR) + "/l_prism.off");
  ASSERT_TRUE(l_prism.ok()) << l_prism.status().message();
  const ModelPtr l_model = closedModel(l_prism.value());
  ASSERT_TRUE(l_model);
  const double l_size = (l_model->bounds().max - l_model->bounds().min).maxCoeff();
  const RotationMode modes[4] = {RotationMode::None, RotationMode::Input, RotationMode::Free,
                                 RotationMode::Mix};
  int both_penetrating = 0, one_penetrating = 0, apart = 0, bitwise = 0, compared = 0;
  for (int i = 0; i < kCases; ++i) {
    SCOPED_TRACE(testing::Message() << "case " << i);
    // A: a random convex shape or the L-prism (non-convex); B: a random convex shape.
    ModelPtr ma;
    double size_a = 1.0;
    if (i % 3 == 0) {
      ma = l_model;
      size_a = l_size;
    } else {
      ma = closedModel(meshOf(randomConvexShape(rng, 1.0).poly));
    }
    const ModelPtr mb = closedModel(meshOf(randomConvexShape(rng, uniform(rng, 0.5, 2.0)).poly));
    ASSERT_TRUE(ma && mb);
    const Part part_a{ma.get(), Rigid(), 11}, part_b{mb.get(), Rigid(), 22};
    // Centres of rotation off the shapes' centres, so the two directions differ.
    const Vec3 ca = 0.3 * size_a * randomDirection(rng), cb = 0.3 * randomDirection(rng);
    const Vec3 u = randomDirection(rng);
    // Start apart: each centre of rotation farther from the origin than its shape reaches.
    const auto reach = [](const Model& m, const Vec3& c) {
      return (m.bounds().max - c).cwiseAbs().cwiseMax((m.bounds().min - c).cwiseAbs()).norm();
    };
    const double s0 = reach(*ma, ca) + reach(*mb, cb) + 0.1;
    const Quat qa = randomRotation(rng), qb = randomRotation(rng);
    const Vec3 wa = randomDirection(rng), wb = randomDirection(rng);
    const double spin = uniform(rng, 0.0, 0.01);
    SceneSettings settings;
    settings.tolerance = 1e-3;
    settings.rotation_mode = modes[i % 4];
    PairTracker ab, ba;
    DirectedResult r_ab[2], r_ba[2];
    // Both move towards each other along u, overlap, then go back.
    for (int k = 0; k <= kSteps; ++k) {
      SCOPED_TRACE(testing::Message() << "step " << k);
      const double t = k <= kSteps / 2 ? k : kSteps - k;
      const double s = 0.5 * s0 * (1.0 - 0.1 * t);
      const Placement pa = placementAt(ca, Quat(Eigen::AngleAxisd(spin * t, wa)) * qa, s * u);
      const Placement pb = placementAt(cb, Quat(Eigen::AngleAxisd(spin * t, wb)) * qb, -s * u);
      const GroupView a{&part_a, 1, pa}, b{&part_b, 1, pb};
      ab.update(a, b, {true, true}, settings, r_ab);
      ba.update(b, a, {true, true}, settings, r_ba);
      ASSERT_EQ(r_ab[0].code, ErrorCode::Ok);
      ASSERT_EQ(r_ab[1].code, ErrorCode::Ok);
      EXPECT_EQ(r_ab[0].target_object, 11);
      EXPECT_EQ(r_ab[1].target_object, 22);
      Status valid = detail::checkResult(r_ab[0], pa, pb);
      EXPECT_TRUE(valid.ok()) << "A->B: " << valid.message();
      valid = detail::checkResult(r_ab[1], pb, pa);
      EXPECT_TRUE(valid.ok()) << "B->A: " << valid.message();
      const bool pa_in = r_ab[0].penetrating(), pb_in = r_ab[1].penetrating();
      if (pa_in && pb_in) {
        ++both_penetrating;
      } else if (!pa_in && !pb_in) {
        ++apart;
        // Apart, the two directions are the same minimum distance seen from each side.
        EXPECT_NEAR(r_ab[0].distance, r_ab[1].distance, 1e-12 * (1.0 + r_ab[0].distance));
        EXPECT_VEC_NEAR(r_ab[0].normal, -r_ab[1].normal, 1e-9);
      } else {
        ++one_penetrating;  // one proxy may lag behind on leaving; reported below
      }
      expectSame(r_ba[0], r_ab[1]);
      expectSame(r_ba[1], r_ab[0]);
      ++compared;
      if (identical(r_ba[0], r_ab[1]) && identical(r_ba[1], r_ab[0])) ++bitwise;
      if (HasFatalFailure()) return;
    }
  }
  std::printf(
      "[ bidirectional ] %d cases, %d updates: both penetrating %d, both apart %d, one only "
      "%d; swapped A/B identical bit for bit in %d of %d\n",
      kCases, compared, both_penetrating, apart, one_penetrating, bitwise, compared);
  EXPECT_GT(both_penetrating, kCases);
}

}  // namespace
}  // namespace sc::test
