// SPDX-License-Identifier: MIT
// Many knots dropped on the ground at 60 Hz: a pile of CGAL knots (knot1, 6,400
// triangles, laid flat) in layers of 5 x 5, on an ScBulletShape ground box, with the
// potential model and StackingSolver, as an application drops them. Per run: wall and
// thread-CPU time per step (median, p95, max), peak RSS, the pile's outcome (the top
// knot's horizontal drift, the last second's RMS speed, the deepest depth the plugin
// reported) and the plugin's pair figures of the last step.
// --count=N (100), --size=M (0.3), --seconds=S (10), --seed=N (0: unturned, else a
// small random turn per knot), --callgrind-from=S: under valgrind --tool=callgrind
// --collect-atstart=no, collect from simulated second S on.
#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include "../demos/common/bullet_world.h"
#include "meshes.h"
#include "sc_support/off_mesh.h"

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define SC_HAVE_CALLGRIND 1
#endif

namespace {

constexpr double kHz = 60.0;

struct Options {
  int count = 100;
  double size = 0.3;
  double seconds = 10.0;
  unsigned seed = 0;
  double callgrind_from = -1.0;
};

double threadMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * double(ts.tv_sec) + 1e-6 * double(ts.tv_nsec);
}

double wallMs() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

double peakRssMb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;
}

/// Value at fraction `q` of the sorted samples (nearest rank).
double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const auto i = static_cast<std::size_t>(q * double(v.size() - 1) + 0.5);
  return v[std::min(i, v.size() - 1)];
}

/// Knot1 with its thin axis (z) turned to y, so that it lies flat.
sc::MeshData flatKnot(double size) {
  sc::MeshData mesh = sc_bench::loadOff("knot1");
  if (mesh.triangles.empty()) std::exit(1);
  for (sc::Vec3& v : mesh.vertices) v = sc::Vec3(v.x(), v.z(), -v.y());
  return sc::support::fitToSize(std::move(mesh), size);
}

/// Knot i's start: layers of 5 x 5, (size + 0.1) apart across and half that plus 0.1
/// up; seed 0 leaves them unturned, else each turns about a random near-vertical axis
/// (tilted at most 6 degrees, so that the layers stay clear of each other).
btTransform startPose(int i, const Options& o, unsigned& lcg) {
  auto next = [&lcg] { return (lcg = lcg * 1103515245u + 12345u) / 4294967296.0; };
  const int layer = i / 25, j = (i / 5) % 5, l = i % 5;
  const btVector3 p(btScalar((j - 2) * (o.size + 0.1)),
                    btScalar(0.2 * o.size + 0.05 + layer * (0.5 * o.size + 0.1)),
                    btScalar((l - 2) * (o.size + 0.1)));
  btQuaternion q = btQuaternion::getIdentity();
  if (o.seed != 0) {
    const double angle = 6.283 * next(), x = 0.2 * (next() - 0.5), z = 0.2 * (next() - 0.5);
    q = btQuaternion(btVector3(btScalar(x), 1, btScalar(z)).normalized(), btScalar(angle));
  }
  return btTransform(q, p);
}

