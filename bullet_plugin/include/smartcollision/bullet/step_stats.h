// SPDX-License-Identifier: MIT
// StepStats: what a collision detection of the plugin saw (metrics and tests).
#pragma once

namespace sc::bullet {

/// What the last collision detection saw (for metrics and tests).
struct StepStats {
  int pairs = 0;              ///< pairs the algorithm ran on
  int penetrating = 0;        ///< directions with a penetration depth
  int recovering = 0;         ///< directions first seen intersecting (AABB push)
  /// largest translational depth [m]: |TPDV| of the results the rows are measured
  /// from (on a non-convex pair in Mix and Free, the Input-mode tracker's: the mode's
  /// own TPDV goes with its RPDV, a turned contact pose's share of the way out)
  double max_depth = 0.0;
  double max_rotation = 0.0;  ///< largest |RPDV| [rad]
  int projected = 0;          ///< directions whose impact was projected to the entry side
  int rows = 0;               ///< contact rows handed to Bullet's solver
  int dropped_rows = 0;       ///< row candidates beyond the patches a pair keeps
  /// directions in contact this step: a row touching, or whose gap closes within the
  /// step at the current approach speed (the rows stop a body at the surface, so an
  /// impact shows here before any penetration does)
  int touching = 0;
  /// pairs not queried: apart at their last query by more than the bodies could have
  /// moved towards each other since (a conservative bound), so nothing can respond
  int skipped = 0;
  /// pairs not queried: in contact, and neither body moved by more than a hundredth of
  /// the tolerance since their last query (a conservative bound), so that query's rows
  /// and figures still hold; they are counted again in the fields above
  int reused = 0;
};

/// Adds one pair's figures to a step's: counts add, largest values take the larger.
void accumulate(StepStats& into, const StepStats& pair);

}  // namespace sc::bullet
