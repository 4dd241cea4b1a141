// SPDX-License-Identifier: MIT
// Closest points of two convex polytopes by GJK with warm start.
#pragma once

#include <cstdint>

#include "geometry/convex_polytope.h"

namespace sc::detail {

/// Warm start: the vertex pairs of the previous final simplex and the support
/// hints. Default-constructed = cold start. In/out; one per polytope pair.
struct SimplexCache {
  int count = 0;
  int a[4] = {0, 0, 0, 0};
  int b[4] = {0, 0, 0, 0};
  int hint_a = 0;
  int hint_b = 0;
};

enum class GjkStatus : std::uint8_t {
  Separated,          ///< distance > 0; every field valid
  Intersecting,       ///< the polytopes overlap or touch (distance 0); points unset
  BeyondMaxDistance,  ///< lower_bound > max_distance; only lower_bound valid
  WithinDistance,     ///< distance <= within_distance (an upper bound); only the bounds valid
  NotConverged,       ///< iteration cap; fields hold the best finite estimate
};

struct GjkSettings {
  double max_distance = kInfinity;  ///< stop once the lower bound exceeds this
  /// Stop once the distance is known to be at most this (a traversal that only asks
  /// whether two hulls are within a reach needs no more); negative: never.
  double within_distance = -1.0;
  /// A's translation relative to B (common frame). With `motion_clearance` finite:
  /// stop as BeyondMaxDistance, too, once a separating plane is found that keeps A
  /// farther than that from B while it translates by any part of `motion` (a sweep
  /// asks no more of a pair moving along its plane).
  Vec3 motion = Vec3::Zero();
  double motion_clearance = kInfinity;
  int max_iterations = 128;
};

struct GjkResult {
  GjkStatus status = GjkStatus::BeyondMaxDistance;
  double distance = 0.0;        ///< >= 0
  double lower_bound = 0.0;     ///< <= true distance, always valid
  Vec3 point_a = Vec3::Zero();  ///< on A, in the common frame
  Vec3 point_b = Vec3::Zero();  ///< on B, in the common frame
  Vec3 normal = Vec3::UnitX();  ///< unit, from B towards A: (point_a - point_b) / distance
  /// Final simplex: vertex indices (into ConvexPolytope::vertices) on A and B.
  int count = 0;
  int a[4] = {-1, -1, -1, -1};
  int b[4] = {-1, -1, -1, -1};
  int iterations = 0;
};

/// Minimum distance between A and B placed in a common frame.
/// Based on: G. van den Bergen, "A Fast and Robust GJK Implementation for Collision
/// Detection of Convex Objects", JGT 1999, with the signed-volumes sub-algorithm of
/// Montanari, Petrinic, Barbieri, "Improving the GJK algorithm for faster and more
/// reliable distance queries between convex objects", ACM TOG 2017.
/// Exact up to rounding on polytopes: terminates when no support point improves.
/// Allocates nothing; thread-safe for distinct caches.
GjkResult gjkDistance(const ConvexPolytope& a, const Rigid& frame_from_a, const ConvexPolytope& b,
                      const Rigid& frame_from_b, const GjkSettings& settings, SimplexCache& cache);

}  // namespace sc::detail