/// A box of half extents `h` (a ground 40 m across, 2 m thick).
sc::MeshData boxMesh(const btVector3& h) {
  sc::MeshData m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                            (i & 4) ? h.z() : -h.z());
  const int f[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                        {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  for (const auto& t : f) m.triangles.emplace_back(t[0], t[1], t[2]);
  return m;
}

bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const char* a = argv[i];
    if (std::strncmp(a, "--count=", 8) == 0) {
      o.count = std::atoi(a + 8);
    } else if (std::strncmp(a, "--size=", 7) == 0) {
      o.size = std::atof(a + 7);
    } else if (std::strncmp(a, "--seconds=", 10) == 0) {
      o.seconds = std::atof(a + 10);
    } else if (std::strncmp(a, "--seed=", 7) == 0) {
      o.seed = static_cast<unsigned>(std::atoi(a + 7));
    } else if (std::strncmp(a, "--callgrind-from=", 17) == 0) {
      o.callgrind_from = std::atof(a + 17);
    } else {
      return false;
    }
  }
  return o.count > 0 && o.size > 0.0 && o.seconds > 0.0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (!parse(argc, argv, o)) {
    std::fprintf(stderr,
                 "usage: %s [--count=N (100)] [--size=M (0.3)] [--seconds=S (10)] [--seed=N (0)]"
                 " [--callgrind-from=S]\n",
                 argv[0]);
    return 2;
  }
  auto knot = sc::bullet::ScBulletShape::create(sc::ModelKind::ClosedPolyhedron, flatKnot(o.size));
  if (!knot.ok()) {
    std::fprintf(stderr, "knot1: %s\n", knot.status().message().c_str());
    return 1;
  }
  auto ground = sc::bullet::ScBulletShape::create(sc::ModelKind::ClosedPolyhedron,
                                                  boxMesh(btVector3(20, 1, 20)));
  if (!ground.ok()) return 1;

  sc::demo::BulletWorld<> w;
  w.makeSmartCollision(sc::bullet::PluginSettings{},
                       std::make_unique<sc::bullet::StackingSolver>());
  w.world->setGravity(btVector3(0, -9.81f, 0));
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  sc::demo::addBody(*w.world, bodies, ground.value().get(), 0.0,
                    btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0)));
  unsigned lcg = o.seed;
  std::vector<btVector3> spawn;
  for (int i = 0; i < o.count; ++i) {
    const btTransform pose = startPose(i, o, lcg);
    sc::demo::addBody(*w.world, bodies, knot.value().get(), 1.0, pose);
    spawn.push_back(pose.getOrigin());
  }

  const int steps = static_cast<int>(o.seconds * kHz), last = static_cast<int>(kHz);
  const int collect_from = o.callgrind_from >= 0.0 ? static_cast<int>(o.callgrind_from * kHz) : -1;
  std::vector<double> wall, cpu;
  double depth_mm = 0.0, speed2 = 0.0;
  for (int s = 0; s < steps; ++s) {
#ifdef SC_HAVE_CALLGRIND
    if (s == collect_from) CALLGRIND_START_INSTRUMENTATION;
    if (s == collect_from) CALLGRIND_TOGGLE_COLLECT;
#endif
    const double w0 = wallMs(), c0 = threadMs();
    w.world->stepSimulation(btScalar(1.0 / kHz), 1, btScalar(1.0 / kHz));
    cpu.push_back(threadMs() - c0);
    wall.push_back(wallMs() - w0);
    depth_mm = std::max(depth_mm, 1e3 * w.plugin->stats().max_depth);
    if (s < steps - last) continue;
    for (int b = 1; b <= o.count; ++b)
      speed2 += double(bodies[std::size_t(b)]->getLinearVelocity().length2()) / (o.count * last);
  }
  const btVector3 top = bodies.back()->getWorldTransform().getOrigin() - spawn.back();
  const double drift_mm = 1e3 * std::hypot(double(top.x()), double(top.z()));
  const sc::bullet::StepStats st = w.plugin->stats();
  std::printf("knots_on_ground: %d knots of %.2f m, 60 Hz, %.1f s, seed %u\n", o.count, o.size,
              o.seconds, o.seed);
  std::printf("wall ms/step   median %.2f p95 %.2f max %.1f\n", quantile(wall, 0.5),
              quantile(wall, 0.95), quantile(wall, 1.0));
  std::printf("thread ms/step median %.2f p95 %.2f max %.1f\n", quantile(cpu, 0.5),
              quantile(cpu, 0.95), quantile(cpu, 1.0));
  std::printf("peak RSS %.0f MB\n", peakRssMb());
  std::printf("top drift %.2f mm, last-second RMS speed %.2e m/s, max depth %.3f mm\n", drift_mm,
              std::sqrt(speed2), depth_mm);
  std::printf("last step: pairs %d skipped %d reused %d penetrating %d rows %d projected %d\n",
              st.pairs, st.skipped, st.reused, st.penetrating, st.rows, st.projected);
  for (auto& b : bodies) w.world->removeRigidBody(b.get());
  return 0;
}
