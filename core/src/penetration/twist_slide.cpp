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

int twistSlide(GroupPairQuery& query, Rigid& proxy, const Rigid& goal, const Vec3& center,
               const Rigid& previous_proxy, const PairSettings& settings, double skin,
               TwistScratch& scratch) {
  const double rho = targetRadius(query, center);
  const Vec6 weights = twistWeights(settings, rho);
  const double cap = settings.safety_coefficient * settings.tolerance;
  const Vec3 goal_center = goal * center;
  const double margin = 2.0 * settings.tolerance;  // contactsNear's, as the translation slide
  int k = 0;
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
    if (contact && turn > cap) z *= cap / turn;  // a shorter step; advancement keeps it safe
    if (z.head<3>().norm() + z.tail<3>().norm() * rho <= 1e-12 * (rho + y.norm())) break;
    TwistMotion motion;
    motion.start = proxy;
    motion.center = center;
    motion.dc = z.head<3>();
    motion.dtheta = z.tail<3>();
    scratch.skip.clear();
    const double s = advance(query, motion, 0.5 * skin, scratch.skip, scratch.candidates, margin);
    if (!contact && s >= 1.0 && z == target) {  // reached the goal unobstructed
      proxy = goal;
      ++k;
      break;
    }
    proxy = motion.at(s);
  }
  return k;
}

}  // namespace sc::detail
