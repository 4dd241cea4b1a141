// SPDX-License-Identifier: MIT
// Bullet plugin against Bullet's own non-convex shapes (issue 6), in one process on
// the same scenes: a 10-box tower, a 15-box pyramid and four cows on the ground, each
// with four contact models (SmartCollision potential and manifold, btGImpactMeshShape,
// a btCompoundShape of HACD convex parts). Time per step, top drift, jitter and
// penetration; then the potential model's largest stable stiffness per time step.
// Writes CSVs with --csv-dir=<dir>; --quick (or SC_BENCH_QUICK=1) runs shorter.
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <LinearMath/btConvexHullComputer.h>
#include <btBulletDynamicsCommon.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#if SC_BENCH_HAVE_HACD
#include <HACD/hacdHACD.h>
#endif

#include "off_mesh.h"
#include "smartcollision/bullet/bullet.h"

namespace {

using Clock = std::chrono::steady_clock;

constexpr double kHz = 240.0;
constexpr double kGravity = -9.81;
constexpr double kGap = 0.01;           // spawn gap: touching pairs count as intersecting
constexpr double kBulletMargin = 0.01;  // GImpact triangles and HACD hulls [m]
constexpr int kBlock = 60;              // steps per model before the next model's turn
constexpr double kPi = 3.141592653589793;

enum class Model { Potential, Manifold, GImpact, Hacd };
constexpr Model kModels[] = {Model::Potential, Model::Manifold, Model::GImpact, Model::Hacd};

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
  }
  return "?";
}

double threadSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

btVector3 toBt(const sc::Vec3& v) {
  return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z()));
}

bool finite(const btVector3& v) {
  return std::isfinite(double(v.x())) && std::isfinite(double(v.y())) &&
         std::isfinite(double(v.z()));
}

sc::MeshData boxMesh(double h) {
  sc::MeshData m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back((i & 1) ? h : -h, (i & 2) ? h : -h, (i & 4) ? h : -h);
  m.triangles = {sc::Tri(0, 2, 3), sc::Tri(0, 3, 1), sc::Tri(4, 5, 7), sc::Tri(4, 7, 6),
                 sc::Tri(0, 1, 5), sc::Tri(0, 5, 4), sc::Tri(2, 6, 7), sc::Tri(2, 7, 3),
                 sc::Tri(0, 4, 6), sc::Tri(0, 6, 2), sc::Tri(1, 3, 7), sc::Tri(1, 7, 5)};
  return m;
}

// ---------------------------------------------------------------- shapes

/// One mesh as every model's collision shape, all in the ScBulletShape's principal
/// frame, so every model simulates the same body (same centre of mass and inertia).
struct ShapeSet {
  std::shared_ptr<sc::bullet::ScBulletShape> sc_shape;
  btTransform mesh_from_shape;
  std::vector<btVector3> vertices;  ///< shape frame
  std::vector<int> indices;
  btVector3 unit_inertia;  ///< principal inertia of 1 kg
  bool convex = false;     ///< penetration between two bodies is measured for convex sets only
  // GImpact: Bullet keeps pointers into these.
  std::vector<btScalar> gimpact_vertices;
  std::unique_ptr<btTriangleIndexVertexArray> gimpact_array;
  std::shared_ptr<btGImpactMeshShape> gimpact;
  // HACD compound and its children.
  std::vector<std::shared_ptr<btConvexHullShape>> parts;
  std::shared_ptr<btCompoundShape> compound;
  // Separating-axis candidates of a convex set: its face normals and distinct edge
  // directions (shape frame).
  std::vector<btVector3> normals, edges;

  btCollisionShape* shape(Model m) const {
    if (m == Model::GImpact) return gimpact.get();
    if (m == Model::Hacd) return compound.get();
    return sc_shape.get();
  }
};

