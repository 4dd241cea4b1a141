// SPDX-License-Identifier: MIT
// Queries between two groups of convex leaves (convex pieces, patch hulls, soup
// triangles): minimum distance, contacts within a gap, intersection, and time of
// impact along a translation. Runs in the opponent group's frame with the target
// placed by `o_from_t`. Each query is a best-first traversal of the pieces' hull
// hierarchies (preprocess/hull_bvh.h) with GJK lower bounds on node pairs; warm
// starts per node pair and the last closest leaf pair persist across calls.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "preprocess/piece_data.h"
#include "query/gjk.h"
#include "query/leaf_types.h"
#include "query/near_front.h"
#include "query/near_pairs.h"
#include "query/pair_cache.h"
#include "query/plane_memo.h"
#include "smartcollision/group.h"

namespace sc::detail {

/// Per directed group pair; not thread-safe (one per pair and direction).
/// Leaves are numbered per group: the pieces of the parts in order, each piece's
/// leaves (PieceData::patches) in order.
class GroupPairQuery {
 public:
  /// Binds the two groups (target, opponent); resets the warm starts when the
  /// pieces change, and the remembered distance when any placement in a group does.
  /// Allocates only when the groups have more pieces than ever before.
  void bind(const GroupView& target, const GroupView& opponent);

  int targetLeafCount() const { return t_leaf_count_; }
  /// Radius of a sphere holding the target group: the length its relative
  /// thresholds scale with (set by bind(), so no query pays for it).
  double targetSize() const { return near_.target().radius; }
  /// contactsNear()'s rebuilds take the pairs they already keep with their bounds,
  /// unmeasured (default); false measures every pair (tests compare the two).
  void setNearReuseInRebuilds(bool reuse) { near_.setReuseInRebuilds(reuse); }
  /// contactsNear()'s rebuilds so far that started from the last one's front.
  int frontRebuilds() const { return front_.served(); }
  int opponentLeafCount() const { return o_leaf_count_; }
  Leaf targetLeaf(int t_leaf) const { return leafOf(t_slots_, t_leaf); }
  Leaf opponentLeaf(int o_leaf) const { return leafOf(o_slots_, o_leaf); }
  /// Every leaf as a list: built on first use after the groups change, O(leaves)
  /// time and memory (prefer targetLeaf / targetLeafCount on large models).
  const std::vector<Leaf>& targetLeaves() const;
  const std::vector<Leaf>& opponentLeaves() const;

  /// Minimum distance over all leaf pairs. False when every pair is farther than
  /// `max_distance` (then `best` is unset). An intersecting pair gives gap 0.
  /// Exact surface distance: a leaf pair whose GJK closest points lie on real faces
  /// is final; otherwise (a virtual feature: the patch's hull may reach out of the
  /// solid by the decomposition's tolerance) it is measured on its real triangles.
  /// Seeded with the last call's closest pair; answered from contactsNear()'s kept
  /// pairs, without a traversal, when they cover the pose up to the distance found.
  /// `sweep_next`: a sweep at this rotation is likely next (a long move's end): the
  /// separating planes the traversal finds are kept for it (PlaneMemo).
  bool distance(const Rigid& o_from_t, double max_distance, LeafContact& best,
                bool sweep_next = false);

  /// Pairs a contacts query gathers at most: two overlapping 10k-triangle meshes have
  /// some 10^8 leaf pairs within a body's size, 13 GB of them. Beyond it a query stops
  /// with every pair nearer than the lower bound of what is left in its queue (and
  /// some farther ones); contactsNear() reports that bound (nearCoveredReach).
  static constexpr std::size_t kMaxContacts = 16384;

  /// Every leaf pair with gap <= `threshold` (intersecting ones included), appended
  /// to `out` after clearing it, nearest first (ties by leaf indices); at most
  /// kMaxContacts of them, every one nearer than where the cap stopped the query.
  void contacts(const Rigid& o_from_t, double threshold, std::vector<LeafContact>& out);

