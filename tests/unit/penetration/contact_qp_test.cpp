// SPDX-License-Identifier: MIT
// The proxy's QP: the working-set solver against the all-rows solve, on problems
// shaped like contacts (many nearly parallel rows from one face, a few others) and on
// random ones, feasible and infeasible; and the optimality conditions of the answer.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "penetration/contact_qp.h"

namespace sc::detail {
namespace {

struct Problem {
  VecX goal, weights, b;
  MatX a;
};

/// m rows in n unknowns: `face` rows with normals within `spread` of one direction
/// (a face resting on a large mesh), the rest random on that direction's side (so a
/// far enough step along it frees everything); right-hand sides up to `depth`.
Problem contactLike(std::mt19937& rng, int n, int m, int face, double spread, double depth) {
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Problem p;
  p.goal = VecX::Zero(n);
  for (int i = 0; i < n; ++i) p.goal[i] = 0.1 * g(rng);
  p.weights = VecX::Ones(n);
  if (n == 6) p.weights.tail(3).setConstant(1e-3);  // cheap rotation, as in FREE
  p.a = MatX(m, n);
  p.b = VecX(m);
  VecX dir = VecX::Zero(n);
  dir[0] = 1.0;
  for (int i = 0; i < m; ++i) {
    VecX row(n);
    for (int k = 0; k < n; ++k) row[k] = g(rng);
    if (i < face) row = dir + spread * row;
    row[0] = std::abs(row[0]) + 0.1;
    p.a.row(i) = row.normalized().transpose();
    p.b[i] = depth * u(rng);
  }
  return p;
}

/// KKT of min 1/2 (z - goal)^T W (z - goal) s.t. A z >= b at (z, lambda).
void expectOptimal(const Problem& p, const QpResult& r, const char* what) {
  ASSERT_TRUE(r.feasible) << what;
  const VecX slack = p.a * r.z - p.b;
  EXPECT_GT(slack.minCoeff(), -1e-8) << what;
  EXPECT_GT(r.lambda.minCoeff(), -1e-12) << what;
  const VecX stationarity = p.weights.asDiagonal() * (r.z - p.goal) - p.a.transpose() * r.lambda;
  EXPECT_LT(stationarity.norm(), 1e-7 * (1.0 + r.lambda.norm())) << what;
  EXPECT_LT(std::abs(r.lambda.dot(slack)), 1e-8 * (1.0 + r.lambda.norm())) << what;
}

TEST(ContactQp, WorkingSetMatchesAllRows) {
  std::mt19937 rng(7);
  int compared = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = trial % 2 == 0 ? 3 : 6;
    const int m = 30 + trial * 3;
    const Problem p = contactLike(rng, n, m, m * 3 / 4, trial % 3 == 0 ? 1e-3 : 0.05, 0.05);
    const QpResult ws = solveContactQp(p.goal, p.weights, p.a, p.b);
    const QpResult all = solveContactQpAllRows(p.goal, p.weights, p.a, p.b);
    ASSERT_EQ(ws.feasible, all.feasible) << "trial " << trial;
    if (!ws.feasible) continue;
    ++compared;
    // The minimiser is unique (W positive definite): both must find it.
    EXPECT_LT((ws.z - all.z).norm(), 1e-7 * (1.0 + all.z.norm())) << "trial " << trial;
    expectOptimal(p, ws, "working set");
  }
  EXPECT_GT(compared, 150);
}

/// A working set's step started from the previous step's solution (rows appended
/// since) finds the same minimiser and equally optimal multipliers as a cold solve.
TEST(ContactQp, StepStartedFromTheKeptRowsEqualsAColdStep) {
  std::mt19937 rng(11);
  int compared = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = trial % 2 == 0 ? 3 : 6;
    const int m = 8 + trial % 40, kept = 1 + trial % (m - 1);
    const Problem p = contactLike(rng, n, m, m * 3 / 4, trial % 3 == 0 ? 1e-3 : 0.05, 0.05);
    const VecZ goal = p.goal, weights = p.weights;
    const double length = (p.b - p.a * p.goal).maxCoeff();
    if (length <= 0.0) continue;
    QpWork warm, cold;
    solveLdpStep(goal, weights, p.a.topRows(kept), p.b.head(kept), length, warm);
    const bool warm_ok = solveLdpStep(goal, weights, p.a, p.b, length, warm, kept);
    const bool cold_ok = solveLdpStep(goal, weights, p.a, p.b, length, cold);
    ASSERT_EQ(warm_ok, cold_ok) << "trial " << trial;
    if (!cold_ok) continue;
    ++compared;
    EXPECT_LT((warm.z - cold.z).norm(), 1e-9 * (1.0 + cold.z.norm())) << "trial " << trial;
    QpResult r;
    r.feasible = true;
    r.z = warm.z;
    r.lambda = Eigen::Map<const VecX>(warm.lambda.data(), m);
    expectOptimal(p, r, "warm step");
  }
  EXPECT_GT(compared, 200);
}

