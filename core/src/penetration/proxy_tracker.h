// SPDX-License-Identifier: MIT
// Dynamic penetration depth of one directed pair (manual 5.4, 8.6): a proxy, the
// last non-penetrating configuration of the target, follows the target's current
// configuration without ever passing through the opponent.
#pragma once

#include <cstdint>
#include <vector>

#include "penetration/travel_budget.h"
#include "penetration/twist_slide.h"
#include "query/group_pair_query.h"
#include "smartcollision/pair_settings.h"

namespace sc::detail {

/// What one update found, in the opponent group's frame.
struct ProxyOutcome {
  ErrorCode code = ErrorCode::NoResult;
  bool penetrating = false;
  double distance = 0.0;     ///< > 0 apart; <= 0 penetrating (-|tpdv|)
  LeafContact contact;       ///< closest pair (apart) or main contact at the contact pose
  Rigid contact_pose;        ///< o_from_t at contact (== goal when apart)
  Vec3 tpdv = Vec3::Zero();  ///< goal centre minus contact centre
  Vec3 rpdv = Vec3::Zero();  ///< rotation vector of R_goal R_contact^T
  int iterations = 0;
  bool lagging = false;  ///< penetrating, but the iterations ran out before the proxy settled
};

/// The depth of `goal` against a proxy at `contact_pose` (centre `center`): fills the
/// outcome's code, penetration vectors, contact pose and distance, and returns true;
/// false, leaving `out` alone, when the goal only touches: no target point (within
/// `size` of the centre) moves farther than the rounding of a pose between the two.
bool reportDepth(const Rigid& goal, const Rigid& contact_pose, const Vec3& center, double size,
                 ProxyOutcome& out);

/// Outline of one update (design.md section 4):
///   1. First sight: intersecting -> InvalidInitialTransformation; else start here.
///   2. Orient the proxy: Input follows the goal's rotation (and turns as in Free,
///      rotation weighted first, when no translation resolves); None keeps the
///      rotation at the impact (the motion from the last free proxy advanced to
///      its first contact); Free and Mix let the
///      proxy turn (twistSlide: a 6-DOF version of step 3).
///   3. Up to max_iterations: collect contacts within the tolerance; solve the QP
///      "closest centre to the goal's centre, every contact's exact separating plane
///      kept at >= skin" (planes from support mappings are exact for convex leaves);
///      move towards its solution by conservative advancement against every other
///      leaf pair, so nothing is passed through. Stop when the step vanishes.
///   4. Report the depth against the planes at zero skin, so it carries no bias
///      (with rotation when the proxy turned: Free, Mix, Input in a wedge).
class ProxyTracker {
 public:
  /// `goal` places the target group in the opponent group's frame; `center` is the
  /// target's centre of rotation in its own group frame.
  void update(GroupPairQuery& query, const Rigid& goal, const Vec3& center,
              const PairSettings& settings, ProxyOutcome& out);
  void forget() { tracking_ = false; }
  /// This update's travel (PairSettings::proxy_travel_ratio): set before update().
  TravelBudget& travel() { return travel_; }
  bool tracking() const { return tracking_; }
  /// Starts tracking with the proxy at `proxy`, a free pose found elsewhere (the
  /// convex fast path: convex_resolution.h), penetrating since this update as after
  /// the general path, or apart (then the proxy is the goal).
  void startAt(const Rigid& proxy, bool penetrating = true) {
    tracking_ = true;
    penetrating_ = penetrating;
    ran_out_ = false;
    proxy_ = proxy;
  }
  /// The proxy (o_from_t) and whether it was penetrating after the last update.
  const Rigid& proxy() const { return proxy_; }
  bool penetrating() const { return penetrating_; }
  /// The first intersecting leaf pair the last update met, when it refused a goal
  /// first seen intersecting (InvalidInitialTransformation).
  const LeafContact& firstIntersecting() const { return first_intersecting_; }