  /// contacts() for poses that differ by small motions, as a sliding proxy or a
  /// resting body makes: one traversal with threshold + `margin` keeps its pairs, and
  /// later calls whose target points moved less than `margin` from that pose
  /// (displacementBound) evaluate only those (moving every point by at most d changes
  /// every gap by at most d). Same output as contacts(). Empty, touching no near
  /// pair, when the last distance less the motion since exceeds the threshold.
  void contactsNear(const Rigid& o_from_t, double threshold, double margin,
                    std::vector<LeafContact>& out);
  /// How far the last contactsNear()'s answer is complete at o_from_t: at least its
  /// threshold, unless kMaxContacts cut its pairs short; at least the last distance
  /// less the motion since.
  double nearCoveredReach(const Rigid& o_from_t) const;
  /// True when contactsNear(o_from_t, threshold, ...) answers from the kept pairs or
  /// the last distance, without running a rebuild.
  bool nearReaches(const Rigid& o_from_t, double threshold) const {
    return near_.covers(o_from_t, threshold) || knownLowerBound(o_from_t) > threshold;
  }
  /// contactsNear() will soon be called around o_from_t, where its kept pairs do not
  /// reach: their rebuild there is started, or continued, a share of it per call, so
  /// that no single call pays for all of it. `gap`, the distance at o_from_t, is the
  /// approach left before the contacts are due: the shares are paced to end by then.
  void rebuildNearAhead(const Rigid& o_from_t, double threshold, double margin, double gap);

  /// Closest points of one leaf pair (GJK with its warm start).
  LeafContact pairAt(int t_leaf, int o_leaf, const Rigid& o_from_t);

  /// True when some leaf pair intersects; the first one found goes to `first`.
  bool intersects(const Rigid& o_from_t, LeafContact* first = nullptr);

  /// Separation of one leaf pair along the unit direction n (opponent towards target):
  /// min over the target leaf of n.x minus max over the opponent leaf of n.x. Exact for
  /// convex leaves; positive means the plane orthogonal to n separates them.
  double separationAlong(int t_leaf, int o_leaf, const Rigid& o_from_t, const Vec3& n);

  /// Largest s in [0, 1] such that translating the target by s * delta (opponent frame)
  /// from `o_from_t` keeps every leaf pair not listed in `skip` at gap >= skin/2,
  /// ending at gap <= skin when a pair blocks. Conservative advancement per pair. A
  /// pair starting within skin blocks at once, unless it starts at skin/2 or more and
  /// the translation opens it (its separation along its normal only grows).
  /// `skip` is sorted (LeafPair::operator<).
  double translationToi(const Rigid& o_from_t, const Vec3& delta, double skin,
                        const std::vector<LeafPair>& skip);

  /// A length D such that the target translated by D * u (unit, opponent frame) from
  /// o_from_t is more than `gap` from the opponent: every target piece's root sphere
  /// beyond every opponent piece's along u (0 when already so).
  double clearingLength(const Rigid& o_from_t, const Vec3& u, double gap) const;

  const TraversalCounters& counters() const { return counters_; }

  /// Lower bound of the distance at `o_from_t` from the last distance() (its gap less
  /// the motion since), or -inf when none is known (none yet, or the groups changed).
  double distanceLowerBound(const Rigid& o_from_t) const { return knownLowerBound(o_from_t); }

  /// Largest displacement of a target point from pose `from` to pose `to`.
  double displacementBound(const Rigid& from, const Rigid& to) const {
    return near_.target().displacement(from, to);
  }
  /// About how far the target's farthest point moves from `from` to `to` (the centre's
  /// shift plus the turn's 2 sin(angle / 2) at the radius): a measure, not a bound.
  double targetMotion(const Rigid& from, const Rigid& to) const {
    return near_.target().motion(from, to);
  }

 private:
  /// One piece of a part of a group, with its leaf and node index ranges.
  struct Slot {
    const PieceData* data = nullptr;
    Rigid group_from_piece;
    int part = -1;
    int piece = -1;
    int first_leaf = 0;
    int first_node = 0;
  };
  /// A real face of a leaf, placed in the opponent frame, with its bounding sphere.
  struct PlacedFace {
    Vec3 corners[3];
    Vec3 center;
    double radius = 0.0;
    int face = -1;     ///< index into the leaf's faces
    double key = 0.0;  ///< refine()'s order: the face's extent along the hulls' normal
  };
  struct DistancePolicy;
  struct ContactsPolicy;
  struct IntersectPolicy;
  struct ToiPolicy;

  static void collectSlots(const GroupView& group, std::vector<Slot>& out, int& leaf_count);
  static int slotOf(const std::vector<Slot>& slots, int leaf);
  static Leaf leafOf(const std::vector<Slot>& slots, int leaf);
  static bool sameSlots(const std::vector<Slot>& a, const std::vector<Slot>& b, bool& moved);
  void updateGroupSphere();

