// SPDX-License-Identifier: MIT
// Best-first traversal of two groups' hull hierarchies. Outline (design.md §3):
//  1. the queue starts with the root pair of every (target piece, opponent piece),
//     bounded below by their bounding spheres;
//  2. pop the pair with the smallest lower bound; stop once the policy prunes it
//     (farther than the best so far or than the query's reach);
//  3. an inner pair first gets an exact lower bound: GJK on the two node hulls,
//     warm-started per node pair, stopped as soon as it proves the pair pruned;
//     if other pairs are now nearer it goes back to the queue;
//  4. then the larger node is split; children inherit the parent's bound (their
//     hulls lie inside it) or their spheres' bound if higher;
//  5. leaf pairs are final: GJK on the leaf polytopes, handed to the policy.
// Coherence: distance() first evaluates the last call's closest leaf pair, so the
// traversal starts with a tight bound; and contacts, intersects and translationToi
// answer without traversal when the last distance, less the most any target point
// has moved since, already decides them.
#include "query/group_pair_query.h"

#include <algorithm>
#include <cmath>

#include "geometry/math_util.h"
#include "geometry/triangle_distance.h"
#include "query/features.h"

namespace sc::detail {

namespace {

constexpr int kMaxAdvanceSteps = 64;
/// The remembered distance is trusted to this relative accuracy (GJK's is ~1e-12).
constexpr double kKnownGapMargin = 1e-9;

bool realFaceHolds(const ConvexPolytope& poly, int f, const Vec3& local, double tolerance) {
  if (f >= static_cast<int>(poly.face_source.size()) || poly.face_source[f] < 0) return false;
  const Tri& t = poly.faces[f];
  const Vec3 corners[3] = {poly.vertices[t[0]], poly.vertices[t[1]], poly.vertices[t[2]]};
  return pointTriangleDistance(local, corners) <= tolerance;
}

/// A real face of the polytope (placed by `frame_from_poly`) that `point` (frame)
/// lies on within featureTolerance, or -1. The faces around GJK's simplex vertices
/// (`simplex`, `count`) hold it almost always; all faces are scanned otherwise.
int realFaceAt(const ConvexPolytope& poly, const Rigid& frame_from_poly, const Vec3& point,
               const int* simplex, int count) {
  const Vec3 local = frame_from_poly.inverse() * point;
  const double tolerance = featureTolerance(poly);
  const int n = static_cast<int>(poly.vertices.size());
  for (int i = 0; i < count && static_cast<int>(poly.vertex_face_start.size()) == n + 1; ++i) {
    if (simplex[i] < 0 || simplex[i] >= n) continue;
    for (int k = poly.vertex_face_start[simplex[i]]; k < poly.vertex_face_start[simplex[i] + 1];
         ++k)
      if (realFaceHolds(poly, poly.vertex_faces[k], local, tolerance)) return poly.vertex_faces[k];
  }
  for (int f = 0; f < static_cast<int>(poly.faces.size()); ++f)
    if (realFaceHolds(poly, f, local, tolerance)) return f;
  return -1;
}

/// Seeds the feature search (features.h) of each side with the corners of the real
/// face holding its closest point: GJK's vertices may be the far ends of a straight
/// run of collinear vertices, which misses the short edge the point is on.
void seedWithFaces(const Tri& t_face, const Tri& o_face, LeafContact& c) {
  c.simplex_count = 3;
  for (int k = 0; k < 3; ++k) {
    c.simplex_t[k] = t_face[k];
    c.simplex_o[k] = o_face[k];
  }
  c.simplex_t[3] = c.simplex_o[3] = -1;
}

Rigid translated(const Rigid& x, const Vec3& delta) { return {x.rotation, x.translation + delta}; }

/// Heap order: the smallest bound on top.
struct Farther {
  template <class P>
  bool operator()(const P& a, const P& b) const {
    return a.bound > b.bound;
  }
};

}  // namespace

// ---------------------------------------------------------------------------
// Binding

void GroupPairQuery::collectSlots(const GroupView& group, std::vector<Slot>& out, int& leaf_count) {
  out.clear();
  int leaves = 0, nodes = 0;
  for (int p = 0; p < group.part_count; ++p) {
    const Part& part = group.parts[p];
    if (part.model == nullptr) continue;
    const auto& pieces = part.model->pieces();
    for (int k = 0; k < static_cast<int>(pieces.size()); ++k) {
      const PieceData& data = pieces[k]->internals();
      if (data.patches.empty() || data.hierarchy.nodes.empty()) continue;
      Slot slot;
      slot.data = &data;
      slot.group_from_piece = part.group_from_model;
      slot.part = p;
      slot.piece = k;
      slot.first_leaf = leaves;
      slot.first_node = nodes;
      leaves += static_cast<int>(data.patches.size());
      nodes += static_cast<int>(data.hierarchy.nodes.size());
      out.push_back(slot);
    }
  }
  leaf_count = leaves;
}

bool GroupPairQuery::sameSlots(const std::vector<Slot>& a, const std::vector<Slot>& b,
                               bool& moved) {
  moved = false;
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].data != b[i].data || a[i].part != b[i].part || a[i].piece != b[i].piece) return false;
    moved = moved || a[i].group_from_piece.rotation != b[i].group_from_piece.rotation ||
            a[i].group_from_piece.translation != b[i].group_from_piece.translation;
  }
  return true;
}

