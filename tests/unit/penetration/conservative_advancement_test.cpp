// SPDX-License-Identifier: MIT
// advance(): a long twist next to a non-convex model (a turn of a whole body, as a
// lagging Mix or Free proxy makes) gathers only the leaf pairs near where each of its
// passes starts, not every pair within the motion's reach (thousands, each query
// keeping them), and is still exact: along the part it advances no leaf pair comes
// nearer than skin / 2, and where calls going on from each other's stop end short of
// the motion's end, one is within the skin (checked by exact distances); a long motion
// that meets nothing completes in one call.
#include "penetration/conservative_advancement.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "geometry/math_util.h"
#include "support/meshes.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::detail {
namespace {

constexpr double kMaxReachMargins = 4.0;  // conservative_advancement.cpp's

struct Scene {
  ModelPtr model;
  Part t_part, o_part;
  GroupView t_view, o_view;
  Vec3 centre = Vec3::Zero();
  double size = 0.0;
  double tolerance = 0.0, skin = 0.0, margin = 0.0;  ///< as a proxy tracker's
  GroupPairQuery probe;                              ///< exact distances and the start poses

  Scene() {
    model = test::closedModel(test::loadTestMesh("elephant"));
    if (!model) return;
    centre = 0.5 * (model->bounds().min + model->bounds().max);
    size = 0.5 * (model->bounds().max - model->bounds().min).norm();
    tolerance = 1e-3 * size;
    skin = 0.25 * tolerance;
    margin = 2.0 * tolerance;
    t_part = {model.get(), Rigid(), 1};
    o_part = {model.get(), Rigid(), 2};
    t_view = {&t_part, 1, Placement()};
    o_view = {&o_part, 1, Placement()};
    probe.bind(t_view, o_view);
  }

  /// The target turned by `turn`, moved from far along d until it touches, then
  /// backed off by `gap` along d.
  Rigid nearPose(const Vec3& d, const Mat3& turn, double gap) {
    const Rigid far{turn, centre + 2.5 * size * d - turn * centre};
    const Vec3 in = -2.5 * size * d;
    const double s = probe.translationToi(far, in, 1e-9 * size, {});
    return {turn, far.translation + s * in + gap * d};
  }
};

class ConservativeAdvancement : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(scene.model); }
  Scene scene;
};

/// Smallest exact distance between the groups at `samples` poses of the motion in
/// [0, s].
double closestAlong(GroupPairQuery& probe, const TwistMotion& m, double s, int samples) {
  double closest = kInfinity;
  for (int i = 0; i <= samples; ++i) {
    LeafContact c;
    EXPECT_TRUE(probe.distance(m.at(s * i / samples), kInfinity, c));
    closest = std::min(closest, c.intersecting ? 0.0 : c.gap);
  }
  return closest;
}

TEST_F(ConservativeAdvancement, ALongTurnGathersOnlyNearPairsAndStopsOnlyAtAContact) {
  const double tolerance = scene.tolerance, skin = scene.skin, margin = scene.margin;
  GroupPairQuery& probe = scene.probe;
  test::Rng rng(0x5eed);
  for (int run = 0; run < (SC_TEST_SANITIZED ? 2 : 6); ++run) {
    SCOPED_TRACE(run);
    const Vec3 d = test::randomDirection(rng);
    const Mat3 turn = Eigen::AngleAxisd(6.0 * test::uniform(rng, 0, 1), test::randomDirection(rng))
                          .toRotationMatrix();
    TwistMotion m;
    m.start = scene.nearPose(d, turn, 2.0 * tolerance);
    m.center = scene.centre;
    m.dc = 0.05 * scene.size * test::randomDirection(rng);
    m.dtheta = 0.5 * test::randomDirection(rng);  // a point at the body's radius: 0.5 size
    GroupPairQuery query;
    query.bind(scene.t_view, scene.o_view);
    std::vector<LeafContact> candidates;
    // A motion longer than a call's passes cover is advanced partly: calls go on from
    // where the last one stopped until a pair blocks or the motion ends.
    double done = 0.0;
    for (int call = 0; call < 8 && done < 1.0; ++call) {
      TwistMotion rest = m;
      rest.start = m.at(done);
      rest.dc = (1.0 - done) * m.dc;
      rest.dtheta = (1.0 - done) * m.dtheta;
      const double s = advance(query, rest, skin, {}, candidates, margin);
      ASSERT_GE(s, 0.0);
      ASSERT_LE(s, 1.0);
      for (const LeafContact& c : candidates) ASSERT_LE(c.gap, skin + kMaxReachMargins * margin);
      if (s <= 0.0) break;
      done = s >= 1.0 ? 1.0 : done + s * (1.0 - done);
    }
    EXPECT_GE(closestAlong(probe, m, done, 64), 0.5 * skin * (1.0 - 1e-9)) << "done " << done;
    if (done < 1.0) {  // stopped by a pair, not by how far the candidates reached
      LeafContact c;
      ASSERT_TRUE(probe.distance(m.at(done), kInfinity, c));
      EXPECT_LE(c.gap, skin) << "done " << done;
    }
  }
}

TEST_F(ConservativeAdvancement, ALongMotionMeetingNothingCompletesInOneCall) {
  const double tolerance = scene.tolerance, skin = scene.skin, margin = scene.margin;
  GroupPairQuery& probe = scene.probe;
  test::Rng rng(0xc0de);
  const Vec3 d = test::randomDirection(rng);
  TwistMotion m;
  m.start = scene.nearPose(d, Mat3::Identity(), 2.0 * tolerance);
  m.center = scene.centre;
  m.dc = 3.0 * scene.size * d;  // straight away while turning: nothing in the way
  m.dtheta = 0.3 * test::randomDirection(rng);
  ASSERT_GE(closestAlong(probe, m, 1.0, 64), skin);
  GroupPairQuery query;
  query.bind(scene.t_view, scene.o_view);
  std::vector<LeafContact> candidates;
  EXPECT_EQ(advance(query, m, skin, {}, candidates, margin), 1.0);
}

}  // namespace
}  // namespace sc::detail
