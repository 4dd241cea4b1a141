// SPDX-License-Identifier: MIT
// A bounding-box tree over the triangles that can meet one region's hulls, which
// knows how many of the current patch's triangles each node holds, so that the
// inside tests skip the subtrees the patch fills instead of walking them.
#pragma once

#include <cstdint>
#include <vector>

#include "preprocess/decomposition_mesh.h"

namespace sc::detail {

class RegionTree {
 public:
  /// Sized for `shared`'s mesh; one per thread.
  explicit RegionTree(const SharedMesh& shared);

  /// Rebuilds over the triangles whose boxes reach region `region`'s box widened by
  /// `margin`: every hull, tetrahedron and probe of a patch in the region lies in
  /// the box of its vertices widened by the probes' depth, so no triangle that can
  /// reach one is left out. No patch triangle counted.
  void build(int region, double margin);
  /// Counts triangle t (of the current region) into the patch, or out of it.
  void markPatch(int t, int delta);

  /// Like AabbTree::query; with `skip_patch`, subtrees whose triangles all lie in
  /// the patch (as counted by markPatch) are not entered.
  template <class Descend, class Visit>
  bool query(bool skip_patch, Descend&& descend, Visit&& visit) const;
  /// query() for several tests at once: `descend(box, mask)` returns the tests of
  /// `mask` not yet ruled out for the box (0: not entered), and its children start
  /// from that, since their boxes lie in its box; `visit(item, mask)` gets its
  /// leaf's.
  template <class Descend, class Visit>
  bool queryMasked(bool skip_patch, std::uint64_t mask, Descend&& descend, Visit&& visit) const;
  const Aabb& box(int t) const { return shared_.tree.box(t); }

 private:
  static constexpr int kLeafSize = 4;
  static constexpr int kMaxDepth = 64;

  struct Node {
    Aabb box;
    int first = 0;  ///< leaf: first index into items_; inner: left child
    int count = 0;  ///< leaf: item count; inner: 0 (right child = left + 1)
    int parent = -1;
    int size = 0;      ///< triangles in the subtree
    int in_patch = 0;  ///< of them, in the current patch
  };

  void buildNode(int index, int begin, int end, int depth);
  /// Twice triangle t's box centre: the splits compare centres without storing them.
  Vec3 twiceCentre(int t) const;

  const SharedMesh& shared_;
  std::vector<Node> nodes_;
  std::vector<int> items_;    ///< triangle indices
  std::vector<int> leaf_of_;  ///< per mesh triangle: its leaf (valid for this region's)
};

template <class Descend, class Visit>
bool RegionTree::query(bool skip_patch, Descend&& descend, Visit&& visit) const {
  // One test: queryMasked with a single bit.
  return queryMasked(
      skip_patch, 1, [&](const Aabb& box, std::uint64_t) -> std::uint64_t { return descend(box); },
      [&](int t, std::uint64_t) { return visit(t); });
}

template <class Descend, class Visit>
bool RegionTree::queryMasked(bool skip_patch, std::uint64_t mask, Descend&& descend,
                             Visit&& visit) const {
  if (nodes_.empty()) return true;
  struct Entry {
    int node;
    std::uint64_t mask;
  };
  Entry stack[kMaxDepth + 1];
  int top = 0;
  stack[top++] = {0, mask};
  while (top > 0) {
    const Entry entry = stack[--top];
    const Node& node = nodes_[entry.node];
    if (skip_patch && node.in_patch == node.size) continue;
    const std::uint64_t open = descend(node.box, entry.mask);
    if (open == 0) continue;
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        if (!visit(items_[i], open)) return false;
      }
    } else {
      stack[top++] = {node.first + 1, open};
      stack[top++] = {node.first, open};
    }
  }
  return true;
}

}  // namespace sc::detail