void buildGImpact(ShapeSet& s) {
  for (const btVector3& v : s.vertices)
    for (int k = 0; k < 3; ++k) s.gimpact_vertices.push_back(v[k]);
  s.gimpact_array = std::make_unique<btTriangleIndexVertexArray>(
      int(s.indices.size() / 3), s.indices.data(), int(3 * sizeof(int)), int(s.vertices.size()),
      s.gimpact_vertices.data(), int(3 * sizeof(btScalar)));
  s.gimpact = std::make_shared<btGImpactMeshShape>(s.gimpact_array.get());
  // Bullet's default triangle margin is 0.1 m, a tenth of our boxes.
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
  if (out.empty()) {
    std::vector<btScalar> coords;
    for (const btVector3& v : s.vertices)
      for (int k = 0; k < 3; ++k) coords.push_back(v[k]);
    out.push_back(std::move(coords));
  }
  return out;
}

void buildCompound(ShapeSet& s) {
  s.compound = std::make_shared<btCompoundShape>();
  for (const std::vector<btScalar>& coords : convexParts(s)) {
    s.parts.push_back(hullPart(coords));
    s.compound->addChildShape(btTransform::getIdentity(), s.parts.back().get());
  }
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

std::unique_ptr<ShapeSet> makeShapeSet(const sc::MeshData& mesh, bool convex) {
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
  buildGImpact(*s);
  buildCompound(*s);
  if (convex) satAxes(*s);
  return s;
}

// ---------------------------------------------------------------- worlds

/// Bullet's usual objects for one contact model: the plugin's world for ours, a plain
/// btDiscreteDynamicsWorld (GImpact registered) for Bullet's.
struct World {
  World(Model m, double step, const sc::bullet::ContactSettings& contact = {})
      : model(m), dt(step) {
    const bool ours = m == Model::Potential || m == Model::Manifold;
    config = ours ? std::make_unique<btDefaultCollisionConfiguration>(
                        sc::bullet::collisionConstructionInfo())
                  : std::make_unique<btDefaultCollisionConfiguration>();
    dispatcher = std::make_unique<btCollisionDispatcher>(config.get());
    broadphase = std::make_unique<btDbvtBroadphase>();
    solver = std::make_unique<btSequentialImpulseConstraintSolver>();
    if (ours) {
      sc::bullet::PluginSettings settings;
      settings.model = m == Model::Potential ? sc::bullet::ContactModel::Potential
                                             : sc::bullet::ContactModel::Manifold;
      settings.contact = contact;
      auto plugin = sc::bullet::registerSmartCollision(dispatcher.get(), settings);
      if (!plugin.ok()) {
        std::fprintf(stderr, "bench: %s\n", plugin.status().message().c_str());
        std::exit(1);
      }
      world = std::make_unique<sc::bullet::ScDynamicsWorld>(
          dispatcher.get(), broadphase.get(), solver.get(), config.get(), plugin.value());
    } else {
      btGImpactCollisionAlgorithm::registerAlgorithm(dispatcher.get());
      world = std::make_unique<btDiscreteDynamicsWorld>(dispatcher.get(), broadphase.get(),
                                                        solver.get(), config.get());
    }
    world->setGravity(btVector3(0, btScalar(kGravity), 0));
    addBody(ground_shape.get(), 0, btVector3(0, 0, 0),
            btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0)));
  }
  ~World() {
    for (auto& b : bodies) world->removeRigidBody(b.get());
  }
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// Sleeping is off so every step sees the model (and costs what it costs).
  btRigidBody* addBody(btCollisionShape* shape, double mass, const btVector3& inertia,
                       const btTransform& pose) {
    btRigidBody::btRigidBodyConstructionInfo ci(btScalar(mass), nullptr, shape, inertia);
    ci.m_startWorldTransform = pose;
    bodies.push_back(std::make_unique<btRigidBody>(ci));
    bodies.back()->setActivationState(DISABLE_DEACTIVATION);
    world->addRigidBody(bodies.back().get());
    return bodies.back().get();
  }
  void step() { world->stepSimulation(btScalar(dt), 1, btScalar(dt)); }

  Model model;
  double dt;
  std::unique_ptr<btBoxShape> ground_shape = std::make_unique<btBoxShape>(btVector3(50, 1, 50));
  std::unique_ptr<btDefaultCollisionConfiguration> config;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  std::unique_ptr<btBroadphaseInterface> broadphase;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver;
  std::unique_ptr<btDiscreteDynamicsWorld> world;
  std::vector<std::unique_ptr<btRigidBody>> bodies;  ///< [0] is the ground
};

