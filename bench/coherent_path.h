// SPDX-License-Identifier: MIT
// The coherent distance path of bench/mesh_distance.cpp (issue 3a and, at a haptic
// rate, issue 19), shared with bench/warm_jump.cpp, which adds jumps to it.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "sc_support/stats.h"
#include "smartcollision/smartcollision.h"

namespace sc_bench {

struct CoherentPathSpec {
  unsigned seed = 42;
  double step_angle = 0.003;  ///< radians per step, of the orbit and of the body
  int steps = 2000;
  double start_offset = 1.0;  ///< the target's centre starts this far out, then approaches
  int jump_every = 0;         ///< > 0: every this many steps the orbit jumps ahead ...
  double jump = 0.0;          ///< ... by this length along it (model units)
};

/// The target orbits the opponent's centre and turns; it backs off along the last
/// contact normal when a turn brings it closer than 1e-3, and slides towards the
/// opponent's centre by at most 0.005 x step_angle / 0.003 per step towards a gap
/// breathing in [2, 20] mm (the distance is 1-Lipschitz, so a slide of d - gap never
/// reaches contact): small steps even where a contact slips away. `cold(pose)` is a
/// fresh tracker's result there (code not Ok or distance < 0 when intersecting).
template <class Cold>
std::vector<sc::Rigid> coherentPath(const CoherentPathSpec& spec, Cold cold) {
  std::mt19937_64 rng(spec.seed);
  const sc::Quat q0 = sc::support::randomRotation(rng);
  const sc::Vec3 u0 = sc::support::randomDirection(rng);
  const sc::Vec3 body_axis = sc::support::randomDirection(rng);
  const sc::Vec3 orbit_axis = u0.cross(sc::support::randomDirection(rng)).normalized();
  constexpr double kMinGap = 1e-3, kBackOff = 0.002;
  const double max_slide = 0.005 * spec.step_angle / 0.003;
  sc::Vec3 t = spec.start_offset * u0, normal = u0;
  for (int it = 0; it < 40; ++it) {  // start near contact
    const sc::DirectedResult r = cold(sc::Rigid{q0.toRotationMatrix(), t});
    if (r.distance < 0.01) break;
    t -= (r.distance - 0.005) * t.normalized();
  }
  std::vector<sc::Rigid> path;
  for (int k = 0; k < spec.steps; ++k) {
    const sc::Quat q = sc::Quat(Eigen::AngleAxisd(spec.step_angle * k, body_axis)) * q0;
    const sc::Mat3 rotation = q.toRotationMatrix();
    const double gap = 0.002 * std::pow(10.0, 0.5 + 0.5 * std::sin(2.0 * M_PI * k / 400.0));
    const bool jumps = spec.jump_every > 0 && k > 0 && k % spec.jump_every == 0;
    const double angle = spec.step_angle + (jumps ? spec.jump / t.norm() : 0.0);
    if (k > 0) t = Eigen::AngleAxisd(angle, orbit_axis) * t;
    sc::DirectedResult r = cold(sc::Rigid{rotation, t});
    for (int it = 0; r.code != sc::ErrorCode::Ok || r.distance < kMinGap; ++it) {
      t += kBackOff * (it < 20 ? normal : t.normalized());
      r = cold(sc::Rigid{rotation, t});
    }
    double slide_left = max_slide;
    for (int it = 0; it < 3; ++it) {
      const double slide = std::min(r.distance - gap, slide_left);
      if (slide < 1e-6) break;
      t -= slide * t.normalized();
      slide_left -= slide;
      r = cold(sc::Rigid{rotation, t});
    }
    normal = r.normal;
    path.push_back(sc::Rigid{rotation, t});
  }
  return path;
}

}  // namespace sc_bench
