// SPDX-License-Identifier: MIT
// Scale sweep (docs/api.md, "Scale"): the same scene at every supported scale, in
// decades, gives the same answer in units of the scale: two cubes against their
// analytic distance and penetration depth, and a CGAL mesh against its own answer at
// scale 1, through PairTracker and through sc.h (the Scene beneath it). Pieces
// outside the supported extents are refused at buildPiece and AddTriangles.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "sc.h"
#include "smartcollision/collision.h"
#include "support/meshes.h"
#include "support/sc_results.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::test {
namespace {

/// Every answer, in units of the scale, within this of the reference.
constexpr double kRelativeAccuracy = 1e-6;

/// 10^lo, 10^(lo + step), ..., 10^hi.
std::vector<double> decades(int lo, int hi, int step = 1) {
  std::vector<double> out;
  for (int k = lo; k <= hi; k += step) out.push_back(std::pow(10.0, k));
  return out;
}

/// The mesh sweep builds knot1 at every scale: every third decade under the
/// sanitizers, which make each build some ten times slower.
constexpr int kMeshDecadeStep = SC_TEST_SANITIZED ? 3 : 1;

/// A rigid pose whose origin is given in units of the scale.
struct Pose {
  Quat orientation = Quat::Identity();
  Vec3 origin = Vec3::Zero();
};

/// One frame's result of the moving object (group 0) against the fixed one, lengths
/// divided by the scale.
struct Answer {
  int code = -1;
  double distance = 0.0;
  Vec3 normal = Vec3::Zero();
  Vec3 tpdv = Vec3::Zero();
  Vec3 contact = Vec3::Zero();  ///< centre of the moving object at contact
};

/// A scene at one scale: the fixed object's pose, the moving one's poses in turn.
struct Sweep {
  const MeshData* fixed = nullptr;   ///< at scale 1
  const MeshData* moving = nullptr;  ///< at scale 1
  Pose fixed_pose;
  std::vector<Pose> frames;
};

MeshData scaled(const MeshData& m, double s) {
  MeshData out = m;
  for (Vec3& v : out.vertices) v *= s;
  return out;
}

Placement placementOf(const Pose& p, double s) {
  Placement out;
  out.orientation = p.orientation;
  out.setOrigin(s * p.origin);
  return out;
}

/// Tolerance of a run: `fraction` of the scale, or the default (absolute) for 0.
double toleranceAt(double s, double fraction) {
  return fraction > 0.0 ? fraction * s : kDefaultTolerance;
}

std::vector<Answer> runPairTracker(const Sweep& sweep, double s, double fraction) {
  auto fixed = buildPiece(ModelKind::ClosedPolyhedron, scaled(*sweep.fixed, s));
  auto moving = sweep.moving == sweep.fixed
                    ? fixed  // one piece serves both models
                    : buildPiece(ModelKind::ClosedPolyhedron, scaled(*sweep.moving, s));
  EXPECT_TRUE(fixed.ok() && moving.ok()) << "scale " << s;
  if (!fixed.ok() || !moving.ok()) return {};
  const Model mf(ModelKind::ClosedPolyhedron, {fixed.value()});
  const Model mm(ModelKind::ClosedPolyhedron, {moving.value()});
  const Part pf{&mf, Rigid(), 2}, pm{&mm, Rigid(), 1};
  SceneSettings settings;
  settings.tolerance = toleranceAt(s, fraction);
  PairTracker tracker;
  std::vector<Answer> out;
  for (const Pose& frame : sweep.frames) {
    DirectedResult r[2];
    tracker.update({&pm, 1, placementOf(frame, s)}, {&pf, 1, placementOf(sweep.fixed_pose, s)},
                   {true, false}, settings, r);
    out.push_back({static_cast<int>(r[0].code), r[0].distance / s, r[0].normal, r[0].tpdv / s,
                   r[0].contact_position / s});
  }
  return out;
}

/// Sets a pose through sc.h: orientation {s, vx, vy, vz}, then origin.
template <class Target>
void setPose(Target&& set, const Pose& p, double s) {
  const double q[4] = {p.orientation.w(), p.orientation.x(), p.orientation.y(), p.orientation.z()};
  const Vec3 o = s * p.origin;
  const double origin[3] = {o.x(), o.y(), o.z()};
  EXPECT_EQ(set(SC_ORIENTATION_QUATERNION, q), SC_NO_ERROR);
  EXPECT_EQ(set(SC_POSITION_ORIGIN, origin), SC_NO_ERROR);
}

Vec3 readVec(SCSceneManager& scene, SCenum type) {
  double v[3] = {0, 0, 0};
  EXPECT_EQ(scene.GetStatus(type, v, 0, false), SC_NO_ERROR);
  return {v[0], v[1], v[2]};
}

std::vector<Answer> runManualApi(const Sweep& sweep, double s, double fraction) {
  SCObject fixed(SC_OBJECT_TYPE_CLOSED_POLYHEDRON), moving(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
  EXPECT_EQ(addPiece(fixed, scaled(*sweep.fixed, s)), SC_NO_ERROR) << "scale " << s;
  EXPECT_EQ(addPiece(moving, scaled(*sweep.moving, s)), SC_NO_ERROR) << "scale " << s;
  setPose([&](SCenum type, const double* v) { return fixed.SetTransformation(type, v); },
          sweep.fixed_pose, s);
  SCSceneManager scene(SC_SCENE_MANAGER_CLOSED_POLYHEDRA);
  EXPECT_EQ(scene.SetAttributeDouble(SC_SCENE_MANAGER_TOLERANCE, toleranceAt(s, fraction)),
            SC_NO_ERROR);
  EXPECT_EQ(scene.AddObject(1, &moving), SC_NO_ERROR);
  EXPECT_EQ(scene.AddObject(2, &fixed), SC_NO_ERROR);
  EXPECT_EQ(scene.AddObjectToGroup(0, 1), SC_NO_ERROR);
  std::vector<Answer> out;
  for (const Pose& frame : sweep.frames) {
    setPose([&](SCenum type, const double* v) { return scene.SetTransformation(0, type, v); },
            frame, s);
    EXPECT_EQ(scene.UpdateStatus(), SC_NO_ERROR);
    SCint count = 0, code = -1;
    EXPECT_EQ(scene.GetStatus(SC_STATUS_COUNT, &count), SC_NO_ERROR);
    Answer a;
    if (count == 1 && scene.GetStatus(SC_STATUS_RESULT, &code, 0, false) == SC_NO_ERROR) {
      a.code = code;
      if (code == SC_NO_ERROR) {
        EXPECT_EQ(scene.GetStatus(SC_DISTANCE, &a.distance, 0, false), SC_NO_ERROR);
        a.distance /= s;
        a.normal = readVec(scene, SC_CONTACT_NORMAL);
        a.tpdv = readVec(scene, SC_TPD_VECTOR) / s;
        a.contact = readVec(scene, SC_CONTACT_POSITION) / s;
      }
    }
    out.push_back(a);
  }
  return out;
}

/// "api, tolerance T[, scale S]" for messages: T is `fraction` s, or the default for
/// 0; no scale for s = 0.
std::string label(const char* api, double fraction, double s) {
  char tolerance[48], scale[32] = "";
  if (fraction > 0.0)
    std::snprintf(tolerance, sizeof tolerance, "tolerance %g s", fraction);
  else
    std::snprintf(tolerance, sizeof tolerance, "default tolerance");
  if (s > 0.0) std::snprintf(scale, sizeof scale, ", scale %g", s);
  return std::string(api) + ", " + tolerance + scale;
}

/// Largest difference between two runs (codes must agree), in units of the scale.
double worstDifference(const std::vector<Answer>& got, const std::vector<Answer>& want,
                       const std::string& what) {
  EXPECT_EQ(got.size(), want.size()) << what;
  double worst = 0.0;
  for (std::size_t i = 0; i < std::min(got.size(), want.size()); ++i) {
    EXPECT_EQ(got[i].code, want[i].code) << what << ", frame " << i;
    worst = std::max({worst, std::abs(got[i].distance - want[i].distance),
                      (got[i].normal - want[i].normal).norm(), (got[i].tpdv - want[i].tpdv).norm(),
                      (got[i].contact - want[i].contact).norm()});
  }
  return worst;
}

using Runner = std::vector<Answer> (*)(const Sweep&, double, double);

struct Api {
  const char* name;
  Runner run;
};

void PrintTo(const Api& api, std::ostream* os) { *os << api.name; }

/// One test per API, so that ctest runs them side by side.
class ScaleSweep : public ::testing::TestWithParam<Api> {};

// --- Two cubes: the analytic answer -------------------------------------------

/// Unit cubes, the fixed one turned and off the origin; the moving one, in the fixed
/// one's frame, passes an edge-face gap, then comes in along -x and sinks 1/4 deep.
struct CubeScene {
  MeshData cube = boxMesh(Vec3::Constant(0.5));
  Quat turn = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  Vec3 offset = Vec3(0.37, -0.21, 0.52);
  std::vector<Vec3> local = {{2.0, 1.6, 0.2}, {3.0, 0.3, 0.2}, {0.75, 0.3, 0.2}};

  Sweep sweep() const {
    Sweep s{&cube, &cube, {turn, offset}, {}};
    for (const Vec3& p : local) s.frames.push_back({turn, offset + turn * p});
    return s;
  }
  /// Gaps per axis (1, 0.6, 0) apart, then 1 along x, then 0.25 deep along x.
  std::vector<Answer> truth() const {
    const Vec3 x = turn * Vec3::UnitX();
    const Vec3 edge = turn * Vec3(1.0, 0.6, 0.0);
    return {{0, edge.norm(), edge.normalized(), Vec3::Zero(), offset + turn * local[0]},
            {0, 2.0, x, Vec3::Zero(), offset + turn * local[1]},
            {0, -0.25, x, -0.25 * x, offset + turn * Vec3(1.0, 0.3, 0.2)}};
  }
};

TEST_P(ScaleSweep, CubesMeetTheAnalyticAnswerAtEveryScale) {
  const Api& api = GetParam();
  const CubeScene scene;
  const Sweep sweep = scene.sweep();
  const std::vector<Answer> truth = scene.truth();
  // Tolerances in proportion to the model, and the default one at every scale.
  for (const double fraction : {1e-3, 1e-6, 0.0}) {
    double worst = 0.0;
    for (const double s : decades(-9, 9)) {
      const std::string what = label(api.name, fraction, s);
      const double d = worstDifference(api.run(sweep, s, fraction), truth, what);
      EXPECT_LE(d, kRelativeAccuracy) << what;
      worst = std::max(worst, d);
    }
    std::printf("cubes, %s, 1e-9 to 1e9: worst difference %.3g of the scale\n",
                label(api.name, fraction, 0.0).c_str(), worst);
  }
}

// --- A CGAL mesh: the answer at scale 1, scaled --------------------------------

/// knot1 (a non-convex tube) of extent 1 against a turned copy coming in along -x
/// from a clear gap until it is well inside, one frame per twentieth of its size.
struct KnotScene {
  MeshData knot;
  Sweep sweep() const {
    Sweep s{&knot, &knot, {Quat::Identity(), Vec3::Zero()}, {}};
    const Quat turn(Eigen::AngleAxisd(0.5 * EIGEN_PI, Vec3::UnitX()));
    for (int i = 0; i <= 16; ++i) s.frames.push_back({turn, Vec3(1.3 - 0.05 * i, 0.07, 0.03)});
    return s;
  }
};

MeshData unitKnot() {
  MeshData m = loadTestMesh("knot1");
  if (m.triangles.empty()) return m;
  Aabb box;
  for (const Vec3& v : m.vertices) box.extend(v);
  const Vec3 center = 0.5 * (box.min + box.max);
  const double size = (box.max - box.min).maxCoeff();
  for (Vec3& v : m.vertices) v = (v - center) / size;
  return m;
}

TEST_P(ScaleSweep, MeshMatchesItsScaleOneAnswerAtEveryScale) {
  const Api& api = GetParam();
  KnotScene scene;
  ASSERT_NO_FATAL_FAILURE(scene.knot = unitKnot());
  const Sweep sweep = scene.sweep();
  const std::vector<Answer> reference = api.run(sweep, 1.0, 1e-3);
  // The path must show both kinds of answer for the sweep to test them.
  ASSERT_EQ(reference.size(), sweep.frames.size());
  for (const Answer& a : reference) ASSERT_EQ(a.code, 0);
  ASSERT_GT(reference.front().distance, 0.0);
  ASSERT_LT(reference.back().distance, -0.01);
  double worst = 0.0;
  for (const double s : decades(-6, 6, kMeshDecadeStep)) {
    const std::string what = label(api.name, 1e-3, s);
    const double d = worstDifference(api.run(sweep, s, 1e-3), reference, what);
    EXPECT_LE(d, kRelativeAccuracy) << what;
    worst = std::max(worst, d);
  }
  std::printf("knot1, %s, 1e-6 to 1e6: worst difference %.3g of the scale\n",
              label(api.name, 1e-3, 0.0).c_str(), worst);
}

INSTANTIATE_TEST_SUITE_P(Apis, ScaleSweep,
                         ::testing::Values(Api{"PairTracker", runPairTracker},
                                           Api{"sc.h", runManualApi}),
                         [](const ::testing::TestParamInfo<Api>& param) {
                           return std::string(param.index == 0 ? "PairTracker" : "ManualApi");
                         });

// --- Refused scales ---------------------------------------------------------------

TEST(ScaleLimits, PiecesOutsideTheSupportedExtentsAreRefused) {
  for (const double s :
       {1e-310, 1e-160, 1e-12, 0.99 * kMinPieceExtent, 1.01 * kMaxPieceExtent, 1e12, 1e99}) {
    SCOPED_TRACE(testing::Message() << "extent " << s);
    const MeshData cube = boxMesh(Vec3::Constant(0.5 * s));
    for (const ModelKind kind : {ModelKind::ClosedPolyhedron, ModelKind::TriangleSoup}) {
      const Result<PiecePtr> piece = buildPiece(kind, cube);
      EXPECT_FALSE(piece.hasValue());
      EXPECT_EQ(piece.status().code(), ErrorCode::InvalidArgument);
      EXPECT_NE(piece.status().message().find("outside the supported scales"), std::string::npos)
          << piece.status().message();
    }
    // sc.h: refused, and the object is unchanged (a valid piece is still piece 0).
    SCObject o(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
    EXPECT_EQ(addPiece(o, cube), SC_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(addPiece(o, boxMesh(Vec3::Constant(0.5))), SC_NO_ERROR);
    SCObject probe(SC_OBJECT_TYPE_CLOSED_POLYHEDRON);
    EXPECT_EQ(addPiece(probe, boxMesh(Vec3::Constant(0.5))), SC_NO_ERROR);
    const double origin[3] = {3, 0, 0};
    EXPECT_EQ(probe.SetTransformation(SC_POSITION_ORIGIN, origin), SC_NO_ERROR);
    PairScene scene(probe, o);
    SCint pieces[2] = {-1, -1};
    EXPECT_EQ(scene.manager.GetStatus(SC_PIECE_ID, pieces, 0, false), SC_NO_ERROR);
    EXPECT_EQ(pieces[1], 0);
    EXPECT_NEAR(scene.distance(), 2.0, 1e-12);
  }
}

TEST(ScaleLimits, TheSupportedExtentsThemselvesAreAccepted) {
  for (const double s : {kMinPieceExtent, kMaxPieceExtent}) {
    for (const ModelKind kind : {ModelKind::ClosedPolyhedron, ModelKind::TriangleSoup}) {
      const Result<PiecePtr> piece = buildPiece(kind, boxMesh(Vec3::Constant(0.5 * s)));
      EXPECT_TRUE(piece.ok()) << "extent " << s << ": " << piece.status().message();
    }
  }
  // A soup that is one point has no scale: kept, as any degenerate soup triangle.
  MeshData point;
  point.vertices = {Vec3(1e-20, 0, 0)};
  point.triangles = {Tri(0, 0, 0)};
  EXPECT_TRUE(buildPiece(ModelKind::TriangleSoup, point).ok());
}

}  // namespace
}  // namespace sc::test
