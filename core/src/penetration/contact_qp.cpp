// SPDX-License-Identifier: MIT
// LDP through NNLS. Outline (Lawson & Hanson ch. 23):
//   1. x = W^(1/2) (z - goal) turns the QP into: minimise |x| s.t. G x >= h,
//      G = A W^(-1/2), h = b - A goal.
//   2. NNLS on E = [G^T; h^T], f = (0, ..., 0, 1) gives u >= 0 and r = E u - f.
//   3. r = 0 means infeasible; otherwise x_j = -r_j / r_(n+1).
#include "penetration/contact_qp.h"

#include "geometry/math_util.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace sc::detail {

namespace {

/// Relative violation of a row beyond which a solution is rejected (rounding is ~1e-16).
constexpr double kRowTolerance = 1e-9;
/// Up to this many rows the QP is solved on all rows at once; beyond, on a working set
/// of the most violated rows, grown by at least half this many per round.
constexpr int kWorkingSetRows = 24;

/// Least squares on the passive columns only; the others are zero.
VecX solvePassive(const MatX& e, const VecX& f, const std::vector<bool>& passive) {
  const int m = static_cast<int>(e.cols());
  std::vector<int> cols;
  for (int j = 0; j < m; ++j)
    if (passive[j]) cols.push_back(j);
  VecX z = VecX::Zero(m);
  if (cols.empty()) return z;
  MatX sub(e.rows(), static_cast<Eigen::Index>(cols.size()));
  for (size_t k = 0; k < cols.size(); ++k) sub.col(static_cast<Eigen::Index>(k)) = e.col(cols[k]);
  const VecX s = sub.colPivHouseholderQr().solve(f);
  for (size_t k = 0; k < cols.size(); ++k) z[cols[k]] = s[static_cast<Eigen::Index>(k)];
  return z;
}

/// Magnitude a row's violation is compared with: the largest terms of the rows at z
/// (|a_ij z_j| and |b_i|: lengths, also for a twist's angles times levers) and
/// `length`, the largest violation at the goal. No absolute floor: models of any size.
double rowScale(const MatX& a, const VecX& b, const VecX& z, double length) {
  double largest = 0.0;  // a loop: no temporary vector per call
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    double terms = std::abs(b[i]);
    for (Eigen::Index j = 0; j < a.cols(); ++j) terms += std::abs(a(i, j) * z[j]);
    largest = std::max(largest, terms);
  }
  return length + largest;
}

}  // namespace

VecX nonNegativeLeastSquares(const MatX& e, const VecX& f, int max_iterations) {
  const int m = static_cast<int>(e.cols());
  if (max_iterations <= 0) max_iterations = 3 * m + 10;
  const double tol = 1e-12 * std::max(1.0, e.norm());
  VecX u = VecX::Zero(m);
  std::vector<bool> passive(m, false);
  for (int outer = 0; outer < max_iterations; ++outer) {
    const VecX w = e.transpose() * (f - e * u);  // negative gradient
    int best = -1;
    double best_w = tol;
    for (int j = 0; j < m; ++j) {
      if (!passive[j] && w[j] > best_w) {
        best_w = w[j];
        best = j;
      }
    }
    if (best < 0) break;  // KKT holds
    passive[best] = true;
    for (int inner = 0; inner < max_iterations; ++inner) {
      const VecX z = solvePassive(e, f, passive);
      bool positive = true;
      for (int j = 0; j < m; ++j)
        if (passive[j] && z[j] <= 0.0) positive = false;
      if (positive) {
        u = z;
        break;
      }
      // Step from u towards z until the first passive variable hits zero.
      double alpha = 1.0;
      for (int j = 0; j < m; ++j) {
        if (passive[j] && z[j] <= 0.0) {
          const double denom = u[j] - z[j];
          if (denom > 0.0) alpha = std::min(alpha, u[j] / denom);
        }
      }
      u += alpha * (z - u);
      for (int j = 0; j < m; ++j) {
        if (passive[j] && u[j] <= tol) {
          passive[j] = false;
          u[j] = 0.0;
        }
      }
    }
  }
  return u;
}

