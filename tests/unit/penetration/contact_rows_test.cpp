// SPDX-License-Identifier: MIT
// Contact rows against their definition: for each contact, one row per target-leaf
// vertex within `near` of the leaf's lowest point along the row's normal, its gap the
// exact separation plus that height, its lever the vertex minus the target's centre;
// and the twist QP over rows generated on demand (solvePatchQp) against the QP over
// all of them.
#include "penetration/contact_rows.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "smartcollision/model.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::detail {
namespace {

TEST(ContactRows, OneRowPerVertexNearTheContactPlane) {
  const ModelPtr target = test::boxModel(Vec3(0.2, 0.1, 0.05));
  const ModelPtr opponent = test::boxModel(Vec3(0.5, 0.5, 0.5));
  ASSERT_TRUE(target && opponent);
  const Part t_part{target.get(), Rigid(), 1}, o_part{opponent.get(), Rigid(), 2};
  GroupPairQuery q;
  q.bind(GroupView{&t_part, 1, Placement()}, GroupView{&o_part, 1, Placement()});
  test::Rng rng(19);
  int rows_seen = 0, vertices_left_out = 0;
  for (int trial = 0; trial < 200; ++trial) {
    // The target's face nearly flat on the opponent's top face, tilted by up to
    // 0.01 rad: a few of its corners within `near` of the plane, some not.
    const double near = test::uniform(rng, 1e-4, 2e-3);
    const Vec3 axis = test::randomDirection(rng);
    const Rigid pose{Mat3(Eigen::AngleAxisd(test::uniform(rng, 0.0, 0.01), axis)),
                     Vec3(test::uniform(rng, -0.2, 0.2), test::uniform(rng, -0.2, 0.2),
                          0.5 + 0.05 + test::uniform(rng, -1e-3, 1e-3))};
    std::vector<LeafContact> contacts;
    q.contacts(pose, 2e-3, contacts);
    const Vec3 center = pose * Vec3(0.01, -0.02, 0.0);
    std::vector<ContactRow> rows;
    buildContactRows(q, pose, center, contacts, pose, rows, near);
    std::size_t r = 0;
    for (int c = 0; c < static_cast<int>(contacts.size()); ++c) {
      const Leaf leaf = q.targetLeaf(contacts[c].t_leaf);
      ASSERT_LT(r, rows.size());
      const Vec3 n = rows[r].normal;
      const double separation = q.separationAlong(contacts[c].t_leaf, contacts[c].o_leaf, pose, n);
      double lowest = kInfinity;
      for (const Vec3& v : leaf.poly->vertices)
        lowest = std::min(lowest, n.dot(pose * (leaf.group_from_leaf * v)));
      for (const Vec3& v : leaf.poly->vertices) {
        const Vec3 p = pose * (leaf.group_from_leaf * v);
        const double above = n.dot(p) - lowest;
        if (above > near + 1e-12) {
          ++vertices_left_out;
          continue;
        }
        ASSERT_LT(r, rows.size());
        EXPECT_EQ(rows[r].contact, c);
        EXPECT_NEAR(rows[r].gap, separation + above, 1e-12);
        EXPECT_LT((rows[r].lever - (p - center)).norm(), 1e-12);
        ++r;
        ++rows_seen;
      }
    }
    EXPECT_EQ(r, rows.size());
  }
  EXPECT_GT(rows_seen, 200);
  EXPECT_GT(vertices_left_out, 200);
}

/// A coin about the z axis: `sides` rim vertices per face, each face a fan, so the
/// face in contact gives hundreds of rows and its support is found by hill climbing.
ModelPtr coinModel(int sides, double radius, double half_height) {
  return test::closedModel(test::prismMesh(sides, radius, half_height));
}

using Vec6 = Eigen::Matrix<double, 6, 1>;

/// 1/2 (z - goal)^T W (z - goal).
double objective(const VecX& z, const Vec6& goal, const Vec6& weights) {
  return 0.5 * (z - goal).cwiseAbs2().dot(weights);
}

TEST(ContactRows, PatchQpIsTheQpOverAllRows) {
  // A coin or a box tilted on a large box, touching or slightly in, and random goal
  // twists: the working set of rows found by support queries gives the optimum (and
  // the verdict) of the all-rows solve on buildContactRows' rows.
  const ModelPtr opponent = test::boxModel(Vec3(0.5, 0.5, 0.5));
  const ModelPtr targets[] = {coinModel(200, 0.1, 0.01), test::boxModel(Vec3(0.1, 0.07, 0.01))};
  ASSERT_TRUE(opponent && targets[0] && targets[1]);
  test::Rng rng(29);
  int compared = 0, infeasible = 0, rows_total = 0, set_total = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Part t_part{targets[trial % 2].get(), Rigid(), 1}, o_part{opponent.get(), Rigid(), 2};
    GroupPairQuery q;
    q.bind(GroupView{&t_part, 1, Placement()}, GroupView{&o_part, 1, Placement()});
    const Vec3 axis = test::randomDirection(rng);
    const Rigid pose{Mat3(Eigen::AngleAxisd(test::uniform(rng, 0.0, 0.02), axis)),
                     Vec3(test::uniform(rng, -0.3, 0.3), test::uniform(rng, -0.3, 0.3),
                          0.51 + test::uniform(rng, -1e-3, 1e-3))};
    const Rigid previous{pose.rotation, pose.translation + Vec3(0, 0, 0.01)};  // free
    const double near = 2e-3, skin = test::uniform(rng, 0.0, 5e-4);
    std::vector<LeafContact> contacts;
    q.contacts(pose, near, contacts);
    if (contacts.empty()) continue;
    const Vec3 y = pose.translation;
    std::vector<ContactRow> rows;
    buildContactRows(q, pose, y, contacts, previous, rows, near);
    std::vector<ContactPatch> patches;
    buildContactPatches(q, pose, contacts, previous, patches);
    Vec6 goal, weights;
    goal << test::randomDirection(rng) * test::uniform(rng, 0.0, 0.01) - Vec3(0, 0, 0.01),
        test::randomDirection(rng) * test::uniform(rng, 0.0, 0.1);
    const double rho = 0.1;
    weights << Vec3::Ones(), Vec3::Constant(trial % 4 < 2 ? 1e-6 * rho * rho : rho * rho);
    const auto m = static_cast<Eigen::Index>(rows.size());
    MatX a(m, 6);
    VecX b(m);
    for (Eigen::Index i = 0; i < m; ++i) {
      a.row(i) << rows[i].normal.transpose(), rows[i].lever.cross(rows[i].normal).transpose();
      b[i] = skin - rows[i].gap;
    }
    const QpResult all = solveContactQpAllRows(goal, weights, a, b);
    PatchQpWork work;
    solvePatchQp(patches, y, goal, weights, skin, near, work);
    ASSERT_EQ(work.qp.feasible, all.feasible) << "trial " << trial;
    rows_total += static_cast<int>(m);
    set_total += static_cast<int>(work.rows.size());
    if (!all.feasible) {
      ++infeasible;
      continue;
    }
    ++compared;
    const VecX z = work.qp.z;
    // The same minimum, at a point that keeps every row (the minimiser is unique).
    const double f_all = objective(all.z, goal, weights), f = objective(z, goal, weights);
    EXPECT_NEAR(f, f_all, 1e-9 * (f_all + 1e-12)) << "trial " << trial;
    EXPECT_GT((a * z - b).minCoeff(), -1e-9 * (1.0 + b.cwiseAbs().maxCoeff())) << "trial " << trial;
    EXPECT_LT((weights.cwiseSqrt().asDiagonal() * (z - all.z)).norm(),
              1e-6 * std::sqrt(2.0 * f_all) + 1e-12)
        << "trial " << trial;
  }
  EXPECT_GT(compared, 300);
  // Far fewer rows than the whole set: what the working set is for.
  EXPECT_LT(set_total * 10, rows_total);
}

}  // namespace
}  // namespace sc::detail