void GroupPairQuery::bind(const GroupView& target, const GroupView& opponent) {
  bool t_moved = false, o_moved = false;
  int count = 0;
  collectSlots(target, scratch_slots_, count);
  const bool t_same = sameSlots(scratch_slots_, t_slots_, t_moved);
  t_slots_.swap(scratch_slots_);
  t_leaf_count_ = count;
  collectSlots(opponent, scratch_slots_, count);
  const bool o_same = sameSlots(scratch_slots_, o_slots_, o_moved);
  o_slots_.swap(scratch_slots_);
  o_leaf_count_ = count;
  // Warm starts are keyed by node index: drop them when the pieces change.
  if (!t_same || !o_same) {
    caches_.clear();
    seed_ = LeafPair();
  }
  if (!t_same || !o_same || t_moved || o_moved) known_ = near_valid_ = pending_.active = false;
  if (!t_same || t_moved) {
    updateGroupSphere();
    t_leaves_valid_ = false;
  }
  if (!o_same || o_moved) o_leaves_valid_ = false;
}

namespace {

template <class Slots, class LeafAt>
void listLeaves(const Slots& slots, int count, LeafAt&& leaf_at, std::vector<Leaf>& out) {
  out.clear();
  if (slots.empty()) return;
  out.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) out.push_back(leaf_at(i));
}

}  // namespace

const std::vector<Leaf>& GroupPairQuery::targetLeaves() const {
  if (!t_leaves_valid_) {
    listLeaves(
        t_slots_, t_leaf_count_, [this](int i) { return targetLeaf(i); }, t_leaves_);
    t_leaves_valid_ = true;
  }
  return t_leaves_;
}

const std::vector<Leaf>& GroupPairQuery::opponentLeaves() const {
  if (!o_leaves_valid_) {
    listLeaves(
        o_slots_, o_leaf_count_, [this](int i) { return opponentLeaf(i); }, o_leaves_);
    o_leaves_valid_ = true;
  }
  return o_leaves_;
}

void GroupPairQuery::updateGroupSphere() {
  // A sphere around the pieces' root spheres: centre at their box's centre.
  Aabb box;
  for (const Slot& s : t_slots_) {
    const HullBvhNode& root = s.data->hierarchy.nodes[0];
    const Vec3 c = s.group_from_piece * root.center;
    box.extend(Aabb{c - Vec3::Constant(root.radius), c + Vec3::Constant(root.radius)});
  }
  t_center_ = box.empty() ? Vec3::Zero() : Vec3(0.5 * (box.min + box.max));
  t_radius_ = 0.0;
  for (const Slot& s : t_slots_) {
    const HullBvhNode& root = s.data->hierarchy.nodes[0];
    t_radius_ =
        std::max(t_radius_, (s.group_from_piece * root.center - t_center_).norm() + root.radius);
  }
}

int GroupPairQuery::slotOf(const std::vector<Slot>& slots, int leaf) {
  const auto it = std::upper_bound(slots.begin(), slots.end(), leaf,
                                   [](int l, const Slot& s) { return l < s.first_leaf; });
  return static_cast<int>(it - slots.begin()) - 1;
}

Leaf GroupPairQuery::leafOf(const std::vector<Slot>& slots, int leaf) {
  const Slot& slot = slots[slotOf(slots, leaf)];
  Leaf out;
  out.poly = &slot.data->patches[leaf - slot.first_leaf];
  out.group_from_leaf = slot.group_from_piece;
  out.part = slot.part;
  out.piece = slot.piece;
  out.center = slot.group_from_piece * out.poly->center;
  out.radius = out.poly->radius;
  return out;
}

// ---------------------------------------------------------------------------
// Node pairs

SimplexCache& GroupPairQuery::cacheOf(const NodePair& p) {
  const auto t = static_cast<std::uint32_t>(t_slots_[p.t_slot].first_node + p.t_node);
  const auto o = static_cast<std::uint32_t>(o_slots_[p.o_slot].first_node + p.o_node);
  return caches_.at(static_cast<std::uint64_t>(t) << 32 | o);
}

void GroupPairQuery::placeTargets(const Rigid& o_from_t) {
  o_from_piece_.resize(t_slots_.size());
  for (std::size_t i = 0; i < t_slots_.size(); ++i)
    o_from_piece_[i] = o_from_t * t_slots_[i].group_from_piece;
}

double GroupPairQuery::sphereBound(const NodePair& p) const {
  const HullBvhNode& t = t_slots_[p.t_slot].data->hierarchy.nodes[p.t_node];
  const Slot& os = o_slots_[p.o_slot];
  const HullBvhNode& o = os.data->hierarchy.nodes[p.o_node];
  const Vec3 tc = o_from_piece_[p.t_slot] * t.center;
  const Vec3 oc = os.group_from_piece * o.center;
  return (tc - oc).norm() - t.radius - o.radius;
}

GjkResult GroupPairQuery::nodeGjk(const NodePair& p, double max_distance, double within_distance) {
  GjkSettings settings;
  settings.max_distance = max_distance;
  settings.within_distance = within_distance;
  return nodeGjkAt(p, o_from_piece_[p.t_slot], settings, cacheOf(p));
}