QpResult solveContactQpAllRows(const VecX& goal, const VecX& weights, const MatX& a,
                               const VecX& b) {
  const int n = static_cast<int>(goal.size());
  const int m = static_cast<int>(a.rows());
  QpResult out;
  out.z = goal;
  out.lambda = VecX::Zero(m);
  if (m == 0) {
    out.feasible = true;
    return out;
  }
  const VecX inv_sqrt_w = weights.cwiseSqrt().cwiseInverse();
  const MatX g = a * inv_sqrt_w.asDiagonal();
  const VecX h = b - a * goal;
  if ((h.array() <= 0.0).all()) {  // the goal itself is feasible
    out.feasible = true;
    return out;
  }
  // The LDP in units of the largest violation at the goal: its thresholds (NNLS,
  // infeasibility) are then the same at every model scale.
  const double length = h.maxCoeff();
  MatX e(n + 1, m);
  e.topRows(n) = g.transpose();
  e.row(n) = h.transpose() / length;
  VecX f = VecX::Zero(n + 1);
  f[n] = 1.0;
  const VecX u = nonNegativeLeastSquares(e, f);
  const VecX r = e * u - f;
  if (r.norm() < 1e-12 || std::abs(r[n]) < 1e-300) return out;  // infeasible
  const VecX x = -(length / r[n]) * r.head(n);
  const VecX z = goal + inv_sqrt_w.cwiseProduct(x);
  // Nearly opposite rows (a wedge) leave r small but not zero: x = -r / r_(n+1) is
  // then huge and violates the rows. Only a solution that keeps them is one.
  if (!allFinite(z) || ((a * z - b).array() < -kRowTolerance * rowScale(a, b, z, length)).any())
    return out;
  out.z = z;
  // Multipliers of the LDP: lambda = u / |r_(n+1)| scaled back to the QP's rows and
  // to model units (x = G^T lambda, and x is `length` times the scaled solution).
  out.lambda = (length / std::abs(r[n])) * u;
  out.feasible = true;
  return out;
}

namespace {

/// Rows violated at `z` beyond the acceptance tolerance, with their violation scaled
/// by the row's norm (most negative = most violated), skipping those in `in_set`.
void violatedRows(const MatX& a, const VecX& b, const VecX& z, double length,
                  const std::vector<bool>& in_set, std::vector<std::pair<double, int>>& out) {
  out.clear();
  const double scale = rowScale(a, b, z, length);
  const VecX slack = a * z - b;
  for (int i = 0; i < static_cast<int>(a.rows()); ++i)
    if (!in_set[i] && slack[i] < -kRowTolerance * scale)
      out.emplace_back(slack[i] / std::max(a.row(i).norm(), 1e-300), i);
}

}  // namespace

QpResult solveContactQp(const VecX& goal, const VecX& weights, const MatX& a, const VecX& b) {
  const int m = static_cast<int>(a.rows());
  if (m <= kWorkingSetRows) return solveContactQpAllRows(goal, weights, a, b);
  // Working set: solve with the rows the current point violates most, add the rows
  // its solution violates, repeat. The optimum over a subset that keeps every other
  // row is the optimum over all rows, and a subset without a solution means none;
  // the NNLS stays small where hundreds of nearly parallel rows (a face on a large
  // mesh) made it cycle. Each round adds a row, so it ends.
  QpResult out;
  out.feasible = true;
  out.z = goal;
  out.lambda = VecX::Zero(m);
  std::vector<bool> in_set(static_cast<std::size_t>(m), false);
  std::vector<int> rows;
  std::vector<std::pair<double, int>> violated;
  const double length = std::max(0.0, (b - a * goal).maxCoeff());
  violatedRows(a, b, goal, length, in_set, violated);
  while (!violated.empty()) {
    // The most violated first, the set at least doubling: few rounds on thousands of rows.
    const std::size_t add = std::min<std::size_t>(
        violated.size(), std::max<std::size_t>(kWorkingSetRows / 2, rows.size()));
    std::nth_element(violated.begin(), violated.begin() + static_cast<std::ptrdiff_t>(add) - 1,
                     violated.end());
    for (std::size_t k = 0; k < add; ++k) {
      in_set[static_cast<std::size_t>(violated[k].second)] = true;
      rows.push_back(violated[k].second);
    }
    const auto count = static_cast<Eigen::Index>(rows.size());
    MatX sub_a(count, a.cols());
    VecX sub_b(count);
    for (Eigen::Index k = 0; k < count; ++k) {
      sub_a.row(k) = a.row(rows[static_cast<std::size_t>(k)]);
      sub_b[k] = b[rows[static_cast<std::size_t>(k)]];
    }
    const QpResult sub = solveContactQpAllRows(goal, weights, sub_a, sub_b);
    if (!sub.feasible) {
      out.feasible = false;
      out.z = goal;
      out.lambda.setZero();
      return out;
    }
    out.z = sub.z;
    out.lambda.setZero();
    for (Eigen::Index k = 0; k < count; ++k)
      out.lambda[rows[static_cast<std::size_t>(k)]] = sub.lambda[k];
    violatedRows(a, b, out.z, length, in_set, violated);
  }
  return out;
}

}  // namespace sc::detail