  const ConvexPolytope& polytopeOf(const Slot& slot, int node) const {
    return slot.data->hierarchy.polytope(slot.data->patches, node);
  }
  /// A node pair's key in caches_ and planes_: its two nodes' group-wide indices.
  std::uint64_t keyOf(const NodePair& p) const;
  SimplexCache& cacheOf(const NodePair& p) { return caches_.at(keyOf(p)); }
  /// Places every target piece in the opponent frame for this query.
  void placeTargets(const Rigid& o_from_t);
  double sphereBound(const NodePair& p) const;
  /// The two node pairs p splits into: a node without hull is split first, else the
  /// larger; each bounded by p's bound and its spheres, unrefined.
  std::array<NodePair, 2> childrenOf(const NodePair& p) const;
  /// Calls f with the root pair of every target slot and opponent slot, bounded by
  /// its spheres.
  template <class F>
  void forEachRoot(F f) const {
    for (int ts = 0; ts < static_cast<int>(t_slots_.size()); ++ts) {
      for (int os = 0; os < static_cast<int>(o_slots_.size()); ++os) {
        NodePair root;
        root.t_slot = ts;
        root.o_slot = os;
        root.bound = std::max(0.0, sphereBound(root));
        f(root);
      }
    }
  }
  /// True when both nodes of p are leaves (a leaf pair, to visit).
  bool leavesOf(const NodePair& p) const {
    return t_slots_[p.t_slot].data->hierarchy.nodes[p.t_node].leaf() &&
           o_slots_[p.o_slot].data->hierarchy.nodes[p.o_node].leaf();
  }
  /// Both nodes have a polytope (a leaf, or an inner node that keeps its hull), so
  /// GJK can bound the pair; otherwise its sphere bound is all there is.
  bool hullsOf(const NodePair& p) const {
    return t_slots_[p.t_slot].data->hierarchy.nodes[p.t_node].hasPolytope() &&
           o_slots_[p.o_slot].data->hierarchy.nodes[p.o_node].hasPolytope();
  }
  /// GJK lower bound of a node pair's distance, exact up to max_distance unless the
  /// pair is found within `within_distance` first (negative: never); 0 for a pair
  /// without both hulls.
  double nodeLowerBound(const NodePair& p, double max_distance, double within_distance);
  /// GJK on a node pair's hulls (as nodeLowerBound), with its closest points and normal.
  GjkResult nodeGjk(const NodePair& p, double max_distance, double within_distance);
  /// GJK on a node pair's hulls, the target piece placed by `o_from_piece`.
  GjkResult nodeGjkAt(const NodePair& p, const Rigid& o_from_piece, const GjkSettings& settings,
                      SimplexCache& cache);
  /// contactsNear() without its memo of the last call.
  void contactsNearUncached(const Rigid& o_from_t, double threshold, double margin,
                            std::vector<LeafContact>& out);
  /// distance() from the kept near pairs: true when `best` (found: already a
  /// candidate) is the distance at o_from_t, which they cover.
  bool distanceNear(const Rigid& o_from_t, double max_distance, LeafContact& best, bool& found);
  /// contactsNear()'s pairs at o_from_t, none farther than `threshold`, into `out`.
  void evaluateNear(const Rigid& o_from_t, double threshold, std::vector<LeafContact>& out);
  /// near_.mutablePairs() (sorted; gaps measured at `pose`, or lower bounds there for
  /// the pairs a rebuild kept unmeasured) become the pairs within `reach` there.
  void installNear(const Rigid& pose, double reach);
  /// A rebuild's leaf pair p at `pose` that near_ keeps: into `out` unmeasured with
  /// its bound when that is within `reach`, else recorded beyond it in `front`; false
  /// (nothing done) when near_ does not keep it.
  bool visitKept(const NodePair& p, const Rigid& pose, double reach, std::vector<LeafContact>& out,
                 NearFront* front);
  /// The pose a rebuild at `pose` takes near_'s kept pairs at, or null (measure all).
  const Rigid* keptAt(const Rigid& pose) const { return near_.reuseInRebuilds() ? &pose : nullptr; }
  /// Writes the kept pairs' warm starts back to caches_ before a rebuild replaces them.
  void saveNearCaches();
  /// Measures the unmeasured pairs of `out` (near_'s, at o_from_t) and drops those
  /// beyond `threshold`.
  void measureKept(const Rigid& o_from_t, double threshold, std::vector<LeafContact>& out);
  /// The next rebuild, started at o_from_t ahead of need and run a little per call.
  void startPendingNear(const Rigid& o_from_t, double reach);
  /// The pending rebuild's first node pairs into `heap`: from front_ when it serves,
  /// else from the roots.
  void seedPendingNear(ContactsPolicy& policy, const Rigid& o_from_t, std::vector<NodePair>& heap);
  /// The pending rebuild, given up before its end, leaves its partition as the front.
  void frontFromPending();
  /// Runs the pending rebuild for a while and installs it once done. With `finish`
  /// (the kept pairs no longer cover o_from_t) it runs only as far as o_from_t needs
  /// and installs what it found, going on afterwards. Dropped when it no longer
  /// covers o_from_t within `threshold`. Returns the work it did.
  TraversalCounters advancePendingNear(const Rigid& o_from_t, double threshold, bool finish);
  /// GJK on a leaf pair, the target piece placed by `o_from_piece`, warm-started from
  /// `cache` (the pair's entry of caches_ when null).
  LeafContact evaluate(const NodePair& p, const Rigid& o_from_piece, double max_distance,
                       bool& beyond, SimplexCache* cache = nullptr);
  NodePair leafPair(int t_leaf, int o_leaf) const;
  /// Replaces `c` by the closest points of the two leaves' real triangles when
  /// nearer than `bound`; false (c unchanged) when no triangle pair is.
  bool refine(const NodePair& p, const Rigid& o_from_piece, double bound, LeafContact& c);
  /// GJK on a leaf pair for distance(): refined when its closest feature is virtual
  /// and it could beat `bound`. `beyond` when it cannot, or when its feature is
  /// virtual and `defer_virtual` (the caller measures it later with a tighter bound).
  LeafContact exactLeafDistance(const NodePair& p, double bound, bool& beyond,
                                bool defer_virtual = false);
  template <class Policy>
  void traverse(Policy& policy);
  /// translationToi()'s traversal: node pairs taken in the order of the earliest
  /// fraction of the motion at which they can block, not of their distance.
  void sweep(ToiPolicy& policy);
  /// traverse() in two parts: the root pairs into `heap`, then node pairs taken from
  /// it, at most `budget` of them (negative: no limit) and only while the nearest
  /// left is nearer than `until`; true once the traversal is done.
  template <class Policy>
  void seedTraversal(Policy& policy, std::vector<NodePair>& heap);
  template <class Policy>
  bool runTraversal(Policy& policy, std::vector<NodePair>& heap, int budget,
                    double until = kInfinity);
  /// True when the last closest leaf pair is worth measuring first at o_from_t.
  bool seedHelps(const Rigid& o_from_t) const;
  /// Upper bound of the distance at `o_from_t` from the last distance() (its gap plus
  /// the motion since), at most max_distance.
  double seedBound(const Rigid& o_from_t, double max_distance) const;
  /// Lower bound of the distance at `o_from_t` from the last distance(), or -inf.
  double knownLowerBound(const Rigid& o_from_t) const;

