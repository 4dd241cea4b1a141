// SPDX-License-Identifier: MIT
// ScBulletShape bodies on a static btBvhTriangleMeshShape terrain (what a Bullet user
// gives a static mesh): a 4 x 4 m bumpy height field (bumps 2 x 3 cm, a valley at every
// half-integer x and z) of about 10k and 100k triangles. Per size: Bullet's own BVH
// build, the plugin's soup of the mesh (Plugin::shapeModel, what the first pair of the
// terrain builds), then a 0.2 m box and a 0.5 m CGAL cow dropped from 21 cm into two
// valleys at 60 Hz for 15 s in both contact models: thread CPU per step (the first
// step apart: it builds the soup unless built ahead; the landing, to 2 s; the whole
// run, mostly at rest), and the deepest overlap with the
// terrain measured on the geometry (body vertices below the terrain's piecewise-linear
// surface, terrain vertices inside the box), over the run and over the last second.
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <vector>

#include "../demos/common/bullet_world.h"
#include "meshes.h"

namespace {

constexpr double kHz = 60.0, kSize = 4.0, kBoxHalf = 0.1;

double cpuSeconds(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}
double threadSeconds() { return cpuSeconds(CLOCK_THREAD_CPUTIME_ID); }

double wallSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// The height field as Bullet reads it (float coordinates, 32-bit indices).
struct Terrain {
  int cells;
  std::vector<float> coords;
  std::vector<int> indices;
  std::unique_ptr<btTriangleIndexVertexArray> mesh;

  explicit Terrain(int n) : cells(n) {
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        const double x = -0.5 * kSize + kSize * i / n, z = -0.5 * kSize + kSize * j / n;
        const double y = 0.03 * (std::cos(2 * M_PI * x) + std::cos(2 * M_PI * z));
        coords.insert(coords.end(), {float(x), float(y), float(z)});
      }
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const int a = i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
        indices.insert(indices.end(), {a, b, d, a, d, c});
      }
    mesh = std::make_unique<btTriangleIndexVertexArray>(
        int(indices.size() / 3), indices.data(), 3 * int(sizeof(int)), int(coords.size() / 3),
        coords.data(), 3 * int(sizeof(float)));
  }
  int triangles() const { return int(indices.size() / 3); }
  double y(int i, int j) const { return coords[3 * std::size_t(i * (cells + 1) + j) + 1]; }
  /// The triangles' height at (x, z).
  double heightAt(double x, double z) const {
    const double h = kSize / cells, u = (x + 0.5 * kSize) / h, v = (z + 0.5 * kSize) / h;
    const int i = std::clamp(int(std::floor(u)), 0, cells - 1);
    const int j = std::clamp(int(std::floor(v)), 0, cells - 1);
    const double fu = u - i, fv = v - j;
    const double ha = y(i, j), hb = y(i, j + 1), hc = y(i + 1, j), hd = y(i + 1, j + 1);
    return fv >= fu ? ha + (hb - ha) * fv + (hd - hb) * fu : ha + (hc - ha) * fu + (hd - hc) * fv;
  }
};

double overlap(const Terrain& t, const sc::bullet::ScBulletShape& box, const btTransform& tb,
               const sc::bullet::ScBulletShape& cow, const btTransform& tc) {
  double deepest = 0.0;
  for (const auto& [shape, pose] : {std::pair{&box, tb}, std::pair{&cow, tc}})
    for (const btVector3& v : shape->vertices()) {
      const btVector3 w = pose * v;
      deepest = std::max(deepest, t.heightAt(w.x(), w.z()) - double(w.y()));
    }
  const btTransform inv = tb.inverse();
  for (std::size_t k = 0; k < t.coords.size(); k += 3) {
    const btVector3 l = inv * btVector3(t.coords[k], t.coords[k + 1], t.coords[k + 2]);
    deepest = std::max(
        deepest,
        kBoxHalf - double(std::max({std::fabs(l.x()), std::fabs(l.y()), std::fabs(l.z())})));
  }
  return deepest;
}

/// A cube of half edge kBoxHalf, faces outwards.
sc::MeshData boxMesh() {
  sc::MeshData m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back((i & 1) ? kBoxHalf : -kBoxHalf, (i & 2) ? kBoxHalf : -kBoxHalf,
                            (i & 4) ? kBoxHalf : -kBoxHalf);
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.emplace_back(q[0], q[1], q[2]);
    m.triangles.emplace_back(q[0], q[2], q[3]);
  }
  return m;
}

std::shared_ptr<sc::bullet::ScBulletShape> closedShape(const sc::MeshData& mesh) {
  auto s = sc::bullet::ScBulletShape::create(sc::ModelKind::ClosedPolyhedron, mesh);
  if (!s.ok()) {
    std::fprintf(stderr, "ScBulletShape: %s\n", s.status().message().c_str());
    std::exit(1);
  }
  return s.value();
}