// ---------------------------------------------------------------- scenes

/// Where the dynamic bodies start and where they would rest (spawn minus the gaps).
struct Scene {
  std::string name;
  const ShapeSet* shapes = nullptr;
  std::vector<btTransform> spawn;
  std::vector<double> rest_drop;  ///< height each body falls to close the gaps below it
  std::vector<int> top;           ///< bodies whose drift is reported (worst of them)
};

Scene tower(const ShapeSet& box, int n) {
  Scene s{"tower10", &box, {}, {}, {n - 1}};
  for (int i = 0; i < n; ++i) {
    const btVector3 p(0, btScalar((i + 0.5) + (i + 1) * kGap), 0);
    s.spawn.push_back(btTransform(btQuaternion::getIdentity(), p) * box.mesh_from_shape);
    s.rest_drop.push_back((i + 1) * kGap);
  }
  return s;
}

Scene pyramid(const ShapeSet& box) {
  Scene s{"pyramid15", &box, {}, {}, {14}};
  const double pitch = 1.1;  // 10% gaps in a row; each box rests on two
  for (int row = 0; row < 5; ++row)
    for (int i = 0; i < 5 - row; ++i) {
      const double x = (i - 0.5 * (4 - row)) * pitch;
      const btVector3 p(btScalar(x), btScalar((row + 0.5) + (row + 1) * kGap), 0);
      s.spawn.push_back(btTransform(btQuaternion::getIdentity(), p) * box.mesh_from_shape);
      s.rest_drop.push_back((row + 1) * kGap);
    }
  return s;
}

/// Four copies standing on the ground, apart: every contact is a non-convex body's
/// several feet on the box ground. The body is posed so the mesh keeps its frame.
Scene meshes(const ShapeSet& mesh, const std::string& name) {
  Scene s{name, &mesh, {}, {}, {0, 1, 2, 3}};
  double min_y = 1e9;
  for (const btVector3& v : mesh.vertices)
    min_y = std::min(min_y, double((mesh.mesh_from_shape * v).y()));
  for (int i = 0; i < 4; ++i) {
    const btVector3 p(btScalar(1.5 * (i % 2)), btScalar(kGap - min_y), btScalar(1.0 * (i / 2)));
    s.spawn.push_back(btTransform(btQuaternion::getIdentity(), p) * mesh.mesh_from_shape);
    s.rest_drop.push_back(kGap);
  }
  return s;
}

void populate(World& w, const Scene& s, double mass = 1.0) {
  for (const btTransform& pose : s.spawn)
    w.addBody(s.shapes->shape(w.model), mass, mass * s.shapes->unit_inertia, pose);
}

btRigidBody* body(World& w, int i) { return w.bodies[std::size_t(i) + 1].get(); }

// ---------------------------------------------------------------- measurements

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

/// Penetration depth of two convex polytopes: the smallest overlap over the face
/// normals of both and the cross products of their edges (separating axis theorem).
double satDepth(const ShapeSet& set, const btTransform& a, const btTransform& b) {
  std::vector<btVector3> axes;
  for (const btVector3& n : set.normals) {
    axes.push_back(a.getBasis() * n);
    axes.push_back(b.getBasis() * n);
  }
  for (const btVector3& ea : set.edges)
    for (const btVector3& eb : set.edges) {
      const btVector3 c = (a.getBasis() * ea).cross(b.getBasis() * eb);
      if (c.length2() > 1e-10) axes.push_back(c.normalized());
    }
  double depth = 1e30;
  for (const btVector3& axis : axes) {
    depth = std::min(depth, overlapAlong(set, a, b, axis));
    if (depth <= 0.0) return 0.0;
  }
  return depth;
}

