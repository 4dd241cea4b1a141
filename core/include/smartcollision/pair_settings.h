// SPDX-License-Identifier: MIT
// What one pair's update needs: reach, tolerance, proxy iterations and the rotation
// mode. A scene's settings add how it finds and runs its pairs (settings.h).
#pragma once

#include "smartcollision/types.h"

namespace sc {

/// Default of PairSettings::tolerance (model units).
inline constexpr double kDefaultTolerance = 1e-3;
/// Floor of the tolerance: a pair's tolerance is raised to kMinRelativeTolerance x
/// sqrt(r (r + d)), r the target's radius and d its centre's distance from the
/// opponent's origin; below it, rounding of the coordinates tilts contact normals
/// enough to move the contact configuration by more than the tolerance.
inline constexpr double kMinRelativeTolerance = 1e-7;
/// Default of PairSettings::safety_coefficient; the manual says not to change it.
inline constexpr double kDefaultSafetyCoefficient = 0.49;
/// Default of PairSettings::max_iterations.
inline constexpr int kDefaultMaxIterations = 30;

struct PairSettings {
  /// Pairs whose distance exceeds this report NoResult (model units; +inf = all pairs).
  double max_distance = kInfinity;
  /// Accuracy of the dynamic penetration depth: the contact configuration penetrates
  /// by at most about this and lies within about this of touching (model units, > 0;
  /// an absolute length, raised per pair to its floor kMinRelativeTolerance).
  double tolerance = kDefaultTolerance;
  /// Fraction of the tolerance a rotational step of the proxy may move a point (0, 1).
  double safety_coefficient = kDefaultSafetyCoefficient;
  /// Proxy iterations per update and direction (>= 1).
  int max_iterations = kDefaultMaxIterations;
  RotationMode rotation_mode = RotationMode::Input;
  /// kT of manual (5-3) and (5-5), used by RotationMode::Mix (force per model unit, > 0).
  double force_stiffness = 1.0;
  /// kR of manual (5-4) and (5-5), used by RotationMode::Mix (torque per radian, > 0).
  double torque_stiffness = 1.0;
  /// A direction first seen intersecting starts from a nearby free pose (and reports
  /// that depth) instead of reporting InvalidInitialTransformation: the exact global
  /// depth of a convex pair; for a non-convex one, the exits of its intersecting convex
  /// leaves, or for a deep overlap the shortest sweep in from outside (an upper bound;
  /// docs/api.md, "Initial intersection"). Off by default, as in the manual.
  bool resolve_initial_intersection = false;
  /// A motion of the target relative to the opponent that moves some target point
  /// farther than this between two updates of a direction is a teleport: the
  /// direction starts again at the new pose as a fresh tracker would (distance apart;
  /// intersecting, InvalidInitialTransformation or the resolved depth) instead of
  /// following a path to it (model units, > 0). +inf, the default: every motion is a
  /// path, and nothing passes through however far one update goes.
  double teleport_distance = kInfinity;
  /// In one update the proxy (the contact configuration) moves no point farther than
  /// this many times the target's farthest-moving point did since the last update
  /// (>= 1; in Input and None modes the proxy's turn follows the target's and only
  /// its translation counts). +inf, the default: the proxy settles at its local
  /// minimum in every update, and where that minimum moves faster than the target
  /// (round a facet, off a local minimum past a convex edge) the TPDV changes by up to
  /// the depth at once. A haptic loop that wants continuous forces sets 2: the TPDV
  /// then changes by at most about 3x the target's step, and a proxy held back
  /// reports DirectionStatus::Lagging until it has caught up.
  double proxy_travel_ratio = kInfinity;
};

/// Ok, or InvalidArgument naming the first field out of range.
SC_API Status validate(const PairSettings& settings);

}  // namespace sc
