// SPDX-License-Identifier: MIT
// Pairs first seen intersecting, with resolve_initial_intersection on: convex pairs
// report the exact global depth (hull of the Minkowski difference) to the tolerance;
// non-convex pairs and soups report a contact configuration that does not intersect,
// deep overlaps of CGAL models one within 5% of the shortest sampled exit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "penetration/result_invariants.h"
#include "query/gjk.h"
#include "sc_support/off_mesh.h"
#include "smartcollision/collision.h"
#include "support/brute_force.h"
#include "support/meshes.h"
#include "support/placements.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::test {
namespace {

ModelPtr modelOf(ModelKind kind, const MeshData& mesh) {
  auto piece = buildPiece(kind, mesh);
  EXPECT_TRUE(piece.ok()) << piece.status().message();
  if (!piece.ok()) return nullptr;
  return std::make_shared<Model>(kind, std::vector<PiecePtr>{piece.value()});
}

bool convexOverlap(const ConvexShape& a, const Placement& pa, const ConvexShape& b,
                   const Placement& pb) {
  detail::SimplexCache cache;
  return detail::gjkDistance(a.poly, pa.worldFromLocal(), b.poly, pb.worldFromLocal(), {}, cache)
             .status == detail::GjkStatus::Intersecting;
}

/// True when the target, placed at the result's contact configuration and moved out
/// by `clearance` along the normal, intersects the opponent (brute force).
bool contactPoseIntersects(const MeshData& target, const DirectedResult& r, const MeshData& opponent,
                           const Placement& opponent_placement, double clearance) {
  Placement contact;
  contact.orientation = r.contact_orientation;
  contact.world_center = r.contact_position + clearance * r.normal;
  const SurfaceDistance d = meshSurfaceDistance(target, contact.worldFromLocal(), opponent,
                                                opponent_placement.worldFromLocal());
  return d.distance <= 0.0;
}

TEST(InitialResolution, OffByDefaultReportsInvalidInitialTransformation) {
  const ModelPtr box = modelOf(ModelKind::ClosedPolyhedron, boxMesh(Vec3(1, 1, 1)));
  const Part a{box.get(), Rigid(), 1}, b{box.get(), Rigid(), 2};
  PairTracker tracker;
  DirectedResult out[2];
  SceneSettings settings;
  const Placement pa = placementOf(Quat::Identity(), Vec3(1.5, 0, 0));
  const Placement pb = placementOf(Quat::Identity(), Vec3::Zero());
  tracker.update({&a, 1, pa}, {&b, 1, pb}, {true, true}, settings, out);
  EXPECT_EQ(out[0].code, ErrorCode::InvalidInitialTransformation);
  EXPECT_EQ(out[1].code, ErrorCode::InvalidInitialTransformation);
  settings.resolve_initial_intersection = true;
  tracker.update({&a, 1, pa}, {&b, 1, pb}, {true, true}, settings, out);
  ASSERT_EQ(out[0].code, ErrorCode::Ok);
  ASSERT_EQ(out[1].code, ErrorCode::Ok);
  // Boxes overlapping by 0.5 along x: each direction's exit is 0.5 along +-x.
  EXPECT_NEAR(out[0].distance, -0.5, settings.tolerance);
  EXPECT_VEC_NEAR(out[0].tpdv, Vec3(-0.5, 0, 0), settings.tolerance);
  EXPECT_VEC_NEAR(out[1].tpdv, Vec3(0.5, 0, 0), settings.tolerance);
  EXPECT_TRUE(detail::checkResult(out[0], pa, pb).ok());
  EXPECT_TRUE(detail::checkResult(out[1], pb, pa).ok());
}

TEST(InitialResolution, ConvexPairsReportTheGlobalDepthToTheTolerance) {
  const std::uint64_t seed = 77012026;
  SCOPED_TRACE(testing::Message() << "seed " << seed);
  Rng rng(seed);
  const int wanted = SC_TEST_SANITIZED ? 100 : 500;
  int cases = 0, within = 0;
  double worst = 0.0;
  while (cases < wanted) {
    const double size = logUniform(rng, 1e-2, 1e2);
    const ConvexShape a = randomConvexShape(rng, size);
    const ConvexShape b = randomConvexShape(rng, size * uniform(rng, 0.5, 2.0));
    const Placement pb = placementOf(randomRotation(rng), Vec3::Zero());
    // Deep or shallow: centres anywhere within about the shapes' size.
    const Placement pa = placementOf(randomRotation(rng), size * uniform(rng, 0.0, 0.8) *
                                                              randomDirection(rng));
    if (!convexOverlap(a, pa, b, pb)) continue;
    const ExactDepth truth =
        exactPenetrationDepth(a.poly, pa.worldFromLocal(), b.poly, pb.worldFromLocal());
    if (!(truth.depth > 0.0) || !std::isfinite(truth.depth)) continue;
    const ModelPtr ma = modelOf(ModelKind::ClosedPolyhedron, meshOf(a.poly));
    const ModelPtr mb = modelOf(ModelKind::ClosedPolyhedron, meshOf(b.poly));
    const Part part_a{ma.get(), Rigid(), 1}, part_b{mb.get(), Rigid(), 2};
    SceneSettings settings;
    settings.tolerance = 1e-3 * size;
    settings.resolve_initial_intersection = true;
    PairTracker tracker;
    DirectedResult out[2];
    tracker.update({&part_a, 1, pa}, {&part_b, 1, pb}, {true, false}, settings, out);
    ASSERT_EQ(out[0].code, ErrorCode::Ok) << "case " << cases;
    ASSERT_LE(out[0].distance, 0.0) << "case " << cases;
    const Status s = detail::checkResult(out[0], pa, pb);
    EXPECT_TRUE(s.ok()) << s.message() << " case " << cases;
    ++cases;
    const double err = std::abs(-out[0].distance - truth.depth);
    worst = std::max(worst, err / settings.tolerance);
    if (err <= settings.tolerance) ++within;
  }
  std::printf("initial resolution, convex: %d cases, %d within the tolerance of the exact "
              "depth, worst error %.3g tolerances\n",
              cases, within, worst);
  EXPECT_GE(within, cases * 99 / 100);
}

TEST(InitialResolution, NonConvexPrismsStartFromAFreeContactConfiguration) {
  auto prism = support::readOff(std::string(SC_TEST_DATA_DIR) + "/l_prism.off");
  ASSERT_TRUE(prism.ok()) << prism.status().message();
  const MeshData& mesh = prism.value();
  const ModelPtr model = modelOf(ModelKind::ClosedPolyhedron, mesh);
  const Part a{model.get(), Rigid(), 1}, b{model.get(), Rigid(), 2};
  Rng rng(4242);
  const double size = (model->bounds().max - model->bounds().min).norm();
  int resolved = 0, intersecting = 0;
  for (int i = 0; i < (SC_TEST_SANITIZED ? 20 : 100); ++i) {
    const Placement pb = placementOf(randomRotation(rng), Vec3::Zero());
    const Placement pa =
        placementOf(randomRotation(rng), uniform(rng, 0.0, 0.4) * size * randomDirection(rng));
    SceneSettings settings;
    settings.tolerance = 1e-3 * size;
    settings.resolve_initial_intersection = true;
    if (meshSurfaceDistance(mesh, pa.worldFromLocal(), mesh, pb.worldFromLocal()).distance > 0.0)
      continue;  // not intersecting (or one inside the other's hull only)
    ++intersecting;
    PairTracker tracker;
    DirectedResult out[2];
    tracker.update({&a, 1, pa}, {&b, 1, pb}, {true, true}, settings, out);
    for (int d = 0; d < 2; ++d) {
      if (out[d].code != ErrorCode::Ok) continue;
      ++resolved;
      EXPECT_LE(out[d].distance, 0.0);
      const Placement& target = d == 0 ? pa : pb;
      const Placement& opponent = d == 0 ? pb : pa;
      EXPECT_TRUE(detail::checkResult(out[d], target, opponent).ok());
      EXPECT_FALSE(contactPoseIntersects(mesh, out[d], mesh, opponent, settings.tolerance))
          << "case " << i << " direction " << d;
    }
  }
  ASSERT_GT(intersecting, 10);
  // Two L prisms can interlock so that the half-space rounds free nothing; the sweeps
  // that follow always end at a free pose.
  EXPECT_EQ(resolved, 2 * intersecting);
}

TEST(InitialResolution, CrossingSoupTrianglesSeparate) {
  MeshData quad;
  quad.vertices = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)};
  quad.triangles = {Tri(0, 1, 2), Tri(0, 2, 3)};
  const ModelPtr soup = modelOf(ModelKind::TriangleSoup, quad);
  const Part a{soup.get(), Rigid(), 1}, b{soup.get(), Rigid(), 2};
  // Two unit quads crossing at right angles through each other's centre.
  const Placement pa = placementOf(Quat(Eigen::AngleAxisd(0.5 * M_PI, Vec3::UnitX())), Vec3(0, 0, 0.3));
  const Placement pb = placementOf(Quat::Identity(), Vec3::Zero());
  SceneSettings settings;
  settings.resolve_initial_intersection = true;
  PairTracker tracker;
  DirectedResult out[2];
  tracker.update({&a, 1, pa}, {&b, 1, pb}, {true, true}, settings, out);
  for (int d = 0; d < 2; ++d) {
    ASSERT_EQ(out[d].code, ErrorCode::Ok) << "direction " << d;
    EXPECT_LT(out[d].distance, 0.0);
    const Placement& target = d == 0 ? pa : pb;
    const Placement& opponent = d == 0 ? pb : pa;
    EXPECT_TRUE(detail::checkResult(out[d], target, opponent).ok());
    EXPECT_FALSE(contactPoseIntersects(quad, out[d], quad, opponent, settings.tolerance));
  }
  // A stands in the xz-plane, z in [-0.7, 1.3], through B (z = 0): no exit of A is
  // shorter than 0.7 (up); the exit found is a free pose, not always the shortest.
  EXPECT_GE(out[0].tpdv.norm(), 0.7 - settings.tolerance);
  EXPECT_LE(out[0].tpdv.norm(), 1.3 + settings.tolerance);
}

