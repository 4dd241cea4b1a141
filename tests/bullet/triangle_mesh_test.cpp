// SPDX-License-Identifier: MIT
// ScBulletShape bodies against Bullet's static triangle meshes (btBvhTriangleMeshShape,
// btScaledBvhTriangleMeshShape), what a Bullet user gives a static mesh: the plugin
// reads the mesh as a SmartCollision soup (every subpart, float or double vertices,
// 32-, 16- or 8-bit indices, scaled), a box and a cow dropped on a bumpy terrain at
// 60 Hz rest on it as they do on an ScBulletShape soup of the same triangles, the
// closest-points table answers both orders, and a bad mesh gives a status, no crash.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "bullet_world.h"
#include "support/shapes.h"

namespace sc::test {
namespace {

using bullet::ContactModel;

// Bullet is built in single precision: its transforms carry ~1e-7 relative error.
constexpr double kExact = 2e-5;

/// A height field over [-size/2, size/2]^2 as a grid of cells split along a diagonal
/// (y up), stored as Bullet reads it (float coordinates, 32-bit indices). heightAt is
/// the exact piecewise-linear surface of those triangles.
class Grid {
 public:
  template <class Height>
  Grid(int cells, double size, Height height) : cells_(cells), size_(size) {
    for (int i = 0; i <= cells; ++i)
      for (int j = 0; j <= cells; ++j) {
        const double x = coord(i), z = coord(j);
        coords_.insert(coords_.end(), {float(x), float(height(x, z)), float(z)});
      }
    for (int i = 0; i < cells; ++i)
      for (int j = 0; j < cells; ++j) {
        const int a = i * (cells + 1) + j, b = a + 1, c = a + cells + 1, d = c + 1;
        indices_.insert(indices_.end(), {a, b, d, a, d, c});  // facing +y
      }
    mesh_ = std::make_unique<btTriangleIndexVertexArray>(
        static_cast<int>(indices_.size() / 3), indices_.data(), 3 * int(sizeof(int)),
        static_cast<int>(coords_.size() / 3), coords_.data(), 3 * int(sizeof(float)));
  }

  /// The same triangles as Bullet's mesh (a btBvhTriangleMeshShape over it).
  std::shared_ptr<btBvhTriangleMeshShape> bvhShape() const {
    return std::make_shared<btBvhTriangleMeshShape>(mesh_.get(), true);
  }
  /// The same triangles as an ScBulletShape soup.
  std::shared_ptr<bullet::ScBulletShape> soupShape() const {
    MeshData m;
    for (std::size_t v = 0; v < coords_.size(); v += 3)
      m.vertices.emplace_back(coords_[v], coords_[v + 1], coords_[v + 2]);
    for (std::size_t t = 0; t < indices_.size(); t += 3)
      m.triangles.emplace_back(indices_[t], indices_[t + 1], indices_[t + 2]);
    auto s = bullet::ScBulletShape::create(ModelKind::TriangleSoup, m);
    EXPECT_TRUE(s.ok()) << s.status().message();
    return s.value();
  }

  /// Height of the triangles at (x, z), clamped to the grid.
  double heightAt(double x, double z) const {
    const double h = size_ / cells_;
    const double u = (x + 0.5 * size_) / h, v = (z + 0.5 * size_) / h;
    const int i = std::clamp(static_cast<int>(std::floor(u)), 0, cells_ - 1);
    const int j = std::clamp(static_cast<int>(std::floor(v)), 0, cells_ - 1);
    const double fu = u - i, fv = v - j;
    const double ha = y(i, j), hb = y(i, j + 1), hc = y(i + 1, j), hd = y(i + 1, j + 1);
    // Triangle (a, b, d) where fv >= fu, (a, d, c) elsewhere.
    return fv >= fu ? ha + (hb - ha) * fv + (hd - hb) * fu : ha + (hc - ha) * fu + (hd - hc) * fv;
  }

