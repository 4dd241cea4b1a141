// SPDX-License-Identifier: MIT
// Hull hierarchy (manual Fig. 6-14). Outline:
//  1. top-down: split the leaves at the median of their centres along the principal
//     axis of those centres (largest eigenvector of their covariance), so the tree is
//     balanced (depth ceil(log2 n)) whatever the shape;
//  2. bottom-up: an inner node's polytope is the hull of its descendants' points
//     (its children's polytopes, or theirs below a child without one), built by our
//     Quickhull (quick_hull.h), qhull where that declines, and a set qhull finds
//     flat is reduced to its 2-D hull in its plane. Up to kFewPoints points are
//     kept as a bare point set (the same hull; GJK scans it). A soup's nodes keep
//     no polytope at odd depths (HullLevels): on a curved surface each depth's
//     hulls hold about half of all the vertices again.
// Departure from SWIFT++'s bottom-up merging: the top-down median split costs
// O(n log n) and never degenerates; hulls are not simplified, so they are exact.
#include "preprocess/hull_bvh.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <memory>
#include <thread>
#include <utility>

#include "preprocess/convex_hull.h"
#include "preprocess/quick_hull.h"

namespace sc::detail {
namespace {

/// Inner nodes with at most this many distinct points keep a bare point set (the
/// same hull, without faces; GJK scans it).
constexpr int kFewPoints = 24;

/// Whether inner nodes at `depth` (root 0) may keep a hull. A node without one
/// costs the queries a sphere bound where GJK on its hull would have pruned: GJK
/// runs on the depth below instead.
bool keepsHullAt(int depth, HullLevels levels) {
  return levels == HullLevels::Every || depth % 2 == 0;
}

/// Unit eigenvectors of the covariance of `points[ids]`, largest eigenvalue last.
Mat3 principalAxes(const std::vector<Vec3>& points, const int* ids, int count) {
  Vec3 mean = Vec3::Zero();
  for (int k = 0; k < count; ++k) mean += points[ids[k]];
  mean /= static_cast<double>(count);
  Mat3 covariance = Mat3::Zero();
  for (int k = 0; k < count; ++k) {
    const Vec3 d = points[ids[k]] - mean;
    covariance += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(covariance);
  if (solver.info() != Eigen::Success) return Mat3::Identity();
  return solver.eigenvectors();
}

/// A polytope of bare points (no faces): GJK scans its vertices.
ConvexPolytope pointSet(PolytopeParts& parts) {
  parts.faces.clear();
  parts.face_source.clear();
  return ConvexPolytope::build(parts, PolytopeKeep::Support);
}

/// 2-D hull of points lying in a plane (within rounding): Andrew's monotone chain
/// in the plane of the two largest principal axes; strict corners only.
ConvexPolytope flatHull(const std::vector<Vec3>& points, const std::vector<int>& original) {
  std::vector<int> ids(points.size());
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<int>(i);
  const Mat3 axes = principalAxes(points, ids.data(), static_cast<int>(ids.size()));
  const Vec3 u = axes.col(2), v = axes.col(1);
  std::vector<std::pair<double, double>> planar(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) planar[i] = {u.dot(points[i]), v.dot(points[i])};
  std::sort(ids.begin(), ids.end(),
            [&](int a, int b) { return planar[a] != planar[b] ? planar[a] < planar[b] : a < b; });
  const auto cross = [&](int o, int a, int b) {
    return (planar[a].first - planar[o].first) * (planar[b].second - planar[o].second) -
           (planar[a].second - planar[o].second) * (planar[b].first - planar[o].first);
  };
  std::vector<int> chain(2 * ids.size() + 1);
  int k = 0;
  for (int i : ids) {  // lower chain
    while (k >= 2 && cross(chain[k - 2], chain[k - 1], i) <= 0.0) --k;
    chain[k++] = i;
  }
  const int lower = k + 1;
  for (auto it = ids.rbegin() + 1; it != ids.rend(); ++it) {  // upper chain
    while (k >= lower && cross(chain[k - 2], chain[k - 1], *it) <= 0.0) --k;
    chain[k++] = *it;
  }
  if (k > 1) --k;  // the last point repeats the first
  PolytopeParts kept;
  for (int m = 0; m < k; ++m) {
    kept.vertices.push_back(points[chain[m]]);
    kept.original.push_back(original[chain[m]]);
  }
  return pointSet(kept);
}

/// An inner node's polytope keeps only what queries read of it (PolytopeKeep::
/// Support): the traversal takes its support points (vertices, adjacency) and
/// bounds; the source of every face is -1 (virtual), which an absent face_source
/// also says, and the vertex-face lists serve the leaves' features only. Faces
/// stay: the cache file stores them and a load rebuilds the adjacency from them.

/// Inner nodes of one depth whose hulls are built by one thread.
constexpr int kMinNodesPerThread = 64;

class Builder {
 public:
  Builder(const std::vector<ConvexPolytope>& leaves, const ProgressCallback& progress, int threads,
          HullLevels levels)
      : leaves_(leaves),
        progress_(progress),
        threads_(std::max(1, threads)),
        levels_kept_(levels) {}

  HullBvh run() {
    const int n = static_cast<int>(leaves_.size());
    if (n == 0) return {};
    order_.resize(leaves_.size());
    centres_.reserve(leaves_.size());
    for (int i = 0; i < n; ++i) {
      order_[i] = i;
      centres_.push_back(leaves_[i].center);
    }
    bvh_.nodes.reserve(2 * leaves_.size() - 1);
    if (sparse())
      slots_.resize(leaves_.size() - 1);
    else
      bvh_.hulls.resize(leaves_.size() - 1);
    inner_total_ = n - 1;
    split(0, n, 0);
    // The split's arrays are done with: freed before the hulls, whose last levels
    // are the build's peak (28 bytes per leaf).
    std::vector<int>().swap(order_);
    std::vector<Vec3>().swap(centres_);
    buildHulls();
    if (sparse()) collectHulls();
    finishHullBvh(leaves_, bvh_);
    return std::move(bvh_);
  }

 private:
  /// Top-down: the nodes in pre-order, slots in post-order, inner nodes listed by
  /// depth for the bottom-up pass.
  int split(int begin, int end, int depth) {
    const int index = static_cast<int>(bvh_.nodes.size());
    bvh_.nodes.emplace_back();
    if (end - begin == 1) {
      bvh_.nodes[index].polytope = order_[begin];
      return index;
    }
    const Vec3 axis = principalAxes(centres_, order_.data() + begin, end - begin).col(2);
    const int mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](int a, int b) {
                       const double da = axis.dot(centres_[a]), db = axis.dot(centres_[b]);
                       return da != db ? da < db : a < b;
                     });
    const int left = split(begin, mid, depth + 1);
    const int right = split(mid, end, depth + 1);
    bvh_.nodes[index].left = left;
    bvh_.nodes[index].right = right;
    bvh_.nodes[index].polytope = next_slot_++;
    if (static_cast<int>(levels_.size()) <= depth) levels_.resize(depth + 1);
    levels_[depth].push_back(index);
    return index;
  }

