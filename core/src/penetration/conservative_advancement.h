// SPDX-License-Identifier: MIT
// Conservative advancement of a target group along a screw-free rigid motion:
// translation of its centre by s * dc and rotation by s * dtheta about that
// centre, s in [0, 1] (Mirtich 1996; Zhang et al., "Continuous collision
// detection for articulated models using Taylor models and temporal culling",
// SIGGRAPH 2007, for the motion bound).
#pragma once

#include <vector>

#include "query/group_pair_query.h"

namespace sc::detail {

/// A rigid motion of the target group, in the opponent group's frame.
struct TwistMotion {
  Rigid start;                 ///< o_from_t at s = 0
  Vec3 center = Vec3::Zero();  ///< target's centre of rotation, target group frame
  Vec3 dc = Vec3::Zero();      ///< translation of the centre over the motion
  Vec3 dtheta = Vec3::Zero();  ///< rotation vector (opponent frame) over the motion

  /// o_from_t at fraction s.
  Rigid at(double s) const;
};

/// Largest s in [0, 1] such that along the motion every leaf pair not in `skip`
/// (sorted) keeps a gap >= skin / 2; when a pair blocks, it ends at a gap <=
/// skin. Pairs intersecting at s = 0 are ignored (nothing to advance from); a
/// pair within skin at s = 0 blocks at once unless the motion opens it.
/// Per pair: the gap along the last separating normal n shrinks at most at rate
/// max(0, -n . dc) + |dtheta| rho, rho bounding the leaf's distance to the centre.
/// `scratch` is reused between calls. The candidates come from the query's near
/// pairs (contactsNear with `near_margin`), gathered in passes along the motion, each
/// up to a few near margins from where it starts; a motion longer than the passes of
/// one call cover (32) is advanced partly, to a pose where no pair is within the skin.
double advance(GroupPairQuery& query, const TwistMotion& motion, double skin,
               const std::vector<LeafPair>& skip, std::vector<LeafContact>& scratch,
               double near_margin);

}  // namespace sc::detail
