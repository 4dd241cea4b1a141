// SPDX-License-Identifier: MIT
// Dynamic penetration depth (issue 4): update time of two >= 10k-triangle models under
// haptic-like motion, speed against accuracy on convex pairs next to libccd's EPA
// and MPR and Bullet's GJK-EPA, and the global depth of convex pairs first seen
// intersecting against the same peers (issue 19). Writes CSVs with --csv-dir=<dir>.
#include <benchmark/benchmark.h>

#include <time.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define SC_HAVE_CALLGRIND 1
#endif

#include "harness.h"
#include "meshes.h"
#include "pair_queries.h"
#include "sc_support/csv.h"
#include "sc_support/stats.h"
#include "smartcollision/smartcollision.h"

#if SC_BENCH_HAVE_CCD
#include "ccd_problem.h"
#endif
#if SC_BENCH_HAVE_BULLET
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>
#endif

namespace {

using sc::Quat;
using sc::Vec3;
using sc::support::quantile;
using sc::support::randomDirection;
using sc::support::randomRotation;
using sc_bench::Clock;

using sc_bench::closedModel;
using sc_bench::updateOneWay;

// ---------------------------------------------------------------------------------
// Haptic-like motion between two large meshes.

constexpr int kHapticSteps = 2000;
const char* const kHapticPairs[][2] = {{"fandisk", "armadillo"}, {"fandisk", "bunny00"}};

struct HapticRow {
  std::string pair, mode;
  int steps = 0, penetrating = 0, not_ok = 0;
  double median_us = 0, p99_us = 0, max_us = 0, cpu_median_us = 0, cpu_p99_us = 0, cpu_max_us = 0;
  double max_step = 0, delta_max = 0, max_tpdv = 0, max_tpdv_jump = 0;
  /// |dTPDV| over the step's largest point motion: the worst, the step it is at, and
  /// the steps over 3x (issue 19.4 asks for at most 3x, or the exceptions explained).
  double max_jump_ratio = 0;
  int jump_ratio_step = -1, jumps_over_3x = 0;
};
std::vector<HapticRow> g_haptic;
/// --callgrind-updates: under `valgrind --tool=callgrind --collect-atstart=no`, each
/// update along a haptic path is collected alone and dumped after (OUT.1, OUT.2, ...;
/// bench/callgrind_updates.py reads them).
bool g_callgrind_updates = false;
/// Per step of the first pair in INPUT mode: step, wall us, cpu us, |tpdv|.
std::vector<std::array<double, 4>> g_haptic_steps;

struct LoadedMesh {
  sc::MeshData mesh;
  sc::ModelPtr model;
  double radius = 0.0;
};

const LoadedMesh* loadMesh(const std::string& name) {
  static std::map<std::string, std::unique_ptr<LoadedMesh>> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second.get();
  std::unique_ptr<LoadedMesh> l;
  sc::MeshData raw = sc_bench::loadOff(name);
  if (!raw.triangles.empty()) {
    l = std::make_unique<LoadedMesh>();
    l->mesh = sc::support::fitToSize(std::move(raw), 1.0);
    l->model = closedModel(l->mesh);
    for (const Vec3& v : l->mesh.vertices) l->radius = std::max(l->radius, v.norm());
    if (!l->model) l.reset();
  }
  return (cache[name] = std::move(l)).get();
}

/// The target approaches the fixed opponent from 0.02 away, penetrates 0.015 to 0.045
/// deep along the approach (unit-size models) while it circles sideways and rocks,
/// and withdraws at the end.
std::vector<sc::Placement> hapticPath(double radius_a, double radius_b, const sc::Part& part_a,
                                      const sc::Part& part_b, const sc::SceneSettings& settings,
                                      unsigned seed) {
  std::mt19937_64 rng(seed);
  const Quat q0 = randomRotation(rng);
  const Vec3 u = randomDirection(rng);
  const Vec3 e1 = u.unitOrthogonal(), e2 = u.cross(e1);
  const Vec3 body_axis = randomDirection(rng);
  const auto placementAt = [&](double s, const Vec3& lateral, const Quat& q) {
    sc::Placement p;
    p.orientation = q;
    p.world_center = s * u + lateral;
    return p;
  };
  // Touching offset along u: slide in from far by the distance (1-Lipschitz, so a
  // step of d - gap never reaches contact).
  double s_touch = radius_a + radius_b;
  for (int k = 0; k < 40; ++k) {
    sc::PairTracker probe;
    const sc::DirectedResult r = updateOneWay(probe, part_a, placementAt(s_touch, Vec3::Zero(), q0),
                                              part_b, sc::Placement(), settings);
    if (r.code != sc::ErrorCode::Ok || r.distance < 2e-5) break;
    s_touch -= r.distance - 1e-5;
  }
  std::vector<sc::Placement> path;
  double depth_end = 0.0;
  for (int k = 0; k < kHapticSteps; ++k) {
    const double phase = static_cast<double>(k - 100);
    double depth = 0.03 + 0.015 * std::sin(2.0 * M_PI * phase / 300.0);
    if (k < 100) depth = -0.02 + 0.05 * k / 100.0;
    if (k == kHapticSteps - 100) depth_end = depth;
    if (k >= kHapticSteps - 100)
      depth = depth_end - (depth_end + 0.02) * (k - (kHapticSteps - 100)) / 99.0;
    const double angle = 2.0 * M_PI * std::max(0.0, phase) / 500.0;
    const Vec3 lateral = 0.03 * ((std::cos(angle) - 1.0) * e1 + std::sin(angle) * e2);
    const Quat q = Quat(Eigen::AngleAxisd(0.05 * std::sin(2.0 * M_PI * k / 700.0), body_axis)) * q0;
    path.push_back(placementAt(s_touch - depth, lateral, q));
  }
  return path;
}

/// Update time along the haptic path of a pair. Every step moves a point of the target
/// by about 1e-3: a hand at 0.1 m/s on a 10 cm tool in a 1 kHz loop, an order below
/// delta_max of the defaults.
void BM_HapticPath(benchmark::State& state) {
  const int index = static_cast<int>(state.range(0));
  const auto mode = static_cast<sc::RotationMode>(state.range(1));
  const LoadedMesh* la = loadMesh(kHapticPairs[index][0]);
  const LoadedMesh* lb = loadMesh(kHapticPairs[index][1]);
  if (!la || !lb) {
    state.SkipWithError("meshes not found");
    return;
  }
  const sc::Part part_a{la->model.get(), sc::Rigid(), 0}, part_b{lb->model.get(), sc::Rigid(), 1};
  sc::SceneSettings settings;
  settings.rotation_mode = mode;
  const sc::Placement opponent;
  const double travel_ratio = static_cast<double>(state.range(2));
  // A seed whose path intersects at most probes of its penetrating part (a contact
  // on a thin feature, an ear, would be left by the sideways motion).
  std::vector<sc::Placement> path;
  for (unsigned attempt = 0; attempt < 8; ++attempt) {
    path = hapticPath(la->radius, lb->radius, part_a, part_b, settings,
                      77 + 10 * static_cast<unsigned>(index) + attempt);
    int intersecting = 0;
    for (int k = 150; k < kHapticSteps - 100; k += 200) {
      sc::PairTracker probe;
      const sc::DirectedResult r =
          updateOneWay(probe, part_a, path[k], part_b, sc::Placement(), settings);
      if (r.code == sc::ErrorCode::InvalidInitialTransformation || r.penetrating()) ++intersecting;
    }
    if (intersecting >= 8) break;
  }
  double max_step = 0.0;
  std::vector<double> step_motion(path.size(), 0.0);  // largest point motion into step k
  for (size_t k = 1; k < path.size(); ++k) {
    for (const Vec3& v : la->mesh.vertices) {
      const Vec3 before = path[k - 1].worldFromLocal() * v, after = path[k].worldFromLocal() * v;
      step_motion[k] = std::max(step_motion[k], (after - before).norm());
    }
    max_step = std::max(max_step, step_motion[k]);
  }

  HapticRow row;
  row.pair = std::string(kHapticPairs[index][0]) + "-" + kHapticPairs[index][1];
  const char* const mode_names[] = {"none", "input", "free", "mix"};
  row.mode = mode_names[static_cast<int>(mode)];
  // The path is chosen at the defaults (above), so both travel rows share it.
  if (travel_ratio > 0.0) {
    settings.proxy_travel_ratio = travel_ratio;
    row.mode += "/travel" + std::to_string(state.range(2));
  }
  row.steps = kHapticSteps;
  row.max_step = max_step;
  row.delta_max = settings.safety_coefficient * settings.tolerance * settings.max_iterations;
  std::vector<double> wall, cpu;
  const bool keep_steps = index == 0 && mode == sc::RotationMode::Input && travel_ratio == 0.0;
  for (auto _ : state) {
    sc::PairTracker tracker;
    Vec3 previous_tpdv = Vec3::Zero();
    for (int k = 0; k < kHapticSteps; ++k) {
      const double c0 = sc_bench::threadCpuSeconds();
      const auto t0 = Clock::now();
#ifdef SC_HAVE_CALLGRIND
      if (g_callgrind_updates) CALLGRIND_TOGGLE_COLLECT;
#endif
      const sc::DirectedResult r =
          updateOneWay(tracker, part_a, path[k], part_b, opponent, settings);
#ifdef SC_HAVE_CALLGRIND
      if (g_callgrind_updates) {
        CALLGRIND_TOGGLE_COLLECT;
        CALLGRIND_DUMP_STATS;
      }
#endif
      const auto t1 = Clock::now();
      const double c1 = sc_bench::threadCpuSeconds();
      wall.push_back(sc_bench::seconds(t0, t1));
      cpu.push_back(c1 - c0);
      if (r.code != sc::ErrorCode::Ok) ++row.not_ok;
      if (r.penetrating()) ++row.penetrating;
      const double jump = (r.tpdv - previous_tpdv).norm();
      row.max_tpdv_jump = std::max(row.max_tpdv_jump, jump);
      if (k > 0 && step_motion[k] > 0.0) {
        const double ratio = jump / step_motion[k];
        row.jumps_over_3x += ratio > 3.0;
        if (ratio > row.max_jump_ratio) {
          row.max_jump_ratio = ratio;
          row.jump_ratio_step = k;
        }
      }
      previous_tpdv = r.tpdv;
      row.max_tpdv = std::max(row.max_tpdv, r.tpdv.norm());
      if (keep_steps)
        g_haptic_steps.push_back({double(k), 1e6 * wall.back(), 1e6 * cpu.back(), r.tpdv.norm()});
    }
    double total = 0.0;
    for (double t : wall) total += t;
    state.SetIterationTime(total);
  }
  row.median_us = 1e6 * quantile(wall, 0.5);
  row.p99_us = 1e6 * quantile(wall, 0.99);
  row.max_us = 1e6 * quantile(wall, 1.0);
  row.cpu_median_us = 1e6 * quantile(cpu, 0.5);
  row.cpu_p99_us = 1e6 * quantile(cpu, 0.99);
  row.cpu_max_us = 1e6 * quantile(cpu, 1.0);
  state.counters["penetrating"] = row.penetrating;
  state.counters["median_us"] = row.median_us;
  state.counters["p99_us"] = row.p99_us;
  state.counters["cpu_p99_us"] = row.cpu_p99_us;
  state.counters["max_step"] = row.max_step;
  state.counters["delta_max"] = row.delta_max;
  state.counters["max_tpdv"] = row.max_tpdv;
  state.counters["max_tpdv_jump"] = row.max_tpdv_jump;
  state.counters["max_jump_ratio"] = row.max_jump_ratio;
  state.counters["jump_ratio_step"] = row.jump_ratio_step;
  state.counters["jumps_over_3x"] = row.jumps_over_3x;
  g_haptic.push_back(row);
}

// ---------------------------------------------------------------------------------
// Convex pairs: speed against accuracy.

/// A convex polytope: local vertices, the directions its faces face and its edges run
/// along (the candidate separating axes), and a closed triangulation for our models.
struct Convex {
  std::vector<Vec3> vertices;
  std::vector<Vec3> face_normals;
  std::vector<Vec3> edge_directions;
  sc::MeshData mesh;
  Vec3 centre = Vec3::Zero();  ///< mean of the vertices: inside, for MPR
};

Convex box(const Vec3& h) {
  Convex c;
  for (int i = 0; i < 8; ++i)
    c.vertices.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                            (i & 4) ? h.z() : -h.z());
  c.face_normals = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  c.edge_directions = c.face_normals;
  c.mesh.vertices = c.vertices;
  c.mesh.triangles = {sc::Tri(0, 2, 3), sc::Tri(0, 3, 1), sc::Tri(4, 5, 7), sc::Tri(4, 7, 6),
                      sc::Tri(0, 1, 5), sc::Tri(0, 5, 4), sc::Tri(2, 6, 7), sc::Tri(2, 7, 3),
                      sc::Tri(0, 4, 6), sc::Tri(0, 6, 2), sc::Tri(1, 3, 7), sc::Tri(1, 7, 5)};
  return c;
}