/// A fresh tracker's first update of `target` at `pose` against `opponent` at the
/// origin; `resolve` sets resolve_initial_intersection.
DirectedResult firstSight(const Part& target, const Part& opponent, const Placement& pose,
                          bool resolve) {
  PairTracker tracker;
  SceneSettings settings;
  settings.resolve_initial_intersection = resolve;
  DirectedResult out[2];
  tracker.update({&target, 1, pose}, {&opponent, 1, Placement()}, {true, false}, settings, out);
  return out[0];
}

/// Free: a fresh tracker does not see the pair intersecting (apart or touching,
/// within the tolerance of contact).
bool freeAt(const Part& target, const Part& opponent, const Placement& pose) {
  return firstSight(target, opponent, pose, false).code != ErrorCode::InvalidInitialTransformation;
}

/// Least free offset along u from `pose` found by marching (steps of 0.1) and
/// bisecting: the translation of a free pose, an upper bound of the depth.
double directionalExit(const Part& target, const Part& opponent, const Placement& pose,
                       const Vec3& u) {
  const auto at = [&](double s) {
    return placementOf(pose.orientation, pose.world_center + s * u);
  };
  double lo = 0.0, hi = 0.1;
  while (!freeAt(target, opponent, at(hi))) lo = hi, hi += 0.1;
  for (int i = 0; i < 14; ++i) {
    const double mid = 0.5 * (lo + hi);
    (freeAt(target, opponent, at(mid)) ? hi : lo) = mid;
  }
  return hi;
}