GjkResult GroupPairQuery::nodeGjkAt(const NodePair& p, const Rigid& o_from_piece,
                                    const GjkSettings& settings, SimplexCache& cache) {
  ++counters_.node_gjk;
  const Slot& os = o_slots_[p.o_slot];
  return gjkDistance(polytopeOf(t_slots_[p.t_slot], p.t_node), o_from_piece,
                     polytopeOf(os, p.o_node), os.group_from_piece, settings, cache);
}

double GroupPairQuery::nodeLowerBound(const NodePair& p, double max_distance,
                                      double within_distance) {
  const GjkResult r = nodeGjk(p, max_distance, within_distance);
  return r.status == GjkStatus::Intersecting ? 0.0 : r.lower_bound;
}

LeafContact GroupPairQuery::evaluate(const NodePair& p, const Rigid& o_from_piece,
                                     double max_distance, bool& beyond, SimplexCache* cache) {
  ++counters_.leaf_gjk;
  const Slot& ts = t_slots_[p.t_slot];
  const Slot& os = o_slots_[p.o_slot];
  const HullBvhNode& tn = ts.data->hierarchy.nodes[p.t_node];
  const HullBvhNode& on = os.data->hierarchy.nodes[p.o_node];
  GjkSettings settings;
  settings.max_distance = max_distance;
  const GjkResult r =
      gjkDistance(ts.data->patches[tn.polytope], o_from_piece, os.data->patches[on.polytope],
                  os.group_from_piece, settings, cache != nullptr ? *cache : cacheOf(p));
  LeafContact c;
  c.t_leaf = ts.first_leaf + tn.polytope;
  c.o_leaf = os.first_leaf + on.polytope;
  beyond = r.status == GjkStatus::BeyondMaxDistance;
  c.intersecting = r.status == GjkStatus::Intersecting;
  c.gap = c.intersecting ? 0.0 : (beyond ? r.lower_bound : r.distance);
  c.normal = r.normal;
  c.point_t = r.point_a;
  c.point_o = r.point_b;
  c.simplex_count = r.count;
  for (int i = 0; i < 4; ++i) {
    c.simplex_t[i] = r.a[i];
    c.simplex_o[i] = r.b[i];
  }
  return c;
}

GroupPairQuery::NodePair GroupPairQuery::leafPair(int t_leaf, int o_leaf) const {
  NodePair p;
  p.t_slot = slotOf(t_slots_, t_leaf);
  p.o_slot = slotOf(o_slots_, o_leaf);
  const Slot& ts = t_slots_[p.t_slot];
  const Slot& os = o_slots_[p.o_slot];
  p.t_node = ts.data->hierarchy.leaf_node[t_leaf - ts.first_leaf];
  p.o_node = os.data->hierarchy.leaf_node[o_leaf - os.first_leaf];
  return p;
}

namespace {

/// The real faces of `poly` in the frame `frame_from_poly` places it in.
template <class Face>
void placeRealFaces(const ConvexPolytope& poly, const Rigid& frame_from_poly,
                    std::vector<Face>& out) {
  out.clear();
  for (std::size_t f = 0; f < poly.faces.size(); ++f) {
    if (f >= poly.face_source.size() || poly.face_source[f] < 0) continue;
    Face face;
    for (int k = 0; k < 3; ++k) face.corners[k] = frame_from_poly * poly.vertices[poly.faces[f][k]];
    face.center = (face.corners[0] + face.corners[1] + face.corners[2]) / 3.0;
    for (const Vec3& v : face.corners)
      face.radius = std::max(face.radius, (v - face.center).norm());
    face.face = static_cast<int>(f);
    out.push_back(face);
  }
}

}  // namespace

bool GroupPairQuery::refine(const NodePair& p, const Rigid& o_from_piece, double bound,
                            LeafContact& c) {
  ++counters_.refined;
  const Slot& ts = t_slots_[p.t_slot];
  const Slot& os = o_slots_[p.o_slot];
  const ConvexPolytope& pt = polytopeOf(ts, p.t_node);
  const ConvexPolytope& po = polytopeOf(os, p.o_node);
  placeRealFaces(pt, o_from_piece, faces_t_);
  placeRealFaces(po, os.group_from_piece, faces_o_);
  double best = bound;
  int best_t = -1, best_o = -1;
  TriangleDistance best_d;
  for (int i = 0; i < static_cast<int>(faces_t_.size()); ++i) {
    const PlacedFace& ft = faces_t_[i];
    for (int j = 0; j < static_cast<int>(faces_o_.size()); ++j) {
      const PlacedFace& fo = faces_o_[j];
      if ((ft.center - fo.center).norm() - ft.radius - fo.radius >= best) continue;
      const TriangleDistance d = triangleDistance(ft.corners, fo.corners);
      if (d.distance < best) {
        best = d.distance;
        best_d = d;
        best_t = i;
        best_o = j;
      }
    }
  }
  if (best_t < 0) return false;
  c.gap = best_d.distance;
  c.point_t = best_d.point_a;
  c.point_o = best_d.point_b;
  c.normal = normalizedOr(best_d.point_a - best_d.point_b, c.normal);
  seedWithFaces(pt.faces[faces_t_[best_t].face], po.faces[faces_o_[best_o].face], c);
  return true;
}