  int vertexCount() const { return static_cast<int>(coords_.size() / 3); }
  btVector3 vertex(int k) const {
    const std::size_t v = 3 * static_cast<std::size_t>(k);
    return btVector3(coords_[v], coords_[v + 1], coords_[v + 2]);
  }

 private:
  double coord(int i) const { return -0.5 * size_ + size_ * i / cells_; }
  double y(int i, int j) const {
    return coords_[3 * static_cast<std::size_t>(i * (cells_ + 1) + j) + 1];
  }

  int cells_;
  double size_;
  std::vector<float> coords_;
  std::vector<int> indices_;
  std::unique_ptr<btTriangleIndexVertexArray> mesh_;
};

/// 4 x 4 m of bumps 2 * 3 cm high, a valley at every half-integer x and z; the
/// slopes stay below 11 degrees, within Bullet's default friction (0.5).
Grid bumpyTerrain() {
  return Grid(64, 4.0, [](double x, double z) {
    return 0.03 * (std::cos(2 * kPi * x) + std::cos(2 * kPi * z));
  });
}

/// Deepest vertex of `shape` (at `t`) below the terrain; 0 when none is.
double sinkBelow(const Grid& terrain, const bullet::ScBulletShape& shape, const btTransform& t) {
  double deepest = 0.0;
  for (const btVector3& v : shape.vertices()) {
    const btVector3 w = t * v;
    deepest = std::max(deepest, terrain.heightAt(w.x(), w.z()) - double(w.y()));
  }
  return deepest;
}

/// Deepest terrain vertex inside the box of half edge `half` at `t` (a bump poking
/// into a face touches no corner of the box); 0 when none is.
double terrainInBox(const Grid& terrain, double half, const btTransform& t) {
  const btTransform inv = t.inverse();
  double deepest = 0.0;
  for (int k = 0; k < terrain.vertexCount(); ++k) {
    const btVector3 l = inv * terrain.vertex(k);
    const double inside = half - std::max({std::abs(double(l.x())), std::abs(double(l.y())),
                                           std::abs(double(l.z()))});
    deepest = std::max(deepest, inside);
  }
  return deepest;
}

struct Landing {
  double box_y = 0.0, cow_y = 0.0;  ///< centres of mass at the end [m]
  double settled = 0.0;             ///< deepest overlap with the terrain over the last second [m]
  double impact = 0.0;              ///< deepest overlap over the whole run [m]
  double rms_speed = 0.0;           ///< RMS speed of both centres over the last second [m/s]
  double early_rms = 0.0;           ///< the same over the fourth second [m/s]
  double max_speed = 0.0;           ///< largest speed of a centre over the last second [m/s]
  double ms_per_step = 0.0;
};

constexpr double kBoxHalf = 0.1;

/// Drops a 0.2 m box and a 0.5 m cow (lowest points 15 cm above the terrain's top) into
/// two valleys of the terrain `ground` at 60 Hz for 15 s.
Landing drop(ContactModel model, const Grid& terrain,
             const std::shared_ptr<btCollisionShape>& ground,
             const std::shared_ptr<bullet::ScBulletShape>& cow) {
  BulletWorld w(model, -9.81, 60.0);
  w.addBody(ground, 0.0, btVector3(0, 0, 0));
  auto box = boxShape(btVector3(kBoxHalf, kBoxHalf, kBoxHalf));
  btRigidBody* b = w.addBody(box, 1.0, btVector3(0.5f, btScalar(0.21 + kBoxHalf), 0.5f));
  const btTransform& mesh_from_shape = cow->meshFromShape();
  double lowest = std::numeric_limits<double>::infinity();
  for (const btVector3& v : cow->vertices())
    lowest = std::min(lowest, double((mesh_from_shape * v).y()));
  btRigidBody* c = w.addBody(
      cow, 1.0, btVector3(-0.5f, btScalar(0.21 - lowest), -0.5f) + mesh_from_shape.getOrigin(),
      mesh_from_shape.getRotation());
  Landing out;
  const int steps = 900, last = 60, early = 180;  // early: the fourth second's first step
  double v2 = 0.0, early_v2 = 0.0;
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) {
    w.step();
    const double overlap = std::max({sinkBelow(terrain, *box, b->getWorldTransform()),
                                     terrainInBox(terrain, kBoxHalf, b->getWorldTransform()),
                                     sinkBelow(terrain, *cow, c->getWorldTransform())});
    out.impact = std::max(out.impact, overlap);
    if (k >= early && k < early + last)
      for (const btRigidBody* r : {b, c}) early_v2 += double(r->getLinearVelocity().length2());
    if (k < steps - last) continue;
    out.settled = std::max(out.settled, overlap);
    for (const btRigidBody* r : {b, c}) {
      v2 += double(r->getLinearVelocity().length2());
      out.max_speed = std::max(out.max_speed, double(r->getLinearVelocity().length()));
    }
  }
  out.ms_per_step =
      1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / steps;
  out.rms_speed = std::sqrt(v2 / (2 * last));
  out.early_rms = std::sqrt(early_v2 / (2 * last));
  out.box_y = b->getCenterOfMassPosition().y();
  out.cow_y = c->getCenterOfMassPosition().y();
  return out;
}

std::shared_ptr<bullet::ScBulletShape> cowShape() {
  const MeshData mesh = scaledOff("cow.off", 0.5);
  EXPECT_FALSE(mesh.triangles.empty()) << "cow.off missing from " SC_MESH_DIR;
  auto cow = bullet::ScBulletShape::create(ModelKind::ClosedPolyhedron, mesh);
  EXPECT_TRUE(cow.ok()) << cow.status().message();
  return cow.value();
}

class TerrainDrop : public ::testing::TestWithParam<ContactModel> {};

// Bounds: at rest within about the contact tolerance (1 mm) of the surface, as on a
// floor (CowsOnTheGround); landings at 2 m/s within a few tolerances. At rest by the
// fourth second as in the last: the potential model's cow rocked in its valley at
// 1-2.6e-2 m/s until the tenth second while one of its patch's five rows took another's
// place in the manifold every step (docs/bullet.md, "Patches").
TEST_P(TerrainDrop, BodiesRestOnABvhTriangleMeshAsOnASoupOfItsTriangles) {
  const Grid terrain = bumpyTerrain();
  const auto cow = cowShape();
  ASSERT_TRUE(cow);
  const Landing bvh = drop(GetParam(), terrain, terrain.bvhShape(), cow);
  const Landing soup = drop(GetParam(), terrain, terrain.soupShape(), cow);
  for (const auto& [name, l] : {std::pair{"bvh", bvh}, std::pair{"soup", soup}}) {
    std::printf(
        "[terrain %s %s] box y %.5f m, cow y %.5f m, overlap settled %.2f mm, impacts %.2f mm, "
        "rms speed (last s) %.2e m/s, (fourth s) %.2e m/s, max %.2e m/s, %.2f ms/step\n",
        GetParam() == ContactModel::Potential ? "potential" : "manifold", name, l.box_y, l.cow_y,
        1e3 * l.settled, 1e3 * l.impact, l.rms_speed, l.early_rms, l.max_speed, l.ms_per_step);
    EXPECT_LT(l.settled, 0.002) << name;
    EXPECT_LT(l.impact, 0.005) << name;
    EXPECT_LT(l.rms_speed, 1e-3) << name;
    EXPECT_LT(l.early_rms, 1e-3) << name;
    EXPECT_LT(l.max_speed, 5e-3) << name;
  }
  // The same triangles and the same algorithm: the same resting poses, within what
  // the rows resolve (the soups' vertex orders, hence their hierarchies, differ).
  EXPECT_NEAR(bvh.box_y, soup.box_y, 1e-3);
  EXPECT_NEAR(bvh.cow_y, soup.cow_y, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Models, TerrainDrop, bothContactModels(), contactModelName);

/// The model's triangles as corner coordinates, in order.
std::vector<Vec3> cornersOf(const Model& model) {
  std::vector<Vec3> out;
  const MeshData& m = model.pieces().at(0)->mesh();
  for (const Tri& t : m.triangles)
    for (int k = 0; k < 3; ++k) out.push_back(m.vertices[static_cast<std::size_t>(t[k])]);
  return out;
}

// Three subparts: float vertices with a padded stride and 16-bit indices, double
// vertices with 8-bit indices, float vertices with 32-bit indices and a vertex no
// triangle uses. The soup holds every triangle, in order, and only the used vertices.
TEST(TriangleMeshModel, ReadsEverySubpartVertexAndIndexType) {
  const std::vector<float> padded = {0, 0, 0, 9, 1, 0, 0, 9, 0, 0, 1, 9, 1, 0, 1, 9};
  const std::vector<unsigned short> shorts = {0, 1, 2, 1, 3, 2};
  const std::vector<double> doubles = {0, 1, 0, 1, 1, 0, 0, 1, 1};
  const std::vector<unsigned char> bytes = {2, 1, 0};
  const std::vector<float> floats = {5, 5, 5, 0, 2, 0, 1, 2, 0, 0, 2, 1};  // vertex 0 unused
  const std::vector<int> ints = {1, 2, 3};
  btTriangleIndexVertexArray array;
  auto add = [&array](const void* idx, int idx_stride, PHY_ScalarType idx_type, const void* v,
                      int v_stride, PHY_ScalarType v_type, int tris, int verts) {
    btIndexedMesh m;
    m.m_numTriangles = tris;
    m.m_triangleIndexBase = static_cast<const unsigned char*>(idx);
    m.m_triangleIndexStride = idx_stride;
    m.m_numVertices = verts;
    m.m_vertexBase = static_cast<const unsigned char*>(v);
    m.m_vertexStride = v_stride;
    m.m_vertexType = v_type;
    array.addIndexedMesh(m, idx_type);
  };
  add(shorts.data(), 3 * sizeof(short), PHY_SHORT, padded.data(), 4 * sizeof(float), PHY_FLOAT, 2,
      4);
  add(bytes.data(), 3, PHY_UCHAR, doubles.data(), 3 * sizeof(double), PHY_DOUBLE, 1, 3);
  add(ints.data(), 3 * sizeof(int), PHY_INTEGER, floats.data(), 3 * sizeof(float), PHY_FLOAT, 1, 4);
  btBvhTriangleMeshShape shape(&array, true);
  BulletWorld w(ContactModel::Potential);
  Result<ModelPtr> model = w.plugin->shapeModel(&shape);
  ASSERT_TRUE(model.ok()) << model.status().message();
  EXPECT_EQ(model.value()->kind(), ModelKind::TriangleSoup);
  const std::vector<Vec3> expected = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1, 0, 0},
                                      {1, 0, 1}, {0, 0, 1}, {0, 1, 1}, {1, 1, 0},
                                      {0, 1, 0}, {0, 2, 0}, {1, 2, 0}, {0, 2, 1}};
  EXPECT_EQ(cornersOf(*model.value()), expected);
  EXPECT_EQ(model.value()->pieces()[0]->mesh().vertices.size(), 10u);  // 4 + 3 + 3 used
}