  /// Bottom-up, one depth at a time: the hulls of one depth depend only on deeper
  /// ones, and each goes to its own slot, so threads do not change the result.
  void buildHulls() {
    for (int depth = static_cast<int>(levels_.size()) - 1; depth >= 0; --depth) {
      const std::vector<int>& nodes = levels_[depth];
      const int count = static_cast<int>(nodes.size());
      const int threads = std::min(threads_, std::max(1, count / kMinNodesPerThread));
      std::vector<std::thread> helpers;
      for (int i = 1; i < threads; ++i) {
        helpers.emplace_back(
            [this, &nodes, i, threads, depth] { buildNodes(nodes, depth, i, threads, false); });
      }
      buildNodes(nodes, depth, 0, threads, true);
      for (std::thread& helper : helpers) helper.join();
      reportProgress(true);
    }
  }

  /// Hulls of nodes[first], nodes[first + stride], ...; only the calling thread
  /// (`report`) reports progress.
  void buildNodes(const std::vector<int>& nodes, int depth, int first, int stride, bool report) {
    std::vector<Keyed> keyed;
    std::vector<int> stack;
    PolytopeParts parts;  // reused: its arrays keep their capacity
    QuickHullWorkspace work;
    for (std::size_t k = first; k < nodes.size(); k += stride) {
      const int index = nodes[k];
      if (keepsHullAt(depth, levels_kept_)) {
        std::unique_ptr<ConvexPolytope> hull = hullOf(index, keyed, stack, parts, work);
        const int slot = bvh_.nodes[index].polytope;
        if (sparse())
          slots_[slot] = std::move(hull);
        else
          bvh_.hulls[slot] = std::move(*hull);  // every node keeps one
      }
      ++inner_done_;
      if (report) reportProgress(false);
    }
  }

