// SPDX-License-Identifier: MIT
// The C++ half of bench/python_overhead.py: the same queries as the Python half
// (two boxes, the same pose cycles), timed through sc::PairTracker directly.
// Prints "name nanoseconds_per_call" lines.
// Usage: python_overhead [CALLS]
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

double nsPerCall(const std::vector<sc::Placement>& poses, long calls) {
  const sc::ModelPtr a = boxModel(1, 1, 1), b = boxModel(2, 0.5, 0.5);
  const sc::Part pa{a.get(), sc::Rigid(), 0}, pb{b.get(), sc::Rigid(), 1};
  sc::PairTracker tracker;
  sc::SceneSettings settings;
  sc::DirectedResult out[2];
  const sc::GroupView gb{&pb, 1, sc::Placement()};
  // Seen apart first, so a penetrating cycle is tracked.
  tracker.update({&pa, 1, pose(0, 3.0)}, gb, {true, false}, settings, out);
  double sink = 0.0;
  const auto run = [&](long n) {
    for (long i = 0; i < n; ++i) {
      tracker.update({&pa, 1, poses[static_cast<size_t>(i % kPoses)]}, gb, {true, false}, settings,
                     out);
      sink += out[0].distance;
    }
  };
  run(calls / 10);
  const auto start = std::chrono::steady_clock::now();
  run(calls);
  const std::chrono::duration<double, std::nano> ns = std::chrono::steady_clock::now() - start;
  if (sink == 0.123456789) std::puts("");  // keeps the loop
  return ns.count() / static_cast<double>(calls);
}

}  // namespace

int main(int argc, char** argv) {
  const long calls = argc > 1 ? std::atol(argv[1]) : 200000;
  std::vector<sc::Placement> apart, pressed;
  for (int k = 0; k < kPoses; ++k) {
    apart.push_back(pose(k, 3.0));
    pressed.push_back(pose(k, 1.4));
  }
  std::printf("apart %.1f\n", nsPerCall(apart, calls));
  std::printf("penetrating %.1f\n", nsPerCall(pressed, calls));
}
