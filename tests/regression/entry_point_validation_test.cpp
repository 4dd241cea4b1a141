// SPDX-License-Identifier: MIT
// Bad input at the public entry points, as a new user would try it: a null piece
// in a model, an out-of-range model kind, calls on an object of unknown type, a
// non-unit quaternion for a static object, out-of-range tracker settings or poses,
// unnamed activity values, a scene manager of unknown type, and a float read of a
// distance beyond float's range. Each gets a clear code (or, for a
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

/// A unit cube (half extent 0.5) as group a at `pa`, one at the origin as group b.
struct CubeOverCube {
  ModelPtr cube = boxModel(Vec3(0.5, 0.5, 0.5));
  Part a{cube.get(), Rigid(), 1}, b{cube.get(), Rigid(), 2};
  PairTracker tracker;
  DirectedResult out[2];

  void update(const Placement& pa) {
    tracker.update({&a, 1, pa}, {&b, 1, Placement()}, {true, true}, SceneSettings(), out);
  }
};

Placement at(const Vec3& center, const Quat& q = Quat::Identity()) {
  Placement p;
  p.world_center = center;
  p.orientation = q;
  return p;
}

/// Placements Scene::setGroupPlacement refuses.
std::vector<Placement> unusablePlacements() {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<Placement> bad = {at(Vec3(kNaN, 0, 2)), at(Vec3(inf, 0, 2)), at(Vec3(1e200, 0, 2)),
                                at(Vec3(0, 0, 2), Quat(kNaN, 0, 0, 0)),
                                at(Vec3(0, 0, 2), Quat(0, 0, 0, 0))};
  bad.push_back(at(Vec3(0, 0, 2)));
  bad.back().local_center = Vec3(0, -1e101, 0);
  return bad;
}

TEST(EntryPointValidation, PairTrackerRefusesThePlacementsTheSceneRefuses) {
  Scene scene(ModelKind::ClosedPolyhedron);
  ASSERT_TRUE(scene.addObject(1, boxModel(Vec3(1, 1, 1)), Placement()).ok());
  ASSERT_TRUE(scene.addObjectToGroup(0, 1).ok());
  for (const Placement& p : unusablePlacements()) {
    SCOPED_TRACE(::testing::Message() << "centre " << p.world_center.transpose() << " q "
                                      << p.orientation.coeffs().transpose());
    ASSERT_EQ(scene.setGroupPlacement(0, p).code(), ErrorCode::InvalidArgument);
    CubeOverCube pair;
    const Status why = validate(GroupView{&pair.a, 1, p});
    EXPECT_EQ(why.code(), ErrorCode::InvalidArgument);
    EXPECT_FALSE(why.message().empty());
    // First seen: refused, nothing started.
    pair.update(p);
    EXPECT_EQ(pair.out[0].code, ErrorCode::InvalidArgument);
    EXPECT_EQ(pair.out[1].code, ErrorCode::InvalidArgument);
    EXPECT_FALSE(pair.tracker.tracking(0));
    // While tracking: refused, either side, and the tracking state is kept: the path
    // goes on from z = 1.5 into a penetration 0.1 deep, then out to z = 2 (apart by 1).
    pair.update(at(Vec3(0, 0, 1.5)));
    ASSERT_EQ(pair.out[0].code, ErrorCode::Ok);
    pair.update(p);
    EXPECT_EQ(pair.out[0].code, ErrorCode::InvalidArgument);
    EXPECT_EQ(pair.out[1].code, ErrorCode::InvalidArgument);
    pair.tracker.update({&pair.a, 1, at(Vec3(0, 0, 1.5))}, {&pair.b, 1, p}, {true, true},
                        SceneSettings(), pair.out);
    EXPECT_EQ(pair.out[0].code, ErrorCode::InvalidArgument);
    EXPECT_TRUE(pair.tracker.tracking(0));
    pair.update(at(Vec3(0, 0, 0.9)));
    ASSERT_EQ(pair.out[0].code, ErrorCode::Ok);
    EXPECT_EQ(pair.out[0].status, DirectionStatus::Penetrating);
    EXPECT_NEAR(pair.out[0].distance, -0.1, 1e-9);
    EXPECT_NEAR(pair.out[0].tpdv.z(), -0.1, 1e-9);
    pair.update(at(Vec3(5, 0, 2)));
    ASSERT_EQ(pair.out[0].code, ErrorCode::Ok);
    EXPECT_NEAR(pair.out[0].distance, std::hypot(4.0, 1.0), 1e-9);
  }
}

