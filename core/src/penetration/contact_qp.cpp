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

/// Up to this many rows the QP is solved on all rows at once; beyond, on a working set
/// of the most violated rows, grown by at least half this many per round.
constexpr int kWorkingSetRows = 24;
/// The LDP's E has at most 7 rows, so its passive columns (linearly independent) are
/// few: their least squares is done in fixed-capacity arrays, off the heap.
constexpr int kMaxPassive = 16;
using PassiveMat =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 7, kMaxPassive>;
using SmallVec = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 7, 1>;
using PassiveVec = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxPassive, 1>;

/// Least squares on the passive columns only; the others are zero.
void solvePassive(const RowsRef& e, const RhsRef& f, const std::vector<char>& passive,
                  std::vector<int>& cols, Eigen::Ref<VecX> z) {
  cols.clear();
  for (int j = 0; j < static_cast<int>(z.size()); ++j)
    if (passive[static_cast<std::size_t>(j)]) cols.push_back(j);
  z.setZero();
  if (cols.empty()) return;
  const auto count = static_cast<Eigen::Index>(cols.size());
  if (e.rows() <= 7 && count <= kMaxPassive) {
    PassiveMat sub(e.rows(), count);
    for (Eigen::Index k = 0; k < count; ++k) sub.col(k) = e.col(cols[static_cast<std::size_t>(k)]);
    const SmallVec rhs = f;
    const PassiveVec s = sub.colPivHouseholderQr().solve(rhs);
    for (Eigen::Index k = 0; k < count; ++k) z[cols[static_cast<std::size_t>(k)]] = s[k];
    return;
  }
  MatX sub(e.rows(), count);  // a larger problem than the contact QP's: general arrays
  for (Eigen::Index k = 0; k < count; ++k) sub.col(k) = e.col(cols[static_cast<std::size_t>(k)]);
  const VecX s = sub.colPivHouseholderQr().solve(f);
  for (Eigen::Index k = 0; k < count; ++k) z[cols[static_cast<std::size_t>(k)]] = s[k];
}

/// Lawson-Hanson NNLS into u (size e.cols()), with work arrays from `w`. With `warm`
/// > 0, u's first `warm` entries are the solution of the problem on the first `warm`
/// columns, a state the outer loop passes through (its positive entries passive, each
/// their least squares), so the solve goes on from there instead of from zero.
void nnls(const RowsRef& e, const RhsRef& f, int max_iterations, QpWork& w, Eigen::Ref<VecX> u,
          Eigen::Index warm = 0) {
  const Eigen::Index m = e.cols();
  if (max_iterations <= 0) max_iterations = 3 * static_cast<int>(m) + 10;
  const double tol = 1e-12 * std::max(1.0, e.norm());
  if (w.gradient.size() < m) w.gradient.resize(2 * m);
  if (w.trial.size() < m) w.trial.resize(2 * m);
  auto gradient = w.gradient.head(m), z = w.trial.head(m);
  w.passive.assign(static_cast<std::size_t>(m), 0);
  u.tail(m - warm).setZero();
  for (Eigen::Index j = 0; j < warm; ++j) {
    if (u[j] > tol)
      w.passive[static_cast<std::size_t>(j)] = 1;
    else
      u[j] = 0.0;
  }
  if (w.residual.size() != e.rows()) w.residual.resize(e.rows());  // any size of E
  VecX& residual = w.residual;
  for (int outer = 0; outer < max_iterations; ++outer) {
    residual.noalias() = f - e * u;
    gradient.noalias() = e.transpose() * residual;  // negative gradient
    Eigen::Index best = -1;
    double best_w = tol;
    for (Eigen::Index j = 0; j < m; ++j) {
      if (!w.passive[static_cast<std::size_t>(j)] && gradient[j] > best_w) {
        best_w = gradient[j];
        best = j;
      }
    }
    if (best < 0) break;  // KKT holds
    w.passive[static_cast<std::size_t>(best)] = 1;
    for (int inner = 0; inner < max_iterations; ++inner) {
      solvePassive(e, f, w.passive, w.passive_cols, z);
      bool positive = true;
      for (const int j : w.passive_cols)
        if (z[j] <= 0.0) positive = false;
      if (positive) {
        u = z;
        break;
      }
      // Step from u towards z until the first passive variable hits zero.
      double alpha = 1.0;
      for (const int j : w.passive_cols) {
        if (z[j] <= 0.0) {
          const double denom = u[j] - z[j];
          if (denom > 0.0) alpha = std::min(alpha, u[j] / denom);
        }
      }
      u += alpha * (z - u);
      for (const int j : w.passive_cols) {
        if (u[j] <= tol) {
          w.passive[static_cast<std::size_t>(j)] = 0;
          u[j] = 0.0;
        }
      }
    }
  }
}

