// SPDX-License-Identifier: MIT
// The proxy step with rotation free (rotation modes Free and Mix): one 6-DOF QP
// per iteration over the twist (dc, dtheta) of the proxy about its centre.
#pragma once

#include <vector>

#include "penetration/conservative_advancement.h"
#include "penetration/contact_rows.h"
#include "penetration/travel_budget.h"
#include "smartcollision/pair_settings.h"

namespace sc::detail {

/// Work arrays kept between updates, so steady state allocates nothing (also those of
/// the translation slide's QP).
struct TwistScratch {
  std::vector<LeafContact> contacts;
  std::vector<LeafContact> candidates;
  std::vector<ContactPatch> patches;
  PatchQpWork qp;
  std::vector<LeafPair> skip;
  MatX slide_a;  ///< the translation slide's rows
  VecX slide_b;
  QpWork slide_qp;
};

/// Weights (w_T, w_R) of 1/2 w_T |TPDV - dc|^2 + 1/2 w_R |RPDV - dtheta|^2.
/// Mix: (kT, kR), manual (5-5). Free: rotation almost free, so translation is
/// minimised first and rotation second. Input (only when no translation resolves):
/// the reverse, rotation first. `rho` (target radius about its centre)
/// makes the Free weights scale-free.
Eigen::Matrix<double, 6, 1> twistWeights(const PairSettings& settings, double rho);

struct TwistSlideResult {
  int iterations = 0;
  bool blocked = false;  ///< advancement allowed no motion at all: not settled
};

/// Moves `proxy` (o_from_t) towards `goal` with rotation free, never through the
/// opponent: per iteration, contacts within the tolerance give rows kept at gap >=
/// skin; while in contact the QP's turn is capped to a rotational displacement of
/// safety_coefficient * tolerance at radius rho (the linearisation of rotation is
/// first order) and the translation solved again at the capped turn; a step that
/// continues a run of shrinking parallel steps is stretched to the run's sum;
/// conservative advancement applies it. Converged when a step in contact brings the
/// proxy nearer the goal by less than 1e-4 of the tolerance, in translation and in
/// rotation (at radius rho). Each step is charged to `travel` at its farthest point
/// motion (translation + turn x rho); a step beyond what is left is cut to it.
TwistSlideResult twistSlide(GroupPairQuery& query, Rigid& proxy, const Rigid& goal,
                            const Vec3& center, const Rigid& previous_proxy,
                            const PairSettings& settings, double skin, TwistScratch& scratch,
                            TravelBudget& travel);

/// Radius of the target's leaves about its centre (target group frame).
double targetRadius(const GroupPairQuery& query, const Vec3& center);

}  // namespace sc::detail