  std::vector<Slot> t_slots_, o_slots_, scratch_slots_;
  int t_leaf_count_ = 0;
  int o_leaf_count_ = 0;
  std::vector<Rigid> o_from_piece_;  ///< per target slot, for the current query
  std::vector<NodePair> heap_;
  std::vector<PlacedFace> faces_t_, faces_o_;  ///< refine()'s scratch
  PairCache caches_;
  PlaneMemo planes_;  ///< node pairs' separating planes found by the sweeps
  /// sweep()'s queue entry: a node pair, the fraction of the motion before which it
  /// stays more than skin apart, and the GJK runs that pushed that on.
  struct Timed {
    double when = 0.0;
    int steps = 0;
    NodePair pair;
  };
  std::vector<Timed> sweep_heap_;
  bool record_planes_ = false;  ///< nodeGjk() keeps its planes: distance(sweep_next)
  LeafPair seed_;  ///< closest leaf pair of the last distance(), or -1s
  /// The last distance(): every leaf pair was at least known_gap_ apart at known_pose_.
  bool known_ = false;
  Rigid known_pose_;
  double known_gap_ = 0.0;
  NearPairs near_;   ///< contactsNear()'s warm state; holds the target group's sphere
  NearFront front_;  ///< where the next rebuild of near_'s pairs starts
  TraversalCounters counters_;
  // Lazily built leaf lists (targetLeaves / opponentLeaves); a cache, not state.
  mutable std::vector<Leaf> t_leaves_, o_leaves_;
  mutable bool t_leaves_valid_ = false;
  mutable bool o_leaves_valid_ = false;
};

}  // namespace sc::detail
