// SPDX-License-Identifier: MIT
// Queries between two groups of convex leaves (convex pieces, patch hulls, soup
// triangles): minimum distance, contacts within a gap, intersection, and time of
// impact along a translation. Runs in the opponent group's frame with the target
// placed by `o_from_t`. Candidate leaf pairs are culled by bounding spheres and
// visited nearest first; per-pair GJK warm starts persist across calls.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "query/gjk.h"
#include "smartcollision/collision.h"

namespace sc::detail {

/// A convex leaf of a group, placed in the group's frame.
struct Leaf {
  const ConvexPolytope* poly = nullptr;
  Rigid group_from_leaf;
  int part = -1;   ///< index into GroupView::parts
  int piece = -1;  ///< piece index within the part's model
  Vec3 center = Vec3::Zero();  ///< bounding sphere in the group frame
  double radius = 0.0;
};

/// Collects the leaves of a group into `out` (cleared first, capacity kept).
void collectLeaves(const GroupView& group, std::vector<Leaf>& out);

/// One leaf pair's closest points or contact, in the opponent group's frame.
struct LeafContact {
  int t_leaf = -1;
  int o_leaf = -1;
  bool intersecting = false;
  double gap = 0.0;                 ///< GJK distance; 0 when intersecting
  Vec3 normal = Vec3::UnitX();      ///< unit, from the opponent leaf towards the target leaf
  Vec3 point_t = Vec3::Zero();
  Vec3 point_o = Vec3::Zero();
  int simplex_count = 0;
  int simplex_t[4] = {-1, -1, -1, -1};
  int simplex_o[4] = {-1, -1, -1, -1};
};

class GroupPairQuery {
 public:
  /// Binds the two groups (target, opponent); resets caches if the leaf sets change.
  void bind(const GroupView& target, const GroupView& opponent);

  const std::vector<Leaf>& targetLeaves() const { return t_leaves_; }
  const std::vector<Leaf>& opponentLeaves() const { return o_leaves_; }

  /// Minimum distance over all leaf pairs. False when every pair is farther than
  /// `max_distance` (then `best` is unset). An intersecting pair gives gap 0.
  bool distance(const Rigid& o_from_t, double max_distance, LeafContact& best);

  /// Every leaf pair with gap <= `threshold` (intersecting ones included), appended
  /// to `out` after clearing it.
  void contacts(const Rigid& o_from_t, double threshold, std::vector<LeafContact>& out);

  /// Closest points of one leaf pair (GJK with its warm start).
  LeafContact pairAt(int t_leaf, int o_leaf, const Rigid& o_from_t);

  /// True when some leaf pair intersects.
  bool intersects(const Rigid& o_from_t);

  /// Separation of one leaf pair along the unit direction n (opponent towards target):
  /// min over the target leaf of n.x minus max over the opponent leaf of n.x. Exact for
  /// convex leaves; positive means the plane orthogonal to n separates them.
  double separationAlong(int t_leaf, int o_leaf, const Rigid& o_from_t, const Vec3& n);

  /// Largest s in [0, 1] such that translating the target by s * delta (opponent frame)
  /// from `o_from_t` keeps every leaf pair not flagged in `skip` at gap >= stop_gap/2,
  /// ending at gap <= stop_gap when a pair blocks. Conservative advancement per pair.
  /// `skip` is indexed t_leaf * opponentLeaves().size() + o_leaf; empty = skip none.
  double translationToi(const Rigid& o_from_t, const Vec3& delta, double stop_gap,
                        const std::vector<std::uint8_t>& skip);

 private:
  struct Candidate {
    double lower_bound;
    int t_leaf;
    int o_leaf;
  };
  LeafContact evaluate(int t_leaf, int o_leaf, const Rigid& o_from_t, double max_distance,
                       bool& beyond);
  void gatherCandidates(const Rigid& o_from_t, double max_gap);
  SimplexCache& cacheFor(int t_leaf, int o_leaf);

  std::vector<Leaf> t_leaves_;
  std::vector<Leaf> o_leaves_;
  std::vector<Candidate> candidates_;
  std::unordered_map<std::uint64_t, SimplexCache> caches_;
};

}  // namespace sc::detail