LeafContact GroupPairQuery::exactLeafDistance(const NodePair& p, double bound, bool& beyond) {
  const Rigid& o_from_piece = o_from_piece_[p.t_slot];
  LeafContact c = evaluate(p, o_from_piece, bound, beyond);
  if (beyond || c.intersecting || c.gap >= bound) return c;
  const Slot& os = o_slots_[p.o_slot];
  const ConvexPolytope& pt = polytopeOf(t_slots_[p.t_slot], p.t_node);
  const ConvexPolytope& po = polytopeOf(os, p.o_node);
  const int t_face = realFaceAt(pt, o_from_piece, c.point_t, c.simplex_t, c.simplex_count);
  const int o_face =
      t_face < 0 ? -1
                 : realFaceAt(po, os.group_from_piece, c.point_o, c.simplex_o, c.simplex_count);
  if (o_face >= 0) {
    seedWithFaces(pt.faces[t_face], po.faces[o_face], c);
    return c;
  }
  // A point off the surface (on a virtual feature): the real triangles decide, and
  // they can only be farther (they lie in the hull).
  beyond = !refine(p, o_from_piece, bound, c);
  return c;
}

// A policy says which bounds are pruned (`prunes`, monotone in the bound), how far
// GJK on a node pair needs to look (`reach`), may veto a child pair (`admits`),
// and takes leaf pairs (`visit`, false to stop).
template <class Policy>
void GroupPairQuery::traverse(Policy& policy) {
  seedTraversal(policy, heap_);
  runTraversal(policy, heap_, -1);
}

template <class Policy>
void GroupPairQuery::seedTraversal(Policy& policy, std::vector<NodePair>& heap) {
  heap.clear();
  for (int ts = 0; ts < static_cast<int>(t_slots_.size()); ++ts) {
    for (int os = 0; os < static_cast<int>(o_slots_.size()); ++os) {
      NodePair root;
      root.t_slot = ts;
      root.o_slot = os;
      root.bound = std::max(0.0, sphereBound(root));
      if (policy.prunes(root.bound) || !policy.admits(root)) continue;
      heap.push_back(root);
      std::push_heap(heap.begin(), heap.end(), Farther());
    }
  }
}

template <class Policy>
bool GroupPairQuery::runTraversal(Policy& policy, std::vector<NodePair>& heap, int budget,
                                  double until) {
  for (int taken = 0; !heap.empty(); ++taken) {
    if (budget >= 0 && taken >= budget) return false;
    if (policy.full()) return false;  // the queue kept: its front bounds what is missing
    const double front = heap.front().bound;
    if (front >= until && !policy.prunes(front)) return false;
    std::pop_heap(heap.begin(), heap.end(), Farther());
    NodePair p = heap.back();
    heap.pop_back();
    if (policy.prunes(p.bound)) break;  // every pair left is at least as far
    ++counters_.node_pairs;
    const HullBvhNode& tn = t_slots_[p.t_slot].data->hierarchy.nodes[p.t_node];
    const HullBvhNode& on = o_slots_[p.o_slot].data->hierarchy.nodes[p.o_node];
    if (tn.leaf() && on.leaf()) {
      if (!policy.visit(p)) break;
      continue;
    }
    if (!p.refined) {
      p.bound = std::max(p.bound, nodeLowerBound(p, policy.reach(), policy.splitWithin()));
      p.refined = true;
      if (policy.prunes(p.bound)) continue;
      if (!heap.empty() && p.bound > heap.front().bound) {
        heap.push_back(p);
        std::push_heap(heap.begin(), heap.end(), Farther());
        continue;
      }
    }
    const bool split_t = on.leaf() || (!tn.leaf() && tn.radius >= on.radius);
    const HullBvhNode& split = split_t ? tn : on;
    for (const int child : {split.left, split.right}) {
      NodePair c = p;
      (split_t ? c.t_node : c.o_node) = child;
      c.refined = false;
      c.bound = std::max(p.bound, sphereBound(c));
      if (policy.prunes(c.bound) || !policy.admits(c)) continue;
      heap.push_back(c);
      std::push_heap(heap.begin(), heap.end(), Farther());
    }
  }
  heap.clear();
  return true;
}

double GroupPairQuery::displacementBound(const Rigid& from, const Rigid& to) const {
  // A target point p = c + q (|q| <= radius) moves by at most
  // |(X - K) c| + ||R_X - R_K|| radius; the Frobenius norm bounds the spectral one.
  const double centre_shift = (to * t_center_ - from * t_center_).norm();
  const double spin = (to.rotation - from.rotation).norm();
  return centre_shift + spin * t_radius_;
}

double GroupPairQuery::knownLowerBound(const Rigid& o_from_t) const {
  if (!known_) return -kInfinity;
  return known_gap_ - displacementBound(known_pose_, o_from_t);
}

// ---------------------------------------------------------------------------
// Distance

struct GroupPairQuery::DistancePolicy {
  GroupPairQuery& q;
  double max_distance;
  LeafContact& best;
  bool found = false;