/// Hull of points in general position (every facet a triangle), by brute force over
/// all triples; a triple stops at the first two points on opposite sides.
Convex hullOf(const std::vector<Vec3>& points) {
  const int n = static_cast<int>(points.size());
  std::vector<sc::Tri> facets;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k) {
        const Vec3 normal = (points[j] - points[i]).cross(points[k] - points[i]);
        int above = 0, below = 0;
        for (int m = 0; m < n && (above == 0 || below == 0); ++m) {
          if (m == i || m == j || m == k) continue;
          (normal.dot(points[m] - points[i]) > 0.0 ? above : below)++;
        }
        if (above == 0) facets.emplace_back(i, j, k);
        if (below == 0) facets.emplace_back(i, k, j);
      }
  Convex c;
  std::vector<int> index(n, -1);
  for (const sc::Tri& f : facets)
    for (int v = 0; v < 3; ++v)
      if (index[f[v]] < 0) {
        index[f[v]] = static_cast<int>(c.vertices.size());
        c.vertices.push_back(points[f[v]]);
      }
  std::set<std::pair<int, int>> edges;
  for (const sc::Tri& f : facets) {
    const sc::Tri t(index[f[0]], index[f[1]], index[f[2]]);
    c.mesh.triangles.push_back(t);
    c.face_normals.push_back((c.vertices[t[1]] - c.vertices[t[0]])
                                 .cross(c.vertices[t[2]] - c.vertices[t[0]])
                                 .normalized());
    for (int v = 0; v < 3; ++v) {
      const auto e = std::minmax(t[v], t[(v + 1) % 3]);
      if (edges.insert(e).second)
        c.edge_directions.push_back((c.vertices[e.second] - c.vertices[e.first]).normalized());
    }
  }
  c.mesh.vertices = c.vertices;
  for (const Vec3& v : c.vertices) c.centre += v / static_cast<double>(c.vertices.size());
  return c;
}

