// SPDX-License-Identifier: MIT
// Dynamics rows of the stability matrix: small Bullet worlds stepped with the
// SmartCollision plugin (potential, manifold) and with Bullet's own shapes (btBoxShape,
// btConvexHullShape through GJK-EPA, btGImpactMeshShape), same bodies, same solver
// settings; each row reports a pass/fail outcome and its figure.
#include "stability_dynamics.h"

#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "../demos/common/bullet_world.h"
#include "smartcollision/bullet/bullet.h"
#include "stability_pairs.h"

namespace stab {
namespace {

constexpr double kG = 9.81;
constexpr double kBulletMargin = 0.01;  // hull and GImpact margins [m], as bullet_stacking

enum class Kind { Potential, Manifold, BtBox, BtHull, GImpact };
constexpr Kind kKinds[] = {Kind::Potential, Kind::Manifold, Kind::BtBox, Kind::BtHull, Kind::GImpact};

const char* column(Kind k) {
  switch (k) {
    case Kind::Potential: return kScPotential;
    case Kind::Manifold: return kScManifold;
    case Kind::BtBox: return kBtBox;
    case Kind::BtHull: return kBtGjkEpa;
    case Kind::GImpact: return kBtGImpact;
  }
  return "?";
}

bool isSc(Kind k) { return k == Kind::Potential || k == Kind::Manifold; }

btVector3 bt(const Vec3& v) { return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z())); }

/// A Bullet world of one kind; owns everything Bullet keeps pointers to.
struct World : sc::demo::BulletWorld<> {
  World(Kind k, double hz, double gravity, double stiffness = 0.0) : kind(k), dt(1.0 / hz) {
    if (isSc(k)) {
      sc::bullet::PluginSettings settings;
      settings.model = k == Kind::Potential ? sc::bullet::ContactModel::Potential
                                               : sc::bullet::ContactModel::Manifold;
      settings.contact.contact_stiffness = stiffness;
      makeSmartCollision(settings);
    } else {
      makeGImpact(true);
    }
    world->setGravity(btVector3(0, btScalar(gravity), 0));
  }
  ~World() {
    for (auto& b : bodies) world->removeRigidBody(b.get());
  }
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  btRigidBody* add(const std::shared_ptr<btCollisionShape>& shape, double mass, const Vec3& at) {
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(btScalar(mass), inertia);
    btRigidBody::btRigidBodyConstructionInfo ci(btScalar(mass), nullptr, shape.get(), inertia);
    ci.m_startWorldTransform = btTransform(btQuaternion::getIdentity(), bt(at));
    bodies.push_back(std::make_unique<btRigidBody>(ci));
    bodies.back()->setActivationState(DISABLE_DEACTIVATION);  // measure the model, not sleep
    world->addRigidBody(bodies.back().get());
    shapes.push_back(shape);
    return bodies.back().get();
  }
  void ground() { add(std::make_shared<btBoxShape>(btVector3(50, 1, 50)), 0.0, Vec3(0, -1, 0)); }
  void step(int n = 1) {
    for (int i = 0; i < n; ++i) world->stepSimulation(btScalar(dt), 1, btScalar(dt));
  }
  double kinetic() const {
    double e = 0.0;
    for (const auto& b : bodies) {
      if (b->getInvMass() <= 0) continue;
      const btVector3 w = b->getWorldTransform().getBasis().transpose() * b->getAngularVelocity();
      const btVector3 inv = b->getInvInertiaDiagLocal();
      for (int k = 0; k < 3; ++k)
        if (inv[k] > 0) e += 0.5 * double(w[k] * w[k] / inv[k]);
      e += 0.5 * double(b->getLinearVelocity().length2()) / double(b->getInvMass());
    }
    return e;
  }