  bool prunes(double bound) const { return found ? bound >= best.gap : bound > max_distance; }
  double reach() const { return found ? best.gap : max_distance; }
  double splitWithin() const { return -1.0; }  // the order needs tight bounds
  bool full() const { return false; }
  bool admits(const NodePair&) const { return true; }
  void offer(const LeafContact& c) {
    if (found && c.gap >= best.gap) return;
    best = c;
    found = true;
  }
  bool visit(const NodePair& p) {
    const Slot& ts = q.t_slots_[p.t_slot];
    const Slot& os = q.o_slots_[p.o_slot];
    const int t_leaf = ts.first_leaf + ts.data->hierarchy.nodes[p.t_node].polytope;
    const int o_leaf = os.first_leaf + os.data->hierarchy.nodes[p.o_node].polytope;
    if (t_leaf == q.seed_.t_leaf && o_leaf == q.seed_.o_leaf) return true;  // done first
    bool beyond = false;
    const LeafContact c = q.exactLeafDistance(p, reach(), beyond);
    if (!beyond) offer(c);
    return !(found && best.intersecting);
  }
};

bool GroupPairQuery::distance(const Rigid& o_from_t, double max_distance, LeafContact& best) {
  counters_ = TraversalCounters();
  placeTargets(o_from_t);
  DistancePolicy policy{*this, max_distance, best};
  if (seed_.t_leaf >= 0 && seed_.t_leaf < t_leaf_count_ && seed_.o_leaf < o_leaf_count_) {
    bool beyond = false;
    const LeafContact c =
        exactLeafDistance(leafPair(seed_.t_leaf, seed_.o_leaf), max_distance, beyond);
    if (!beyond) policy.offer(c);
  }
  if (!(policy.found && best.intersecting)) traverse(policy);
  if (policy.found) seed_ = {best.t_leaf, best.o_leaf};
  known_ = true;
  known_pose_ = o_from_t;
  known_gap_ = (policy.found ? best.gap : max_distance) * (1.0 - kKnownGapMargin);
  return policy.found;
}

// ---------------------------------------------------------------------------
// Contacts and intersection

struct GroupPairQuery::ContactsPolicy {
  GroupPairQuery& q;
  double threshold;
  std::vector<LeafContact>& out;

  bool prunes(double bound) const { return bound > threshold; }
  double reach() const { return threshold; }
  /// Every pair within the threshold is visited, in any order: a node pair known to
  /// be within it is split without its exact distance.
  double splitWithin() const { return threshold; }
  /// At kMaxContacts the traversal stops with its queue kept: what it found includes
  /// every pair nearer than the queue front's lower bound.
  bool full() const { return out.size() >= kMaxContacts; }
  bool admits(const NodePair&) const { return true; }
  bool visit(const NodePair& p) {
    bool beyond = false;
    const LeafContact c = q.evaluate(p, q.o_from_piece_[p.t_slot], threshold, beyond);
    if (!beyond && c.gap <= threshold) out.push_back(c);
    return true;
  }
};

namespace {

/// Nearest first, ties by leaf indices: one order whatever found the contacts.
void sortContacts(std::vector<LeafContact>& contacts) {
  std::sort(contacts.begin(), contacts.end(), [](const LeafContact& a, const LeafContact& b) {
    if (a.gap != b.gap) return a.gap < b.gap;
    return LeafPair{a.t_leaf, a.o_leaf} < LeafPair{b.t_leaf, b.o_leaf};
  });
}

}  // namespace

void GroupPairQuery::contacts(const Rigid& o_from_t, double threshold,
                              std::vector<LeafContact>& out) {
  out.clear();
  counters_ = TraversalCounters();
  if (knownLowerBound(o_from_t) > threshold) {
    counters_.shortcut = true;
    return;
  }
  placeTargets(o_from_t);
  ContactsPolicy policy{*this, threshold, out};
  traverse(policy);
  sortContacts(out);
}

double GroupPairQuery::nearCoveredReach(const Rigid& o_from_t) const {
  // The last distance bounds every pair from below: an answer is complete up to that
  // too (an empty one from contactsNear's shortcut, in particular).
  const double near = near_valid_ ? near_reach_ - displacementBound(near_pose_, o_from_t) : 0.0;
  return std::max(near, knownLowerBound(o_from_t));
}

bool GroupPairQuery::nearCovers(const Rigid& o_from_t, double reach) const {
  // Gaps are 1-Lipschitz in the target's point displacements: a small turn (a resting
  // body nudged by a solver) keeps the pairs as a small translation does.
  return near_valid_ && displacementBound(near_pose_, o_from_t) + reach <= near_reach_;
}

void GroupPairQuery::contactsNear(const Rigid& o_from_t, double threshold, double margin,
                                  std::vector<LeafContact>& out) {
  // Every pair is farther than the threshold by the last distance, less the motion
  // since (a free proxy): nothing to gather, and no near pairs to keep or rebuild.
  if (knownLowerBound(o_from_t) > threshold) {
    out.clear();
    counters_ = TraversalCounters();
    counters_.shortcut = true;
    return;
  }
  // The same pose and threshold as the last call (a slide that did not move, then the
  // depth's projection at the same proxy): its answer, without the GJK calls.
  if (near_valid_ && memo_valid_ && threshold == memo_threshold_ &&
      o_from_t.rotation == memo_pose_.rotation && o_from_t.translation == memo_pose_.translation) {
    counters_ = TraversalCounters();
    out = memo_out_;
    return;
  }
  contactsNearUncached(o_from_t, threshold, margin, out);
  // The nearest pair seeds the next distance(): a proxy leaving contact measures its
  // distance next to where it touched, not where it was last seen apart.
  if (!out.empty()) seed_ = {out.front().t_leaf, out.front().o_leaf};
  memo_valid_ = true;
  memo_pose_ = o_from_t;
  memo_threshold_ = threshold;
  memo_out_ = out;
}

