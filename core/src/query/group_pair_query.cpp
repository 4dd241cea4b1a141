// SPDX-License-Identifier: MIT
#include "query/group_pair_query.h"

#include <algorithm>
#include <cmath>

#include "preprocess/piece_data.h"

namespace sc::detail {

namespace {

constexpr int kMaxAdvanceSteps = 64;

std::uint64_t pairKey(int t_leaf, int o_leaf) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(t_leaf)) << 32) |
         static_cast<std::uint32_t>(o_leaf);
}

/// Distance from point p to the segment a + s (b - a), s in [0, 1].
double pointSegmentDistance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}

Rigid translated(const Rigid& x, const Vec3& delta) { return {x.rotation, x.translation + delta}; }

}  // namespace

void collectLeaves(const GroupView& group, std::vector<Leaf>& out) {
  out.clear();
  for (int p = 0; p < group.part_count; ++p) {
    const Part& part = group.parts[p];
    if (part.model == nullptr) continue;
    const auto& pieces = part.model->pieces();
    for (int k = 0; k < static_cast<int>(pieces.size()); ++k) {
      for (const ConvexPolytope& poly : pieces[k]->internals().patches) {
        Leaf leaf;
        leaf.poly = &poly;
        leaf.group_from_leaf = part.group_from_model;
        leaf.part = p;
        leaf.piece = k;
        leaf.center = part.group_from_model * poly.center;
        leaf.radius = poly.radius;
        out.push_back(leaf);
      }
    }
  }
}

void GroupPairQuery::bind(const GroupView& target, const GroupView& opponent) {
  const size_t old_t = t_leaves_.size(), old_o = o_leaves_.size();
  const ConvexPolytope* first_t = old_t ? t_leaves_.front().poly : nullptr;
  const ConvexPolytope* first_o = old_o ? o_leaves_.front().poly : nullptr;
  collectLeaves(target, t_leaves_);
  collectLeaves(opponent, o_leaves_);
  // Warm starts are keyed by leaf index: drop them when the leaf lists change.
  const bool same = t_leaves_.size() == old_t && o_leaves_.size() == old_o &&
                    (old_t == 0 || t_leaves_.front().poly == first_t) &&
                    (old_o == 0 || o_leaves_.front().poly == first_o);
  if (!same) caches_.clear();
}

SimplexCache& GroupPairQuery::cacheFor(int t_leaf, int o_leaf) {
  return caches_[pairKey(t_leaf, o_leaf)];
}

LeafContact GroupPairQuery::evaluate(int t_leaf, int o_leaf, const Rigid& o_from_t,
                                     double max_distance, bool& beyond) {
  const Leaf& lt = t_leaves_[t_leaf];
  const Leaf& lo = o_leaves_[o_leaf];
  GjkSettings settings;
  settings.max_distance = max_distance;
  const GjkResult r = gjkDistance(*lt.poly, o_from_t * lt.group_from_leaf, *lo.poly,
                                  lo.group_from_leaf, settings, cacheFor(t_leaf, o_leaf));
  LeafContact c;
  c.t_leaf = t_leaf;
  c.o_leaf = o_leaf;
  beyond = r.status == GjkStatus::BeyondMaxDistance;
  c.intersecting = r.status == GjkStatus::Intersecting;
  c.gap = c.intersecting ? 0.0 : (beyond ? r.lower_bound : r.distance);
  c.normal = r.normal;
  c.point_t = r.point_a;
  c.point_o = r.point_b;
  c.simplex_count = r.count;
  for (int i = 0; i < 4; ++i) {
    c.simplex_t[i] = r.a[i];
    c.simplex_o[i] = r.b[i];
  }
  return c;
}

void GroupPairQuery::gatherCandidates(const Rigid& o_from_t, double max_gap) {
  candidates_.clear();
  for (int i = 0; i < static_cast<int>(t_leaves_.size()); ++i) {
    const Vec3 c = o_from_t * t_leaves_[i].center;
    for (int j = 0; j < static_cast<int>(o_leaves_.size()); ++j) {
      const Leaf& lo = o_leaves_[j];
      const double lb = (c - lo.center).norm() - t_leaves_[i].radius - lo.radius;
      if (lb <= max_gap) candidates_.push_back({std::max(lb, 0.0), i, j});
    }
  }
  std::sort(candidates_.begin(), candidates_.end(),
            [](const Candidate& a, const Candidate& b) { return a.lower_bound < b.lower_bound; });
}

