// SPDX-License-Identifier: MIT
#include "penetration/convex_resolution.h"

#include <algorithm>

namespace sc::detail {
namespace {

bool convexPiece(const GroupView& group, const Leaf& leaf) {
  if (leaf.part < 0 || leaf.part >= group.part_count) return false;
  const Model* model = group.parts[leaf.part].model;
  if (!model || leaf.piece < 0 || leaf.piece >= static_cast<int>(model->pieces().size()))
    return false;
  const Piece& piece = *model->pieces()[leaf.piece];
  return piece.kind() == ModelKind::ClosedPolyhedron && piece.stats().convex;
}

/// The outcome of a convex pair at `goal` penetrating by e (opponent frame).
void fillOutcome(const EpaResult& e, const Rigid& goal, ProxyOutcome& out) {
  out = ProxyOutcome();
  out.code = ErrorCode::Ok;
  out.penetrating = true;
  out.contact_pose = {goal.rotation, goal.translation + e.depth * e.normal};
  // The pose moved by a translation only: TPDV is that translation reversed, free of
  // the rounding of the two placed centres (which a tiny depth would not survive).
  out.tpdv = -e.depth * e.normal;
  out.distance = -out.tpdv.norm();
  out.iterations = e.iterations;
  LeafContact& c = out.contact;
  c.t_leaf = 0;
  c.o_leaf = 0;
  c.normal = e.normal;
  c.point_t = e.point_a + e.depth * e.normal;  // at the contact pose
  c.point_o = e.point_b;
  c.simplex_count = e.face_count;  // seeds the feature search at the contact
  for (int m = 0; m < e.face_count; ++m) {
    c.simplex_t[m] = e.face_a[m];
    c.simplex_o[m] = e.face_b[m];
  }
}

}  // namespace

bool isConvexPair(const GroupPairQuery& query, const GroupView& target, const GroupView& opponent) {
  return query.targetLeafCount() == 1 && query.opponentLeafCount() == 1 &&
         convexPiece(target, query.targetLeaf(0)) && convexPiece(opponent, query.opponentLeaf(0));
}

bool resolveConvexPair(const GroupPairQuery& query, const GroupView& target,
                       const GroupView& opponent, const Rigid& goal, const PairSettings& settings,
                       ConvexPairCache& cache, ProxyOutcome& out, Rigid& free_pose) {
  const RotationMode mode = settings.rotation_mode;
  if (mode != RotationMode::Input && mode != RotationMode::None) return false;
  if (!isConvexPair(query, target, opponent)) return false;
  const Leaf lt = query.targetLeaf(0);
  const Leaf lo = query.opponentLeaf(0);
  EpaResult e;
  if (convexDepth(*lt.poly, goal * lt.group_from_leaf, *lo.poly, lo.group_from_leaf, cache, e) !=
      ConvexDepthStatus::Penetrating)
    return false;
  fillOutcome(e, goal, out);
  // As the general path: the proxy starts half a tolerance clear of the contact.
  free_pose = {goal.rotation, goal.translation + (e.depth + 0.5 * settings.tolerance) * e.normal};
  return true;
}

// ---------------------------------------------------------------------------------
// Later frames: the general path's proxy steps on the one leaf pair.

namespace {

constexpr int kMaxAdvanceSteps = 64;  // as the general path's translationToi

Rigid poseAt(const Mat3& r, const Vec3& center, const Vec3& y) { return {r, y - r * center}; }

/// The point nearest `g` in the half-space n . z >= b (n unit): the contact QP of a
/// single row.
Vec3 projectOnto(const Vec3& g, const Vec3& n, double b) {
  const double short_by = b - n.dot(g);
  return short_by > 0.0 ? Vec3(g + short_by * n) : g;
}

/// The two pieces in the opponent group's frame, the target's placed by a pose of
/// its group; every query warm-started from one cache.
struct ConvexPair {
  Leaf t, o;
  SimplexCache& cache;

