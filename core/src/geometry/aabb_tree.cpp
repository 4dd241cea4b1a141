// SPDX-License-Identifier: MIT
#include "geometry/aabb_tree.h"

#include <algorithm>

namespace sc::detail {

AabbTree::AabbTree(const std::vector<Aabb>& boxes) : boxes_(boxes) {
  const int n = static_cast<int>(boxes_.size());
  if (n == 0) return;
  items_.resize(n);
  centres_.resize(n);
  for (int i = 0; i < n; ++i) {
    items_[i] = i;
    centres_[i] = 0.5 * (boxes_[i].min + boxes_[i].max);
  }
  nodes_.reserve(static_cast<std::size_t>(n));
  nodes_.emplace_back();
  buildNode(0, 0, n, 0);
  centres_.clear();
  centres_.shrink_to_fit();
}

// Fills node `index` for items_[begin, end). Median splits bound the depth by
// log2(n) + 1, far below kMaxDepth; the depth cap only guards the fixed stack.
void AabbTree::buildNode(int index, int begin, int end, int depth) {
  Aabb box, centres;
  for (int i = begin; i < end; ++i) {
    box.extend(boxes_[items_[i]]);
    centres.extend(centres_[items_[i]]);
  }
  nodes_[index].box = box;
  if (end - begin <= kLeafSize || depth >= kMaxDepth - 1) {
    nodes_[index].first = begin;
    nodes_[index].count = end - begin;
    return;
  }
  int axis = 0;
  (centres.max - centres.min).maxCoeff(&axis);
  const int mid = begin + (end - begin) / 2;
  std::nth_element(items_.begin() + begin, items_.begin() + mid, items_.begin() + end,
                   [&](int a, int b) { return centres_[a][axis] < centres_[b][axis]; });
  // Children sit next to each other, so an inner node needs one link.
  const int left = static_cast<int>(nodes_.size());
  nodes_[index].first = left;
  nodes_[index].count = 0;
  nodes_.emplace_back();
  nodes_.emplace_back();
  buildNode(left, begin, mid, depth + 1);
  buildNode(left + 1, mid, end, depth + 1);
}

}  // namespace sc::detail
