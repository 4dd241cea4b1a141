// SPDX-License-Identifier: MIT
// Dynamic bounding-box tree: insertion by the surface-area heuristic, removal by
// splicing out the parent, and area-reducing rotations on the path to the root.
#include "scene/aabb_tree.h"

#include <algorithm>
#include <iterator>
#include <utility>

namespace sc::detail {

namespace {

/// Fat boxes grow by this fraction of the box's largest extent on every side...
constexpr double kFatFraction = 0.1;
/// ...and by this multiple of the last displacement on its leading side, so a leaf
/// moving steadily is re-inserted only every few frames.
constexpr double kMotionFactor = 2.0;

Aabb merged(const Aabb& a, const Aabb& b) {
  Aabb out = a;
  out.extend(b);
  return out;
}

/// Half the surface area; only compared, so the factor does not matter.
double halfArea(const Aabb& b) {
  const Vec3 e = b.max - b.min;
  return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
}

bool contains(const Aabb& outer, const Aabb& inner) {
  return (outer.min.array() <= inner.min.array()).all() &&
         (inner.max.array() <= outer.max.array()).all();
}

Aabb fattened(const Aabb& box, const Vec3& motion) {
  const double extent = (box.max - box.min).maxCoeff();
  const double margin = extent > 0.0 ? kFatFraction * extent : 0.0;
  Aabb fat;
  fat.min = box.min.array() - margin;
  fat.max = box.max.array() + margin;
  fat.min += motion.cwiseMin(0.0);
  fat.max += motion.cwiseMax(0.0);
  return fat;
}

}  // namespace

int DynamicAabbTree::allocate() {
  if (free_ == kNull) {
    nodes_.emplace_back();
    tight_.emplace_back();
    dirty_.push_back(0);
    return static_cast<int>(nodes_.size()) - 1;
  }
  const int n = free_;
  free_ = nodes_[n].parent;
  nodes_[n] = Node();
  return n;
}

void DynamicAabbTree::release(int node) {
  nodes_[node].parent = free_;
  nodes_[node].left = kNull;
  nodes_[node].right = kNull;
  nodes_[node].height = -1;  // marks a free node
  free_ = node;
}

int DynamicAabbTree::insert(const Aabb& box, int user) {
  const int n = allocate();
  tight_[n] = box;
  nodes_[n].fat = fattened(box, Vec3::Zero());
  nodes_[n].user = user;
  insertLeaf(n);
  markDirty(n);
  ++leaf_count_;
  return n;
}

void DynamicAabbTree::remove(int leaf) {
  detachLeaf(leaf);
  release(leaf);
  markDirty(leaf);  // its pairs go at the next pairs()
  --leaf_count_;
}

void DynamicAabbTree::markDirty(int leaf) {
  if (dirty_[leaf]) return;
  dirty_[leaf] = 1;
  dirty_list_.push_back(leaf);
}

bool DynamicAabbTree::move(int leaf, const Aabb& box) {
  Aabb& tight = tight_[leaf];
  if (contains(nodes_[leaf].fat, box)) {
    tight = box;
    return false;
  }
  const Vec3 motion = 0.5 * kMotionFactor * ((box.min + box.max) - (tight.min + tight.max));
  tight = box;
  nodes_[leaf].fat = fattened(box, motion);
  detachLeaf(leaf);
  insertLeaf(leaf);
  markDirty(leaf);
  return true;
}

void DynamicAabbTree::clear() {
  nodes_.clear();
  tight_.clear();
  dirty_.clear();
  dirty_list_.clear();
  pairs_.clear();
  pairs_valid_ = false;
  root_ = kNull;
  free_ = kNull;
  leaf_count_ = 0;
}

const std::vector<HandlePair>& DynamicAabbTree::pairs(double margin) {
  if (!pairs_valid_ || margin != pair_margin_) {
    // Everything is new: query every live leaf.
    pairs_.clear();
    for (int n = 0; n < static_cast<int>(nodes_.size()); ++n) {
      if (nodes_[n].height == 0) markDirty(n);
    }
    pair_margin_ = margin;
    pairs_valid_ = true;
  }
  // Pairs of untouched leaves still hold; those of touched leaves are found anew.
  pairs_.erase(std::remove_if(pairs_.begin(), pairs_.end(),
                              [this](const HandlePair& p) { return dirty_[p.lo] || dirty_[p.hi]; }),
               pairs_.end());
  fresh_.clear();
  for (int leaf : dirty_list_) {
    if (nodes_[leaf].height != 0) continue;  // removed
    query(nodes_[leaf].fat, margin, [&](int other) {
      if (nodes_[other].user == nodes_[leaf].user) return;
      fresh_.push_back(leaf < other ? HandlePair{leaf, other} : HandlePair{other, leaf});
    });
  }
  for (int leaf : dirty_list_) dirty_[leaf] = 0;
  dirty_list_.clear();
  std::sort(fresh_.begin(), fresh_.end());
  fresh_.erase(std::unique(fresh_.begin(), fresh_.end()), fresh_.end());
  merged_.clear();
  std::merge(pairs_.begin(), pairs_.end(), fresh_.begin(), fresh_.end(), std::back_inserter(merged_));
  pairs_.swap(merged_);
  return pairs_;
}

int DynamicAabbTree::pickSibling(const Aabb& box) const {
  int n = root_;
  while (!nodes_[n].leaf()) {
    const Node& node = nodes_[n];
    const double combined = halfArea(merged(node.fat, box));
    // Cost of a new parent here, and the growth every deeper choice pays as well.
    const double here = 2.0 * combined;
    const double inherited = 2.0 * (combined - halfArea(node.fat));
    auto cost = [&](int c) {
      const Node& child = nodes_[c];
      const double grown = halfArea(merged(child.fat, box));
      return (child.leaf() ? grown : grown - halfArea(child.fat)) + inherited;
    };
    const double left = cost(node.left);
    const double right = cost(node.right);
    if (here < left && here < right) break;
    n = left <= right ? node.left : node.right;
  }
  return n;
}

void DynamicAabbTree::insertLeaf(int leaf) {
  if (root_ == kNull) {
    root_ = leaf;
    nodes_[leaf].parent = kNull;
    return;
  }
  const int sibling = pickSibling(nodes_[leaf].fat);
  const int old_parent = nodes_[sibling].parent;
  const int p = allocate();  // may reallocate nodes_: no references held across it
  nodes_[p].parent = old_parent;
  nodes_[p].left = sibling;
  nodes_[p].right = leaf;
  nodes_[sibling].parent = p;
  nodes_[leaf].parent = p;
  if (old_parent == kNull) {
    root_ = p;
  } else if (nodes_[old_parent].left == sibling) {
    nodes_[old_parent].left = p;
  } else {
    nodes_[old_parent].right = p;
  }
  repairUpFrom(p);
}

void DynamicAabbTree::detachLeaf(int leaf) {
  if (leaf == root_) {
    root_ = kNull;
    return;
  }
  const int p = nodes_[leaf].parent;
  const int grand = nodes_[p].parent;
  const int sibling = nodes_[p].left == leaf ? nodes_[p].right : nodes_[p].left;
  nodes_[sibling].parent = grand;
  if (grand == kNull) {
    root_ = sibling;
  } else {
    if (nodes_[grand].left == p)
      nodes_[grand].left = sibling;
    else
      nodes_[grand].right = sibling;
  }
  release(p);
  nodes_[leaf].parent = kNull;
  if (grand != kNull) repairUpFrom(grand);
}

void DynamicAabbTree::repairUpFrom(int node) {
  while (node != kNull) {
    rotate(node);
    refit(node);
    node = nodes_[node].parent;
  }
}

void DynamicAabbTree::refit(int node) {
  Node& n = nodes_[node];
  const Node& l = nodes_[n.left];
  const Node& r = nodes_[n.right];
  n.fat = merged(l.fat, r.fat);
  n.height = 1 + std::max(l.height, r.height);
}

/// Swaps a child of `node` with a grandchild under its other child when that shrinks
/// the other child's box the most. Rotating by area rather than by height keeps
/// boxes tight (queries visit a third of the nodes they visit in a height-balanced
/// tree of moving boxes) and still unrolls the chains that sorted insertions build.
void DynamicAabbTree::rotate(int node) {
  const int b = nodes_[node].left;
  const int c = nodes_[node].right;
  if (nodes_[b].leaf() && nodes_[c].leaf()) return;
  double best_gain = 0.0;
  int child = kNull, grandchild = kNull;
  // Swapping `x` (a child) with a child of `y` (its sibling) leaves y = x + `rest`.
  auto consider = [&](int x, int y) {
    if (nodes_[y].leaf()) return;
    const double area = halfArea(nodes_[y].fat);
    const int f = nodes_[y].left;
    const int g = nodes_[y].right;
    const double gain_f = area - halfArea(merged(nodes_[x].fat, nodes_[g].fat));  // x <-> f
    const double gain_g = area - halfArea(merged(nodes_[x].fat, nodes_[f].fat));  // x <-> g
    for (const auto& [gain, swapped] : {std::make_pair(gain_f, f), std::make_pair(gain_g, g)}) {
      if (gain > best_gain) {
        best_gain = gain;
        child = x;
        grandchild = swapped;
      }
    }
  };
  consider(b, c);
  consider(c, b);
  if (child == kNull) return;
  const int other = nodes_[grandchild].parent;
  if (nodes_[node].left == child)
    nodes_[node].left = grandchild;
  else
    nodes_[node].right = grandchild;
  if (nodes_[other].left == grandchild)
    nodes_[other].left = child;
  else
    nodes_[other].right = child;
  nodes_[grandchild].parent = node;
  nodes_[child].parent = other;
  refit(other);
}

bool DynamicAabbTree::validNode(int node, int parent, int& leaves) const {
  if (node < 0 || node >= static_cast<int>(nodes_.size())) return false;
  const Node& n = nodes_[node];
  if (n.parent != parent || n.height < 0) return false;
  if (n.leaf()) {
    ++leaves;
    return n.right == kNull && n.height == 0 && contains(n.fat, tight_[node]);
  }
  if (!validNode(n.left, node, leaves) || !validNode(n.right, node, leaves)) return false;
  const Node& l = nodes_[n.left];
  const Node& r = nodes_[n.right];
  return n.height == 1 + std::max(l.height, r.height) && contains(n.fat, l.fat) &&
         contains(n.fat, r.fat);
}

bool DynamicAabbTree::valid() const {
  int leaves = 0;
  if (root_ != kNull && !validNode(root_, kNull, leaves)) return false;
  int free_count = 0;
  for (int n = free_; n != kNull; n = nodes_[n].parent) {
    if (nodes_[n].height != -1 || ++free_count > static_cast<int>(nodes_.size())) return false;
  }
  const int inner = leaves > 0 ? leaves - 1 : 0;
  return leaves == leaf_count_ &&
         leaves + inner + free_count == static_cast<int>(nodes_.size());
}

}  // namespace sc::detail
