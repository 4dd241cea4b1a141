// SPDX-License-Identifier: MIT
// Static bounding-box tree over a fixed set of boxes (typically one per mesh
// triangle), queried with a caller's box predicate and leaf visitor.
#pragma once

#include <vector>

#include "smartcollision/types.h"

namespace sc::detail {

/// True when the boxes overlap (touching counts).
inline bool boxesOverlap(const Aabb& a, const Aabb& b) {
  return !(a.min.array() > b.max.array()).any() && !(a.max.array() < b.min.array()).any();
}

class AabbTree {
 public:
  /// Builds a binary tree by median splits along the longest axis of the box
  /// centres; leaves hold up to kLeafSize items. Item i is boxes[i].
  explicit AabbTree(const std::vector<Aabb>& boxes);
  AabbTree() = default;

  /// Visits every item whose ancestors' boxes all pass `descend(const Aabb&)`;
  /// `visit(int item)` returns false to stop the whole query. Returns false when
  /// stopped. Uses a small fixed stack; allocates nothing.
  template <class Descend, class Visit>
  bool query(Descend&& descend, Visit&& visit) const;

  const Aabb& box(int item) const { return boxes_[item]; }
  int size() const { return static_cast<int>(boxes_.size()); }

 private:
  static constexpr int kLeafSize = 4;
  static constexpr int kMaxDepth = 64;

  struct Node {
    Aabb box;
    int first = 0;  ///< leaf: first index into items_; inner: index of left child
    int count = 0;  ///< leaf: item count; inner: 0 (right child = left + 1)
  };

  void buildNode(int index, int begin, int end, int depth);

  std::vector<Aabb> boxes_;
  std::vector<int> items_;
  std::vector<Node> nodes_;
  std::vector<Vec3> centres_;  ///< only during construction
};

template <class Descend, class Visit>
bool AabbTree::query(Descend&& descend, Visit&& visit) const {
  if (nodes_.empty()) return true;
  int stack[kMaxDepth + 1];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!descend(node.box)) continue;
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        if (!visit(items_[i])) return false;
      }
    } else {
      stack[top++] = node.first + 1;
      stack[top++] = node.first;
    }
  }
  return true;
}

}  // namespace sc::detail
