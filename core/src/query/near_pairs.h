// SPDX-License-Identifier: MIT
// The warm state of GroupPairQuery::contactsNear(): the leaf pairs kept within a reach
// of the pose they were gathered at, their warm starts and gap bounds, the rebuild run
// ahead of need, and the memo of the last answer.
//
// The rule, for every part of it: moving every target point by at most d changes every
// gap by at most d, so state gathered at pose K up to reach r answers at pose X for a
// threshold t while displacement(K, X) + t <= r. Past that it no longer helps and is
// dropped at once, not followed: the kept pairs (covers), the rebuild started ahead
// (pendingCovers, which can never cover again once it fails, the motion since its
// start only growing its need), and the memo, which answers only its own pose and
// threshold (a changed contact set is a new rebuild, which rewrites it). New pieces or
// placements of the groups drop everything (drop()).
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "query/gjk.h"
#include "query/leaf_types.h"

namespace sc::detail {

/// A sphere holding the target group (its own frame): bounds how far any target
/// point moves between two placements of the group.
struct TargetSphere {
  Vec3 center = Vec3::Zero();
  double radius = 0.0;

  /// Largest displacement of a target point from pose `from` to pose `to`.
  double displacement(const Rigid& from, const Rigid& to) const;
  /// The same with the turn's spectral norm 2 sin(angle / 2) (the Frobenius norm of a
  /// rotation's difference is sqrt(2) times it): nearer the true motion, but rounding
  /// may put it below: not a bound.
  double motion(const Rigid& from, const Rigid& to) const;
};

class NearPairs {
 public:
  void setTarget(const TargetSphere& sphere) { sphere_ = sphere; }
  const TargetSphere& target() const { return sphere_; }

  // -- The rule (see the file comment) --
  /// The kept pairs hold every leaf pair within `reach` at o_from_t.
  bool covers(const Rigid& o_from_t, double reach) const {
    return valid_ && sphere_.displacement(pose_, o_from_t) + reach <= reach_;
  }
  /// How far the kept pairs are complete at o_from_t (0 without pairs).
  double coveredReach(const Rigid& o_from_t) const {
    return valid_ ? reach_ - sphere_.displacement(pose_, o_from_t) : 0.0;
  }
  /// The rebuild run ahead can still cover o_from_t within `threshold` (none: false).
  bool pendingCovers(const Rigid& o_from_t, double threshold) const {
    return pending_.active &&
           sphere_.displacement(pending_.pose, o_from_t) + threshold <= pending_.reach;
  }
  /// The last answer when o_from_t and threshold are exactly its own, else null.
  const std::vector<LeafContact>* memo(const Rigid& o_from_t, double threshold) const;
  /// Forgets everything: the groups' pieces or placements changed.
  void drop() { valid_ = memo_valid_ = pending_.active = false; }
  void dropPending() { pending_.active = false; }

  // -- The kept pairs --
  const Rigid& pose() const { return pose_; }
  double reach() const { return reach_; }
  const std::vector<LeafContact>& pairs() const { return pairs_; }
  std::vector<LeafContact>& mutablePairs() { return pairs_; }
  SimplexCache& cache(std::size_t i) { return caches_[i]; }
  /// Starts a set of pairs measured at `pose`, complete up to `reach`: the pairs are
  /// mutablePairs(), sorted; keep() must follow for each in order.
  void install(const Rigid& pose, double reach);
  /// Pair i's warm start and its target leaf's sphere (group frame).
  void keep(const SimplexCache& cache, const Vec3& center, double radius, double gap);
  /// Indexes the installed pairs by leaf pair for find(); after the last keep().
  void indexPairs();
  /// Index of the kept pair (t_leaf, o_leaf), or -1.
  int find(const LeafPair& p) const;
  /// Lower bound of pair i's gap at `pose`, from its last measurement (any pose).
  double gapBoundAt(std::size_t i, const Rigid& pose) const;
  /// Whether a rebuild takes a kept pair's bound instead of measuring it (tests
  /// compare with measuring every pair).
  void setReuseInRebuilds(bool reuse) { reuse_in_rebuilds_ = reuse; }
  bool reuseInRebuilds() const { return reuse_in_rebuilds_ && valid_; }
  /// Prepares gapBound() for the pose o_from_t; returns the index it gets.
  int prepareBounds(const Rigid& o_from_t);
  /// Lower bound of pair i's gap at the pose of the last prepareBounds().
  double gapBound(std::size_t i) const;
  /// Pair i measured again at the pose `pose` of prepareBounds().
  void measured(std::size_t i, double gap, int pose) {
    gaps_[i].gap = gap;
    gaps_[i].pose = pose;
  }
  void remember(const Rigid& o_from_t, double threshold, const std::vector<LeafContact>& out);

  // -- The rebuild run ahead: a traversal spread over calls (GroupPairQuery runs it) --
  struct Pending {
    bool active = false;
    Rigid pose;
    double reach = 0.0;
    std::vector<NodePair> heap;
    std::vector<Rigid> o_from_piece;
    std::vector<LeafContact> found;
    int work = 0;     ///< node pairs taken so far
    Rigid last_pose;  ///< pose of the last call that ran it (the target's speed)
    /// Motion left before its contacts are due, when run ahead of a first contact
    /// (the distance there), else 0: paces it without kept pairs to cover the target.
    double approach = 0.0;
    bool receding = false;  ///< that gap grew since the last call: no hurry
  };
  Pending& pending() { return pending_; }
  const Pending& pending() const { return pending_; }
  /// Node pairs the pending rebuild may take in this call (-1: no limit).
  int pendingBudget(const Rigid& o_from_t, double threshold) const;
  /// The pending rebuild is done: its pairs replace the kept ones.
  void finishPending();

 private:
  /// Per kept pair: its gap when last measured, at poses_[pose], and its target leaf's
  /// sphere (group frame), which bounds how much that gap can shrink since. Measuring
  /// a pair again refreshes its gap, so only pairs near the threshold are measured
  /// again, however far the group moved.
  struct Gap {
    Vec3 center = Vec3::Zero();
    double radius = 0.0;
    double gap = 0.0;
    int pose = 0;
  };
  /// Per poses_ entry, for the current query: the rotation and translation change.
  struct PoseChange {
    Mat3 rotation;
    Vec3 translation;
    double spin;  ///< Frobenius norm of the rotation change
  };

  TargetSphere sphere_;
  bool valid_ = false;
  Rigid pose_;
  double reach_ = 0.0;
  std::vector<LeafContact> pairs_;
  /// Warm starts in the pairs' order: read in sequence, where the set-associative
  /// PairCache would be probed at random.
  std::vector<SimplexCache> caches_;
  std::vector<Gap> gaps_;
  std::vector<std::pair<LeafPair, int>> index_;  ///< sorted by leaf pair
  bool reuse_in_rebuilds_ = true;
  std::vector<Rigid> poses_;  ///< poses a pair was last measured at
  std::vector<PoseChange> changes_;
  Pending pending_;
  int expected_work_ = 0;  ///< node pairs of the last rebuild: sets the next one's pace
  bool memo_valid_ = false;
  Rigid memo_pose_;
  double memo_threshold_ = 0.0;
  std::vector<LeafContact> memo_out_;
};

}  // namespace sc::detail
