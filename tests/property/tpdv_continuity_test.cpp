// SPDX-License-Identifier: MIT
// How far the TPDV moves between updates along a smooth path (INPUT mode). Within one
// facet of the configuration-space obstacle (the Minkowski difference) the TPDV is
// the goal's offset along that facet's normal, so it moves by at most the step. Where
// the contact passes to the next facet, its direction turns by the angle a between
// the two normals, so it moves by up to depth * 2 sin(a/2) in one step: on a
// tessellated curved surface, deep, that is many steps (the haptic bench's rows over
// 3x). The depth itself moves by at most the step plus depth * (1 - cos a), what the
// tracked (local) depth can exceed the global one by before it passes over. Here: a
// small cube pushed 0.04 into a 64-gon prism and carried around it at a haptic step
// of 7.5e-4, checked against the exact depth of the hull of the Minkowski difference.
// With PairSettings::proxy_travel_ratio the proxy moves no farther than the target
// per update, so those turns spread over a few updates: at most 3x the step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "sc.h"
#include "smartcollision/collision.h"
#include "support/brute_force.h"
#include "support/sc_results.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::test {
namespace {

constexpr int kSides = 64;
constexpr double kCircumradius = 1.0, kHalfHeight = 2.0, kCubeHalf = 0.05;
constexpr double kDepth = 0.04, kStep = 7.5e-4;

Placement at(const Vec3& center) {
  Placement p;
  p.world_center = center;
  return p;
}

/// The cube, the prism, their polytopes (for the exact depth) and the path: in along
/// x from 0.01 outside to kDepth deep, then around the axis at a fixed radius over
/// five and a half facets.
struct PrismRun {
  const MeshData prism = prismMesh(kSides, kCircumradius, kHalfHeight),
                 cube = boxMesh(Vec3::Constant(kCubeHalf));
  const ModelPtr opponent = closedModel(prism), target = closedModel(cube);
  const detail::ConvexPolytope prism_poly = polytopeFromMesh(prism);
  const detail::ConvexPolytope cube_poly = polytopeFromMesh(cube);
  std::vector<Vec3> path;

  PrismRun() {
    const double apothem = kCircumradius * std::cos(kPi / kSides), a = 2.0 * kPi / kSides;
    for (double r = apothem + kCubeHalf + 0.01; r > apothem + kCubeHalf - kDepth; r -= kStep)
      path.push_back(Vec3(r, 0, 0));
    const double radius = path.back().x();
    for (double t = kStep / radius; t < 5.5 * a; t += kStep / radius)
      path.push_back(radius * Vec3(std::cos(t), std::sin(t), 0));
  }
};

TEST(TpdvContinuity, DeepAlongATessellatedSurfaceTheTurnAtEachFacetIsBounded) {
  const PrismRun run;
  ASSERT_TRUE(run.opponent && run.target);
  const std::vector<Vec3>& path = run.path;
  const detail::ConvexPolytope &prism_poly = run.prism_poly, &cube_poly = run.cube_poly;
  const ModelPtr &opponent = run.opponent, &target = run.target;
  const Part part_t{target.get(), Rigid(), 1}, part_o{opponent.get(), Rigid(), 2};
  SceneSettings settings;  // INPUT, tolerance 1e-3
  // Facet normals of the Minkowski difference in the xy plane: the prism's and the
  // cube's side normals, so adjacent ones are at most this far apart.
  const double a = 2.0 * kPi / kSides;
  const double turn = 2.0 * std::sin(0.5 * a), rise = 1.0 - std::cos(a);

  PairTracker tracker;
  DirectedResult out[2];
  Vec3 previous = Vec3::Zero();
  double worst_depth_error = 0.0, worst_turn_ratio = 0.0, worst_of_bound = 0.0;
  int penetrating = 0, over_3x = 0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    tracker.update({&part_t, 1, at(path[k])}, {&part_o, 1, at(Vec3::Zero())}, {true, false},
                   settings, out);
    const DirectedResult& r = out[0];
    ASSERT_EQ(r.code, ErrorCode::Ok) << "step " << k;
    const ExactDepth truth =
        exactPenetrationDepth(cube_poly, at(path[k]).worldFromLocal(), prism_poly, Rigid());
    const double depth = r.tpdv.norm();
    if (r.penetrating()) {
      ++penetrating;
      // Never shallower than the global depth; deeper by at most what staying on the
      // last facet can add before the contact passes over.
      const double error = depth - truth.depth;
      worst_depth_error = std::max(worst_depth_error, std::abs(error));
      EXPECT_GE(error, -1e-6 * truth.depth) << "step " << k;
      EXPECT_LE(error, truth.depth * rise + 1e-6 * truth.depth) << "step " << k;
    }
    if (k > 0) {
      const double step = (path[k] - path[k - 1]).norm();
      const double move = (r.tpdv - previous).norm();
      const double len_change = std::abs(depth - previous.norm());
      over_3x += move > 3.0 * step;
      worst_turn_ratio = std::max(worst_turn_ratio, move / step);
      EXPECT_LE(len_change, step + depth * rise + 1e-9) << "step " << k;
      const double bound = step + std::max(depth, previous.norm()) * (turn + rise);
      worst_of_bound = std::max(worst_of_bound, move / bound);
      EXPECT_LE(move, bound + 1e-9) << "step " << k;
    }
    previous = r.tpdv;
  }
  std::printf(
      "tpdv continuity: %zu steps, %d penetrating, %d over 3x the step (worst %.1fx, %.2f of "
      "its bound), worst |depth - exact| %.2g\n",
      path.size(), penetrating, over_3x, worst_turn_ratio, worst_of_bound, worst_depth_error);
  EXPECT_GT(penetrating, static_cast<int>(path.size()) - 30);
  // The exceptions exist (the path crosses five facets deep) and are bounded above.
  EXPECT_GE(over_3x, 1);
}