bool GroupPairQuery::distance(const Rigid& o_from_t, double max_distance, LeafContact& best) {
  gatherCandidates(o_from_t, max_distance);
  bool found = false;
  double bound = max_distance;
  for (const Candidate& cand : candidates_) {
    if (found && cand.lower_bound >= best.gap) break;
    if (cand.lower_bound > bound) break;
    bool beyond = false;
    const LeafContact c = evaluate(cand.t_leaf, cand.o_leaf, o_from_t, bound, beyond);
    if (beyond) continue;
    if (!found || c.gap < best.gap) {
      best = c;
      found = true;
      bound = std::min(bound, c.gap);
      if (c.intersecting) break;
    }
  }
  return found;
}

void GroupPairQuery::contacts(const Rigid& o_from_t, double threshold,
                              std::vector<LeafContact>& out) {
  out.clear();
  gatherCandidates(o_from_t, threshold);
  for (const Candidate& cand : candidates_) {
    bool beyond = false;
    const LeafContact c = evaluate(cand.t_leaf, cand.o_leaf, o_from_t, threshold, beyond);
    if (!beyond && c.gap <= threshold) out.push_back(c);
  }
}

LeafContact GroupPairQuery::pairAt(int t_leaf, int o_leaf, const Rigid& o_from_t) {
  bool beyond = false;
  return evaluate(t_leaf, o_leaf, o_from_t, kInfinity, beyond);
}

bool GroupPairQuery::intersects(const Rigid& o_from_t) {
  gatherCandidates(o_from_t, 0.0);
  for (const Candidate& cand : candidates_) {
    bool beyond = false;
    if (evaluate(cand.t_leaf, cand.o_leaf, o_from_t, 0.0, beyond).intersecting) return true;
  }
  return false;
}

double GroupPairQuery::separationAlong(int t_leaf, int o_leaf, const Rigid& o_from_t,
                                       const Vec3& n) {
  const Leaf& lt = t_leaves_[t_leaf];
  const Leaf& lo = o_leaves_[o_leaf];
  const Rigid o_from_lt = o_from_t * lt.group_from_leaf;
  SimplexCache& cache = cacheFor(t_leaf, o_leaf);
  // Directions in each leaf's own frame.
  const Vec3 nt = o_from_lt.rotation.transpose() * n;
  const Vec3 no = lo.group_from_leaf.rotation.transpose() * n;
  const int it = lt.poly->support(-nt, cache.hint_a);
  const int io = lo.poly->support(no, cache.hint_b);
  const double min_t = n.dot(o_from_lt * lt.poly->vertices[it]);
  const double max_o = n.dot(lo.group_from_leaf * lo.poly->vertices[io]);
  return min_t - max_o;
}

double GroupPairQuery::translationToi(const Rigid& o_from_t, const Vec3& delta, double stop_gap,
                                      const std::vector<std::uint8_t>& skip) {
  const double reach = delta.norm();
  gatherCandidates(o_from_t, reach + stop_gap);
  const size_t no = o_leaves_.size();
  double limit = 1.0;
  for (const Candidate& cand : candidates_) {
    if (!skip.empty() && skip[cand.t_leaf * no + cand.o_leaf]) continue;
    const Leaf& lt = t_leaves_[cand.t_leaf];
    const Leaf& lo = o_leaves_[cand.o_leaf];
    const Vec3 c0 = o_from_t * lt.center;
    const double swept_lb =
        pointSegmentDistance(lo.center, c0, c0 + limit * delta) - lt.radius - lo.radius;
    if (swept_lb > 0.5 * stop_gap) continue;
    // Conservative advancement: the separating plane of the current closest points
    // stays separating while the target moves towards it by less than the gap.
    double s = 0.0;
    for (int step = 0; step < kMaxAdvanceSteps && s < limit; ++step) {
      bool beyond = false;
      const LeafContact c =
          evaluate(cand.t_leaf, cand.o_leaf, translated(o_from_t, s * delta), kInfinity, beyond);
      if (c.intersecting || c.gap <= stop_gap) break;
      const double rate = -c.normal.dot(delta);
      if (rate <= 0.0) {
        s = limit;
        break;
      }
      s = std::min(limit, s + (c.gap - 0.5 * stop_gap) / rate);
    }
    limit = std::min(limit, s);
  }
  return limit;
}

}  // namespace sc::detail
