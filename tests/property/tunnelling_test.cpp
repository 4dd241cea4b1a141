// SPDX-License-Identifier: MIT
// No tunnelling: a small object moved completely through a thin wall (a thin closed
// box, or a two-triangle soup quad) in one update, or in a fast sequence, stays
// penetrating on the side it came from although its final pose is free.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "penetration/result_invariants.h"
#include "smartcollision/collision.h"
#include "support/brute_force.h"
#include "support/placements.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::test {
namespace {

constexpr int kCases = caseCount(400, 40);
constexpr double kWallHalfThickness = 0.01;
constexpr double kWallHalfSize = 1.0;

ModelPtr modelOf(ModelKind kind, const MeshData& mesh) {
  auto piece = buildPiece(kind, mesh);
  EXPECT_TRUE(piece.ok()) << piece.status().message();
  if (!piece.ok()) return nullptr;
  return std::make_shared<Model>(kind, std::vector<PiecePtr>{piece.value()});
}

/// The wall z in [-h, h] (closed box) or the quad z = 0 (soup), |x|, |y| <= 1.
MeshData wallMesh(ModelKind kind) {
  if (kind == ModelKind::ClosedPolyhedron)
    return boxMesh(Vec3(kWallHalfSize, kWallHalfSize, kWallHalfThickness));
  MeshData quad;
  const double s = kWallHalfSize;
  quad.vertices = {Vec3(-s, -s, 0), Vec3(s, -s, 0), Vec3(s, s, 0), Vec3(-s, s, 0)};
  quad.triangles = {Tri{0, 1, 2}, Tri{0, 2, 3}};
  return quad;
}

struct Wall {
  ModelKind kind;
  const char* name;
};

class Tunnelling : public ::testing::TestWithParam<Wall> {};

/// One update from a free pose on one side to a free pose on the other.
TEST_P(Tunnelling, OneUpdateThroughTheWallReportsPenetration) {
  const Wall wall = GetParam();
  const std::uint64_t seed = 4242 + static_cast<int>(wall.kind);
  SCOPED_TRACE(testing::Message() << "seed " << seed);
  Rng rng(seed);
  const MeshData wall_mesh = wallMesh(wall.kind);
  const ModelPtr wall_model = modelOf(wall.kind, wall_mesh);
  ASSERT_TRUE(wall_model);
  const Part wall_part{wall_model.get(), Rigid(), 2};
  const Placement wall_place;
  const RotationMode modes[4] = {RotationMode::None, RotationMode::Input, RotationMode::Free,
                                 RotationMode::Mix};
  int reported = 0;
  for (int i = 0; i < kCases; ++i) {
    SCOPED_TRACE(testing::Message() << "case " << i);
    const double size = uniform(rng, 0.02, 0.2);
    const MeshData body = randomTetrahedronMesh(rng, size);
    const ModelPtr body_model = modelOf(ModelKind::ClosedPolyhedron, body);
    ASSERT_TRUE(body_model);
    const Part body_part{body_model.get(), Rigid(), 1};
    // Start and end well clear of the wall, on opposite sides, over its inner part.
    const double side = uniform(rng, 0.0, 1.0) < 0.5 ? -1.0 : 1.0;
    const Vec3 start(uniform(rng, -0.5, 0.5), uniform(rng, -0.5, 0.5),
                     side * uniform(rng, 0.3, 1.0));
    const Vec3 end(uniform(rng, -0.5, 0.5), uniform(rng, -0.5, 0.5),
                   -side * uniform(rng, 0.3, 1.0));
    const Quat q0 = randomRotation(rng);
    const Quat q1 = Quat(Eigen::AngleAxisd(uniform(rng, 0.0, 0.5), randomDirection(rng))) * q0;
    const Placement from = placementOf(q0, start), to = placementOf(q1, end);
    // The final pose really is free (brute force over the triangle pairs).
    ASSERT_GT(meshSurfaceDistance(body, to.worldFromLocal(), wall_mesh, Rigid()).distance, 0.1);
    SceneSettings settings;
    settings.tolerance = 1e-3;
    settings.rotation_mode = modes[i % 4];
    PairTracker tracker;
    DirectedResult out[2];
    tracker.update({&body_part, 1, from}, {&wall_part, 1, wall_place}, {true, false}, settings,
                   out);
    ASSERT_EQ(out[0].code, ErrorCode::Ok);
    ASSERT_GT(out[0].distance, 0.0);
    tracker.update({&body_part, 1, to}, {&wall_part, 1, wall_place}, {true, false}, settings, out);
    const DirectedResult& r = out[0];
    ASSERT_EQ(r.code, ErrorCode::Ok);
    const Status valid = detail::checkResult(r, to, wall_place);
    EXPECT_TRUE(valid.ok()) << valid.message();
    EXPECT_LT(r.distance, 0.0) << "tunnelled through the " << wall.name;
    if (r.distance < 0.0) ++reported;
    // The contact configuration stays on the side it came from, next to the wall.
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& v : body.vertices) centroid += v / static_cast<double>(body.vertices.size());
    const Rigid contact = placementOf(r.contact_orientation, r.contact_position).worldFromLocal();
    EXPECT_GT(side * (contact * centroid).z(), 0.0);
    // The normal faces the entry side: the wall's normal, but for an edge of the body
    // resting on the soup quad's diagonal, where each triangle's normal is that of
    // two edges (perpendicular to both, so tilted), still towards the entry side.
    const Vec3& on_wall = r.point_on_opponent;
    const bool on_seam = wall.kind == ModelKind::TriangleSoup &&
                         std::abs(on_wall.x() - on_wall.y()) < 1e-9 * kWallHalfSize;
    EXPECT_GT(side * r.normal.z(), on_seam ? 0.0 : 0.9);
    EXPECT_LE(meshSurfaceDistance(body, contact, wall_mesh, Rigid()).distance, settings.tolerance);
  }
  std::printf("[ tunnelling ] %s, one update: %d of %d report penetration\n", wall.name, reported,
              kCases);
}