/// Deepest overlap in the world, by geometry (the same for every model): vertices
/// below the ground's top, and the separating-axis depth between convex bodies whose
/// centres are close.
double maxPenetration(World& w, const Scene& s) {
  const ShapeSet& set = *s.shapes;
  const int n = int(s.spawn.size());
  double depth = 0.0;
  for (int i = 0; i < n; ++i) {
    const btTransform& t = body(w, i)->getWorldTransform();
    for (const btVector3& v : set.vertices) depth = std::max(depth, -double((t * v).y()));
  }
  if (!set.convex) return depth;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const btTransform& a = body(w, i)->getWorldTransform();
      const btTransform& b = body(w, j)->getWorldTransform();
      if ((a.getOrigin() - b.getOrigin()).length() > 1.8) continue;
      depth = std::max(depth, satDepth(set, a, b));
    }
  return depth;
}

double tilt(const btRigidBody* b, const btTransform& spawn) {
  // The rotation since spawn, applied to the vertical.
  const btVector3 up =
      b->getWorldTransform().getBasis() * (spawn.getBasis().transpose() * btVector3(0, 1, 0));
  return std::acos(std::clamp(double(up.y()), -1.0, 1.0));
}

struct Figures {
  std::vector<double> step_ms;  ///< steady-state wall time per step
  double cpu_s = 0.0;           ///< steady-state thread CPU time
  double jitter_sum = 0.0;      ///< sum of squared speeds over the jitter window
  long jitter_samples = 0;
  double max_penetration = 0.0;
  std::vector<btVector3> settled;  ///< top bodies' positions when settled
  double horizontal = 0.0, drop = 0.0, creep = 0.0, max_tilt = 0.0;
  bool stands = true, is_finite = true;
};

/// Timeline of one run: settled at `settle`, jitter over the last `window` steps.
struct Timeline {
  int steps, settle, window;
};

void stepAndMeasure(World& w, const Scene& s, const Timeline& tl, int i, Figures& f) {
  const auto t0 = Clock::now();
  const double c0 = threadSeconds();
  w.step();
  const double c1 = threadSeconds();
  const auto t1 = Clock::now();
  if (i < tl.settle) return;
  if (i == tl.settle)
    for (int k : s.top) f.settled.push_back(body(w, k)->getCenterOfMassPosition());
  f.step_ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
  f.cpu_s += c1 - c0;
  if (i % 2 == 0) f.max_penetration = std::max(f.max_penetration, maxPenetration(w, s));
  if (i < tl.steps - tl.window) return;
  for (std::size_t k = 0; k < s.spawn.size(); ++k) {
    f.jitter_sum += double(body(w, int(k))->getLinearVelocity().length2());
    ++f.jitter_samples;
  }
}

/// Top drift: the worst watched body's horizontal displacement from its spawn, its
/// drop below the resting height (negative: it rests higher, e.g. on margins), its
/// movement after settling; and whether every body still stands where it started.
void finish(World& w, const Scene& s, Figures& f) {
  f.horizontal = f.drop = f.creep = -1e9;
  for (std::size_t k = 0; k < s.top.size(); ++k) {
    const int i = s.top[k];
    const btVector3 p = body(w, i)->getWorldTransform().getOrigin();
    const btVector3 p0 = s.spawn[std::size_t(i)].getOrigin();
    const double dx = double(p.x() - p0.x()), dz = double(p.z() - p0.z());
    f.horizontal = std::max(f.horizontal, std::sqrt(dx * dx + dz * dz));
    f.drop = std::max(f.drop, double(p0.y()) - s.rest_drop[std::size_t(i)] - double(p.y()));
    f.creep =
        std::max(f.creep, double((body(w, i)->getCenterOfMassPosition() - f.settled[k]).length()));
  }
  for (std::size_t i = 0; i < s.spawn.size(); ++i) {
    const btRigidBody* b = body(w, int(i));
    f.is_finite = f.is_finite && finite(b->getWorldTransform().getOrigin());
    const btVector3 d = b->getWorldTransform().getOrigin() - s.spawn[i].getOrigin();
    f.max_tilt = std::max(f.max_tilt, tilt(b, s.spawn[i]));
    if (std::hypot(double(d.x()), double(d.z())) > 0.25 || f.max_tilt > 0.2 || double(d.y()) < -0.5)
      f.stands = false;
  }
  f.stands = f.stands && f.is_finite;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(q * double(v.size())))];
}

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? NAN : s / double(v.size());
}

