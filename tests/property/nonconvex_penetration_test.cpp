// SPDX-License-Identifier: MIT
// Dynamic penetration depth between non-convex CGAL meshes along smooth approach
// paths, checked independently with FCL's mesh distance: the reported contact pose
// penetrates by at most the tolerance, distance = -|TPDV|, and TPDV has no jumps.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "geometry/math_util.h"
#include "penetration/result_invariants.h"
#include "sc_support/off_mesh.h"
#include "smartcollision/collision.h"
#include "support/meshes.h"
#include "support/placements.h"
#include "support/shapes.h"
#include "support/test_support.h"

#if SC_TEST_HAVE_FCL
#include <fcl/fcl.h>
#endif

namespace sc {
namespace {

using test::placementOf;

constexpr int kPaths = test::caseCount(200, 12);
/// Tolerance of the meshes scaled to a largest box side of 1.
constexpr double kTolerance = 1e-3;
/// Path: from kStartGap before first contact to kDepth past it, in steps of kStep.
constexpr double kStartGap = 1.0 * kTolerance;
constexpr double kDepth = 4.0 * kTolerance;
constexpr double kStep = 0.5 * kTolerance;
/// Rotation over the whole path moves points at the target's radius by this.
constexpr double kTurn = 3.0 * kTolerance;
/// Documented bound: |TPDV_k - TPDV_(k-1)| <= kJumpMultiple * (|dc| + |dtheta| rho).
constexpr double kJumpMultiple = 2.0;

struct PairCase {
  const char* target;
  const char* opponent;
};

double boundingRadius(const MeshData& mesh) {
  double r = 0.0;
  for (const Vec3& v : mesh.vertices) r = std::max(r, v.norm());
  return r;
}

#if SC_TEST_HAVE_FCL

using FclModel = fcl::BVHModel<fcl::OBBRSSd>;

fcl::Transform3d fclTransform(const Rigid& r) {
  fcl::Transform3d t = fcl::Transform3d::Identity();
  t.linear() = r.rotation;
  t.translation() = r.translation;
  return t;
}

/// One mesh, preprocessed once for the whole suite (the build takes seconds).
struct Prepared {
  MeshData mesh;
  std::unique_ptr<Model> model;
  std::shared_ptr<FclModel> fcl;
  double radius = 0.0;
};

const Prepared& prepared(const std::string& name) {
  static std::map<std::string, std::unique_ptr<Prepared>> cache;
  auto& slot = cache[name];
  if (slot) return *slot;
  slot = std::make_unique<Prepared>();
  MeshData raw = test::loadTestMesh(name);
  if (raw.triangles.empty()) return *slot;
  slot->mesh = support::fitToSize(std::move(raw), 1.0);  // largest box side 1
  Result<PiecePtr> piece = buildPiece(ModelKind::ClosedPolyhedron, slot->mesh);
  EXPECT_TRUE(piece.ok()) << name << ": " << piece.status().message();
  if (!piece.ok()) return *slot;
  slot->model = std::make_unique<Model>(ModelKind::ClosedPolyhedron,
                                        std::vector<PiecePtr>{piece.value()});
  slot->fcl = std::make_shared<FclModel>();
  std::vector<fcl::Vector3d> points(slot->mesh.vertices.begin(), slot->mesh.vertices.end());
  std::vector<fcl::Triangle> triangles;
  for (const Tri& t : slot->mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  slot->fcl->beginModel();
  slot->fcl->addSubModel(points, triangles);
  slot->fcl->endModel();
  slot->radius = boundingRadius(slot->mesh);
  return *slot;
}

/// FCL's view of the pair: target movable, opponent at the identity.
struct FclPair {
  fcl::CollisionObjectd target, opponent;
  FclPair(const Prepared& t, const Prepared& o) : target(t.fcl), opponent(o.fcl) {
    opponent.setTransform(fcl::Transform3d::Identity());
    opponent.computeAABB();
  }
  void place(const Rigid& pose) {
    target.setTransform(fclTransform(pose));
    target.computeAABB();
  }
  bool collides(const Rigid& pose) {
    place(pose);
    fcl::CollisionRequestd request;
    fcl::CollisionResultd result;
    return fcl::collide(&target, &opponent, request, result) > 0;
  }
  /// Surface distance; 0 when the surfaces intersect.
  double distance(const Rigid& pose) {
    place(pose);
    fcl::DistanceRequestd request;
    fcl::DistanceResultd result;
    fcl::distance(&target, &opponent, request, result);
    return result.min_distance;
  }
};

/// A fixed seed per pair (FNV-1a of the names).
std::uint64_t seedOf(const PairCase& pc) {
  std::uint64_t h = 14695981039346656037ull;
  for (const char* name : {pc.target, pc.opponent})
    for (const char* c = name; *c != 0; ++c)
      h = (h ^ static_cast<unsigned char>(*c)) * 1099511628211ull;
  return h;
}

/// Smallest push t in [0, tolerance] along n that separates the contact pose per FCL
/// (bisection); 2 * tolerance when even the full tolerance does not.
double separatingPush(FclPair& fcl_pair, const Rigid& contact, const Vec3& n) {
  const auto moved = [&](double t) { return Rigid{contact.rotation, contact.translation + t * n}; };
  if (fcl_pair.distance(moved(0.0)) > 0.0) return 0.0;
  if (!(fcl_pair.distance(moved(kTolerance)) > 0.0)) return 2.0 * kTolerance;
  double lo = 0.0, hi = kTolerance;
  for (int i = 0; i < 12; ++i) {
    const double mid = 0.5 * (lo + hi);
    (fcl_pair.distance(moved(mid)) > 0.0 ? hi : lo) = mid;
  }
  return hi;
}

class NonconvexPenetration : public ::testing::TestWithParam<PairCase> {};

TEST_P(NonconvexPenetration, ContactPoseIsWithinToleranceAndDepthIsSmooth) {
  const PairCase pc = GetParam();
  const std::uint64_t seed = seedOf(pc);
  SCOPED_TRACE(::testing::Message() << "seed " << seed);
  const auto start_time = std::chrono::steady_clock::now();
  const Prepared& t = prepared(pc.target);
  const Prepared& o = prepared(pc.opponent);
  ASSERT_TRUE(t.model && o.model) << "meshes missing or not built";
  const Part part_t{t.model.get(), Rigid(), 1};
  const Part part_o{o.model.get(), Rigid(), 2};
  FclPair fcl_pair(t, o);
  SceneSettings settings;
  settings.tolerance = kTolerance;
  test::Rng rng(seed);
  const double reach = t.radius + o.radius;

  int paths = 0, attempts = 0, penetrating = 0, clean = 0;
  double worst_push = 0.0, worst_jump = 0.0, deepest = 0.0;
  while (paths < kPaths && attempts < 10 * kPaths) {
    ++attempts;
    SCOPED_TRACE(::testing::Message() << "attempt " << attempts);
    const Quat q0 = test::randomRotation(rng);
    const Vec3 u = test::randomDirection(rng);
    const Vec3 axis = test::randomDirection(rng);
    const Rigid r0{q0.toRotationMatrix(), Vec3::Zero()};
    if (!fcl_pair.collides(r0)) continue;
    // First contact along u: bisect between colliding (lo) and apart (hi).
    double lo = 0.0, hi = reach;
    for (int i = 0; i < 40; ++i) {
      const double mid = 0.5 * (lo + hi);
      (fcl_pair.collides(Rigid{r0.rotation, mid * u}) ? lo : hi) = mid;
    }
    const int steps = static_cast<int>(std::lround((kStartGap + kDepth) / kStep));
    const double turn_per_step = kTurn / t.radius / steps;
    const auto poseAt = [&](int k, Quat* q) {
      *q = Quat(Eigen::AngleAxisd(k * turn_per_step, axis)) * q0;
      return (hi + kStartGap - k * kStep) * u;
    };
    Quat q;
    Vec3 c = poseAt(0, &q);
    if (!(fcl_pair.distance(Rigid{q.toRotationMatrix(), c}) > 0.0)) continue;
    ++paths;
    PairTracker tracker;
    DirectedResult out[2];
    const Placement opponent_place;
    bool have_previous = false;
    Vec3 previous_tpdv = Vec3::Zero(), previous_c = c;
    Quat previous_q = q;
    for (int k = 0; k <= steps; ++k) {
      c = poseAt(k, &q);
      const Placement place = placementOf(q, c);
      tracker.update({&part_t, 1, place}, {&part_o, 1, opponent_place}, {true, false}, settings,
                     out);
      const DirectedResult& r = out[0];
      ASSERT_EQ(r.code, ErrorCode::Ok) << "path " << paths << " step " << k;
      const Status valid = detail::checkResult(r, place, opponent_place);
      EXPECT_TRUE(valid.ok()) << valid.message() << " (path " << paths << " step " << k << ")";
      if (!r.penetrating()) {
        have_previous = false;
        previous_c = c;
        previous_q = q;
        continue;
      }
      ++penetrating;
      EXPECT_EQ(r.distance, -r.tpdv.norm());
      deepest = std::max(deepest, -r.distance);
      const Rigid contact = placementOf(r.contact_orientation, r.contact_position).worldFromLocal();
      const double push = separatingPush(fcl_pair, contact, r.normal);
      if (push == 0.0) ++clean;
      worst_push = std::max(worst_push, push);
      EXPECT_LE(push, kTolerance) << "path " << paths << " step " << k << " depth "
                                  << -r.distance;
      if (have_previous) {
        const double moved = (c - previous_c).norm() +
                             Eigen::AngleAxisd(q * previous_q.inverse()).angle() * t.radius;
        const double jump = (r.tpdv - previous_tpdv).norm() / moved;
        worst_jump = std::max(worst_jump, jump);
        EXPECT_LE(jump, kJumpMultiple) << "path " << paths << " step " << k;
      }
      have_previous = true;
      previous_tpdv = r.tpdv;
      previous_c = c;
      previous_q = q;
    }
    if (HasFatalFailure()) return;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  std::printf(
      "[ nonconvex pd ] %s->%s: %d paths (%d attempts), %d penetrating results, %d clean "
      "contact poses, worst separating push %.3g tol, max |dTPDV|/step %.3g, deepest %.3g "
      "tol, %.1f s\n",
      pc.target, pc.opponent, paths, attempts, penetrating, clean, worst_push / kTolerance,
      worst_jump, deepest / kTolerance, seconds);
  RecordProperty("worst_push_over_tolerance", std::to_string(worst_push / kTolerance));
  RecordProperty("max_tpdv_change_multiple", std::to_string(worst_jump));
  EXPECT_EQ(paths, kPaths) << "too few approach paths";
  EXPECT_GE(penetrating, paths * 4) << "paths should mostly penetrate";
}

#else

TEST_P(NonconvexPenetration, ContactPoseIsWithinToleranceAndDepthIsSmooth) {
  GTEST_SKIP() << "FCL was not found at configure time";
}

#endif

INSTANTIATE_TEST_SUITE_P(CgalMeshes, NonconvexPenetration,
                         ::testing::Values(PairCase{"knot1", "fandisk"},
                                           PairCase{"elephant", "femur"},
                                           PairCase{"femur", "knot1"},
                                           PairCase{"cow", "elephant"}),
                         [](const ::testing::TestParamInfo<PairCase>& param_info) {
                           const PairCase& pc = param_info.param;
                           return std::string(pc.target) + "_" + pc.opponent;
                         });

}  // namespace
}  // namespace sc
