// SPDX-License-Identifier: MIT
// Bullet plugin against Bullet's own shapes at game rates (issues 6 and 16), in one
// process on the same scenes: a 10-box tower, a 1:100 mass-ratio stack, a 15-box
// pyramid, four cows on the ground and a pile of 24 tori in a closed bowl, each at
// 60, 120 and 240 Hz with every contact model that applies (SmartCollision potential
// and manifold, btGImpactMeshShape, a btCompoundShape of HACD convex parts, and
// btBoxShape for the boxes). Time per step, drift, overlap (measured geometrically,
// never from a model's answer), rest and energy; then the potential model's stable
// stiffness range per time step. Writes CSVs with --csv-dir=<dir>; --quick (or
// SC_BENCH_QUICK=1) runs shorter. Exits 1 when a target is missed.
#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <btBulletDynamicsCommon.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "../demos/common/bullet_world.h"
#include "bullet_shapes.h"
#include "meshes.h"
#include "sc_support/sample_meshes.h"
#include "sc_support/stats.h"

namespace {

using sc_bench::Model;
using sc_bench::ShapeSet;
using Clock = std::chrono::steady_clock;

constexpr double kGravity = -9.81;
constexpr double kSize = 0.5;           // every body's largest extent [m]
constexpr double kGap = 0.01;           // spawn gap: touching pairs count as intersecting
constexpr double kBlockSeconds = 0.25;  // simulated time per model before the next one's turn
constexpr double kChecksPerSecond = 30.0;
constexpr double kTorusMajor = 0.17, kTorusMinor = 0.08;  // 0.5 m across
constexpr double kBowlInner = 1.2, kBowlOuter = 1.3;
constexpr int kBowlRings = 16, kBowlSegments = 48;
constexpr Model kModels[] = {Model::Potential, Model::Manifold, Model::GImpact, Model::Hacd,
                             Model::BtBox};

double threadSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
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

// ---------------------------------------------------------------- worlds

/// Bullet's usual objects for one contact model: the plugin's world for ours, a plain
/// btDiscreteDynamicsWorld (GImpact registered) for Bullet's; the same solver
/// settings for all, so that only the contacts differ.
struct World : sc::demo::BulletWorld<> {
  World(Model m, double step, double ground_top, const sc::bullet::ContactSettings& contact = {})
      : model(m), dt(step) {
    const bool ours = m == Model::Potential || m == Model::Manifold;
    if (ours) {
      sc::bullet::PluginSettings settings;
      settings.model = m == Model::Potential ? sc::bullet::ContactModel::Potential
                                             : sc::bullet::ContactModel::Manifold;
      settings.contact = contact;
      makeSmartCollision(settings);
    } else {
      makeGImpact(false);
    }
    world->setGravity(btVector3(0, btScalar(kGravity), 0));
    addBody(ground_shape.get(), 0, btVector3(0, 0, 0),
            btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(ground_top - 1), 0)));
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
    if (mass > 0) dynamic.push_back(bodies.back().get());
    return bodies.back().get();
  }
  void step() { world->stepSimulation(btScalar(dt), 1, btScalar(dt)); }

  Model model;
  double dt;
  std::unique_ptr<btBoxShape> ground_shape = std::make_unique<btBoxShape>(btVector3(50, 1, 50));
  std::vector<std::unique_ptr<btRigidBody>> bodies;  ///< [0] is the ground
  std::vector<btRigidBody*> dynamic;                 ///< in the scene's spawn order
};

// ---------------------------------------------------------------- scenes

/// Where the dynamic bodies start and where they would rest (spawn minus the gaps);
/// a pile also has a static container and no resting heights.
struct Scene {
  std::string name;
  const ShapeSet* shapes = nullptr;
  std::vector<btTransform> spawn;
  std::vector<double> mass;
  std::vector<double> rest_drop;  ///< height each body falls to close the gaps below it
  std::vector<int> top;           ///< bodies whose drift is reported (worst of them)
  double ground_top = 0.0;
  const ShapeSet* container = nullptr;  ///< static, its mesh frame at the origin
  const sc::samples::BowlInnerDepth* container_depth = nullptr;  ///< on its facets
  int id = 0;                           ///< position in the run (the charts' x)