  /// Closest points at `pose` as a leaf contact; `beyond` when farther than `max`.
  LeafContact at(const Rigid& pose, double max, bool& beyond) const {
    GjkSettings gs;
    gs.max_distance = max;
    const GjkResult r =
        gjkDistance(*t.poly, pose * t.group_from_leaf, *o.poly, o.group_from_leaf, gs, cache);
    beyond = r.status == GjkStatus::BeyondMaxDistance;
    return leafContactOf(r, 0, 0);
  }
  /// Min over the target of n . x less max over the opponent (n unit, opponent frame).
  double separationAlong(const Rigid& pose, const Vec3& n) const {
    const Rigid o_from_lt = pose * t.group_from_leaf;
    const int it = t.poly->support(-(o_from_lt.rotation.transpose() * n), cache.hint_a);
    const int io = o.poly->support(o.group_from_leaf.rotation.transpose() * n, cache.hint_b);
    return n.dot(o_from_lt * t.poly->vertices[it]) -
           n.dot(o.group_from_leaf * o.poly->vertices[io]);
  }
  /// An exit for a pair intersecting at the re-oriented proxy: its separating
  /// direction at the last free proxy, as the general path's seedNormal.
  Vec3 seedNormal(const Rigid& previous) const {
    bool beyond = false;
    const LeafContact before = at(previous, kInfinity, beyond);
    if (!before.intersecting) return before.normal;
    return normalizedOr(previous * t.center - o.center, Vec3::UnitZ());
  }
  /// The row of a contact at `pose` for a proxy centre z (its rotation * centre is
  /// `rc`): n . z >= b, summed in the general path's order (a knife-edge touch rounds
  /// the same way).
  void row(const LeafContact& c, const Rigid& pose, const Vec3& rc, const Rigid& previous, Vec3& n,
           double& b) const {
    n = c.intersecting ? seedNormal(previous) : c.normal;
    const double offset = n.dot(pose.translation) - separationAlong(pose, n);
    b = offset + n.dot(rc);
  }
  /// Conservative advancement along the translation `delta` from `start`: the largest
  /// s in [0, 1] keeping the gap >= skin/2, ending within skin when the pair blocks.
  double advance(const Rigid& start, const Vec3& delta, double skin) const {
    double s = 0.0;
    for (int step = 0; step < kMaxAdvanceSteps && s < 1.0; ++step) {
      bool beyond = false;
      const LeafContact c = at({start.rotation, start.translation + s * delta}, kInfinity, beyond);
      if (c.intersecting || c.gap <= skin) break;
      const double rate = -c.normal.dot(delta);
      if (rate <= 0.0) return 1.0;
      s = std::min(1.0, s + (c.gap - 0.5 * skin) / rate);
    }
    return s;
  }
};

/// The pair at one pose of the proxy: its closest points and, within the tolerance,
/// the row of its contact (zero skin).
struct Probe {
  LeafContact c;
  bool contact = false;
  Vec3 n = Vec3::UnitZ();
  double b = 0.0;
};

Probe probeAt(const ConvexPair& pair, const Rigid& pose, const Vec3& center, const Rigid& previous,
              double tolerance) {
  Probe p;
  bool beyond = false;
  p.c = pair.at(pose, tolerance, beyond);
  p.contact = !beyond && p.c.gap <= tolerance;
  if (p.contact) pair.row(p.c, pose, pose.rotation * center, previous, p.n, p.b);
  return p;
}

/// The general path's slide for one pair: y, the proxy's centre, moves towards the
/// goal's centre, projected on the contact's plane (at the skin) while within the
/// tolerance, else advanced conservatively. Returns the iterations; `settled` is the
/// probe at y when the slide stopped there (as the general path's memo of the last
/// contacts, it spares the report measuring the same pose again).
int slide(const ConvexPair& pair, const Mat3& rotation, const Vec3& goal_center, const Vec3& center,
          const PairSettings& settings, const Rigid& previous, double size, Vec3& y, Probe& settled,
          bool& has_settled, TravelBudget& travel) {
  const double skin = 0.25 * settings.tolerance;
  has_settled = false;
  int k = 0;
  for (; k < settings.max_iterations; ++k) {
    const Rigid pose = poseAt(rotation, center, y);
    const Probe p = probeAt(pair, pose, center, previous, settings.tolerance);
    const Vec3 z = p.contact ? projectOnto(goal_center, p.n, p.b + skin) : goal_center;
    Vec3 delta = z - y;
    // Settled when the step is rounding: of the pose, and of the normal (its closest
    // points round by ~1e-15 L at a gap >= skin/2) turning the projection of a goal
    // |goal - z| away. The general path's bound omits the second: deep, it can
    // spin on it to its last iteration.
    const double rounding = 1e-12 * (size + y.norm());
    if (delta.norm() <= rounding * (1.0 + (goal_center - z).norm() / skin)) {
      settled = p;
      has_settled = true;
      break;
    }
    // The travel left cuts the step, but never short of the contact's plane: the proxy
    // leaves the intersection its turn to the goal's rotation may have made.
    const double exit = p.contact ? holdFraction(p.b - p.n.dot(y), p.n.dot(delta)) : 0.0;
    const double keep = std::max(travel.share(delta.norm()), exit);
    delta *= std::min(keep, 1.0);
    const double s = p.contact ? 1.0 : std::min(1.0, pair.advance(pose, delta, skin));
    travel.charge(s * delta.norm(), keep < 1.0);
    y = s >= 1.0 && keep >= 1.0 ? z : Vec3(y + s * delta);
    if (keep < 1.0) {  // held back: the proxy lags and catches up in later updates
      ++k;
      break;
    }
    if (!p.contact && s >= 1.0) {  // reached the goal unobstructed
      ++k;
      break;
    }
  }
  return k;
}

void reportApart(const ConvexPair& pair, const Rigid& goal, const PairSettings& settings,
                 ProxyOutcome& out) {
  out.penetrating = false;
  out.contact_pose = goal;
  out.tpdv.setZero();
  out.rpdv.setZero();
  bool beyond = false;
  out.contact = pair.at(goal, settings.max_distance, beyond);
  out.code = beyond ? ErrorCode::NoResult : ErrorCode::Ok;
  out.distance = beyond ? 0.0 : out.contact.gap;
}

/// The depth at `proxy` against the contact's exact plane (zero skin), as the
/// general path's projectTranslation; false when the goal only touches (then
/// `touch_normal` is the contact's normal, if any).
bool reportPenetration(const ConvexPair& pair, const Rigid& proxy, const Probe& at_proxy,
                       const Rigid& goal, const Vec3& center, double size,
                       const PairSettings& settings, bool ran_out, Vec3& touch_normal,
                       ProxyOutcome& out) {
  const Probe& p = at_proxy;
  Rigid contact_pose = proxy;
  if (p.contact) {
    const Vec3 y = proxy * center;
    const Vec3 z = projectOnto(goal * center, p.n, p.b);
    if ((z - y).norm() <= settings.tolerance) contact_pose = poseAt(proxy.rotation, center, z);
  }
  if (!reportDepth(goal, contact_pose, center, size, out)) {  // the goal only touches
    if (p.contact) touch_normal = p.n;
    return false;
  }
  out.lagging = ran_out || !p.contact;
  // A lagging proxy with nothing within the tolerance: its closest points name
  // where the contact will be.
  bool beyond = false;
  out.contact = p.contact ? p.c : pair.at(proxy, kInfinity, beyond);
  if (p.contact) out.contact.normal = p.n;
  out.contact.point_t = contact_pose * (proxy.inverse() * out.contact.point_t);
  return true;
}

}  // namespace

bool trackConvexPair(const GroupPairQuery& query, const GroupView& target,
                     const GroupView& opponent, const Rigid& goal, const Vec3& center,
                     const PairSettings& settings, ConvexPairCache& cache, ProxyTracker& tracker,
                     ProxyOutcome& out) {
  const RotationMode mode = settings.rotation_mode;
  if (mode != RotationMode::Input && mode != RotationMode::None) return false;
  if (!isConvexPair(query, target, opponent)) return false;
  const ConvexPair pair{query.targetLeaf(0), query.opponentLeaf(0), cache.gjk};
  ProxyOutcome result;
  if (!tracker.tracking()) {  // first sight: apart starts tracking here
    reportApart(pair, goal, settings, result);
    if (result.contact.intersecting) return false;
    tracker.startAt(goal, false);
    out = result;
    return true;
  }
  const Rigid previous = tracker.proxy();
  // None's orientation at the impact lasts while the goal intersects (as follow()).
  bool freeze = mode == RotationMode::None && tracker.penetrating();
  if (freeze) {
    bool beyond = false;
    const LeafContact c = pair.at(goal, 0.0, beyond);
    freeze = !beyond && (c.intersecting || !(c.gap > 0.0));
  }
  const Mat3 rotation = freeze ? previous.rotation : goal.rotation;
  const Vec3 goal_center = goal * center;
  const double size = query.targetSize();
  Vec3 y = previous * center;
  Probe settled;
  bool has_settled = false;
  const TravelBudget travel = tracker.travel();  // kept for the general path
  result.iterations = slide(pair, rotation, goal_center, center, settings, previous, size, y,
                            settled, has_settled, tracker.travel());
  Rigid proxy = poseAt(rotation, center, y);
  // Within the rounding of a pose written as a centre and a rotation, at the goal.
  const bool reached =
      rotation == goal.rotation &&
      (proxy * center - goal_center).norm() <= 1e-12 * (size + goal_center.norm() + center.norm());
  // None mode's first contact keeps the orientation at the impact: the general path.
  if (!reached && mode == RotationMode::None && !tracker.penetrating()) {
    tracker.travel() = travel;
    return false;
  }
  const bool ran_out = result.iterations >= settings.max_iterations || tracker.travel().spent;
  Vec3 touch_normal = Vec3::Zero();
  if (!reached) {
    const Probe at_proxy =
        has_settled ? settled : probeAt(pair, proxy, center, previous, settings.tolerance);
    if (reportPenetration(pair, proxy, at_proxy, goal, center, size, settings, ran_out,
                          touch_normal, result)) {
      tracker.startAt(proxy, true);
      out = result;
      return true;
    }
  }
  tracker.startAt(goal, false);
  reportApart(pair, goal, settings, result);
  // A goal that only touches keeps the normal of the contact the proxy rested on.
  if (result.code == ErrorCode::Ok && result.distance <= 0.0 && !touch_normal.isZero(0.0))
    result.contact.normal = touch_normal;
  out = result;
  return true;
}

}  // namespace sc::detail