  /// The slots' hulls into bvh_.hulls in node order; inner nodes without one get -1.
  /// Their arrays move; each slot's object is freed as it moves.
  void collectHulls() {
    std::size_t kept = 0;
    for (const auto& slot : slots_) kept += slot ? 1 : 0;
    bvh_.hulls.reserve(kept);
    for (HullBvhNode& node : bvh_.nodes) {
      if (node.leaf()) continue;
      std::unique_ptr<ConvexPolytope>& slot = slots_[node.polytope];
      node.polytope = slot ? static_cast<int>(bvh_.hulls.size()) : -1;
      if (slot) bvh_.hulls.push_back(std::move(*slot));
      slot.reset();
    }
    std::vector<std::unique_ptr<ConvexPolytope>>().swap(slots_);
  }

  /// Whether some inner nodes may keep no hull. Their hulls then go to slots of
  /// their own and are gathered at the end: an array of n - 1 polytopes would cost
  /// a polytope object per inner node. Otherwise bvh_.hulls is that array.
  bool sparse() const { return levels_kept_ != HullLevels::Every; }

  /// The polytope of `node` while building: a leaf's, or its slot's (null if none).
  const ConvexPolytope* polytopeOf(int node) const {
    const HullBvhNode& n = bvh_.nodes[node];
    if (n.leaf()) return &leaves_[n.polytope];
    return sparse() ? slots_[n.polytope].get() : &bvh_.hulls[n.polytope];
  }

  struct Keyed {
    int original;
    const Vec3* point;
  };

  /// Hull of the node's descendants' vertices, each input vertex once: its
  /// children's polytopes, or those below a child without one.
  std::unique_ptr<ConvexPolytope> hullOf(int index, std::vector<Keyed>& keyed,
                                         std::vector<int>& stack, PolytopeParts& parts,
                                         QuickHullWorkspace& work) const {
    keyed.clear();
    stack.assign({bvh_.nodes[index].right, bvh_.nodes[index].left});
    while (!stack.empty()) {
      const int node = stack.back();
      stack.pop_back();
      const ConvexPolytope* p = polytopeOf(node);
      if (p == nullptr) {
        stack.push_back(bvh_.nodes[node].right);
        stack.push_back(bvh_.nodes[node].left);
        continue;
      }
      for (std::size_t i = 0; i < p->vertices.size(); ++i) {
        const int id = i < p->original.size() ? p->original[i] : -1;
        keyed.push_back({id, &p->vertices[i]});
      }
    }
    // Shared input vertices once: same original index and the same point.
    std::stable_sort(keyed.begin(), keyed.end(),
                     [](const Keyed& a, const Keyed& b) { return a.original < b.original; });
    std::vector<Vec3>& points = parts.vertices;
    std::vector<int>& original = parts.original;
    points.clear();
    original.clear();
    for (std::size_t k = 0; k < keyed.size(); ++k) {
      if (k > 0 && keyed[k].original == keyed[k - 1].original &&
          *keyed[k].point == *keyed[k - 1].point)
        continue;
      points.push_back(*keyed[k].point);
      original.push_back(keyed[k].original);
    }
    auto out = std::make_unique<ConvexPolytope>();
    if (points.size() <= static_cast<std::size_t>(kFewPoints)) {
      *out = pointSet(parts);
      return out;
    }
    if (quickHull(points, original, work, *out, PolytopeKeep::Support)) return out;
    Result<ConvexPolytope> hull = convexHull(points, original);
    *out = hull.ok() ? hull.value().reduced(PolytopeKeep::Support) : flatHull(points, original);
    return out;
  }

  void reportProgress(bool level_done) {
    if (!progress_) return;
    const int done = inner_done_;
    const double fraction = static_cast<double>(done) / inner_total_;
    const bool last = level_done && done == inner_total_;
    if (fraction - reported_ < 0.01 && !last) return;
    if (fraction <= reported_) return;
    reported_ = fraction;
    progress_(fraction, "hierarchy");
  }

  const std::vector<ConvexPolytope>& leaves_;
  const ProgressCallback& progress_;
  const int threads_;
  const HullLevels levels_kept_;
  std::vector<int> order_;
  std::vector<Vec3> centres_;
  std::vector<std::vector<int>> levels_;  ///< inner nodes per depth
  /// Per inner node (its polytope field while building): its hull, or null.
  std::vector<std::unique_ptr<ConvexPolytope>> slots_;
  HullBvh bvh_;
  int next_slot_ = 0;
  int inner_total_ = 0;
  std::atomic<int> inner_done_{0};
  double reported_ = 0.0;
};

}  // namespace

HullBvh buildHullBvh(const std::vector<ConvexPolytope>& leaves, const ProgressCallback& progress,
                     int threads, HullLevels levels) {
  return Builder(leaves, progress, threads, levels).run();
}