/// Hull of n random points on an ellipsoid.
Convex randomHull(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> axis(0.3, 1.0);
  const Vec3 radii = sc::support::randomVec3(axis, rng);
  std::vector<Vec3> points;
  for (int i = 0; i < n; ++i) points.push_back(randomDirection(rng).cwiseProduct(radii));
  return hullOf(points);
}

double support(const std::vector<Vec3>& world, const Vec3& d) {
  double best = -sc::kInfinity;
  for (const Vec3& v : world) best = std::max(best, v.dot(d));
  return best;
}

/// Exact translational penetration depth of A and B (world vertices and world axes):
/// the least support of the Minkowski difference A - B over the candidate axes (face
/// normals of each, cross products of an edge of each) contains every facet normal
/// of the difference, so its minimum is the origin's distance to the hull boundary.
/// Negative when some axis separates.
double exactDepth(const std::vector<Vec3>& a, const std::vector<Vec3>& axes_a_faces,
                  const std::vector<Vec3>& axes_a_edges, const std::vector<Vec3>& b,
                  const std::vector<Vec3>& axes_b_faces, const std::vector<Vec3>& axes_b_edges) {
  double depth = sc::kInfinity;
  const auto tryAxis = [&](const Vec3& n) {
    for (const Vec3& d : {n, Vec3(-n)}) depth = std::min(depth, support(a, d) + support(b, -d));
  };
  for (const Vec3& n : axes_a_faces) tryAxis(n);
  for (const Vec3& n : axes_b_faces) tryAxis(n);
  for (const Vec3& ea : axes_a_edges)
    for (const Vec3& eb : axes_b_edges) {
      const Vec3 n = ea.cross(eb);
      const double len = n.norm();
      if (len > 1e-9) tryAxis(n / len);
    }
  return depth;
}

struct PosedConvex {
  const Convex* shape;
  sc::Rigid pose;
  std::vector<Vec3> world, faces, edges;
  void place(const sc::Rigid& p) {
    pose = p;
    world.clear();
    faces.clear();
    edges.clear();
    for (const Vec3& v : shape->vertices) world.push_back(p * v);
    for (const Vec3& n : shape->face_normals) faces.push_back(p.rotation * n);
    for (const Vec3& e : shape->edge_directions) edges.push_back(p.rotation * e);
  }
};

double exactDepth(const PosedConvex& a, const PosedConvex& b) {
  return exactDepth(a.world, a.faces, a.edges, b.world, b.faces, b.edges);
}

/// One case: A's free pose just outside B, its penetrating pose pushed in along the
/// approach, and the exact depth there.
struct ConvexCase {
  std::shared_ptr<Convex> a, b;
  sc::ModelPtr model_a, model_b;
  sc::Rigid pose_b, free_a, deep_a;
  double depth = 0.0;
};

constexpr int kCasesPerShape = 150;
constexpr int kRepeats = 5;  // each case is timed this often; the fastest counts

