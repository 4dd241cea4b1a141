// SPDX-License-Identifier: MIT
// The front a rebuild of contactsNear()'s pairs leaves behind, so that the next rebuild
// starts from it instead of from the roots of the two hierarchies.
//
// A complete traversal partitions every leaf pair under the roots into the node pairs
// it pruned (each with a lower bound of its distance at the rebuild's pose K) and the
// leaf pairs it measured. At a pose X each bound b is still a bound b - d, with d the
// largest displacement of a target point from K to X, so the next rebuild takes only
// the entries that may now be within its reach and keeps the others as they are, with
// their bounds lowered by d. Rule: the front serves a rebuild while d stays within the
// reach that rebuild is for (after a jump most of it would be expanded again: the
// roots are cheaper) and while it has grown to at most kGrowth times the size of the
// last front that started from the roots (it only ever refines, never coarsens: a
// contact sliding over the surface leaves a fine trail behind).
#pragma once

#include <cstddef>
#include <vector>

#include "query/leaf_types.h"

namespace sc::detail {

class NearFront {
 public:
  static constexpr std::size_t kGrowth = 2;

  /// The groups' pieces or placements changed.
  void drop() { valid_ = recording_ = false; }
  /// True when a rebuild for `reach` at a pose `moved` from pose() may start from it.
  bool serves(double moved, double reach) const {
    return valid_ && moved <= reach && pairs_.size() <= kGrowth * root_size_;
  }
  const Rigid& pose() const { return pose_; }
  const std::vector<NodePair>& pairs() const { return pairs_; }
  /// Rebuilds that started from a front so far.
  int served() const { return served_; }

  /// A rebuild starts: what it leaves unexpanded is record()ed until finish().
  void begin(bool from_roots) {
    served_ += from_roots ? 0 : 1;
    next_.clear();
    recording_ = true;
    next_from_roots_ = from_roots;
  }
  void record(const NodePair& p) {
    if (recording_) next_.push_back(p);
  }
  /// The rebuild is complete at `pose`: its front replaces this one.
  void finish(const Rigid& pose) {
    if (!recording_) return;
    recording_ = false;
    valid_ = true;
    pose_ = pose;
    pairs_.swap(next_);
    if (next_from_roots_) root_size_ = pairs_.size();
  }

 private:
  bool valid_ = false;
  bool recording_ = false;
  bool next_from_roots_ = false;
  Rigid pose_;
  int served_ = 0;
  std::size_t root_size_ = 0;  ///< entries of the last front that started from the roots
  std::vector<NodePair> pairs_, next_;
};

}  // namespace sc::detail
