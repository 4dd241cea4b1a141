// SPDX-License-Identifier: MIT
// Minimum distance between real meshes against FCL's exact mesh distance
// (BVHModel<OBBRSSd>, triangle pairs): closed polyhedra (bunny00, armadillo,
// fandisk, knot1, and the self-intersecting cow and camel) and triangle soups
// (ChineseDragon-10kv, lion, elephant-with-holes), each pair at >= 500 random
// separated poses (100 in sanitizer builds, where meshes above 15000 triangles are
// skipped as in the decomposition invariants). Checks the distance to 1e-9
// relative, that the closest points are on the surfaces, and that the reported
// features hold the points and agree with the normal. Through the public API:
// buildPiece, Model and PairTracker with one direction.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "sc_support/off_mesh.h"
#include "smartcollision/collision.h"
#include "support/brute_force.h"
#include "support/meshes.h"
#include "support/shapes.h"
#include "support/test_support.h"

#if SC_TEST_HAVE_FCL
#include <fcl/fcl.h>
#endif

namespace sc {
namespace {

#if SC_TEST_SANITIZED
constexpr int kPoses = 100;
constexpr std::size_t kMaxTriangles = 15000;
#else
constexpr int kPoses = 500;
constexpr std::size_t kMaxTriangles = ~std::size_t{0};
#endif
/// Poses closer than this (the meshes scaled to unit size) are not used: hull
/// leaves may reach out of the solid by the decomposition's tolerance (1e-6 of
/// the diagonal), so touching at that scale counts as intersecting.
constexpr double kMinGap = 1e-4;

struct PairCase {
  const char* a;
  ModelKind kind_a;
  const char* b;
  ModelKind kind_b;
};

std::ostream& operator<<(std::ostream& os, const PairCase& c) { return os << c.a << "_" << c.b; }

constexpr ModelKind kClosed = ModelKind::ClosedPolyhedron;
constexpr ModelKind kSoup = ModelKind::TriangleSoup;

/// Point in a closed mesh by the parity of a ray's crossings (Möller-Trumbore).
bool insideByParity(const MeshData& mesh, const Vec3& p) {
  const Vec3 dir = Vec3(0.5773, 0.5774, 0.5775).normalized();
  int crossings = 0;
  for (const Tri& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[t[0]];
    const Vec3 e1 = mesh.vertices[t[1]] - a, e2 = mesh.vertices[t[2]] - a;
    const Vec3 h = dir.cross(e2);
    const double det = e1.dot(h);
    if (std::abs(det) < 1e-300) continue;
    const Vec3 s = p - a;
    const double u = s.dot(h) / det;
    if (u < 0.0 || u > 1.0) continue;
    const Vec3 q = s.cross(e1);
    const double v = dir.dot(q) / det;
    if (v < 0.0 || u + v > 1.0) continue;
    if (e2.dot(q) / det > 0.0) ++crossings;
  }
  return crossings % 2 == 1;
}

/// Edges and triangles of a mesh by their sorted vertex indices.
struct MeshElements {
  std::set<std::pair<int, int>> edges;
  std::set<std::array<int, 3>> triangles;