// The mesh's scaling (btBvhTriangleMeshShape::setLocalScaling) and a
// btScaledBvhTriangleMeshShape's on top of it, as Bullet applies them.
TEST(TriangleMeshModel, AppliesBothScalings) {
  const Grid plane(2, 2.0, [](double, double) { return 1.0; });
  auto bvh = plane.bvhShape();
  BulletWorld w(ContactModel::Potential);
  const ModelPtr unscaled = w.plugin->shapeModel(bvh.get()).value();
  ASSERT_TRUE(unscaled);
  EXPECT_EQ(w.plugin->shapeModel(bvh.get()).value(), unscaled);  // cached
  bvh->setLocalScaling(btVector3(1, 0.5f, 1));
  const ModelPtr half = w.plugin->shapeModel(bvh.get()).value();
  ASSERT_TRUE(half);
  EXPECT_NE(half, unscaled);
  EXPECT_NEAR(half->bounds().max.y(), 0.5, 1e-7);
  btScaledBvhTriangleMeshShape scaled(bvh.get(), btVector3(2, 3, 4));
  const ModelPtr both = w.plugin->shapeModel(&scaled).value();
  ASSERT_TRUE(both);
  EXPECT_NEAR(both->bounds().min.x(), -2.0, 1e-7);
  EXPECT_NEAR(both->bounds().max.y(), 1.5, 1e-7);
  EXPECT_NEAR(both->bounds().max.z(), 4.0, 1e-7);
  scaled.setLocalScaling(btVector3(1, 1, 1));
  const ModelPtr rescaled = w.plugin->shapeModel(&scaled).value();
  ASSERT_TRUE(rescaled);
  EXPECT_NEAR(rescaled->bounds().max.z(), 1.0, 1e-7);
}