void GroupPairQuery::contactsNearUncached(const Rigid& o_from_t, double threshold, double margin,
                                          std::vector<LeafContact>& out) {
  out.clear();
  // The kept pairs no longer cover this pose: what is left of a rebuild started
  // ahead is cheaper than a new one, when that still covers it.
  const bool due = !nearCovers(o_from_t, threshold);
  const TraversalCounters ahead = advancePendingNear(o_from_t, threshold, due);
  if (!nearCovers(o_from_t, threshold)) {
    // Nothing gathered ahead covers it: a rebuild here, run as far as this pose needs
    // and then on, a little per call, as one started ahead.
    startPendingNear(o_from_t, threshold + margin);
    counters_ = advancePendingNear(o_from_t, threshold, true);
    for (const LeafContact& c : near_pairs_)  // already sorted
      if (c.gap <= threshold) out.push_back(c);
  } else {
    counters_ = TraversalCounters();
    placeTargets(o_from_t);
    const int pose = prepareNearBounds(o_from_t);
    for (std::size_t i = 0; i < near_pairs_.size(); ++i) {
      if (nearGapBound(i) > threshold) continue;
      const LeafContact& candidate = near_pairs_[i];
      const NodePair p = leafPair(candidate.t_leaf, candidate.o_leaf);
      bool beyond = false;
      // Evaluated up to the set's reach: an exact gap there keeps the pair pruned for
      // longer than the lower bound an early exit at the threshold would give.
      const LeafContact c =
          evaluate(p, o_from_piece_[p.t_slot], near_reach_, beyond, &near_caches_[i]);
      near_gaps_[i].gap = c.gap;
      near_gaps_[i].pose = pose;
      if (!beyond && c.gap <= threshold) out.push_back(c);
    }
    sortContacts(out);
    // A third of the slack used: the next rebuild starts here, spread over the calls
    // while the rest lasts.
    const double slack = near_reach_ - threshold;
    if (!pending_.active && displacementBound(near_pose_, o_from_t) > slack / 3.0)
      startPendingNear(o_from_t, threshold + margin);
  }
  counters_.ahead_node_pairs = ahead.node_pairs;
  counters_.ahead_gjk = ahead.node_gjk + ahead.leaf_gjk;
  counters_.ahead_installed = ahead.ahead_installed;
}

void GroupPairQuery::installNear(const Rigid& pose, double reach) {
  near_valid_ = true;
  near_pose_ = pose;
  near_reach_ = reach;
  near_poses_.assign(1, pose);
  near_caches_.clear();
  near_gaps_.clear();
  for (const LeafContact& c : near_pairs_) {
    const NodePair p = leafPair(c.t_leaf, c.o_leaf);
    const Slot& ts = t_slots_[p.t_slot];
    const HullBvhNode& node = ts.data->hierarchy.nodes[p.t_node];
    near_caches_.push_back(cacheOf(p));
    near_gaps_.push_back({ts.group_from_piece * node.center, node.radius, c.gap, 0});
  }
}

void GroupPairQuery::startPendingNear(const Rigid& o_from_t, double reach) {
  pending_.active = true;
  pending_.pose = o_from_t;
  pending_.reach = reach;
  pending_.found.clear();
  pending_.work = 0;
  pending_.last_pose = o_from_t;
  // The traversal reads the placements from o_from_piece_: the pending ones are placed
  // there and lent back to it on every call.
  o_from_piece_.swap(pending_.o_from_piece);
  placeTargets(o_from_t);
  ContactsPolicy policy{*this, reach, pending_.found};
  seedTraversal(policy, pending_.heap);
  o_from_piece_.swap(pending_.o_from_piece);
}

TraversalCounters GroupPairQuery::advancePendingNear(const Rigid& o_from_t, double threshold,
                                                     bool finish) {
  if (!pending_.active) return {};
  const double need = displacementBound(pending_.pose, o_from_t) + threshold;
  if (need > pending_.reach) {  // moved so far since it started that it cannot cover
    pending_.active = false;
    return {};
  }
  const int budget = finish ? -1 : pendingBudget(o_from_t, threshold);
  // Due, it runs only as far as this pose and a few calls more need: the traversal
  // takes node pairs nearest first, so every leaf pair nearer than its queue's front
  // is among the pairs found (the pairs of a rebuild of that reach).
  const double until = finish ? need + 0.5 * (pending_.reach - need) : kInfinity;
  pending_.last_pose = o_from_t;
  const TraversalCounters saved = counters_;
  counters_ = TraversalCounters();
  o_from_piece_.swap(pending_.o_from_piece);
  ContactsPolicy policy{*this, pending_.reach, pending_.found};
  const bool done = runTraversal(policy, pending_.heap, budget, until);
  o_from_piece_.swap(pending_.o_from_piece);
  const TraversalCounters work = counters_;
  counters_ = saved;
  pending_.work += work.node_pairs;
  if (!done && !finish) return work;
  TraversalCounters installed = work;
  installed.ahead_installed = true;
  if (!done) {  // installed as far as it got; it goes on
    near_pairs_ = pending_.found;
    sortContacts(near_pairs_);
    // A pair exactly at the front's bound may be still in the queue.
    installNear(pending_.pose, std::nextafter(pending_.heap.front().bound, 0.0));
    return installed;
  }
  expected_near_work_ = pending_.work;
  pending_.active = false;
  sortContacts(pending_.found);
  near_pairs_.swap(pending_.found);
  installNear(pending_.pose, pending_.reach);
  return installed;
}