  explicit MeshElements(const MeshData& mesh) {
    for (const Tri& t : mesh.triangles) {
      std::array<int, 3> ids{t[0], t[1], t[2]};
      std::sort(ids.begin(), ids.end());
      triangles.insert(ids);
      for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
    }
  }
  /// The feature is a vertex, edge or triangle of the mesh.
  bool has(const Feature& f) const {
    if (f.type == FeatureType::Vertex) return f.vertices[0] >= 0;
    if (f.type == FeatureType::Edge) return edges.count(std::minmax(f.vertices[0], f.vertices[1]));
    std::array<int, 3> ids{f.vertices[0], f.vertices[1], f.vertices[2]};
    std::sort(ids.begin(), ids.end());
    return triangles.count(ids) > 0;
  }
};

/// The feature holds the point (world), and a face's normal or an edge's direction
/// agrees with the contact normal n (from opponent to target; `outward` is the
/// face normal's expected sign along n, 0 for two-sided soup faces).
void expectFeature(const MeshData& mesh, const Rigid& world_from_mesh, const Feature& f,
                   const Vec3& point, const Vec3& n, double outward) {
  const Vec3 local = world_from_mesh.inverse() * point;
  EXPECT_LE(test::pointFeatureDistance(mesh.vertices, f, local), 1e-9);
  const Vec3& a = mesh.vertices[f.vertices[0]];
  if (f.type == FeatureType::Face) {
    const Vec3 cross = (mesh.vertices[f.vertices[1]] - a).cross(mesh.vertices[f.vertices[2]] - a);
    if (cross.norm() < 1e-300) return;  // a degenerate soup triangle has no normal
    const Vec3 normal = world_from_mesh.rotation * cross.normalized();
    if (outward != 0.0) {
      EXPECT_NEAR(normal.dot(n), outward, 1e-6);
    } else {
      EXPECT_NEAR(std::abs(normal.dot(n)), 1.0, 1e-6);
    }
  } else if (f.type == FeatureType::Edge) {
    const Vec3 e = mesh.vertices[f.vertices[1]] - a;
    if (e.norm() < 1e-300) return;
    EXPECT_NEAR((world_from_mesh.rotation * e.normalized()).dot(n), 0.0, 1e-6);
  }
}

class MeshDistanceFcl : public ::testing::TestWithParam<PairCase> {};

#if SC_TEST_HAVE_FCL

using FclModel = fcl::BVHModel<fcl::OBBRSSd>;

std::shared_ptr<FclModel> fclModel(const MeshData& mesh) {
  auto model = std::make_shared<FclModel>();
  std::vector<fcl::Vector3d> points(mesh.vertices.begin(), mesh.vertices.end());
  std::vector<fcl::Triangle> triangles;
  for (const Tri& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  model->beginModel();
  model->addSubModel(points, triangles);
  model->endModel();
  return model;
}

fcl::Transform3d fclTransform(const Rigid& r) {
  fcl::Transform3d t = fcl::Transform3d::Identity();
  t.linear() = r.rotation;
  t.translation() = r.translation;
  return t;
}

/// A fixed seed per pair (FNV-1a of the names).
std::uint64_t seedOf(const PairCase& pc) {
  std::uint64_t h = 14695981039346656037ull;
  for (const char* name : {pc.a, pc.b}) {
    for (const char* c = name; *c != 0; ++c)
      h = (h ^ static_cast<unsigned char>(*c)) * 1099511628211ull;
  }
  return h;
}

double boundingRadius(const MeshData& mesh) {
  double r = 0.0;
  for (const Vec3& v : mesh.vertices) r = std::max(r, v.norm());
  return r;
}

TEST_P(MeshDistanceFcl, DistanceEqualsFclOnRandomSeparatedPoses) {
  const PairCase pc = GetParam();
  const std::uint64_t seed = seedOf(pc);
  SCOPED_TRACE(::testing::Message() << "seed " << seed);
  MeshData raw_a, raw_b;
  ASSERT_NO_FATAL_FAILURE(raw_a = test::loadTestMesh(pc.a));
  ASSERT_NO_FATAL_FAILURE(raw_b = test::loadTestMesh(pc.b));
  if (raw_a.triangles.size() > kMaxTriangles || raw_b.triangles.size() > kMaxTriangles)
    GTEST_SKIP() << "meshes above " << kMaxTriangles << " triangles run in the Release pass only";
  const MeshData mesh_a = support::fitToSize(raw_a, 1.0), mesh_b = support::fitToSize(raw_b, 1.0);
  Result<PiecePtr> piece_a = buildPiece(pc.kind_a, mesh_a);
  Result<PiecePtr> piece_b = buildPiece(pc.kind_b, mesh_b);
  ASSERT_TRUE(piece_a.ok()) << pc.a << ": " << piece_a.status().message();
  ASSERT_TRUE(piece_b.ok()) << pc.b << ": " << piece_b.status().message();
  // The stored meshes (closed ones may be flipped) name the features.
  const MeshData& stored_a = piece_a.value()->mesh();
  const MeshData& stored_b = piece_b.value()->mesh();
  const Model model_a(pc.kind_a, {piece_a.value()});
  const Model model_b(pc.kind_b, {piece_b.value()});
  const Part part_a{&model_a, Rigid(), 10};
  const Part part_b{&model_b, Rigid(), 20};
  const MeshElements elements_a(stored_a), elements_b(stored_b);

  fcl::CollisionObjectd fcl_a(fclModel(mesh_a)), fcl_b(fclModel(mesh_b));
  fcl_b.setTransform(fcl::Transform3d::Identity());
  fcl_b.computeAABB();

  test::Rng rng(seed);
  const double reach = boundingRadius(mesh_a) + boundingRadius(mesh_b);
  PairTracker tracker;
  SceneSettings settings;
  double max_relative = 0.0;
  int accepted = 0, attempts = 0, colliding = 0, nested = 0, too_close = 0, near_contact = 0;
  int feature_dims[3][3] = {};
  while (accepted < kPoses && attempts < 20 * kPoses) {
    ++attempts;
    const Quat q = test::randomRotation(rng);
    const Vec3 u = test::randomDirection(rng);
    const auto collides = [&](double s) {
      fcl_a.setTransform(fclTransform(Rigid{q.toRotationMatrix(), s * u}));
      fcl_a.computeAABB();
      fcl::CollisionRequestd creq;
      fcl::CollisionResultd cres;
      return fcl::collide(&fcl_a, &fcl_b, creq, cres) > 0;
    };
    // Every other pose near contact: bisect for a touching offset along u, then
    // back off by a log-uniform gap; the others anywhere within reach.
    double s = test::uniform(rng, 0.2, 1.0) * reach;
    if (attempts % 2 == 0 && collides(0.0)) {
      double lo = 0.0, hi = reach;
      for (int k = 0; k < 30; ++k) (collides(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
      s = hi + test::logUniform(rng, 1e-4, 0.1);
    }
    const Vec3 centre = s * u;
    const Rigid pose{q.toRotationMatrix(), centre};
    if (collides(s)) {
      ++colliding;
      continue;
    }
    // Separated surfaces may still be nested solids (or a soup inside a solid).
    if ((pc.kind_b == kClosed &&
         insideByParity(mesh_b, pose * mesh_a.vertices[mesh_a.triangles[0][0]])) ||
        (pc.kind_a == kClosed &&
         insideByParity(mesh_a, pose.inverse() * mesh_b.vertices[mesh_b.triangles[0][0]]))) {
      ++nested;
      continue;
    }
    fcl::DistanceRequestd dreq(true);
    fcl::DistanceResultd dres;
    fcl::distance(&fcl_a, &fcl_b, dreq, dres);
    const double expected = dres.min_distance;
    if (expected < kMinGap) {
      ++too_close;
      continue;
    }
    ++accepted;
    if (expected < 0.01) ++near_contact;
    SCOPED_TRACE(::testing::Message() << "pose " << accepted << " fcl distance " << expected);

    GroupView target{&part_a, 1, Placement()};
    target.placement.orientation = q;
    target.placement.world_center = centre;
    const GroupView opponent{&part_b, 1, Placement()};
    DirectedResult out[2];
    tracker.forget(0);
    tracker.update(target, opponent, Directions{true, false}, settings, out);
    const DirectedResult& r = out[0];
    ASSERT_EQ(r.code, ErrorCode::Ok);
    EXPECT_EQ(out[1].code, ErrorCode::NoResult);
    const double relative = std::abs(r.distance - expected) / expected;
    max_relative = std::max(max_relative, relative);
    EXPECT_LE(relative, 1e-9) << "ours " << r.distance << " fcl " << expected;
    EXPECT_EQ(r.target_object, 10);
    EXPECT_EQ(r.opponent_object, 20);
    EXPECT_EQ(r.target_piece, 0);
    EXPECT_EQ(r.opponent_piece, 0);
    EXPECT_VEC_NEAR(r.tpdv, Vec3::Zero(), 0.0);

    // Points: apart by the distance along the normal, on the surfaces.
    EXPECT_NEAR((r.point_on_target - r.point_on_opponent).norm(), r.distance, 1e-12);
    EXPECT_VEC_NEAR(r.normal, (r.point_on_target - r.point_on_opponent) / r.distance, 1e-9);
    EXPECT_FALSE(r.target_feature.is_virtual);
    EXPECT_FALSE(r.opponent_feature.is_virtual);
    EXPECT_TRUE(elements_a.has(r.target_feature));
    EXPECT_TRUE(elements_b.has(r.opponent_feature));
    const Rigid world_from_a = target.placement.worldFromLocal();
    expectFeature(stored_a, world_from_a, r.target_feature, r.point_on_target, r.normal,
                  pc.kind_a == kClosed ? -1.0 : 0.0);
    expectFeature(stored_b, Rigid(), r.opponent_feature, r.point_on_opponent, r.normal,
                  pc.kind_b == kClosed ? 1.0 : 0.0);
    ++feature_dims[r.target_feature.count() - 1][r.opponent_feature.count() - 1];
    if (accepted % 25 == 0) {  // independently of the features, now and then
      EXPECT_LE(test::pointSurfaceDistance(stored_a, world_from_a.inverse() * r.point_on_target),
                1e-9);
      EXPECT_LE(test::pointSurfaceDistance(stored_b, r.point_on_opponent), 1e-9);
    }
    if (HasFatalFailure()) return;
  }
  std::printf(
      "[ mesh distance ] %s-%s: %d poses (%d attempts: %d colliding, %d nested, %d closer "
      "than %g), %d within 0.01; max relative error vs FCL %.3g; feature pairs VV %d VE %d VF "
      "%d EV %d EE %d EF %d FV %d FE %d FF %d\n",
      pc.a, pc.b, accepted, attempts, colliding, nested, too_close, kMinGap, near_contact,
      max_relative, feature_dims[0][0], feature_dims[0][1], feature_dims[0][2], feature_dims[1][0],
      feature_dims[1][1], feature_dims[1][2], feature_dims[2][0], feature_dims[2][1],
      feature_dims[2][2]);
  EXPECT_EQ(accepted, kPoses) << "too few separated poses";
  // Representative: many near contact, and the generic contact types all occur.
  EXPECT_GE(near_contact, kPoses / 4);
  EXPECT_GT(feature_dims[0][2] + feature_dims[2][0], kPoses / 20);
  EXPECT_GT(feature_dims[1][1], kPoses / 20);
}

#else

TEST_P(MeshDistanceFcl, DistanceEqualsFclOnRandomSeparatedPoses) {
  GTEST_SKIP() << "FCL was not found at configure time";
}

#endif

INSTANTIATE_TEST_SUITE_P(CgalMeshes, MeshDistanceFcl,
                         ::testing::Values(PairCase{"bunny00", kClosed, "armadillo", kClosed},
                                           PairCase{"fandisk", kClosed, "knot1", kClosed},
                                           PairCase{"cow", kClosed, "camel", kClosed},
                                           PairCase{"ChineseDragon-10kv", kSoup, "lion", kSoup},
                                           PairCase{"elephant-with-holes", kSoup, "lion", kSoup},
                                           PairCase{"cow", kClosed, "elephant-with-holes", kSoup},
                                           PairCase{"knot1", kClosed, "ChineseDragon-10kv", kSoup}),
                         [](const ::testing::TestParamInfo<PairCase>& param_info) {
                           std::string name =
                               std::string(param_info.param.a) + "_" + param_info.param.b;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace sc
