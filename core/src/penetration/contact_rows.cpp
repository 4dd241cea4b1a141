// SPDX-License-Identifier: MIT
#include "penetration/contact_rows.h"

#include <algorithm>

#include "geometry/math_util.h"
#include "query/epa.h"

namespace sc::detail {

Vec3 exitNormal(GroupPairQuery& query, const LeafContact& c, const Rigid& previous_proxy) {
  const LeafContact before = query.pairAt(c.t_leaf, c.o_leaf, previous_proxy);
  if (!before.intersecting) return before.normal;
  // The previous proxy intersects or touches too (a goal reached exactly touching):
  // the leaves' own exit direction, where the direction between their centres would
  // be any direction at all (a face-on-face contact offset sideways turned FREE's
  // proxy a little more at every update).
  const Leaf t = query.targetLeaf(c.t_leaf);
  const Leaf o = query.opponentLeaf(c.o_leaf);
  const EpaResult e =
      penetrationDepth(*t.poly, previous_proxy * t.group_from_leaf, *o.poly, o.group_from_leaf);
  if (e.normal.allFinite() && e.normal.norm() > 0.5) return e.normal.normalized();
  const Vec3 t_center = previous_proxy * t.center;
  return normalizedOr(t_center - o.center, Vec3::UnitZ());
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