  /// A cube of half size h in this world's representation.
  std::shared_ptr<btCollisionShape> cube(double h) { return meshShape(boxMesh(Vec3::Constant(h)), true); }
  /// A 2 m x 2 m single-sheet wall in the plane x = 0 (two triangles, no thickness).
  std::shared_ptr<btCollisionShape> wall() {
    sc::MeshData m;
    m.vertices = {Vec3(0, -1, -1), Vec3(0, 1, -1), Vec3(0, 1, 1), Vec3(0, -1, 1)};
    m.triangles = {sc::Tri(0, 1, 2), sc::Tri(0, 2, 3)};
    return meshShape(m, false);
  }

  Kind kind;
  double dt;
  std::vector<std::shared_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::vector<std::unique_ptr<btTriangleMesh>> meshes;

 private:
  std::shared_ptr<btCollisionShape> meshShape(const sc::MeshData& m, bool closed) {
    if (isSc(kind)) {
      auto s = sc::bullet::ScBulletShape::create(
          closed ? sc::ModelKind::ClosedPolyhedron : sc::ModelKind::TriangleSoup, m);
      if (!s.ok()) std::exit((std::fprintf(stderr, "%s\n", s.status().message().c_str()), 1));
      return s.value();
    }
    if (closed && kind == Kind::BtBox) {
      const double h = m.vertices[7].x();
      return std::make_shared<btBoxShape>(btVector3(btScalar(h), btScalar(h), btScalar(h)));
    }
    if (closed && kind == Kind::BtHull) {
      auto hull = std::make_shared<btConvexHullShape>();
      for (const Vec3& v : m.vertices) hull->addPoint(bt(v), false);
      hull->recalcLocalAabb();
      hull->setMargin(btScalar(kBulletMargin));
      return hull;
    }
    meshes.push_back(std::make_unique<btTriangleMesh>());
    for (const sc::Tri& t : m.triangles)
      meshes.back()->addTriangle(bt(m.vertices[std::size_t(t[0])]), bt(m.vertices[std::size_t(t[1])]),
                                 bt(m.vertices[std::size_t(t[2])]));
    if (kind == Kind::GImpact) {
      auto g = std::make_shared<btGImpactMeshShape>(meshes.back().get());
      g->setMargin(btScalar(kBulletMargin));
      g->updateBound();
      return g;
    }
    // Box and hull worlds: Bullet's static triangle mesh for the wall.
    return std::make_shared<btBvhTriangleMeshShape>(meshes.back().get(), true);
  }
};

bool finite(const btRigidBody* b) {
  const btVector3 p = b->getCenterOfMassPosition(), v = b->getLinearVelocity();
  return std::isfinite(double(p.x() + p.y() + p.z())) && std::isfinite(double(v.x() + v.y() + v.z()));
}

std::string fmt(const char* format, double x, double y = 0.0, double z = 0.0) {
  char buf[200];
  std::snprintf(buf, sizeof buf, format, x, y, z);
  return buf;
}

// ---------------------------------------------------------------- rows

/// A 10 cm cube at 50 m/s (two cube sizes per substep at 240 Hz) against a wall with
/// no thickness, from eight start offsets spread over one substep's travel.
Cell thinWall(Kind kind) {
  const char* row = "thin wall at 50 m/s";
  constexpr int kPhases = 8;
  int passes = 0;
  double deepest = 1e9;
  for (int phase = 0; phase < kPhases; ++phase) {
    World w(kind, 240.0, 0.0);
    w.add(w.wall(), 0.0, Vec3::Zero());
    btRigidBody* shot = w.add(w.cube(0.05), 0.1, Vec3(1.0 + phase * 50.0 * w.dt / kPhases, 0, 0));
    shot->setLinearVelocity(btVector3(-50, 0, 0));
    for (int i = 0; i < 120; ++i) {
      w.step();
      deepest = std::min(deepest, double(shot->getCenterOfMassPosition().x()));
    }
    passes += shot->getCenterOfMassPosition().x() < 0 ? 1 : 0;
  }
  return {row, column(kind), passes ? "tunnelled" : "pass", double(passes), std::nan(""),
          fmt("%.0f of 8 shots ended behind the wall; deepest centre x %.3f m", passes, deepest)};
}

