// SPDX-License-Identifier: MIT
// The small dense QP of each proxy step:
//   minimise 1/2 (z - goal)^T W (z - goal)  subject to  A z >= b,
// W diagonal positive, z of dimension 3 (translation) or 6 (twist), a handful of
// rows (one per contact).
#pragma once

#include <Eigen/Core>

namespace sc::detail {

using MatX = Eigen::MatrixXd;
using VecX = Eigen::VectorXd;

struct QpResult {
  bool feasible = false;
  VecX z;       ///< the minimiser when feasible
  VecX lambda;  ///< one multiplier >= 0 per row; > 0 on active rows
};

/// Solves the QP above as a least-distance program (Lawson & Hanson, "Solving Least
/// Squares Problems", 1974, ch. 23: LDP through NNLS). Exact up to rounding and
/// finite: no starting point needed, infeasible systems are reported, not guessed
/// (a solution violating a row by more than 1e-9 of the magnitudes involved, as
/// nearly opposite rows produce, counts as infeasible).
/// `weights` holds diag(W). Allocates its (small) work arrays.
/// Beyond a couple of dozen rows it works on a growing subset of them (the rows
/// violated so far), which gives the same solution.
QpResult solveContactQp(const VecX& goal, const VecX& weights, const MatX& a, const VecX& b);

/// The same QP solved on all rows at once (the reference the working set is tested
/// against).
QpResult solveContactQpAllRows(const VecX& goal, const VecX& weights, const MatX& a, const VecX& b);

/// Non-negative least squares: argmin |E u - f| subject to u >= 0 (Lawson-Hanson).
VecX nonNegativeLeastSquares(const MatX& e, const VecX& f, int max_iterations = 0);

}  // namespace sc::detail