TEST(EntryPointValidation, PairTrackerNormalisesTheQuaternionAsTheSceneDoes) {
  // A 2 x 1 x 1 box turned a quarter about z spans y in [-1, 1]: at y = 2.5 it is 1
  // from a unit cube at the origin, whatever the quaternion's scale.
  const ModelPtr bar = boxModel(Vec3(1, 0.5, 0.5));
  const ModelPtr cube = boxModel(Vec3(0.5, 0.5, 0.5));
  const Part a{bar.get(), Rigid(), 1}, b{cube.get(), Rigid(), 2};
  const Quat quarter(Eigen::AngleAxisd(0.5 * kPi, Vec3::UnitZ()));
  for (const double scale : {1.0, 0.5, 2.0, 1e-200, 1e200}) {
    PairTracker tracker;
    DirectedResult out[2];
    const Placement p = at(Vec3(0, 2.5, 0), Quat(quarter.coeffs() * scale));
    tracker.update({&a, 1, p}, {&b, 1, Placement()}, {true, true}, SceneSettings(), out);
    ASSERT_EQ(out[0].code, ErrorCode::Ok) << scale;
    EXPECT_NEAR(out[0].distance, 1.0, 1e-9) << "quaternion scaled by " << scale;
    EXPECT_NEAR(out[1].distance, 1.0, 1e-9) << "quaternion scaled by " << scale;
  }
}

TEST(EntryPointValidation, PairTrackerRefusesAMalformedGroupView) {
  CubeOverCube pair;
  const Placement up = at(Vec3(0, 0, 2));
  for (const GroupView& bad : {GroupView{nullptr, 1, up}, GroupView{&pair.a, -1, up}}) {
    EXPECT_EQ(validate(bad).code(), ErrorCode::InvalidArgument);
    pair.tracker.update(bad, {&pair.b, 1, Placement()}, {true, true}, SceneSettings(), pair.out);
    EXPECT_EQ(pair.out[0].code, ErrorCode::InvalidArgument);
    EXPECT_EQ(pair.out[1].code, ErrorCode::InvalidArgument);
  }
  // An empty group is valid and has nothing to measure.
  EXPECT_TRUE(validate(GroupView{nullptr, 0, up}).ok());
  pair.update(up);
  EXPECT_NEAR(pair.out[0].distance, 1.0, 1e-12);
}

/// A moving unit cube 0.5 above a static one: one pair listed, 0.5 apart.
struct TwoCubeScene {
  Scene scene{ModelKind::ClosedPolyhedron};
  TwoCubeScene() {
    const ModelPtr cube = boxModel(Vec3(0.5, 0.5, 0.5));
    EXPECT_TRUE(scene.addObject(1, cube, at(Vec3(0, 0, 1.5))).ok());
    EXPECT_TRUE(scene.addObject(2, cube, Placement()).ok());
    EXPECT_TRUE(scene.addObjectToGroup(0, 1).ok());
  }
  void expectListedApart() {
    ASSERT_TRUE(scene.update().ok());
    ASSERT_EQ(scene.pairs().size(), 1u);
    EXPECT_EQ(scene.pairs()[0].results[0].code, ErrorCode::Ok);
    EXPECT_NEAR(scene.pairs()[0].results[0].distance, 0.5, 1e-12);
  }
};

TEST(EntryPointValidation, UnnamedActivitiesAreRefusedAndChangeNothing) {
  TwoCubeScene s;
  s.expectListedApart();
  for (const int value : {4, 9, 255}) {
    const Status group = s.scene.setGroupActivity(0, static_cast<Activity>(value));
    EXPECT_EQ(group.code(), ErrorCode::InvalidArgument) << value;
    EXPECT_FALSE(group.message().empty());
    s.expectListedApart();
    const Status pair = s.scene.setPairActivity(0, kStaticGroup, static_cast<PairActivity>(value));
    EXPECT_EQ(pair.code(), ErrorCode::InvalidArgument) << value;
    EXPECT_FALSE(pair.message().empty());
    s.expectListedApart();
  }
}