int GroupPairQuery::pendingBudget(const Rigid& o_from_t, double threshold) const {
  // Node pairs per call: a rebuild of a broad contact (thousands of leaf pairs) spread
  // over a few physics steps, each of which calls this several times...
  const int base = std::max(64, expected_near_work_ / 8);
  // ...unless the kept pairs stop covering the target first. Pace the rest by the
  // calls left at the last call's speed. A body approaching a broad contact finds
  // many more pairs than the last rebuild did (11 node pairs, then 1,882, then 4,487
  // as a bunny meets a floor): past half the expected work, as much again is assumed
  // to remain.
  const double step = displacementBound(pending_.last_pose, o_from_t);
  if (!(step > 0.0)) return base;
  // Kept pairs exist here: with none, every call is due and finishes the rebuild.
  const double room = near_reach_ - threshold - displacementBound(near_pose_, o_from_t);
  const double calls_left = std::max(1.0, std::floor(room / step));
  const int rest = std::max(expected_near_work_ - pending_.work, pending_.work);
  return std::max(base, static_cast<int>(std::ceil(rest / calls_left)));
}

int GroupPairQuery::prepareNearBounds(const Rigid& o_from_t) {
  // A pair's gap shrinks by at most its target leaf's displacement since its gap was
  // measured. Poses are kept while few; past that every gap is re-based on this pose
  // (a valid, looser bound) so the list stays short.
  constexpr std::size_t kMaxPoses = 32;
  auto changeTo = [&](const Rigid& from) {
    PoseChange d{o_from_t.rotation - from.rotation, o_from_t.translation - from.translation, 0.0};
    d.spin = d.rotation.norm();
    return d;
  };
  near_changes_.clear();
  for (const Rigid& from : near_poses_) near_changes_.push_back(changeTo(from));
  if (near_poses_.size() >= kMaxPoses) {
    for (std::size_t i = 0; i < near_gaps_.size(); ++i) {
      near_gaps_[i].gap = nearGapBound(i);
      near_gaps_[i].pose = 0;
    }
    near_poses_.clear();
    near_changes_.clear();
  }
  near_poses_.push_back(o_from_t);
  near_changes_.push_back(changeTo(o_from_t));
  return static_cast<int>(near_poses_.size()) - 1;
}

double GroupPairQuery::nearGapBound(std::size_t i) const {
  const NearGap& g = near_gaps_[i];
  const PoseChange& d = near_changes_[g.pose];
  return g.gap - ((d.rotation * g.center + d.translation).norm() + d.spin * g.radius);
}

struct GroupPairQuery::IntersectPolicy {
  GroupPairQuery& q;
  bool hit = false;

  bool prunes(double bound) const { return bound > 0.0; }
  double reach() const { return 0.0; }
  double splitWithin() const { return -1.0; }
  bool full() const { return false; }
  bool admits(const NodePair&) const { return true; }
  bool visit(const NodePair& p) {
    bool beyond = false;
    hit = q.evaluate(p, q.o_from_piece_[p.t_slot], 0.0, beyond).intersecting;
    return !hit;
  }
};

bool GroupPairQuery::intersects(const Rigid& o_from_t) {
  counters_ = TraversalCounters();
  if (knownLowerBound(o_from_t) > 0.0) {
    counters_.shortcut = true;
    return false;
  }
  placeTargets(o_from_t);
  IntersectPolicy policy{*this};
  traverse(policy);
  return policy.hit;
}

LeafContact GroupPairQuery::pairAt(int t_leaf, int o_leaf, const Rigid& o_from_t) {
  const NodePair p = leafPair(t_leaf, o_leaf);
  bool beyond = false;
  return evaluate(p, o_from_t * t_slots_[p.t_slot].group_from_piece, kInfinity, beyond);
}

double GroupPairQuery::separationAlong(int t_leaf, int o_leaf, const Rigid& o_from_t,
                                       const Vec3& n) {
  const NodePair p = leafPair(t_leaf, o_leaf);
  const Slot& ts = t_slots_[p.t_slot];
  const Slot& os = o_slots_[p.o_slot];
  const ConvexPolytope& pt = polytopeOf(ts, p.t_node);
  const ConvexPolytope& po = polytopeOf(os, p.o_node);
  const Rigid o_from_lt = o_from_t * ts.group_from_piece;
  SimplexCache& cache = cacheOf(p);
  // Directions in each leaf's own frame.
  const Vec3 nt = o_from_lt.rotation.transpose() * n;
  const Vec3 no = os.group_from_piece.rotation.transpose() * n;
  const int it = pt.support(-nt, cache.hint_a);
  const int io = po.support(no, cache.hint_b);
  const double min_t = n.dot(o_from_lt * pt.vertices[it]);
  const double max_o = n.dot(os.group_from_piece * po.vertices[io]);
  return min_t - max_o;
}