/// The same path with the proxy's travel capped at the target's motion, against the
/// convex fast path (one convex piece each) and the general one (the prism's group also
/// holds a far cube, so the pair is not convex).
void cappedTravelRun(bool general_path) {
  const PrismRun run;
  ASSERT_TRUE(run.opponent && run.target);
  const std::vector<Vec3>& path = run.path;
  const detail::ConvexPolytope &prism_poly = run.prism_poly, &cube_poly = run.cube_poly;
  const ModelPtr &opponent = run.opponent, &target = run.target;
  const Part part_t{target.get(), Rigid(), 1};
  const Part parts_o[2] = {{opponent.get(), Rigid(), 2},
                           {target.get(), Rigid{Mat3::Identity(), Vec3(0, 0, 50)}, 3}};
  SceneSettings settings;  // INPUT, tolerance 1e-3
  settings.proxy_travel_ratio = 2.0;

  PairTracker tracker;
  DirectedResult out[2];
  Vec3 previous = Vec3::Zero();
  double worst_ratio = 0.0;
  int lagging = 0, penetrating = 0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    tracker.update({&part_t, 1, at(path[k])}, {parts_o, general_path ? 2 : 1, at(Vec3::Zero())},
                   {true, false}, settings, out);
    const DirectedResult& r = out[0];
    ASSERT_EQ(r.code, ErrorCode::Ok) << "step " << k;
    penetrating += r.penetrating();
    lagging += r.status == DirectionStatus::Lagging;
    if (r.penetrating()) {  // a proxy held back is still free: never shallower
      const ExactDepth truth =
          exactPenetrationDepth(cube_poly, at(path[k]).worldFromLocal(), prism_poly, Rigid());
      EXPECT_GE(r.tpdv.norm(), truth.depth * (1.0 - 1e-6)) << "step " << k;
    }
    if (k > 0) {
      const double step = (path[k] - path[k - 1]).norm();
      const double ratio = (r.tpdv - previous).norm() / step;
      worst_ratio = std::max(worst_ratio, ratio);
      EXPECT_LE(ratio, 3.0) << "step " << k;
    }
    previous = r.tpdv;
  }
  std::printf("capped travel (%s path): %d penetrating, %d lagging, worst %.2fx the step\n",
              general_path ? "general" : "convex", penetrating, lagging, worst_ratio);
  EXPECT_GT(penetrating, static_cast<int>(path.size()) - 30);
  // The cap acted at the facets, and the proxy caught up between them.
  EXPECT_GE(lagging, 1);
  EXPECT_LT(lagging, penetrating / 5);
}

TEST(TpdvContinuity, CappedProxyTravelSpreadsEachTurnOverUpdatesConvexPath) {
  cappedTravelRun(false);
}

TEST(TpdvContinuity, CappedProxyTravelSpreadsEachTurnOverUpdatesGeneralPath) {
  cappedTravelRun(true);
}

TEST(TpdvContinuity, ProxyTravelRatioOutOfRangeIsRefusedAndChangesNothing) {
  const ModelPtr cube = boxModel(Vec3::Constant(0.5));
  const Part part_t{cube.get(), Rigid(), 1}, part_o{cube.get(), Rigid(), 2};
  PairTracker tracker;
  DirectedResult out[2];
  SceneSettings good;
  tracker.update({&part_t, 1, at(Vec3(2, 0, 0))}, {&part_o, 1, at(Vec3::Zero())}, {true, false},
                 good, out);
  ASSERT_EQ(out[0].code, ErrorCode::Ok);
  for (const double bad : {0.5, 0.0, -1.0, std::nan("")}) {
    SceneSettings settings;
    settings.proxy_travel_ratio = bad;
    EXPECT_EQ(validate(static_cast<const PairSettings&>(settings)).code(),
              ErrorCode::InvalidArgument);
    tracker.update({&part_t, 1, at(Vec3(-5, 0, 0))}, {&part_o, 1, at(Vec3::Zero())}, {true, false},
                   settings, out);
    EXPECT_EQ(out[0].code, ErrorCode::InvalidArgument);
  }
  // Nothing moved: the next valid update still follows the path from x = 2.
  tracker.update({&part_t, 1, at(Vec3(1.9, 0, 0))}, {&part_o, 1, at(Vec3::Zero())}, {true, false},
                 good, out);
  ASSERT_EQ(out[0].code, ErrorCode::Ok);
  EXPECT_NEAR(out[0].distance, 0.9, 1e-12);
  SCSceneManager scene(SC_SCENE_MANAGER_CLOSED_POLYHEDRA);
  expectDoubleAttribute(scene, SC_SCENE_MANAGER_PROXY_TRAVEL_RATIO, kInfinity, 0.5, 2.0);
}

}  // namespace
}  // namespace sc::test
