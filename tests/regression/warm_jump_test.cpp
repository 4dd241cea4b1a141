// SPDX-License-Identifier: MIT
// A carried PairTracker after a jump sideways along a non-convex opponent: the
// jump's sweep is pruned by the hulls' separating planes (a motion along the
// contact neither closes nor opens them much), and where the sweep meets nothing
// the carried tracker answers what a fresh one answers at that pose, exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "smartcollision/collision.h"
#include "support/meshes.h"
#include "support/test_support.h"

namespace sc::test {
namespace {

struct Elephants {
  ModelPtr model;
  Part a, b;
  SceneSettings settings;

  DirectedResult update(PairTracker& tracker, const Rigid& pose) const {
    GroupView target{&a, 1, Placement()};
    target.placement.setMatrix(pose.rotation, pose.translation);
    const GroupView opponent{&b, 1, Placement()};
    DirectedResult out[2];
    tracker.update(target, opponent, Directions{true, false}, settings, out);
    return out[0];
  }
  double fresh(const Rigid& pose) const {
    PairTracker tracker;
    const DirectedResult r = update(tracker, pose);
    return r.code == ErrorCode::Ok ? r.distance : -1.0;
  }
  double size() const { return (model->bounds().max - model->bounds().min).norm(); }
  /// Offset along u where the target is about `gap` away (the distance is
  /// 1-Lipschitz in the offset: a step of d - gap never reaches contact).
  double offsetAtGap(const Mat3& q, const Vec3& u, double gap) const {
    double s = 2.0 * (model->bounds().max - model->bounds().min).norm();
    for (int k = 0; k < 80; ++k) {
      const double d = fresh({q, s * u});
      if (d < 0.0 || std::abs(d - gap) < 0.1 * gap) break;
      s -= d - gap;
    }
    return s;
  }
};

/// Two parts of one elephant model (CGAL's elephant), both at the origin; call as
/// ASSERT_NO_FATAL_FAILURE(twoElephants(e)).
void twoElephants(Elephants& e) {
  MeshData mesh;
  ASSERT_NO_FATAL_FAILURE(mesh = loadTestMesh("elephant"));
  e.model = std::make_shared<const Model>(
      ModelKind::ClosedPolyhedron,
      std::vector<PiecePtr>{buildPiece(ModelKind::ClosedPolyhedron, mesh).value()});
  e.a = {e.model.get(), Rigid(), 0};
  e.b = {e.model.get(), Rigid(), 1};
}

/// A path around the opponent: the target's offset direction turns about an axis
/// orthogonal to where it starts, its body about `spin`.
struct Orbit {
  Vec3 u0, axis, spin;
  explicit Orbit(Rng& rng)
      : u0(randomDirection(rng)), axis(u0.unitOrthogonal()), spin(randomDirection(rng)) {}
  Vec3 direction(double angle) const { return Eigen::AngleAxisd(angle, axis) * u0; }
  Mat3 turn(double angle) const { return Eigen::AngleAxisd(angle, spin).toRotationMatrix(); }
};

TEST(WarmJump, CarriedTrackerEqualsAFreshOneAfterSidewaysJumps) {
  Elephants e;
  ASSERT_NO_FATAL_FAILURE(twoElephants(e));
  const double size = e.size();
  Rng rng(19);
  int compared = 0;
  for (int path = 0; path < 4; ++path) {
    const Mat3 q = randomRotation(rng).toRotationMatrix();
    const Vec3 u0 = randomDirection(rng);
    const Vec3 axis = u0.unitOrthogonal();
    PairTracker warm;
    double angle = 0.0;
    for (int jump = 0; jump < 6; ++jump, angle += 0.05) {
      // Each jump moves the target some 5 % of the size along the opponent.
      const Vec3 u = Eigen::AngleAxisd(angle, axis) * u0;
      const Rigid pose{q, e.offsetAtGap(q, u, 0.01 * size) * u};
      const double expected = e.fresh(pose);
      if (expected <= 0.0) continue;
      const DirectedResult r = e.update(warm, pose);
      ASSERT_EQ(r.code, ErrorCode::Ok);
      // A sweep that met the opponent on the way stops the proxy short: then the
      // pair reports a depth (the path semantics), which a fresh tracker cannot.
      if (r.distance <= 0.0) {
        warm.reset();
        continue;
      }
      EXPECT_NEAR(r.distance, expected, 1e-12 * size) << "path " << path << " jump " << jump;
      ++compared;
    }
  }
  EXPECT_GE(compared, 12);
}

/// Motions whose distances at both ends exceed half their length (plus the skin)
/// cannot meet the opponent anywhere on the way: the carried tracker answers from the
/// goal's distance without a sweep, and that answer is a fresh tracker's. The turn
/// with each motion (INPUT and NONE modes) is covered by the start's bound.
TEST(WarmJump, AMotionItsEndsCertifyFreeEqualsAFreshTracker) {
  Elephants e;
  ASSERT_NO_FATAL_FAILURE(twoElephants(e));
  const double size = e.size();
  Rng rng(7);
  int compared = 0;
  for (const RotationMode mode : {RotationMode::Input, RotationMode::None}) {
    Elephants carried = e;
    carried.settings.rotation_mode = mode;
    for (int path = 0; path < 3; ++path) {
      const Orbit orbit(rng);
      PairTracker warm;
      for (int step = 0; step < 8; ++step) {
        // 5 % of the size away, each step 3 % of it along the opponent and a turn.
        const Vec3 u = orbit.direction(0.03 * step);
        const Mat3 q = orbit.turn(0.02 * step);
        const Rigid pose{q, e.offsetAtGap(q, u, 0.05 * size) * u};
        PairTracker cold;
        const DirectedResult expected = carried.update(cold, pose);
        const DirectedResult r = carried.update(warm, pose);
        ASSERT_EQ(r.code, ErrorCode::Ok);
        ASSERT_EQ(expected.code, ErrorCode::Ok);
        EXPECT_NEAR(r.distance, expected.distance, 1e-12 * size) << "path " << path;
        EXPECT_LE((r.point_on_target - expected.point_on_target).norm(), 1e-9 * size);
        EXPECT_EQ(r.status, DirectionStatus::Separated);
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 48);
}

/// After a jump the carried tracker's contacts lie where it was: at the next small
/// steps, within the tolerance of the opponent, it measures the goal as a fresh
/// tracker does and sweeps to it rather than gathering contacts anew around the proxy
/// (proxy_tracker.h, sweptFree). Where that goal is free the answer is a fresh one's.
TEST(WarmJump, SmallStepsWithinTheToleranceAfterAJumpEqualAFreshTracker) {
  Elephants e;
  ASSERT_NO_FATAL_FAILURE(twoElephants(e));
  const double size = e.size();
  e.settings.tolerance = 1e-3 * size;
  Rng rng(31);
  int compared = 0;
  // 0.6 tolerances, and 0.19: within the skin (TOLERANCE/4), where the slide gathers
  // the contacts, but beyond half of it, where the sweep stops.
  for (const double gap : {0.6, 0.19})
    for (const RotationMode mode : {RotationMode::Input, RotationMode::None}) {
      e.settings.rotation_mode = mode;
      for (int path = 0; path < 2; ++path) {
        const Orbit orbit(rng);
        PairTracker warm;
        for (int step = 0; step < 12; ++step) {
          // A 5 % jump every fourth step, else 0.05 % of the size and a small turn; the
          // target `gap` tolerances from the opponent.
          const double angle = 0.05 * (step / 4) + 5e-4 * step;
          const Vec3 u = orbit.direction(angle);
          const Mat3 q = orbit.turn(5e-4 * step);
          const Rigid pose{q, e.offsetAtGap(q, u, gap * e.settings.tolerance) * u};
          PairTracker cold;
          const DirectedResult expected = e.update(cold, pose);
          const DirectedResult r = e.update(warm, pose);
          ASSERT_EQ(r.code, ErrorCode::Ok);
          if (expected.code != ErrorCode::Ok || r.distance <= 0.0) continue;
          EXPECT_NEAR(r.distance, expected.distance, 1e-12 * size)
              << "gap " << gap << " mode " << static_cast<int>(mode) << " path " << path << " step "
              << step;
          ++compared;
        }
      }
    }
  EXPECT_GE(compared, 72);
}

/// A carried tracker whose jumps exceed PairSettings::teleport_distance answers what a
/// fresh one answers at every jump: the distance, and inside the opponent the depth
/// a fresh tracker resolves (resolve_initial_intersection), not the path's.
TEST(WarmJump, BeyondTheTeleportDistanceEveryJumpEqualsAFreshTracker) {
  Elephants e;
  ASSERT_NO_FATAL_FAILURE(twoElephants(e));
  const double size = e.size();
  Elephants carried = e;
  carried.settings.teleport_distance = 0.02 * size;
  carried.settings.resolve_initial_intersection = true;
  Elephants fresh = carried;
  fresh.settings.teleport_distance = kInfinity;
  Rng rng(23);
  int apart = 0, deep = 0;
  for (int path = 0; path < 3; ++path) {
    const Mat3 q = randomRotation(rng).toRotationMatrix();
    const Vec3 u0 = randomDirection(rng);
    const Vec3 axis = u0.unitOrthogonal();
    PairTracker warm;
    for (int jump = 0; jump < 6; ++jump) {
      // 5 % of the size along the opponent, apart and then 2 % of it deeper than touching.
      const Vec3 u = Eigen::AngleAxisd(0.05 * jump, axis) * u0;
      const double s = e.offsetAtGap(q, u, 0.01 * size);
      for (const double offset : {s, s - 0.03 * size}) {
        const Rigid pose{q, offset * u};
        PairTracker cold;
        const DirectedResult expected = fresh.update(cold, pose);
        const DirectedResult r = carried.update(warm, pose);
        ASSERT_EQ(r.code, expected.code) << "path " << path << " jump " << jump;
        if (r.code != ErrorCode::Ok) continue;
        EXPECT_NEAR(r.distance, expected.distance, 1e-12 * size);
        EXPECT_LE((r.tpdv - expected.tpdv).norm(), 1e-12 * size);
        ++(expected.distance > 0.0 ? apart : deep);
      }
    }
  }
  EXPECT_GE(apart, 12);
  EXPECT_GE(deep, 12);
}

}  // namespace
}  // namespace sc::test