  bool applies(Model m) const { return shapes->dynamicShape(m) != nullptr; }
  bool pile() const { return container != nullptr; }
};

btTransform posed(const ShapeSet& set, const btVector3& at, const btQuaternion& q = {0, 0, 0, 1}) {
  return btTransform(q, at) * set.mesh_from_shape;
}

Scene tower(const ShapeSet& box, int n, const std::string& name, double top_mass = 1.0) {
  Scene s{name, &box, {}, {}, {}, {n - 1}};
  for (int i = 0; i < n; ++i) {
    const btVector3 p(0, btScalar((i + 0.5) * kSize + (i + 1) * kGap), 0);
    s.spawn.push_back(posed(box, p));
    s.mass.push_back(i == n - 1 ? top_mass : 1.0);
    s.rest_drop.push_back((i + 1) * kGap);
  }
  return s;
}

Scene pyramid(const ShapeSet& box) {
  Scene s{"pyramid15", &box, {}, {}, {}, {14}};
  const double pitch = 1.1 * kSize;  // 10% gaps in a row; each box rests on two
  for (int row = 0; row < 5; ++row)
    for (int i = 0; i < 5 - row; ++i) {
      const double x = (i - 0.5 * (4 - row)) * pitch;
      const btVector3 p(btScalar(x), btScalar((row + 0.5) * kSize + (row + 1) * kGap), 0);
      s.spawn.push_back(posed(box, p));
      s.mass.push_back(1.0);
      s.rest_drop.push_back((row + 1) * kGap);
    }
  return s;
}

/// Four copies standing on the ground, apart: every contact is a non-convex body's
/// several feet on the box ground. The body is posed so the mesh keeps its frame.
Scene standing(const ShapeSet& mesh, const std::string& name) {
  Scene s{name, &mesh, {}, {}, {}, {0, 1, 2, 3}};
  double min_y = 1e9;
  for (const btVector3& v : mesh.vertices)
    min_y = std::min(min_y, double((mesh.mesh_from_shape * v).y()));
  for (int i = 0; i < 4; ++i) {
    const btVector3 p(btScalar(1.5 * kSize * (i % 2)), btScalar(kGap - min_y),
                      btScalar(kSize * (i / 2)));
    s.spawn.push_back(posed(mesh, p));
    s.mass.push_back(1.0);
    s.rest_drop.push_back(kGap);
  }
  return s;
}

/// 24 tori dropped in layers of four into the closed bowl (rim at y = 0), turned at
/// random: tests/bullet/pile_test.cpp's scene.
Scene pile(const ShapeSet& torus, const ShapeSet& bowl, const sc::samples::BowlInnerDepth& depth) {
  Scene s;
  s.name = "pile24";
  s.shapes = &torus;
  s.container = &bowl;
  s.container_depth = &depth;
  s.ground_top = -kBowlOuter - 0.05;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * sc::kPi);
  for (int i = 0; i < 24; ++i) {
    const int layer = i / 4, k = i % 4;
    const btVector3 at(btScalar(k % 2 ? 0.3 : -0.3), btScalar(-0.6 + 0.6 * layer),
                       btScalar(k / 2 ? 0.3 : -0.3));
    const double a = angle(rng), b = angle(rng), c = angle(rng);
    const btQuaternion q(btVector3(btScalar(std::cos(a)), 1.0f, btScalar(std::sin(b))).normalized(),
                         btScalar(c));
    s.spawn.push_back(posed(torus, at, q));
    s.mass.push_back(1.0);
  }
  return s;
}

void populate(World& w, const Scene& s) {
  if (s.container != nullptr) {
    const btTransform pose = s.container->mesh_from_shape;  // mesh frame at the origin
    w.addBody(s.container->staticShape(w.model), 0.0, btVector3(0, 0, 0), pose);
  }
  for (std::size_t i = 0; i < s.spawn.size(); ++i)
    w.addBody(s.shapes->dynamicShape(w.model), s.mass[i], s.mass[i] * s.shapes->unit_inertia,
              s.spawn[i]);
}

// ---------------------------------------------------------------- measurements