// A mesh grown after its first model (a level editor adding triangles) gets a new one.
TEST(TriangleMeshModel, GrownMeshGetsANewModel) {
  btTriangleMesh mesh;
  mesh.addTriangle(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 0, 1));
  btBvhTriangleMeshShape shape(&mesh, true);
  BulletWorld w(ContactModel::Potential);
  const ModelPtr one = w.plugin->shapeModel(&shape).value();
  ASSERT_TRUE(one);
  mesh.addTriangle(btVector3(1, 0, 0), btVector3(1, 0, 1), btVector3(0, 0, 1));
  const ModelPtr two = w.plugin->shapeModel(&shape).value();
  ASSERT_TRUE(two);
  EXPECT_EQ(two->pieces()[0]->mesh().triangles.size(), 2u);
}

// Bad meshes give no model and say why; their pairs are ignored, nothing crashes.
TEST(TriangleMeshModel, BadMeshesGiveAStatusNotAModel) {
  BulletWorld w(ContactModel::Potential);
  btTriangleMesh empty;
  btBvhTriangleMeshShape empty_shape(&empty, true, false);
  Result<ModelPtr> none = w.plugin->shapeModel(&empty_shape);
  EXPECT_FALSE(none.hasValue());
  EXPECT_EQ(none.status().code(), ErrorCode::InvalidArgument);
  EXPECT_NE(none.status().message().find("no triangles"), std::string::npos)
      << none.status().message();

  // A NaN set after the shape was made (Bullet's own bounds computation traps on it).
  std::vector<float> nan_coords = {0, 0, 0, 1, 0, 0, 0, 0, 1};
  std::vector<int> tri = {0, 1, 2};
  btTriangleIndexVertexArray nan_mesh(1, tri.data(), 3 * sizeof(int), 3, nan_coords.data(),
                                      3 * sizeof(float));
  btBvhTriangleMeshShape nan_shape(&nan_mesh, true, false);
  nan_coords[3] = std::nanf("");
  Result<ModelPtr> nan = w.plugin->shapeModel(&nan_shape);
  EXPECT_FALSE(nan.hasValue());
  EXPECT_NE(nan.status().message().find("non-finite"), std::string::npos) << nan.status().message();
  EXPECT_EQ(w.plugin->shapeModel(&nan_shape).status().message(), nan.status().message());

  // An index beyond its subpart's vertex count (the buffer itself is longer, so that
  // Bullet's own bounds computation reads nothing out of range).
  const std::vector<float> coords = {0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 1};
  std::vector<int> indices = {0, 1, 3};
  btTriangleIndexVertexArray array(1, indices.data(), 3 * sizeof(int), 3,
                                   const_cast<float*>(coords.data()), 3 * sizeof(float));
  btBvhTriangleMeshShape beyond(&array, true, false);
  Result<ModelPtr> out_of_range = w.plugin->shapeModel(&beyond);
  EXPECT_FALSE(out_of_range.hasValue());
  EXPECT_NE(out_of_range.status().message().find("index 3"), std::string::npos)
      << out_of_range.status().message();

  // A body over the empty mesh: the pair is ignored (as a shape without a model).
  auto ground = std::make_shared<btBvhTriangleMeshShape>(&empty, true, false);
  w.addBody(ground, 0.0, btVector3(0, 0, 0));
  btRigidBody* box = w.addBody(boxShape(btVector3(0.1f, 0.1f, 0.1f)), 1.0, btVector3(0, 0.05f, 0));
  w.step(10);
  EXPECT_LT(box->getCenterOfMassPosition().y(), 0.05f);
  EXPECT_EQ(w.plugin->stats().pairs, 0);
}

