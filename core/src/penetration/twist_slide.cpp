// SPDX-License-Identifier: MIT
#include "penetration/twist_slide.h"

#include <algorithm>
#include <cmath>

#include "geometry/math_util.h"
#include "penetration/contact_qp.h"

namespace sc::detail {

using Vec6 = Eigen::Matrix<double, 6, 1>;

Vec6 twistWeights(const PairSettings& settings, double rho) {
  Vec6 w;
  if (settings.rotation_mode == RotationMode::Mix) {
    w << Vec3::Constant(settings.force_stiffness), Vec3::Constant(settings.torque_stiffness);
  } else if (settings.rotation_mode == RotationMode::Input) {
    // Input turns only when no translation resolves: rotation first.
    const double r2 = std::max(rho * rho, 1e-300);
    w << Vec3::Constant(1.0), Vec3::Constant(1e6 * r2);
  } else {
    const double r2 = std::max(rho * rho, 1e-300);
    w << Vec3::Constant(1.0), Vec3::Constant(1e-6 * r2);
  }
  return w;
}

double targetRadius(const GroupPairQuery& query, const Vec3& center) {
  double rho = 0.0;
  for (const Leaf& leaf : query.targetLeaves())
    rho = std::max(rho, (leaf.center - center).norm() + leaf.radius);
  return rho;
}

namespace {

/// A step in contact that brings the proxy nearer the goal by less than this fraction
/// of the tolerance, in translation and in rotation (at radius rho), ends the slide.
constexpr double kProgressStop = 1e-4;
/// The longest stretch of a step that continues a run of shrinking parallel steps.
constexpr double kMaxStretch = 8.0;

/// The QP's twist turns farther than `scale` of it may: turn by that part and solve
/// again for the translation at that turn (held by a rotation weight far above the
/// translation's, as Input's), so the translation goes as far as the rows allow there.
/// Scaling the whole twist moved the translation by ~1e-5 per iteration when FREE's
/// nearly free rotation asked for turns hundreds of caps long. No point at that turn:
/// the scaled twist.
Vec6 cappedTwist(TwistScratch& scratch, const Vec3& y, const Vec6& target, const Vec6& z,
                 double scale, double rho, double skin, double near) {
  Vec6 pinned, weights;
  pinned << target.head<3>(), scale * z.tail<3>();
  weights << Vec3::Ones(), Vec3::Constant(1e6 * std::max(rho * rho, 1e-300));
  solvePatchQp(scratch.patches, y, pinned, weights, skin, near, scratch.qp);
  return scratch.qp.qp.feasible ? Vec6(scratch.qp.qp.z) : Vec6(scale * z);
}

/// The farthest point motion of the twist z (translation + turn at radius rho).
double pointTravel(const Vec6& z, double rho) {
  return z.head<3>().norm() + z.tail<3>().norm() * rho;
}

/// How far the step `z` brings the proxy nearer the goal twist `target`: the larger
/// of the gains in translation and in rotation (at radius rho).
double progress(const Vec6& target, const Vec6& z, double rho) {
  const Vec6 rest = target - z;
  const double translation = target.head<3>().norm() - rest.head<3>().norm();
  const double rotation = (target.tail<3>().norm() - rest.tail<3>().norm()) * rho;
  return std::max(translation, rotation);
}

/// Along a curved contact each QP sees only part of the way (its rows are tangent
/// planes): the steps run parallel and shrink by a ratio q, so the proxy creeps. When
/// `z` continues such a run (parallel to the last step, which was taken whole, and
/// q in [0.3, 1)), the factor 1 / (1 - q) that sums the series, at most kMaxStretch;
/// else 1. Conservative advancement keeps the longer step safe; the next QP corrects it.
double stretchOf(const Vec6& z, const Vec6& last, double rho) {
  const double r2 = rho * rho;
  const double zz = z.head<3>().squaredNorm() + r2 * z.tail<3>().squaredNorm();
  const double ll = last.head<3>().squaredNorm() + r2 * last.tail<3>().squaredNorm();
  const double zl = z.head<3>().dot(last.head<3>()) + r2 * z.tail<3>().dot(last.tail<3>());
  if (!(zz > 0.0 && ll > 0.0) || zl < 0.99 * std::sqrt(zz * ll)) return 1.0;
  const double q = std::sqrt(zz / ll);
  return q >= 0.3 && q < 1.0 ? std::min(1.0 / (1.0 - q), kMaxStretch) : 1.0;
}

}  // namespace

TwistSlideResult twistSlide(GroupPairQuery& query, Rigid& proxy, const Rigid& goal,
                            const Vec3& center, const Rigid& previous_proxy,
                            const PairSettings& settings, double skin, TwistScratch& scratch,
                            TravelBudget& travel) {
  const double rho = targetRadius(query, center);
  const Vec6 weights = twistWeights(settings, rho);
  const double cap = settings.safety_coefficient * settings.tolerance;
  const Vec3 goal_center = goal * center;
  const double margin = 2.0 * settings.tolerance;  // contactsNear's, as the translation slide
  TwistSlideResult out;
  Vec6 last = Vec6::Zero();  // the last QP step, when it was taken whole
  int& k = out.iterations;
  for (; k < settings.max_iterations; ++k) {
    const Vec3 y = proxy * center;
    // Each iteration turns and moves the proxy a little: re-evaluate only the pairs
    // found within a margin while it moves less than that (as the translation slide).
    query.contactsNear(proxy, settings.tolerance, margin, scratch.contacts);
    buildContactPatches(query, proxy, scratch.contacts, previous_proxy, scratch.patches);
    const bool contact = !scratch.patches.empty();
    Vec6 target;
    target << goal_center - y, rotationVector(goal.rotation * proxy.rotation.transpose());
    solvePatchQp(scratch.patches, y, target, weights, skin, settings.tolerance, scratch.qp);
    if (!scratch.qp.qp.feasible) break;
    Vec6 z = scratch.qp.qp.z;
    const double turn = z.tail<3>().norm() * rho;
    if (contact && turn > cap)
      z = cappedTwist(scratch, y, target, z, cap / turn, rho, skin, settings.tolerance);
    if (z.head<3>().norm() + z.tail<3>().norm() * rho <= 1e-12 * (rho + y.norm())) break;
    // Converged: the rest of the way is below the tolerance's resolution.
    if (contact && progress(target, z, rho) <= kProgressStop * settings.tolerance) break;
    const Vec6 step = z;
    if (contact) {
      z *= stretchOf(z, last, rho);
      const double stretched_turn = z.tail<3>().norm() * rho;
      if (stretched_turn > cap) z *= cap / stretched_turn;
    }
    // Cut to the travel left before the sweep (a shorter one costs less).
    const double keep = travel.share(pointTravel(z, rho));
    z *= std::min(keep, 1.0);
    TwistMotion motion;
    motion.start = proxy;
    motion.center = center;
    motion.dc = z.head<3>();
    motion.dtheta = z.tail<3>();
    scratch.skip.clear();
    double s = advance(query, motion, 0.5 * skin, scratch.skip, scratch.candidates, margin);
    bool continues = true;  // the step taken is the QP's (a run may go on from it)
    if (s <= 0.0 && contact && !z.tail<3>().isZero(0.0)) {
      continues = false;
      // Blocked at once: a pair nearer than the skin that the turn may close (the
      // advancement's bound counts the turn at the leaf's whole radius). The
      // translation alone, at no turn, opens it provably.
      z = cappedTwist(scratch, y, target, z, 0.0, rho, skin, settings.tolerance);
      z *= std::min(travel.share(pointTravel(z, rho)), 1.0);
      motion.dc = z.head<3>();
      motion.dtheta = z.tail<3>();
      s = advance(query, motion, 0.5 * skin, scratch.skip, scratch.candidates, margin);
    }
    travel.charge(std::min(s, 1.0) * pointTravel(z, rho), keep < 1.0);
    if (keep < 1.0) {  // held back: the proxy lags and catches up in later updates
      proxy = motion.at(std::max(s, 0.0));
      ++k;
      break;
    }
    if (!contact && s >= 1.0 && z == target) {  // reached the goal unobstructed
      proxy = goal;
      ++k;
      break;
    }
    if (s <= 0.0) {  // blocked where it stands: every further iteration would be this one
      ++k;
      out.blocked = true;
      break;
    }
    proxy = motion.at(s);
    last = continues && s >= 1.0 ? step : Vec6::Zero();
  }
  return out;
}

}  // namespace sc::detail