// A knot deep in an elephant (both of unit size, the knot's centre 0.1 and 0.3 from
// the elephant's, random orientations): the half-space rounds met conflicting exits
// of many leaf pairs and reported InvalidInitialTransformation in most such poses
// (bench/first_sight_depth: 16 and 17 of 20 at 0.1 and 0.3). Each pose must start
// from a free pose whose depth is within 5% (and the tolerance) of the shortest exit
// over random directions (each marched and bisected with fresh trackers, the ground
// truth).
TEST(InitialResolution, DeepNonConvexOverlapsResolveNearTheShortestSampledExit) {
  MeshData knot, elephant;
  ASSERT_NO_FATAL_FAILURE(knot = loadTestMesh("knot1"));
  ASSERT_NO_FATAL_FAILURE(elephant = loadTestMesh("elephant"));
  const ModelPtr mk = modelOf(ModelKind::ClosedPolyhedron, support::fitToSize(knot, 1.0));
  const ModelPtr me = modelOf(ModelKind::ClosedPolyhedron, support::fitToSize(elephant, 1.0));
  ASSERT_TRUE(mk && me);
  const Part a{mk.get(), Rigid(), 1}, b{me.get(), Rigid(), 2};
  Rng rng(20261127);
  const int directions = caseCount(32, 8);
  int cases = 0;
  for (const double offset : {0.1, 0.3}) {
    for (int i = 0; i < caseCount(2, 1); ++i) {
      const Placement pose = placementOf(randomRotation(rng), offset * randomDirection(rng));
      if (freeAt(a, b, pose)) continue;
      ++cases;
      const DirectedResult r = firstSight(a, b, pose, true);
      ASSERT_EQ(r.code, ErrorCode::Ok) << "offset " << offset << " pose " << i;
      EXPECT_TRUE(detail::checkResult(r, pose, Placement()).ok());
      EXPECT_TRUE(freeAt(a, b, placementOf(r.contact_orientation, r.contact_position)));
      double bound = kInfinity;
      for (int d = 0; d < directions; ++d)
        bound = std::min(bound, directionalExit(a, b, pose, randomDirection(rng)));
      // The probes call an overlap within the tolerance touching, hence free: the
      // bound is short of an exit by up to that much.
      EXPECT_LE(r.tpdv.norm(), 1.05 * bound + kDefaultTolerance)
          << "offset " << offset << " pose " << i;
    }
  }
  EXPECT_GE(cases, caseCount(3, 1));
}

}  // namespace
}  // namespace sc::test
