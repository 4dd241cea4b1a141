// SPDX-License-Identifier: MIT
#include "penetration/conservative_advancement.h"

#include <algorithm>
#include <cmath>

#include "geometry/math_util.h"

namespace sc::detail {

namespace {
constexpr int kMaxSteps = 64;
/// Each pass gathers its candidates up to this many near margins: a long motion (a
/// lagging proxy's turn back, a point at a body's radius) would gather thousands of
/// pairs at once, each query keeping them, for the few that decide. A pass advances as
/// far as the pairs it gathered cover; the next one starts there.
constexpr double kMaxReachMargins = 4.0;
/// Passes per call: a motion longer than this many reaches is advanced partly (the
/// caller's next iteration goes on).
constexpr int kMaxPasses = 32;

/// The part of `motion` after fraction s (the same screw-free motion).
TwistMotion restOf(const TwistMotion& motion, double s) {
  TwistMotion rest = motion;
  rest.start = motion.at(s);
  rest.dc = (1.0 - s) * motion.dc;
  rest.dtheta = (1.0 - s) * motion.dtheta;
  return rest;
}

/// One pass of advance() (its contract), from candidates gathered up to a capped
/// reach; `cut` when that coverage, not a pair, set the result.
double advancePass(GroupPairQuery& query, const TwistMotion& motion, double reach_rho, double skin,
                   const std::vector<LeafPair>& skip, std::vector<LeafContact>& scratch,
                   double near_margin, bool& cut) {
  const double angle = motion.dtheta.norm();
  const Vec3 y0_local = motion.center;
  const double reach = motion.dc.norm() + angle * reach_rho + skin;
  const double gathered = std::min(reach, skin + kMaxReachMargins * near_margin);
  query.contactsNear(motion.start, gathered, near_margin, scratch);
  // No point moves farther than `sweep` per unit of s: a pair whose gap exceeds
  // skin + limit * sweep cannot block before `limit`. The candidates come nearest
  // first, so the first such pair ends the search.
  const double sweep = motion.dc.norm() + angle * reach_rho;
  double limit = 1.0;
  // The candidates are complete up to the reach gathered (less where
  // GroupPairQuery::kMaxContacts cut them short; the query's kept pairs may reach
  // farther, but they are not among them), and every other pair is at least the
  // distance apart: the motion is advanced only as far as the larger covers.
  double covered = std::min(query.nearCoveredReach(motion.start), gathered);
  if (covered < reach) {
    LeafContact nearest;
    if (!query.distance(motion.start, reach, nearest))
      covered = reach;  // nothing within the motion's reach
    else if (!nearest.intersecting)
      covered = std::max(covered, nearest.gap);
  }
  if (covered < reach && sweep > 0.0) limit = std::clamp((covered - skin) / sweep, 0.0, 1.0);
  const double coverage = limit;
  for (const LeafContact& cand : scratch) {
    if (cand.gap > skin + limit * sweep) break;
    if (cand.intersecting) continue;
    if (std::binary_search(skip.begin(), skip.end(), LeafPair{cand.t_leaf, cand.o_leaf})) continue;
    const Leaf& leaf = query.targetLeaves()[cand.t_leaf];
    const double rho = (leaf.center - y0_local).norm() + leaf.radius;
    double s = 0.0;
    LeafContact c = cand;
    for (int step = 0; step < kMaxSteps && s < limit; ++step) {
      if (step > 0) c = query.pairAt(cand.t_leaf, cand.o_leaf, motion.at(s));
      // A pair already this close blocks unless the motion provably opens it: the
      // separation along its normal grows at least at n.dc - angle * rho.
      if (step == 0 && !c.intersecting && c.gap <= skin && c.normal.dot(motion.dc) > angle * rho) {
        s = limit;
        break;
      }
      if (c.intersecting || c.gap <= skin) break;
      const double rate = std::max(0.0, -c.normal.dot(motion.dc)) + angle * rho;
      if (rate <= 0.0) {
        s = limit;
        break;
      }
      s = std::min(limit, s + (c.gap - 0.5 * skin) / rate);
    }
    limit = std::min(limit, s);
  }
  cut = limit < 1.0 && limit >= coverage;
  return limit;
}

}  // namespace

Rigid TwistMotion::at(double s) const {
  const Mat3 r = rotationFromVector(s * dtheta) * start.rotation;
  const Vec3 y = start * center + s * dc;
  return {r, y - r * center};
}

double advance(GroupPairQuery& query, const TwistMotion& motion, double skin,
               const std::vector<LeafPair>& skip, std::vector<LeafContact>& scratch,
               double near_margin) {
  double reach_rho = 0.0;  // bounds every target point's distance to the centre
  for (const Leaf& leaf : query.targetLeaves())
    reach_rho = std::max(reach_rho, (leaf.center - motion.center).norm() + leaf.radius);
  double done = 0.0;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    bool cut = false;
    const TwistMotion rest = pass == 0 ? motion : restOf(motion, done);
    const double s = advancePass(query, rest, reach_rho, skin, skip, scratch, near_margin, cut);
    done += s * (1.0 - done);
    if (!cut || !(s > 0.0)) break;
  }
  return done;
}

}  // namespace sc::detail