/// A 1 kg unit cube dropped from 1 cm onto the ground at dt = 1/60; stable when it
/// comes to rest (kinetic energy of the last 2 s under 1 mJ, within 10 cm of its
/// resting height, finite).
struct Drop {
  bool stable;
  double sag;
};
Drop drop(Kind kind, double stiffness) {
  World w(kind, 60.0, -kG, stiffness);
  w.ground();
  btRigidBody* box = w.add(w.cube(0.5), 1.0, Vec3(0, 0.51, 0));
  double late_energy = 0.0;
  for (int i = 0; i < 300; ++i) {
    w.step();
    if (!finite(box)) return {false, std::nan("")};
    if (i >= 180) late_energy = std::max(late_energy, w.kinetic());
  }
  const double sag = 0.5 - double(box->getCenterOfMassPosition().y());
  return {late_energy < 1e-3 && std::abs(sag) < 0.1, sag};
}

Cell stiffness(Kind kind) {
  const char* row = "stiff penalty at dt = 1/60";
  constexpr double kGiven = 1e6;  // N/m for a 1 kg body: omega * dt = 16.7
  if (kind != Kind::Potential) {
    const Drop d = drop(kind, 0.0);
    return {row, column(kind), d.stable ? "pass" : "exploded", d.sag, std::nan(""),
            fmt("no penalty stiffness (rigid contact); same drop at dt = 1/60, rest sag %.2g m",
                d.sag)};
  }
  double largest = 0.0;
  std::string note = "largest stable k [N/m] of 1e2..1e8; at k:";
  Drop at_given{false, 0.0};
  for (double k = 1e2; k <= 1e8 * 1.001; k *= 10.0) {
    const Drop d = drop(kind, k);
    if (d.stable) largest = k;
    if (std::abs(k - kGiven) < 1.0) at_given = d;
    note += fmt(" %.0e ", k) + (d.stable ? "stable" : "exploded") + ";";
  }
  note += " given k = 1e6; rest sag at it " + fmt("%.2g m", at_given.sag);
  return {row, column(kind), at_given.stable ? "pass" : "exploded", largest, std::nan(""), note};
}

/// A stack of unit cubes spawned 1 cm apart: standing when its top has drifted under
/// 5 cm sideways and is within 10 cm of its resting height after `seconds`.
Cell stack(Kind kind, const char* row, const std::vector<double>& masses, double seconds) {
  World w(kind, 240.0, -kG);
  w.ground();
  std::vector<btRigidBody*> boxes;
  for (std::size_t i = 0; i < masses.size(); ++i)
    boxes.push_back(w.add(w.cube(0.5), masses[i], Vec3(0, 0.5 + 1.01 * double(i) + 0.005, 0)));
  const int steps = int(seconds / w.dt);
  bool ok = true;
  for (int i = 0; i < steps && ok; ++i) {
    w.step();
    ok = finite(boxes.back());
  }
  if (!ok) return {row, column(kind), "exploded", std::nan(""), std::nan(""), "non-finite state"};
  const btVector3 top = boxes.back()->getCenterOfMassPosition();
  const double drift = std::hypot(double(top.x()), double(top.z()));
  const double rest = 0.5 + double(masses.size() - 1);
  const double height_error = rest - double(top.y());
  const bool fell = double(top.y()) < rest - 0.5;
  const char* outcome = fell ? "fell" : (drift < 0.05 && std::abs(height_error) < 0.1) ? "pass" : "drifted";
  return {row, column(kind), outcome, drift, height_error,
          fmt("top drift %.3g m sideways, %.3g m below its resting height after %.0f s", drift,
              height_error, seconds)};
}

