// SPDX-License-Identifier: MIT
// Dynamic bounding-box tree of the scene broadphase: leaves with fattened boxes,
// inserted, moved and removed one at a time, queried with a distance margin, and
// the leaf pairs within a margin kept up to date from frame to frame.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/ordered_pair.h"
#include "smartcollision/types.h"

namespace sc::detail {

/// Two leaf handles, lo < hi.
using HandlePair = OrderedPair;

/// Binary tree whose leaves hold a tight box, a fat box containing it, and a user
/// integer. A leaf is re-inserted only when its tight box leaves its fat box, so
/// slowly moving leaves cost nothing per frame. Insertion picks the sibling by the
/// surface-area heuristic; on the way back up, a rotation swaps a child and a
/// grandchild when that shrinks the boxes (docs/scene.md has the measurements).
/// Leaf handles stay valid until the leaf is removed.
class DynamicAabbTree {
 public:
  static constexpr int kNull = -1;

  /// Adds a leaf; returns its handle. Allocates only while the node pool grows.
  int insert(const Aabb& box, int user);
  void remove(int leaf);
  /// Sets the leaf's tight box; re-inserts it (true) when it left the fat box.
  bool move(int leaf, const Aabb& box);
  void clear();

  const Aabb& box(int leaf) const { return tight_[leaf]; }
  const Aabb& fatBox(int leaf) const { return nodes_[leaf].fat; }
  int user(int leaf) const { return nodes_[leaf].user; }
  int leafCount() const { return leaf_count_; }
  bool empty() const { return root_ == kNull; }
  /// Height of the root (a single leaf has height 0; an empty tree -1).
  int height() const { return root_ == kNull ? -1 : nodes_[root_].height; }

  /// Calls visit(leaf) for every leaf whose fat box overlaps `box` grown by `margin`
  /// on every side (a superset of the leaves within Euclidean distance `margin`).
  /// margin may be +inf. Returns the number of nodes tested (a measure of the tree's
  /// quality). Not reentrant: it uses the tree's own stack.
  template <class Visit>
  int query(const Aabb& box, double margin, Visit&& visit);

  /// Every pair of leaves with different user values whose fat boxes overlap when
  /// one is grown by `margin`, sorted. Temporal coherence: only the leaves inserted
  /// or re-inserted since the last call are queried; the pairs of the others still
  /// hold, as their fat boxes have not changed. A new margin recomputes all.
  const std::vector<HandlePair>& pairs(double margin);

  /// Checks parent links, heights, containment of boxes, the free list and the leaf
  /// count (for tests). Returns false at the first broken invariant.
  bool valid() const;

 private:
  struct Node {
    Aabb fat;  ///< leaf: the fattened box; inner: union of the children's fat boxes
    int parent = kNull;  ///< also the next free node while on the free list
    int left = kNull;
    int right = kNull;
    int height = 0;  ///< 0 for leaves
    int user = -1;
    bool leaf() const { return left == kNull; }
  };

  int allocate();
  void release(int node);
  void insertLeaf(int leaf);
  void detachLeaf(int leaf);
  int pickSibling(const Aabb& box) const;
  /// Rotates and refits every ancestor from `node` up to the root.
  void repairUpFrom(int node);
  void rotate(int node);
  void refit(int node);
  bool validNode(int node, int parent, int& leaves) const;
  void markDirty(int leaf);

  std::vector<Node> nodes_;
  std::vector<Aabb> tight_;  ///< by node; meaningful for leaves (apart from the nodes: queries skip it)
  std::vector<int> stack_;
  // Pair maintenance.
  std::vector<std::uint8_t> dirty_;  ///< by node: inserted, re-inserted or removed since pairs()
  std::vector<int> dirty_list_;
  std::vector<HandlePair> pairs_;
  std::vector<HandlePair> fresh_;
  std::vector<HandlePair> merged_;
  double pair_margin_ = 0.0;
  bool pairs_valid_ = false;
  int root_ = kNull;
  int free_ = kNull;
  int leaf_count_ = 0;
};

/// True when the boxes overlap (touching counts).
inline bool overlaps(const Aabb& a, const Aabb& b) {
  return (a.min.array() <= b.max.array()).all() && (b.min.array() <= a.max.array()).all();
}

template <class Visit>
int DynamicAabbTree::query(const Aabb& box, double margin, Visit&& visit) {
  if (root_ == kNull) return 0;
  Aabb grown;
  grown.min = box.min.array() - margin;
  grown.max = box.max.array() + margin;
  stack_.clear();
  stack_.push_back(root_);
  int tested = 0;
  while (!stack_.empty()) {
    const int n = stack_.back();
    stack_.pop_back();
    ++tested;
    const Node& node = nodes_[n];
    if (!overlaps(node.fat, grown)) continue;
    if (node.leaf()) {
      visit(n);
    } else {
      stack_.push_back(node.right);
      stack_.push_back(node.left);
    }
  }
  return tested;
}

}  // namespace sc::detail
