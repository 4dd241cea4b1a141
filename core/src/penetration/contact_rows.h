// SPDX-License-Identifier: MIT
// Linearised non-penetration constraints of the proxy: one row per contact within
// the tolerance, with an exact separating plane (support mappings of convex leaves).
#pragma once

#include <vector>

#include "penetration/contact_qp.h"
#include "query/group_pair_query.h"

namespace sc::detail {

struct ContactRow {
  Vec3 normal = Vec3::UnitZ();  ///< unit, opponent towards target (opponent frame)
  Vec3 lever = Vec3::Zero();    ///< contact point on the target minus the target's centre
  double gap = 0.0;             ///< separation along `normal` at the pose, at `lever`
  int contact = -1;             ///< index into the contact list
};

/// Exit direction of a leaf pair that intersects at the proxy only because the
/// proxy was re-oriented (or the opponent changed): its separating direction at the
/// previous, free proxy; else the direction between the leaves' centres.
Vec3 exitNormal(GroupPairQuery& query, const LeafContact& c, const Rigid& previous_proxy);

/// Rows for `contacts` at `pose`; `center_at_pose` is the target's centre (opponent
/// frame). For a twist (dc, dtheta) about that centre the gap changes by about
/// normal . dc + (lever x normal) . dtheta. Each contact gives one row per vertex of
/// the target leaf within `near` of its supporting plane (its lowest along the
/// normal), so a face or edge contact constrains rotation about every corner.
void buildContactRows(GroupPairQuery& query, const Rigid& pose, const Vec3& center_at_pose,
                      const std::vector<LeafContact>& contacts, const Rigid& previous_proxy,
                      std::vector<ContactRow>& rows, double near);

/// One contact's rows of buildContactRows kept implicit. A vertex v's row has, at a
/// twist (dc, dtheta), the slack n . dc + (p_v - y) . (n x dtheta) + gap_v - skin,
/// affine in v: the most violated row is a support query on the leaf.
struct ContactPatch {
  Vec3 normal = Vec3::UnitZ();  ///< unit, opponent frame
  double gap = 0.0;             ///< separation along `normal` at the lowest vertex
  Rigid o_from_leaf;
  Vec3 leaf_normal = Vec3::UnitZ();  ///< `normal` in the leaf's frame
  double lowest = 0.0;               ///< min over the leaf's vertices of leaf_normal . v
  const ConvexPolytope* poly = nullptr;
  Vec3 center = Vec3::Zero();  ///< the leaf's bounding sphere, opponent frame
  double radius = 0.0;
  int contact = -1;  ///< index into the contact list
  mutable int hint = 0;
};

/// The patches of `contacts` at `pose` (normals and gaps as buildContactRows).
void buildContactPatches(GroupPairQuery& query, const Rigid& pose,
                         const std::vector<LeafContact>& contacts, const Rigid& previous_proxy,
                         std::vector<ContactPatch>& patches);

/// Work arrays of solvePatchQp, kept between calls.
struct PatchQpWork {
  QpWork qp;                             ///< the answer: qp.feasible, qp.z, qp.lambda per row
  std::vector<ContactRow> rows;          ///< the working set's rows
  std::vector<std::pair<int, int>> ids;  ///< their (patch, vertex)
  std::vector<int> near_list;            ///< vertices near each patch's plane, listed lazily
  std::vector<std::pair<int, int>> near_range;  ///< per patch: its part of near_list, or -1
};

/// The twist QP min 1/2 (z - goal)^T W (z - goal) over every row of the patches
/// (those of buildContactRows with `near`, at gap >= skin, centre y), solved on a
/// working set: each round adds every patch's most violated row, found by a support
/// query, so a solve is accepted only when no row of any patch is violated (exact,
/// without building the rows). Same answer as solveContactQp on all the rows.
void solvePatchQp(const std::vector<ContactPatch>& patches, const Vec3& y,
                  const Eigen::Matrix<double, 6, 1>& goal,
                  const Eigen::Matrix<double, 6, 1>& weights, double skin, double near,
                  PatchQpWork& work);

}  // namespace sc::detail