/// Two 1 kg unit cubes spawned 25% overlapping, no gravity: they must separate, and
/// the push should not give them more than 1/2 m_red v^2 with v = 1 m/s (the plugin's
/// recovery speed; Bullet's own columns are held to the same bound).
Cell overlap(Kind kind) {
  const char* row = "overlap recovery (25%)";
  World w(kind, 240.0, 0.0);
  btRigidBody* a = w.add(w.cube(0.5), 1.0, Vec3::Zero());
  btRigidBody* b = w.add(w.cube(0.5), 1.0, Vec3(0.75, 0.1, 0.05));
  const double bound = 0.5 * 0.5 * 1.0 * 1.0;
  double max_energy = 0.0;
  int separated_at = -1;
  for (int i = 0; i < 720; ++i) {
    w.step();
    max_energy = std::max(max_energy, w.kinetic());
    const double gap = double(b->getCenterOfMassPosition().x() - a->getCenterOfMassPosition().x()) - 1.0;
    if (separated_at < 0 && gap > 0) separated_at = i;
  }
  if (!finite(a) || !finite(b)) return {row, column(kind), "exploded", std::nan(""), std::nan(""), ""};
  const double gap = double(b->getCenterOfMassPosition().x() - a->getCenterOfMassPosition().x()) - 1.0;
  const char* outcome = gap <= 0 ? "stuck" : max_energy <= bound * 1.001 ? "pass" : "overshoot";
  return {row, column(kind), outcome, max_energy, std::max(0.0, max_energy - bound),
          fmt("max kinetic energy %.3g J (bound %.3g J); separated after %.0f steps", max_energy,
              bound, separated_at)};
}

/// The ground-truth column of a dynamics row: what a pass must reach.
Cell criterion(const std::string& row) {
  if (row == "thin wall at 50 m/s") return {row, kTruth, "criterion", 0.0, std::nan(""), "shots behind the wall"};
  if (row == "stiff penalty at dt = 1/60")
    return {row, kTruth, "criterion", 1e6, std::nan(""), "stable at the given k [N/m]"};
  if (row == "1:100 mass ratio") return {row, kTruth, "criterion", 1.5, std::nan(""), "top at rest height [m]"};
  if (row == "overlap recovery (25%)")
    return {row, kTruth, "criterion", 0.25, std::nan(""), "max kinetic energy 1/2 m_red v^2 [J]"};
  return {row, kTruth, "criterion", 9.5, std::nan(""), "top at rest height [m]"};
}

void naPairColumns(std::vector<Cell>& cells, const std::string& row) {
  for (const char* col : {kScInput, kScCold, kScMix, kScFree, kScNone})
    cells.push_back({row, col, "n/a", std::nan(""), std::nan(""),
                     "n/a (the core has no dynamics)"});
  for (const char* col : {kFclDistance, kFclCollide, kCcdEpa, kCcdMpr})
    cells.push_back({row, col, "n/a", std::nan(""), std::nan(""),
                     "n/a (no dynamics world)"});
}

}  // namespace

std::vector<Cell> runDynamicsRows() {
  std::vector<Cell> cells;
  const std::vector<double> tower(10, 1.0), ratio{1.0, 100.0};
  for (const char* row : {"thin wall at 50 m/s", "stiff penalty at dt = 1/60", "tall tower (10 boxes, 20 s)",
                          "1:100 mass ratio", "overlap recovery (25%)"}) {
    cells.push_back(criterion(row));
    naPairColumns(cells, row);
    for (Kind k : kKinds) {
      const std::string r = row;
      if (r == "thin wall at 50 m/s") cells.push_back(thinWall(k));
      else if (r == "stiff penalty at dt = 1/60") cells.push_back(stiffness(k));
      else if (r == "tall tower (10 boxes, 20 s)") cells.push_back(stack(k, row, tower, 20.0));
      else if (r == "1:100 mass ratio") cells.push_back(stack(k, row, ratio, 10.0));
      else cells.push_back(overlap(k));
      std::printf("  %-32s %-22s %s\n", row, column(k), cells.back().outcome.c_str());
      std::fflush(stdout);
    }
  }
  return cells;
}

}  // namespace stab