/// Depth of world point `p` inside the smooth torus whose mesh frame is `mesh_pose`
/// (<= 0 outside). The mesh is inscribed in it: over-reports by the facets' sagitta.
double torusDepth(const btTransform& mesh_pose, const btVector3& p) {
  const btVector3 q = mesh_pose.inverse() * p;
  return sc::samples::torusDepth(kTorusMajor, kTorusMinor,
                                 sc::Vec3(double(q.x()), double(q.y()), double(q.z())));
}

/// Depth of `p` in the bowl's shell (rim at y = 0, centre at the origin), on the
/// mesh's facets (up to 4 mm inside the sphere of radius kBowlInner).
double bowlDepth(const Scene& s, const btVector3& p) {
  const double d = (*s.container_depth)(sc::Vec3(double(p.x()), double(p.y()), double(p.z())));
  return std::max(0.0, d);
}

/// Deepest overlap in the world, by geometry: vertices below the ground's top; the
/// separating-axis depth between convex bodies; in the pile, vertices inside another
/// torus's tube or inside the bowl's shell. Non-convex bodies standing apart are not
/// measured against each other.
double maxOverlap(const World& w, const Scene& s) {
  const ShapeSet& set = *s.shapes;
  const std::size_t n = w.dynamic.size();
  double depth = 0.0;
  for (const btRigidBody* b : w.dynamic)
    for (const btVector3& v : set.vertices)
      depth = std::max(depth, s.ground_top - double((b->getWorldTransform() * v).y()));
  if (set.convex)
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) {
        const btTransform& a = w.dynamic[i]->getWorldTransform();
        const btTransform& b = w.dynamic[j]->getWorldTransform();
        if ((a.getOrigin() - b.getOrigin()).length() > 1.8 * kSize) continue;
        depth = std::max(depth, sc_bench::satDepth(set, a, b));
      }
  if (!s.pile()) return depth;
  const btTransform to_mesh = set.mesh_from_shape.inverse();
  for (std::size_t i = 0; i < n; ++i) {
    const btTransform& t = w.dynamic[i]->getWorldTransform();
    for (const btVector3& v : set.vertices) {
      const btVector3 p = t * v;
      depth = std::max(depth, bowlDepth(s, p));
      for (std::size_t j = 0; j < n; ++j) {
        const btTransform& o = w.dynamic[j]->getWorldTransform();
        if (j == i || (o.getOrigin() - t.getOrigin()).length() > 2 * (kTorusMajor + kTorusMinor))
          continue;
        depth = std::max(depth, torusDepth(o * to_mesh, p));
      }
    }
  }
  return depth;
}

double energy(const World& w) {
  double e = 0.0;
  for (const btRigidBody* b : w.dynamic) {
    const double m = 1.0 / double(b->getInvMass());
    const btVector3 omega = b->getAngularVelocity();
    const btVector3 l = b->getInvInertiaTensorWorld().inverse() * omega;
    e += 0.5 * m * double(b->getLinearVelocity().length2()) + 0.5 * double(omega.dot(l)) -
         kGravity * m * double(b->getCenterOfMassPosition().y());
  }
  return e;
}

double tilt(const btRigidBody* b, const btTransform& spawn) {
  // The rotation since spawn, applied to the vertical.
  const btVector3 up =
      b->getWorldTransform().getBasis() * (spawn.getBasis().transpose() * btVector3(0, 1, 0));
  return std::acos(std::clamp(double(up.y()), -1.0, 1.0));
}

struct Figures {
  std::vector<double> step_ms;                      ///< wall time of every step
  double cpu_s = 0.0;                               ///< thread CPU time of all steps
  double max_overlap = 0.0, settled_overlap = 0.0;  ///< whole run; last second
  double speed2 = 0.0;                              ///< squared speeds, last second
  long samples = 0;
  double max_spin = 0.0, energy0 = 0.0, energy_rise = 0.0;
  double drift = NAN;  ///< watched bodies' horizontal displacement plus drop [m]
  bool stands = true;  ///< piles: nothing escaped the bowl
};

