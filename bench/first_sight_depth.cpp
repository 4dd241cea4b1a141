// SPDX-License-Identifier: MIT
// A non-convex pair first seen deeply intersecting, with resolve_initial_intersection:
// per pose, a fresh PairTracker's first update (time, result) against a sampled bound
// of the translational depth. Both meshes are scaled to unit size; the target gets a
// random rotation and its centre a random direction at `offset` of the size.
// Sampled bound: along each of --directions=N random directions u, the target is
// moved by s u with s marched up in steps of 0.1 until a fresh tracker (resolution
// off) no longer reports it first seen intersecting, then bisected 14 times; the
// least such s over the directions is a free pose's translation, an upper bound of
// the translational depth. The result's contact pose is checked free the same way.
// Usage: first_sight_depth [--pairs=bunny00:armadillo,...] [--offsets=0.02,0.1,...]
//                          [--poses=20] [--directions=200] [--seed=1] [--verbose]
// Prints one line per pair and offset: resolved, contact poses free, thread CPU time
// per call (median, max), |TPDV| over the sampled bound (median, max), and how many
// exceed 1.05 times the bound plus the tolerance (a probe calls an overlap within the
// tolerance touching, hence free, so the bound is short of an exit by up to that); with
// --directions=0 no bound is sampled (timing runs).
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "meshes.h"
#include "sc_support/off_mesh.h"
#include "sc_support/stats.h"
#include "smartcollision/smartcollision.h"

namespace {

using sc::Quat;
using sc::Vec3;

struct Body {
  std::shared_ptr<sc::Model> model;
  sc::Part part;
};

bool loadBody(const std::string& name, int id, Body& body) {
  const sc::MeshData mesh = sc::support::fitToSize(sc_bench::loadOff(name), 1.0);
  if (mesh.vertices.empty()) return false;
  auto piece = sc::buildPiece(sc::ModelKind::ClosedPolyhedron, mesh);
  if (!piece.ok()) return false;
  body.model = std::make_shared<sc::Model>(sc::ModelKind::ClosedPolyhedron,
                                           std::vector<sc::PiecePtr>{piece.value()});
  body.part = sc::Part{body.model.get(), {}, id};
  return true;
}

sc::Placement placed(const Quat& q, const Vec3& c) {
  sc::Placement p;
  p.orientation = q;
  p.world_center = c;
  return p;
}

/// First update of a fresh tracker, target a at `pa`, opponent b at the origin.
sc::DirectedResult firstUpdate(const Body& a, const Body& b, const sc::Placement& pa,
                               bool resolve) {
  sc::PairTracker tracker;
  sc::PairSettings settings;
  settings.resolve_initial_intersection = resolve;
  settings.max_distance = 1e-2;  // a probe only asks whether the pose is free
  sc::DirectedResult out[2];
  tracker.update({&a.part, 1, pa}, {&b.part, 1, placed(Quat::Identity(), Vec3::Zero())},
                 {true, false}, settings, out);
  return out[0];
}

bool isFree(const Body& a, const Body& b, const sc::Placement& pa) {
  return firstUpdate(a, b, pa, false).code != sc::ErrorCode::InvalidInitialTransformation;
}

/// Least free offset found along u from pa: marched, then bisected.
double directionalDepth(const Body& a, const Body& b, const sc::Placement& pa, const Vec3& u) {
  constexpr double step = 0.1;
  double lo = 0.0, hi = step;
  while (!isFree(a, b, placed(pa.orientation, pa.world_center + hi * u))) {
    lo = hi;
    hi += step;
    if (hi > 4.0) return 4.0;
  }
  for (int i = 0; i < 14; ++i) {  // to 6e-6 of the size
    const double mid = 0.5 * (lo + hi);
    (isFree(a, b, placed(pa.orientation, pa.world_center + mid * u)) ? hi : lo) = mid;
  }
  return hi;
}

/// This thread's CPU time: other processes' load on the machine does not count.
double threadCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, sep);) out.push_back(item);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::string pairs = "bunny00:armadillo,bunny00:bunny00,knot1:elephant";
  std::string offsets = "0.02,0.1,0.2,0.4";
  int poses = 20, directions = 200;
  unsigned seed = 1;
  bool verbose = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], "--pairs=", 8) == 0) pairs = argv[i] + 8;
    if (std::strncmp(argv[i], "--offsets=", 10) == 0) offsets = argv[i] + 10;
    if (std::strncmp(argv[i], "--poses=", 8) == 0) poses = std::atoi(argv[i] + 8);
    if (std::strncmp(argv[i], "--directions=", 13) == 0) directions = std::atoi(argv[i] + 13);
    if (std::strcmp(argv[i], "--verbose") == 0) verbose = true;
    if (std::strncmp(argv[i], "--seed=", 7) == 0)
      seed = static_cast<unsigned>(std::strtoul(argv[i] + 7, nullptr, 10));
  }
  std::printf(
      "pair offset: resolved/poses, contact pose free, CPU ms per call (median, max), "
      "|TPDV| / sampled bound of %d directions (median, max)\n",
      directions);
  for (const std::string& pair : split(pairs, ',')) {
    const std::vector<std::string> names = split(pair, ':');
    Body a, b;
    if (names.size() != 2 || !loadBody(names[0], 1, a) || !loadBody(names[1], 2, b)) return 2;
    for (const std::string& offset_text : split(offsets, ',')) {
      const double offset = std::atof(offset_text.c_str());
      std::mt19937_64 rng(seed);
      std::vector<double> times, ratios;
      int intersecting = 0, resolved = 0, free = 0, over = 0;
      for (int i = 0; i < poses; ++i) {
        const sc::Placement pa =
            placed(sc::support::randomRotation(rng), offset * sc::support::randomDirection(rng));
        if (isFree(a, b, pa)) continue;
        ++intersecting;
        const double t0 = threadCpuMs();
        const sc::DirectedResult r = firstUpdate(a, b, pa, true);
        times.push_back(threadCpuMs() - t0);
        if (r.code != sc::ErrorCode::Ok) continue;
        ++resolved;
        if (isFree(a, b, placed(r.contact_orientation, r.contact_position))) ++free;
        std::mt19937_64 sample_rng(seed + 1000 + i);  // the poses do not depend on results
        double bound = 4.0;
        for (int d = 0; d < directions; ++d) {
          const Vec3 u = sc::support::randomDirection(sample_rng);
          bound = std::min(bound, directionalDepth(a, b, pa, u));
        }
        if (directions > 0) ratios.push_back(r.tpdv.norm() / bound);
        // A probe calls an overlap within the tolerance free: the bound is short by that.
        if (directions > 0 && r.tpdv.norm() > 1.05 * bound + sc::kDefaultTolerance) ++over;
        if (verbose)
          std::printf("  pose %d: %.2f ms, |TPDV| %.4f, bound %.4f\n", i, times.back(),
                      r.tpdv.norm(), bound);
      }
      std::printf(
          "%s %s: %d/%d resolved, %d free, %.1f %.1f ms, ratio %.3f %.3f, %d over 1.05 "
          "bound + tolerance\n",
          pair.c_str(), offset_text.c_str(), resolved, intersecting, free,
          sc::support::quantile(times, 0.5), sc::support::quantile(times, 1.0),
          sc::support::quantile(ratios, 0.5), sc::support::quantile(ratios, 1.0), over);
      std::fflush(stdout);
    }
  }
  return 0;
}
