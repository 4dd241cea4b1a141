// SPDX-License-Identifier: MIT
// UpdateStatus time against the number of groups: 10 to 10,000 small convex
// objects plus a few non-convex ones at constant density, each a group on a random
// walk; AABB-tree broadphase against brute-force enumeration. Writes a CSV for
// bench/plot_scene_scaling.gp with --csv=<file>.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "harness.h"
#include "sc_support/csv.h"
#include "sc_support/stats.h"
#include "smartcollision/smartcollision.h"

namespace {

using sc::Vec3;
using sc::support::randomRotation;

constexpr double kDensity = 0.05;        // groups per unit volume (objects are ~0.7 across)
constexpr double kSparseDensity = 0.002;  // hardly any close pair: the broadphase alone
constexpr double kMaxDistance = 0.5;  // model units
constexpr int kNonConvexGroups = 3;
constexpr int kStaticObstacles = 2;
constexpr int kWarmupFrames = 20;

sc::MeshData boxMesh(const Vec3& h) {
  sc::MeshData m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
  m.triangles = {sc::Tri(0, 2, 3), sc::Tri(0, 3, 1), sc::Tri(4, 5, 7), sc::Tri(4, 7, 6),
                 sc::Tri(0, 1, 5), sc::Tri(0, 5, 4), sc::Tri(2, 6, 7), sc::Tri(2, 7, 3),
                 sc::Tri(0, 4, 6), sc::Tri(0, 6, 2), sc::Tri(1, 3, 7), sc::Tri(1, 7, 5)};
  return m;
}

/// An L-shaped prism of about `size`: closed, non-convex (two convex patches).
sc::MeshData lPrismMesh(double size) {
  const double s = 0.5 * size, hz = 0.25 * size;
  const double xy[6][2] = {{-s, -s}, {s, -s}, {s, 0}, {0, 0}, {0, s}, {-s, s}};
  sc::MeshData m;
  for (const auto& p : xy) m.vertices.emplace_back(p[0], p[1], -hz);
  for (const auto& p : xy) m.vertices.emplace_back(p[0], p[1], hz);
  for (int i = 1; i + 1 < 6; ++i) {
    m.triangles.emplace_back(0, i + 1, i);
    m.triangles.emplace_back(6, 6 + i, 7 + i);
  }
  for (int i = 0; i < 6; ++i) {
    const int j = (i + 1) % 6;
    m.triangles.emplace_back(i, j, 6 + j);
    m.triangles.emplace_back(i, 6 + j, 6 + i);
  }
  return m;
}

sc::ModelPtr modelOf(const sc::MeshData& mesh) {
  auto piece = sc::buildPiece(sc::ModelKind::ClosedPolyhedron, mesh);
  if (!piece.hasValue()) {
    std::fprintf(stderr, "bench mesh rejected: %s\n", piece.status().message().c_str());
    std::abort();
  }
  return std::make_shared<const sc::Model>(sc::ModelKind::ClosedPolyhedron,
                                           std::vector<sc::PiecePtr>{piece.value()});
}

/// The models, built once and shared by every scene.
struct Library {
  std::vector<sc::ModelPtr> convex;
  sc::ModelPtr non_convex;
  sc::ModelPtr obstacle;
  Library() {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> half(0.15, 0.4);
    for (int i = 0; i < 8; ++i)
      convex.push_back(modelOf(boxMesh(sc::support::randomVec3(half, rng))));
    non_convex = modelOf(lPrismMesh(1.2));
    obstacle = modelOf(lPrismMesh(2.0));
  }
};

const Library& library() {
  static const Library lib;
  return lib;
}

/// n groups of one object each on a random walk in a cube sized for kDensity.
class World {
 public:
  World(int n, double density, sc::Broadphase broadphase, int threads)
      : scene_(sc::ModelKind::ClosedPolyhedron), rng_(1234 + static_cast<unsigned>(n)),
        half_(0.5 * std::cbrt(n / density)) {
    sc::SceneSettings s;
    s.max_distance = kMaxDistance;
    s.broadphase = broadphase;
    s.threads = threads;
    check(scene_.setSettings(s));
    const Library& lib = library();
    for (int i = 0; i < n; ++i) {
      const sc::ModelPtr& model = i < kNonConvexGroups ? lib.non_convex : lib.convex[rng_() % lib.convex.size()];
      check(scene_.addObject(i, model, randomPlacement()));
      check(scene_.addObjectToGroup(i, i));
      placements_.push_back(scene_.groupPlacement(i).value());
    }
    for (int k = 0; k < kStaticObstacles; ++k) check(scene_.addObject(n + k, lib.obstacle, randomPlacement()));
  }

  /// Moves every group one random-walk step (reflected at the walls).
  void step() {
    std::normal_distribution<double> n(0.0, 1.0);
    for (size_t g = 0; g < placements_.size(); ++g) {
      sc::Placement& p = placements_[g];
      const Vec3 d = 0.04 * Vec3(n(rng_), n(rng_), n(rng_));
      p.world_center += d;
      for (int a = 0; a < 3; ++a) {
        if (std::abs(p.world_center[a]) > half_) p.world_center[a] -= 2.0 * d[a];
      }
      const sc::Quat turn(Eigen::AngleAxisd(0.03, Vec3(n(rng_), n(rng_), n(rng_)).normalized()));
      p.orientation = (turn * p.orientation).normalized();
      check(scene_.setGroupPlacement(static_cast<int>(g), p));
    }
  }