/// A 0.1 cube (part 1) and the wall (part 2), both at the origin of their frames.
struct BoxAndWall {
  explicit BoxAndWall(ModelKind kind)
      : wall_mesh(wallMesh(kind)),
        body(boxMesh(Vec3(0.05, 0.05, 0.05))),
        wall_model(modelOf(kind, wall_mesh)),
        body_model(modelOf(ModelKind::ClosedPolyhedron, body)),
        wall_part{wall_model.get(), Rigid(), 2},
        body_part{body_model.get(), Rigid(), 1} {}
  MeshData wall_mesh, body;
  ModelPtr wall_model, body_model;
  Part wall_part, body_part;
};

/// A fast sequence: steps far larger than the wall's thickness cross it; the depth
/// stays path-dependent while beyond it and vanishes when the body comes back.
TEST_P(Tunnelling, FastSequenceStaysOnTheEntrySide) {
  const Wall wall = GetParam();
  const BoxAndWall scene(wall.kind);
  ASSERT_TRUE(scene.wall_model && scene.body_model);
  const Part &wall_part = scene.wall_part, &body_part = scene.body_part;
  const Placement wall_place;
  SceneSettings settings;
  PairTracker tracker;
  DirectedResult out[2];
  // z: 1.0, 0.7, ..., -1.1 (steps of 0.3), then back up the same way.
  std::vector<double> zs;
  for (int k = 0; k <= 7; ++k) zs.push_back(1.0 - 0.3 * k);
  for (int k = 6; k >= 0; --k) zs.push_back(1.0 - 0.3 * k);
  bool crossed = false;
  for (double z : zs) {
    SCOPED_TRACE(testing::Message() << "z " << z);
    const Placement p = placementOf(Quat::Identity(), Vec3(0.1, -0.2, z));
    tracker.update({&body_part, 1, p}, {&wall_part, 1, wall_place}, {true, false}, settings, out);
    const DirectedResult& r = out[0];
    ASSERT_EQ(r.code, ErrorCode::Ok);
    EXPECT_TRUE(detail::checkResult(r, p, wall_place).ok());
    const double top = wall.kind == ModelKind::ClosedPolyhedron ? kWallHalfThickness : 0.0;
    if (z - 0.05 > top) crossed = false;  // back out on top: the proxy follows
    if (z + 0.05 < -top) crossed = true;
    if (crossed || (z - 0.05 <= top && z + 0.05 >= -top)) {
      EXPECT_LT(r.distance, 0.0);
      // Pushed back up to the top face: depth = how far below it the body's bottom is.
      EXPECT_NEAR(-r.distance, top - (z - 0.05), 1e-9);
      EXPECT_VEC_NEAR(r.normal, Vec3::UnitZ(), 1e-9);
    } else {
      EXPECT_GT(r.distance, 0.0);
    }
  }
}

/// A body resting within the tolerance above the wall, its contacts never gathered
/// (it came down in certified steps), then moved through the wall in one update to a
/// free pose: the update measures the goal first (its near pairs do not reach the
/// body), and its sweep from the rest still stops at the wall.
TEST_P(Tunnelling, FromRestWithinTheToleranceThroughTheWall) {
  const Wall wall = GetParam();
  const BoxAndWall scene(wall.kind);
  ASSERT_TRUE(scene.wall_model && scene.body_model);
  const Part &wall_part = scene.wall_part, &body_part = scene.body_part;
  const MeshData &wall_mesh = scene.wall_mesh, &body = scene.body;
  const Placement wall_place;
  const double top = wall.kind == ModelKind::ClosedPolyhedron ? kWallHalfThickness : 0.0;
  for (const RotationMode mode : {RotationMode::Input, RotationMode::None}) {
    SceneSettings settings;
    settings.tolerance = 1e-3;
    settings.rotation_mode = mode;
    PairTracker tracker;
    DirectedResult out[2];
    // Down to 0.6 tolerances above the wall, then 0.3 further down, through it.
    for (const double z : {0.5, 0.2, top + 0.05 + 0.6e-3, top + 0.05 + 0.6e-3 - 0.3}) {
      SCOPED_TRACE(testing::Message() << "mode " << static_cast<int>(mode) << " z " << z);
      const Placement p = placementOf(Quat::Identity(), Vec3(0.1, -0.2, z));
      tracker.update({&body_part, 1, p}, {&wall_part, 1, wall_place}, {true, false}, settings, out);
      const DirectedResult& r = out[0];
      ASSERT_EQ(r.code, ErrorCode::Ok);
      EXPECT_TRUE(detail::checkResult(r, p, wall_place).ok());
      if (z > 0.0) {
        EXPECT_NEAR(r.distance, z - 0.05 - top, 1e-9);
        continue;
      }
      ASSERT_GT(meshSurfaceDistance(body, p.worldFromLocal(), wall_mesh, Rigid()).distance, 0.1);
      EXPECT_NEAR(-r.distance, top - (z - 0.05), 1e-9) << "tunnelled through the " << wall.name;
      EXPECT_VEC_NEAR(r.normal, Vec3::UnitZ(), 1e-9);
    }
  }
}