void stepAndMeasure(World& w, const Scene& s, int i, int steps, Figures& f) {
  if (i == 0) f.energy0 = energy(w);
  const auto t0 = Clock::now();
  const double c0 = threadSeconds();
  w.step();
  f.cpu_s += threadSeconds() - c0;
  f.step_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  const int hz = int(std::lround(1.0 / w.dt));
  const bool last_second = i >= steps - hz;
  f.energy_rise = std::max(f.energy_rise, energy(w) - f.energy0);
  for (const btRigidBody* b : w.dynamic) {
    f.max_spin = std::max(f.max_spin, double(b->getAngularVelocity().length()));
    if (last_second) f.speed2 += double(b->getLinearVelocity().length2()), ++f.samples;
  }
  const int every = std::max(1, int(std::lround(hz / kChecksPerSecond)));
  if (i % every != every - 1 && i != steps - 1) return;
  const double o = maxOverlap(w, s);
  f.max_overlap = std::max(f.max_overlap, o);
  if (last_second) f.settled_overlap = std::max(f.settled_overlap, o);
}

/// Drift of the watched bodies (worst of them) and whether every body stayed up: for
/// stacks within a fifth of a body (horizontally) and 0.2 rad of its spawn; for a
/// pile, every centre still inside the bowl.
void finish(const World& w, const Scene& s, Figures& f) {
  for (const btRigidBody* b : w.dynamic) {
    const btVector3 c = b->getCenterOfMassPosition();
    if (!finite(c)) f.stands = false;
    if (s.pile() && (double(c.y()) < -kBowlInner || double(c.length()) > 3 * kBowlOuter))
      f.stands = false;
  }
  if (s.pile()) return;
  f.drift = 0.0;
  for (int i : s.top) {
    const btVector3 p = w.dynamic[std::size_t(i)]->getWorldTransform().getOrigin();
    const btVector3 p0 = s.spawn[std::size_t(i)].getOrigin();
    const double dx = double(p.x() - p0.x()), dz = double(p.z() - p0.z());
    const double drop = double(p0.y()) - s.rest_drop[std::size_t(i)] - double(p.y());
    f.drift = std::max(f.drift, std::hypot(dx, dz) + std::max(0.0, drop));
  }
  for (std::size_t i = 0; i < s.spawn.size(); ++i) {
    const btVector3 d = w.dynamic[i]->getWorldTransform().getOrigin() - s.spawn[i].getOrigin();
    if (std::hypot(double(d.x()), double(d.z())) > 0.2 * kSize ||
        tilt(w.dynamic[i], s.spawn[i]) > 0.2 || double(d.y()) < -0.5 * kSize)
      f.stands = false;
  }
}

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? NAN : s / double(v.size());
}

struct Options {
  std::string dir = ".";
  bool quick = false, sweep = true;
  std::vector<int> rates = {60, 120, 240};
  std::vector<std::string> scenes = {"tower10", "stack100", "pyramid15", "cow4", "pile24"};
  std::vector<std::string> models;  ///< empty: every model
  double seconds = 10.0;

  bool wants(Model m) const {
    return models.empty() ||
           std::find(models.begin(), models.end(), sc_bench::modelName(m)) != models.end();
  }
};

struct Row {
  std::string scene;
  int hz;
  Model model;
  double mean_ms;
};