// The closest-points table in both orders: a 0.2 m box above a flat 2 x 2 m mesh at
// y = 0.1, plain (0.15 to the face) and scaled by (0.5, 2, 1) (the plane at
// y = 0.2 ends at x = 0.5, 0.1 short of the box's side: the edges 0.1 across and
// 0.05 apart in height).
TEST(TriangleMeshPairs, ClosestPointsInBothOrders) {
  const Grid plane(8, 2.0, [](double, double) { return 0.1; });
  auto bvh = plane.bvhShape();
  auto scaled = std::make_shared<btScaledBvhTriangleMeshShape>(bvh.get(), btVector3(0.5f, 2, 1));
  BulletWorld w(ContactModel::Potential, 0.0);
  btRigidBody* flat = w.addBody(bvh, 0.0, btVector3(0, 0, 0));
  btRigidBody* raised = w.addBody(scaled, 0.0, btVector3(0, 0, 5));
  btRigidBody* over_flat =
      w.addBody(boxShape(btVector3(0.1f, 0.1f, 0.1f)), 1.0, btVector3(0.7f, 0.35f, 0));
  btRigidBody* over_raised =
      w.addBody(boxShape(btVector3(0.1f, 0.1f, 0.1f)), 1.0, btVector3(0.7f, 0.35f, 5));
  EXPECT_NEAR(closestDistance(w, over_flat, flat), 0.15, kExact);
  EXPECT_NEAR(closestDistance(w, flat, over_flat), 0.15, kExact);
  const double edges = std::hypot(0.1, 0.05);
  EXPECT_NEAR(closestDistance(w, over_raised, raised), edges, kExact);
  EXPECT_NEAR(closestDistance(w, raised, over_raised), edges, kExact);
}