// ---------------------------------------------------------------------------
// Time of impact along a translation

struct GroupPairQuery::ToiPolicy {
  GroupPairQuery& q;
  const Vec3& delta;
  double reach_length;  ///< |delta|
  double skin;
  const std::vector<LeafPair>& skip;
  double limit = 1.0;

  // The pair's gap shrinks by at most limit * |delta| along the way; a pair that
  // starts within skin would block at once.
  bool prunes(double bound) const {
    return bound > skin && bound - limit * reach_length > 0.5 * skin;
  }
  double reach() const { return limit * reach_length + 0.5 * skin; }
  double splitWithin() const { return -1.0; }
  bool full() const { return false; }
  bool admits(const NodePair& p) {
    // Swept bounding spheres: the target sphere's centre runs along a segment.
    const HullBvhNode& t = q.t_slots_[p.t_slot].data->hierarchy.nodes[p.t_node];
    const Slot& os = q.o_slots_[p.o_slot];
    const HullBvhNode& o = os.data->hierarchy.nodes[p.o_node];
    const Vec3 c0 = q.o_from_piece_[p.t_slot] * t.center;
    const double swept =
        pointSegmentDistance(os.group_from_piece * o.center, c0, c0 + limit * delta) - t.radius -
        o.radius;
    if (swept > 0.5 * skin) return false;
    return !planeKeepsApart(p);
  }
  /// True when the hulls stay more than skin apart up to `limit`, by their
  /// separating planes: along the normal n of the plane at the start they part at
  /// the rate n.delta, whatever the distance does, so it keeps them apart up to some
  /// s1; the plane at `limit` does back to some s0; s0 < s1 covers the motion. Then
  /// every leaf pair below advances to `limit`: a motion along the contact (a jump
  /// sideways) prunes what the distance bound alone, assuming the worst direction,
  /// would keep.
  bool planeKeepsApart(const NodePair& p) {
    const double s1 = openUntil(q.nodeGjk(p, reach(), -1.0), -1.0);
    if (s1 >= limit) return true;
    if (s1 < 0.0) return false;
    SimplexCache cold;  // the pair's cache keeps its warm start at the start pose
    const Rigid end = translated(q.o_from_piece_[p.t_slot], limit * delta);
    const double s0 = limit - openUntil(q.nodeGjkAt(p, end, GjkSettings(), cold), 1.0);
    return s0 < s1;
  }
  /// How far along the motion (sign -1) or back from its end (+1) the separating
  /// plane of `r` stays more than skin open; -1 when it is not open there.
  double openUntil(const GjkResult& r, double sign) const {
    if (r.status != GjkStatus::Separated || r.distance <= skin) return -1.0;
    const double closing = sign * r.normal.dot(delta);
    return closing <= 0.0 ? kInfinity : (r.distance - skin) / closing;
  }
  bool visit(const NodePair& p) {
    const Slot& ts = q.t_slots_[p.t_slot];
    const Slot& os = q.o_slots_[p.o_slot];
    const LeafPair leaves{ts.first_leaf + ts.data->hierarchy.nodes[p.t_node].polytope,
                          os.first_leaf + os.data->hierarchy.nodes[p.o_node].polytope};
    if (std::binary_search(skip.begin(), skip.end(), leaves)) return true;
    if (!admits(p)) return true;
    // Conservative advancement: the separating plane of the current closest points
    // stays separating while the target moves towards it by less than the gap.
    const Rigid& start = q.o_from_piece_[p.t_slot];
    double s = 0.0;
    for (int step = 0; step < kMaxAdvanceSteps && s < limit; ++step) {
      bool beyond = false;
      const LeafContact c = q.evaluate(p, translated(start, s * delta), kInfinity, beyond);
      if (c.intersecting || c.gap <= skin) break;
      const double rate = -c.normal.dot(delta);
      if (rate <= 0.0) {
        s = limit;
        break;
      }
      s = std::min(limit, s + (c.gap - 0.5 * skin) / rate);
    }
    limit = std::min(limit, s);
    return limit > 0.0;
  }
};

double GroupPairQuery::translationToi(const Rigid& o_from_t, const Vec3& delta, double skin,
                                      const std::vector<LeafPair>& skip) {
  counters_ = TraversalCounters();
  const double reach_length = delta.norm();
  const double known = knownLowerBound(o_from_t);
  if (known > skin && known - reach_length > 0.5 * skin) {
    counters_.shortcut = true;
    return 1.0;
  }
  placeTargets(o_from_t);
  ToiPolicy policy{*this, delta, reach_length, skin, skip};
  // A pair that can block starts within this reach. When contactsNear()'s pairs hold
  // every pair within it, advance only those, nearest first; a pair whose gap (less
  // the translation since) rules it out is pruned as the traversal would.
  const double reach = std::max(skin, reach_length + 0.5 * skin);
  if (!nearCovers(o_from_t, reach)) {
    traverse(policy);
    return policy.limit;
  }
  prepareNearBounds(o_from_t);
  for (std::size_t i = 0; i < near_pairs_.size(); ++i) {
    if (policy.prunes(nearGapBound(i))) continue;
    const LeafContact& candidate = near_pairs_[i];
    if (!policy.visit(leafPair(candidate.t_leaf, candidate.o_leaf))) break;
  }
  return policy.limit;
}

}  // namespace sc::detail
