// SPDX-License-Identifier: MIT
// A tracked convex pair in Input or None mode updates straight on its two pieces
// (trackConvexPair): along random paths (apart, touching, deep, across the medial
// axis and out again; boxes with coplanar faces sliding on each other) every update
// equals the general path's (ProxyTracker on the pair's query) update by update.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "penetration/convex_resolution.h"
#include "penetration/proxy_tracker.h"
#include "penetration/result_invariants.h"
#include "smartcollision/collision.h"
#include "support/placements.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::test {
namespace {

/// One direction's tracking state: the general path (every update through the
/// query and the proxy) or the convex one (trackConvexPair, the general path only
/// where it declines).
struct Direction {
  detail::GroupPairQuery query;
  detail::ProxyTracker tracker;
  detail::ConvexPairCache cache;
  int direct = 0;  ///< updates the convex path took

  detail::ProxyOutcome update(const GroupView& target, const GroupView& opponent,
                              const PairSettings& settings, bool convex) {
    query.bind(target, opponent);
    const Rigid goal =
        opponent.placement.worldFromLocal().inverse() * target.placement.worldFromLocal();
    const Vec3& center = target.placement.local_center;
    detail::ProxyOutcome out;
    if (convex && detail::trackConvexPair(query, target, opponent, goal, center, settings, cache,
                                          tracker, out)) {
      ++direct;
      return out;
    }
    tracker.update(query, goal, center, settings, out);
    return out;
  }
};

constexpr int kMaxIterations = PairSettings().max_iterations;

struct Tally {
  int updates = 0, penetrating = 0, touching = 0, differ = 0, spun = 0;
  double worst = 0.0;  ///< largest difference, in tolerances
};

/// The two outcomes agree: same code and state, the same depth, contact pose,
/// normal and points to `tol`; `scale` bounds the coordinates. Returns the largest
/// difference. Where faces may lie
/// flat on each other (`flat`), the closest points are any of a region: only their
/// offsets along the normal are compared.
double compare(const detail::ProxyOutcome& g, const detail::ProxyOutcome& c, double tol,
               double scale, bool flat) {
  EXPECT_EQ(g.code, c.code);
  if (g.code != ErrorCode::Ok || c.code != ErrorCode::Ok) return 0.0;
  // A goal that exactly touches is penetrating by rounding or not at all (then its
  // closest points are unset): rounding of the closest points (~1e-15 of the
  // coordinates' size L) over a gap of a skin tilts the normal, which moves the
  // depth by that times L.
  const double rounding = 1e-14 * scale * scale / (0.25 * tol);
  if (std::abs(g.distance) <= rounding && std::abs(c.distance) <= rounding) return 0.0;
  EXPECT_EQ(g.penetrating, c.penetrating) << g.distance << " " << c.distance;
  // Deep, the general path can spin on rounding to its last iteration and call the
  // proxy lagging (convex_resolution.cpp, slide): only a settled one is compared.
  if (!g.lagging || g.iterations < kMaxIterations) {
    EXPECT_EQ(g.lagging, c.lagging) << g.iterations << " " << c.iterations;
  }
  const Vec3& n = g.contact.normal;
  const Vec3 dt = g.contact.point_t - c.contact.point_t,
             d_o = g.contact.point_o - c.contact.point_o;
  const double diff = std::max(
      {std::abs(g.distance - c.distance), (g.tpdv - c.tpdv).norm(), (g.rpdv - c.rpdv).norm(),
       (g.contact_pose.translation - c.contact_pose.translation).norm(),
       flat ? std::abs(n.dot(dt)) : dt.norm(), flat ? std::abs(n.dot(d_o)) : d_o.norm()});
  EXPECT_LE(diff, tol);
  // The normal of a contact deeper or farther than the tolerance is the exit's (or
  // the closest points') direction: equal up to rounding amplified by 1/gap.
  EXPECT_LE((g.contact.normal - c.contact.normal).norm(), 1e-6) << g.distance;
  return diff;
}

/// Both paths along the same goals; `a` is the target.
void runPath(const ModelPtr& a, const ModelPtr& b, const std::vector<Placement>& path,
             const Placement& pb, const PairSettings& settings, bool flat, Tally& tally) {
  const Part part_a{a.get(), Rigid(), 1}, part_b{b.get(), Rigid(), 2};
  const GroupView gb{&part_b, 1, pb};
  Direction general, convex;
  PairTracker api;  // takes the convex path: the same outcome to the bit
  DirectedResult out[2];
  for (const Placement& pa : path) {
    const GroupView ga{&part_a, 1, pa};
    const double scale = pa.world_center.norm() + pb.world_center.norm() + settings.tolerance * 1e3;
    const detail::ProxyOutcome g = general.update(ga, gb, settings, false);
    const detail::ProxyOutcome c = convex.update(ga, gb, settings, true);
    const double diff = compare(g, c, settings.tolerance, scale, flat);
    tally.worst = std::max(tally.worst, diff / settings.tolerance);
    tally.differ += diff > 1e-9 * settings.tolerance;
    ++tally.updates;
    tally.spun += g.iterations >= kMaxIterations && c.iterations < kMaxIterations;
    tally.penetrating += c.penetrating;
    tally.touching += c.code == ErrorCode::Ok && !c.penetrating && c.distance <= settings.tolerance;
    api.update(ga, gb, {true, false}, settings, out);
    ASSERT_EQ(out[0].code, c.code);
    if (c.code != ErrorCode::Ok) continue;
    EXPECT_EQ(out[0].distance, c.distance);
    EXPECT_EQ(out[0].hasDepth(), c.penetrating);
    const Status s = detail::checkResult(out[0], pa, pb);
    EXPECT_TRUE(s.ok()) << s.message();
  }
  // The convex path took every update but None mode's first contacts.
  EXPECT_GE(convex.direct, static_cast<int>(path.size()) - 3);
}

/// Goals from `from` through `via` to `to` (centres, steps of about `step`), the
/// orientation turning about `axis` by `turn` per step.
std::vector<Placement> pathThrough(const Vec3& from, const Vec3& via, const Vec3& to,
                                   const Mat3& r0, const Vec3& axis, double turn, double step) {
  std::vector<Placement> path;
  const Vec3 legs[3] = {from, via, to};
  double angle = 0.0;
  for (int leg = 0; leg < 2; ++leg) {
    const Vec3 d = legs[leg + 1] - legs[leg];
    const int n = std::max(1, static_cast<int>(std::ceil(d.norm() / step)));
    for (int i = 0; i < n; ++i, angle += turn) {
      const Mat3 r = Eigen::AngleAxisd(angle, axis).toRotationMatrix() * r0;
      path.push_back(placementOf(r, legs[leg] + (static_cast<double>(i) / n) * d));
    }
  }
  path.push_back(placementOf(r0, to));
  return path;
}

void report(const char* what, const Tally& t) {
  std::printf(
      "%s: %d updates (%d penetrating, %d touching), %d differ by more than 1e-9 "
      "tolerances, worst %.3g tolerances; the general path ran out of iterations where the "
      "convex one settled in %d\n",
      what, t.updates, t.penetrating, t.touching, t.differ, t.worst, t.spun);
}

TEST(ConvexFrames, RandomPathsEqualTheGeneralPath) {
  Rng rng(26112026);
  Tally tally;
  const int paths = SC_TEST_SANITIZED ? 12 : 120;
  for (int i = 0; i < paths; ++i) {
    const double size = logUniform(rng, 1e-2, 1e2);
    const ConvexShape sa = randomConvexShape(rng, size);
    const ConvexShape sb = randomConvexShape(rng, size * uniform(rng, 0.5, 2.0));
    const ModelPtr a = convexModel(sa.poly), b = convexModel(sb.poly);
    ASSERT_TRUE(a && b);
    const Vec3 shift = i % 5 == 0 ? Vec3(size * 1e2 * randomDirection(rng)) : Vec3::Zero();
    const Placement pb = placementOf(randomRotation(rng).toRotationMatrix(), shift);
    // From well apart, through the opponent near its centre (deep, across the medial
    // axis), out on the other side.
    const Vec3 d = randomDirection(rng);
    const Vec3 from = shift + 3.0 * size * d;
    const Vec3 via = shift + size * uniform(rng, 0.0, 0.3) * randomDirection(rng);
    const Vec3 to = shift - 3.0 * size * d + size * randomDirection(rng);
    PairSettings settings;
    settings.tolerance = 1e-3 * size;
    settings.rotation_mode = i % 3 == 0 ? RotationMode::None : RotationMode::Input;
    const double step = size * uniform(rng, 0.005, 0.05);
    const double turn = i % 2 == 0 ? 0.0 : uniform(rng, -0.01, 0.01);
    runPath(a, b,
            pathThrough(from, via, to, randomRotation(rng).toRotationMatrix(), randomDirection(rng),
                        turn, step),
            pb, settings, false, tally);
  }
  report("convex frames, random paths", tally);
  EXPECT_GT(tally.penetrating, tally.updates / 4);
}

TEST(ConvexFrames, BoxesSlidingOnCoplanarFacesEqualTheGeneralPath) {
  // A box brought down on another's top face (exactly touching, half a tolerance, a
  // tolerance and 0.3 deep) and slid across it and over its far edge (coplanar faces,
  // ties between normals), or brought in from the side below the top (the proxy
  // stays on the side face: past the medial axis, 5 deep at the end), in Input and
  // None.
  const ModelPtr a = boxModel(Vec3(0.5, 0.5, 0.5)), b = boxModel(Vec3(2, 1, 1.5));
  ASSERT_TRUE(a && b);
  const Placement pb = placementOf(Mat3::Identity(), Vec3::Zero());
  Tally tally;
  for (const RotationMode mode : {RotationMode::Input, RotationMode::None}) {
    PairSettings settings;
    settings.rotation_mode = mode;
    const double tol = settings.tolerance;
    for (const double depth : {0.0, 0.5 * tol, tol, 0.3}) {
      const double y = 1.5 - depth;
      const Vec3 land = depth == 0.0 ? Vec3(-1.5, y, 0.2) : Vec3(-1.5 - 1.0 / 3.0, y, 0.2);
      runPath(a, b,
              pathThrough(Vec3(-1.5, 3, 0.2), land, Vec3(3, y, 0.2), Mat3::Identity(),
                          Vec3::UnitY(), 0.0, 0.01),
              pb, settings, true, tally);
      if (depth > 0.0)
        runPath(a, b,
                pathThrough(Vec3(-3, 3, 0.2), Vec3(-2.6, y, 0.2), Vec3(3, y, 0.2), Mat3::Identity(),
                            Vec3::UnitY(), 0.0, 0.01),
                pb, settings, true, tally);
    }
  }
  report("convex frames, boxes", tally);
  EXPECT_GT(tally.touching, 0);
  EXPECT_GT(tally.penetrating, tally.updates / 2);
}

}  // namespace
}  // namespace sc::test
