// SPDX-License-Identifier: MIT
// Contact clusters: a pair's row candidates (thousands for two 75k-triangle meshes)
// grouped by normal into a few patches, each reduced to the few points that span it,
// so that each patch keeps a manifold of its own and its rows stay the same from step
// to step.
#pragma once

#include <array>
#include <vector>

#include "smartcollision/types.h"

namespace sc::bullet::detail {

/// A row candidate in the manifold's frame: `normal` from body 1 towards body 0 (unit),
/// `on_b` the point on body 1, `separation` along the normal (< 0 penetrating).
struct RowCandidate {
  Vec3 on_b = Vec3::Zero();
  Vec3 normal = Vec3::UnitY();
  double separation = 0.0;
  bool exact = false;  ///< a corner of a convex piece (a stable vertex), not a leaf contact
  bool corner = false;  ///< a corner of a convex piece, exact or on a face's plane
  /// The body (0 or 1, the manifold's order) the candidate was measured against when
  /// that body is one convex piece, else -1.
  int convex_body = -1;
};

/// Patches per pair, rows per patch: a patch of corners keeps them (up to
/// kClusterPoints; Bullet's manifold keeps the deepest and the widest 4 of them), a
/// patch of leaf contacts gets five rows from its moments (growCluster), its four ends
/// first and its centroid last (the plugin keeps the centroid in a second manifold).
constexpr int kMaxClusters = 4;
constexpr int kClusterPoints = 16;
/// Candidates whose normals are within this cosine (about 25 degrees) share a patch.
constexpr double kClusterCos = 0.9;

struct ContactCluster {
  Vec3 normal = Vec3::UnitY();                      ///< the deepest candidate's normal
  int count = 0;                                    ///< candidates in the patch
  std::array<RowCandidate, kClusterPoints> points;  ///< the patch's rows
  int point_count = 0;
};

/// Groups `candidates` into at most kMaxClusters patches: the deepest candidate seeds
/// the first and takes every candidate whose normal is within kClusterCos of its own
/// and whose point lies within `radius` of its point (two regions of one overlap with
/// close normals are two patches: rows spread over both would stand between them;
/// the corners of a convex piece, its support polygon, stay one patch, and so do
/// regions on one convex body, whose surface spans the space between them: the feet
/// of a body standing on a box, whether the seed or a candidate within `radius` of it
/// was measured against the box), the deepest of the rest seeds the next, and so on. A patch's
/// depth weighs its candidates by exp(-(height above its deepest) / `depth_scale`) (the contact
/// tolerance, > 0). Candidates left when all patches
/// are taken are dropped; returns how many. `labels` is scratch (one per candidate);
/// allocation-free once the vectors have their capacity.
int buildClusters(const std::vector<RowCandidate>& candidates, double radius, double depth_scale,
                  std::vector<int>& labels, std::vector<ContactCluster>& clusters);

}  // namespace sc::bullet::detail
