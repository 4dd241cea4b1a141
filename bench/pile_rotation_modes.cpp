// SPDX-License-Identifier: MIT
// A pile in every rotation mode: 24 CGAL knots (0.5 m, 6,400 triangles) dropped into a
// box of Bullet boxes, as the stacking demo's pile, at 60 Hz with the potential model,
// once in Input, Mix and Free, each in a fresh world. Per mode: thread CPU per step,
// the live heap the run added (glibc's mallinfo2: what the pairs keep, not what the
// allocator holds), the largest depth reported (StepStats::max_depth) and the last
// second's RMS speed. Targets: Mix and Free cost at most 4x Input's CPU per step (they
// run two trackers per non-convex pair, theirs and the Input one the rows come from)
// and keep at most 3x its heap (when a lagging proxy's turn gathered every leaf pair
// within its sweep: 8.6x and 7.2x the CPU, 17x and 15x the heap, 1.3-1.5 GB). Exits 1
// when one is missed.
// --seconds=S (default 6), --seed=N (the knots' turns, default 7).
#include <malloc.h>
#include <time.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "../demos/common/bullet_world.h"
#include "../demos/common/knot_pile.h"
#include "meshes.h"

namespace {

constexpr double kHz = 60.0;
constexpr int kKnots = 24;
constexpr double kCpuRatio = 4.0, kHeapRatio = 3.0;

double threadSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double liveHeapMb() {
  const struct mallinfo2 m = mallinfo2();
  return double(m.uordblks + m.hblkhd) / (1024.0 * 1024.0);
}

const char* modeName(sc::RotationMode m) {
  return m == sc::RotationMode::Input ? "input" : m == sc::RotationMode::Mix ? "mix" : "free";
}

struct Figures {
  double cpu_ms = 0.0;   ///< per step
  double heap_mb = 0.0;  ///< live heap added by the run
  double depth_mm = 0.0;
  double rest = 0.0;  ///< RMS speed over the last second [m/s]
};

/// The demo's pile (demos/common/knot_pile.h), in a fresh world.
Figures run(sc::RotationMode mode, const std::shared_ptr<sc::bullet::ScBulletShape>& knot,
            double seconds, unsigned seed) {
  const double heap_before = liveHeapMb();
  Figures f;
  {
    sc::demo::BulletWorld<> w;
    sc::bullet::PluginSettings settings;
    settings.query.rotation_mode = mode;
    w.makeSmartCollision(settings);
    w.world->setGravity(btVector3(0, -9.81f, 0));
    std::vector<std::unique_ptr<btCollisionShape>> walls;
    std::vector<std::unique_ptr<btRigidBody>> bodies;
    auto add = [&](btCollisionShape* shape, double mass, const btTransform& pose) {
      sc::demo::addBody(*w.world, bodies, shape, mass, pose);
    };
    for (const sc::demo::PileWall& wall : sc::demo::pileWalls()) {
      walls.push_back(std::make_unique<btBoxShape>(wall.half_extents));
      add(walls.back().get(), 0.0, btTransform(btQuaternion::getIdentity(), wall.center));
    }
    const std::size_t first_knot = bodies.size();
    for (const sc::demo::PileBodyPose& pose : sc::demo::pileBodyPoses(kKnots, seed))
      add(knot.get(), 1.0, btTransform(pose.rotation, pose.position));
    const int steps = static_cast<int>(seconds * kHz), last = static_cast<int>(kHz);
    double cpu = 0.0, speed2 = 0.0;
    for (int s = 0; s < steps; ++s) {
      const double t0 = threadSeconds();
      w.world->stepSimulation(btScalar(1.0 / kHz), 1, btScalar(1.0 / kHz));
      cpu += threadSeconds() - t0;
      f.depth_mm = std::max(f.depth_mm, 1e3 * w.plugin->stats().max_depth);
      if (s < steps - last) continue;
      for (std::size_t b = first_knot; b < bodies.size(); ++b)
        speed2 += double(bodies[b]->getLinearVelocity().length2()) / (kKnots * last);
    }
    f.cpu_ms = 1e3 * cpu / steps;
    f.rest = std::sqrt(speed2);
    f.heap_mb = liveHeapMb() - heap_before;
    for (auto& b : bodies) w.world->removeRigidBody(b.get());
  }
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 6.0;
  unsigned seed = 7;
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], "--seconds=", 10) == 0) {
      seconds = std::atof(argv[i] + 10);
    } else if (std::strncmp(argv[i], "--seed=", 7) == 0) {
      seed = static_cast<unsigned>(std::atoi(argv[i] + 7));
    } else {
      std::fprintf(stderr, "usage: %s [--seconds=S (6)] [--seed=N (7)]\n", argv[0]);
      return 2;
    }
  }
  sc::MeshData mesh = sc_bench::loadOff("knot1");
  if (mesh.triangles.empty()) return 1;
  auto knot = sc::bullet::ScBulletShape::create(sc::ModelKind::ClosedPolyhedron,
                                                sc::support::fitToSize(std::move(mesh), 0.5));
  if (!knot.ok()) {
    std::fprintf(stderr, "knot1: %s\n", knot.status().message().c_str());
    return 1;
  }
  std::printf("pile of %d knots, 60 Hz, potential model, %.1f s, seed %u\n", kKnots, seconds, seed);
  std::printf("%-6s %12s %14s %14s %14s\n", "mode", "cpu ms/step", "heap added MB", "max depth mm",
              "rest m/s");
  const sc::RotationMode modes[3] = {sc::RotationMode::Input, sc::RotationMode::Mix,
                                     sc::RotationMode::Free};
  Figures f[3];
  for (int m = 0; m < 3; ++m) {
    f[m] = run(modes[m], knot.value(), seconds, seed);
    std::printf("%-6s %12.2f %14.1f %14.2f %14.2e\n", modeName(modes[m]), f[m].cpu_ms, f[m].heap_mb,
                f[m].depth_mm, f[m].rest);
  }
  bool met = true;
  for (int m = 1; m < 3; ++m) {
    const bool cpu = f[m].cpu_ms <= kCpuRatio * f[0].cpu_ms;
    const bool heap = f[m].heap_mb <= kHeapRatio * std::max(f[0].heap_mb, 1.0);
    std::printf("target: %s CPU %.2fx Input's (<= %.0fx): %s; heap %.2fx (<= %.0fx): %s\n",
                modeName(modes[m]), f[m].cpu_ms / f[0].cpu_ms, kCpuRatio, cpu ? "met" : "MISSED",
                f[m].heap_mb / std::max(f[0].heap_mb, 1.0), kHeapRatio, heap ? "met" : "MISSED");
    met = met && cpu && heap;
  }
  return met ? 0 : 1;
}
