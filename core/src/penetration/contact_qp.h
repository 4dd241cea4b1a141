// SPDX-License-Identifier: MIT
// The small dense QP of each proxy step:
//   minimise 1/2 (z - goal)^T W (z - goal)  subject to  A z >= b,
// W diagonal positive, z of dimension 3 (translation) or 6 (twist), a handful of
// rows (one per contact).
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace sc::detail {

using MatX = Eigen::MatrixXd;
using VecX = Eigen::VectorXd;
/// z, goal and weights: at most 6 entries, held without the heap.
using VecZ = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 6, 1>;
using RowsRef = Eigen::Ref<const MatX>;
using RhsRef = Eigen::Ref<const VecX>;

struct QpResult {
  bool feasible = false;
  VecX z;       ///< the minimiser when feasible
  VecX lambda;  ///< one multiplier >= 0 per row; > 0 on active rows
};

/// Work arrays of the QP kept by the caller between calls: once grown to the largest
/// problem seen, a solve allocates nothing.
struct QpWork {
  MatX e;                   ///< the LDP's matrix, (n + 1) x rows
  VecX u, gradient, trial;  ///< per row
  bool u_valid = false;     ///< u holds the last NNLS solution (solveLdpStep's start)
  VecX residual;            ///< per row of the LDP's matrix
  std::vector<char> passive, in_set;
  std::vector<int> passive_cols;
  std::vector<int> set_rows;  ///< the working set, in the order added
  MatX sub_a;                 ///< the working set's rows
  VecX sub_b;
  std::vector<std::pair<double, int>> violated;
  bool feasible = false;
  VecZ z;                      ///< the minimiser when feasible
  std::vector<double> lambda;  ///< per row of the last solve's problem
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
/// The same in kept work arrays: the answer in work.feasible, work.z, work.lambda.
void solveContactQp(const VecZ& goal, const VecZ& weights, const RowsRef& a, const RhsRef& b,
                    QpWork& work);

/// The same QP solved on all rows at once (the reference the working set is tested
/// against).
QpResult solveContactQpAllRows(const VecX& goal, const VecX& weights, const MatX& a, const VecX& b);

/// One step of a working set whose rows are drawn from a larger set: the LDP on the
/// rows (a, b) with `length`, the largest violation at the goal over the whole set
/// (the unit of the LDP's thresholds, so that a subset is judged as the whole).
/// False when the rows admit no point; else the minimiser over them in work.z and
/// their multipliers in work.lambda, which the caller checks against the other rows.
/// `kept_rows`: the first rows are those of the previous call on `work` (same goal,
/// weights and length; rows only appended since), whose solution starts this one.
bool solveLdpStep(const VecZ& goal, const VecZ& weights, const RowsRef& a, const RhsRef& b,
                  double length, QpWork& work, Eigen::Index kept_rows = 0);

/// Relative violation of a row beyond which a point is rejected (rounding is ~1e-16).
constexpr double kRowTolerance = 1e-9;

/// Non-negative least squares: argmin |E u - f| subject to u >= 0 (Lawson-Hanson).
VecX nonNegativeLeastSquares(const MatX& e, const VecX& f, int max_iterations = 0);

}  // namespace sc::detail
