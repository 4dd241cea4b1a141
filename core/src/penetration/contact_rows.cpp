// SPDX-License-Identifier: MIT
#include "penetration/contact_rows.h"

#include <algorithm>

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
                      std::vector<ContactRow>& rows, double near) {
  rows.clear();
  for (int i = 0; i < static_cast<int>(contacts.size()); ++i) {
    const LeafContact& c = contacts[i];
    ContactRow row;
    row.normal = c.intersecting ? exitNormal(query, c, previous_proxy) : c.normal;
    row.gap = query.separationAlong(c.t_leaf, c.o_leaf, pose, row.normal);
    row.contact = i;
    // One row per target vertex near the separating plane: a face or edge in contact
    // must not turn into the opponent about any of its corners, which a single
    // witness point would allow.
    const Leaf& leaf = query.targetLeaves()[c.t_leaf];
    const Rigid o_from_leaf = pose * leaf.group_from_leaf;
    double lowest = kInfinity;
    for (const Vec3& v : leaf.poly->vertices)
      lowest = std::min(lowest, row.normal.dot(o_from_leaf * v));
    for (const Vec3& v : leaf.poly->vertices) {
      const Vec3 p = o_from_leaf * v;
      const double above = row.normal.dot(p) - lowest;
      if (above > near) continue;
      ContactRow corner = row;
      corner.gap = row.gap + above;
      corner.lever = p - center_at_pose;
      rows.push_back(corner);
    }
  }
}

}  // namespace sc::detail