/// Runs one scene at one rate with every model that applies, interleaved in blocks of
/// simulated time so that the load of the (shared) machine falls on all of them
/// alike; one printed line and one CSV row per model.
void runScene(const Scene& s, int hz, const Options& opt, FILE* csv, std::vector<Row>& rows) {
  const double seconds = opt.seconds;
  std::vector<std::unique_ptr<World>> worlds;
  std::vector<Model> models;
  for (Model m : kModels)
    if (s.applies(m) && opt.wants(m)) {
      models.push_back(m);
      worlds.push_back(std::make_unique<World>(m, 1.0 / hz, s.ground_top));
      populate(*worlds.back(), s);
    }
  std::vector<Figures> figs(worlds.size());
  const int steps = int(std::lround(seconds * hz));
  const int block = std::max(1, int(std::lround(kBlockSeconds * hz)));
  for (int start = 0; start < steps; start += block)
    for (std::size_t m = 0; m < worlds.size(); ++m)
      for (int i = start; i < std::min(steps, start + block); ++i)
        stepAndMeasure(*worlds[m], s, i, steps, figs[m]);
  for (std::size_t m = 0; m < worlds.size(); ++m) {
    Figures& f = figs[m];
    finish(*worlds[m], s, f);
    const double rest = std::sqrt(f.speed2 / double(std::max(1L, f.samples)));
    const double cpu_ms = 1e3 * f.cpu_s / double(std::max<std::size_t>(1, f.step_ms.size()));
    const char* verdict =
        f.stands ? (s.pile() ? "inside" : "stands") : (s.pile() ? "ESCAPED" : "FALLS");
    std::printf("%-9s %4d %-17s %8.3f %8.3f %8.3f %9.2f %9.2f %9.2f %9.2e %7.2f %9.3f %s\n",
                s.name.c_str(), hz, sc_bench::modelName(models[m]), mean(f.step_ms),
                sc::support::quantile(f.step_ms, 0.95), cpu_ms, 1e3 * f.drift, 1e3 * f.max_overlap,
                1e3 * f.settled_overlap, rest, f.max_spin, f.energy_rise, verdict);
    std::fprintf(csv, "%s,%d,%d,%s,%d,%d,%.5f,%.5f,%.5f,%.3f,%.3f,%.3f,%.4e,%.3f,%.4f,%d\n",
                 s.name.c_str(), s.id, hz, sc_bench::modelName(models[m]), int(models[m]), steps,
                 mean(f.step_ms), sc::support::quantile(f.step_ms, 0.95), cpu_ms, 1e3 * f.drift,
                 1e3 * f.max_overlap, 1e3 * f.settled_overlap, rest, f.max_spin, f.energy_rise,
                 f.stands ? 1 : 0);
    std::fflush(csv);
    rows.push_back({s.name, hz, models[m], mean(f.step_ms)});
  }
}

/// The speed target: the potential pile's step time no worse than the HACD
/// compound's, at every rate. Prints each comparison; false when one misses.
bool checkTargets(const std::vector<Row>& rows) {
  bool ok = true;
  for (const Row& p : rows) {
    if (p.scene != "pile24" || p.model != Model::Potential) continue;
    for (const Row& h : rows)
      if (h.scene == p.scene && h.hz == p.hz && h.model == Model::Hacd) {
        const bool met = p.mean_ms <= h.mean_ms;
        ok = ok && met;
        std::printf("target: pile24 %d Hz potential %.3f ms/step <= HACD compound %.3f: %s\n", p.hz,
                    p.mean_ms, h.mean_ms, met ? "met" : "MISSED");
      }
  }
  return ok;
}

// ---------------------------------------------------------------- stiffness sweep

/// How a potential-model tower ended: the first failure seen, or "stable".
struct SweepRun {
  const char* outcome = "stable";
  double drop = 0.0;       ///< top box below its resting height [m]
  double rms_speed = 0.0;  ///< over the last second [m/s]; NaN when stopped early
};

const char* towerFailure(const World& w, const Scene& s, double max_speed) {
  double below = 0.0;  // the ground's top
  for (std::size_t i = 0; i < w.dynamic.size(); ++i) {
    const btRigidBody* b = w.dynamic[i];
    const btVector3 p = b->getWorldTransform().getOrigin();
    if (!finite(p) || !finite(b->getLinearVelocity())) return "nan";
    if (max_speed > 10.0) return "blow_up";
    const btVector3 d = p - s.spawn[i].getOrigin();
    if (std::hypot(double(d.x()), double(d.z())) > 0.2 * kSize || tilt(b, s.spawn[i]) > 0.2)
      return "toppled";
    // A box more than half inside the one under it (or the ground) has sunk.
    if (double(p.y()) - below < (i == 0 ? 0.0 : 0.5 * kSize)) return "sank";
    below = double(p.y());
  }
  return nullptr;
}

