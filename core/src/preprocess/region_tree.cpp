// SPDX-License-Identifier: MIT
#include "preprocess/region_tree.h"

#include <algorithm>

namespace sc::detail {

Vec3 RegionTree::twiceCentre(int t) const { return box(t).min + box(t).max; }

RegionTree::RegionTree(const SharedMesh& shared)
    : shared_(shared), leaf_of_(shared.mesh.triangles.size(), -1) {}

void RegionTree::build(int region, double margin) {
  Aabb reach;
  for (int i = shared_.region_start[region]; i < shared_.region_start[region + 1]; ++i) {
    reach.extend(shared_.tree.box(shared_.region_order[i]));
  }
  reach.min -= Vec3::Constant(margin);
  reach.max += Vec3::Constant(margin);
  items_.clear();
  nodes_.clear();
  shared_.tree.query([&](const Aabb& box) { return boxesOverlap(box, reach); },
                     [&](int t) {
                       if (boxesOverlap(shared_.tree.box(t), reach)) items_.push_back(t);
                       return true;
                     });
  if (items_.empty()) return;
  // Sorted, so the tree depends on the mesh alone, not on the shared tree's order.
  std::sort(items_.begin(), items_.end());
  nodes_.emplace_back();
  buildNode(0, 0, static_cast<int>(items_.size()), 0);
}

void RegionTree::buildNode(int index, int begin, int end, int depth) {
  Aabb box_all, centres;
  for (int i = begin; i < end; ++i) {
    box_all.extend(box(items_[i]));
    centres.extend(twiceCentre(items_[i]));
  }
  nodes_[index].box = box_all;
  nodes_[index].size = end - begin;
  if (end - begin <= kLeafSize || depth >= kMaxDepth - 1) {
    nodes_[index].first = begin;
    nodes_[index].count = end - begin;
    for (int i = begin; i < end; ++i) leaf_of_[items_[i]] = index;
    return;
  }
  int axis = 0;
  (centres.max - centres.min).maxCoeff(&axis);
  const int mid = begin + (end - begin) / 2;
  std::nth_element(items_.begin() + begin, items_.begin() + mid, items_.begin() + end,
                   [&](int a, int b) {
                     const double ca = twiceCentre(a)[axis], cb = twiceCentre(b)[axis];
                     return ca != cb ? ca < cb : a < b;
                   });
  const int left = static_cast<int>(nodes_.size());
  nodes_[index].first = left;
  nodes_[index].count = 0;
  nodes_.emplace_back();
  nodes_.emplace_back();
  nodes_[left].parent = nodes_[left + 1].parent = index;
  buildNode(left, begin, mid, depth + 1);
  buildNode(left + 1, mid, end, depth + 1);
}

void RegionTree::markPatch(int t, int delta) {
  for (int node = leaf_of_[t]; node >= 0; node = nodes_[node].parent) {
    nodes_[node].in_patch += delta;
  }
}

}  // namespace sc::detail
