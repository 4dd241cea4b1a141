// SPDX-License-Identifier: MIT
#include "penetration/conservative_advancement.h"

#include <algorithm>
#include <cmath>

#include "geometry/math_util.h"

namespace sc::detail {

namespace {
constexpr int kMaxSteps = 64;
}

Rigid TwistMotion::at(double s) const {
  const Mat3 r = rotationFromVector(s * dtheta) * start.rotation;
  const Vec3 y = start * center + s * dc;
  return {r, y - r * center};
}

double advance(GroupPairQuery& query, const TwistMotion& motion, double skin,
               const std::vector<LeafPair>& skip, std::vector<LeafContact>& scratch,
               double near_margin) {
  const double angle = motion.dtheta.norm();
  const Vec3 y0_local = motion.center;
  // Candidates: every pair within reach of the motion at its start.
  double reach_rho = 0.0;
  for (const Leaf& leaf : query.targetLeaves())
    reach_rho = std::max(reach_rho, (leaf.center - y0_local).norm() + leaf.radius);
  const double reach = motion.dc.norm() + angle * reach_rho + skin;
  query.contactsNear(motion.start, reach, near_margin, scratch);
  // No point moves farther than `sweep` per unit of s: a pair whose gap exceeds
  // skin + limit * sweep cannot block before `limit`. The candidates come nearest
  // first, so the first such pair ends the search (a long motion may gather
  // thousands of candidates, of which the nearest few decide).
  const double sweep = motion.dc.norm() + angle * reach_rho;
  double limit = 1.0;
  // Candidates cut short at GroupPairQuery::kMaxContacts are complete only up to a
  // smaller reach: the motion is advanced only as far as that covers.
  const double covered = query.nearCoveredReach(motion.start);
  if (covered < reach && sweep > 0.0) limit = std::clamp((covered - skin) / sweep, 0.0, 1.0);
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
  return limit;
}

}  // namespace sc::detail