/// Runs one scene with every model, interleaved in blocks of steps so that the load
/// of the (shared) machine falls on all of them alike; one CSV row per model.
void runScene(const Scene& s, int scene_id, const Timeline& tl, FILE* csv) {
  std::vector<std::unique_ptr<World>> worlds;
  std::vector<Figures> figs(std::size(kModels));
  for (Model m : kModels) {
    worlds.push_back(std::make_unique<World>(m, 1.0 / kHz));
    populate(*worlds.back(), s);
  }
  for (int start = 0; start < tl.steps; start += kBlock)
    for (std::size_t m = 0; m < worlds.size(); ++m)
      for (int i = start; i < std::min(tl.steps, start + kBlock); ++i)
        stepAndMeasure(*worlds[m], s, tl, i, figs[m]);
  for (std::size_t m = 0; m < worlds.size(); ++m) {
    Figures& f = figs[m];
    finish(*worlds[m], s, f);
    const double jitter = std::sqrt(f.jitter_sum / double(std::max(1L, f.jitter_samples)));
    const double drift = f.horizontal + std::max(0.0, f.drop);
    const double cpu_ms = 1e3 * f.cpu_s / double(std::max<std::size_t>(1, f.step_ms.size()));
    std::printf("%-10s %-17s %8.3f %8.3f %8.3f %9.2f %9.2f %8.2f %9.2f %10.2e %8.2f %s\n",
                s.name.c_str(), modelName(kModels[m]), mean(f.step_ms), percentile(f.step_ms, 0.95),
                cpu_ms, 1e3 * f.horizontal, 1e3 * f.drop, 1e3 * f.creep, 1e3 * drift, jitter,
                1e3 * f.max_penetration, f.stands ? "stands" : "FALLS");
    std::fprintf(csv, "%s,%d,%s,%d,%d,%.5f,%.5f,%.5f,%.3f,%.3f,%.3f,%.3f,%.4f,%.4e,%.3f,%d\n",
                 s.name.c_str(), scene_id, modelName(kModels[m]), int(m), tl.steps - tl.settle,
                 mean(f.step_ms), percentile(f.step_ms, 0.95), cpu_ms, 1e3 * f.horizontal,
                 1e3 * f.drop, 1e3 * f.creep, 1e3 * drift, 1e3 * f.max_tilt, jitter,
                 1e3 * f.max_penetration, f.stands ? 1 : 0);
    std::fflush(csv);
  }
}

// ---------------------------------------------------------------- stiffness sweep

/// How a potential-model tower ended: the first failure seen, or "stable".
struct SweepRun {
  const char* outcome = "stable";
  double drop = 0.0;       ///< top box below its resting height [m]
  double rms_speed = 0.0;  ///< over the last second [m/s]; NaN when stopped early
};

const char* towerFailure(World& w, const Scene& s, double max_speed) {
  const int n = int(s.spawn.size());
  double below = 0.0;  // the ground's top
  for (int i = 0; i < n; ++i) {
    const btRigidBody* b = body(w, i);
    const btVector3 p = b->getWorldTransform().getOrigin();
    if (!finite(p) || !finite(b->getLinearVelocity())) return "nan";
    if (max_speed > 10.0) return "blow_up";
    const btVector3 d = p - s.spawn[std::size_t(i)].getOrigin();
    if (std::hypot(double(d.x()), double(d.z())) > 0.25 || tilt(b, s.spawn[std::size_t(i)]) > 0.2)
      return "toppled";
    // A box more than half inside the one under it (or the ground) has sunk.
    if (double(p.y()) - below < (i == 0 ? 0.0 : 0.5)) return "sank";
    below = double(p.y());
  }
  return nullptr;
}