TEST(ContactQp, WorkingSetReportsInfeasibleWedges) {
  // Two opposite half-spaces that cannot both hold, buried among many harmless rows.
  std::mt19937 rng(11);
  for (const int n : {3, 6}) {
    Problem p = contactLike(rng, n, 120, 100, 0.05, 0.01);
    VecX e = VecX::Zero(n);
    e[1] = 1.0;
    p.a.row(5) = e.transpose();
    p.b[5] = 1.0;  // z_1 >= 1
    p.a.row(77) = -e.transpose();
    p.b[77] = 1.0;  // z_1 <= -1
    EXPECT_FALSE(solveContactQp(p.goal, p.weights, p.a, p.b).feasible) << n;
    EXPECT_FALSE(solveContactQpAllRows(p.goal, p.weights, p.a, p.b).feasible) << n;
  }
}

TEST(ContactQp, WorkingSetVerdictOnThinStrips) {
  // Two opposite rows leaving a strip of width delta among contact-like rows, one of
  // which holds by a far larger margin than the rest (it sets the acceptance
  // tolerance, 1e-9 x 1e3): strips down to 1e-12 wide have their point, strips of
  // negative width beyond the tolerance none, on both solvers. (Within the tolerance
  // the verdict rests on rounding and the two can differ either way.)
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int feasible = 0, infeasible = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = trial % 2 == 0 ? 3 : 6;
    Problem p = contactLike(rng, n, 60, 40, 0.05, 0.01);
    const double delta =
        u(rng) < 0.5 ? std::pow(10.0, -4.0 - 8.0 * u(rng)) : -std::pow(10.0, -3.0 - 2.0 * u(rng));
    VecX d = VecX::Zero(n);
    d[1] = 1.0;
    p.a.row(7) = d.transpose();
    p.b[7] = 0.02;  // z_1 >= 0.02
    p.a.row(31) = -d.transpose();
    p.b[31] = -0.02 - delta;  // z_1 <= 0.02 + delta
    p.b[50] = -1e3;           // holds by far
    const QpResult ws = solveContactQp(p.goal, p.weights, p.a, p.b);
    const QpResult all = solveContactQpAllRows(p.goal, p.weights, p.a, p.b);
    ASSERT_EQ(ws.feasible, all.feasible) << "trial " << trial << ", delta " << delta;
    (all.feasible ? feasible : infeasible)++;
    if (all.feasible) {
      EXPECT_LT((ws.z - all.z).norm(), 1e-7 * (1.0 + all.z.norm())) << "trial " << trial;
    }
  }
  EXPECT_GT(feasible, 150);
  EXPECT_GT(infeasible, 150);
}

