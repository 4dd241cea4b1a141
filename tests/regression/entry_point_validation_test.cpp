// SPDX-License-Identifier: MIT
// Bad input at the public entry points, as a new user would try it: a null piece
// in a model, an out-of-range model kind, calls on an object of unknown type, a
// non-unit quaternion for a static object, out-of-range tracker settings, and a
// float read of a distance beyond float's range. Each gets a clear code (or, for a
// constructor, an exception) and changes nothing; none crashes or answers wrongly.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include "sc.h"
#include "smartcollision/collision.h"
#include "smartcollision/scene.h"
#include "support/sc_results.h"
#include "support/shapes.h"

namespace sc::test {
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(EntryPointValidation, ModelRefusesANullPiece) {
  EXPECT_THROW(Model(ModelKind::ClosedPolyhedron, {nullptr}), std::invalid_argument);
  const ModelPtr box = boxModel(Vec3(1, 1, 1));
  ASSERT_TRUE(box);
  EXPECT_THROW(Model(ModelKind::ClosedPolyhedron, {box->pieces()[0], nullptr}),
               std::invalid_argument);
}

TEST(EntryPointValidation, ModelRefusesPiecesOfAnotherKind) {
  const ModelPtr box = boxModel(Vec3(1, 1, 1));
  ASSERT_TRUE(box);
  EXPECT_THROW(Model(ModelKind::TriangleSoup, box->pieces()), std::invalid_argument);
  EXPECT_THROW(Model(static_cast<ModelKind>(7), {}), std::invalid_argument);
}

TEST(EntryPointValidation, BuildPieceRefusesAnUnknownKind) {
  for (const int kind : {2, 7, 255}) {
    const Result<PiecePtr> piece = buildPiece(static_cast<ModelKind>(kind), boxMesh(Vec3(1, 1, 1)));
    EXPECT_FALSE(piece.hasValue()) << kind;
    EXPECT_EQ(piece.status().code(), ErrorCode::InvalidArgument) << kind;
    EXPECT_FALSE(piece.status().message().empty());
  }
}

TEST(EntryPointValidation, UnknownObjectTypeRefusesTransformations) {
  SCObject object(0x1234);
  const double origin[3] = {1, 2, 3};
  const float origin_f[3] = {1, 2, 3};
  EXPECT_EQ(object.SetTransformation(SC_POSITION_ORIGIN, origin), SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(object.SetTransformation(SC_POSITION_ORIGIN, origin_f), SC_ERROR_INVALID_ARGUMENT);
  double out[3] = {7, 7, 7};
  float out_f[3] = {7, 7, 7};
  EXPECT_EQ(object.GetTransformation(SC_POSITION_ORIGIN, out), SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(object.GetTransformation(SC_POSITION_ORIGIN, out_f), SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(out[0], 7.0) << "a refused call writes nothing";
  EXPECT_EQ(out_f[0], 7.0f);
}

/// Distance between a unit-half-extent box at x = 3 placed with `q` (static) and a
/// moving box at the origin, or the failing status.
Result<double> staticBoxDistance(const Quat& q) {
  const ModelPtr box = boxModel(Vec3(1, 1, 1));
  Scene scene(ModelKind::ClosedPolyhedron);
  Placement moving;
  if (Status s = scene.addObject(1, box, moving); !s.ok()) return s;
  if (Status s = scene.addObjectToGroup(0, 1); !s.ok()) return s;
  Placement fixed;
  fixed.world_center = Vec3(3.5, 0, 0);
  fixed.orientation = q;
  if (Status s = scene.addObject(2, box, fixed); !s.ok()) return s;
  if (Status s = scene.update(); !s.ok()) return s;
  if (scene.pairs().size() != 1) return Status(ErrorCode::NoResult, "no pair listed");
  return scene.pairs()[0].results[0].distance;
}

TEST(EntryPointValidation, AddObjectNormalisesTheQuaternionAsSetGroupPlacementDoes) {
  // A quarter turn about z leaves the box where it was: the boxes are 1.5 apart
  // whatever the quaternion's scale (unnormalised, it would shear the box).
  const Quat quarter(Eigen::AngleAxisd(0.5 * kPi, Vec3::UnitZ()));
  for (const double scale : {1.0, 0.5, 2.0, 1e-200, 1e200}) {
    const Result<double> d = staticBoxDistance(Quat(quarter.coeffs() * scale));
    ASSERT_TRUE(d.ok()) << scale << ": " << d.status().message();
    EXPECT_NEAR(d.value(), 1.5, 1e-9) << "quaternion scaled by " << scale;
  }
  // A group placed with the same quaternion sits where the static object does.
  const ModelPtr box = boxModel(Vec3(1, 1, 1));
  Scene scene(ModelKind::ClosedPolyhedron);
  Placement p;
  p.orientation = Quat(quarter.coeffs() * 0.5);
  ASSERT_TRUE(scene.addObject(1, box, p).ok());
  EXPECT_NEAR(scene.objectPlacement(1).value().orientation.norm(), 1.0, 1e-15);
  ASSERT_TRUE(scene.addObjectToGroup(0, 1).ok());
  ASSERT_TRUE(scene.setGroupPlacement(0, p).ok());
  EXPECT_NEAR(scene.groupPlacement(0).value().orientation.norm(), 1.0, 1e-15);
}

TEST(EntryPointValidation, ZeroOrNonFiniteQuaternionsAreRefusedEverywhere) {
  const ModelPtr box = boxModel(Vec3(1, 1, 1));
  Scene scene(ModelKind::ClosedPolyhedron);
  ASSERT_TRUE(scene.addObject(1, box, Placement()).ok());
  ASSERT_TRUE(scene.addObjectToGroup(0, 1).ok());
  for (const Quat& q : {Quat(0, 0, 0, 0), Quat(kNaN, 0, 0, 0), Quat(1, 0, kNaN, 0),
                        Quat(std::numeric_limits<double>::infinity(), 0, 0, 0)}) {
    Placement p;
    p.orientation = q;
    EXPECT_EQ(scene.addObject(2, box, p).code(), ErrorCode::InvalidArgument);
    EXPECT_FALSE(scene.hasObject(2));
    EXPECT_EQ(scene.setGroupPlacement(0, p).code(), ErrorCode::InvalidArgument);
    EXPECT_EQ(scene.groupPlacement(0).value().orientation.coeffs(), Quat::Identity().coeffs());
  }
}

/// A tracker's two boxes 0.3 deep in each other after a free first frame.
void trackDeepPair(const SceneSettings& settings, DirectedResult out[2]) {
  const ModelPtr box = boxModel(Vec3(1, 1, 1));
  const Part a{box.get(), Rigid(), 1}, b{box.get(), Rigid(), 2};
  Placement pa, pb;
  pb.world_center = Vec3(2.5, 0, 0);
  PairTracker tracker;
  tracker.update({&a, 1, pa}, {&b, 1, pb}, {true, true}, SceneSettings(), out);
  ASSERT_EQ(out[0].code, ErrorCode::Ok);
  ASSERT_NEAR(out[0].distance, 0.5, 1e-12);
  pb.world_center = Vec3(1.7, 0, 0);
  tracker.update({&a, 1, pa}, {&b, 1, pb}, {true, true}, settings, out);
  // The tracker's state is kept: with valid settings it still finds the depth.
  DirectedResult again[2];
  tracker.update({&a, 1, pa}, {&b, 1, pb}, {true, true}, SceneSettings(), again);
  EXPECT_NEAR(again[0].distance, -0.3, 1e-9) << "a refused update changed the tracker";
}

TEST(EntryPointValidation, PairTrackerRefusesOutOfRangeSettings) {
  std::vector<SceneSettings> bad(9);
  bad[0].tolerance = kNaN;
  bad[1].tolerance = 0.0;
  bad[2].max_iterations = 0;
  bad[3].max_iterations = -3;
  bad[4].safety_coefficient = 1.0;
  bad[5].max_distance = kNaN;
  bad[6].force_stiffness = -1.0;
  bad[7].rotation_mode = static_cast<RotationMode>(9);
  bad[8].torque_stiffness = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < bad.size(); ++i) {
    SCOPED_TRACE(::testing::Message() << "settings " << i << ": " << validate(bad[i]).message());
    ASSERT_FALSE(validate(bad[i]).ok());
    DirectedResult out[2];
    ASSERT_NO_FATAL_FAILURE(trackDeepPair(bad[i], out));
    EXPECT_EQ(out[0].code, ErrorCode::InvalidArgument);
    EXPECT_EQ(out[1].code, ErrorCode::InvalidArgument);
  }
  DirectedResult out[2];
  ASSERT_NO_FATAL_FAILURE(trackDeepPair(SceneSettings(), out));
  EXPECT_NEAR(out[0].distance, -0.3, 1e-9);
}

TEST(EntryPointValidation, FloatStatusRefusesValuesBeyondFloatRange) {
  const double v[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const int t[12] = {0, 2, 1, 1, 3, 0, 0, 3, 2, 1, 2, 3};
  SCObject near_object(SC_OBJECT_TYPE_CLOSED_POLYHEDRON),
      far_object(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  ASSERT_EQ(near_object.AddTriangles(v, 4, t, 4), SC_NO_ERROR);
  ASSERT_EQ(far_object.AddTriangles(v, 4, t, 4), SC_NO_ERROR);
  const double far_origin[3] = {2e99, 0, 0};
  ASSERT_EQ(far_object.SetTransformation(SC_POSITION_ORIGIN, far_origin), SC_NO_ERROR);
  PairScene scene(near_object, far_object);
  EXPECT_NEAR(scene.distance(), 2e99, 1e85);
  // As GetTransformation does, a float read of a value beyond float's range is refused.
  float position[3] = {7, 7, 7};
  EXPECT_EQ(far_object.GetTransformation(SC_POSITION_ORIGIN, position), SC_ERROR_INVALID_ARGUMENT);
  float f = 7.0f;
  EXPECT_EQ(scene.manager.GetStatus(SC_DISTANCE, &f, 0, false), SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(f, 7.0f) << "a refused read writes nothing";
  float point[3] = {7, 7, 7};
  EXPECT_EQ(scene.manager.GetStatus(SC_POINT_ON_OPPONENT, point, 0, false),
            SC_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(point[0], 7.0f);
  // Values within range still read as float.
  float normal[3] = {};
  EXPECT_EQ(scene.manager.GetStatus(SC_CONTACT_NORMAL, normal, 0, false), SC_NO_ERROR);
  EXPECT_NEAR(std::abs(normal[0]), 1.0f, 1e-6f);
}

}  // namespace
}  // namespace sc::test
