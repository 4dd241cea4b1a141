// SPDX-License-Identifier: MIT
// sc::PairTracker: two directed proxy trackers over the pair's leaf queries, and
// the conversion of their outcomes to world-frame DirectedResults.
#include <cmath>

#include "geometry/math_util.h"
#include "penetration/proxy_tracker.h"
#include "query/features.h"
#include "smartcollision/collision.h"

namespace sc {

namespace detail {

struct PairState {
  GroupPairQuery query[2];
  ProxyTracker tracker[2];
};

namespace {

/// Feature of a leaf at a point given in the opponent group's frame.
Feature featureAt(const Leaf& leaf, const Rigid& frame_from_group, const Vec3& point,
                  const int* simplex, int count) {
  const Rigid frame_from_leaf = frame_from_group * leaf.group_from_leaf;
  const Vec3 local = frame_from_leaf.inverse() * point;
  const double tol = 1e-9 * (1.0 + leaf.poly->radius + leaf.poly->center.norm());
  return closestFeature(*leaf.poly, local, simplex, count, tol);
}

void toWorld(const ProxyOutcome& o, const GroupView& target, const GroupView& opponent,
             const GroupPairQuery& query, DirectedResult& r) {
  r = DirectedResult();
  r.code = o.code;
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

void runDirection(PairState& state, int dir, const GroupView& target, const GroupView& opponent,
                  const SceneSettings& settings, DirectedResult& out) {
  GroupPairQuery& query = state.query[dir];
  query.bind(target, opponent);
  const Rigid goal =
      opponent.placement.worldFromLocal().inverse() * target.placement.worldFromLocal();
  ProxyOutcome outcome;
  state.tracker[dir].update(query, goal, target.placement.local_center, settings, outcome);
  toWorld(outcome, target, opponent, query, out);
}

}  // namespace
}  // namespace detail

PairTracker::PairTracker() : state_(std::make_unique<detail::PairState>()) {}
PairTracker::~PairTracker() = default;
PairTracker::PairTracker(PairTracker&&) noexcept = default;
PairTracker& PairTracker::operator=(PairTracker&&) noexcept = default;

void PairTracker::update(const GroupView& a, const GroupView& b, Directions directions,
                         const SceneSettings& settings, DirectedResult out[2]) {
  out[0] = DirectedResult();
  out[1] = DirectedResult();
  if (directions.a_target) detail::runDirection(*state_, 0, a, b, settings, out[0]);
  if (directions.b_target) detail::runDirection(*state_, 1, b, a, settings, out[1]);
}

void PairTracker::forget(int direction) { state_->tracker[direction & 1].forget(); }

bool PairTracker::tracking(int direction) const {
  return state_->tracker[direction & 1].tracking();
}

}  // namespace sc