namespace {

/// The polytopes nearest below inner node `index` (its children, or below a child
/// without one), each passed to `visit`.
template <class Visit>
void forEachPolytopeBelow(const std::vector<ConvexPolytope>& leaves, const HullBvh& bvh, int index,
                          std::vector<int>& stack, Visit&& visit) {
  stack.assign({bvh.nodes[index].right, bvh.nodes[index].left});
  while (!stack.empty()) {
    const HullBvhNode& node = bvh.nodes[stack.back()];
    stack.pop_back();
    if (node.hasPolytope()) {
      visit(bvh.polytope(leaves, static_cast<int>(&node - bvh.nodes.data())));
    } else {
      stack.push_back(node.right);
      stack.push_back(node.left);
    }
  }
}

/// The bounding sphere a hull of the node's descendants would get (finalize():
/// centre of the box, farthest vertex), from the polytopes below it.
void sphereBelow(const std::vector<ConvexPolytope>& leaves, const HullBvh& bvh, int index,
                 std::vector<int>& stack, HullBvhNode& out) {
  Aabb box;
  forEachPolytopeBelow(leaves, bvh, index, stack,
                       [&](const ConvexPolytope& p) { box.extend(p.bounds()); });
  const Vec3 center = 0.5 * (box.min + box.max);
  double radius2 = 0.0;
  forEachPolytopeBelow(leaves, bvh, index, stack, [&](const ConvexPolytope& p) {
    const double reach = (p.center - center).norm() + p.radius;
    if (reach * reach < radius2 * (1.0 - 1e-12)) return;  // no vertex of p is farther
    for (const Vec3& v : p.vertices) radius2 = std::max(radius2, (v - center).squaredNorm());
  });
  out.center = center;
  out.radius = std::sqrt(radius2);
}

/// The tree's structure: a binary tree rooted at 0 reaching every node once, each
/// leaf index and each hull once. Fills leaf_node and depth; false when invalid.
bool checkStructure(const HullBvh& bvh, int leaf_count, std::vector<int>& leaf_node, int& depth) {
  const int node_count = static_cast<int>(bvh.nodes.size());
  const int hull_count = static_cast<int>(bvh.hulls.size());
  leaf_node.assign(static_cast<std::size_t>(leaf_count), -1);
  std::vector<char> node_seen(bvh.nodes.size(), 0), hull_seen(bvh.hulls.size(), 0);
  std::vector<std::pair<int, int>> stack = {{0, 0}};  // node, depth
  int hulls_seen = 0;
  depth = 0;
  node_seen[0] = 1;
  while (!stack.empty()) {
    const auto [index, level] = stack.back();
    stack.pop_back();
    depth = std::max(depth, level);
    const HullBvhNode& node = bvh.nodes[index];
    if (node.leaf()) {
      if (node.right >= 0 || node.polytope < 0 || node.polytope >= leaf_count ||
          leaf_node[node.polytope] >= 0)
        return false;
      leaf_node[node.polytope] = index;
      continue;
    }
    if (node.polytope < -1 || node.polytope >= hull_count) return false;
    if (node.polytope >= 0) {
      if (hull_seen[node.polytope]) return false;
      hull_seen[node.polytope] = 1;
      ++hulls_seen;
    }
    for (const int child : {node.left, node.right}) {
      if (child <= 0 || child >= node_count || node_seen[child]) return false;
      node_seen[child] = 1;
      stack.emplace_back(child, level + 1);
    }
  }
  // With 2n - 1 nodes all reached, the n leaves are each used once.
  return hulls_seen == hull_count &&
         std::find(node_seen.begin(), node_seen.end(), 0) == node_seen.end();
}

}  // namespace

bool finishHullBvh(const std::vector<ConvexPolytope>& leaves, HullBvh& bvh) {
  const int node_count = static_cast<int>(bvh.nodes.size());
  const int leaf_count = static_cast<int>(leaves.size());
  const int hull_count = static_cast<int>(bvh.hulls.size());
  if (leaf_count == 0) return node_count == 0 && hull_count == 0;
  if (node_count != 2 * leaf_count - 1 || hull_count > leaf_count - 1) return false;
  std::vector<int> leaf_node;
  int depth = 0;
  if (!checkStructure(bvh, leaf_count, leaf_node, depth)) return false;
  std::vector<int> stack;
  for (int i = 0; i < node_count; ++i) {
    HullBvhNode& node = bvh.nodes[i];
    if (!node.hasPolytope()) {
      sphereBelow(leaves, bvh, i, stack, node);
      continue;
    }
    const ConvexPolytope& p = bvh.polytope(leaves, i);
    node.center = p.center;
    node.radius = p.radius;
  }
  bvh.leaf_node = std::move(leaf_node);
  bvh.depth = depth;
  return true;
}

}  // namespace sc::detail