TEST(EntryPointValidation, UnknownSceneTypeRefusesEveryCall) {
  const double v[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const int t[12] = {0, 2, 1, 1, 3, 0, 0, 3, 2, 1, 2, 3};
  // SC_OBJECT_TYPE_CLOSED_POLYHEDRON is an object type, easily taken for the scene's.
  for (const SCenum type : {SCenum(0x1234), SC_OBJECT_TYPE_CLOSED_POLYHEDRON}) {
    SCOPED_TRACE(::testing::Message() << "type " << type);
    SCSceneManager m(type);
    SCObject object(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
    ASSERT_EQ(object.AddTriangles(v, 4, t, 4), SC_NO_ERROR);
    const SCint bad = SC_ERROR_INVALID_ARGUMENT;
    EXPECT_EQ(m.AddObject(1, &object), bad);
    EXPECT_EQ(m.DeleteObject(1), bad);
    EXPECT_EQ(m.AddObjectToGroup(0, 1), bad);
    EXPECT_EQ(m.DeleteObjectFromGroup(0, 1), bad);
    EXPECT_EQ(m.DeleteFromGroup(0, 1), bad);
    double d3[3] = {7, 7, 7};
    float f3[3] = {7, 7, 7};
    EXPECT_EQ(m.SetTransformation(0, SC_POSITION_ORIGIN, d3), bad);
    EXPECT_EQ(m.SetTransformation(0, SC_POSITION_ORIGIN, f3), bad);
    EXPECT_EQ(m.GetTransformation(0, SC_POSITION_ORIGIN, d3), bad);
    EXPECT_EQ(m.GetTransformation(0, SC_POSITION_ORIGIN, f3), bad);
    EXPECT_EQ(m.SetActivityObject(1, SC_ACTIVITY_ACTIVE), bad);
    EXPECT_EQ(m.SetActivityGroup(0, SC_ACTIVITY_ACTIVE), bad);
    EXPECT_EQ(m.SetActivityPair(0, 1, SC_ACTIVITY_ACTIVE), bad);
    EXPECT_EQ(m.SetAttributeDouble(SC_SCENE_MANAGER_TOLERANCE, 0.1), bad);
    EXPECT_EQ(m.SetAttributeInteger(SC_SCENE_MANAGER_MAX_ITERATION, 10), bad);
    EXPECT_EQ(m.SetAttributeEnum(SC_SCENE_MANAGER_ROTATION_MODE, SC_ROTATION_MODE_INPUT), bad);
    double d = 7;
    SCint n = 7;
    SCenum e = 7;
    float f = 7;
    EXPECT_EQ(m.GetAttributeDouble(SC_SCENE_MANAGER_TOLERANCE, &d), bad);
    EXPECT_EQ(m.GetAttributeInteger(SC_SCENE_MANAGER_MAX_ITERATION, &n), bad);
    EXPECT_EQ(m.GetAttributeEnum(SC_SCENE_MANAGER_ROTATION_MODE, &e), bad);
    EXPECT_EQ(m.UpdateStatus(), bad);
    EXPECT_EQ(m.GetStatus(SC_STATUS_COUNT, &n), bad);
    EXPECT_EQ(m.GetStatus(SC_STATUS_COUNT, &n, 0, false), bad);
    EXPECT_EQ(m.GetStatus(SC_DISTANCE, &f, 0, false), bad);
    EXPECT_EQ(m.GetStatus(SC_DISTANCE, &d, 0, false), bad);
    EXPECT_EQ(d3[0], 7.0) << "a refused call writes nothing";
    EXPECT_EQ(f3[0], 7.0f);
    EXPECT_EQ(d, 7.0);
    EXPECT_EQ(n, 7);
    EXPECT_EQ(e, 7);
    EXPECT_EQ(f, 7.0f);
  }
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