std::vector<ConvexCase> makeCases(bool boxes) {
  std::mt19937_64 rng(boxes ? 5 : 6);
  std::uniform_real_distribution<double> half(0.2, 1.0), push(0.005, 0.05);
  std::vector<ConvexCase> cases;
  while (static_cast<int>(cases.size()) < kCasesPerShape) {
    ConvexCase c;
    if (boxes) {
      c.a = std::make_shared<Convex>(box(sc::support::randomVec3(half, rng)));
      c.b = std::make_shared<Convex>(box(sc::support::randomVec3(half, rng)));
    } else {
      c.a = std::make_shared<Convex>(randomHull(rng, 20));
      c.b = std::make_shared<Convex>(randomHull(rng, 20));
    }
    c.pose_b = {randomRotation(rng).toRotationMatrix(), Vec3::Zero()};
    const sc::Mat3 ra = randomRotation(rng).toRotationMatrix();
    const Vec3 u = randomDirection(rng);
    PosedConvex pa{c.a.get(), {}, {}, {}, {}}, pb{c.b.get(), {}, {}, {}, {}};
    pb.place(c.pose_b);
    const auto depthAt = [&](double s) {
      pa.place({ra, s * u});
      return exactDepth(pa, pb);
    };
    double lo = 0.0, hi = 4.0;  // lo overlapping, hi apart
    if (depthAt(lo) <= 0.0 || depthAt(hi) >= 0.0) continue;
    for (int k = 0; k < 60; ++k) (depthAt(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
    c.free_a = {ra, (hi + 1e-3) * u};
    c.deep_a = {ra, (hi - push(rng)) * u};
    pa.place(c.deep_a);
    c.depth = exactDepth(pa, pb);
    if (c.depth <= 0.0) continue;
    c.model_a = closedModel(c.a->mesh);
    c.model_b = closedModel(c.b->mesh);
    if (!c.model_a || !c.model_b) continue;
    cases.push_back(std::move(c));
  }
  return cases;
}

const std::vector<ConvexCase>& cases(bool boxes) {
  static const std::vector<ConvexCase> box_cases = makeCases(true);
  static const std::vector<ConvexCase> hull_cases = makeCases(false);
  return boxes ? box_cases : hull_cases;
}

struct SweepRow {
  std::string method, shapes, parameters;
  double tolerance = 0;
  int iterations = 0;
  int cases = 0, failures = 0, over_1e6 = 0;  ///< over_1e6: relative error above 1e-6
  double median_us = 0, median_err = 0, p90_err = 0, max_err = 0;
};
std::vector<SweepRow> g_sweep;

void finishRow(benchmark::State& state, SweepRow row, const std::vector<double>& times,
               std::vector<double> errors) {
  row.cases = static_cast<int>(errors.size());
  row.median_us = 1e6 * quantile(times, 0.5);
  row.median_err = quantile(errors, 0.5);
  row.p90_err = quantile(errors, 0.9);
  row.max_err = quantile(errors, 1.0);
  row.over_1e6 = static_cast<int>(
      std::count_if(errors.begin(), errors.end(), [](double e) { return e > 1e-6; }));
  state.counters["median_us"] = row.median_us;
  state.counters["median_err"] = row.median_err;
  state.counters["p90_err"] = row.p90_err;
  state.counters["max_err"] = row.max_err;
  state.counters["failures"] = row.failures;
  state.counters["over_1e-6"] = row.over_1e6;
  g_sweep.push_back(row);
}

/// One solver's attempt on a case: the depth it found (NaN when it found none) and the
/// seconds the solve alone took.
struct Attempt {
  double depth = std::numeric_limits<double>::quiet_NaN();
  double seconds = 0.0;
};

/// Runs `attempt(case)` kRepeats times per case, keeps the fastest, and records the
/// error of the depth against the exact one: the row's times and errors.
template <class Solve>
void sweepRow(benchmark::State& state, const SweepRow& row, bool boxes, Solve attempt) {
  SweepRow out = row;
  std::vector<double> times, errors;
  for (auto _ : state) {
    double total = 0.0;
    for (const ConvexCase& c : cases(boxes)) {
      double best = sc::kInfinity, depth = 0.0;
      for (int k = 0; k < kRepeats; ++k) {
        const Attempt a = attempt(c);
        best = std::min(best, a.seconds);
        depth = a.depth;
      }
      total += best;
      times.push_back(best);
      const bool failed = !std::isfinite(depth);
      out.failures += failed;
      errors.push_back(failed ? 1.0 : std::abs(depth - c.depth) / c.depth);
    }
    state.SetIterationTime(total);
  }
  finishRow(state, out, times, errors);
}

sc::Placement placementOf(const sc::Rigid& r) {
  sc::Placement p;
  p.setMatrix(r.rotation, r.translation);
  return p;
}

/// Ours: an update at the free pose starts tracking, the timed update at the
/// penetrating pose gives the depth.
void BM_OursConvex(benchmark::State& state) {
  const bool boxes = state.range(0) == 0;
  SweepRow row;
  row.method = "smartcollision";
  row.shapes = boxes ? "boxes" : "hulls";
  row.tolerance = std::pow(10.0, -static_cast<double>(state.range(1)));
  row.iterations = static_cast<int>(state.range(2));
  row.parameters = "tolerance=" + std::to_string(row.tolerance) +
                   " iterations=" + std::to_string(row.iterations);
  sc::SceneSettings settings;
  settings.tolerance = row.tolerance;
  settings.max_iterations = row.iterations;
  sweepRow(state, row, boxes, [&](const ConvexCase& c) {
    const sc::Part pa{c.model_a.get(), sc::Rigid(), 0}, pb{c.model_b.get(), sc::Rigid(), 1};
    const sc::Placement opponent = placementOf(c.pose_b);
    sc::PairTracker tracker;
    updateOneWay(tracker, pa, placementOf(c.free_a), pb, opponent, settings);
    const sc::Placement deep = placementOf(c.deep_a);
    Attempt attempt;
    const auto t0 = Clock::now();
    const sc::DirectedResult r = updateOneWay(tracker, pa, deep, pb, opponent, settings);
    attempt.seconds = sc_bench::seconds(t0, Clock::now());
    if (r.penetrating()) attempt.depth = r.tpdv.norm();
    return attempt;
  });
}

#if SC_BENCH_HAVE_CCD
struct CcdShape {
  const Convex* shape;
  const sc::Rigid* pose;
};

void ccdSupport(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto* s = static_cast<const CcdShape*>(obj);
  const Vec3 d = s->pose->rotation.transpose() * Vec3(dir->v[0], dir->v[1], dir->v[2]);
  const Vec3* best = &s->shape->vertices[0];
  double best_dot = best->dot(d);
  for (const Vec3& v : s->shape->vertices) {
    const double dot = v.dot(d);
    if (dot > best_dot) {
      best_dot = dot;
      best = &v;
    }
  }
  const Vec3 w = *s->pose * *best;
  ccdVec3Set(out, w.x(), w.y(), w.z());
}

/// MPR's interior point.
void ccdCenter(const void* obj, ccd_vec3_t* out) {
  const auto* s = static_cast<const CcdShape*>(obj);
  const Vec3 w = *s->pose * s->shape->centre;
  ccdVec3Set(out, w.x(), w.y(), w.z());
}

/// libccd: EPA (method 0) or MPR (method 1); the tolerance of the method swept.
void BM_CcdConvex(benchmark::State& state) {
  const bool boxes = state.range(0) == 0;
  const bool mpr = state.range(1) == 1;
  SweepRow row;
  row.method = mpr ? "libccd_mpr" : "libccd_epa";
  row.shapes = boxes ? "boxes" : "hulls";
  row.tolerance = std::pow(10.0, -static_cast<double>(state.range(2)));
  row.parameters =
      std::string(mpr ? "mpr_tolerance=" : "epa_tolerance=") + std::to_string(row.tolerance);
  ccd_t ccd = sc_bench::ccdProblem(ccdSupport, ccdCenter);
  ccd.max_iterations = 1000;
  if (mpr)
    ccd.mpr_tolerance = row.tolerance;
  else
    ccd.epa_tolerance = row.tolerance;
  sweepRow(state, row, boxes, [&](const ConvexCase& c) {
    const CcdShape a{c.a.get(), &c.deep_a}, b{c.b.get(), &c.pose_b};
    ccd_real_t depth = 0;
    ccd_vec3_t dir, pos;
    Attempt attempt;
    const auto t0 = Clock::now();
    const int status = mpr ? ccdMPRPenetration(&a, &b, &ccd, &depth, &dir, &pos)
                           : ccdGJKPenetration(&a, &b, &ccd, &depth, &dir, &pos);
    attempt.seconds = sc_bench::seconds(t0, Clock::now());
    if (status == 0) attempt.depth = depth;
    return attempt;
  });
}
#endif

#if SC_BENCH_HAVE_BULLET
btTransform btPose(const sc::Rigid& r) {
  const sc::Mat3& m = r.rotation;
  return btTransform(
      btMatrix3x3(m(0, 0), m(0, 1), m(0, 2), m(1, 0), m(1, 1), m(1, 2), m(2, 0), m(2, 1), m(2, 2)),
      btVector3(r.translation.x(), r.translation.y(), r.translation.z()));
}

std::unique_ptr<btConvexHullShape> btHull(const Convex& c) {
  auto hull = std::make_unique<btConvexHullShape>();
  for (const Vec3& v : c.vertices) hull->addPoint(btVector3(v.x(), v.y(), v.z()), false);
  hull->recalcLocalAabb();
  hull->setMargin(0);  // the exact shapes, as ours and libccd's
  return hull;
}

/// Bullet's GJK-EPA (its accuracies are compile-time constants: one point).
void BM_BulletConvex(benchmark::State& state) {
  const bool boxes = state.range(0) == 0;
  SweepRow row;
  row.method = "bullet_gjk_epa";
  row.shapes = boxes ? "boxes" : "hulls";
  row.parameters =
      std::string("defaults; btScalar of ") + std::to_string(sizeof(btScalar)) + " bytes";
  sweepRow(state, row, boxes, [&](const ConvexCase& c) {
    const auto ha = btHull(*c.a), hb = btHull(*c.b);
    const btTransform ta = btPose(c.deep_a), tb = btPose(c.pose_b);
    btGjkEpaSolver2::sResults result;
    Attempt attempt;
    const auto t0 = Clock::now();
    const bool ok =
        btGjkEpaSolver2::Penetration(ha.get(), ta, hb.get(), tb, btVector3(1, 0, 0), result);
    attempt.seconds = sc_bench::seconds(t0, Clock::now());
    if (ok) attempt.depth = -static_cast<double>(result.distance);
    return attempt;
  });
}
#endif

// ---------------------------------------------------------------------------------
// Global depth of a convex pair first seen intersecting (issue 19): hulls of CGAL
// models, random intersecting poses, ours (a fresh tracker resolving the initial
// intersection) against libccd's MPR and EPA and Bullet's GJK-EPA, interleaved.

/// Hull of n extreme vertices of a CGAL model scaled to unit size: the vertices
/// furthest along random directions, until n distinct ones are found.
std::shared_ptr<Convex> modelHull(const std::string& name, int n, unsigned seed) {
  sc::MeshData raw = sc_bench::loadOff(name);
  if (raw.vertices.empty()) return nullptr;
  const sc::MeshData mesh = sc::support::fitToSize(std::move(raw), 1.0);
  std::mt19937_64 rng(seed);
  std::vector<int> chosen;
  for (int tries = 0; static_cast<int>(chosen.size()) < n && tries < 100 * n; ++tries) {
    const Vec3 d = randomDirection(rng);
    int best = 0;
    for (int i = 1; i < static_cast<int>(mesh.vertices.size()); ++i)
      if (mesh.vertices[i].dot(d) > mesh.vertices[best].dot(d)) best = i;
    if (std::find(chosen.begin(), chosen.end(), best) == chosen.end()) chosen.push_back(best);
  }
  std::vector<Vec3> points;
  for (int i : chosen) points.push_back(mesh.vertices[i]);
  auto hull = std::make_shared<Convex>(hullOf(points));
  if (static_cast<int>(hull->vertices.size()) != n) return nullptr;
  return hull;
}

/// The facets of a convex mesh around each edge: (first, second) triangle normals.
struct EdgeFaces {
  int v0, v1;
  Vec3 n0, n1;
};

std::vector<EdgeFaces> edgeFaces(const Convex& c) {
  std::map<std::pair<int, int>, EdgeFaces> edges;
  for (const sc::Tri& t : c.mesh.triangles) {
    const Vec3 n = (c.vertices[t[1]] - c.vertices[t[0]])
                       .cross(c.vertices[t[2]] - c.vertices[t[0]])
                       .normalized();
    for (int v = 0; v < 3; ++v) {
      const auto key = std::minmax(t[v], t[(v + 1) % 3]);
      auto it = edges.find(key);
      if (it == edges.end())
        edges[key] = {key.first, key.second, n, Vec3::Zero()};
      else
        it->second.n1 = n;
    }
  }
  std::vector<EdgeFaces> out;
  for (const auto& e : edges) out.push_back(e.second);
  return out;
}

/// Exact depth of two convex meshes (world vertices, world edge facets): the least
/// support of A - B over the facet normals of the difference, which are the face
/// normals of A and of B and the cross products of an edge of A with an edge of B
/// whose arcs cross on the Gauss map (Minkowski faces). The arc test is loosened, so
/// it keeps every true facet and a few more directions; any direction bounds the depth
/// from above, so extra ones change nothing. Negative when some direction separates.
double exactGlobalDepth(const PosedConvex& a, const std::vector<EdgeFaces>& ea,
                        const PosedConvex& b, const std::vector<EdgeFaces>& eb) {
  double depth = sc::kInfinity;
  const auto tryAxis = [&](const Vec3& n) {
    for (const Vec3& d : {n, Vec3(-n)})
      depth = std::min(depth, support(a.world, d) + support(b.world, -d));
  };
  for (const Vec3& n : a.faces) tryAxis(n);
  for (const Vec3& n : b.faces) tryAxis(n);
  constexpr double kSlack = 1e-9;
  for (const EdgeFaces& x : ea) {
    const Vec3 p = a.pose.rotation * x.n0, q = a.pose.rotation * x.n1;
    const Vec3 qxp = q.cross(p);
    const Vec3 edge_a = a.world[x.v1] - a.world[x.v0];
    for (const EdgeFaces& y : eb) {
      // B's facets enter A - B negated.
      const Vec3 r = -(b.pose.rotation * y.n0), s = -(b.pose.rotation * y.n1);
      const Vec3 sxr = s.cross(r);
      const double rqp = r.dot(qxp), sqp = s.dot(qxp), psr = p.dot(sxr), qsr = q.dot(sxr);
      if (rqp * sqp > kSlack || psr * qsr > kSlack || rqp * qsr < -kSlack) continue;
      const Vec3 n = edge_a.cross(b.world[y.v1] - b.world[y.v0]);
      const double len = n.norm();
      if (len > 1e-12) tryAxis(n / len);
    }
  }
  return depth;
}

struct GlobalCase {
  sc::Rigid pose_a, pose_b;
  double depth = 0.0;
};

struct GlobalSet {
  std::shared_ptr<Convex> a, b;
  sc::ModelPtr model_a, model_b;
  std::vector<GlobalCase> cases;
};

constexpr int kGlobalCases = 500;

/// bunny00's hull (A) and armadillo's (B), n vertices each, at random orientations,
/// A's centre at up to 0.9 of the mean radius from B's; intersecting poses only.
const GlobalSet* globalSet(int n) {
  static std::map<int, std::unique_ptr<GlobalSet>> sets;
  auto found = sets.find(n);
  if (found != sets.end()) return found->second.get();
  auto set = std::make_unique<GlobalSet>();
  set->a = modelHull("bunny00", n, 11);
  set->b = modelHull("armadillo", n, 12);
  if (set->a) set->model_a = closedModel(set->a->mesh);
  if (set->b) set->model_b = closedModel(set->b->mesh);
  if (!set->model_a || !set->model_b) {
    std::fprintf(stderr, "bench: no %d-vertex hulls of bunny00 and armadillo\n", n);
    set.reset();
    return (sets[n] = std::move(set)).get();
  }
  const auto ea = edgeFaces(*set->a), eb = edgeFaces(*set->b);
  double ra = 0, rb = 0;
  for (const Vec3& v : set->a->vertices) ra = std::max(ra, v.norm());
  for (const Vec3& v : set->b->vertices) rb = std::max(rb, v.norm());
  std::mt19937_64 rng(19 + n);
  std::uniform_real_distribution<double> reach(0.0, 0.9);
  PosedConvex pa{set->a.get(), {}, {}, {}, {}}, pb{set->b.get(), {}, {}, {}, {}};
  while (static_cast<int>(set->cases.size()) < kGlobalCases) {
    GlobalCase c;
    c.pose_b = {randomRotation(rng).toRotationMatrix(), Vec3::Zero()};
    c.pose_a = {randomRotation(rng).toRotationMatrix(),
                reach(rng) * 0.5 * (ra + rb) * randomDirection(rng)};
    pa.place(c.pose_a);
    pb.place(c.pose_b);
    c.depth = exactGlobalDepth(pa, ea, pb, eb);
    if (c.depth > 0.0) set->cases.push_back(c);
  }
  return (sets[n] = std::move(set)).get();
}

struct GlobalRow {
  std::string method;
  int vertices = 0, cases = 0, failures = 0, over_1e9 = 0;
  double median_us = 0, p90_us = 0, max_us = 0, median_err = 0, max_err = 0;
  double min_depth = 0, max_depth = 0;
};
std::vector<GlobalRow> g_global;
bool g_target_missed = false;

/// One method on one case: the depth (negative: failed) and the fastest of kRepeats.
using GlobalMethod = std::function<double(const GlobalSet&, const GlobalCase&, double&)>;

template <class Run>
double fastest(Run run, double& depth) {
  double best = sc::kInfinity;
  for (int k = 0; k < kRepeats; ++k) {
    double seconds = 0;
    depth = run(seconds);
    best = std::min(best, seconds);
  }
  return best;
}

double oursGlobal(const GlobalSet& set, const GlobalCase& c, double& depth) {
  sc::SceneSettings settings;
  settings.resolve_initial_intersection = true;
  const sc::Part pa{set.model_a.get(), sc::Rigid(), 0}, pb{set.model_b.get(), sc::Rigid(), 1};
  const sc::Placement a = placementOf(c.pose_a), b = placementOf(c.pose_b);
  return fastest(
      [&](double& seconds) {
        sc::PairTracker tracker;  // first seen: a fresh tracker
        const auto t0 = Clock::now();
        const sc::DirectedResult r = updateOneWay(tracker, pa, a, pb, b, settings);
        seconds = sc_bench::seconds(t0, Clock::now());
        return r.code == sc::ErrorCode::Ok && r.penetrating() ? -r.distance : -1.0;
      },
      depth);
}

#if SC_BENCH_HAVE_CCD
double ccdGlobal(const GlobalSet& set, const GlobalCase& c, double& depth, bool mpr) {
  ccd_t ccd = sc_bench::ccdProblem(ccdSupport, ccdCenter);
  ccd.max_iterations = 1000;
  ccd.mpr_tolerance = 1e-8;
  ccd.epa_tolerance = 1e-8;
  const CcdShape a{set.a.get(), &c.pose_a}, b{set.b.get(), &c.pose_b};
  return fastest(
      [&](double& seconds) {
        ccd_real_t d = 0;
        ccd_vec3_t dir, pos;
        const auto t0 = Clock::now();
        const int status = mpr ? ccdMPRPenetration(&a, &b, &ccd, &d, &dir, &pos)
                               : ccdGJKPenetration(&a, &b, &ccd, &d, &dir, &pos);
        seconds = sc_bench::seconds(t0, Clock::now());
        return status == 0 && std::isfinite(d) ? static_cast<double>(d) : -1.0;
      },
      depth);
}
#endif

#if SC_BENCH_HAVE_BULLET
double bulletGlobal(const GlobalSet& set, const GlobalCase& c, double& depth) {
  const auto ha = btHull(*set.a), hb = btHull(*set.b);
  const btTransform ta = btPose(c.pose_a), tb = btPose(c.pose_b);
  return fastest(
      [&](double& seconds) {
        btGjkEpaSolver2::sResults result;
        const auto t0 = Clock::now();
        const bool ok =
            btGjkEpaSolver2::Penetration(ha.get(), ta, hb.get(), tb, btVector3(1, 0, 0), result);
        seconds = sc_bench::seconds(t0, Clock::now());
        const double d = -static_cast<double>(result.distance);
        return ok && std::isfinite(d) ? d : -1.0;
      },
      depth);
}
#endif

/// Every method on every case, the methods in a rotating order per case.
void BM_ConvexGlobalDepth(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const GlobalSet* set = globalSet(n);
  if (!set) {
    state.SkipWithError("meshes missing");
    return;
  }
  std::vector<std::pair<std::string, GlobalMethod>> methods = {{"smartcollision", oursGlobal}};
#if SC_BENCH_HAVE_CCD
  methods.emplace_back("libccd_mpr", [](const GlobalSet& s, const GlobalCase& c, double& d) {
    return ccdGlobal(s, c, d, true);
  });
  methods.emplace_back("libccd_epa", [](const GlobalSet& s, const GlobalCase& c, double& d) {
    return ccdGlobal(s, c, d, false);
  });
#endif
#if SC_BENCH_HAVE_BULLET
  methods.emplace_back("bullet_gjk_epa", bulletGlobal);
#endif
  const int m = static_cast<int>(methods.size());
  std::vector<std::vector<double>> times(m), errors(m);
  std::vector<GlobalRow> rows(m);
  for (auto _ : state) {
    double total = 0.0;
    for (int i = 0; i < static_cast<int>(set->cases.size()); ++i) {
      const GlobalCase& c = set->cases[i];
      for (int k = 0; k < m; ++k) {
        const int j = (i + k) % m;
        double depth = 0;
        const double seconds = methods[j].second(*set, c, depth);
        if (j == 0) total += seconds;
        times[j].push_back(seconds);
        const double err = depth < 0 ? 1.0 : std::abs(depth - c.depth) / c.depth;
        if (depth < 0) ++rows[j].failures;
        errors[j].push_back(err);
      }
    }
    state.SetIterationTime(total);
  }
  std::vector<double> depths;
  for (const GlobalCase& c : set->cases) depths.push_back(c.depth);
  for (int j = 0; j < m; ++j) {
    GlobalRow& row = rows[j];
    row.method = methods[j].first;
    row.vertices = n;
    row.cases = static_cast<int>(set->cases.size());
    row.median_us = 1e6 * quantile(times[j], 0.5);
    row.p90_us = 1e6 * quantile(times[j], 0.9);
    row.max_us = 1e6 * quantile(times[j], 1.0);
    row.median_err = quantile(errors[j], 0.5);
    row.max_err = quantile(errors[j], 1.0);
    row.over_1e9 = static_cast<int>(
        std::count_if(errors[j].begin(), errors[j].end(), [](double e) { return e > 1e-9; }));
    row.min_depth = quantile(depths, 0.0);
    row.max_depth = quantile(depths, 1.0);
    state.counters[row.method + "_median_us"] = row.median_us;
    state.counters[row.method + "_max_err"] = row.max_err;
    g_global.push_back(row);
  }
  // Target (256-vertex hulls): median <= libccd MPR's, every error <= 1e-9 relative.
  if (n >= 256) {
    bool met = rows[0].over_1e9 == 0 && rows[0].failures == 0;
    for (const GlobalRow& r : rows)
      if (r.method == "libccd_mpr") met = met && rows[0].median_us <= r.median_us;
    if (!met) g_target_missed = true;
    std::printf(
        "convex global depth, %d-vertex hulls: target %s (ours %.2f us median, max error "
        "%.2g, %d over 1e-9)\n",
        n, met ? "met" : "MISSED", rows[0].median_us, rows[0].max_err, rows[0].over_1e9);
  }
}

// ---------------------------------------------------------------------------------
// A convex pair along a haptic path (issue 19): each update of a carried tracker
// against libccd's MPR and EPA and Bullet's GJK-EPA at the same pose.

struct ConvexPathRow {
  std::string method, shapes;
  int steps = 0, penetrating = 0;
  double median_us = 0, p99_us = 0, max_us = 0, cpu_median_us = 0, cpu_p99_us = 0, cpu_max_us = 0;
};
std::vector<ConvexPathRow> g_convex_path;

/// One method at step k of the path; true when it reports penetration.
using PathStep = std::function<bool(int)>;

double radiusOf(const Convex& c) {
  double r = 0.0;
  for (const Vec3& v : c.vertices) r = std::max(r, v.norm());
  return r;
}

void finishPathRow(benchmark::State& state, ConvexPathRow& row, std::vector<double>& wall,
                   std::vector<double>& cpu) {
  row.median_us = 1e6 * quantile(wall, 0.5);
  row.p99_us = 1e6 * quantile(wall, 0.99);
  row.max_us = 1e6 * quantile(wall, 1.0);
  row.cpu_median_us = 1e6 * quantile(cpu, 0.5);
  row.cpu_p99_us = 1e6 * quantile(cpu, 0.99);
  row.cpu_max_us = 1e6 * quantile(cpu, 1.0);
  state.counters[row.method + "_cpu_median_us"] = row.cpu_median_us;
  g_convex_path.push_back(row);
}

/// Boxes (arg 0) or the 256-vertex hulls of bunny00 and armadillo (arg 1) along the
/// haptic path (2000 steps, 0.015 to 0.045 deep); every method at every pose, in a
/// rotating order, timed once (ours carries its tracker: a repeat would be free).
void BM_ConvexPath(benchmark::State& state) {
  const bool boxes = state.range(0) == 0;
  static const Convex box_a = box(Vec3(0.3, 0.4, 0.5)), box_b = box(Vec3(0.5, 0.35, 0.6));
  const GlobalSet* set = boxes ? nullptr : globalSet(256);
  if (!boxes && !set) {
    state.SkipWithError("meshes missing");
    return;
  }
  const Convex& a = boxes ? box_a : *set->a;
  const Convex& b = boxes ? box_b : *set->b;
  const sc::ModelPtr ma = boxes ? closedModel(a.mesh) : set->model_a;
  const sc::ModelPtr mb = boxes ? closedModel(b.mesh) : set->model_b;
  const sc::Part part_a{ma.get(), sc::Rigid(), 0}, part_b{mb.get(), sc::Rigid(), 1};
  const sc::SceneSettings settings;
  const std::vector<sc::Placement> path =
      hapticPath(radiusOf(a), radiusOf(b), part_a, part_b, settings, 1926);
  std::vector<sc::Rigid> poses;
  for (const sc::Placement& p : path) poses.push_back(p.worldFromLocal());
  const sc::Rigid pose_b;
  sc::PairTracker tracker;
  std::vector<std::pair<std::string, PathStep>> methods;
  methods.emplace_back("smartcollision", [&](int k) {
    return updateOneWay(tracker, part_a, path[k], part_b, sc::Placement(), settings).penetrating();
  });
#if SC_BENCH_HAVE_CCD
  ccd_t ccd = sc_bench::ccdProblem(ccdSupport, ccdCenter);
  ccd.max_iterations = 1000;
  ccd.mpr_tolerance = 1e-8;
  ccd.epa_tolerance = 1e-8;
  for (const bool mpr : {true, false})
    methods.emplace_back(mpr ? "libccd_mpr" : "libccd_epa", [&, mpr](int k) {
      const CcdShape sa{&a, &poses[k]}, sb{&b, &pose_b};
      ccd_real_t depth = 0;
      ccd_vec3_t dir, pos;
      return (mpr ? ccdMPRPenetration(&sa, &sb, &ccd, &depth, &dir, &pos)
                  : ccdGJKPenetration(&sa, &sb, &ccd, &depth, &dir, &pos)) == 0;
    });
#endif
#if SC_BENCH_HAVE_BULLET
  const auto ha = btHull(a), hb = btHull(b);
  methods.emplace_back("bullet_gjk_epa", [&](int k) {
    btGjkEpaSolver2::sResults result;
    return btGjkEpaSolver2::Penetration(ha.get(), btPose(poses[k]), hb.get(), btPose(pose_b),
                                        btVector3(1, 0, 0), result);
  });
#endif
  const int m = static_cast<int>(methods.size());
  std::vector<std::vector<double>> wall(m), cpu(m);
  std::vector<ConvexPathRow> rows(m);
  for (auto _ : state) {
    double total = 0.0;
    for (int k = 0; k < static_cast<int>(path.size()); ++k)
      for (int i = 0; i < m; ++i) {
        const int j = (k + i) % m;
        const double c0 = sc_bench::threadCpuSeconds();
        const auto t0 = Clock::now();
        rows[j].penetrating += methods[j].second(k);
        const auto t1 = Clock::now();
        cpu[j].push_back(sc_bench::threadCpuSeconds() - c0);
        wall[j].push_back(sc_bench::seconds(t0, t1));
        if (j == 0) total += wall[j].back();
      }
    state.SetIterationTime(total);
  }
  for (int j = 0; j < m; ++j) {
    rows[j].method = methods[j].first;
    rows[j].shapes = boxes ? "boxes" : "hulls256";
    rows[j].steps = static_cast<int>(path.size());
    finishPathRow(state, rows[j], wall[j], cpu[j]);
  }
}

// Modes: 1 = INPUT (the default), 2 = FREE.
// arg2: PairSettings::proxy_travel_ratio (0: the default, +inf).
BENCHMARK(BM_HapticPath)
    ->ArgsProduct({{0, 1}, {1, 2}, {0, 2}})
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
// tolerance = 10^-arg1, iterations arg2.
BENCHMARK(BM_OursConvex)
    ->ArgsProduct({{0, 1}, {2, 3, 4, 5, 6}, {1, 2, 4, 8, 30}})
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
#if SC_BENCH_HAVE_CCD
BENCHMARK(BM_CcdConvex)
    ->ArgsProduct({{0, 1}, {0, 1}, {2, 4, 6, 8}})
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
#endif
#if SC_BENCH_HAVE_BULLET
BENCHMARK(BM_BulletConvex)
    ->DenseRange(0, 1)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
#endif
// Hull vertices per model.
BENCHMARK(BM_ConvexGlobalDepth)
    ->Arg(24)
    ->Arg(256)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

BENCHMARK(BM_ConvexPath)
    ->DenseRange(0, 1)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

void writeCsvs(const std::string& dir) {
  // A file whose benchmarks were filtered out is left as it is.
  if (!g_haptic.empty()) {
    sc::support::CsvFile f(dir + "/penetration_haptic.csv",
                           "pair,mode,steps,penetrating,not_ok,median_us,p99_us,max_us,"
                           "cpu_median_us,cpu_p99_us,cpu_max_us,max_step,delta_max,max_tpdv,"
                           "max_tpdv_jump,max_jump_ratio,jump_ratio_step,jumps_over_3x");
    for (const HapticRow& r : g_haptic)
      f.row("%s,%s,%d,%d,%d,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.3g,%.3g,%.4g,%.4g,%.3g,%d,%d",
            r.pair.c_str(), r.mode.c_str(), r.steps, r.penetrating, r.not_ok, r.median_us, r.p99_us,
            r.max_us, r.cpu_median_us, r.cpu_p99_us, r.cpu_max_us, r.max_step, r.delta_max,
            r.max_tpdv, r.max_tpdv_jump, r.max_jump_ratio, r.jump_ratio_step, r.jumps_over_3x);
  }
  if (!g_haptic_steps.empty()) {
    sc::support::CsvFile f(dir + "/penetration_haptic_steps.csv", "step,wall_us,cpu_us,tpdv");
    for (const auto& s : g_haptic_steps) f.row("%d,%.2f,%.2f,%.5g", int(s[0]), s[1], s[2], s[3]);
  }
  if (!g_sweep.empty()) {
    sc::support::CsvFile f(dir + "/penetration_sweep.csv",
                           "method,shapes,tolerance,iterations,cases,failures,median_us,"
                           "median_err,p90_err,max_err,parameters,over_1e-6");
    for (const SweepRow& r : g_sweep)
      f.row("%s,%s,%.0e,%d,%d,%d,%.3f,%.3g,%.3g,%.3g,%s,%d", r.method.c_str(), r.shapes.c_str(),
            r.tolerance, r.iterations, r.cases, r.failures, r.median_us, r.median_err, r.p90_err,
            r.max_err, r.parameters.c_str(), r.over_1e6);
  }
  if (!g_convex_path.empty()) {
    sc::support::CsvFile f(dir + "/penetration_convex_path.csv",
                           "method,shapes,steps,penetrating,median_us,p99_us,max_us,"
                           "cpu_median_us,cpu_p99_us,cpu_max_us");
    for (const ConvexPathRow& r : g_convex_path)
      f.row("%s,%s,%d,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f", r.method.c_str(), r.shapes.c_str(),
            r.steps, r.penetrating, r.median_us, r.p99_us, r.max_us, r.cpu_median_us, r.cpu_p99_us,
            r.cpu_max_us);
  }
  if (!g_global.empty()) {
    sc::support::CsvFile f(dir + "/penetration_global.csv",
                           "method,hull_vertices,cases,failures,median_us,p90_us,max_us,"
                           "median_err,max_err,over_1e-9,min_depth,max_depth");
    for (const GlobalRow& r : g_global)
      f.row("%s,%d,%d,%d,%.3f,%.3f,%.3f,%.3g,%.3g,%d,%.4g,%.4g", r.method.c_str(), r.vertices,
            r.cases, r.failures, r.median_us, r.p90_us, r.max_us, r.median_err, r.max_err,
            r.over_1e9, r.min_depth, r.max_depth);
  }
}

}  // namespace

// --csv-dir=<dir> and --callgrind-updates are ours; the rest is Google Benchmark's.
// Exits 1 when the convex global depth misses its target.
int main(int argc, char** argv) {
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::strcmp(argv[i], "--callgrind-updates") == 0)
      g_callgrind_updates = true;
    else
      args.push_back(argv[i]);
  }
  const int code =
      sc_bench::benchmarkMain(static_cast<int>(args.size()), args.data(), "--csv-dir=", writeCsvs);
  return code != 0 ? code : (g_target_missed ? 1 : 0);
}