 private:
  struct Row {
    Vec3 normal;
    double offset;  ///< normal . y >= offset (zero skin)
  };
  /// The distance at `goal` into `out`; `sweep_next`: GroupPairQuery::distance's.
  void reportApart(GroupPairQuery& query, const Rigid& goal, const PairSettings& settings,
                   ProxyOutcome& out, bool sweep_next = false);
  /// A free proxy's motion to `goal` (INPUT, NONE) that provably meets nothing within
  /// the skin: the distances at both ends exceed half its length by more than the
  /// skin. Measures the goal into `out` first (`measured`), as a fresh tracker does;
  /// true when that certifies the whole motion, so no sweep is needed.
  bool certifiedFree(GroupPairQuery& query, const Rigid& goal, const Vec3& center,
                     const PairSettings& settings, ProxyOutcome& out, bool& measured);
  /// Called for a free proxy whose contacts the query's kept state no longer reaches
  /// (the first update after a long move), INPUT or NONE: the slide would gather them
  /// anew around it. Instead the goal is measured into `out` (`measured`), as a fresh
  /// tracker does,
  /// and when it is apart by more than the skin the proxy's centre is swept there at
  /// its rotation, which then turns in place (as the slide turns it). True when that
  /// sweep meets nothing: the proxy is at the goal.
  bool sweptFree(GroupPairQuery& query, const Rigid& goal, const Vec3& center,
                 const PairSettings& settings, ProxyOutcome& out, bool& measured);
  /// Steps 2-3 for this update's rotation mode; true when the proxy reached the goal.
  bool follow(GroupPairQuery& query, const Rigid& goal, const Vec3& center,
              const PairSettings& settings, ProxyOutcome& out);
  /// Runs step 3 with the proxy rotation fixed to `rotation`; returns the iterations.
  /// `feasible` is false when the rows admit no translation (the proxy stays stuck).
  int slide(GroupPairQuery& query, const Mat3& rotation, const Vec3& goal_center,
            const Vec3& center, const PairSettings& settings, bool* feasible);
  /// None mode: the pose where the motion from the last free proxy to `goal` first
  /// meets the opponent.
  Rigid impactPose(GroupPairQuery& query, const Rigid& goal, const Vec3& center,
                   const PairSettings& settings);
  /// twistSlide from the proxy; true when it reached the goal.
  bool turn(GroupPairQuery& query, const Rigid& goal, const Vec3& center,
            const PairSettings& settings, ProxyOutcome& out);
  /// Fills `out` from the proxy; false when the goal itself only touches.
  bool reportPenetration(GroupPairQuery& query, const Rigid& goal, const Vec3& center,
                         const PairSettings& settings, ProxyOutcome& out);
  /// Zero-skin projection of the proxy at its rotation (3-D) or with rotation (6-D):
  /// sets the contact pose and the main contact's normal, returns the main contact's
  /// index in contacts_ (-1: none; kGoalTouches: the goal itself keeps every row).
  int projectTranslation(GroupPairQuery& query, const Rigid& goal, const Vec3& center,
                         const PairSettings& settings, Rigid& contact_pose, Vec3& normal);
  int projectTwist(GroupPairQuery& query, const Rigid& goal, const Vec3& center,
                   const PairSettings& settings, Rigid& contact_pose, Vec3& normal);
  static constexpr int kGoalTouches = -2;
  /// contactsNear() at `pose` into contacts_ (within the tolerance, the slide's margin).
  void gatherContacts(GroupPairQuery& query, const Rigid& pose, const PairSettings& settings);
  /// rows_ from contacts_, both at `pose`.
  void buildRows(GroupPairQuery& query, const Rigid& pose);
  /// True when contacts_ and rows_ are those at exactly `pose` (the slide's last
  /// iteration there): the depth's projection need not gather nor build them again.
  bool rowsAt(const Rigid& pose) const {
    return rows_current_ && rows_pose_.rotation == pose.rotation &&
           rows_pose_.translation == pose.translation;
  }
  Vec3 seedNormal(GroupPairQuery& query, const LeafContact& c) const;

  bool tracking_ = false;
  LeafContact first_intersecting_;
  bool penetrating_ = false;
  bool ran_out_ = false;  ///< the last slide or turn used all its iterations
  Rigid proxy_;           ///< o_from_t of the proxy
  Rigid previous_proxy_;  ///< proxy at the start of this update (free)
  std::vector<LeafContact> contacts_;
  std::vector<Row> rows_;
  Rigid rows_pose_;                   ///< where contacts_ and rows_ were last built
  bool rows_current_ = false;         ///< rows_ are those of contacts_ (both at rows_pose_)
  std::vector<LeafPair> skip_;        ///< the current contacts, sorted
  Vec3 touch_normal_ = Vec3::Zero();  ///< main contact's normal when the goal only touches
  /// A free proxy turned to the goal's rotation in place, where the slide starts: a
  /// lower bound of its gap, read before the goal's distance moves the query's bound
  /// there. Above the tolerance the slide's first contacts are none (a jump's start,
  /// whose gathering would be a rebuild far from the kept pairs); else -inf.
  double start_gap_ = -kInfinity;
  TwistScratch twist_;                ///< Free and Mix work arrays
  TravelBudget travel_;
};

}  // namespace sc::detail