class ScaledMeshContact : public ::testing::TestWithParam<ContactModel> {};

// The contact table through a btScaledBvhTriangleMeshShape: a 0.2 m box dropped 5 cm
// onto a flat mesh at y = 0.1 scaled by (1, 2, 1) rests on y = 0.2 (within the contact
// tolerance, 1 mm, as on any floor), not on the unscaled y = 0.1.
TEST_P(ScaledMeshContact, BoxRestsOnTheScaledSurface) {
  const Grid plane(8, 2.0, [](double, double) { return 0.1; });
  auto bvh = plane.bvhShape();
  BulletWorld w(GetParam(), -9.81, 60.0);
  w.addBody(std::make_shared<btScaledBvhTriangleMeshShape>(bvh.get(), btVector3(1, 2, 1)), 0.0,
            btVector3(0, 0, 0));
  btRigidBody* box = w.addBody(boxShape(btVector3(0.1f, 0.1f, 0.1f)), 1.0, btVector3(0, 0.35f, 0));
  w.step(120);
  double lowest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 8; ++i) {
    const btVector3 c((i & 1) ? 0.1f : -0.1f, (i & 2) ? 0.1f : -0.1f, (i & 4) ? 0.1f : -0.1f);
    lowest = std::min(lowest, double((box->getWorldTransform() * c).y()));
  }
  EXPECT_NEAR(lowest, 0.2, 1e-3);
  EXPECT_LT(box->getLinearVelocity().length(), 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Models, ScaledMeshContact, bothContactModels(), contactModelName);

}  // namespace
}  // namespace sc::test
