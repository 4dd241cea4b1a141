// SPDX-License-Identifier: MIT
// Linearised non-penetration constraints of the proxy: one row per contact within
// the tolerance, with an exact separating plane (support mappings of convex leaves).
#pragma once

#include <vector>

#include "query/group_pair_query.h"

namespace sc::detail {

struct ContactRow {
  Vec3 normal = Vec3::UnitZ();  ///< unit, opponent towards target (opponent frame)
  Vec3 lever = Vec3::Zero();    ///< contact point on the target minus the target's centre
  double gap = 0.0;             ///< separation along `normal` at the pose, at `lever`
  int contact = -1;             ///< index into the contact list
};

/// Exit direction of a leaf pair that intersects at the proxy only because the
/// proxy was re-oriented (or the opponent changed): its separating direction at the
/// previous, free proxy; else the direction between the leaves' centres.
Vec3 exitNormal(GroupPairQuery& query, const LeafContact& c, const Rigid& previous_proxy);

/// Rows for `contacts` at `pose`; `center_at_pose` is the target's centre (opponent
/// frame). For a twist (dc, dtheta) about that centre the gap changes by about
/// normal . dc + (lever x normal) . dtheta. Each contact gives one row per vertex of
/// the target leaf within `near` of its supporting plane (its lowest along the
/// normal), so a face or edge contact constrains rotation about every corner.
void buildContactRows(GroupPairQuery& query, const Rigid& pose, const Vec3& center_at_pose,
                      const std::vector<LeafContact>& contacts, const Rigid& previous_proxy,
                      std::vector<ContactRow>& rows, double near);

}  // namespace sc::detail