/// A body pressed into a ground slab, then moved in one update far along it (a jump):
/// with a fin standing between, the proxy stays on the side it came from, touching
/// the fin and the ground; with the fin out of the way it reaches the goal's contact. The
/// update may leave the surface on its way (a free path certifies the move as well
/// as the straight one), never pass through what stands in it.
TEST(TunnellingJump, AlongTheGroundPastAFinInOneUpdate) {
  const MeshData ground = boxMesh(Vec3(1.0, 1.0, 0.01));
  const MeshData fin = boxMesh(Vec3(0.005, 1.0, 0.1));
  const MeshData body = boxMesh(Vec3(0.05, 0.05, 0.05));
  const ModelPtr ground_model = modelOf(ModelKind::ClosedPolyhedron, ground);
  const ModelPtr fin_model = modelOf(ModelKind::ClosedPolyhedron, fin);
  const ModelPtr body_model = modelOf(ModelKind::ClosedPolyhedron, body);
  ASSERT_TRUE(ground_model && fin_model && body_model);
  const Part body_part{body_model.get(), Rigid(), 1};
  const double rest = 0.01 + 0.05, depth = 2e-3;
  for (const bool with_fin : {true, false}) {
    // On the ground, x in +-0.005, or out of the way at x = 0.8 (still a non-convex
    // opponent, so the general path runs).
    const Rigid fin_pose{Mat3::Identity(), Vec3(with_fin ? 0.0 : 0.8, 0.0, 0.1)};
    const Part parts[2] = {{ground_model.get(), Rigid(), 2}, {fin_model.get(), fin_pose, 3}};
    for (const double jump : {0.1, 0.3, 0.6}) {
      SCOPED_TRACE(testing::Message() << "fin " << with_fin << " jump " << jump);
      SceneSettings settings;
      settings.tolerance = 1e-3;
      PairTracker tracker;
      DirectedResult out[2];
      const GroupView opponent{parts, 2, Placement()};
      const double x0 = -0.06 - 0.5 * jump;
      // Apart, pressed in, pressed in a little further (the proxy in contact), then far.
      for (const Vec3& c :
           {Vec3(x0, 0.1, rest + 5e-4), Vec3(x0, 0.1, rest - 0.5 * depth),
            Vec3(x0, 0.1, rest - depth), Vec3(x0 + jump + 0.12, 0.1, rest - depth)}) {
        const Placement p = placementOf(Quat::Identity(), c);
        tracker.update({&body_part, 1, p}, opponent, {true, false}, settings, out);
        ASSERT_EQ(out[0].code, ErrorCode::Ok);
        EXPECT_TRUE(detail::checkResult(out[0], p, Placement()).ok());
      }
      const DirectedResult& r = out[0];
      ASSERT_LT(r.distance, 0.0);
      const Rigid contact = placementOf(r.contact_orientation, r.contact_position).worldFromLocal();
      // The contact configuration rests on the ground, within the tolerance of it, and,
      // with the fin, on the side the body came from, next to it.
      EXPECT_NEAR(r.contact_position.z(), rest, settings.tolerance);
      if (with_fin) {
        EXPECT_LT(r.contact_position.x(), -0.005 - 0.05 + 1e-9) << "passed through the fin";
        EXPECT_GT(r.contact_position.x(), -0.005 - 0.05 - settings.tolerance);
        EXPECT_LE(meshSurfaceDistance(body, contact, fin, fin_pose).distance, settings.tolerance);
      } else {
        EXPECT_NEAR(-r.distance, depth, 1e-9);
        EXPECT_VEC_NEAR(r.normal, Vec3::UnitZ(), 1e-9);
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Walls, Tunnelling,
                         ::testing::Values(Wall{ModelKind::ClosedPolyhedron, "thin box"},
                                           Wall{ModelKind::TriangleSoup, "soup quad"}),
                         [](const ::testing::TestParamInfo<Wall>& param_info) {
                           return param_info.param.kind == ModelKind::ClosedPolyhedron ? "ThinBox"
                                                                                       : "SoupQuad";
                         });

}  // namespace
}  // namespace sc::test