/// The 10-box tower with the potential model at time step dt and kT = k, for
/// `seconds`; stable = standing, finite, and at rest (RMS speed < 0.05 m/s) at the end.
SweepRun sweepRun(const ShapeSet& box, double dt, double k, double seconds) {
  sc::bullet::ContactSettings contact;
  contact.force_stiffness = k;
  World w(Model::Potential, dt, contact);
  const Scene s = tower(box, 10);
  populate(w, s);
  const int steps = int(std::lround(seconds / dt));
  const int last_second = std::max(1, int(std::lround(1.0 / dt)));
  SweepRun r;
  double speed2 = 0.0;
  for (int i = 0; i < steps; ++i) {
    w.step();
    double max_speed = 0.0;
    for (std::size_t b = 0; b < s.spawn.size(); ++b) {
      const double v2 = double(body(w, int(b))->getLinearVelocity().length2());
      max_speed = std::max(max_speed, std::sqrt(v2));
      if (i >= steps - last_second) speed2 += v2;
    }
    // Checked every 1/60 s and at the end: a failed tower is not run further.
    if (i % std::max(1, int(std::lround(1.0 / (60.0 * dt)))) == 0 || i + 1 == steps)
      if (const char* failure = towerFailure(w, s, max_speed)) {
        r.outcome = failure;
        break;
      }
  }
  // A run stopped at a failure has no last second: its speed is not a figure.
  const bool ran_out = std::strcmp(r.outcome, "stable") == 0;
  r.rms_speed = ran_out ? std::sqrt(speed2 / double(last_second * int(s.spawn.size()))) : NAN;
  const btVector3 top = body(w, 9)->getWorldTransform().getOrigin();
  r.drop = double(s.spawn[9].getOrigin().y()) - s.rest_drop[9] - double(top.y());
  if (std::strcmp(r.outcome, "stable") == 0 && r.rms_speed > 0.05) r.outcome = "restless";
  return r;
}

/// Stiffness range of one time step. "Stands" is the stability (standing, no
/// NaN, no blow-up); "at rest" also asks for an RMS speed under 0.05 m/s at the end.
struct Limits {
  double stand_lo = NAN, stand_hi = NAN, rest_lo = NAN, rest_hi = NAN, fail_above = NAN;
  std::string failure = "none";  ///< the first failure above the largest standing k

  void add(double k, const char* outcome) {
    const bool rest = std::strcmp(outcome, "stable") == 0;
    const bool stands = rest || std::strcmp(outcome, "restless") == 0;
    if (rest) {
      if (std::isnan(rest_lo)) rest_lo = k;
      rest_hi = k;
    }
    if (stands) {
      if (std::isnan(stand_lo)) stand_lo = k;
      stand_hi = k;
      fail_above = NAN;
      failure = "none";
    } else if (!std::isnan(stand_hi) && std::isnan(fail_above)) {
      fail_above = k;
      failure = outcome;
    }
  }
};

void runSweep(const ShapeSet& box, bool quick, FILE* csv, FILE* limits) {
  const int hz[] = {60, 120, 240, 480, 960};
  const double seconds = quick ? 2.0 : 5.0;
  const double step = quick ? 0.5 : 0.25;  // decades between stiffnesses
  for (int f : hz) {
    const double dt = 1.0 / f;
    Limits l;
    for (double e = 1.0; e <= 7.0 + 1e-9; e += step) {
      const double k = std::pow(10.0, e);
      const SweepRun r = sweepRun(box, dt, k, seconds);
      l.add(k, r.outcome);
      std::fprintf(csv, "%d,%.6f,%.4e,%.4e,%.4e,%s,%.3f,%.4e\n", f, dt, k,
                   std::min(k, 0.5 / (dt * dt)), std::min(k, 1.0 / (dt * dt)), r.outcome,
                   1e3 * r.drop, r.rms_speed);
      std::fflush(csv);
    }
    const double clamp = 0.5 / (dt * dt);  // the plugin's k <= m_red / dt^2, 1 kg boxes
    const double derived = 0.5 * std::pow(2.0 * kPi / (10.0 * dt), 2.0);
    std::printf(
        "%4d Hz: stands for kT %.3g..%.3g N/m, at rest for %.3g..%.3g; first failure "
        "above: %.3g (%s); clamp m/dt^2 = %.3g, default (N = 10) = %.3g\n",
        f, l.stand_lo, l.stand_hi, l.rest_lo, l.rest_hi, l.fail_above, l.failure.c_str(), clamp,
        derived);
    std::fprintf(limits, "%d,%.6f,%.4e,%.4e,%.4e,%.4e,%.4e,%s,%.4e,%.4e\n", f, dt, l.stand_lo,
                 l.stand_hi, l.rest_lo, l.rest_hi, l.fail_above, l.failure.c_str(), clamp, derived);
    std::fflush(limits);
  }
}

