// SPDX-License-Identifier: MIT
#include "penetration/proxy_tracker.h"

#include <algorithm>
#include <cmath>

#include "geometry/math_util.h"
#include "penetration/conservative_advancement.h"
#include "penetration/contact_qp.h"

namespace sc::detail {

namespace {

/// Pose with rotation r whose centre (a point fixed in the target) lands on y.
Rigid poseAt(const Mat3& r, const Vec3& center, const Vec3& y) { return {r, y - r * center}; }

/// Gap the proxy keeps from contacts, so the normals it reads stay well defined.
double skinOf(const PairSettings& s) { return 0.25 * s.tolerance; }
/// contactsNear()'s margin in a slide: wider keeps the pairs over more iterations but
/// evaluates more of them; two tolerances was the fastest of 1, 2 and 4 (haptic bench).
double slideMarginOf(const PairSettings& s) { return 2.0 * s.tolerance; }

/// The least fraction t of `delta` from y at which every row a x >= b - skin holds
/// at y + t delta: every contact free (the rows are linear; 0 when they hold at y, 1
/// when the QP's target, y + delta, is needed).
double rowsHoldFrom(const Eigen::Ref<const MatX>& a, const Eigen::Ref<const VecX>& b, double skin,
                    const Vec3& y, const Vec3& delta) {
  double t = 0.0;
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    t = std::max(t, holdFraction(b[i] - skin - a.row(i).dot(y), a.row(i).dot(delta)));
  return t;
}

/// The longest stretch of a slide step that continues a run of shrinking parallel steps.
constexpr double kMaxStretch = 8.0;

/// Along a curved contact (an edge or a vertex of a leaf, its normal turning as the
/// proxy moves) each QP sees a tangent plane only: the steps run parallel and shrink
/// by a ratio q (a half where the contact meets another at a small angle), so the
/// proxy creeps. When `delta` continues such a run (parallel to `last`, the last step,
/// taken whole, and q in [0.3, 1)), the factor 1 / (1 - q) that sums the series, at
/// most kMaxStretch and past the QP target by at most `reach`; else 1.
double stretchOf(const Vec3& delta, const Vec3& last, double reach) {
  const double dd = delta.norm(), ll = last.norm();
  if (!(dd > 0.0 && ll > 0.0) || delta.dot(last) < 0.99 * dd * ll) return 1.0;
  const double q = dd / ll;
  if (q < 0.3 || q >= 1.0) return 1.0;
  return std::min({1.0 / (1.0 - q), kMaxStretch, 1.0 + reach / dd});
}

/// True when every contact is at least `gap` apart (a kept pair's bound counts).
bool clearOf(const std::vector<LeafContact>& contacts, double gap) {
  for (const LeafContact& c : contacts)
    if (c.intersecting || c.gap < gap) return false;
  return true;
}

}  // namespace

Vec3 ProxyTracker::seedNormal(GroupPairQuery& query, const LeafContact& c) const {
  // The pair intersects at the proxy only because the proxy was re-oriented: its
  // separating direction at the previous (free) proxy is a good exit direction.
  const LeafContact before = query.pairAt(c.t_leaf, c.o_leaf, previous_proxy_);
  if (!before.intersecting) return before.normal;
  const Vec3 t_center = previous_proxy_ * query.targetLeaf(c.t_leaf).center;
  return normalizedOr(t_center - query.opponentLeaf(c.o_leaf).center, Vec3::UnitZ());
}

void ProxyTracker::buildRows(GroupPairQuery& query, const Rigid& pose) {
  rows_.clear();
  for (const LeafContact& c : contacts_) {
    const Vec3 n = c.intersecting ? seedNormal(query, c) : c.normal;
    const double sep = query.separationAlong(c.t_leaf, c.o_leaf, pose, n);
    const Vec3 y = pose.translation;  // rows are written for the pose's translation
    rows_.push_back({n, n.dot(y) - sep});
  }
  rows_pose_ = pose;
  rows_current_ = true;
}

void ProxyTracker::gatherContacts(GroupPairQuery& query, const Rigid& pose,
                                  const PairSettings& settings) {
  query.contactsNear(pose, settings.tolerance, slideMarginOf(settings), contacts_);
  rows_current_ = false;
}

int ProxyTracker::slide(GroupPairQuery& query, const Mat3& rotation, const Vec3& goal_center,
                        const Vec3& center, const PairSettings& settings, bool* feasible) {
  const double skin = skinOf(settings);
  const double size = query.targetSize();  // step thresholds are relative to it
  Vec3 y = proxy_ * center;
  *feasible = true;
  Vec3 last = Vec3::Zero();  // the last QP step, when it was taken whole
  Vec3 certified = y;        // the last QP target reached, when a stretch went past it
  bool stretched = false;
  int k = 0;
  for (; k < settings.max_iterations; ++k) {
    const Rigid pose = poseAt(rotation, center, y);
    // Each iteration moves the proxy a little at one rotation: re-evaluate only the
    // pairs found within a margin while it moves less than that margin.
    if (k == 0 && start_gap_ > settings.tolerance) {
      contacts_.clear();
      rows_current_ = false;
    } else {
      gatherContacts(query, pose, settings);
    }
    start_gap_ = -kInfinity;  // true of this pose only
    if (stretched && !clearOf(contacts_, 0.5 * skin)) {
      // Past its target no row held the stretch: back to the target, which they did.
      y = certified;
      stretched = false;
      last.setZero();
      continue;
    }
    stretched = false;
    buildRows(query, pose);
    // Rows constrain the pose's translation t = y - R c; shift them to y.
    const Vec3 rc = rotation * center;
    const int m = static_cast<int>(rows_.size());
    MatX& a = twist_.slide_a;  // kept arrays: no allocation per iteration
    VecX& b = twist_.slide_b;
    if (a.rows() < m) {
      a.resize(2 * m, 3);
      b.resize(2 * m);
    }
    for (int i = 0; i < m; ++i) {
      a.row(i) = rows_[i].normal.transpose();
      b[i] = rows_[i].offset + rows_[i].normal.dot(rc) + skin;
    }
    QpWork& qp = twist_.slide_qp;
    solveContactQp(goal_center, Vec3::Ones(), a.topRows(m), b.head(m), qp);
    if (!qp.feasible) {  // no translation frees the proxy at this rotation
      *feasible = false;
      break;
    }
    const Vec3 target = qp.z;
    Vec3 delta = target - y;
    if (delta.norm() <= 1e-12 * (size + y.norm())) break;
    // The travel left cuts the step, but never short of where every row holds: the
    // proxy leaves the intersection its turn to the goal's rotation may have made.
    double keep = travel_.share(delta.norm());
    if (keep < 1.0) keep = std::max(keep, rowsHoldFrom(a.topRows(m), b.head(m), skin, y, delta));
    delta *= std::min(keep, 1.0);
    skip_.clear();
    for (const LeafContact& c : contacts_) skip_.push_back({c.t_leaf, c.o_leaf});
    std::sort(skip_.begin(), skip_.end());
    // The rows hold the contacts up to the target; a stretch past it by at most skin / 2
    // keeps them at >= skin / 2 all the way if they are there at its end (the gap is
    // 1-Lipschitz), which the next iteration's contacts check. A cut step is not
    // stretched.
    const double stretch = m > 0 && keep >= 1.0 ? stretchOf(delta, last, 0.5 * skin) : 1.0;
    const double s = stretch * query.translationToi(pose, stretch * delta, skin, skip_);
    travel_.charge(s * delta.norm(), keep < 1.0);
    last = s >= stretch ? delta : Vec3::Zero();
    stretched = s > 1.0;
    certified = target;
    y = s == 1.0 && keep >= 1.0 ? target : Vec3(y + s * delta);
    if (keep < 1.0) {  // held back: the proxy lags and catches up in later updates
      ++k;
      break;
    }
    if (m == 0 && s >= 1.0) {  // reached the goal unobstructed
      ++k;
      break;
    }
  }
  if (stretched) {  // the iterations ran out before a stretch was checked
    gatherContacts(query, poseAt(rotation, center, y), settings);
    if (!clearOf(contacts_, 0.5 * skin)) y = certified;
  }
  proxy_ = poseAt(rotation, center, y);
  return k;
}

void ProxyTracker::reportApart(GroupPairQuery& query, const Rigid& goal,
                               const PairSettings& settings, ProxyOutcome& out, bool sweep_next) {
  out.penetrating = false;
  out.contact_pose = goal;
  out.tpdv.setZero();
  out.rpdv.setZero();
  if (!query.distance(goal, settings.max_distance, out.contact, sweep_next)) {
    out.code = ErrorCode::NoResult;
    return;
  }
  out.code = ErrorCode::Ok;
  out.distance = out.contact.gap;
}

bool ProxyTracker::certifiedFree(GroupPairQuery& query, const Rigid& goal, const Vec3& center,
                                 const PairSettings& settings, ProxyOutcome& out, bool& measured) {
  const RotationMode mode = settings.rotation_mode;
  if (mode != RotationMode::Input && mode != RotationMode::None) return false;
  // The slide turns the proxy to the goal's rotation in place, then translates its
  // centre: the gap there is bounded by the last distance less that turn.
  const Vec3 from = proxy_ * center;
  const double start_gap = start_gap_;
  // Within the tolerance the slide gathers contacts and may not head straight.
  if (!(start_gap > settings.tolerance)) return false;
  // Every point moves |t| along the translation t, and the gap is 1-Lipschitz in it:
  // at fraction s it is at least max(start - s|t|, end - (1 - s)|t|) >=
  // (start + end - |t|) / 2, which must stay above the skin the sweep stops within.
  const double length = (goal * center - from).norm();
  // A move longer than the start gap is likely swept next, from here to the goal.
  reportApart(query, goal, settings, out, length > start_gap);
  measured = true;
  if (out.code != ErrorCode::Ok && out.code != ErrorCode::NoResult) return false;
  const double end_gap = out.code == ErrorCode::Ok ? out.distance : settings.max_distance;
  return start_gap + end_gap - length > 2.0 * skinOf(settings);
}

bool ProxyTracker::sweptFree(GroupPairQuery& query, const Rigid& goal, const Vec3& center,
                             const PairSettings& settings, ProxyOutcome& out, bool& measured) {
  const RotationMode mode = settings.rotation_mode;
  if (mode != RotationMode::Input && mode != RotationMode::None) return false;
  const Vec3 from = proxy_ * center;
  if (!measured) reportApart(query, goal, settings, out);
  measured = true;
  const double skin = skinOf(settings);
  // Within the skin the slide gathers the contacts. (Sweeping to goals free by half the
  // skin to the skin, where the sweep would still reach them, saved that rebuild after
  // a jump but changed a chaotic Bullet pile's rest: docs/benchmarks.md, (d).)
  const bool apart =
      out.code == ErrorCode::NoResult || (out.code == ErrorCode::Ok && out.distance > skin);
  if (!apart) return false;
  // Nothing within skin / 2 along the translation (translationToi), and the goal free.
  skip_.clear();
  if (query.translationToi(proxy_, goal * center - from, skin, skip_) < 1.0) return false;
  // Contacts will be needed here soon: their rebuild runs ahead, a share per update.
  const double gap = out.code == ErrorCode::Ok ? out.distance : settings.max_distance;
  query.rebuildNearAhead(goal, settings.tolerance, slideMarginOf(settings), gap);
  return true;
}

void ProxyTracker::update(GroupPairQuery& query, const Rigid& goal, const Vec3& center,
                          const PairSettings& settings, ProxyOutcome& out) {
  out = ProxyOutcome();
  rows_current_ = false;  // seeded normals follow previous_proxy_, which moves on
  if (!tracking_) {
    if (query.intersects(goal, &first_intersecting_)) {
      out.code = ErrorCode::InvalidInitialTransformation;
      return;
    }
    tracking_ = true;
    penetrating_ = false;
    proxy_ = goal;
    reportApart(query, goal, settings, out);
    return;
  }
  previous_proxy_ = proxy_;
  touch_normal_.setZero();
  bool measured = false;
  // Both read where the slide starts (the proxy turned to the goal's rotation in
  // place), before the goal's measurement moves the last distance: the gap there, and
  // whether the slide would gather its contacts anew (the first update after a long move).
  const Rigid turned = poseAt(goal.rotation, center, proxy_ * center);
  start_gap_ = penetrating_ ? -kInfinity : query.distanceLowerBound(turned);
  const bool reentry = !penetrating_ && !query.nearReaches(turned, settings.tolerance);
  if (!penetrating_ && (certifiedFree(query, goal, center, settings, out, measured) ||
                        (reentry && sweptFree(query, goal, center, settings, out, measured)))) {
    proxy_ = goal;  // where the slide's one unobstructed sweep would have put it
    ran_out_ = false;
    out.iterations = 1;
    return;
  }
  // A proxy stopped short of a free goal still reports a depth: the goal was reached
  // through the opponent (a thin wall), or the proxy lags and catches up later.
  const bool reached = follow(query, goal, center, settings, out);
  if (reached || !reportPenetration(query, goal, center, settings, out)) {
    penetrating_ = false;
    proxy_ = goal;
    if (!measured) reportApart(query, goal, settings, out);
    // A goal that only touches has no normal of its own (its closest points
    // coincide): keep the one of the contact the proxy rested on.
    if (out.code == ErrorCode::Ok && out.distance <= 0.0 && !touch_normal_.isZero(0.0))
      out.contact.normal = touch_normal_;
    return;
  }
  penetrating_ = true;
}

bool ProxyTracker::follow(GroupPairQuery& query, const Rigid& goal, const Vec3& center,
                          const PairSettings& settings, ProxyOutcome& out) {
  const RotationMode mode = settings.rotation_mode;
  if (mode == RotationMode::Free || mode == RotationMode::Mix)
    return turn(query, goal, center, settings, out);
  const Vec3 goal_center = goal * center;
  // None keeps the orientation at the impact while the penetration lasts: a goal free
  // itself ends it, and the proxy follows the goal's orientation as Input's does (else
  // a body turned while pressed in, then lifted away, reported the turn as a depth at
  // every later update).
  const bool freeze = mode == RotationMode::None && penetrating_ && query.intersects(goal);
  const Mat3 rotation = freeze ? previous_proxy_.rotation : goal.rotation;
  bool feasible = true;
  const TravelBudget travel = travel_;  // for a turn from the last free proxy
  out.iterations = slide(query, rotation, goal_center, center, settings, &feasible);
  ran_out_ = out.iterations >= settings.max_iterations || travel_.spent;
  // An infeasible slide left the proxy intersecting: even at the goal it has not
  // reached a free pose. The slide writes its pose as a centre and a rotation, which
  // rounds: within that rounding the proxy is at the goal (else NONE would freeze its
  // orientation at a free goal).
  const bool reached = feasible && rotation == goal.rotation &&
                       (proxy_ * center - goal_center).norm() <=
                           1e-12 * (query.targetSize() + goal_center.norm() + center.norm());
  if (reached) proxy_ = goal;
  if (!reached && mode == RotationMode::None && !penetrating_) {
    // Penetration began in this update: None keeps the orientation at the impact.
    proxy_ = impactPose(query, goal, center, settings);
    const int used = slide(query, proxy_.rotation, goal_center, center, settings, &feasible);
    ran_out_ = used >= settings.max_iterations || travel_.spent;
    out.iterations += used;
  } else if (!feasible && mode == RotationMode::Input) {
    // No translation resolves (manual Fig. 5-11): Input turns too, rotation weighted
    // far above translation, from the last free proxy.
    proxy_ = previous_proxy_;
    travel_ = travel;
    const int used = out.iterations;
    const bool turned_to_goal = turn(query, goal, center, settings, out);
    out.iterations += used;
    return turned_to_goal;
  }
  return reached;
}

Rigid ProxyTracker::impactPose(GroupPairQuery& query, const Rigid& goal, const Vec3& center,
                               const PairSettings& settings) {
  // The input's motion from the last free proxy, translation and rotation together,
  // advanced to its first contact (within the skin): the pose at the time of impact.
  TwistMotion motion;
  motion.start = previous_proxy_;
  motion.center = center;
  motion.dc = goal * center - previous_proxy_ * center;
  // No turn at all is exactly none: R R^T rounds, and the impact's rotation would then
  // differ from the goal's by ~1e-17 rad at every later update.
  motion.dtheta = goal.rotation == previous_proxy_.rotation
                      ? Vec3::Zero()
                      : rotationVector(goal.rotation * previous_proxy_.rotation.transpose());
  skip_.clear();
  const double s =
      advance(query, motion, skinOf(settings), skip_, twist_.candidates, slideMarginOf(settings));
  return motion.at(s);
}

bool ProxyTracker::turn(GroupPairQuery& query, const Rigid& goal, const Vec3& center,
                        const PairSettings& settings, ProxyOutcome& out) {
  const TwistSlideResult slid = twistSlide(query, proxy_, goal, center, previous_proxy_, settings,
                                           skinOf(settings), twist_, travel_);
  out.iterations = slid.iterations;
  ran_out_ = slid.blocked || slid.iterations >= settings.max_iterations || travel_.spent;
  return proxy_.rotation == goal.rotation && proxy_.translation == goal.translation;
}

bool reportDepth(const Rigid& goal, const Rigid& contact_pose, const Vec3& center, double size,
                 ProxyOutcome& out) {
  const Vec3 goal_center = goal * center;
  const Vec3 tpdv = goal_center - contact_pose * center;
  // Exactly zero when the proxy follows the goal's rotation (Input mode).
  const Vec3 rpdv = contact_pose.rotation == goal.rotation
                        ? Vec3::Zero()
                        : rotationVector(goal.rotation * contact_pose.rotation.transpose());
  // A proxy at the goal's centre whose rotation, written again (a twist's in Free and
  // Mix), differs from the goal's by rounding alone (~1e-17 rad) has no depth: else a
  // pair lifted apart after a contact reported one at every later update.
  const double rounding = 1e-12 * (size + goal_center.norm() + center.norm());
  if (tpdv.isZero(0.0) && rpdv.norm() * size <= rounding) return false;
  out.code = ErrorCode::Ok;
  out.penetrating = true;
  out.contact_pose = contact_pose;
  out.tpdv = tpdv;
  out.rpdv = rpdv;
  out.distance = -tpdv.norm();
  return true;
}

bool ProxyTracker::reportPenetration(GroupPairQuery& query, const Rigid& goal, const Vec3& center,
                                     const PairSettings& settings, ProxyOutcome& out) {
  // Depth against the exact planes (zero skin): unbiased by the skin. A proxy that
  // turned is projected with rotation too, or the skin would stay in its RPDV.
  // A slide that stopped here gathered them here last (the query's memo would
  // answer the same).
  if (!rowsAt(proxy_)) gatherContacts(query, proxy_, settings);
  const bool turned =
      settings.rotation_mode != RotationMode::None && proxy_.rotation != goal.rotation;
  Rigid contact_pose = proxy_;
  Vec3 normal = Vec3::UnitZ();
  const int main = turned ? projectTwist(query, goal, center, settings, contact_pose, normal)
                          : projectTranslation(query, goal, center, settings, contact_pose, normal);
  if (main == kGoalTouches) return false;
  if (!reportDepth(goal, contact_pose, center, query.targetSize(), out)) {  // only touches
    if (main >= 0) touch_normal_ = normal;
    return false;
  }
  // A turned proxy held a skin away, its goal free: the projection's rows are linear
  // in the turn, so a goal just out of contact could keep the proxy turned away from
  // it, a rotational depth, for as long as it stayed within the skin. A free goal
  // whose depth moves no point farther than the tolerance only touches: no wall
  // thinner than the tolerance is resolved.
  if (turned && query.displacementBound(contact_pose, goal) <= settings.tolerance &&
      !query.intersects(goal)) {
    if (main >= 0) touch_normal_ = normal;
    return false;
  }
  out.lagging = ran_out_ || main < 0;
  if (main >= 0) {
    out.contact = contacts_[main];
    out.contact.normal = normal;
  } else {
    // The proxy lags (iterations ran out) with nothing within the tolerance: its
    // closest pair still names where the contact will be.
    query.distance(proxy_, kInfinity, out.contact);
  }
  out.contact.point_t = contact_pose * (proxy_.inverse() * out.contact.point_t);
  return true;
}

int ProxyTracker::projectTranslation(GroupPairQuery& query, const Rigid& goal, const Vec3& center,
                                     const PairSettings& settings, Rigid& contact_pose,
                                     Vec3& normal) {
  const Vec3 y = proxy_ * center;
  if (!rowsAt(proxy_)) buildRows(query, proxy_);  // else the slide's last, at this pose
  const Vec3 rc = proxy_.rotation * center;
  const int m = static_cast<int>(rows_.size());
  MatX& a = twist_.slide_a;  // the slide's kept arrays: no allocation per report
  VecX& b = twist_.slide_b;
  if (a.rows() < m) {
    a.resize(2 * m, 3);
    b.resize(2 * m);
  }
  for (int i = 0; i < m; ++i) {
    a.row(i) = rows_[i].normal.transpose();
    b[i] = rows_[i].offset + rows_[i].normal.dot(rc);
  }
  QpWork& qp = twist_.slide_qp;
  solveContactQp(goal * center, Vec3::Ones(), a.topRows(m), b.head(m), qp);
  if (qp.feasible && (Vec3(qp.z) - y).norm() <= settings.tolerance)
    contact_pose = poseAt(proxy_.rotation, center, qp.z);
  // Main contact: the most loaded row, else the first.
  int main = -1;
  for (int i = 0; i < m; ++i)
    if (main < 0 || (qp.feasible && qp.lambda[i] > qp.lambda[main])) main = i;
  if (main >= 0) normal = rows_[main].normal;
  return main;
}

int ProxyTracker::projectTwist(GroupPairQuery& query, const Rigid& goal, const Vec3& center,
                               const PairSettings& settings, Rigid& contact_pose, Vec3& normal) {
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  const Vec3 y = proxy_ * center;
  buildContactPatches(query, proxy_, contacts_, previous_proxy_, twist_.patches);
  Vec6 target;
  target << goal * center - y, rotationVector(goal.rotation * proxy_.rotation.transpose());
  const double rho = targetRadius(query, center);
  solvePatchQp(twist_.patches, y, target, twistWeights(settings, rho), 0.0, settings.tolerance,
               twist_.qp);
  const QpWork& qp = twist_.qp.qp;
  // Only a step within the tolerance: the rows are linear in rotation.
  const Vec6 z = qp.feasible ? Vec6(qp.z) : Vec6::Zero();
  if (!twist_.patches.empty() && qp.feasible &&
      z.head<3>().norm() + z.tail<3>().norm() * rho <= settings.tolerance) {
    if (z == target) return kGoalTouches;  // every row holds at the goal itself
    contact_pose =
        poseAt(rotationFromVector(z.tail<3>()) * proxy_.rotation, center, y + z.head<3>());
  }
  if (twist_.patches.empty()) return -1;
  // Main contact: the most loaded row (of the working set: the others carry none),
  // else the first contact.
  int main = -1;
  double load = 0.0;
  for (std::size_t i = 0; qp.feasible && i < qp.lambda.size(); ++i) {
    if (qp.lambda[i] > load) {
      load = qp.lambda[i];
      main = static_cast<int>(i);
    }
  }
  if (main < 0) {
    normal = twist_.patches.front().normal;
    return twist_.patches.front().contact;
  }
  normal = twist_.qp.rows[static_cast<std::size_t>(main)].normal;
  return twist_.qp.rows[static_cast<std::size_t>(main)].contact;
}

}  // namespace sc::detail
