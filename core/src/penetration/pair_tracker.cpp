// SPDX-License-Identifier: MIT
// sc::PairTracker: two directed proxy trackers over the pair's leaf queries, and
// the conversion of their outcomes to world-frame DirectedResults.
#include <algorithm>
#include <cmath>

#include "geometry/math_util.h"
#include "geometry/placement_check.h"
#include "penetration/convex_resolution.h"
#include "penetration/initial_resolution.h"
#include "penetration/proxy_tracker.h"
#include "penetration/result_invariants.h"
#include "query/features.h"
#include "smartcollision/pair_tracker.h"

namespace sc {

namespace detail {

struct PairState {
  GroupPairQuery query[2];
  ProxyTracker tracker[2];
  ResolutionScratch resolution;
  ConvexPairCache convex[2];  ///< per direction: the convex fast path's warm start
  // The last update per direction, for contactPoints().
  ProxyOutcome last[2];
  Rigid goal[2];
  GroupView target[2];
  GroupView opponent[2];
  double tolerance[2] = {0.0, 0.0};
  std::vector<LeafContact> leaf_contacts;
};

namespace {

/// Feature of a leaf at a point given in the opponent group's frame.
Feature featureAt(const Leaf& leaf, const Rigid& frame_from_group, const Vec3& point,
                  const int* simplex, int count) {
  const Rigid frame_from_leaf = frame_from_group * leaf.group_from_leaf;
  const Vec3 local = frame_from_leaf.inverse() * point;
  return closestFeature(*leaf.poly, local, simplex, count, featureTolerance(*leaf.poly));
}

DirectionStatus statusOf(const ProxyOutcome& o, double tolerance) {
  switch (o.code) {
    case ErrorCode::Ok:
      if (o.penetrating) return o.lagging ? DirectionStatus::Lagging : DirectionStatus::Penetrating;
      return o.distance > tolerance ? DirectionStatus::Separated : DirectionStatus::Touching;
    case ErrorCode::NoResult:
      return DirectionStatus::BeyondMaxDistance;
    case ErrorCode::InvalidInitialTransformation:
      return DirectionStatus::FirstSeenIntersecting;
    default:
      return DirectionStatus::NotComputed;
  }
}

void toWorld(const ProxyOutcome& o, const GroupView& target, const GroupView& opponent,
             const GroupPairQuery& query, double tolerance, DirectedResult& r) {
  r = DirectedResult();
  r.code = o.code;
  r.status = statusOf(o, tolerance);
  if (o.code != ErrorCode::Ok) return;
  const Rigid world_from_o = opponent.placement.worldFromLocal();
  const Leaf lt = query.targetLeaf(o.contact.t_leaf);
  const Leaf lo = query.opponentLeaf(o.contact.o_leaf);
  r.target_object = target.parts[lt.part].id;
  r.opponent_object = opponent.parts[lo.part].id;
  r.target_piece = lt.piece;
  r.opponent_piece = lo.piece;
  r.distance = o.distance;
  r.normal = normalizedOr(world_from_o.rotation * o.contact.normal, Vec3::UnitZ());
  r.point_on_target = world_from_o * o.contact.point_t;
  r.point_on_opponent = world_from_o * o.contact.point_o;
  r.target_feature = featureAt(lt, o.contact_pose, o.contact.point_t, o.contact.simplex_t,
                               o.contact.simplex_count);
  r.opponent_feature =
      featureAt(lo, Rigid(), o.contact.point_o, o.contact.simplex_o, o.contact.simplex_count);
  r.tpdv = world_from_o.rotation * o.tpdv;
  r.rpdv = world_from_o.rotation * o.rpdv;
  const Rigid world_from_contact = world_from_o * o.contact_pose;
  r.contact_position = world_from_contact * target.placement.local_center;
  r.contact_orientation = Quat(world_from_contact.rotation).normalized();
}

/// The settings with the tolerance raised to its floor for this pair (pair_settings.h).
/// A contact normal read from closest points a tolerance t apart is tilted by about
/// (rounding of the coordinates, ~1e-15 L) / t, which moves the contact pose by that
/// times the depth (~ the target's radius r): within t when t >= ~4e-8 sqrt(r L).
PairSettings effectiveSettings(const PairSettings& settings, const GroupPairQuery& query,
                               const Vec3& goal_center) {
  PairSettings s = settings;
  const double r = query.targetSize();
  const double floor = kMinRelativeTolerance * std::sqrt(r * (r + goal_center.norm()));
  s.tolerance = std::max(settings.tolerance, floor);
  return s;
}

/// The convex fast path of one direction (convex_resolution.h): a convex pair first
/// seen intersecting gets its global depth, a tracked one its update, straight on the
/// two pieces. False leaves the update to the general path.
bool runConvex(PairState& state, int dir, const GroupView& target, const GroupView& opponent,
               const Rigid& goal, const PairSettings& settings, ProxyOutcome& outcome) {
  ProxyTracker& tracker = state.tracker[dir];
  Rigid free_pose;
  if (!tracker.tracking() && settings.resolve_initial_intersection &&
      resolveConvexPair(state.query[dir], target, opponent, goal, settings, state.convex[dir],
                        outcome, free_pose)) {
    tracker.startAt(free_pose);
    return true;
  }
  return trackConvexPair(state.query[dir], target, opponent, goal, target.placement.local_center,
                         settings, state.convex[dir], tracker, outcome);
}

/// A direction first seen intersecting, but within the tolerance of touching: every
/// intersecting leaf pair's exit at most the tolerance deep (docs/penetration.md). The
/// proxy starts at the free pose just out of contact (the slide's rows need closest
/// points there, which touching leaves lack) and the goal reports Touching: distance
/// 0, the free pose's closest pair carried to the goal. A deeper overlap changes
/// nothing and stays InvalidInitialTransformation.
void startTouching(PairState& state, int dir, const Rigid& goal, const PairSettings& settings,
                   ProxyOutcome& outcome) {
  GroupPairQuery& query = state.query[dir];
  Rigid free_pose;
  ProxyOutcome touching;
  // The tracker's intersection test just met that pair at this goal.
  if (!resolveInitialIntersection(query, goal, settings, free_pose, state.resolution,
                                  settings.tolerance, &state.tracker[dir].firstIntersecting()) ||
      !query.distance(free_pose, kInfinity, touching.contact))
    return;
  touching.code = ErrorCode::Ok;
  touching.contact.point_t += goal.translation - free_pose.translation;
  touching.contact.gap = 0.0;
  touching.contact_pose = goal;
  touching.distance = 0.0;
  state.tracker[dir].startAt(free_pose, false);
  outcome = touching;
}

/// The general path's answer to a pair first seen intersecting: Touching within the
/// tolerance; else, with resolve_initial_intersection, the depth from a free pose nearby.
void firstSeenIntersecting(PairState& state, int dir, const Rigid& goal, const Vec3& center,
                           const PairSettings& settings, ProxyOutcome& outcome) {
  if (!settings.resolve_initial_intersection) {
    startTouching(state, dir, goal, settings, outcome);
    return;
  }
  Rigid free_pose;
  GroupPairQuery& query = state.query[dir];
  if (resolveInitialIntersection(query, goal, settings, free_pose, state.resolution)) {
    // Start tracking at the free pose, then move to the goal as on any later frame.
    state.tracker[dir].update(query, free_pose, center, settings, outcome);
    state.tracker[dir].update(query, goal, center, settings, outcome);
  }
}

void runDirection(PairState& state, int dir, const GroupView& target, const GroupView& opponent,
                  const PairSettings& requested, DirectedResult& out) {
  GroupPairQuery& query = state.query[dir];
  query.bind(target, opponent);
  const Rigid goal =
      opponent.placement.worldFromLocal().inverse() * target.placement.worldFromLocal();
  ProxyOutcome outcome;
  ProxyTracker& tracker = state.tracker[dir];
  const Vec3& center = target.placement.local_center;
  const PairSettings settings = effectiveSettings(requested, query, goal * center);
  // The one rule for a jump: beyond the teleport distance the motion is not a path,
  // and the direction starts again as first seen (the query's own warm state follows
  // its rule, near_pairs.h: beyond its reach it no longer answers).
  if (tracker.tracking() &&
      query.displacementBound(state.goal[dir], goal) > settings.teleport_distance)
    tracker.forget();
  // How far the proxy may move in this update: a multiple of how far the target did.
  const bool capped = tracker.tracking() && std::isfinite(settings.proxy_travel_ratio);
  tracker.travel() = TravelBudget{
      capped ? settings.proxy_travel_ratio * query.targetMotion(state.goal[dir], goal) : kInfinity};
  if (!runConvex(state, dir, target, opponent, goal, settings, outcome)) {
    tracker.update(query, goal, center, settings, outcome);
    if (outcome.code == ErrorCode::InvalidInitialTransformation)
      firstSeenIntersecting(state, dir, goal, center, settings, outcome);
  }
  toWorld(outcome, target, opponent, query, settings.tolerance, out);
  // Debug builds: a result breaking its contract aborts here, at its source.
  enforceResultInvariants(out, target.placement, opponent.placement);
  state.last[dir] = outcome;
  state.goal[dir] = goal;
  state.target[dir] = target;
  state.opponent[dir] = opponent;
  state.tolerance[dir] = settings.tolerance;
}

/// `c` measured at the contact pose moved out by `lift` along the result's normal.
ContactPoint contactPointOf(const PairState& state, int dir, const GroupPairQuery& query,
                            const LeafContact& c, double lift) {
  const ProxyOutcome& o = state.last[dir];
  const Rigid world_from_o = state.opponent[dir].placement.worldFromLocal();
  const Vec3& n = c.normal;
  const Vec3 t_contact = c.point_t - lift * o.contact.normal;
  const Vec3 t_now = state.goal[dir] * (o.contact_pose.inverse() * t_contact);
  const Leaf lt = query.targetLeaf(c.t_leaf);
  const Leaf lo = query.opponentLeaf(c.o_leaf);
  ContactPoint p;
  p.point_on_target = world_from_o * t_now;
  p.point_on_opponent = world_from_o * c.point_o;
  p.normal = normalizedOr(world_from_o.rotation * n, Vec3::UnitZ());
  p.separation = n.dot(t_now - c.point_o);
  p.target_object = state.target[dir].parts[lt.part].id;
  p.opponent_object = state.opponent[dir].parts[lo.part].id;
  p.target_piece = lt.piece;
  p.opponent_piece = lo.piece;
  return p;
}

/// `g` with a unit quaternion, normalised as the scene normalises; one already unit to
/// rounding (the scene's, any caller's normalised one) is kept bit for bit.
GroupView unitView(const GroupView& g) {
  if (unitToRounding(g.placement.orientation)) return g;
  GroupView unit = g;
  unit.placement = unitPlacement(g.placement);
  return unit;
}

}  // namespace
}  // namespace detail

PairTracker::PairTracker() : state_(std::make_unique<detail::PairState>()) {}
PairTracker::~PairTracker() = default;
PairTracker::PairTracker(PairTracker&&) noexcept = default;
PairTracker& PairTracker::operator=(PairTracker&&) noexcept = default;

void PairTracker::update(const GroupView& a, const GroupView& b, Directions directions,
                         const PairSettings& settings, DirectedResult out[2]) {
  out[0] = DirectedResult();
  out[1] = DirectedResult();
  state_->last[0] = state_->last[1] = detail::ProxyOutcome();
  // A few comparisons; on bad input no tracking state is touched.
  if (!validate(settings).ok() || !validate(a).ok() || !validate(b).ok()) {
    if (directions.a_target) out[0].code = ErrorCode::InvalidArgument;
    if (directions.b_target) out[1].code = ErrorCode::InvalidArgument;
    return;
  }
  const GroupView unit_a = detail::unitView(a);
  const GroupView unit_b = detail::unitView(b);
  if (directions.a_target) detail::runDirection(*state_, 0, unit_a, unit_b, settings, out[0]);
  if (directions.b_target) detail::runDirection(*state_, 1, unit_b, unit_a, settings, out[1]);
}

void PairTracker::contactPoints(int direction, double threshold, std::vector<ContactPoint>& out) {
  out.clear();
  const int dir = direction & 1;
  detail::PairState& s = *state_;
  const detail::ProxyOutcome& o = s.last[dir];
  if (o.code != ErrorCode::Ok || !(threshold >= 0.0)) return;
  // Leaves touching at the contact pose (a depth, or a Touching result at distance
  // 0: both count as intersecting) have no closest points: measure them lifted off
  // by half the tolerance along the normal. Apart, the closest pair counts even
  // beyond the threshold, so a consumer always has the point the result names.
  const bool in_contact = !(o.distance > 0.0);  // a depth reads negative
  const double lift = in_contact ? 0.5 * s.tolerance[dir] : 0.0;
  Rigid probe = o.contact_pose;
  probe.translation += lift * o.contact.normal;
  const double probe_threshold = std::max(threshold, in_contact ? 0.0 : o.distance) + lift;
  s.query[dir].contacts(probe, probe_threshold, s.leaf_contacts);
  for (const detail::LeafContact& c : s.leaf_contacts) {
    if (c.intersecting) continue;  // deeper than the lift: a lagging proxy; skipped
    out.push_back(detail::contactPointOf(s, dir, s.query[dir], c, lift));
  }
}

void PairTracker::forget(int direction) { state_->tracker[direction & 1].forget(); }

void PairTracker::reset() {
  forget(0);
  forget(1);
}

bool PairTracker::tracking(int direction) const {
  return state_->tracker[direction & 1].tracking();
}

}  // namespace sc