void drop(const Terrain& terrain, sc::bullet::ContactModel model, bool ahead,
          const std::shared_ptr<sc::bullet::ScBulletShape>& cow) {
  sc::demo::BulletWorld<> w;
  sc::bullet::PluginSettings settings;
  settings.model = model;
  w.makeSmartCollision(settings, std::make_unique<sc::bullet::StackingSolver>());
  sc::bullet::useStackingSolverSettings(w.world->getSolverInfo());
  w.world->setGravity(btVector3(0, -9.81f, 0));
  btBvhTriangleMeshShape ground(terrain.mesh.get(), true);
  if (ahead) (void)w.plugin->shapeModel(&ground);
  auto box = closedShape(boxMesh());
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  auto add = [&](btCollisionShape* s, double mass, const btTransform& t) {
    return sc::demo::addBody(*w.world, bodies, s, mass, t);
  };
  add(&ground, 0.0, btTransform::getIdentity());
  btRigidBody* b =
      add(box.get(), 1.0, btTransform(btQuaternion::getIdentity(), btVector3(0.5f, 0.31f, 0.5f)));
  const btTransform& mfs = cow->meshFromShape();
  double lowest = std::numeric_limits<double>::infinity();
  for (const btVector3& v : cow->vertices()) lowest = std::min(lowest, double((mfs * v).y()));
  btRigidBody* c =
      add(cow.get(), 1.0,
          btTransform(mfs.getRotation(),
                      btVector3(-0.5f, btScalar(0.21 - lowest), -0.5f) + mfs.getOrigin()));
  const int steps = int(15 * kHz), last = int(kHz);
  const int landing = int(2 * kHz);
  double first_ms = 0.0, landing_ms = 0.0, cpu = 0.0, impact = 0.0, settled = 0.0;
  for (int k = 0; k < steps; ++k) {
    const double t0 = threadSeconds();
    w.world->stepSimulation(btScalar(1 / kHz), 1, btScalar(1 / kHz));
    const double dt = threadSeconds() - t0;
    (k == 0 ? first_ms : cpu) += 1e3 * dt;
    if (k > 0 && k < landing) landing_ms += 1e3 * dt;
    const double o = overlap(terrain, *box, b->getWorldTransform(), *cow, c->getWorldTransform());
    impact = std::max(impact, o);
    if (k >= steps - last) settled = std::max(settled, o);
  }
  std::printf(
      "  %-9s soup %-6s first step %6.1f ms, landing (to 2 s) %.3f ms/step, all %.3f "
      "ms/step (CPU); overlap impacts %.2f mm, last second %.2f mm; box y %.4f, cow y "
      "%.4f\n",
      model == sc::bullet::ContactModel::Potential ? "potential" : "manifold",
      ahead ? "ahead" : "at 1st", first_ms, landing_ms / (landing - 1), cpu / (steps - 1),
      1e3 * impact, 1e3 * settled, double(b->getCenterOfMassPosition().y()),
      double(c->getCenterOfMassPosition().y()));
  for (auto& body : bodies) w.world->removeRigidBody(body.get());
}

void measure(int cells, const std::shared_ptr<sc::bullet::ScBulletShape>& cow) {
  const Terrain terrain(cells);
  std::printf("terrain %d x %d cells, %d triangles\n", cells, cells, terrain.triangles());
  for (int run = 0; run < 3; ++run) {
    auto t0 = std::chrono::steady_clock::now();
    btBvhTriangleMeshShape shape(terrain.mesh.get(), true);
    const double bvh = wallSince(t0);
    sc::demo::BulletWorld<> w;
    w.makeSmartCollision({});
    t0 = std::chrono::steady_clock::now();
    const double c0 = threadSeconds(), p0 = cpuSeconds(CLOCK_PROCESS_CPUTIME_ID);
    sc::Result<sc::ModelPtr> model = w.plugin->shapeModel(&shape);
    const double wall = wallSince(t0), cpu = threadSeconds() - c0;
    const double all = cpuSeconds(CLOCK_PROCESS_CPUTIME_ID) - p0;
    if (!model.ok()) {
      std::fprintf(stderr, "shapeModel: %s\n", model.status().message().c_str());
      std::exit(1);
    }
    std::printf(
        "  run %d: Bullet's BVH %.1f ms wall; the plugin's soup %.1f ms wall, CPU %.1f ms "
        "on the calling thread, %.1f ms on all threads\n",
        run + 1, 1e3 * bvh, 1e3 * wall, 1e3 * cpu, 1e3 * all);
  }
  for (auto model : {sc::bullet::ContactModel::Potential, sc::bullet::ContactModel::Manifold})
    for (bool ahead : {false, true}) drop(terrain, model, ahead, cow);
}

}  // namespace

int main() {
  const sc::MeshData cow_mesh = sc::support::fitToSize(sc_bench::loadOff("cow"), 0.5);
  if (cow_mesh.vertices.empty()) return 1;
  const auto cow = closedShape(cow_mesh);
  for (int cells : {71, 224}) measure(cells, cow);  // 10,082 and 100,352 triangles
  return 0;
}
