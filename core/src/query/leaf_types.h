// SPDX-License-Identifier: MIT
// Leaves, leaf pairs and their contacts as the group pair queries name them, and the
// node pairs their traversals queue.
#pragma once

#include "geometry/convex_polytope.h"
#include "geometry/math_util.h"
#include "query/gjk.h"

namespace sc::detail {

/// A convex leaf of a group, placed in the group's frame.
struct Leaf {
  const ConvexPolytope* poly = nullptr;
  Rigid group_from_leaf;
  int part = -1;               ///< index into GroupView::parts
  int piece = -1;              ///< piece index within the part's model
  Vec3 center = Vec3::Zero();  ///< bounding sphere in the group frame
  double radius = 0.0;
};

/// A target leaf and an opponent leaf, by their indices in the query's leaf lists.
struct LeafPair {
  int t_leaf = -1;
  int o_leaf = -1;

  bool operator<(const LeafPair& o) const {
    return t_leaf != o.t_leaf ? t_leaf < o.t_leaf : o_leaf < o.o_leaf;
  }
  bool operator==(const LeafPair& o) const { return t_leaf == o.t_leaf && o_leaf == o.o_leaf; }
};

/// One leaf pair's closest points or contact, in the opponent group's frame.
struct LeafContact {
  int t_leaf = -1;
  int o_leaf = -1;
  bool intersecting = false;
  double gap = 0.0;  ///< GJK distance; 0 when intersecting
  /// False for a pair a near-pair rebuild kept unmeasured: then gap is only a lower
  /// bound and the other fields are stale.
  bool measured = true;
  Vec3 normal = Vec3::UnitX();  ///< unit, from the opponent leaf towards the target leaf
  Vec3 point_t = Vec3::Zero();
  Vec3 point_o = Vec3::Zero();
  int simplex_count = 0;
  int simplex_t[4] = {-1, -1, -1, -1};
  int simplex_o[4] = {-1, -1, -1, -1};
};

/// A leaf pair's GJK result as a contact: its closest points, normal and simplex;
/// the gap is GJK's lower bound when the pair lies beyond the query's max distance.
inline LeafContact leafContactOf(const GjkResult& r, int t_leaf, int o_leaf) {
  LeafContact c;
  c.t_leaf = t_leaf;
  c.o_leaf = o_leaf;
  c.intersecting = r.status == GjkStatus::Intersecting;
  const bool beyond = r.status == GjkStatus::BeyondMaxDistance;
  c.gap = c.intersecting ? 0.0 : (beyond ? r.lower_bound : r.distance);
  c.normal = r.normal;
  c.point_t = r.point_a;
  c.point_o = r.point_b;
  c.simplex_count = r.count;
  for (int i = 0; i < 4; ++i) {
    c.simplex_t[i] = r.a[i];
    c.simplex_o[i] = r.b[i];
  }
  return c;
}

/// Work done by the last traversal (for tests and benchmarks).
struct TraversalCounters {
  int node_pairs = 0;     ///< node pairs taken from the queue
  int node_gjk = 0;       ///< GJK runs on inner node pairs (lower bounds)
  int leaf_gjk = 0;       ///< GJK runs on leaf pairs
  int refined = 0;        ///< leaf pairs measured on their real triangles
  bool shortcut = false;  ///< answered from the last distance without traversal
  /// contactsNear(): node pairs and GJK runs of the rebuild run ahead of need.
  int ahead_node_pairs = 0;
  int ahead_gjk = 0;
  bool ahead_installed = false;  ///< that rebuild replaced the pairs (done, or as far as due)
};

/// A node of each side's hull hierarchy (by slot: a piece of a part) and a lower
/// bound of their distance.
struct NodePair {
  double bound = 0.0;
  int t_slot = 0;
  int t_node = 0;
  int o_slot = 0;
  int o_node = 0;
  bool refined = false;  ///< bound from GJK on the pair's own polytopes
};

}  // namespace sc::detail