/// Magnitude a row's violation is compared with: the largest terms of the rows at z
/// (|a_ij z_j| and |b_i|: lengths, also for a twist's angles times levers) and
/// `length`, the largest violation at the goal. No absolute floor: models of any size.
double rowScale(const RowsRef& a, const RhsRef& b, const VecZ& z, double length) {
  double largest = 0.0;  // a loop: no temporary vector per call
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    double terms = std::abs(b[i]);
    for (Eigen::Index j = 0; j < a.cols(); ++j) terms += std::abs(a(i, j) * z[j]);
    largest = std::max(largest, terms);
  }
  return length + largest;
}

/// The largest violation at the goal (0 when the goal keeps every row).
double goalViolation(const VecZ& goal, const RowsRef& a, const RhsRef& b) {
  double length = 0.0;
  for (Eigen::Index i = 0; i < a.rows(); ++i) length = std::max(length, b[i] - a.row(i).dot(goal));
  return length;
}

void setGoal(const VecZ& goal, Eigen::Index rows, QpWork& w) {
  w.feasible = true;
  w.z = goal;
  w.lambda.assign(static_cast<std::size_t>(rows), 0.0);
}

QpResult resultOf(const QpWork& w) {
  QpResult out;
  out.feasible = w.feasible;
  out.z = w.z;
  out.lambda = Eigen::Map<const VecX>(w.lambda.data(), static_cast<Eigen::Index>(w.lambda.size()));
  return out;
}

/// True when a row is violated at w.z beyond the acceptance tolerance.
bool anyRowViolated(const RowsRef& a, const RhsRef& b, double length, const QpWork& w) {
  const double threshold = kRowTolerance * rowScale(a, b, w.z, length);
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    if (a.row(i).dot(w.z) - b[i] < -threshold) return true;
  return false;
}

/// The all-rows solve into w.
void solveAllRows(const VecZ& goal, const VecZ& weights, const RowsRef& a, const RhsRef& b,
                  QpWork& w) {
  setGoal(goal, a.rows(), w);
  const double length = goalViolation(goal, a, b);
  if (a.rows() == 0 || length <= 0.0) return;  // the goal itself is feasible
  // Nearly opposite rows (a wedge) leave r small but not zero: x = -r / r_(n+1) is
  // then huge and violates the rows. Only a solution that keeps them is one.
  if (!solveLdpStep(goal, weights, a, b, length, w) || anyRowViolated(a, b, length, w)) {
    setGoal(goal, a.rows(), w);
    w.feasible = false;
  }
}

}  // namespace

bool solveLdpStep(const VecZ& goal, const VecZ& weights, const RowsRef& a, const RhsRef& b,
                  double length, QpWork& w, Eigen::Index kept_rows) {
  const Eigen::Index n = goal.size(), m = a.rows();
  setGoal(goal, m, w);
  if (m == 0) return true;
  // The kept rows' solution (w.u's head) starts the NNLS only if it is there.
  if (kept_rows > m || w.u.size() < kept_rows || !w.u_valid) kept_rows = 0;
  w.u_valid = false;
  const VecZ inv_sqrt_w = weights.cwiseSqrt().cwiseInverse();
  // The LDP in units of the largest violation at the goal: its thresholds (NNLS,
  // infeasibility) are then the same at every model scale.
  if (w.e.rows() != n + 1 || w.e.cols() < m) w.e.resize(n + 1, std::max<Eigen::Index>(2 * m, 32));
  auto e = w.e.leftCols(m);
  bool goal_keeps_rows = true;
  for (Eigen::Index i = 0; i < m; ++i) {
    const double h = b[i] - a.row(i).dot(goal);
    goal_keeps_rows = goal_keeps_rows && h <= 0.0;
    e.col(i).head(n) = a.row(i).transpose().cwiseProduct(inv_sqrt_w);
    e(n, i) = h / length;
  }
  if (goal_keeps_rows) return true;
  SmallVec f = SmallVec::Zero(n + 1);
  f[n] = 1.0;
  if (w.u.size() < m) w.u.conservativeResize(2 * m);
  auto u = w.u.head(m);
  nnls(e, f, 0, w, u, kept_rows);
  w.u_valid = true;
  const SmallVec r = e * u - f;
  if (r.norm() < 1e-12 || std::abs(r[n]) < 1e-300) return false;  // infeasible
  const VecZ x = -(length / r[n]) * r.head(n);
  w.z = goal + inv_sqrt_w.cwiseProduct(x);
  if (!allFinite(w.z)) {
    w.z = goal;
    return false;
  }
  // Multipliers of the LDP: lambda = u / |r_(n+1)| scaled back to the QP's rows and
  // to model units (x = G^T lambda, and x is `length` times the scaled solution).
  const double to_lambda = length / std::abs(r[n]);
  for (Eigen::Index i = 0; i < m; ++i) w.lambda[static_cast<std::size_t>(i)] = to_lambda * u[i];
  return true;
}

VecX nonNegativeLeastSquares(const MatX& e, const VecX& f, int max_iterations) {
  QpWork w;
  VecX u(e.cols());
  nnls(e, f, max_iterations, w, u);
  return u;
}

