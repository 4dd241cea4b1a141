// SPDX-License-Identifier: MIT
// The front a rebuild of contactsNear()'s pairs leaves behind, so that the next rebuild
// starts from it instead of from the roots of the two hierarchies.
//
// A complete traversal partitions every leaf pair under the roots into the node pairs
// it pruned (each with a lower bound of its distance at the rebuild's pose K) and the
// leaf pairs it measured; so does one given up on the way, with what is left in its
// queue. At a pose X each bound b is still a bound b - d, with d the largest
// displacement of a target point from K to X, and the entry's two spheres placed at X
// bound it as well; the next rebuild takes only the entries that neither bound puts
// beyond its reach and keeps the others with the better bound. Rule: the front serves
// a rebuild while d stays within a few times that reach (kFrontMoves in
// group_pair_near.cpp; farther, the trail lies away from the new contact and the
// roots' GJK bounds prune more at once) and while it has grown to at most kGrowth
// times the size of the largest front that started from the roots (it only ever
// refines, never coarsens: a contact sliding over the surface leaves a fine trail).
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "query/leaf_types.h"

namespace sc::detail {

class NearFront {
 public:
  /// Four, not two: a fine trail far from the contact costs one comparison per entry
  /// (its bound less the motion), while a rebuild from the roots costs hundreds of GJK
  /// runs on node hulls (bunny00 x bunny00 PD path: p99 1.28 -> 1.23 M instructions).
  static constexpr std::size_t kGrowth = 4;

  /// The groups' pieces or placements changed.
  void drop() { valid_ = recording_ = false; }
  /// True when a rebuild may start from it.
  bool serves() const { return valid_ && pairs_.size() <= kGrowth * root_size_; }
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
    if (next_from_roots_) root_size_ = std::max(root_size_, pairs_.size());
  }

 private:
  bool valid_ = false;
  bool recording_ = false;
  bool next_from_roots_ = false;
  Rigid pose_;
  int served_ = 0;
  /// Entries of the largest front that started from the roots: one at a free pose
  /// (a few dozen) must not make a contact's front (hundreds) look overgrown.
  std::size_t root_size_ = 0;
  std::vector<NodePair> pairs_, next_;
};

}  // namespace sc::detail
