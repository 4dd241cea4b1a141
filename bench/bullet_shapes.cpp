// SPDX-License-Identifier: MIT
#include "bullet_shapes.h"

#include <LinearMath/btConvexHullComputer.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#if SC_BENCH_HAVE_HACD
#include <HACD/hacdHACD.h>
#endif

namespace sc_bench {

const char* modelName(Model m) {
  switch (m) {
    case Model::Potential:
      return "sc_potential";
    case Model::Manifold:
      return "sc_manifold";
    case Model::GImpact:
      return "bt_gimpact";
    case Model::Hacd:
      return "bt_hacd_compound";
    case Model::BtBox:
      return "bt_box";
  }
  return "?";
}

btCollisionShape* ShapeSet::dynamicShape(Model m) const {
  switch (m) {
    case Model::GImpact:
      return gimpact.get();
    case Model::Hacd:
      return compound.get();
    case Model::BtBox:
      return box.get();
    default:
      return sc_shape.get();
  }
}

btCollisionShape* ShapeSet::staticShape(Model m) const {
  const bool ours = m == Model::Potential || m == Model::Manifold;
  return ours ? static_cast<btCollisionShape*>(sc_shape.get()) : static_mesh.get();
}

namespace {

btVector3 toBt(const sc::Vec3& v) {
  return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z()));
}

void buildArray(ShapeSet& s) {
  for (const btVector3& v : s.vertices)
    for (int k = 0; k < 3; ++k) s.coords.push_back(v[k]);
  s.array = std::make_unique<btTriangleIndexVertexArray>(
      int(s.indices.size() / 3), s.indices.data(), int(3 * sizeof(int)), int(s.vertices.size()),
      s.coords.data(), int(3 * sizeof(btScalar)));
}

void buildGImpact(ShapeSet& s) {
  s.gimpact = std::make_shared<btGImpactMeshShape>(s.array.get());
  // Bullet's default triangle margin is 0.1 m, a fifth of our bodies.
  s.gimpact->setMargin(btScalar(kBulletMargin));
  s.gimpact->updateBound();
}

/// A convex part: the hull of `points` shrunk by the margin, so that hull plus margin
/// has the part's size (Bullet's recommended way for convex hull shapes).
std::shared_ptr<btConvexHullShape> hullPart(const std::vector<btScalar>& coords) {
  btConvexHullComputer hull;
  hull.compute(coords.data(), int(3 * sizeof(btScalar)), int(coords.size() / 3),
               btScalar(kBulletMargin), btScalar(0.3));
  auto part = std::make_shared<btConvexHullShape>();
  for (int i = 0; i < hull.vertices.size(); ++i) part->addPoint(hull.vertices[i], false);
  part->recalcLocalAabb();
  part->setMargin(btScalar(kBulletMargin));
  return part;
}

/// Convex parts of the shape-frame mesh: HACD's clusters, or the whole hull when
/// HACD is not there (stated in the output).
std::vector<std::vector<btScalar>> convexParts(const ShapeSet& s) {
  std::vector<std::vector<btScalar>> out;
#if SC_BENCH_HAVE_HACD
  // HACD moves and scales its input in place: give it copies.
  std::vector<HACD::Vec3<HACD::Real>> points;
  for (const btVector3& v : s.vertices) points.emplace_back(v.x(), v.y(), v.z());
  std::vector<HACD::Vec3<long>> tris;
  for (std::size_t i = 0; i + 2 < s.indices.size(); i += 3)
    tris.emplace_back(s.indices[i], s.indices[i + 1], s.indices[i + 2]);
  HACD::HACD hacd;
  hacd.SetPoints(points.data());
  hacd.SetNPoints(points.size());
  hacd.SetTriangles(tris.data());
  hacd.SetNTriangles(tris.size());
  // Parameters of Bullet's own convex decomposition demo, except at least one cluster
  // (not two), so that a box stays one hull.
  hacd.SetCompacityWeight(0.1);
  hacd.SetVolumeWeight(0.0);
  hacd.SetNClusters(1);
  hacd.SetNVerticesPerCH(100);
  hacd.SetConcavity(100);
  hacd.SetAddExtraDistPoints(false);
  hacd.SetAddNeighboursDistPoints(false);
  hacd.SetAddFacesPoints(false);
  if (hacd.Compute()) {
    for (std::size_t c = 0; c < hacd.GetNClusters(); ++c) {
      std::vector<HACD::Vec3<HACD::Real>> p(hacd.GetNPointsCH(c));
      std::vector<HACD::Vec3<long>> t(hacd.GetNTrianglesCH(c));
      if (p.empty() || !hacd.GetCH(c, p.data(), t.data())) continue;
      std::vector<btScalar> coords;
      for (const auto& v : p)
        for (double x : {v.X(), v.Y(), v.Z()}) coords.push_back(btScalar(x));
      out.push_back(std::move(coords));
    }
  }
#endif
  if (out.empty()) out.push_back(s.coords);
  return out;
}