  /// One UpdateStatus; returns its wall time and the CPU time of the process (all
  /// threads) in seconds. CPU time is the cost, robust to other load on the machine.
  std::pair<double, double> update() {
    const std::clock_t c0 = std::clock();
    const auto t0 = std::chrono::steady_clock::now();
    check(scene_.update());
    const auto t1 = std::chrono::steady_clock::now();
    const std::clock_t c1 = std::clock();
    return {std::chrono::duration<double>(t1 - t0).count(),
            static_cast<double>(c1 - c0) / CLOCKS_PER_SEC};
  }

  size_t pairs() const { return scene_.pairs().size(); }

 private:
  sc::Placement randomPlacement() {
    std::uniform_real_distribution<double> u(-half_, half_);
    sc::Placement p;
    p.world_center = Vec3(u(rng_), u(rng_), u(rng_));
    p.orientation = randomRotation(rng_);
    return p;
  }

  static void check(const sc::Status& s) {
    if (!s.ok()) {
      std::fprintf(stderr, "bench: %s\n", s.message().c_str());
      std::abort();
    }
  }

  sc::Scene scene_;
  std::mt19937_64 rng_;
  double half_;
  std::vector<sc::Placement> placements_;
};

struct Row {
  double ms_per_update = 0.0;      ///< wall clock
  double cpu_ms_per_update = 0.0;  ///< summed over threads
  double pairs_per_update = 0.0;
  long frames = 0;
};
/// (scene, broadphase, threads, groups) -> the last (final) run of that benchmark.
std::map<std::tuple<std::string, std::string, int, int>, Row> g_rows;

void runScene(benchmark::State& state, sc::Broadphase broadphase, bool sparse) {
  const int n = static_cast<int>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  World world(n, sparse ? kSparseDensity : kDensity, broadphase, threads);
  for (int f = 0; f < kWarmupFrames; ++f) {
    world.step();
    world.update();
  }
  double seconds = 0.0, cpu_seconds = 0.0, pairs = 0.0;
  long frames = 0;
  for (auto _ : state) {
    world.step();
    const auto [wall, cpu] = world.update();
    state.SetIterationTime(wall);
    seconds += wall;
    cpu_seconds += cpu;
    pairs += static_cast<double>(world.pairs());
    ++frames;
  }
  const double per_frame = 1.0 / static_cast<double>(frames);
  state.counters["groups"] = n;
  state.counters["pairs"] = pairs * per_frame;
  state.counters["cpu_ms"] = 1e3 * cpu_seconds * per_frame;
  state.counters["cpu_us_per_group"] = 1e6 * cpu_seconds * per_frame / n;
  const std::string name = broadphase == sc::Broadphase::Tree ? "tree" : "brute_force";
  g_rows[{sparse ? "sparse" : "dense", name, threads, n}] =
      Row{1e3 * seconds * per_frame, 1e3 * cpu_seconds * per_frame, pairs * per_frame, frames};
}

void BM_UpdateStatusTree(benchmark::State& state) { runScene(state, sc::Broadphase::Tree, false); }
void BM_UpdateStatusBruteForce(benchmark::State& state) {
  runScene(state, sc::Broadphase::BruteForce, false);
}
void BM_SparseTree(benchmark::State& state) { runScene(state, sc::Broadphase::Tree, true); }
void BM_SparseBruteForce(benchmark::State& state) { runScene(state, sc::Broadphase::BruteForce, true); }

// Serial runs give the algorithmic scaling; two threads are shown where it matters.
BENCHMARK(BM_UpdateStatusTree)
    ->ArgsProduct({{10, 30, 100, 300, 1000, 3000, 10000}, {1}})
    ->Args({1000, 2})
    ->Args({10000, 2})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK(BM_UpdateStatusBruteForce)
    ->ArgsProduct({{10, 30, 100, 300, 1000, 3000, 10000}, {1}})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
// Sparse scenes: the cost of finding the pairs, with almost none to compute.
BENCHMARK(BM_SparseTree)
    ->ArgsProduct({{1000, 10000}, {1}})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);
BENCHMARK(BM_SparseBruteForce)->Args({1000, 1})->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(1.0);

void writeCsv(const std::string& path) {
  sc::support::CsvFile f(
      path, "scene,broadphase,threads,groups,wall_ms,cpu_ms,pairs,cpu_us_per_group,frames");
  if (!f.ok()) return;
  for (const auto& [key, row] : g_rows) {
    const auto& [scene, name, threads, n] = key;
    f.row("%s,%s,%d,%d,%.4f,%.4f,%.1f,%.3f,%ld", scene.c_str(), name.c_str(), threads, n,
          row.ms_per_update, row.cpu_ms_per_update, row.pairs_per_update,
          1e3 * row.cpu_ms_per_update / n, row.frames);
  }
  for (const char* scene : {"dense", "sparse"}) {
    const auto tree = g_rows.find({scene, "tree", 1, 1000});
    const auto brute = g_rows.find({scene, "brute_force", 1, 1000});
    if (tree == g_rows.end() || brute == g_rows.end()) continue;
    std::printf("%s, 1000 groups, serial: tree %.3f ms (cpu %.3f), brute force %.3f ms (cpu %.3f), "
                "ratio %.2f (cpu %.2f)\n",
                scene, tree->second.ms_per_update, tree->second.cpu_ms_per_update,
                brute->second.ms_per_update, brute->second.cpu_ms_per_update,
                brute->second.ms_per_update / tree->second.ms_per_update,
                brute->second.cpu_ms_per_update / tree->second.cpu_ms_per_update);
  }
}

}  // namespace

int main(int argc, char** argv) {  // --csv=<file> is ours; the rest is Google Benchmark's
  return sc_bench::benchmarkMain(argc, argv, "--csv=", writeCsv);
}