TEST(ContactQp, FeasibleGoalIsItsOwnAnswer) {
  std::mt19937 rng(3);
  Problem p = contactLike(rng, 6, 100, 60, 0.05, 0.01);
  p.b = p.a * p.goal - VecX::Constant(100, 0.01);  // every row holds at the goal
  const QpResult r = solveContactQp(p.goal, p.weights, p.a, p.b);
  ASSERT_TRUE(r.feasible);
  EXPECT_EQ(r.z, p.goal);
  EXPECT_EQ(r.lambda.cwiseAbs().maxCoeff(), 0.0);
}

TEST(ContactQp, NonNegativeLeastSquaresMeetsItsOptimalityConditions) {
  // Any shape of E, also taller than the LDP's 7 rows: u >= 0, the gradient
  // E^T (f - E u) zero where u > 0 and <= 0 where u = 0.
  std::mt19937 rng(17);
  std::normal_distribution<double> g(0.0, 1.0);
  for (const auto& [rows, cols] :
       {std::pair{4, 9}, std::pair{7, 30}, std::pair{12, 5}, std::pair{20, 20}}) {
    for (int trial = 0; trial < 20; ++trial) {
      MatX e(rows, cols);
      VecX f(rows);
      for (int i = 0; i < rows; ++i) {
        f[i] = g(rng);
        for (int j = 0; j < cols; ++j) e(i, j) = g(rng);
      }
      const VecX u = nonNegativeLeastSquares(e, f);
      const VecX gradient = e.transpose() * (f - e * u);
      const double scale = 1e-9 * (1.0 + e.norm() * f.norm());
      for (int j = 0; j < cols; ++j) {
        EXPECT_GE(u[j], 0.0) << rows << "x" << cols << " trial " << trial;
        if (u[j] > 0.0) {
          EXPECT_NEAR(gradient[j], 0.0, scale) << rows << "x" << cols << " trial " << trial;
        } else {
          EXPECT_LT(gradient[j], scale) << rows << "x" << cols << " trial " << trial;
        }
      }
    }
  }
}

/// The problem with every length multiplied by s: translations, offsets and levers
/// (the rotational columns of a twist row), rotation weights by s^2; angles are kept.
Problem scaledProblem(const Problem& p, double s) {
  Problem q = p;
  const int n = static_cast<int>(p.goal.size());
  q.b *= s;
  q.goal.head(3) *= s;
  if (n == 6) {
    q.a.rightCols(3) *= s;
    q.weights.tail(3) *= s * s;
  }
  return q;
}

TEST(ContactQp, SolutionScalesWithTheProblem) {
  // docs/api.md, "Scale": the same contact at any model scale has the same answer in
  // units of the scale, on both paths (all rows; the working set beyond 24 rows).
  std::mt19937 rng(5);
  int compared = 0;
  for (int trial = 0; trial < 24; ++trial) {
    const int n = trial % 2 == 0 ? 3 : 6;
    const int m = trial % 4 < 2 ? 8 : 60;
    const Problem p = contactLike(rng, n, m, m / 2, 0.05, 0.05);
    const QpResult ref = solveContactQp(p.goal, p.weights, p.a, p.b);
    for (int k = -9; k <= 9; ++k) {
      const double s = std::pow(10.0, k);
      const Problem q = scaledProblem(p, s);
      const QpResult r = solveContactQp(q.goal, q.weights, q.a, q.b);
      ASSERT_EQ(r.feasible, ref.feasible) << "trial " << trial << ", scale " << s;
      if (!ref.feasible) continue;
      ++compared;
      VecX z = r.z;
      z.head(3) /= s;
      EXPECT_LT((z - ref.z).norm(), 1e-9 * (1.0 + ref.z.norm()))
          << "trial " << trial << ", scale " << s;
      EXPECT_LT((r.lambda / s - ref.lambda).norm(), 1e-7 * (1.0 + ref.lambda.norm()))
          << "trial " << trial << ", scale " << s;
    }
  }
  EXPECT_GT(compared, 19 * 16);
}

}  // namespace
}  // namespace sc::detail