/// The 10-box tower with the potential model at time step dt and kT = k, for
/// `seconds`; stable = standing, finite, and at rest (RMS speed < 0.05 m/s) at the end.
SweepRun sweepRun(const ShapeSet& box, double dt, double k, double seconds) {
  sc::bullet::ContactSettings contact;
  contact.contact_stiffness = k;
  World w(Model::Potential, dt, 0.0, contact);
  const Scene s = tower(box, 10, "tower10");
  populate(w, s);
  const int steps = int(std::lround(seconds / dt));
  const int last_second = std::max(1, int(std::lround(1.0 / dt)));
  SweepRun r;
  double speed2 = 0.0;
  for (int i = 0; i < steps; ++i) {
    w.step();
    double max_speed = 0.0;
    for (const btRigidBody* b : w.dynamic) {
      const double v2 = double(b->getLinearVelocity().length2());
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
  const btVector3 top = w.dynamic.back()->getWorldTransform().getOrigin();
  r.drop = double(s.spawn.back().getOrigin().y()) - s.rest_drop.back() - double(top.y());
  if (ran_out && r.rms_speed > 0.05) r.outcome = "restless";
  return r;
}

/// Stiffness range of one time step. "Stands" is standing, no NaN, no blow-up; "at
/// rest" also asks for an RMS speed under 0.05 m/s at the end.
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
  const double seconds = quick ? 2.0 : 5.0;
  const double step = quick ? 0.5 : 0.25;  // decades between stiffnesses
  for (int f : {60, 120, 240, 480, 960}) {
    const double dt = 1.0 / f;
    Limits l;
    for (double e = 1.0; e <= 8.0 + 1e-9; e += step) {
      const double k = std::pow(10.0, e);
      const SweepRun r = sweepRun(box, dt, k, seconds);
      l.add(k, r.outcome);
      std::fprintf(csv, "%d,%.6f,%.4e,%s,%.3f,%.4e\n", f, dt, k, r.outcome, 1e3 * r.drop,
                   r.rms_speed);
      std::fflush(csv);
    }
    std::printf(
        "%4d Hz: stands for kT %.3g..%.3g N/m, at rest for %.3g..%.3g; first failure "
        "above: %.3g (%s)\n",
        f, l.stand_lo, l.stand_hi, l.rest_lo, l.rest_hi, l.fail_above, l.failure.c_str());
    std::fprintf(limits, "%d,%.6f,%.4e,%.4e,%.4e,%.4e,%.4e,%s\n", f, dt, l.stand_lo, l.stand_hi,
                 l.rest_lo, l.rest_hi, l.fail_above, l.failure.c_str());
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
  mesh = sc::support::fitToSize(std::move(mesh), 1.0);
  for (sc::Vec3& v : mesh.vertices) v *= kSize;
  return mesh;
}

template <typename T>
std::vector<T> list(const char* text) {
  std::vector<T> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
    if constexpr (std::is_same_v<T, int>)
      out.push_back(std::atoi(item.c_str()));
    else
      out.push_back(item);
  return out;
}

Options parse(int argc, char** argv) {
  Options o;
  const char* env = std::getenv("SC_BENCH_QUICK");
  o.quick = env != nullptr && std::strcmp(env, "1") == 0;
  for (int i = 1; i < argc; ++i) {
    const char* a = argv[i];
    if (std::strncmp(a, "--csv-dir=", 10) == 0)
      o.dir = a + 10;
    else if (std::strcmp(a, "--quick") == 0)
      o.quick = true;
    else if (std::strcmp(a, "--no-sweep") == 0)
      o.sweep = false;
    else if (std::strncmp(a, "--hz=", 5) == 0)
      o.rates = list<int>(a + 5);
    else if (std::strncmp(a, "--scenes=", 9) == 0)
      o.scenes = list<std::string>(a + 9);
    else if (std::strncmp(a, "--models=", 9) == 0)
      o.models = list<std::string>(a + 9);
    else if (std::strncmp(a, "--seconds=", 10) == 0)
      o.seconds = std::atof(a + 10);
    else {
      std::fprintf(
          stderr,
          "usage: %s [--csv-dir=DIR] [--quick] [--no-sweep] [--hz=60,120,240]\n"
          "          [--scenes=tower10,stack100,pyramid15,cow4,pile24] [--seconds=10]\n"
          "          [--models=sc_potential,sc_manifold,bt_gimpact,bt_hacd_compound,bt_box]\n",
          argv[0]);
      std::exit(2);
    }
  }
  if (o.quick) o.seconds = std::min(o.seconds, 4.0);
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options opt = parse(argc, argv);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // progress shows in a redirected log
  const auto t0 = Clock::now();
  using sc_bench::Use;
  const auto box = sc_bench::makeShapeSet(boxMesh(0.5 * kSize), true, Use::Dynamic);
  const auto cow = sc_bench::makeShapeSet(loadMesh("cow"), false, Use::Dynamic);
  const auto torus = sc_bench::makeShapeSet(
      sc::samples::torusMesh(kTorusMajor, kTorusMinor, 32, 12), false, Use::Dynamic);
  const sc::MeshData bowl_mesh =
      sc::samples::bowlMesh(kBowlInner, kBowlOuter, kBowlRings, kBowlSegments);
  const auto bowl = sc_bench::makeShapeSet(bowl_mesh, false, Use::Static);
  const sc::samples::BowlInnerDepth bowl_depth(bowl_mesh, kBowlInner, kBowlOuter, kBowlRings,
                                               kBowlSegments);
  std::printf(
      "shapes: box %zu HACD part(s)%s, cow %zu triangles %zu parts, torus %zu "
      "triangles %zu parts%s; %.1f s\n",
      box->parts.size(), box->box ? " and a btBoxShape" : " (no btBoxShape)",
      cow->indices.size() / 3, cow->parts.size(), torus->indices.size() / 3, torus->parts.size(),
      SC_BENCH_HAVE_HACD ? "" : " (no HACD: one convex hull each)",
      std::chrono::duration<double>(Clock::now() - t0).count());

  std::vector<Scene> scenes;
  for (const std::string& name : opt.scenes) {
    if (name == "tower10")
      scenes.push_back(tower(*box, 10, name));
    else if (name == "stack100")
      scenes.push_back(tower(*box, 2, name, 100.0));
    else if (name == "pyramid15")
      scenes.push_back(pyramid(*box));
    else if (name == "cow4")
      scenes.push_back(standing(*cow, name));
    else if (name == "pile24")
      scenes.push_back(pile(*torus, *bowl, bowl_depth));
    else {
      std::fprintf(stderr, "bench: unknown scene %s\n", name.c_str());
      return 2;
    }
  }
  FILE* csv = openCsv(opt.dir, "bullet_stacking.csv",
                      "scene,scene_id,hz,model,model_id,steps,mean_ms,p95_ms,cpu_mean_ms,drift_mm,"
                      "max_overlap_mm,settled_overlap_mm,rest_rms_mps,max_spin_radps,"
                      "energy_rise_j,stands");
  std::printf("%-9s %4s %-17s %8s %8s %8s %9s %9s %9s %9s %7s %9s\n", "scene", "hz", "model",
              "mean_ms", "p95_ms", "cpu_ms", "drift_mm", "overlap", "settled", "rest_m/s", "spin",
              "energy_J");
  std::vector<Row> rows;
  for (std::size_t i = 0; i < scenes.size(); ++i) scenes[i].id = int(i);
  for (const Scene& s : scenes)
    for (int hz : opt.rates) runScene(s, hz, opt, csv, rows);
  std::fclose(csv);
  std::printf("scenes done: %.1f s\n", std::chrono::duration<double>(Clock::now() - t0).count());
  const bool targets_met = checkTargets(rows);

  if (opt.sweep) {
    FILE* sweep = openCsv(opt.dir, "potential_stiffness_vs_dt.csv",
                          "hz,dt_s,k_requested,outcome,top_drop_mm,rms_speed_mps");
    FILE* limits = openCsv(opt.dir, "potential_stiffness_limits.csv",
                           "hz,dt_s,smallest_standing_k,largest_standing_k,smallest_at_rest_k,"
                           "largest_at_rest_k,first_failure_above,failure");
    runSweep(*box, opt.quick, sweep, limits);
    std::fclose(sweep);
    std::fclose(limits);
  }
  std::printf("total: %.1f s\n", std::chrono::duration<double>(Clock::now() - t0).count());
  return targets_met ? 0 : 1;
}