void buildCompound(ShapeSet& s) {
  s.compound = std::make_shared<btCompoundShape>();
  for (const std::vector<btScalar>& coords : convexParts(s)) {
    s.parts.push_back(hullPart(coords));
    s.compound->addChildShape(btTransform::getIdentity(), s.parts.back().get());
  }
}

/// A btBoxShape when the shape-frame vertices are the 8 corners of an axis-aligned
/// box (a cube's principal frame may be any rotation; then there is no box column).
void buildBox(ShapeSet& s) {
  if (s.vertices.size() != 8) return;
  btVector3 hi = s.vertices[0], lo = s.vertices[0];
  for (const btVector3& v : s.vertices) hi.setMax(v), lo.setMin(v);
  for (const btVector3& v : s.vertices)
    for (int k = 0; k < 3; ++k)
      if (std::min(std::abs(v[k] - lo[k]), std::abs(v[k] - hi[k])) > 1e-5f) return;
  s.box = std::make_shared<btBoxShape>(0.5f * (hi - lo));
}

/// Adds `d` (normalised) unless a parallel direction is there already.
void addDirection(std::vector<btVector3>& set, btVector3 d) {
  if (d.length2() < 1e-12) return;
  d.normalize();
  for (const btVector3& e : set)
    if (e.cross(d).length2() < 1e-10) return;
  set.push_back(d);
}

void satAxes(ShapeSet& s) {
  for (std::size_t i = 0; i + 2 < s.indices.size(); i += 3) {
    const btVector3& a = s.vertices[std::size_t(s.indices[i])];
    const btVector3& b = s.vertices[std::size_t(s.indices[i + 1])];
    const btVector3& c = s.vertices[std::size_t(s.indices[i + 2])];
    addDirection(s.normals, (b - a).cross(c - a));
    for (const btVector3& e : {b - a, c - b, a - c}) addDirection(s.edges, e);
  }
}

/// Overlap of two posed copies of a convex set along `axis` (<= 0: apart).
double overlapAlong(const ShapeSet& set, const btTransform& a, const btTransform& b,
                    const btVector3& axis) {
  double a_lo = 1e30, a_hi = -1e30, b_lo = 1e30, b_hi = -1e30;
  for (const btVector3& v : set.vertices) {
    const double pa = double(axis.dot(a * v)), pb = double(axis.dot(b * v));
    a_lo = std::min(a_lo, pa), a_hi = std::max(a_hi, pa);
    b_lo = std::min(b_lo, pb), b_hi = std::max(b_hi, pb);
  }
  return std::min(a_hi - b_lo, b_hi - a_lo);
}

}  // namespace

std::unique_ptr<ShapeSet> makeShapeSet(const sc::MeshData& mesh, bool convex, Use use) {
  auto shape = sc::bullet::ScBulletShape::create(sc::ModelKind::ClosedPolyhedron, mesh);
  if (!shape.ok()) {
    std::fprintf(stderr, "bench: mesh rejected: %s\n", shape.status().message().c_str());
    std::exit(1);
  }
  auto s = std::make_unique<ShapeSet>();
  s->sc_shape = shape.value();
  s->mesh_from_shape = s->sc_shape->meshFromShape();
  const btTransform to_shape = s->mesh_from_shape.inverse();
  for (const sc::Vec3& v : mesh.vertices) s->vertices.push_back(to_shape * toBt(v));
  for (const sc::Tri& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) s->indices.push_back(t[k]);
  s->sc_shape->calculateLocalInertia(1, s->unit_inertia);
  s->convex = convex;
  buildArray(*s);
  if (use == Use::Static) {
    s->static_mesh = std::make_shared<btBvhTriangleMeshShape>(s->array.get(), true);
    return s;
  }
  buildGImpact(*s);
  buildCompound(*s);
  buildBox(*s);
  if (convex) satAxes(*s);
  return s;
}

double satDepth(const ShapeSet& set, const btTransform& a, const btTransform& b) {
  double depth = 1e30;
  auto test = [&](const btVector3& axis) {
    depth = std::min(depth, overlapAlong(set, a, b, axis));
    return depth > 0.0;
  };
  for (const btVector3& n : set.normals)
    if (!test(a.getBasis() * n) || !test(b.getBasis() * n)) return 0.0;
  for (const btVector3& ea : set.edges)
    for (const btVector3& eb : set.edges) {
      const btVector3 c = (a.getBasis() * ea).cross(b.getBasis() * eb);
      if (c.length2() > 1e-10 && !test(c.normalized())) return 0.0;
    }
  return depth;
}

}  // namespace sc_bench
