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
#include "query/group_pair_traversal.h"

namespace sc::detail {

namespace {

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
  if (!t_same || !o_same || t_moved || o_moved) {
    known_ = false;
    planes_.clear();
    near_.drop();
    front_.drop();
  }
  if (!t_same || t_moved) {
    updateGroupSphere();
    t_leaves_valid_ = false;
  }
  if (!o_same || o_moved) o_leaves_valid_ = false;
}

namespace {

/// A side's leaves, listed again only when `valid` was cleared (pieces or pose changed).
template <class Slots, class LeafAt>
const std::vector<Leaf>& listLeaves(const Slots& slots, int count, LeafAt&& leaf_at, bool& valid,
                                    std::vector<Leaf>& out) {
  if (valid) return out;
  out.clear();
  if (!slots.empty()) {
    out.reserve(static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i) out.push_back(leaf_at(i));
  }
  valid = true;
  return out;
}

}  // namespace

const std::vector<Leaf>& GroupPairQuery::targetLeaves() const {
  return listLeaves(
      t_slots_, t_leaf_count_, [this](int i) { return targetLeaf(i); }, t_leaves_valid_, t_leaves_);
}

const std::vector<Leaf>& GroupPairQuery::opponentLeaves() const {
  return listLeaves(
      o_slots_, o_leaf_count_, [this](int i) { return opponentLeaf(i); }, o_leaves_valid_,
      o_leaves_);
}

void GroupPairQuery::updateGroupSphere() {
  // A sphere around the pieces' root spheres: centre at their box's centre.
  Aabb box;
  for (const Slot& s : t_slots_) {
    const HullBvhNode& root = s.data->hierarchy.nodes[0];
    const Vec3 c = s.group_from_piece * root.center;
    box.extend(Aabb{c - Vec3::Constant(root.radius), c + Vec3::Constant(root.radius)});
  }
  TargetSphere sphere;
  sphere.center = box.empty() ? Vec3::Zero() : Vec3(0.5 * (box.min + box.max));
  for (const Slot& s : t_slots_) {
    const HullBvhNode& root = s.data->hierarchy.nodes[0];
    sphere.radius = std::max(
        sphere.radius, (s.group_from_piece * root.center - sphere.center).norm() + root.radius);
  }
  near_.setTarget(sphere);
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

std::uint64_t GroupPairQuery::keyOf(const NodePair& p) const {
  const auto t = static_cast<std::uint32_t>(t_slots_[p.t_slot].first_node + p.t_node);
  const auto o = static_cast<std::uint32_t>(o_slots_[p.o_slot].first_node + p.o_node);
  return static_cast<std::uint64_t>(t) << 32 | o;
}

void GroupPairQuery::placeTargets(const Rigid& o_from_t) {
  o_from_piece_.resize(t_slots_.size());
  for (std::size_t i = 0; i < t_slots_.size(); ++i)
    o_from_piece_[i] = o_from_t * t_slots_[i].group_from_piece;
}

double GroupPairQuery::clearingLength(const Rigid& o_from_t, const Vec3& u, double gap) const {
  // |c + D u| >= c . u + D, so D >= radii + gap - c . u clears a sphere pair.
  double length = 0.0;
  for (const Slot& ts : t_slots_) {
    const HullBvhNode& t = ts.data->hierarchy.nodes[0];
    const Vec3 tc = o_from_t * (ts.group_from_piece * t.center);
    for (const Slot& os : o_slots_) {
      const HullBvhNode& o = os.data->hierarchy.nodes[0];
      const Vec3 c = tc - os.group_from_piece * o.center;
      length = std::max(length, t.radius + o.radius + gap - c.dot(u));
    }
  }
  return length;
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
  const GjkResult r = nodeGjkAt(p, o_from_piece_[p.t_slot], settings, cacheOf(p));
  if (record_planes_ && r.status == GjkStatus::Separated)  // a plane for the sweep next
    planes_.record(keyOf(p), o_from_piece_[p.t_slot], r.normal,
                   std::min(r.lower_bound, r.distance));
  return r;
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
  if (!hullsOf(p)) return 0.0;  // the caller's sphere bound stands
  const GjkResult r = nodeGjk(p, max_distance, within_distance);
  return r.status == GjkStatus::Intersecting ? 0.0 : r.lower_bound;
}

std::array<NodePair, 2> GroupPairQuery::childrenOf(const NodePair& p) const {
  const HullBvhNode& tn = t_slots_[p.t_slot].data->hierarchy.nodes[p.t_node];
  const HullBvhNode& on = o_slots_[p.o_slot].data->hierarchy.nodes[p.o_node];
  // A node without hull goes first: only its children can tighten the bound.
  const bool split_t = tn.hasPolytope() != on.hasPolytope()
                           ? !tn.hasPolytope()
                           : on.leaf() || (!tn.leaf() && tn.radius >= on.radius);
  const HullBvhNode& split = split_t ? tn : on;
  std::array<NodePair, 2> children{p, p};
  (split_t ? children[0].t_node : children[0].o_node) = split.left;
  (split_t ? children[1].t_node : children[1].o_node) = split.right;
  for (NodePair& c : children) {
    c.refined = false;
    c.bound = std::max(p.bound, sphereBound(c));
  }
  return children;
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
  beyond = r.status == GjkStatus::BeyondMaxDistance;
  return leafContactOf(r, ts.first_leaf + tn.polytope, os.first_leaf + on.polytope);
}

NodePair GroupPairQuery::leafPair(int t_leaf, int o_leaf) const {
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
  // Along the hulls' normal n every point of the target's faces lies at least h (the
  // hulls' gap) beyond every point of the opponent's, and a face pair is no nearer
  // than its faces' extents along n are apart: sorted by that extent (the target's
  // least, the opponent's greatest), the pairs that can beat the bound are a few at
  // the head of each list, measured first. Real faces close to their hulls (the
  // usual case: a virtual feature grazed) leave almost no pair to measure.
  const Vec3& n = c.normal;
  for (PlacedFace& f : faces_t_)
    f.key = std::min({n.dot(f.corners[0]), n.dot(f.corners[1]), n.dot(f.corners[2])});
  for (PlacedFace& f : faces_o_)
    f.key = -std::max({n.dot(f.corners[0]), n.dot(f.corners[1]), n.dot(f.corners[2])});
  const auto byKey = [](const PlacedFace& a, const PlacedFace& b) { return a.key < b.key; };
  std::sort(faces_t_.begin(), faces_t_.end(), byKey);
  std::sort(faces_o_.begin(), faces_o_.end(), byKey);
  double best = bound;
  int best_t = -1, best_o = -1;
  TriangleDistance best_d;
  for (int i = 0; i < static_cast<int>(faces_t_.size()); ++i) {
    const PlacedFace& ft = faces_t_[i];
    if (faces_o_.empty() || ft.key + faces_o_.front().key >= best) break;
    for (int j = 0; j < static_cast<int>(faces_o_.size()); ++j) {
      const PlacedFace& fo = faces_o_[j];
      if (ft.key + fo.key >= best) break;
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

LeafContact GroupPairQuery::exactLeafDistance(const NodePair& p, double bound, bool& beyond,
                                              bool defer_virtual) {
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
  beyond = defer_virtual || !refine(p, o_from_piece, bound, c);
  return c;
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
  void pruned(const NodePair&) const {}
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
    // A pair whose hulls are closest on a virtual feature measures its real faces, at
    // a cost that grows with the bound it is given: it goes back in the queue at its
    // hulls' gap, a lower bound of its faces', and is measured when no pair is nearer
    // (with the bound the traversal has by then: often none is needed).
    const LeafContact c = q.exactLeafDistance(p, reach(), beyond, !p.refined);
    const bool deferred = beyond && !p.refined && !c.intersecting && c.gap < reach();
    if (deferred) {
      NodePair later = p;
      later.bound = std::max(p.bound, c.gap);
      later.refined = true;
      q.heap_.push_back(later);
      std::push_heap(q.heap_.begin(), q.heap_.end(), Farther());
    }
    if (!beyond) offer(c);
    return !(found && best.intersecting);
  }
};

bool GroupPairQuery::seedHelps(const Rigid& o_from_t) const {
  if (seed_.t_leaf < 0 || seed_.t_leaf >= t_leaf_count_ || seed_.o_leaf >= o_leaf_count_)
    return false;
  // Moved farther than the seed pair's gap and its target leaf's radius (a jump), it
  // bounds the distance only loosely and its refinement on real triangles can cost
  // more than a traversal without it.
  if (!known_) return true;
  const double reach = known_gap_ + leafOf(t_slots_, seed_.t_leaf).radius;
  return displacementBound(known_pose_, o_from_t) <= reach;
}

double GroupPairQuery::seedBound(const Rigid& o_from_t, double max_distance) const {
  if (!known_) return max_distance;
  const double last = known_gap_ / (1.0 - kKnownGapMargin);
  return std::min(max_distance, last + displacementBound(known_pose_, o_from_t));
}

bool GroupPairQuery::distance(const Rigid& o_from_t, double max_distance, LeafContact& best,
                              bool sweep_next) {
  counters_ = TraversalCounters();
  placeTargets(o_from_t);
  DistancePolicy policy{*this, max_distance, best};
  if (seedHelps(o_from_t)) {
    // The distance is at most the last one plus the motion since: a seed beyond that
    // is not the closest pair. A seed on a virtual feature is not refined here, where
    // nothing else bounds its refinement on the real triangles (every face pair of two
    // patches: 2 ms after a 5 cm jump, against a 0.3 ms fresh traversal): the
    // traversal measures it in its turn, with the bound it has by then.
    bool beyond = false;
    const LeafContact c = exactLeafDistance(leafPair(seed_.t_leaf, seed_.o_leaf),
                                            seedBound(o_from_t, max_distance), beyond, true);
    if (!beyond)
      policy.offer(c);
    else
      seed_ = LeafPair();
  } else {
    seed_ = LeafPair();  // the traversal measures it in its turn
  }
  const bool done = (policy.found && best.intersecting) ||
                    distanceNear(o_from_t, max_distance, best, policy.found);
  record_planes_ = sweep_next;
  if (!done) traverse(policy);
  record_planes_ = false;
  if (policy.found) seed_ = {best.t_leaf, best.o_leaf};
  known_ = true;
  known_pose_ = o_from_t;
  known_gap_ = (policy.found ? best.gap : max_distance) * (1.0 - kKnownGapMargin);
  return policy.found;
}

// ---------------------------------------------------------------------------
// Contacts and intersection

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

struct GroupPairQuery::IntersectPolicy {
  GroupPairQuery& q;
  bool hit = false;
  LeafContact found;

  bool prunes(double bound) const { return bound > 0.0; }
  double reach() const { return 0.0; }
  double splitWithin() const { return -1.0; }
  bool full() const { return false; }
  bool admits(const NodePair&) const { return true; }
  void pruned(const NodePair&) const {}
  bool visit(const NodePair& p) {
    bool beyond = false;
    found = q.evaluate(p, q.o_from_piece_[p.t_slot], 0.0, beyond);
    hit = found.intersecting;
    return !hit;
  }
};

bool GroupPairQuery::intersects(const Rigid& o_from_t, LeafContact* first) {
  counters_ = TraversalCounters();
  if (knownLowerBound(o_from_t) > 0.0) {
    counters_.shortcut = true;
    return false;
  }
  placeTargets(o_from_t);
  IntersectPolicy policy{*this, false, LeafContact()};
  traverse(policy);
  if (policy.hit && first != nullptr) *first = policy.found;
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

}  // namespace sc::detail