QpResult solveContactQpAllRows(const VecX& goal, const VecX& weights, const MatX& a,
                               const VecX& b) {
  QpWork w;
  solveAllRows(goal, weights, a, b, w);
  return resultOf(w);
}

namespace {

/// Rows violated at w.z beyond the acceptance tolerance, with their violation scaled
/// by the row's norm (most negative = most violated), skipping those in the set;
/// true when a row of the set itself is violated (nearly opposite rows: no point).
bool violatedRows(const RowsRef& a, const RhsRef& b, double length, QpWork& w) {
  w.violated.clear();
  const double threshold = kRowTolerance * rowScale(a, b, w.z, length);
  bool wedge = false;
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    const double slack = a.row(i).dot(w.z) - b[i];
    if (slack >= -threshold) continue;
    if (w.in_set[static_cast<std::size_t>(i)])
      wedge = true;
    else
      w.violated.emplace_back(slack / std::max(a.row(i).norm(), 1e-300), static_cast<int>(i));
  }
  return wedge;
}

/// Adds the most violated rows (at least half kWorkingSetRows, at least doubling the
/// set: few rounds on thousands of rows) to the working set's arrays.
void growWorkingSet(const RowsRef& a, const RhsRef& b, QpWork& w) {
  const std::size_t add = std::min<std::size_t>(
      w.violated.size(), std::max<std::size_t>(kWorkingSetRows / 2, w.set_rows.size()));
  std::nth_element(w.violated.begin(), w.violated.begin() + static_cast<std::ptrdiff_t>(add) - 1,
                   w.violated.end());
  const auto count = static_cast<Eigen::Index>(w.set_rows.size() + add);
  if (w.sub_a.cols() != a.cols()) w.sub_a.resize(0, a.cols());
  if (w.sub_a.rows() < count) {  // grows geometrically: rarely
    w.sub_a.conservativeResize(std::max<Eigen::Index>(2 * count, 64), a.cols());
    w.sub_b.conservativeResize(w.sub_a.rows());
  }
  for (std::size_t k = 0; k < add; ++k) {
    const int i = w.violated[k].second;
    const auto at = static_cast<Eigen::Index>(w.set_rows.size());
    w.in_set[static_cast<std::size_t>(i)] = 1;
    w.set_rows.push_back(i);
    w.sub_a.row(at) = a.row(i);
    w.sub_b[at] = b[i];
  }
}

void setInfeasible(const VecZ& goal, Eigen::Index rows, QpWork& w) {
  setGoal(goal, rows, w);
  w.feasible = false;
}

/// The working set's multipliers (w.lambda, in the set's order) to the m rows'.
void spreadMultipliers(Eigen::Index m, QpWork& w) {
  const auto count = static_cast<Eigen::Index>(w.set_rows.size());
  if (w.gradient.size() < count) w.gradient.resize(2 * count);
  for (Eigen::Index k = 0; k < count; ++k) w.gradient[k] = w.lambda[static_cast<std::size_t>(k)];
  w.lambda.assign(static_cast<std::size_t>(m), 0.0);
  for (Eigen::Index k = 0; k < count; ++k)
    w.lambda[static_cast<std::size_t>(w.set_rows[static_cast<std::size_t>(k)])] = w.gradient[k];
}

}  // namespace

void solveContactQp(const VecZ& goal, const VecZ& weights, const RowsRef& a, const RhsRef& b,
                    QpWork& w) {
  const Eigen::Index m = a.rows();
  if (m <= kWorkingSetRows) return solveAllRows(goal, weights, a, b, w);
  // Working set: solve with the rows the current point violates most, add the rows
  // its solution violates, repeat. The optimum over a subset that keeps every other
  // row is the optimum over all rows, and a subset without a solution means none;
  // the NNLS stays small where hundreds of nearly parallel rows (a face on a large
  // mesh) made it cycle. Each round adds a row, so it ends. The subset's LDP is in
  // the whole set's units and its point judged against every row: the verdict is the
  // all-rows solve's.
  const double length = goalViolation(goal, a, b);
  w.in_set.assign(static_cast<std::size_t>(m), 0);
  w.set_rows.clear();
  setGoal(goal, m, w);
  if (violatedRows(a, b, length, w)) return setInfeasible(goal, m, w);
  if (w.violated.empty()) return;  // the goal keeps every row
  for (;;) {
    // Rows are only appended: the last round's solution starts the next.
    const auto kept = static_cast<Eigen::Index>(w.set_rows.size());
    growWorkingSet(a, b, w);
    const auto count = static_cast<Eigen::Index>(w.set_rows.size());
    if (!solveLdpStep(goal, weights, w.sub_a.topRows(count), w.sub_b.head(count), length, w,
                      kept) ||
        violatedRows(a, b, length, w))
      return setInfeasible(goal, m, w);
    if (w.violated.empty()) return spreadMultipliers(m, w);
  }
}

QpResult solveContactQp(const VecX& goal, const VecX& weights, const MatX& a, const VecX& b) {
  QpWork w;
  solveContactQp(goal, weights, a, b, w);
  return resultOf(w);
}

}  // namespace sc::detail
