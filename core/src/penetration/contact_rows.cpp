// SPDX-License-Identifier: MIT
#include "penetration/contact_rows.h"

#include "geometry/math_util.h"

namespace sc::detail {

Vec3 exitNormal(GroupPairQuery& query, const LeafContact& c, const Rigid& previous_proxy) {
  const LeafContact before = query.pairAt(c.t_leaf, c.o_leaf, previous_proxy);
  if (!before.intersecting) return before.normal;
  const Vec3 t_center = previous_proxy * query.targetLeaves()[c.t_leaf].center;
  return normalizedOr(t_center - query.opponentLeaves()[c.o_leaf].center, Vec3::UnitZ());
}

void buildContactRows(GroupPairQuery& query, const Rigid& pose, const Vec3& center_at_pose,
                      const std::vector<LeafContact>& contacts, const Rigid& previous_proxy,
                      std::vector<ContactRow>& rows) {
  rows.clear();
  for (int i = 0; i < static_cast<int>(contacts.size()); ++i) {
    const LeafContact& c = contacts[i];
    ContactRow row;
    row.normal = c.intersecting ? exitNormal(query, c, previous_proxy) : c.normal;
    row.gap = query.separationAlong(c.t_leaf, c.o_leaf, pose, row.normal);
    // For an intersecting pair the GJK points are unset: lever from the leaf centre.
    const Vec3 point = c.intersecting ? Vec3(pose * query.targetLeaves()[c.t_leaf].center)
                                      : c.point_t;
    row.lever = point - center_at_pose;
    row.contact = i;
    rows.push_back(row);
  }
}

}  // namespace sc::detail
