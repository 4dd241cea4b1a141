// SPDX-License-Identifier: MIT
// The C++ half of bench/python_overhead.py, a shared library the script loads with
// ctypes: the same queries as the Python half (two boxes, the same pose cycles),
// timed through sc::PairTracker directly, in the same process, so that the two
// halves can alternate in short rounds.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "smartcollision/smartcollision.h"

namespace {

constexpr int kPoses = 64;

sc::ModelPtr boxModel(double hx, double hy, double hz) {
  sc::MeshData m;
  for (double x : {-hx, hx})
    for (double y : {-hy, hy})
      for (double z : {-hz, hz}) m.vertices.emplace_back(x, y, z);
  const int f[12][3] = {{0, 1, 3}, {0, 3, 2}, {4, 6, 7}, {4, 7, 5}, {0, 4, 5}, {0, 5, 1},
                        {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3}};
  for (const auto& t : f) m.triangles.emplace_back(t[0], t[1], t[2]);
  auto piece = sc::buildPiece(sc::ModelKind::ClosedPolyhedron, m);
  if (!piece.ok()) std::exit(1);
  return std::make_shared<const sc::Model>(sc::ModelKind::ClosedPolyhedron,
                                           std::vector<sc::PiecePtr>{piece.value()});
}

/// Pose k of a cycle, as the Python half builds it: position and quaternion w, x, y, z.
sc::Placement pose(int k, double height) {
  const double a = 2.0 * M_PI * k / kPoses;
  sc::Placement p;
  p.setOrientation(sc::Quat(1.0, 0.0, 0.0, 0.02 * std::sin(a)));
  p.setOrigin(sc::Vec3(0.1 * std::cos(a), 0.1 * std::sin(a), height + 0.02 * std::sin(a)));
  return p;
}

/// One pair followed along a cycle, as the Python half's tracker is.
struct Scenario {
  explicit Scenario(double height) : a(boxModel(1, 1, 1)), b(boxModel(2, 0.5, 0.5)) {
    for (int k = 0; k < kPoses; ++k) poses.push_back(pose(k, height));
    // Seen apart first, so a penetrating cycle is tracked.
    run(pose(0, 3.0));
  }
  void run(const sc::Placement& p) {
    const sc::Part pa{a.get(), sc::Rigid(), 0}, pb{b.get(), sc::Rigid(), 1};
    tracker.update({&pa, 1, p}, {&pb, 1, sc::Placement()}, {true, false}, settings, out);
  }
  sc::ModelPtr a, b;
  std::vector<sc::Placement> poses;
  sc::PairTracker tracker;
  sc::SceneSettings settings;
  sc::DirectedResult out[2];
};

}  // namespace

/// Nanoseconds per query over `calls` queries of the apart (0) or penetrating (1)
/// cycle; the tracker carries on from the previous call.
extern "C" double sc_bench_cpp_ns(int penetrating, long calls) {
  static Scenario apart(3.0), pressed(1.4);
  Scenario& s = penetrating ? pressed : apart;
  double sink = 0.0;
  const auto start = std::chrono::steady_clock::now();
  for (long i = 0; i < calls; ++i) {
    s.run(s.poses[static_cast<size_t>(i % kPoses)]);
    sink += s.out[0].distance;
  }
  const std::chrono::duration<double, std::nano> ns = std::chrono::steady_clock::now() - start;
  if (sink == 0.123456789) std::puts("");  // keeps the loop
  return ns.count() / static_cast<double>(calls);
}