// ---------------------------------------------------------------- main

FILE* openCsv(const std::string& dir, const char* name, const char* header) {
  const std::string path = dir + "/" + name;
  FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) {
    std::fprintf(stderr, "bench: cannot write %s\n", path.c_str());
    std::exit(1);
  }
  std::fprintf(f, "%s\n", header);
  return f;
}

sc::MeshData loadMesh(const char* name) {
  sc::MeshData mesh = sc_bench::loadOff(name);
  if (mesh.triangles.empty()) std::exit(1);
  return sc_bench::unitSize(std::move(mesh));
}

}  // namespace

int main(int argc, char** argv) {
  std::string dir = ".";
  const char* env = std::getenv("SC_BENCH_QUICK");
  bool quick = env != nullptr && std::strcmp(env, "1") == 0;
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], "--csv-dir=", 10) == 0)
      dir = argv[i] + 10;
    else if (std::strcmp(argv[i], "--quick") == 0)
      quick = true;
    else {
      std::fprintf(stderr, "usage: %s [--csv-dir=DIR] [--quick]\n", argv[0]);
      return 2;
    }
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // progress shows in a redirected log
  const auto t0 = Clock::now();
  const char* mesh_name = "cow";
  const auto box = makeShapeSet(boxMesh(0.5), true);
  const auto mesh = makeShapeSet(loadMesh(mesh_name), false);
  std::printf("shapes: box %zu HACD part(s), %s %zu triangles, %zu HACD part(s)%s; %.1f s\n",
              box->parts.size(), mesh_name, mesh->indices.size() / 3, mesh->parts.size(),
              SC_BENCH_HAVE_HACD ? "" : " (no HACD: one convex hull each)",
              std::chrono::duration<double>(Clock::now() - t0).count());

  const int steps = int(std::lround((quick ? 4.0 : 10.0) * kHz));
  const Timeline tl{steps, int(std::lround(2.0 * kHz)), int(std::lround(2.0 * kHz))};
  FILE* csv = openCsv(dir, "bullet_stacking.csv",
                      "scene,scene_id,model,model_id,steps,mean_ms,p95_ms,cpu_mean_ms,"
                      "top_horizontal_mm,top_drop_mm,creep_mm,drift_mm,max_tilt_mrad,"
                      "jitter_mps,max_penetration_mm,stands");
  std::printf("%-10s %-17s %8s %8s %8s %9s %9s %8s %9s %10s %8s\n", "scene", "model", "mean_ms",
              "p95_ms", "cpu_ms", "horiz_mm", "drop_mm", "creep_mm", "drift_mm", "jitter_m/s",
              "pen_mm");
  runScene(tower(*box, 10), 0, tl, csv);
  runScene(pyramid(*box), 1, tl, csv);
  runScene(meshes(*mesh, std::string(mesh_name) + "4"), 2, tl, csv);
  std::fclose(csv);
  std::printf("scenes done: %.1f s\n", std::chrono::duration<double>(Clock::now() - t0).count());

  FILE* sweep = openCsv(dir, "potential_stiffness_vs_dt.csv",
                        "hz,dt_s,k_requested,k_eff_box_box,k_eff_ground,outcome,top_drop_mm,"
                        "rms_speed_mps");
  FILE* limits = openCsv(dir, "potential_stiffness_limits.csv",
                         "hz,dt_s,smallest_standing_k,largest_standing_k,smallest_at_rest_k,"
                         "largest_at_rest_k,first_failure_above,failure,clamp_k,default_k");
  runSweep(*box, quick, sweep, limits);
  std::fclose(sweep);
  std::fclose(limits);
  std::printf("total: %.1f s\n", std::chrono::duration<double>(Clock::now() - t0).count());
  return 0;
}
